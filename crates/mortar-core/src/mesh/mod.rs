//! Surface meshes: nodes with tags and coordinates, faces with a surface element type. (The
//! volume meshes of the bodies, whose boundary faces come out as outward-oriented surface
//! meshes, are in `mortar-fem`.)

mod nodes;
pub mod orient;
mod surface_mesh;

pub use nodes::{NodeRefusal, NodeSet};
pub use surface_mesh::{FaceView, SurfaceMesh};
