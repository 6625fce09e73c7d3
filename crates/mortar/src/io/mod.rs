//! File input and output: Gmsh 4.1 meshes in, Matrix Market and JSON out.
//!
//! - [`read_surface`] / [`read_gmsh_surface`]: the faces of a Gmsh 4.1 file (ASCII or binary,
//!   either byte order), whole or one physical group, as a [`SurfaceMesh`](crate::SurfaceMesh)
//!   with the file's node and element tags.
//! - [`read_volume`] / [`read_gmsh_volume`]: a body (the cells of a physical group of
//!   dimension 2 or 3) as a [`VolumeMesh`](crate::VolumeMesh), with its boundary faces
//!   selected by physical group ([`GmshVolume::boundary_faces_in`]).
//! - [`parse_interface_arg`]: `mesh.msh#group` arguments.
//! - [`write_msh41_ascii`], [`write_msh41_binary`], [`write_msh41`]: surface meshes as Gmsh 4.1;
//!   [`write_msh41_volume`]: a body and groups of its boundary faces.
//! - [`matrix_market`]: D and M as Matrix Market `coordinate real general`, values round-trip.
//! - [`CouplingSummary`]: the JSON summary of a run.
//! - [`vtu`]: volume meshes and nodal fields as ASCII VTU files for ParaView.
//! - [`write_outputs`] / [`write_coupling`]: all output files or none (temporary names, then
//!   renames).
//!
//! Every failure is an [`IoError`] that names the file and the place in it.
//!
//! ```
//! use mortar::generate::{square_quads, square_triangles, Diagonal};
//! use mortar::io::{read_surface, write_msh41_ascii};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let dir = std::env::temp_dir().join(format!("mortar-io-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! let path = dir.join("slave.msh");
//! let mesh = square_triangles(3, Diagonal::Main, 0.0, false, 1)?;
//! write_msh41_ascii(&mesh, &path, "contact")?;
//! let back = read_surface(&path, Some("contact"), &mortar::elements::ElementRegistry::new())?;
//! assert_eq!(back.face_count(), 18);
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok(()) }
//! ```

mod error;
pub mod gmsh;
mod interface_arg;
pub mod json;
pub mod matrix_market;
mod output;
mod summary;
pub mod vtu;

/// The coupling vocabulary, at its former path: its home is [`crate::settings`].
pub use crate::settings::{CouplingSettings, Integration, Multipliers};
pub use error::{IoError, Location};
pub use gmsh::{
    msh41_bytes, msh41_volume_bytes, parse_gmsh_surface, parse_gmsh_volume, read_gmsh_surface,
    read_gmsh_volume, read_surface, read_volume, write_msh41, write_msh41_ascii,
    write_msh41_binary, write_msh41_volume, Endianness, GmshSurface, GmshVolume, MshFormat,
    PhysicalGroup,
};
pub use interface_arg::{parse_interface_arg, InterfaceArg};
pub use output::{remove_stale_outputs, write_coupling, write_operators, write_outputs};
pub use summary::{
    warning_text, CouplingSummary, GapSummary, OrientationMethod, OrientationSummary, PhaseSummary,
    SideOrientation, ThreadSecondsSummary, WarningSummary, RECOMBINATION_FILE,
};
