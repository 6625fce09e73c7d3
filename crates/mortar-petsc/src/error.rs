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
    /// A direct solve (`preonly`) finished, but its solution misses the tolerance: the
    /// matrix is singular or too ill-conditioned for the factorisation.
    #[error(
        "{ksp_type}+{pc_type} gave |b - Ax|/|b| = {relative_residual:.3e}, above the tolerance \
         {tolerance:.1e}: the matrix is singular or too ill-conditioned"
    )]
    Inaccurate {
        /// `|b - A x| / |b|` of the solution found.
        relative_residual: f64,
        /// The tolerance it missed (`rtol`).
        tolerance: f64,
        /// The Krylov method that ran.
        ksp_type: String,
        /// The preconditioner that ran.
        pc_type: String,
    },
}
