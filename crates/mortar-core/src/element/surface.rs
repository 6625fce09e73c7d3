//! `SurfaceElement`: a reference element mapped into space (points, tangents, unit normals and
//! Jacobians), and `ElementRef`, the shared static handle the meshes store.

use nalgebra::{Vector2, Vector3};

use super::{ReferenceDomain, ReferenceElement, MAX_FACE_NODES};
use crate::geometry::stable_norm;

/// A surface element shared between threads and meshes: element types are zero-sized statics.
pub type ElementRef = &'static dyn SurfaceElement;

/// A surface element: the geometric map of a reference element into space.
///
/// All points are 3D; a 2D problem lives in the plane `z = 0` and uses line elements.
/// The provided methods compute the map `x(xi) = sum_i N_i(xi) x_i`, its tangents, the unit
/// normal and the measure (Jacobian determinant) from the shape functions; an element may
/// override them with faster closed forms.
///
/// Normal convention: for a line in the xy-plane with tangent `t = dx/dxi`, `n = (t_y, -t_x)`
/// normalised (outward for a boundary traversed counter-clockwise); for a face,
/// `n = (dx/dxi x dx/deta) / |.|` (right-hand rule on the node order).
pub trait SurfaceElement: ReferenceElement {
    /// Whether the geometric map is affine for every placement of the nodes (Line2, Tri3):
    /// then its inverse is found in one Newton step and its Jacobian is constant. An element
    /// that is affine only for some placements (a straight Line3 with its middle node at the
    /// centre, a parallelogram Quad4) need not say so: the coupling decides per face from the
    /// node positions ([`FaceGeometry::is_affine`](crate::interface::FaceGeometry::is_affine)).
    fn is_affine(&self) -> bool {
        false
    }

    /// The Gmsh element type number, when the element has one (1 = 2-node line, 2 = 3-node
    /// triangle, 3 = 4-node quadrangle, ...). Readers use it to map Gmsh elements to types.
    fn gmsh_type(&self) -> Option<u32> {
        None
    }

    /// Reverses the orientation of a face given by its node list (in element order), in
    /// place: a line's ends are swapped, a face's corners traversed the other way round from
    /// the first. Returns `false`, leaving `nodes` as they are, for an element whose order
    /// cannot be reversed this way (one with nodes besides its corners must override this).
    fn reverse_nodes(&self, nodes: &mut [u32]) -> bool {
        let k = self.node_count();
        if nodes.len() != k || k != self.corner_count() || k < 2 {
            return false;
        }
        if self.domain() == ReferenceDomain::Line {
            nodes.swap(0, 1);
        } else {
            nodes[1..].reverse();
        }
        true
    }

    /// The point `x(xi)` for the node coordinates `nodes`.
    fn map(&self, nodes: &[Vector3<f64>], xi: &Vector2<f64>) -> Vector3<f64> {
        let mut n = [0.0; MAX_FACE_NODES];
        let k = self.node_count();
        self.shape_values_into(xi, &mut n[..k]);
        let mut x = Vector3::zeros();
        for i in 0..k {
            x += nodes[i] * n[i];
        }
        x
    }

    /// The tangents `dx/dxi` and `dx/deta` at `xi` (for lines the second is `e_z`).
    fn tangents(&self, nodes: &[Vector3<f64>], xi: &Vector2<f64>) -> [Vector3<f64>; 2] {
        let mut g = [[0.0; 2]; MAX_FACE_NODES];
        let k = self.node_count();
        self.shape_gradients_into(xi, &mut g[..k]);
        let mut t = [Vector3::zeros(), Vector3::zeros()];
        for i in 0..k {
            t[0] += nodes[i] * g[i][0];
            t[1] += nodes[i] * g[i][1];
        }
        if self.domain() == ReferenceDomain::Line {
            t[1] = Vector3::z();
        }
        t
    }

    /// The (non-normalised) normal `t1 x t2`, whose length is the measure density; for lines
    /// `(t_y, -t_x, 0)`.
    fn scaled_normal(&self, nodes: &[Vector3<f64>], xi: &Vector2<f64>) -> Vector3<f64> {
        let [t1, t2] = self.tangents(nodes, xi);
        if self.domain() == ReferenceDomain::Line {
            Vector3::new(t1.y, -t1.x, 0.0)
        } else {
            t1.cross(&t2)
        }
    }

    /// The unit normal at `xi` (zero if the face is degenerate there). Its length is taken by
    /// [`stable_norm`], so it is the same for a face scaled by 1e-100 or 1e100, whose scaled
    /// normal's squared length would underflow or overflow.
    fn unit_normal(&self, nodes: &[Vector3<f64>], xi: &Vector2<f64>) -> Vector3<f64> {
        let n = self.scaled_normal(nodes, xi);
        let len = stable_norm(&n);
        if len > 0.0 {
            n / len
        } else {
            n
        }
    }

    /// The measure density `|dx/dxi|` (lines) or `|dx/dxi x dx/deta|` (faces) at `xi` (by
    /// [`stable_norm`], like [`unit_normal`](Self::unit_normal)).
    fn jacobian_det(&self, nodes: &[Vector3<f64>], xi: &Vector2<f64>) -> f64 {
        stable_norm(&self.scaled_normal(nodes, xi))
    }
}
