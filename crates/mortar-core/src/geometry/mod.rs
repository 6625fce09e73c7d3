//! Geometry kernels: the auxiliary plane, convex polygon clipping and triangulation, and the
//! inverse maps from physical points to reference coordinates, and norms safe at any scale.
//!
//! Everything here works on stack arrays and allocates nothing.

mod inverse_map;
mod norm;
mod planar_map;
mod plane;
mod polygon;
mod root;

pub use inverse_map::{invert_line_map, invert_surface_map, InverseMapFailure};
pub use norm::{stable_norm, stable_normalize};
pub use planar_map::PlanarMap;
pub use plane::AuxiliaryPlane;
pub use polygon::{clip_convex, Polygon, MAX_POLYGON_VERTICES};
pub use root::bracketed_root;
