//! Element traits: the reference element (shape functions on a reference domain) and the
//! surface element (its geometric map into space, Jacobian and normal).
//!
//! A new element is one type implementing [`ReferenceElement`] and [`SurfaceElement`]; the
//! search, segmentation, integration and assembly code never changes. See the
//! `mortar-elements` crate for `Line2`, `Tri3` and `Quad4`. (The volume elements of the bodies
//! are in `mortar-fem`.)

pub(crate) mod flat;
mod reference;
mod surface;

pub use reference::{ReferenceDomain, ReferenceElement, MAX_FACE_NODES};
pub use surface::{ElementRef, SurfaceElement};
