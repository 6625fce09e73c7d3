//! # mortar
//!
//! A toolkit for non-conforming interfaces in finite-element simulation: mesh tying and
//! simple contact by the mortar method, in 2D and 3D.
//!
//! This facade re-exports [`mortar_core`] (the operators D and M, as [`core`]),
//! [`mortar_fem`] (volume elements, meshes, quadrature and the sparse solvers, as [`fem`]),
//! [`mortar_elements`] and [`mortar_physics`], and adds mesh generators, file input/output (Gmsh, Matrix Market,
//! JSON, VTU), the coupling vocabulary of scene files and the command line ([`settings`]) and
//! the extension traits ([`extend`]). The ready-made problems are the crate `mortar-scenes`,
//! the `mortar` command the crate `mortar-app`: this one builds no command line, progress bar
//! or plot.
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

pub mod extend;
pub mod generate;
pub mod io;
pub mod settings;
#[cfg(feature = "proptest-support")]
#[cfg_attr(docsrs, doc(cfg(feature = "proptest-support")))]
pub mod testing;

pub use mortar_core::{
    assemble_coupling, assemble_coupling_reusing, Coupling, CouplingOptions, CouplingStats,
    CouplingWarning, Interface, MortarError, SearchRadius, Side, SpatialDim, SurfaceMesh,
    Tolerances,
};
pub use mortar_elements as elements;
pub use mortar_fem as fem;
pub use mortar_fem::VolumeMesh;
pub use mortar_petsc as petsc;
pub use mortar_physics as physics;

/// The coupling core, [`mortar_core`], with what moved from it to [`mortar_fem`] (volume
/// elements, volume meshes and quadrature, the sparse solvers) re-exported at its former
/// paths: `mortar::core::element::volume`, `mortar::core::mesh::VolumeMesh`,
/// `mortar::core::quadrature::VolumeQuadratureRule`, `mortar::core::linalg::LuFactorization`
/// and the like keep working. New code names them through [`fem`].
pub mod core {
    pub use mortar_core::*;
    pub use mortar_fem::VolumeMesh;

    /// [`mortar_core::element`], and the volume elements of [`mortar_fem::element`] as
    /// `volume`.
    pub mod element {
        pub use mortar_core::element::*;
        pub use mortar_fem::element as volume;
    }

    /// [`mortar_core::mesh`] and [`mortar_fem::mesh`].
    pub mod mesh {
        pub use mortar_core::mesh::*;
        pub use mortar_fem::mesh::*;
    }

    /// [`mortar_core::quadrature`] and [`mortar_fem::quadrature`].
    pub mod quadrature {
        pub use mortar_core::quadrature::*;
        pub use mortar_fem::quadrature::*;
    }

    /// [`mortar_fem::linalg`], which re-exports the sparse matrix types of
    /// [`mortar_core::linalg`].
    pub mod linalg {
        pub use mortar_fem::linalg::*;
    }
}
