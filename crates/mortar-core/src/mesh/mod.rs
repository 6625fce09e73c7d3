//! Meshes: surface meshes (nodes with tags and coordinates, faces with a surface element
//! type) and volume meshes of bodies (cells with a volume element type), whose boundary faces
//! come out as outward-oriented surface meshes.

mod nodes;
pub mod orient;
mod surface_mesh;
mod volume_mesh;

pub use surface_mesh::{FaceView, SurfaceMesh};
pub use volume_mesh::{BoundaryFace, CellView, VolumeMesh, VolumeMeshError};
