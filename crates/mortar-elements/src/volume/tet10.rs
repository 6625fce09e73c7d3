//! The ten-node quadratic tetrahedron `Tet10` (Gmsh type 11) and its `Tri6` faces.

use mortar_core::element::ElementRef;
use mortar_fem::element::{VolumeDomain, VolumeElement};
use nalgebra::Vector3;

use crate::shape::barycentric;

/// Ten-node quadratic tetrahedron on `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`, Gmsh order: the
/// corners, then the middles of edges 1-2, 2-3, 3-1, 4-1, 4-3, 4-2 (Gmsh's own edge order).
/// With `L_1 = 1 - xi - eta - zeta` and `L_2..L_4 = xi, eta, zeta`: corners `L_i (2 L_i - 1)`,
/// edge middles `4 L_a L_b`. Gmsh type 11.
///
/// Faces ([`crate::Tri6`], outward for a positively oriented cell): those of the
/// [`Tet4`](super::Tet4), `(1,3,2) (1,2,4) (1,4,3) (2,3,4)`, each followed by the middles of
/// its edges.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Tet10;

/// The shared `Tet10` instance.
pub static TET10: Tet10 = Tet10;

const EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]];

impl VolumeElement for Tet10 {
    fn name(&self) -> &'static str {
        "Tet10"
    }
    fn domain(&self) -> VolumeDomain {
        VolumeDomain::Tetrahedron
    }
    fn node_count(&self) -> usize {
        10
    }
    fn shape_degree(&self) -> u32 {
        2
    }
    fn node_reference_coords(&self) -> &'static [[f64; 3]] {
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.5, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.0, 0.5, 0.0],
            [0.0, 0.0, 0.5],
            [0.0, 0.5, 0.5],
            [0.5, 0.0, 0.5],
        ]
    }
    #[inline]
    fn shape_values_into(&self, xi: &Vector3<f64>, out: &mut [f64]) {
        barycentric::<3, 3>(&[xi.x, xi.y, xi.z], &EDGES, Some(out), None);
    }
    #[inline]
    fn shape_gradients_into(&self, xi: &Vector3<f64>, out: &mut [[f64; 3]]) {
        barycentric::<3, 3>(&[xi.x, xi.y, xi.z], &EDGES, None, Some(out));
    }
    fn gmsh_type(&self) -> Option<u32> {
        Some(11)
    }
    fn faces(&self) -> &'static [&'static [usize]] {
        &[
            &[0, 2, 1, 6, 5, 4],
            &[0, 1, 3, 4, 9, 7],
            &[0, 3, 2, 7, 8, 6],
            &[1, 2, 3, 5, 8, 9],
        ]
    }
    fn face_element(&self, face: usize) -> ElementRef {
        assert!(face < 4, "a Tet10 has 4 faces");
        &crate::TRI6
    }
}
