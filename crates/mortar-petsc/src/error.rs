//! The errors of a PETSc solve.

use crate::report::ConvergedReason;

/// Why a PETSc solve gave no solution.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PetscError {
    /// This build has no PETSc: build with the `petsc` feature.
    #[error("this build has no PETSc backend: build with the `petsc` feature (cargo build --features petsc)")]
    NotBuilt,
    /// PETSc (or MPI under it) could not start.
    #[error("PETSc could not start: {message} (error {code})")]
    Initialize {
        /// PETSc's error code.
        code: i32,
        /// PETSc's message.
        message: String,
    },
    /// PETSc was finalised in this process ([`crate::finalize`]); it cannot start again.
    #[error("PETSc was finalised in this process and cannot start again")]
    Finalized,
    /// The input does not make a linear system PETSc can take.
    #[error("invalid input: {0}")]
    InvalidInput(String),
    /// A PETSc function returned an error.
    #[error("{function} failed: {message} (PETSc error {code})")]
    Call {
        /// The PETSc function.
        function: &'static str,
        /// PETSc's error code.
        code: i32,
        /// PETSc's message for the innermost error.
        message: String,
    },
    /// The Krylov solver stopped without converging.
    #[error(
        "{ksp_type}+{pc_type} did not converge: {reason} after {iterations} iterations \
         (residual norm {residual_norm:.3e})"
    )]
    NotConverged {
        /// Why PETSc stopped.
        reason: ConvergedReason,
        /// Iterations done.
        iterations: usize,
        /// The last residual norm.
        residual_norm: f64,
        /// The Krylov method that ran.
        ksp_type: String,
        /// The preconditioner that ran.
        pc_type: String,
    },
    /// A solve finished, but its solution misses the tolerance: a direct solve (`preonly`)
    /// of a singular or too ill-conditioned matrix, or a Krylov method whose preconditioned
    /// residual converged while the true one did not (a preconditioner with a near-zero
    /// pivot); see [`accepted_residual`](crate::accepted_residual).
    #[error(
        "{ksp_type}+{pc_type} gave |b - Ax|/|b| = {relative_residual:.3e}, above the accepted \
         {tolerance:.1e}: the matrix is singular or too ill-conditioned, or the preconditioner \
         does not fit it"
    )]
    Inaccurate {
        /// `|b - A x| / |b|` of the solution found.
        relative_residual: f64,
        /// The bound it missed (`rtol` for a direct solve, else
        /// [`accepted_residual`](crate::accepted_residual)).
        tolerance: f64,
        /// The Krylov method that ran.
        ksp_type: String,
        /// The preconditioner that ran.
        pc_type: String,
    },
}
