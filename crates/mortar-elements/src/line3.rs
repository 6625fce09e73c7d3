//! The three-node quadratic line `Line3` (Gmsh type 8).

use mortar_core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
use nalgebra::Vector2;

use crate::shape::tensor;

/// Three-node quadratic line on `[-1, 1]`, Gmsh order: the ends `-1`, `1`, then the middle
/// `0`: `N_1 = xi (xi - 1) / 2`, `N_2 = xi (xi + 1) / 2`, `N_3 = 1 - xi^2`. Gmsh type 8.
///
/// Affine (and integrated as such) when straight with its middle node at the centre; curved
/// otherwise.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Line3;

/// The shared `Line3` instance.
pub static LINE3: Line3 = Line3;

const NODES: [[f64; 2]; 3] = [[-1.0, 0.0], [1.0, 0.0], [0.0, 0.0]];

impl ReferenceElement for Line3 {
    fn name(&self) -> &'static str {
        "Line3"
    }
    fn domain(&self) -> ReferenceDomain {
        ReferenceDomain::Line
    }
    fn node_count(&self) -> usize {
        3
    }
    fn corner_count(&self) -> usize {
        2
    }
    fn shape_degree(&self) -> u32 {
        2
    }
    fn node_reference_coords(&self) -> &'static [[f64; 2]] {
        &NODES
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
        for (o, n) in out.iter_mut().zip(&NODES) {
            *o = tensor(&[n[0]], &[xi.x]).0;
        }
    }
    #[inline]
    fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        for (o, n) in out.iter_mut().zip(&NODES) {
            *o = [tensor(&[n[0]], &[xi.x]).1[0], 0.0];
        }
    }
}

impl SurfaceElement for Line3 {
    fn gmsh_type(&self) -> Option<u32> {
        Some(8)
    }
    /// The ends swap; the middle node stays.
    fn reverse_nodes(&self, nodes: &mut [u32]) -> bool {
        if nodes.len() != 3 {
            return false;
        }
        nodes.swap(0, 1);
        true
    }
}
