//! # mortar
//!
//! A toolkit for non-conforming interfaces in finite-element simulation: mesh tying and
//! simple contact by the mortar method, in 2D and 3D.
//!
//! This facade re-exports [`mortar_core`] (the operators D and M), [`mortar_elements`] and
//! [`mortar_physics`], and adds mesh generators, file input/output (Gmsh, Matrix Market,
//! JSON, VTU) and ready-made [`scenes`].
//!
//! ```
//! use mortar::generate::{square_quads, square_triangles, Diagonal};
//! use mortar::{assemble_coupling, CouplingOptions, Interface};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! // Two non-matching meshes of the unit square: 4x4 triangles below, 5x5 quads above.
//! let slave = square_triangles(4, Diagonal::Main, 0.0, false, 1)?;
//! let master = square_quads(5, 0.0, true, 1)?;
//! let interface = Interface::new(slave, master)?;
//! let coupling = assemble_coupling(&interface, &CouplingOptions::default())?;
//! assert!((coupling.stats.area - 1.0).abs() < 1e-12);
//! # Ok(()) }
//! ```
#![cfg_attr(docsrs, feature(doc_cfg))]

pub mod cli;
pub mod extend;
pub mod generate;
pub mod interrupt;
pub mod io;
pub mod scenes;
#[cfg(feature = "proptest-support")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest-support")))]
pub mod testing;

pub use mortar_core::{
    self as core, assemble_coupling, assemble_coupling_reusing, Coupling, CouplingOptions,
    CouplingStats, CouplingWarning, Interface, MortarError, SearchRadius, Side, SpatialDim,
    SurfaceMesh, Tolerances, VolumeMesh,
};
pub use mortar_elements as elements;
pub use mortar_physics as physics;
