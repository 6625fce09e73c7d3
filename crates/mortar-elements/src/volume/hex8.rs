//! The eight-node trilinear hexahedron `Hex8` (Gmsh type 5) and its `Quad4` faces.

use crate::shape::{multilinear, Nodewise};
use crate::table::cell_element;

/// The bottom face `zeta = -1` counter-clockwise from `(-1,-1,-1)`, then the top face likewise.
pub(crate) const HEX8_NODES: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

cell_element! {
    /// Eight-node trilinear hexahedron on `[-1, 1]^3`, Gmsh node order: the bottom face
    /// `zeta = -1` counter-clockwise from `(-1,-1,-1)`, then the top face likewise;
    /// `N_i = (1 + xi_i xi)(1 + eta_i eta)(1 + zeta_i zeta) / 8` (of degree 3, by
    /// `xi eta zeta`). Gmsh type 5.
    ///
    /// Faces (Quad4, outward for a positively oriented cell): `(1,4,3,2)` bottom, `(5,6,7,8)`
    /// top, `(1,2,6,5)` at `eta = -1`, `(2,3,7,6)` at `xi = 1`, `(3,4,8,7)` at `eta = 1`,
    /// `(4,1,5,8)` at `xi = -1`.
    Hex8, HEX8: Hexahedron, degree 3, gmsh 5,
    nodes HEX8_NODES, shapes Nodewise(multilinear::<3>),
    face crate::QUAD4, faces &[
        &[0, 3, 2, 1],
        &[4, 5, 6, 7],
        &[0, 1, 5, 4],
        &[1, 2, 6, 5],
        &[2, 3, 7, 6],
        &[3, 0, 4, 7],
    ]
}
