//! Volume elements: the cells of the bodies that the physics assembles on (heat conduction,
//! elasticity), beside the surface elements of the interface.
//!
//! A volume element has a reference dimension of 2 (cells of a 2D body in the plane `z = 0`:
//! triangles and quadrilaterals) or 3 (tetrahedra and hexahedra). Reference domains:
//!
//! - [`VolumeDomain::Triangle`]: `(0,0), (1,0), (0,1)`;
//! - [`VolumeDomain::Quadrilateral`]: `[-1, 1]^2`;
//! - [`VolumeDomain::Tetrahedron`]: `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`;
//! - [`VolumeDomain::Hexahedron`]: `[-1, 1]^3`.
//!
//! Reference points are `Vector3` throughout; 2D elements ignore (and write zero for) the third
//! coordinate. Node order follows Gmsh. Each element lists its boundary faces as local node
//! lists ordered so that the face normal of the face's surface element (see
//! [`SurfaceElement`](mortar_core::element::SurfaceElement): `(t_y, -t_x)` for a line, `t1 x t2` for a face)
//! points out of the cell when the cell is positively oriented (positive Jacobian
//! determinant). Extracting a body's boundary therefore gives an outward-oriented surface that
//! can be handed to an [`Interface`](mortar_core::Interface) directly.
//!
//! [`CellValues`] caches what assembly loops need at the quadrature points of one cell (shape
//! values, physical gradients, weights times Jacobian determinant, points), in the manner of
//! deal.II's `FEValues`: adding an element never changes an assembly loop.

mod cell_values;

pub use cell_values::{CellValues, NonPositiveJacobian};

use nalgebra::{Matrix3, Vector3};

use mortar_core::element::ElementRef;

/// The largest node count of a volume element (Hex27).
pub const MAX_CELL_NODES: usize = 27;

/// The reference domains of volume elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum VolumeDomain {
    /// The unit right triangle `(0,0), (1,0), (0,1)` (2D bodies).
    Triangle,
    /// `[-1, 1]^2` (2D bodies).
    Quadrilateral,
    /// The unit tetrahedron `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`.
    Tetrahedron,
    /// `[-1, 1]^3`.
    Hexahedron,
}

impl VolumeDomain {
    /// Reference dimension: 2 for triangles and quadrilaterals, 3 for tetrahedra and
    /// hexahedra.
    pub fn dim(self) -> usize {
        match self {
            VolumeDomain::Triangle | VolumeDomain::Quadrilateral => 2,
            VolumeDomain::Tetrahedron | VolumeDomain::Hexahedron => 3,
        }
    }

    /// The measure of the reference domain (1/2, 4, 1/6 or 8).
    pub fn measure(self) -> f64 {
        match self {
            VolumeDomain::Triangle => 0.5,
            VolumeDomain::Quadrilateral => 4.0,
            VolumeDomain::Tetrahedron => 1.0 / 6.0,
            VolumeDomain::Hexahedron => 8.0,
        }
    }

    /// The centre (centroid) of the domain.
    pub fn centre(self) -> Vector3<f64> {
        match self {
            VolumeDomain::Triangle => Vector3::new(1.0 / 3.0, 1.0 / 3.0, 0.0),
            VolumeDomain::Tetrahedron => Vector3::new(0.25, 0.25, 0.25),
            _ => Vector3::zeros(),
        }
    }

    /// Whether `xi` lies in the closed domain, allowing `tol` reference units outside it (the
    /// third coordinate is ignored in 2D).
    pub fn contains(self, xi: &Vector3<f64>, tol: f64) -> bool {
        match self {
            VolumeDomain::Triangle => xi.x >= -tol && xi.y >= -tol && xi.x + xi.y <= 1.0 + tol,
            VolumeDomain::Quadrilateral => xi.x.abs() <= 1.0 + tol && xi.y.abs() <= 1.0 + tol,
            VolumeDomain::Tetrahedron => {
                xi.x >= -tol && xi.y >= -tol && xi.z >= -tol && xi.x + xi.y + xi.z <= 1.0 + tol
            }
            VolumeDomain::Hexahedron => xi.iter().all(|c| c.abs() <= 1.0 + tol),
        }
    }
}

/// A volume element type shared between threads and meshes (element types are zero-sized
/// statics).
pub type VolumeElementRef = &'static dyn VolumeElement;

/// A volume element: shape functions on a reference domain of dimension 2 or 3, its boundary
/// faces, and (provided) the geometric map into space.
///
/// Shape values and gradients are written into a caller's buffer of at least
/// [`node_count`](VolumeElement::node_count) entries, so that hot loops allocate nothing.
/// Gradients are with respect to the reference coordinates; in 2D the third component is zero.
pub trait VolumeElement: Send + Sync + std::fmt::Debug {
    /// A short name, such as `"Tet4"`.
    fn name(&self) -> &'static str;
    /// The reference domain.
    fn domain(&self) -> VolumeDomain;
    /// Reference dimension (2 or 3).
    fn dim(&self) -> usize {
        self.domain().dim()
    }
    /// Number of nodes (at most [`MAX_CELL_NODES`]).
    fn node_count(&self) -> usize;
    /// The largest total polynomial degree of a shape function (1 for Tet4, 2 for Quad4,
    /// 3 for Hex8).
    fn shape_degree(&self) -> u32;
    /// Reference coordinates of the nodes, in node order (third coordinate zero in 2D).
    fn node_reference_coords(&self) -> &'static [[f64; 3]];
    /// Shape function values at `xi`, written into `out[..node_count]`.
    fn shape_values_into(&self, xi: &Vector3<f64>, out: &mut [f64]);
    /// Shape function gradients with respect to `xi` at `xi`, written into
    /// `out[..node_count]` (third component zero in 2D).
    fn shape_gradients_into(&self, xi: &Vector3<f64>, out: &mut [[f64; 3]]);
    /// The Gmsh element type number (2 triangle, 3 quadrangle, 4 tetrahedron, 5 hexahedron).
    fn gmsh_type(&self) -> Option<u32> {
        None
    }
    /// Whether the geometric map is affine for every placement of the nodes (Tri3, Tet4).
    fn is_affine(&self) -> bool {
        false
    }
    /// The boundary faces as local node lists, each ordered so that its surface element's
    /// normal points out of a positively oriented cell (lines in 2D, faces in 3D).
    fn faces(&self) -> &'static [&'static [usize]];
    /// The surface element type of face `face` (Line2 for the edges of a 2D cell, Tri3 or
    /// Quad4 for the faces of a 3D one).
    ///
    /// # Panics
    /// If `face` is not below the number of faces.
    fn face_element(&self, face: usize) -> ElementRef;

    /// The point `x(xi) = sum_i N_i(xi) x_i` for the node coordinates `nodes`.
    fn map(&self, nodes: &[Vector3<f64>], xi: &Vector3<f64>) -> Vector3<f64> {
        let mut n = [0.0; MAX_CELL_NODES];
        let k = self.node_count();
        self.shape_values_into(xi, &mut n[..k]);
        (0..k).fold(Vector3::zeros(), |x, i| x + nodes[i] * n[i])
    }

    /// The Jacobian `J[i][j] = dx_i / dxi_j` at `xi`. For 2D elements the third column is
    /// `e_z`, so that `det J` is the area density and `J^-T` maps gradients in the plane.
    fn jacobian(&self, nodes: &[Vector3<f64>], xi: &Vector3<f64>) -> Matrix3<f64> {
        let mut g = [[0.0; 3]; MAX_CELL_NODES];
        let k = self.node_count();
        self.shape_gradients_into(xi, &mut g[..k]);
        jacobian_from_gradients(self.dim(), &nodes[..k], &g[..k])
    }
}

/// `J = sum_i x_i (grad_xi N_i)^T`; in 2D the third column is `e_z` (and the third row of the
/// in-plane columns is ignored, the cell lying in `z = 0`).
pub(crate) fn jacobian_from_gradients(
    dim: usize,
    nodes: &[Vector3<f64>],
    grads: &[[f64; 3]],
) -> Matrix3<f64> {
    let mut j = Matrix3::zeros();
    for (x, g) in nodes.iter().zip(grads) {
        for r in 0..dim {
            for c in 0..dim {
                j[(r, c)] += x[r] * g[c];
            }
        }
    }
    if dim == 2 {
        j[(2, 2)] = 1.0;
    }
    j
}
