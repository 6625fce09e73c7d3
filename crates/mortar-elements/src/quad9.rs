//! The nine-node biquadratic quadrilateral face `Quad9` (Gmsh type 10).

use mortar_core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
use nalgebra::Vector2;

use crate::quad8::{reverse_quadratic_quad, QUAD8_NODES};
use crate::shape::tensor;

/// Nine-node biquadratic quadrilateral on `[-1, 1]^2`, Gmsh order: the nodes of the
/// [`Quad8`](crate::Quad8), then the centre; the products of the 1D quadratic Lagrange
/// polynomials. Gmsh type 10.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Quad9;

/// The shared `Quad9` instance.
pub static QUAD9: Quad9 = Quad9;

pub(crate) const QUAD9_NODES: [[f64; 2]; 9] = {
    let mut n = [[0.0; 2]; 9];
    let mut i = 0;
    while i < 8 {
        n[i] = QUAD8_NODES[i];
        i += 1;
    }
    n
};

impl ReferenceElement for Quad9 {
    fn name(&self) -> &'static str {
        "Quad9"
    }
    fn domain(&self) -> ReferenceDomain {
        ReferenceDomain::Quadrilateral
    }
    fn node_count(&self) -> usize {
        9
    }
    fn corner_count(&self) -> usize {
        4
    }
    /// `xi^2 eta^2`: 4.
    fn shape_degree(&self) -> u32 {
        4
    }
    fn node_reference_coords(&self) -> &'static [[f64; 2]] {
        &QUAD9_NODES
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
        for (o, n) in out.iter_mut().zip(&QUAD9_NODES) {
            *o = tensor(n, &[xi.x, xi.y]).0;
        }
    }
    #[inline]
    fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        for (o, n) in out.iter_mut().zip(&QUAD9_NODES) {
            *o = tensor(n, &[xi.x, xi.y]).1;
        }
    }
}

impl SurfaceElement for Quad9 {
    fn gmsh_type(&self) -> Option<u32> {
        Some(10)
    }
    fn reverse_nodes(&self, nodes: &mut [u32]) -> bool {
        reverse_quadratic_quad(nodes, 9)
    }
}
