//! The three-node triangle cell of a 2D body (Gmsh type 2) and its `Line2` edges.

use mortar_core::element::{ElementRef, ReferenceElement};
use mortar_fem::element::{VolumeDomain, VolumeElement};
use nalgebra::{Vector2, Vector3};

/// Three-node triangle cell of a 2D body on `(0,0), (1,0), (0,1)`: `N_1 = 1 - xi - eta`,
/// `N_2 = xi`, `N_3 = eta` (the shape functions of the surface [`crate::Tri3`]). Gmsh type 2.
/// Edges `(1,2), (2,3), (3,1)`, outward for a counter-clockwise cell.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Tri3;

/// The shared `volume::Tri3` instance.
pub static TRI3: Tri3 = Tri3;

impl VolumeElement for Tri3 {
    fn name(&self) -> &'static str {
        "Tri3"
    }
    fn domain(&self) -> VolumeDomain {
        VolumeDomain::Triangle
    }
    fn node_count(&self) -> usize {
        3
    }
    fn shape_degree(&self) -> u32 {
        1
    }
    fn node_reference_coords(&self) -> &'static [[f64; 3]] {
        &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector3<f64>, out: &mut [f64]) {
        crate::TRI3.shape_values_into(&Vector2::new(xi.x, xi.y), out);
    }
    #[inline]
    fn shape_gradients_into(&self, xi: &Vector3<f64>, out: &mut [[f64; 3]]) {
        let mut g = [[0.0; 2]; 3];
        crate::TRI3.shape_gradients_into(&Vector2::new(xi.x, xi.y), &mut g);
        for (o, g) in out.iter_mut().zip(g) {
            *o = [g[0], g[1], 0.0];
        }
    }
    fn gmsh_type(&self) -> Option<u32> {
        Some(2)
    }
    fn is_affine(&self) -> bool {
        true
    }
    fn faces(&self) -> &'static [&'static [usize]] {
        &[&[0, 1], &[1, 2], &[2, 0]]
    }
    fn face_element(&self, face: usize) -> ElementRef {
        assert!(face < 3, "a Tri3 has 3 edges");
        &crate::LINE2
    }
}
