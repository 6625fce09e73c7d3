//! The six-node quadratic triangle face `Tri6` (Gmsh type 9).

use crate::shape::QuadraticSimplex;
use crate::table::{concat, face_element};
use crate::tri3::TRI3_NODES;

/// The corners, then the middles of edges 1-2, 2-3, 3-1.
pub(crate) const TRI6_NODES: [[f64; 2]; 6] =
    concat(&TRI3_NODES, &[[0.5, 0.0], [0.5, 0.5], [0.0, 0.5]]);

/// The edges whose middles are nodes 4, 5, 6 (0-based corners).
const TRI6_EDGES: [[usize; 2]; 3] = [[0, 1], [1, 2], [2, 0]];

face_element! {
    /// Six-node quadratic triangle on `(0,0), (1,0), (0,1)`, Gmsh order: the corners, then the
    /// middles of edges 1-2, 2-3, 3-1. With `L_1 = 1 - xi - eta, L_2 = xi, L_3 = eta`: corners
    /// `L_i (2 L_i - 1)`, edge middles `4 L_a L_b`. Gmsh type 9. Reversed: corners `1 3 2`,
    /// then the middles of their edges `1-3, 3-2, 2-1`.
    ///
    /// The corner functions integrate to zero over the face, so the plain dual basis does not
    /// exist on a Tri6; [`DualMultipliers`](mortar_core::multiplier::DualMultipliers) first
    /// recombines the functions (Popp, Gee and Wall 2012).
    Tri6, TRI6: Triangle, corners 3, degree 2, gmsh 9,
    nodes TRI6_NODES, shapes QuadraticSimplex::<2>(&TRI6_EDGES), reversed [0, 2, 1, 5, 4, 3]
}
