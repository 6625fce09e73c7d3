//! What a solve did: which backend, method and preconditioner ran, how many iterations, the
//! final residual, and why PETSc stopped.

use std::fmt;

/// Why PETSc's Krylov solver stopped (its `KSPConvergedReason`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ConvergedReason {
    /// The residual norm fell below `rtol` times the initial one.
    Rtol,
    /// The residual norm fell below `atol`.
    Atol,
    /// The iteration count was reached by a method that counts that as done (`preonly`).
    Iterations,
    /// The Krylov space became invariant: the solution is exact in it.
    HappyBreakdown,
    /// Another converged reason of PETSc's, by its code.
    OtherConverged(i32),
    /// `max_it` iterations without reaching the tolerance.
    DivergedIterations,
    /// The residual norm grew past `dtol` times the initial one.
    DivergedDtol,
    /// The method broke down (a zero denominator).
    DivergedBreakdown,
    /// The matrix is indefinite, which the method cannot handle (CG).
    DivergedIndefiniteMatrix,
    /// The preconditioner is indefinite, which the method cannot handle (CG, MINRES).
    DivergedIndefinitePreconditioner,
    /// The preconditioner failed to build or apply (a zero pivot, a singular factor).
    DivergedPreconditionerFailed,
    /// A NaN or an infinity appeared.
    DivergedNanOrInf,
    /// The matrix or preconditioner is not symmetric, which the method needs.
    DivergedNonsymmetric,
    /// Another diverged reason of PETSc's, by its code.
    OtherDiverged(i32),
}

impl ConvergedReason {
    /// The reason of PETSc's code (positive: converged; negative: diverged).
    pub fn from_code(code: i32) -> Self {
        match code {
            1 | 2 => Self::Rtol,
            3 | 9 => Self::Atol,
            4 => Self::Iterations,
            8 => Self::HappyBreakdown,
            -3 => Self::DivergedIterations,
            -4 => Self::DivergedDtol,
            -5 | -6 => Self::DivergedBreakdown,
            -7 => Self::DivergedNonsymmetric,
            -8 => Self::DivergedIndefinitePreconditioner,
            -9 => Self::DivergedNanOrInf,
            -10 => Self::DivergedIndefiniteMatrix,
            -11 => Self::DivergedPreconditionerFailed,
            c if c > 0 => Self::OtherConverged(c),
            c => Self::OtherDiverged(c),
        }
    }

    /// Whether PETSc counts the solve as converged.
    pub fn is_converged(self) -> bool {
        matches!(
            self,
            Self::Rtol
                | Self::Atol
                | Self::Iterations
                | Self::HappyBreakdown
                | Self::OtherConverged(_)
        )
    }
}

impl fmt::Display for ConvergedReason {
    /// PETSc's name of the reason (`CONVERGED_RTOL`, `DIVERGED_INDEFINITE_PC`, ...).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Rtol => f.write_str("CONVERGED_RTOL"),
            Self::Atol => f.write_str("CONVERGED_ATOL"),
            Self::Iterations => f.write_str("CONVERGED_ITS"),
            Self::HappyBreakdown => f.write_str("CONVERGED_HAPPY_BREAKDOWN"),
            Self::OtherConverged(c) => write!(f, "CONVERGED({c})"),
            Self::DivergedIterations => f.write_str("DIVERGED_ITS"),
            Self::DivergedDtol => f.write_str("DIVERGED_DTOL"),
            Self::DivergedBreakdown => f.write_str("DIVERGED_BREAKDOWN"),
            Self::DivergedIndefiniteMatrix => f.write_str("DIVERGED_INDEFINITE_MAT"),
            Self::DivergedIndefinitePreconditioner => f.write_str("DIVERGED_INDEFINITE_PC"),
            Self::DivergedPreconditionerFailed => f.write_str("DIVERGED_PC_FAILED"),
            Self::DivergedNanOrInf => f.write_str("DIVERGED_NANORINF"),
            Self::DivergedNonsymmetric => f.write_str("DIVERGED_NONSYMMETRIC"),
            Self::OtherDiverged(c) => write!(f, "DIVERGED({c})"),
        }
    }
}

/// What one solve did.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveReport {
    /// The backend and its version (`PETSc 3.18.5`).
    pub backend: String,
    /// The Krylov method that ran (PETSc's `KSPType`, after the options were read).
    pub ksp_type: String,
    /// The preconditioner that ran (PETSc's `PCType`, after the options were read).
    pub pc_type: String,
    /// Whether GAMG was given rigid body modes as its near null space.
    pub near_null_space: bool,
    /// The options PETSc read (see `SolveOptions::options_string`).
    pub options: String,
    /// Krylov iterations.
    pub iterations: usize,
    /// The last residual norm PETSc measured (in the norm its convergence test uses).
    pub residual_norm: f64,
    /// Why PETSc stopped.
    pub reason: ConvergedReason,
    /// `|b - A x| / |b|` of the returned solution, measured after the solve (PETSc's own
    /// norm is the preconditioned one for CG and GMRES, and none for `preonly`).
    pub relative_residual: f64,
    /// Seconds to build the preconditioner (`KSPSetUp`: AMG hierarchy, factorisation); 0
    /// when the set-up was kept from an earlier solve of the same matrix.
    pub setup_seconds: f64,
    /// Whether the preconditioner was the one set up for an earlier solve of the same
    /// matrix (a backend's system solved again), not built for this solve.
    pub setup_kept: bool,
    /// Seconds of the Krylov iterations (`KSPSolve`).
    pub solve_seconds: f64,
}

impl fmt::Display for SolveReport {
    /// One line: `PETSc 3.18.5 cg+gamg: 12 iterations, residual 3.1e-9, CONVERGED_RTOL`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} {}+{}{}: {} iterations, residual {:.2e} (|b - Ax|/|b| {:.1e}), {} ({}, solve \
             {:.3} s)",
            self.backend,
            self.ksp_type,
            self.pc_type,
            if self.near_null_space {
                " (rigid body modes)"
            } else {
                ""
            },
            self.iterations,
            self.residual_norm,
            self.relative_residual,
            self.reason,
            if self.setup_kept {
                "setup kept".to_owned()
            } else {
                format!("setup {:.3} s", self.setup_seconds)
            },
            self.solve_seconds
        )
    }
}
