//! The ten-node quadratic tetrahedron `Tet10` (Gmsh type 11) and its `Tri6` faces.

use super::tet4::TET4_NODES;
use crate::shape::QuadraticSimplex;
use crate::table::{cell_element, concat};

/// The corners, then the middles of edges 1-2, 2-3, 3-1, 4-1, 4-3, 4-2.
const TET10_NODES: [[f64; 3]; 10] = concat(
    &TET4_NODES,
    &[
        [0.5, 0.0, 0.0],
        [0.5, 0.5, 0.0],
        [0.0, 0.5, 0.0],
        [0.0, 0.0, 0.5],
        [0.0, 0.5, 0.5],
        [0.5, 0.0, 0.5],
    ],
);

/// The edges whose middles are nodes 5 to 10 (0-based corners).
const TET10_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]];

cell_element! {
    /// Ten-node quadratic tetrahedron on `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`, Gmsh order: the
    /// corners, then the middles of edges 1-2, 2-3, 3-1, 4-1, 4-3, 4-2 (Gmsh's own edge
    /// order). With `L_1 = 1 - xi - eta - zeta` and `L_2..L_4 = xi, eta, zeta`: corners
    /// `L_i (2 L_i - 1)`, edge middles `4 L_a L_b`. Gmsh type 11.
    ///
    /// Faces ([`crate::Tri6`], outward for a positively oriented cell): those of the
    /// [`Tet4`](super::Tet4), `(1,3,2) (1,2,4) (1,4,3) (2,3,4)`, each followed by the middles
    /// of its edges.
    Tet10, TET10: Tetrahedron, degree 2, gmsh 11,
    nodes TET10_NODES, shapes QuadraticSimplex::<3>(&TET10_EDGES),
    face crate::TRI6, faces &[
        &[0, 2, 1, 6, 5, 4],
        &[0, 1, 3, 4, 9, 7],
        &[0, 3, 2, 7, 8, 6],
        &[1, 2, 3, 5, 8, 9],
    ]
}
