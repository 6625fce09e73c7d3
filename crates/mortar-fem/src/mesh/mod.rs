//! Volume meshes of bodies (cells with a volume element type), whose boundary faces come out
//! as outward-oriented surface meshes of `mortar-core`.

mod volume_mesh;

pub use volume_mesh::{BoundaryFace, CellView, VolumeMesh, VolumeMeshError};
