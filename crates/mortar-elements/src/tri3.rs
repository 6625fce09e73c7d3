//! The three-node linear triangle face `Tri3` (Gmsh type 2).

use crate::shape::LinearSimplex;
use crate::table::face_element;

/// The corners `(0,0), (1,0), (0,1)`.
pub(crate) const TRI3_NODES: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];

face_element! {
    /// Three-node triangle on `(0,0), (1,0), (0,1)`: `N_1 = 1 - xi - eta`, `N_2 = xi`,
    /// `N_3 = eta`. Gmsh type 2.
    Tri3, TRI3: Triangle, corners 3, degree 1, gmsh 2,
    nodes TRI3_NODES, shapes LinearSimplex::<2>
}
