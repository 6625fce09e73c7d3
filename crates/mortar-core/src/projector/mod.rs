//! Projectors: the direction along which points move between the slave and the master side.
//!
//! The 3D segment-based method projects both faces onto the auxiliary plane through the slave
//! face centre, with the projector's direction at that centre as the plane normal. The 2D
//! segment-based method and element-based integration project along the direction field at
//! each point.
//!
//! A field of one's own implements [`Projector`] (a name and the direction at a point); what
//! the coupling's fast paths rely on is apart, in [`ProjectorFastPaths`], which only a field
//! that wants them implements (the shipped ones do).

use nalgebra::{Vector2, Vector3};

use rayon::prelude::*;

use crate::element::ElementRef;
use crate::interface::{FaceGeometry, Interface};

/// A projection direction field on a slave face.
///
/// Implement this to add a field: its [`name`](Projector::name) and its
/// [`direction`](Projector::direction) at a point of a slave face are all the coupling needs.
///
/// **Fast paths.** The coupling also has faster ways to the same D and M that rely on facts
/// about a field: that it is affine on a face (the 2D segmentation then projects in closed
/// form), that it is one vector on the whole interface (a straight 2D interface is then a
/// sorted merge), that it stays within a face's nodal normals (the search then needs no
/// heuristic margin). It cannot find them from the directions it is handed, short of
/// sampling the field everywhere, so a field states them, apart from this trait: they are the
/// methods of [`ProjectorFastPaths`], which a field reaches the coupling through by returning
/// itself from [`fast_paths`](Projector::fast_paths). The default, `None`, states none of
/// them and is always correct: a field of one's own computes the same D and M (to round-off)
/// without knowing of them. The shipped [`ElementNormal`] and [`NodalNormalField`] implement
/// them.
///
/// (A trait of their own rather than a struct of flags: the facts are about a face, an
/// element type or an interface, and as methods with defaults a field states only those it
/// has.)
pub trait Projector: Send + Sync + std::fmt::Debug {
    /// A short name.
    fn name(&self) -> &'static str;

    /// The direction at `xi` (any length, pointing out of the slave body) and its derivatives
    /// with respect to `xi`.
    fn direction(
        &self,
        slave: &FaceGeometry,
        xi: &Vector2<f64>,
    ) -> (Vector3<f64>, [Vector3<f64>; 2]);

    /// The facts about this field that the coupling's fast paths rely on (see the trait's
    /// documentation), if it states any. The default, `None`, states none: always correct.
    fn fast_paths(&self) -> Option<&dyn ProjectorFastPaths> {
        None
    }
}

/// Facts about a [`Projector`]'s field that let the coupling take a fast path, reached
/// through [`Projector::fast_paths`]. Every method has a default that claims nothing and is
/// always correct; a field overrides those it knows to hold. A claim that does not hold gives
/// wrong results (a projection along the wrong direction, a master face the search misses),
/// so claim only what the field guarantees.
pub trait ProjectorFastPaths {
    /// Whether [`direction`](Projector::direction) is an affine function of `xi` on `slave` (a
    /// constant derivative). The 2D segmentation then projects master nodes onto an affine
    /// slave line by solving a quadratic in closed form instead of iterating. The default,
    /// `false`, is always correct.
    fn direction_is_affine(&self, slave: &FaceGeometry) -> bool {
        let _ = slave;
        false
    }

    /// The direction when it is one vector at every point of every slave face of
    /// `interface`, unit directions differing by at most `tol` (the coupling passes the
    /// resolution of the coordinates: the nodal normals of a straight line computed in
    /// floating point differ by a few rounding errors of the coordinates over the shortest
    /// face). The coupling then projects by a dot product along it (the sorted merge of a
    /// straight 2D interface; see [`assemble_coupling`](crate::assemble_coupling)). The
    /// default, `None`, is always correct.
    fn uniform_direction(&self, interface: &Interface, tol: f64) -> Option<Vector3<f64>> {
        let _ = (interface, tol);
        None
    }

    /// Whether on every face of type `element` the direction at each point is a convex
    /// combination of the face's nodal normals ([`FaceGeometry::normals`]), its length
    /// included. The search then bounds the reach of each slave face of that type by its
    /// nodes and nodal normals alone and does not inflate its box by
    /// [`Tolerances::search_inflation`](crate::Tolerances::search_inflation) (see
    /// [`Padding`](crate::search::Padding)). The default, `false`, is always correct.
    fn within_nodal_normals(&self, element: ElementRef) -> bool {
        let _ = element;
        false
    }
}

/// `direction(0)` when each of `direction(i)`, `i < count`, is within `tol` of it.
fn uniform(
    count: usize,
    tol: f64,
    direction: impl Fn(usize) -> Vector3<f64> + Sync,
) -> Option<Vector3<f64>> {
    let first = (count > 0).then(|| direction(0))?;
    (0..count)
        .into_par_iter()
        .all(|i| (direction(i) - first).amax() <= tol)
        .then_some(first)
}

/// The slave face's own normal at its centre, constant over the face.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ElementNormal;

impl Projector for ElementNormal {
    fn name(&self) -> &'static str {
        "element-normal"
    }

    fn direction(
        &self,
        slave: &FaceGeometry,
        _xi: &Vector2<f64>,
    ) -> (Vector3<f64>, [Vector3<f64>; 2]) {
        let c = slave.element.domain().centre();
        (
            slave.element.unit_normal(slave.node_coords(), &c),
            [Vector3::zeros(); 2],
        )
    }

    fn fast_paths(&self) -> Option<&dyn ProjectorFastPaths> {
        Some(self)
    }
}

impl ProjectorFastPaths for ElementNormal {
    /// Constant over the face.
    fn direction_is_affine(&self, _slave: &FaceGeometry) -> bool {
        true
    }

    /// The face normal when all of the slave's faces have one.
    fn uniform_direction(&self, interface: &Interface, tol: f64) -> Option<Vector3<f64>> {
        uniform(interface.slave().face_count(), tol, |f| {
            let face = interface.slave_face(f);
            self.direction(&face, &Vector2::zeros()).0
        })
    }
}

/// The continuous field of averaged nodal normals, interpolated with the slave shape
/// functions: `n(xi) = sum_i N_i(xi) n_i`. The default: it is continuous across slave faces,
/// which keeps the projection consistent on curved interfaces.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NodalNormalField;

impl Projector for NodalNormalField {
    fn name(&self) -> &'static str {
        "nodal-normal-field"
    }

    fn direction(
        &self,
        slave: &FaceGeometry,
        xi: &Vector2<f64>,
    ) -> (Vector3<f64>, [Vector3<f64>; 2]) {
        slave.normal_field(xi)
    }

    fn fast_paths(&self) -> Option<&dyn ProjectorFastPaths> {
        Some(self)
    }
}

impl ProjectorFastPaths for NodalNormalField {
    /// Where the shape functions are non-negative (the two-node line, the linear triangle,
    /// the bilinear quad: [`in_hull_of_nodes`](crate::search::in_hull_of_nodes)), the field
    /// interpolates the nodal normals with weights that are non-negative and sum to one.
    fn within_nodal_normals(&self, element: ElementRef) -> bool {
        crate::search::in_hull_of_nodes(element)
    }

    /// On an affine element with shape functions of degree one (Line2, Tri3), the
    /// interpolated nodal normals are affine in `xi`.
    fn direction_is_affine(&self, slave: &FaceGeometry) -> bool {
        slave.element.is_affine() && slave.element.shape_degree() == 1
    }

    /// The nodal normal when all of the slave's are one (the field interpolates them with
    /// shape functions that sum to one).
    fn uniform_direction(&self, interface: &Interface, tol: f64) -> Option<Vector3<f64>> {
        let normals = interface.slave_nodal_normals();
        let nodes = interface.slave_nodes();
        uniform(nodes.len(), tol, |i| normals[nodes[i] as usize])
    }
}
