//! Built-in meshes: structured surfaces for the default scene, tests and benchmarks.
//!
//! Every generator numbers nodes from `first_node_tag` and faces from 1, and orients faces so
//! that the normal points along `normal` (for planes) or outward (for cylinders); `flip`
//! reverses it, as the master side of a tied interface usually wants.

mod cylinder;
mod line;
mod plane;

pub use cylinder::cylinder_surface;
pub use line::line_mesh;
pub use plane::{square_quads, square_triangles, Diagonal};
