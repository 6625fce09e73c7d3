//! Two bodies tied by mortar: the interface and its coupling ([`Tie`]), and the tied linear
//! system ([`TiedSystem`]) solved either as a saddle point (standard or dual multipliers,
//! sparse LU) or, when D is diagonal, condensed to a symmetric positive definite system
//! (sparse Cholesky; by body, the two bodies in parallel, when the interface is small). The choice is automatic by default and reported
//! ([`FormulationReport`]).
//!
//! Dirichlet conditions on slave interface nodes (where the interface meets a Dirichlet
//! boundary) conflict with the condensation; see [`SlaveDirichlet`] for how they are handled
//! (or refused), and [`slave_dirichlet_shares`] for the same treatment of a coupling's rows
//! in a program that assembles its own system.

mod crosspoint;
mod formulation;
mod system;
mod tie;

pub use crosspoint::{slave_dirichlet_shares, SlaveDirichletShares};
pub use formulation::{
    Formulation, FormulationChoice, FormulationReport, SlaveDirichlet, TiedOptions,
};
pub use mortar_fem::linalg::SUBSTRUCTURED_MIN;
pub use system::{SystemSeconds, TiedFields, TiedSystem};
pub use tie::{kron_identity, Interpolated, Tie};
