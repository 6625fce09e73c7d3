//! Surface meshes: nodes with tags and coordinates, faces with an element type.

mod surface_mesh;

pub use surface_mesh::{FaceView, SurfaceMesh};
