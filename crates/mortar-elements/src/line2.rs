//! The two-node line `Line2` (Gmsh type 1).

use mortar_core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
use nalgebra::Vector2;

/// Two-node line on `[-1, 1]`: `N_1 = (1 - xi) / 2`, `N_2 = (1 + xi) / 2`. Gmsh type 1.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Line2;

/// The shared `Line2` instance.
pub static LINE2: Line2 = Line2;

impl ReferenceElement for Line2 {
    fn name(&self) -> &'static str {
        "Line2"
    }
    fn domain(&self) -> ReferenceDomain {
        ReferenceDomain::Line
    }
    fn node_count(&self) -> usize {
        2
    }
    fn corner_count(&self) -> usize {
        2
    }
    fn shape_degree(&self) -> u32 {
        1
    }
    fn node_reference_coords(&self) -> &'static [[f64; 2]] {
        &[[-1.0, 0.0], [1.0, 0.0]]
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
        out[0] = 0.5 * (1.0 - xi.x);
        out[1] = 0.5 * (1.0 + xi.x);
    }
    #[inline]
    fn shape_gradients_into(&self, _xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        out[0] = [-0.5, 0.0];
        out[1] = [0.5, 0.0];
    }
}

impl SurfaceElement for Line2 {
    fn is_affine(&self) -> bool {
        true
    }
    fn gmsh_type(&self) -> Option<u32> {
        Some(1)
    }
}
