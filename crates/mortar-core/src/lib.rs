//! # mortar-core
//!
//! The mortar coupling operators D and M between a slave and a master surface.
//!
//! ```text
//! SurfaceMesh (slave), SurfaceMesh (master)
//!   -> Interface        validated faces, node maps, averaged slave nodal normals
//!   -> search           BVH over inflated face boxes -> candidate pairs
//!   -> integration      per slave face: paired quadrature rule (segment- or element-based)
//!   -> assembly         Phi_j, N_k^s, N_l^m -> local blocks -> sparse D and M
//! ```
//!
//! ## Conventions
//!
//! - Reference domains: line `[-1, 1]`; triangle `(0,0), (1,0), (0,1)`; quad `[-1, 1]^2`.
//!   Node order follows Gmsh.
//! - The slave (non-mortar) side carries the multipliers; its outward normal (right-hand rule
//!   on the face's node order; for lines in the xy-plane `n = (t_y, -t_x)`) is the interface
//!   normal.
//! - `D[j,k] = int Phi_j N_k^s`, `M[j,l] = int Phi_j N_l^m`, both positive as written; the
//!   tying constraint is `D u_s - M u_m = 0` and the weighted gap `G = D x_s - M x_m`.
//! - Rows follow the slave interface nodes, columns the slave (D) or master (M) interface
//!   nodes, each by ascending node tag.
//! - All coordinates are 3D; a 2D problem lives in the plane `z = 0` and uses line elements.
//!   It is a slice of unit thickness, or, with the axisymmetric [`ModelGeometry`] in
//!   [`CouplingOptions::geometry`], the r-z section of a body of revolution (`x = r >= 0`,
//!   `y = z`): D and M are then integrals over the revolved surface (weight `2 pi r`).
//!
//! The core is the coupling alone: it names no solver and builds no C code. The volume
//! elements, meshes and quadrature of the bodies and the sparse solvers are in `mortar-fem`.
//!
//! Elements come from `mortar-elements` (or your own types implementing
//! [`element::SurfaceElement`]). With them:
//!
//! ```text
//! use mortar_core::{assemble_coupling, CouplingOptions, Interface, SurfaceMesh};
//! let interface = Interface::new(slave_mesh, master_mesh)?;
//! let coupling = assemble_coupling(&interface, &CouplingOptions::default().dual())?;
//! println!("area {} over {} pairs", coupling.stats.area, coupling.stats.pairs);
//! ```

// What a run has to say goes into its results; only the command-line program prints.
#![cfg_attr(
    not(test),
    deny(clippy::print_stdout, clippy::print_stderr, clippy::dbg_macro)
)]

pub mod assembly;
pub mod element;
pub mod error;
pub mod geometry;
pub mod integration;
pub mod interface;
pub mod linalg;
mod memory;
pub mod mesh;
pub mod multiplier;
pub mod projector;
pub mod quadrature;
pub mod search;
pub mod tolerances;

pub use assembly::{
    assemble_coupling, assemble_coupling_reusing, Coupling, CouplingOptions, CouplingStats,
    CouplingWarning, Recombined,
};
pub use error::{Inversion, MortarError, RangeLimit, Result, Side};
pub use geometry::ModelGeometry;
pub use interface::{Interface, SpatialDim};
pub use mesh::SurfaceMesh;
pub use tolerances::{SearchRadius, Tolerances};
