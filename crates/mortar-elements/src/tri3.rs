//! The three-node linear triangle face `Tri3` (Gmsh type 2).

use mortar_core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
use nalgebra::Vector2;

/// Three-node triangle on `(0,0), (1,0), (0,1)`: `N_1 = 1 - xi - eta`, `N_2 = xi`,
/// `N_3 = eta`. Gmsh type 2.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Tri3;

/// The shared `Tri3` instance.
pub static TRI3: Tri3 = Tri3;

impl ReferenceElement for Tri3 {
    fn name(&self) -> &'static str {
        "Tri3"
    }
    fn domain(&self) -> ReferenceDomain {
        ReferenceDomain::Triangle
    }
    fn node_count(&self) -> usize {
        3
    }
    fn corner_count(&self) -> usize {
        3
    }
    fn shape_degree(&self) -> u32 {
        1
    }
    fn node_reference_coords(&self) -> &'static [[f64; 2]] {
        &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
        out[0] = 1.0 - xi.x - xi.y;
        out[1] = xi.x;
        out[2] = xi.y;
    }
    #[inline]
    fn shape_gradients_into(&self, _xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        out[0] = [-1.0, -1.0];
        out[1] = [1.0, 0.0];
        out[2] = [0.0, 1.0];
    }
}

impl SurfaceElement for Tri3 {
    fn is_affine(&self) -> bool {
        true
    }
    fn gmsh_type(&self) -> Option<u32> {
        Some(2)
    }
}
