//! The eight-node serendipity quadrilateral face `Quad8` (Gmsh type 16).

use crate::quad4::QUAD4_NODES;
use crate::shape::{serendipity, Nodewise};
use crate::table::{concat, face_element};

/// The corners, then the middles of edges 1-2, 2-3, 3-4, 4-1.
pub(crate) const QUAD8_NODES: [[f64; 2]; 8] = concat(
    &QUAD4_NODES,
    &[[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]],
);

face_element! {
    /// Eight-node serendipity quadrilateral on `[-1, 1]^2`, Gmsh order: the corners
    /// counter-clockwise from `(-1,-1)`, then the middles of edges 1-2, 2-3, 3-4, 4-1. Corners
    /// `(1 + xi_i xi)(1 + eta_i eta)(xi_i xi + eta_i eta - 1) / 4`, edge middles
    /// `(1 - xi^2)(1 + eta_i eta) / 2` and `(1 + xi_i xi)(1 - eta^2) / 2` (of degree 3, by
    /// `xi^2 eta`). Gmsh type 16. Reversed: corners `1 4 3 2`, then the middles of their edges
    /// `1-4, 4-3, 3-2, 2-1`.
    ///
    /// The corner functions integrate to a negative share of the face, so the plain dual basis
    /// is ill-posed on a Quad8; [`DualMultipliers`](mortar_core::multiplier::DualMultipliers)
    /// first recombines the functions (Popp, Gee and Wall 2012).
    Quad8, QUAD8: Quadrilateral, corners 4, degree 3, gmsh 16,
    nodes QUAD8_NODES, shapes Nodewise(serendipity::<2>), reversed [0, 3, 2, 1, 7, 6, 5, 4]
}
