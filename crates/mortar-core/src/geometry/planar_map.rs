//! `PlanarMap`: a face's map into the auxiliary plane, set up once and inverted many times
//! (a 2x2 product for affine faces, Newton otherwise).

use nalgebra::{Matrix2, Vector2};

use super::inverse_map::planar_map_and_jacobian;
use super::{invert_surface_map, InverseMapFailure};
use crate::element::{ElementRef, MAX_FACE_NODES};

/// A face's map from reference coordinates into a plane (its nodes projected onto the
/// auxiliary plane), ready to be inverted many times: for affine elements the inverse
/// Jacobian is computed once, so each inversion is a 2x2 product; otherwise Newton.
#[derive(Debug, Clone, Copy)]
pub struct PlanarMap {
    element: ElementRef,
    nodes: [Vector2<f64>; MAX_FACE_NODES],
    affine: Option<(Vector2<f64>, Vector2<f64>, Matrix2<f64>)>,
}

impl PlanarMap {
    /// The map of `element` with projected nodes `nodes`. The map counts as affine when the
    /// element type is (Tri3), or when this face's Jacobian is the same at every node as at the
    /// centre (a parallelogram Quad4): then its inverse is one 2x2 product.
    pub fn new(element: ElementRef, nodes: &[Vector2<f64>]) -> Self {
        let mut map = Self::unset(element);
        map.set(element, nodes);
        map
    }

    /// A map of `element` with every node at the origin and no inverse, to be
    /// [`set`](Self::set) before use.
    pub(crate) fn unset(element: ElementRef) -> Self {
        Self {
            element,
            nodes: [Vector2::zeros(); MAX_FACE_NODES],
            affine: None,
        }
    }

    /// Makes this the map of `element` with projected nodes `nodes`, in place: what
    /// [`new`](Self::new) returns, without building a new map and moving it here.
    pub fn set(&mut self, element: ElementRef, nodes: &[Vector2<f64>]) {
        self.set_known(element, nodes, false);
    }

    /// [`set`](Self::set) for the projection of a face known to be affine in space
    /// ([`FaceGeometry::is_affine`](crate::interface::FaceGeometry::is_affine)): a projection
    /// is linear, so its map is affine too, and the Jacobian is evaluated at the centre only
    /// (not compared at every node as well).
    pub(crate) fn set_affine(&mut self, element: ElementRef, nodes: &[Vector2<f64>]) {
        self.set_known(element, nodes, true);
    }

    /// [`set`](Self::set), with the map taken as affine without the check at the nodes when
    /// `affine`.
    fn set_known(&mut self, element: ElementRef, nodes: &[Vector2<f64>], affine: bool) {
        let k = element.node_count();
        self.element = element;
        self.nodes[..k].copy_from_slice(&nodes[..k]);
        self.nodes[k..].fill(Vector2::zeros());
        let all = &self.nodes[..k];
        let centre = element.domain().centre();
        let (x, j) = planar_map_and_jacobian(element, all, &centre);
        let affine_shape = affine || element.is_affine() || {
            let scale = j.abs().max();
            element.node_reference_coords().iter().all(|xi| {
                let (_, jn) = planar_map_and_jacobian(element, all, &Vector2::new(xi[0], xi[1]));
                (jn - j).abs().max() <= 1e-13 * scale
            })
        };
        self.affine = if affine_shape {
            j.try_inverse().map(|inv| (centre, x, inv))
        } else {
            None
        };
    }

    /// Whether the map is affine (its inverse is exact in one step).
    pub fn is_affine(&self) -> bool {
        self.affine.is_some()
    }

    /// The affine map's parts, when it is affine: the reference centre `c`, its image `x` and
    /// the inverse Jacobian `inv`, so that the reference coordinates of `p` are
    /// `c + inv (p - x)` (what [`invert`](Self::invert) computes).
    pub(crate) fn affine_parts(&self) -> Option<(Vector2<f64>, Vector2<f64>, Matrix2<f64>)> {
        self.affine
    }

    /// The in-plane point at reference coordinates `xi`, and the Jacobian determinant of the
    /// map there (in-plane area per reference area).
    #[inline]
    pub fn eval(&self, xi: &Vector2<f64>) -> (Vector2<f64>, f64) {
        let (x, j) =
            planar_map_and_jacobian(self.element, &self.nodes[..self.element.node_count()], xi);
        (x, j.determinant())
    }

    /// Reference coordinates of the face point that maps to `p`.
    ///
    /// # Errors
    /// [`InverseMapFailure`] if Newton fails (non-affine faces) or the map is singular.
    #[inline]
    pub fn invert(
        &self,
        p: &Vector2<f64>,
        tol: f64,
        max_iterations: usize,
    ) -> Result<Vector2<f64>, InverseMapFailure> {
        match &self.affine {
            Some((centre, x, inv)) => Ok(centre + inv * (p - x)),
            None => invert_surface_map(
                self.element,
                self.element.is_affine(),
                &self.nodes[..self.element.node_count()],
                p,
                tol,
                max_iterations,
            ),
        }
    }
}
