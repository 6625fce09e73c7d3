//! The interface: a slave and a master surface, validated, with node maps and the slave's
//! averaged nodal normals.

mod face;
#[allow(clippy::module_inception)]
mod interface;
mod master_faces;
mod validate;

pub use face::{FaceGeometry, WARPED_EXTRA_DEGREE};
pub use interface::{Interface, SpatialDim};
pub use master_faces::MasterFaces;
