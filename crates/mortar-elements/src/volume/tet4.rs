//! The four-node linear tetrahedron `Tet4` (Gmsh type 4) and its `Tri3` faces.

use crate::shape::LinearSimplex;
use crate::table::cell_element;

/// The corners `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`.
pub(crate) const TET4_NODES: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];

cell_element! {
    /// Four-node linear tetrahedron on `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`:
    /// `N_1 = 1 - xi - eta - zeta`, `N_2 = xi`, `N_3 = eta`, `N_4 = zeta`. Gmsh type 4.
    ///
    /// Faces (Tri3, outward for a positively oriented cell): `(1,3,2)` on `zeta = 0`, `(1,2,4)`
    /// on `eta = 0`, `(1,4,3)` on `xi = 0`, `(2,3,4)` on the slanted face.
    Tet4, TET4: Tetrahedron, degree 1, gmsh 4,
    nodes TET4_NODES, shapes LinearSimplex::<3>,
    face crate::TRI3, faces &[&[0, 2, 1], &[0, 1, 3], &[0, 3, 2], &[1, 2, 3]]
}
