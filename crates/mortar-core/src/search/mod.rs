//! The candidate search: which master faces may overlap each slave face.
//!
//! Bounding boxes of the faces, inflated by [`Tolerances::search_inflation`] times the face
//! diameter plus [`Tolerances::search_distance`], go into parry's BVH (`parry2d-f64` for 2D
//! interfaces, `parry3d-f64` for 3D); each slave face's box is then queried against the
//! master tree. O(N log N); nothing is all-pairs. parry's API stays inside `bvh.rs`.
//!
//! [`Tolerances::search_inflation`]: crate::tolerances::Tolerances::search_inflation
//! [`Tolerances::search_distance`]: crate::tolerances::Tolerances::search_distance

mod bvh;
mod candidates;

pub use candidates::{find_candidates, Candidates, MasterTree};
