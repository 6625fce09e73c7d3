//! The eight-node serendipity quadrilateral face `Quad8` (Gmsh type 16).

use mortar_core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
use nalgebra::Vector2;

use crate::shape::serendipity;

/// Eight-node serendipity quadrilateral on `[-1, 1]^2`, Gmsh order: the corners
/// counter-clockwise from `(-1,-1)`, then the middles of edges 1-2, 2-3, 3-4, 4-1. Corners
/// `(1 + xi_i xi)(1 + eta_i eta)(xi_i xi + eta_i eta - 1) / 4`, edge middles
/// `(1 - xi^2)(1 + eta_i eta) / 2` and `(1 + xi_i xi)(1 - eta^2) / 2`. Gmsh type 16.
///
/// The corner functions integrate to a negative share of the face, so the plain dual basis is
/// ill-posed on a Quad8; [`DualMultipliers`](mortar_core::multiplier::DualMultipliers) first
/// recombines the functions (Popp, Gee and Wall 2012).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Quad8;

/// The shared `Quad8` instance.
pub static QUAD8: Quad8 = Quad8;

pub(crate) const QUAD8_NODES: [[f64; 2]; 8] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
];

impl ReferenceElement for Quad8 {
    fn name(&self) -> &'static str {
        "Quad8"
    }
    fn domain(&self) -> ReferenceDomain {
        ReferenceDomain::Quadrilateral
    }
    fn node_count(&self) -> usize {
        8
    }
    fn corner_count(&self) -> usize {
        4
    }
    /// `xi^2 eta`: 3.
    fn shape_degree(&self) -> u32 {
        3
    }
    fn node_reference_coords(&self) -> &'static [[f64; 2]] {
        &QUAD8_NODES
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
        for (o, n) in out.iter_mut().zip(&QUAD8_NODES) {
            *o = serendipity(n, &[xi.x, xi.y]).0;
        }
    }
    #[inline]
    fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        for (o, n) in out.iter_mut().zip(&QUAD8_NODES) {
            *o = serendipity(n, &[xi.x, xi.y]).1;
        }
    }
}

impl SurfaceElement for Quad8 {
    fn gmsh_type(&self) -> Option<u32> {
        Some(16)
    }
    fn reverse_nodes(&self, nodes: &mut [u32]) -> bool {
        reverse_quadratic_quad(nodes, 8)
    }
}

/// Reverses a Quad8 or Quad9 node list: corners `1 4 3 2`, then the middles of their edges
/// `1-4, 4-3, 3-2, 2-1`, then the centre (Quad9).
pub(crate) fn reverse_quadratic_quad(nodes: &mut [u32], k: usize) -> bool {
    if nodes.len() != k {
        return false;
    }
    nodes[1..4].reverse();
    nodes[4..8].reverse();
    true
}
