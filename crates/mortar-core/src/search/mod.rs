//! The candidate search: which master faces may overlap each slave face.
//!
//! Bounding boxes of the master faces go into a BVH whose leaves group faces in the Morton
//! order of their first nodes, four leaves to a node in that order (`bvh.rs`). Each slave
//! face queries it with the box of its nodes widened along their nodal normals by the
//! [`Tolerances::search_radius`] both ways (by default one face diameter: an open gap of the
//! order of the element size is crossed). A side whose nodes do not bound what the search
//! must find (higher-order faces, a projector that does not say its directions stay within
//! the nodal normals) has its boxes inflated by [`Tolerances::search_inflation`] times the
//! face diameter ([`Padding`]). O(N log N); nothing is all-pairs.
//!
//! A 2D interface of two-node lines in chains is searched as a merge instead (`chains.rs`):
//! both sides in chain order, each slave face's partners found by walking along the master's
//! chain from its predecessor's, with the same box test; the coupling uses it with its fused
//! kernel for straight lines (see [`assemble_coupling`](crate::assemble_coupling)).
//!
//! [`Tolerances::search_inflation`]: crate::tolerances::Tolerances::search_inflation
//! [`Tolerances::search_radius`]: crate::tolerances::Tolerances::search_radius

mod bvh;
mod candidates;
mod chains;
mod master_cache;
mod morton;
mod nearest;
mod padding;

pub(crate) use candidates::face_search_radius;
pub use candidates::{find_candidates, Candidates, GroupScratch, MasterTree};
pub(crate) use chains::{ChainSearch, LineChains, WALK_LIMIT};
pub(crate) use master_cache::{MasterCorners, MasterCornersCache, MasterLine, MasterLineCache};
pub(crate) use morton::{bounds_of, morton_code, spatial_keys};
pub(crate) use nearest::{keep_within_radius, nearest_master_radii};
pub use padding::{in_hull_of_nodes, Padding};
