//! The four-node bilinear quadrilateral cell of a 2D body (Gmsh type 3) and its `Line2` edges.

use mortar_core::element::{ElementRef, ReferenceElement};
use mortar_fem::element::{VolumeDomain, VolumeElement};
use nalgebra::{Vector2, Vector3};

/// Four-node bilinear quadrilateral cell of a 2D body on `[-1, 1]^2`, nodes counter-clockwise
/// from `(-1,-1)` (the shape functions of the surface [`crate::Quad4`]). Gmsh type 3. Edges
/// `(1,2), (2,3), (3,4), (4,1)`, outward for a counter-clockwise cell.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Quad4;

/// The shared `volume::Quad4` instance.
pub static QUAD4: Quad4 = Quad4;

impl VolumeElement for Quad4 {
    fn name(&self) -> &'static str {
        "Quad4"
    }
    fn domain(&self) -> VolumeDomain {
        VolumeDomain::Quadrilateral
    }
    fn node_count(&self) -> usize {
        4
    }
    fn shape_degree(&self) -> u32 {
        2
    }
    fn node_reference_coords(&self) -> &'static [[f64; 3]] {
        &[
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ]
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector3<f64>, out: &mut [f64]) {
        crate::QUAD4.shape_values_into(&Vector2::new(xi.x, xi.y), out);
    }
    #[inline]
    fn shape_gradients_into(&self, xi: &Vector3<f64>, out: &mut [[f64; 3]]) {
        let mut g = [[0.0; 2]; 4];
        crate::QUAD4.shape_gradients_into(&Vector2::new(xi.x, xi.y), &mut g);
        for (o, g) in out.iter_mut().zip(g) {
            *o = [g[0], g[1], 0.0];
        }
    }
    fn gmsh_type(&self) -> Option<u32> {
        Some(3)
    }
    fn faces(&self) -> &'static [&'static [usize]] {
        &[&[0, 1], &[1, 2], &[2, 3], &[3, 0]]
    }
    fn face_element(&self, face: usize) -> ElementRef {
        assert!(face < 4, "a Quad4 has 4 edges");
        &crate::LINE2
    }
}
