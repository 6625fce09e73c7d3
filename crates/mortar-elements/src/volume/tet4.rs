//! The four-node linear tetrahedron `Tet4` (Gmsh type 4) and its `Tri3` faces.

use mortar_core::element::ElementRef;
use mortar_fem::element::{VolumeDomain, VolumeElement};
use nalgebra::Vector3;

/// Four-node linear tetrahedron on `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`:
/// `N_1 = 1 - xi - eta - zeta`, `N_2 = xi`, `N_3 = eta`, `N_4 = zeta`. Gmsh type 4.
///
/// Faces (Tri3, outward for a positively oriented cell): `(1,3,2)` on `zeta = 0`, `(1,2,4)` on
/// `eta = 0`, `(1,4,3)` on `xi = 0`, `(2,3,4)` on the slanted face.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Tet4;

/// The shared `Tet4` instance.
pub static TET4: Tet4 = Tet4;

impl VolumeElement for Tet4 {
    fn name(&self) -> &'static str {
        "Tet4"
    }
    fn domain(&self) -> VolumeDomain {
        VolumeDomain::Tetrahedron
    }
    fn node_count(&self) -> usize {
        4
    }
    fn shape_degree(&self) -> u32 {
        1
    }
    fn node_reference_coords(&self) -> &'static [[f64; 3]] {
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ]
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector3<f64>, out: &mut [f64]) {
        out[0] = 1.0 - xi.x - xi.y - xi.z;
        out[1] = xi.x;
        out[2] = xi.y;
        out[3] = xi.z;
    }
    #[inline]
    fn shape_gradients_into(&self, _xi: &Vector3<f64>, out: &mut [[f64; 3]]) {
        out[0] = [-1.0, -1.0, -1.0];
        out[1] = [1.0, 0.0, 0.0];
        out[2] = [0.0, 1.0, 0.0];
        out[3] = [0.0, 0.0, 1.0];
    }
    fn gmsh_type(&self) -> Option<u32> {
        Some(4)
    }
    fn is_affine(&self) -> bool {
        true
    }
    fn faces(&self) -> &'static [&'static [usize]] {
        &[&[0, 2, 1], &[0, 1, 3], &[0, 3, 2], &[1, 2, 3]]
    }
    fn face_element(&self, face: usize) -> ElementRef {
        assert!(face < 4, "a Tet4 has 4 faces");
        &crate::TRI3
    }
}
