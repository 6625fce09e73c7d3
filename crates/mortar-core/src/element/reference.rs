//! Reference domains of surface elements (`[-1, 1]`, the unit triangle, `[-1, 1]^2`) and the
//! `ReferenceElement` trait: shape functions and their derivatives on those domains.

use nalgebra::Vector2;

/// The largest node count of a surface element (Quad9).
pub const MAX_FACE_NODES: usize = 9;

/// The reference domains of surface elements.
///
/// - `Line`: `[-1, 1]` (the second reference coordinate is unused and zero);
/// - `Triangle`: vertices `(0,0)`, `(1,0)`, `(0,1)`;
/// - `Quadrilateral`: `[-1, 1]^2`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ReferenceDomain {
    /// `[-1, 1]`.
    Line,
    /// The unit right triangle `(0,0)`, `(1,0)`, `(0,1)`.
    Triangle,
    /// `[-1, 1]^2`.
    Quadrilateral,
}

impl ReferenceDomain {
    /// Topological dimension: 1 for lines, 2 for triangles and quads.
    pub fn dim(self) -> usize {
        match self {
            ReferenceDomain::Line => 1,
            _ => 2,
        }
    }

    /// The measure of the reference domain (2, 1/2 or 4).
    pub fn measure(self) -> f64 {
        match self {
            ReferenceDomain::Line => 2.0,
            ReferenceDomain::Triangle => 0.5,
            ReferenceDomain::Quadrilateral => 4.0,
        }
    }

    /// The centre of the domain.
    pub fn centre(self) -> Vector2<f64> {
        match self {
            ReferenceDomain::Triangle => Vector2::new(1.0 / 3.0, 1.0 / 3.0),
            _ => Vector2::zeros(),
        }
    }

    /// Whether `xi` lies in the closed domain, allowing `tol` reference units outside it.
    pub fn contains(self, xi: &Vector2<f64>, tol: f64) -> bool {
        match self {
            ReferenceDomain::Line => xi.x.abs() <= 1.0 + tol,
            ReferenceDomain::Triangle => xi.x >= -tol && xi.y >= -tol && xi.x + xi.y <= 1.0 + tol,
            ReferenceDomain::Quadrilateral => xi.x.abs() <= 1.0 + tol && xi.y.abs() <= 1.0 + tol,
        }
    }

    /// How far outside the domain `xi` lies (0 inside), in reference units.
    pub fn distance_outside(self, xi: &Vector2<f64>) -> f64 {
        match self {
            ReferenceDomain::Line => (xi.x.abs() - 1.0).max(0.0),
            ReferenceDomain::Triangle => (-xi.x).max(-xi.y).max(xi.x + xi.y - 1.0).max(0.0),
            ReferenceDomain::Quadrilateral => (xi.x.abs() - 1.0).max(xi.y.abs() - 1.0).max(0.0),
        }
    }
}

/// A reference element: nodes and shape functions on a reference domain.
///
/// Shape functions are written into a caller's buffer of at least [`node_count`] entries, so
/// that hot loops allocate nothing. Node order follows Gmsh. Implementations must be
/// `Send + Sync` (they are shared between threads) and should be zero-sized.
///
/// [`node_count`]: ReferenceElement::node_count
pub trait ReferenceElement: Send + Sync + std::fmt::Debug {
    /// A short name, such as `"Tri3"`.
    fn name(&self) -> &'static str;
    /// The reference domain.
    fn domain(&self) -> ReferenceDomain;
    /// Number of nodes (at most [`MAX_FACE_NODES`]).
    fn node_count(&self) -> usize;
    /// Number of corner nodes; they come first in the node order and, in that order, go
    /// counter-clockwise round the reference domain.
    fn corner_count(&self) -> usize;
    /// The largest total polynomial degree of a shape function (1 for Tri3, 2 for Quad4 whose
    /// bilinear term `xi*eta` has degree 2).
    fn shape_degree(&self) -> u32;
    /// Reference coordinates of the nodes, in node order.
    fn node_reference_coords(&self) -> &'static [[f64; 2]];
    /// Shape function values at `xi`, written into `out[..node_count]`.
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]);
    /// Shape function gradients (d/dxi, d/deta) at `xi`, written into `out[..node_count]`.
    /// For line elements the second component is zero.
    fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]);
}
