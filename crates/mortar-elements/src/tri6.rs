//! The six-node quadratic triangle face `Tri6` (Gmsh type 9).

use mortar_core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
use nalgebra::Vector2;

use crate::shape::barycentric;

/// Six-node quadratic triangle on `(0,0), (1,0), (0,1)`, Gmsh order: the corners, then the
/// middles of edges 1-2, 2-3, 3-1. With `L_1 = 1 - xi - eta, L_2 = xi, L_3 = eta`: corners
/// `L_i (2 L_i - 1)`, edge middles `4 L_a L_b`. Gmsh type 9.
///
/// The corner functions integrate to zero over the face, so the plain dual basis does not
/// exist on a Tri6; [`DualMultipliers`](mortar_core::multiplier::DualMultipliers) first
/// recombines the functions (Popp, Gee and Wall 2012).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Tri6;

/// The shared `Tri6` instance.
pub static TRI6: Tri6 = Tri6;

/// The edges whose middles are nodes 4, 5, 6 (0-based corners).
pub(crate) const TRI6_EDGES: [[usize; 2]; 3] = [[0, 1], [1, 2], [2, 0]];

impl ReferenceElement for Tri6 {
    fn name(&self) -> &'static str {
        "Tri6"
    }
    fn domain(&self) -> ReferenceDomain {
        ReferenceDomain::Triangle
    }
    fn node_count(&self) -> usize {
        6
    }
    fn corner_count(&self) -> usize {
        3
    }
    fn shape_degree(&self) -> u32 {
        2
    }
    fn node_reference_coords(&self) -> &'static [[f64; 2]] {
        &[
            [0.0, 0.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [0.5, 0.0],
            [0.5, 0.5],
            [0.0, 0.5],
        ]
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
        barycentric(&[xi.x, xi.y], &TRI6_EDGES, out, None);
    }
    #[inline]
    fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        let mut n = [0.0; 6];
        barycentric(&[xi.x, xi.y], &TRI6_EDGES, &mut n, Some(out));
    }
}

impl SurfaceElement for Tri6 {
    fn gmsh_type(&self) -> Option<u32> {
        Some(9)
    }
    /// Corners `1 3 2`, then the middles of their edges `1-3, 3-2, 2-1`.
    fn reverse_nodes(&self, nodes: &mut [u32]) -> bool {
        if nodes.len() != 6 {
            return false;
        }
        let n: [u32; 6] = std::array::from_fn(|i| nodes[i]);
        nodes.copy_from_slice(&[n[0], n[2], n[1], n[5], n[4], n[3]]);
        true
    }
}
