//! Geometry kernels: the auxiliary plane, convex polygon clipping and triangulation, and the
//! inverse maps from physical points to reference coordinates, norms safe at any scale; and
//! [`ModelGeometry`], what a mesh models (its own coordinates, or the r-z section of a body of
//! revolution) and so the measure of its integrals.
//!
//! Everything here works on stack arrays and allocates nothing.

mod inverse_map;
mod model;
mod norm;
mod planar_map;
mod plane;
mod polygon;
mod root;

pub use inverse_map::{invert_line_map, invert_surface_map, InverseMapFailure};
pub use model::{ModelGeometry, AXIS_TOLERANCE};
pub use norm::{stable_norm, stable_normalize};
pub use planar_map::PlanarMap;
pub use plane::AuxiliaryPlane;
pub use polygon::{
    clip_convex, polygon_diameter, signed_area, wider_than, ClipBuffers, ConvexClipper, Polygon,
    MAX_POLYGON_VERTICES,
};
pub use root::bracketed_root;
