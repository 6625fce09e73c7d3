//! The two-node line `Line2` (Gmsh type 1).

use crate::shape::{multilinear, Nodewise};
use crate::table::face_element;

/// The ends `-1`, `1`.
pub(crate) const LINE2_NODES: [[f64; 2]; 2] = [[-1.0, 0.0], [1.0, 0.0]];

face_element! {
    /// Two-node line on `[-1, 1]`: `N_1 = (1 - xi) / 2`, `N_2 = (1 + xi) / 2`. Gmsh type 1.
    Line2, LINE2: Line, corners 2, degree 1, gmsh 1,
    nodes LINE2_NODES, shapes Nodewise(multilinear::<1>)
}
