//! The four-node bilinear quadrilateral face `Quad4` (Gmsh type 3).

use crate::shape::{multilinear, Nodewise};
use crate::table::face_element;

/// The corners, counter-clockwise from `(-1,-1)`.
pub(crate) const QUAD4_NODES: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

face_element! {
    /// Four-node bilinear quadrilateral on `[-1, 1]^2`, nodes counter-clockwise from `(-1,-1)`:
    /// `N_i = (1 + xi_i xi)(1 + eta_i eta) / 4` (of degree 2, by `xi eta`). Gmsh type 3.
    Quad4, QUAD4: Quadrilateral, corners 4, degree 2, gmsh 3,
    nodes QUAD4_NODES, shapes Nodewise(multilinear::<2>)
}
