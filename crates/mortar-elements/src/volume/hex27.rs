//! The twenty-seven-node triquadratic hexahedron `Hex27` (Gmsh type 12) and its `Quad9` faces.

use mortar_core::element::ElementRef;
use mortar_fem::element::{VolumeDomain, VolumeElement};
use nalgebra::Vector3;

use super::hex20::HEX20_NODES;
use crate::shape::tensor;

/// Twenty-seven-node triquadratic hexahedron on `[-1, 1]^3`, Gmsh order: the nodes of the
/// [`Hex20`](super::Hex20), then the centres of the faces `zeta = -1`, `eta = -1`, `xi = -1`,
/// `xi = 1`, `eta = 1`, `zeta = 1`, then the centre of the cell; the products of the 1D
/// quadratic Lagrange polynomials. Gmsh type 12.
///
/// Faces ([`crate::Quad9`], outward for a positively oriented cell): those of the Hex20, each
/// followed by its centre.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Hex27;

/// The shared `Hex27` instance.
pub static HEX27: Hex27 = Hex27;

const NODES: [[f64; 3]; 27] = {
    let mut n = [[0.0; 3]; 27];
    let mut i = 0;
    while i < 20 {
        n[i] = HEX20_NODES[i];
        i += 1;
    }
    n[20] = [0.0, 0.0, -1.0];
    n[21] = [0.0, -1.0, 0.0];
    n[22] = [-1.0, 0.0, 0.0];
    n[23] = [1.0, 0.0, 0.0];
    n[24] = [0.0, 1.0, 0.0];
    n[25] = [0.0, 0.0, 1.0];
    n
};

impl VolumeElement for Hex27 {
    fn name(&self) -> &'static str {
        "Hex27"
    }
    fn domain(&self) -> VolumeDomain {
        VolumeDomain::Hexahedron
    }
    fn node_count(&self) -> usize {
        27
    }
    /// `xi^2 eta^2 zeta^2`: 6.
    fn shape_degree(&self) -> u32 {
        6
    }
    fn node_reference_coords(&self) -> &'static [[f64; 3]] {
        &NODES
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector3<f64>, out: &mut [f64]) {
        for (o, n) in out.iter_mut().zip(&NODES) {
            *o = tensor(n, &[xi.x, xi.y, xi.z]).0;
        }
    }
    #[inline]
    fn shape_gradients_into(&self, xi: &Vector3<f64>, out: &mut [[f64; 3]]) {
        for (o, n) in out.iter_mut().zip(&NODES) {
            *o = tensor(n, &[xi.x, xi.y, xi.z]).1;
        }
    }
    fn gmsh_type(&self) -> Option<u32> {
        Some(12)
    }
    fn faces(&self) -> &'static [&'static [usize]] {
        &[
            &[0, 3, 2, 1, 9, 13, 11, 8, 20],
            &[4, 5, 6, 7, 16, 18, 19, 17, 25],
            &[0, 1, 5, 4, 8, 12, 16, 10, 21],
            &[1, 2, 6, 5, 11, 14, 18, 12, 23],
            &[2, 3, 7, 6, 13, 15, 19, 14, 24],
            &[3, 0, 4, 7, 9, 10, 17, 15, 22],
        ]
    }
    fn face_element(&self, face: usize) -> ElementRef {
        assert!(face < 6, "a Hex27 has 6 faces");
        &crate::QUAD9
    }
}
