//! Nonlinear solvers: one Newton loop ([`newton`]) that never owns the Jacobian (the problem
//! supplies "solve `J dx = r`", [`NewtonProblem`]), so that an assembled Newton (sparse LU of
//! the Jacobian) and a Jacobian-free Newton-Krylov method ([`jfnk_solve`]: GMRES on
//! finite-difference Jacobian-vector products, right-preconditioned by an assembled
//! approximate Jacobian) share it; Eisenstat-Walker forcing terms ([`Forcing`]) and a
//! backtracking line search.

mod jfnk;
mod newton;
mod stats;

pub use jfnk::{jfnk_solve, FiniteDifferenceJacobian, JfnkOptions};
pub use newton::{
    assembled_residual_scale, newton, Forcing, NewtonFailure, NewtonFailureReason, NewtonOptions,
    NewtonProblem, NewtonReport, ROUNDOFF_FLOOR,
};
pub use stats::SolverStats;
