//! `FaceGeometry`: one face's element, node coordinates and nodal normals gathered on the stack,
//! with its map, measure and the flat/affine tests that choose the quadrature degree.

use nalgebra::{Vector2, Vector3};

use crate::element::{ElementRef, MAX_FACE_NODES};
use crate::error::{FaceLocation, Side};
use crate::geometry::stable_normalize;
use crate::mesh::{FaceView, SurfaceMesh};
use crate::quadrature::{Quadrature, QuadratureRule};

/// The quadrature degree added for a warped or curved face (see [`FaceGeometry::is_flat`]):
/// a bilinear quad whose corners leave its plane by 0.2 of its size then integrates to 1e-10
/// of its nodal areas, standard and dual (the degree of a flat face: 6e-8).
pub const WARPED_EXTRA_DEGREE: u32 = 9;

/// One face's geometry gathered on the stack: element, node coordinates and (on the slave side)
/// the averaged nodal normals at its nodes. What the segmenter and the integrator work on.
#[derive(Debug, Clone, Copy)]
pub struct FaceGeometry {
    /// Face index in its mesh.
    pub index: u32,
    /// Face tag.
    pub tag: u64,
    /// Which side.
    pub side: Side,
    /// The element type.
    pub element: ElementRef,
    /// Node coordinates (the first `element.node_count()` are valid).
    pub nodes: [Vector3<f64>; MAX_FACE_NODES],
    /// Averaged nodal normals (slave side; zero on the master side).
    pub normals: [Vector3<f64>; MAX_FACE_NODES],
}

impl FaceGeometry {
    /// Gathers face `index` of `mesh`; `nodal_normals`, when given, is indexed by mesh node.
    pub fn gather(
        mesh: &SurfaceMesh,
        side: Side,
        index: usize,
        nodal_normals: Option<&[Vector3<f64>]>,
    ) -> Self {
        let view = mesh.face(index);
        let mut face = Self {
            index: 0,
            tag: 0,
            side,
            element: view.element,
            nodes: [Vector3::zeros(); MAX_FACE_NODES],
            normals: [Vector3::zeros(); MAX_FACE_NODES],
        };
        face.fill(mesh, view, side, index, nodal_normals);
        face
    }

    /// [`gather`](Self::gather) into `self`, which holds a face gathered before: the same
    /// value, without building it on the stack and copying it (the arrays hold nine nodes;
    /// a line has two). The entries past the new face's nodes are zeroed as far as the old
    /// face's reached, so they are zero as [`gather`](Self::gather) leaves them.
    pub fn gather_into(
        &mut self,
        mesh: &SurfaceMesh,
        side: Side,
        index: usize,
        nodal_normals: Option<&[Vector3<f64>]>,
    ) {
        let view = mesh.face(index);
        let old = self.node_count();
        let k = view.nodes.len();
        self.fill(mesh, view, side, index, nodal_normals);
        for i in k..old.max(k) {
            self.nodes[i] = Vector3::zeros();
            self.normals[i] = Vector3::zeros();
        }
    }

    /// Writes the face `view` (face `index` of `mesh`) into `self`: its nodes and normals
    /// (zero where `nodal_normals` is not given) over the first entries, and its identity.
    #[inline(always)]
    fn fill(
        &mut self,
        mesh: &SurfaceMesh,
        view: FaceView<'_>,
        side: Side,
        index: usize,
        nodal_normals: Option<&[Vector3<f64>]>,
    ) {
        for (i, &n) in view.nodes.iter().enumerate() {
            self.nodes[i] = mesh.coords()[n as usize];
            self.normals[i] = nodal_normals.map_or(Vector3::zeros(), |nn| nn[n as usize]);
        }
        self.index = index as u32;
        self.tag = view.tag;
        self.side = side;
        self.element = view.element;
    }

    /// Number of nodes.
    #[inline]
    pub fn node_count(&self) -> usize {
        self.element.node_count()
    }

    /// The valid node coordinates.
    #[inline]
    pub fn node_coords(&self) -> &[Vector3<f64>] {
        &self.nodes[..self.node_count()]
    }

    /// The face's location, for error messages.
    pub fn location(&self) -> FaceLocation {
        FaceLocation {
            side: Some(self.side),
            tag: self.tag,
        }
    }

    /// The point at reference coordinates `xi`.
    pub fn map(&self, xi: &Vector2<f64>) -> Vector3<f64> {
        self.element.map(self.node_coords(), xi)
    }

    /// The point at the centre of the reference domain.
    pub fn centre(&self) -> Vector3<f64> {
        self.map(&self.element.domain().centre())
    }

    /// The face's own measure (area; length for a line): exact for an affine face, by a
    /// quadrature of the Jacobian of degree `2 p + 4` otherwise (`p` the shape degree).
    pub fn measure(&self) -> f64 {
        let el = self.element;
        let domain = el.domain();
        if el.is_affine() {
            return el.jacobian_det(self.node_coords(), &domain.centre()) * domain.measure();
        }
        let degree = (2 * el.shape_degree() + 4).min(20);
        match QuadratureRule::cached(domain, degree) {
            Ok(rule) => rule
                .points()
                .iter()
                .zip(rule.weights())
                .map(|(xi, w)| w * el.jacobian_det(self.node_coords(), xi))
                .sum(),
            Err(_) => el.jacobian_det(self.node_coords(), &domain.centre()) * domain.measure(),
        }
    }

    /// Whether this face's map into space is affine (constant tangents, so a point is mapped
    /// back in one exact step and the measure density is constant): always for an element type
    /// that says so ([`SurfaceElement::is_affine`](crate::element::SurfaceElement::is_affine):
    /// Line2, Tri3), and otherwise decided from the node positions, in 2D as in 3D: when the
    /// tangents are the same at every node as at the centre, to round-off of the face's size (a
    /// straight Line3 with its middle node at the centre, a flat parallelogram Quad4, a flat
    /// Tri6 with its middle nodes at the centres of its edges).
    pub fn is_affine(&self) -> bool {
        let el = self.element;
        if el.is_affine() {
            return true;
        }
        let x = self.node_coords();
        let t0 = el.tangents(x, &el.domain().centre());
        let scale = t0[0].norm().max(t0[1].norm());
        el.node_reference_coords().iter().all(|xi| {
            let t = el.tangents(x, &Vector2::new(xi[0], xi[1]));
            (t[0] - t0[0]).amax().max((t[1] - t0[1]).amax()) <= 1e-13 * scale
        })
    }

    /// Whether the face lies in one plane (its unit normal the same at every node, to 1e-12):
    /// its Jacobian is then a polynomial; otherwise (a warped bilinear quad, a curved face)
    /// it is the norm of a polynomial vector, and its integrals need
    /// [`WARPED_EXTRA_DEGREE`] more.
    pub fn is_flat(&self) -> bool {
        let el = self.element;
        if el.is_affine() {
            return true;
        }
        let x = self.node_coords();
        let normal = |xi: &Vector2<f64>| {
            let t = el.tangents(x, xi);
            stable_normalize(&t[0].cross(&t[1])).unwrap_or_default()
        };
        let n0 = normal(&el.domain().centre());
        el.node_reference_coords()
            .iter()
            .all(|xi| (normal(&Vector2::new(xi[0], xi[1])) - n0).amax() <= 1e-12)
    }

    /// The degree a quadrature of an integrand over the face in its reference coordinates
    /// needs beyond the integrand's polynomial degree, for the face's Jacobian: 0 on an
    /// affine face (a constant Jacobian), 1 on a flat one (a polynomial), and
    /// [`WARPED_EXTRA_DEGREE`] on a warped or curved one (the norm of a polynomial vector):
    /// what keeps integrals over the face, or over parts of it, in step with the dual basis,
    /// which is built with the face's own Jacobian.
    pub fn jacobian_extra_degree(&self) -> u32 {
        if self.is_affine() {
            0
        } else if self.is_flat() {
            1
        } else {
            WARPED_EXTRA_DEGREE
        }
    }

    /// The largest distance between two corner nodes.
    pub fn diameter(&self) -> f64 {
        let c = self.element.corner_count();
        let mut d: f64 = 0.0;
        for i in 0..c {
            for j in i + 1..c {
                d = d.max((self.nodes[i] - self.nodes[j]).norm());
            }
        }
        d
    }

    /// The interpolated nodal normal field `sum_i N_i(xi) n_i` (not normalised) and its
    /// derivatives with respect to `xi`.
    pub fn normal_field(&self, xi: &Vector2<f64>) -> (Vector3<f64>, [Vector3<f64>; 2]) {
        let k = self.node_count();
        let mut n = [0.0; MAX_FACE_NODES];
        let mut g = [[0.0; 2]; MAX_FACE_NODES];
        self.element.shape_values_into(xi, &mut n[..k]);
        self.element.shape_gradients_into(xi, &mut g[..k]);
        let mut v = Vector3::zeros();
        let mut d = [Vector3::zeros(), Vector3::zeros()];
        for i in 0..k {
            v += self.normals[i] * n[i];
            d[0] += self.normals[i] * g[i][0];
            d[1] += self.normals[i] * g[i][1];
        }
        (v, d)
    }
}
