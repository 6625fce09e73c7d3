//! `SolverStats`: counts and timings of Newton steps, linear iterations and factorisations,
//! accumulated over the solves of a problem.

use std::time::Instant;

use mortar_fem::linalg::{BorderedLu, Factorization, LuFactorization, SolverError, SparseMatrix};

use super::{newton, NewtonOptions, NewtonProblem, NewtonReport};
use crate::error::PhysicsError;

/// Counters of the Newton solves of a problem and of their linear algebra, accumulated over
/// calls (time steps).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SolverStats {
    /// Newton steps.
    pub newton_iterations: usize,
    /// Linear iterations (1 per direct solve; GMRES iterations for JFNK).
    pub linear_iterations: usize,
    /// Numeric factorisations (of a Jacobian, or of a preconditioner's blocks counted as one).
    pub factorizations: usize,
    /// Symbolic analyses (1 when a pattern is reused throughout).
    pub symbolic_analyses: usize,
    /// Linear solves with a preconditioner kept from an earlier Newton or time step.
    pub reused_preconditioners: usize,
    /// Seconds assembling Jacobians (or preconditioner matrices).
    pub assembly_seconds: f64,
    /// Seconds in factorisations and linear solves.
    pub linear_seconds: f64,
    /// Seconds in the Newton solves, all included.
    pub total_seconds: f64,
}

impl SolverStats {
    /// Runs [`newton`] on `problem` from `x`, adding its time and, on success, its steps and
    /// linear iterations to the counters that `stats` finds in the problem.
    pub(crate) fn timed_newton<P: NewtonProblem>(
        problem: &mut P,
        x: &mut [f64],
        options: &NewtonOptions,
        stats: impl Fn(&mut P) -> &mut SolverStats,
    ) -> Result<NewtonReport, PhysicsError> {
        let start = Instant::now();
        let report = newton(problem, x, options);
        let s = stats(problem);
        s.total_seconds += start.elapsed().as_secs_f64();
        let report = report?;
        s.newton_iterations += report.iterations;
        s.linear_iterations += report.linear_iterations;
        Ok(report)
    }

    /// Factorises `a` into `lu`: numerically only, reusing the symbolic analysis, when the
    /// pattern is the same as the last one; from scratch otherwise. Counted.
    pub(crate) fn factorize<'a>(
        &mut self,
        lu: &'a mut Option<LuFactorization>,
        a: &SparseMatrix,
    ) -> Result<&'a LuFactorization, PhysicsError> {
        self.counted(lu, a, || LuFactorization::try_new(a))
    }

    /// [`factorize`](Self::factorize) with the last `border` rows and columns eliminated by
    /// their Schur complement ([`BorderedLu`]): a few dense rows and columns (the axial
    /// unknowns of free axial expansion) kept out of the sparse factorisation.
    pub(crate) fn factorize_bordered<'a>(
        &mut self,
        lu: &'a mut Option<BorderedLu>,
        a: &SparseMatrix,
        border: usize,
    ) -> Result<&'a BorderedLu, PhysicsError> {
        self.counted(lu, a, || BorderedLu::try_new(a, border))
    }

    /// Refactors the factorisation in `lu` with `a` if there is one and that succeeds, else
    /// `build`s a new one (a symbolic analysis); counted.
    pub(crate) fn counted<'a, F: Factorization>(
        &mut self,
        lu: &'a mut Option<F>,
        a: &SparseMatrix,
        build: impl FnOnce() -> Result<F, SolverError>,
    ) -> Result<&'a F, PhysicsError> {
        let reused = lu.as_mut().is_some_and(|f| f.refactor(a).is_ok());
        if !reused {
            *lu = Some(build()?);
            self.symbolic_analyses += 1;
        }
        self.factorizations += 1;
        Ok(lu.as_ref().expect("factorised above"))
    }
}
