//! The cells of 2D bodies in the plane `z = 0`: [`Tri3`], [`Quad4`], [`Tri6`], [`Quad8`] and
//! [`Quad9`], on the node tables (put in the plane) and with the shape functions of the surface
//! elements of the same names, so that a 2D cell and the interface face of the same shape
//! share every bit of their shape functions; their edges are [`crate::Line2`] or
//! [`crate::Line3`], outward for a counter-clockwise cell.

use crate::quad4::QUAD4_NODES;
use crate::quad8::QUAD8_NODES;
use crate::quad9::QUAD9_NODES;
use crate::shape::InPlane;
use crate::table::{cell_element, in_plane};
use crate::tri3::TRI3_NODES;
use crate::tri6::TRI6_NODES;

const TRI3_CELL: [[f64; 3]; 3] = in_plane(&TRI3_NODES);
const QUAD4_CELL: [[f64; 3]; 4] = in_plane(&QUAD4_NODES);
const TRI6_CELL: [[f64; 3]; 6] = in_plane(&TRI6_NODES);
const QUAD8_CELL: [[f64; 3]; 8] = in_plane(&QUAD8_NODES);
const QUAD9_CELL: [[f64; 3]; 9] = in_plane(&QUAD9_NODES);

/// The edges of a quadratic quadrilateral: the ends, then the middle.
const QUADRATIC_QUAD_EDGES: &[&[usize]] = &[&[0, 1, 4], &[1, 2, 5], &[2, 3, 6], &[3, 0, 7]];

cell_element! {
    /// Three-node triangle cell of a 2D body on `(0,0), (1,0), (0,1)`: `N_1 = 1 - xi - eta`,
    /// `N_2 = xi`, `N_3 = eta` (the shape functions of the surface [`crate::Tri3`]). Gmsh type
    /// 2. Edges `(1,2), (2,3), (3,1)`, outward for a counter-clockwise cell.
    Tri3, TRI3: Triangle, degree 1, gmsh 2,
    nodes TRI3_CELL, shapes InPlane(&crate::TRI3),
    face crate::LINE2, faces &[&[0, 1], &[1, 2], &[2, 0]]
}

cell_element! {
    /// Four-node bilinear quadrilateral cell of a 2D body on `[-1, 1]^2`, nodes
    /// counter-clockwise from `(-1,-1)` (the shape functions of the surface [`crate::Quad4`]).
    /// Gmsh type 3. Edges `(1,2), (2,3), (3,4), (4,1)`, outward for a counter-clockwise cell.
    Quad4, QUAD4: Quadrilateral, degree 2, gmsh 3,
    nodes QUAD4_CELL, shapes InPlane(&crate::QUAD4),
    face crate::LINE2, faces &[&[0, 1], &[1, 2], &[2, 3], &[3, 0]]
}

cell_element! {
    /// Six-node triangle cell of a 2D body (the shape functions of the surface
    /// [`crate::Tri6`]). Gmsh type 9. Edges `(1,2,4), (2,3,5), (3,1,6)` (ends, then middle),
    /// outward for a counter-clockwise cell.
    Tri6, TRI6: Triangle, degree 2, gmsh 9,
    nodes TRI6_CELL, shapes InPlane(&crate::TRI6),
    face crate::LINE3, faces &[&[0, 1, 3], &[1, 2, 4], &[2, 0, 5]]
}

cell_element! {
    /// Eight-node serendipity quadrilateral cell of a 2D body (the shape functions of the
    /// surface [`crate::Quad8`]). Gmsh type 16. Edges `(1,2,5), (2,3,6), (3,4,7), (4,1,8)`,
    /// outward for a counter-clockwise cell.
    Quad8, QUAD8: Quadrilateral, degree 3, gmsh 16,
    nodes QUAD8_CELL, shapes InPlane(&crate::QUAD8),
    face crate::LINE3, faces QUADRATIC_QUAD_EDGES
}

cell_element! {
    /// Nine-node biquadratic quadrilateral cell of a 2D body (the shape functions of the
    /// surface [`crate::Quad9`]). Gmsh type 10. Edges as the [`Quad8`]'s.
    Quad9, QUAD9: Quadrilateral, degree 4, gmsh 10,
    nodes QUAD9_CELL, shapes InPlane(&crate::QUAD9),
    face crate::LINE3, faces QUADRATIC_QUAD_EDGES
}
