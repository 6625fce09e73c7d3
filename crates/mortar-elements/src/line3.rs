//! The three-node quadratic line `Line3` (Gmsh type 8).

use crate::line2::LINE2_NODES;
use crate::shape::{tensor, Nodewise};
use crate::table::{concat, face_element};

/// The ends, then the middle.
const LINE3_NODES: [[f64; 2]; 3] = concat(&LINE2_NODES, &[[0.0, 0.0]]);

face_element! {
    /// Three-node quadratic line on `[-1, 1]`, Gmsh order: the ends `-1`, `1`, then the middle
    /// `0`: `N_1 = xi (xi - 1) / 2`, `N_2 = xi (xi + 1) / 2`, `N_3 = 1 - xi^2`. Gmsh type 8.
    ///
    /// Affine (and integrated as such) when straight with its middle node at the centre; curved
    /// otherwise. Reversed, the ends swap and the middle node stays.
    Line3, LINE3: Line, corners 2, degree 2, gmsh 8,
    nodes LINE3_NODES, shapes Nodewise(tensor::<1>), reversed [1, 0, 2]
}
