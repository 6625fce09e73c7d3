//! The twenty-node serendipity hexahedron `Hex20` (Gmsh type 17) and its `Quad8` faces.

use mortar_core::element::ElementRef;
use mortar_fem::element::{VolumeDomain, VolumeElement};
use nalgebra::Vector3;

use crate::shape::serendipity;

/// Twenty-node serendipity hexahedron on `[-1, 1]^3`, Gmsh order: the corners of the
/// [`Hex8`](super::Hex8), then the middles of edges 1-2, 1-4, 1-5, 2-3, 2-6, 3-4, 3-7, 4-8,
/// 5-6, 5-8, 6-7, 7-8 (Gmsh's own edge order). Corners
/// `prod (1 + c_d x_d) (sum c_d x_d - 2) / 8`, edge middles `(1 - x_z^2) prod_(d != z)
/// (1 + c_d x_d) / 4`. Gmsh type 17.
///
/// Faces ([`crate::Quad8`], outward for a positively oriented cell): those of the Hex8, each
/// followed by the middles of its edges.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Hex20;

/// The shared `Hex20` instance.
pub static HEX20: Hex20 = Hex20;

/// The nodes of the Hex20, and the first 20 of the [`Hex27`](super::Hex27).
pub(crate) const HEX20_NODES: [[f64; 3]; 20] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, -1.0, -1.0],
    [-1.0, 0.0, -1.0],
    [-1.0, -1.0, 0.0],
    [1.0, 0.0, -1.0],
    [1.0, -1.0, 0.0],
    [0.0, 1.0, -1.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [0.0, -1.0, 1.0],
    [-1.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
];

impl VolumeElement for Hex20 {
    fn name(&self) -> &'static str {
        "Hex20"
    }
    fn domain(&self) -> VolumeDomain {
        VolumeDomain::Hexahedron
    }
    fn node_count(&self) -> usize {
        20
    }
    /// `xi^2 eta zeta`: 4.
    fn shape_degree(&self) -> u32 {
        4
    }
    fn node_reference_coords(&self) -> &'static [[f64; 3]] {
        &HEX20_NODES
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector3<f64>, out: &mut [f64]) {
        for (o, n) in out.iter_mut().zip(&HEX20_NODES) {
            *o = serendipity(n, &[xi.x, xi.y, xi.z]).0;
        }
    }
    #[inline]
    fn shape_gradients_into(&self, xi: &Vector3<f64>, out: &mut [[f64; 3]]) {
        for (o, n) in out.iter_mut().zip(&HEX20_NODES) {
            *o = serendipity(n, &[xi.x, xi.y, xi.z]).1;
        }
    }
    fn gmsh_type(&self) -> Option<u32> {
        Some(17)
    }
    fn faces(&self) -> &'static [&'static [usize]] {
        &[
            &[0, 3, 2, 1, 9, 13, 11, 8],
            &[4, 5, 6, 7, 16, 18, 19, 17],
            &[0, 1, 5, 4, 8, 12, 16, 10],
            &[1, 2, 6, 5, 11, 14, 18, 12],
            &[2, 3, 7, 6, 13, 15, 19, 14],
            &[3, 0, 4, 7, 9, 10, 17, 15],
        ]
    }
    fn face_element(&self, face: usize) -> ElementRef {
        assert!(face < 6, "a Hex20 has 6 faces");
        &crate::QUAD8
    }
}
