//! The twenty-seven-node triquadratic hexahedron `Hex27` (Gmsh type 12) and its `Quad9` faces.

use super::hex20::HEX20_NODES;
use crate::shape::{tensor, Nodewise};
use crate::table::{cell_element, concat};

/// The nodes of the Hex20, then the centres of the faces, then that of the cell.
const HEX27_NODES: [[f64; 3]; 27] = concat(
    &HEX20_NODES,
    &[
        [0.0, 0.0, -1.0],
        [0.0, -1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 0.0],
    ],
);

cell_element! {
    /// Twenty-seven-node triquadratic hexahedron on `[-1, 1]^3`, Gmsh order: the nodes of the
    /// [`Hex20`](super::Hex20), then the centres of the faces `zeta = -1`, `eta = -1`,
    /// `xi = -1`, `xi = 1`, `eta = 1`, `zeta = 1`, then the centre of the cell; the products of
    /// the 1D quadratic Lagrange polynomials (of degree 6, by `xi^2 eta^2 zeta^2`). Gmsh type
    /// 12.
    ///
    /// Faces ([`crate::Quad9`], outward for a positively oriented cell): those of the Hex20,
    /// each followed by its centre.
    Hex27, HEX27: Hexahedron, degree 6, gmsh 12,
    nodes HEX27_NODES, shapes Nodewise(tensor::<3>),
    face crate::QUAD9, faces &[
        &[0, 3, 2, 1, 9, 13, 11, 8, 20],
        &[4, 5, 6, 7, 16, 18, 19, 17, 25],
        &[0, 1, 5, 4, 8, 12, 16, 10, 21],
        &[1, 2, 6, 5, 11, 14, 18, 12, 23],
        &[2, 3, 7, 6, 13, 15, 19, 14, 24],
        &[3, 0, 4, 7, 9, 10, 17, 15, 22],
    ]
}
