//! The twenty-node serendipity hexahedron `Hex20` (Gmsh type 17) and its `Quad8` faces.

use super::hex8::HEX8_NODES;
use crate::shape::{serendipity, Nodewise};
use crate::table::{cell_element, concat};

/// The nodes of the Hex20, and the first 20 of the [`Hex27`](super::Hex27): the corners, then
/// the middles of the edges in Gmsh's order.
pub(crate) const HEX20_NODES: [[f64; 3]; 20] = concat(
    &HEX8_NODES,
    &[
        [0.0, -1.0, -1.0],
        [-1.0, 0.0, -1.0],
        [-1.0, -1.0, 0.0],
        [1.0, 0.0, -1.0],
        [1.0, -1.0, 0.0],
        [0.0, 1.0, -1.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [0.0, -1.0, 1.0],
        [-1.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [0.0, 1.0, 1.0],
    ],
);

cell_element! {
    /// Twenty-node serendipity hexahedron on `[-1, 1]^3`, Gmsh order: the corners of the
    /// [`Hex8`](super::Hex8), then the middles of edges 1-2, 1-4, 1-5, 2-3, 2-6, 3-4, 3-7, 4-8,
    /// 5-6, 5-8, 6-7, 7-8 (Gmsh's own edge order). Corners
    /// `prod (1 + c_d x_d) (sum c_d x_d - 2) / 8`, edge middles `(1 - x_z^2) prod_(d != z)
    /// (1 + c_d x_d) / 4` (of degree 4, by `xi^2 eta zeta`). Gmsh type 17.
    ///
    /// Faces ([`crate::Quad8`], outward for a positively oriented cell): those of the Hex8, each
    /// followed by the middles of its edges.
    Hex20, HEX20: Hexahedron, degree 4, gmsh 17,
    nodes HEX20_NODES, shapes Nodewise(serendipity::<3>),
    face crate::QUAD8, faces &[
        &[0, 3, 2, 1, 9, 13, 11, 8],
        &[4, 5, 6, 7, 16, 18, 19, 17],
        &[0, 1, 5, 4, 8, 12, 16, 10],
        &[1, 2, 6, 5, 11, 14, 18, 12],
        &[2, 3, 7, 6, 13, 15, 19, 14],
        &[3, 0, 4, 7, 9, 10, 17, 15],
    ]
}
