//! The error type of the physics: every failure names the body, cell or node concerned.

use mortar_core::{MortarError, Side};
use mortar_fem::element::NonPositiveJacobian;
use mortar_fem::field::FieldError;
use mortar_fem::linalg::SolverError;
use mortar_fem::mesh::VolumeMeshError;

use crate::laws::LawError;
use crate::nonlinear::NewtonFailure;
use crate::tying::TyingError;

/// Errors of the physics crate.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PhysicsError {
    /// A volume mesh is invalid (see [`VolumeMeshError`]).
    #[error(transparent)]
    Mesh(#[from] VolumeMeshError),
    /// The mortar core refused the interface or its options.
    #[error(transparent)]
    Mortar(#[from] MortarError),
    /// A tying operator could not be built (a forced dual condensation with a non-diagonal D).
    #[error(transparent)]
    Tying(#[from] TyingError),
    /// A factorisation or solve failed.
    #[error(transparent)]
    Solver(#[from] SolverError),
    /// The linear solve of a named system failed: an iterative backend that did not converge
    /// (its method, iterations and residual in `source`), say.
    #[error("{system}: {source}")]
    LinearSolve {
        /// Which system, and where in the solve (load step, Newton step).
        system: String,
        /// The backend's error.
        source: SolverError,
    },
    /// A cell's Jacobian determinant is not positive.
    #[error("body {body:?}: cell {cell} is inverted or degenerate: {source}")]
    InvertedCell {
        /// The body.
        body: String,
        /// The cell tag.
        cell: u64,
        /// Where and how much.
        source: NonPositiveJacobian,
    },
    /// Material data or options out of range (a non-positive conductivity, a zero time step).
    #[error("body {body:?}: {what}")]
    InvalidInput {
        /// The body (or `"options"`).
        body: String,
        /// What is wrong.
        what: String,
    },
    /// A node of an axisymmetric (r-z) body lies at a negative radius (x < 0).
    #[error("body {body:?}: node {node} lies at the negative radius x = {radius:e}: an axisymmetric (r-z) model needs x = r >= 0")]
    NegativeRadius {
        /// The body.
        body: String,
        /// The node tag.
        node: u64,
        /// Its x coordinate.
        radius: f64,
    },
    /// A node on the axis (r = 0) of an axisymmetric elastic body has no prescribed radial
    /// displacement: a point of the axis cannot move radially, `u_r = 0` must be prescribed
    /// there (component x).
    #[error("body {body:?}: node {node} lies on the axis (r = 0) of the axisymmetric model and needs u_r = 0 prescribed (a displacement condition on component x)")]
    AxisNodeFree {
        /// The body.
        body: String,
        /// The node tag.
        node: u64,
    },
    /// A rigid motion of a body is held neither by its displacement conditions nor by the
    /// contact (see [`rigid_motions`](crate::contact::rigid_motions)): the solution would be
    /// determined only up to that motion.
    #[error("body {body:?} is not held against rigid motion: {motions} moves none of its prescribed displacements and no slave interface node along its normal, so neither its displacement conditions nor the (frictionless) contact hold it; add a displacement condition that stops it")]
    NotHeld {
        /// The body.
        body: String,
        /// The free motions, described (see
        /// [`RigidMotion::describe`](crate::contact::RigidMotion::describe)), joined by
        /// `" and "`.
        motions: String,
    },
    /// An interface surface names a node its body's mesh does not have.
    #[error("the {side} interface surface refers to node {tag}, which the {side} body's mesh does not have")]
    InterfaceNodeNotInBody {
        /// The side.
        side: Side,
        /// The node tag.
        tag: u64,
    },
    /// Slave interface nodes carry Dirichlet conditions and the options refuse them.
    #[error("{count} slave interface node(s) carry Dirichlet conditions (first: node {tag}) and the tying options refuse them (SlaveDirichlet::Refuse); make that body the master side, or use SlaveDirichlet::Redistribute")]
    DirichletOnSlave {
        /// The first such node's tag.
        tag: u64,
        /// How many there are.
        count: usize,
    },
    /// A vector has the wrong length.
    #[error("{what}: expected length {expected}, got {got}")]
    WrongLength {
        /// Which vector.
        what: String,
        /// The expected length.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// A constraint law refused its input or parameters.
    #[error(transparent)]
    Law(#[from] LawError),
    /// Newton's method failed (its residual history is in the error).
    #[error(transparent)]
    Newton(#[from] NewtonFailure),
}

impl From<FieldError> for PhysicsError {
    /// A field's numbering error as [`PhysicsError::InvalidInput`]: body `"options"` for an
    /// unknown component name (a user's text), `"dof layout"` for the rest.
    fn from(e: FieldError) -> Self {
        let body = match e {
            FieldError::UnknownComponent { .. } => "options",
            _ => "dof layout",
        };
        PhysicsError::InvalidInput {
            body: body.into(),
            what: e.to_string(),
        }
    }
}
