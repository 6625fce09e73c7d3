//! The nine-node biquadratic quadrilateral face `Quad9` (Gmsh type 10).

use crate::quad8::QUAD8_NODES;
use crate::shape::{tensor, Nodewise};
use crate::table::{concat, face_element};

/// The nodes of the Quad8, then the centre.
pub(crate) const QUAD9_NODES: [[f64; 2]; 9] = concat(&QUAD8_NODES, &[[0.0, 0.0]]);

face_element! {
    /// Nine-node biquadratic quadrilateral on `[-1, 1]^2`, Gmsh order: the nodes of the
    /// [`Quad8`](crate::Quad8), then the centre; the products of the 1D quadratic Lagrange
    /// polynomials (of degree 4, by `xi^2 eta^2`). Gmsh type 10. Reversed as the Quad8, the
    /// centre staying.
    Quad9, QUAD9: Quadrilateral, corners 4, degree 4, gmsh 10,
    nodes QUAD9_NODES, shapes Nodewise(tensor::<2>), reversed [0, 3, 2, 1, 7, 6, 5, 4, 8]
}
