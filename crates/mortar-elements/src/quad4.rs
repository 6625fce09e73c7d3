//! The four-node bilinear quadrilateral face `Quad4` (Gmsh type 3).

use mortar_core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
use nalgebra::Vector2;

/// Four-node bilinear quadrilateral on `[-1, 1]^2`, nodes counter-clockwise from `(-1,-1)`:
/// `N_i = (1 + xi_i xi)(1 + eta_i eta) / 4`. Gmsh type 3.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Quad4;

/// The shared `Quad4` instance.
pub static QUAD4: Quad4 = Quad4;

const NODES: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

impl ReferenceElement for Quad4 {
    fn name(&self) -> &'static str {
        "Quad4"
    }
    fn domain(&self) -> ReferenceDomain {
        ReferenceDomain::Quadrilateral
    }
    fn node_count(&self) -> usize {
        4
    }
    fn corner_count(&self) -> usize {
        4
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
            *o = 0.25 * (1.0 + n[0] * xi.x) * (1.0 + n[1] * xi.y);
        }
    }
    #[inline]
    fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        for (o, n) in out.iter_mut().zip(&NODES) {
            *o = [
                0.25 * n[0] * (1.0 + n[1] * xi.y),
                0.25 * n[1] * (1.0 + n[0] * xi.x),
            ];
        }
    }
}

impl SurfaceElement for Quad4 {
    fn gmsh_type(&self) -> Option<u32> {
        Some(3)
    }
}
