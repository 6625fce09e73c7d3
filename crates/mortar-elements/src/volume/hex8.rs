//! The eight-node trilinear hexahedron `Hex8` (Gmsh type 5) and its `Quad4` faces.

use mortar_core::element::ElementRef;
use mortar_fem::element::{VolumeDomain, VolumeElement};
use nalgebra::Vector3;

/// Eight-node trilinear hexahedron on `[-1, 1]^3`, Gmsh node order: the bottom face
/// `zeta = -1` counter-clockwise from `(-1,-1,-1)`, then the top face likewise;
/// `N_i = (1 + xi_i xi)(1 + eta_i eta)(1 + zeta_i zeta) / 8`. Gmsh type 5.
///
/// Faces (Quad4, outward for a positively oriented cell): `(1,4,3,2)` bottom, `(5,6,7,8)` top,
/// `(1,2,6,5)` at `eta = -1`, `(2,3,7,6)` at `xi = 1`, `(3,4,8,7)` at `eta = 1`, `(4,1,5,8)`
/// at `xi = -1`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Hex8;

/// The shared `Hex8` instance.
pub static HEX8: Hex8 = Hex8;

const NODES: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

impl VolumeElement for Hex8 {
    fn name(&self) -> &'static str {
        "Hex8"
    }
    fn domain(&self) -> VolumeDomain {
        VolumeDomain::Hexahedron
    }
    fn node_count(&self) -> usize {
        8
    }
    fn shape_degree(&self) -> u32 {
        3
    }
    fn node_reference_coords(&self) -> &'static [[f64; 3]] {
        &NODES
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector3<f64>, out: &mut [f64]) {
        for (o, n) in out.iter_mut().zip(&NODES) {
            *o = 0.125 * (1.0 + n[0] * xi.x) * (1.0 + n[1] * xi.y) * (1.0 + n[2] * xi.z);
        }
    }
    #[inline]
    fn shape_gradients_into(&self, xi: &Vector3<f64>, out: &mut [[f64; 3]]) {
        for (o, n) in out.iter_mut().zip(&NODES) {
            let (a, b, c) = (1.0 + n[0] * xi.x, 1.0 + n[1] * xi.y, 1.0 + n[2] * xi.z);
            *o = [
                0.125 * n[0] * b * c,
                0.125 * n[1] * a * c,
                0.125 * n[2] * a * b,
            ];
        }
    }
    fn gmsh_type(&self) -> Option<u32> {
        Some(5)
    }
    fn faces(&self) -> &'static [&'static [usize]] {
        &[
            &[0, 3, 2, 1],
            &[4, 5, 6, 7],
            &[0, 1, 5, 4],
            &[1, 2, 6, 5],
            &[2, 3, 7, 6],
            &[3, 0, 4, 7],
        ]
    }
    fn face_element(&self, face: usize) -> ElementRef {
        assert!(face < 6, "a Hex8 has 6 faces");
        &crate::QUAD4
    }
}
