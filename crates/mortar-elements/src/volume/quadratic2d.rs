//! The quadratic cells of 2D bodies: [`Tri6`], [`Quad8`], [`Quad9`], with the shape functions
//! of the surface elements of the same names (as [`super::Tri3`] and [`super::Quad4`] reuse
//! theirs) and three-node edges ([`crate::Line3`]).

use mortar_core::element::{ElementRef, ReferenceElement, MAX_FACE_NODES};
use mortar_fem::element::{VolumeDomain, VolumeElement};
use nalgebra::{Vector2, Vector3};

/// Implements a 2D cell by the surface element `$surface` of the same shape.
macro_rules! cell_2d {
    ($(#[$doc:meta])* $name:ident, $instance:ident, $surface:expr, $domain:expr, $gmsh:expr,
     $edges:expr) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
        pub struct $name;

        #[doc = concat!("The shared `volume::", stringify!($name), "` instance.")]
        pub static $instance: $name = $name;

        impl VolumeElement for $name {
            fn name(&self) -> &'static str {
                $surface.name()
            }
            fn domain(&self) -> VolumeDomain {
                $domain
            }
            fn node_count(&self) -> usize {
                $surface.node_count()
            }
            fn shape_degree(&self) -> u32 {
                $surface.shape_degree()
            }
            fn node_reference_coords(&self) -> &'static [[f64; 3]] {
                static COORDS: std::sync::OnceLock<Vec<[f64; 3]>> = std::sync::OnceLock::new();
                COORDS.get_or_init(|| {
                    $surface
                        .node_reference_coords()
                        .iter()
                        .map(|x| [x[0], x[1], 0.0])
                        .collect()
                })
            }
            #[inline]
            fn shape_values_into(&self, xi: &Vector3<f64>, out: &mut [f64]) {
                $surface.shape_values_into(&Vector2::new(xi.x, xi.y), out);
            }
            #[inline]
            fn shape_gradients_into(&self, xi: &Vector3<f64>, out: &mut [[f64; 3]]) {
                let mut g = [[0.0; 2]; MAX_FACE_NODES];
                let k = self.node_count();
                $surface.shape_gradients_into(&Vector2::new(xi.x, xi.y), &mut g[..k]);
                for (o, g) in out.iter_mut().zip(&g[..k]) {
                    *o = [g[0], g[1], 0.0];
                }
            }
            fn gmsh_type(&self) -> Option<u32> {
                Some($gmsh)
            }
            fn faces(&self) -> &'static [&'static [usize]] {
                $edges
            }
            fn face_element(&self, face: usize) -> ElementRef {
                assert!(face < self.faces().len(), "face {face} of a {}", self.name());
                &crate::LINE3
            }
        }
    };
}

cell_2d!(
    /// Six-node triangle cell of a 2D body (the shape functions of the surface
    /// [`crate::Tri6`]). Gmsh type 9. Edges `(1,2,4), (2,3,5), (3,1,6)` (ends, then middle),
    /// outward for a counter-clockwise cell.
    Tri6,
    TRI6,
    crate::TRI6,
    VolumeDomain::Triangle,
    9,
    &[&[0, 1, 3], &[1, 2, 4], &[2, 0, 5]]
);

cell_2d!(
    /// Eight-node serendipity quadrilateral cell of a 2D body (the shape functions of the
    /// surface [`crate::Quad8`]). Gmsh type 16. Edges `(1,2,5), (2,3,6), (3,4,7), (4,1,8)`,
    /// outward for a counter-clockwise cell.
    Quad8,
    QUAD8,
    crate::QUAD8,
    VolumeDomain::Quadrilateral,
    16,
    &[&[0, 1, 4], &[1, 2, 5], &[2, 3, 6], &[3, 0, 7]]
);

cell_2d!(
    /// Nine-node biquadratic quadrilateral cell of a 2D body (the shape functions of the
    /// surface [`crate::Quad9`]). Gmsh type 10. Edges as the [`Quad8`]'s.
    Quad9,
    QUAD9,
    crate::QUAD9,
    VolumeDomain::Quadrilateral,
    10,
    &[&[0, 1, 4], &[1, 2, 5], &[2, 3, 6], &[3, 0, 7]]
);
