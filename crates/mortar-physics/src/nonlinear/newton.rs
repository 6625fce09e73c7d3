//! Newton's method with backtracking line search and Eisenstat-Walker forcing (`newton`), for
//! any `NewtonProblem` that gives a residual and solves its own linearised system.

use std::time::Instant;

use mortar_core::linalg::SparseMatrix;

use crate::error::PhysicsError;

/// A nonlinear problem `F(x) = 0` as Newton's method sees it: a residual, and a solver of the
/// linearised problem. The problem owns its Jacobian (assembled, approximated, or none).
pub trait NewtonProblem {
    /// Writes `F(x)` into `r`.
    ///
    /// # Errors
    /// A failure of the evaluation (a law refusing a NaN, say); Newton's line search treats
    /// it as a rejected step.
    fn residual(&self, x: &[f64], r: &mut [f64]) -> Result<(), PhysicsError>;

    /// Solves `J(x) dx = r` (`r = F(x)`), to the relative residual `forcing` if the solver is
    /// iterative (a direct solver ignores it). Returns the linear iterations spent (1 for a
    /// direct solve).
    ///
    /// # Errors
    /// A failure of the factorisation or of the iterative solver.
    fn solve_linearized(
        &mut self,
        x: &[f64],
        r: &[f64],
        dx: &mut [f64],
        forcing: f64,
    ) -> Result<usize, PhysicsError>;

    /// The size of the terms that make up `F(x)` before they cancel (for an assembled
    /// operator `A x - f`: `| |A| |x| | + |f|`), the problem's own magnitude. When [`newton`]
    /// can make no more progress (its line search fails, or its steps run out) with `|F|` at
    /// round-off of it ([`ROUNDOFF_FLOOR`] times it), it has converged, whatever the relative
    /// criterion asked: a solve that starts at round-off (zero load) is not a failure. Asked
    /// only then, so it costs nothing on the way. The default, 0, has no floor.
    ///
    /// # Errors
    /// A failure of the evaluation.
    fn residual_scale(&mut self, x: &[f64]) -> Result<f64, PhysicsError> {
        let _ = x;
        Ok(0.0)
    }
}

/// The magnitude of an assembled residual `F(x) = A x - f` before its terms cancel,
/// `| |A| |x| | + |F(x) - A x|` (Euclidean norms): what [`NewtonProblem::residual_scale`]
/// returns for a problem that can assemble a matrix `A` (its Picard matrix, say) beside its
/// residual `r = F(x)`.
pub fn assembled_residual_scale(a: &SparseMatrix, x: &[f64], r: &[f64]) -> f64 {
    let mut terms = vec![0.0; x.len()];
    let mut ax = vec![0.0; x.len()];
    for (row, vec) in a.outer_iterator().enumerate() {
        for (col, v) in vec.iter() {
            terms[row] += (v * x[col]).abs();
            ax[row] += v * x[col];
        }
    }
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let loads: Vec<f64> = r.iter().zip(&ax).map(|(f, a)| f - a).collect();
    norm(&terms) + norm(&loads)
}

/// The round-off floor of [`newton`]'s convergence test, relative to
/// [`NewtonProblem::residual_scale`]: `10 eps`, about 2e-15 (the pellet at zero power
/// stagnates at 8e-18 of its scale, 2e6 W/m against a residual of 1.7e-11 W/m).
pub const ROUNDOFF_FLOOR: f64 = 10.0 * f64::EPSILON;

/// How tightly each Newton step's linear problem is solved (relative residual `eta`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Forcing {
    /// A fixed `eta`.
    Constant(f64),
    /// Eisenstat and Walker's choice 2: `eta_k = gamma (|F_k| / |F_{k-1}|)^alpha`, safeguarded
    /// by `gamma eta_{k-1}^alpha` when that exceeds 0.1, at most `max`, and never below
    /// `0.5 tol / |F_k|` (no oversolving of the last step).
    EisenstatWalker {
        /// `eta_0`.
        initial: f64,
        /// `gamma` (0.9).
        gamma: f64,
        /// `alpha` (2).
        alpha: f64,
        /// The largest `eta` (0.9).
        max: f64,
    },
}

impl Forcing {
    /// Eisenstat-Walker with `eta_0 = 0.1`, `gamma = 0.9`, `alpha = 2`, `eta_max = 0.9`.
    pub fn eisenstat_walker() -> Self {
        Self::EisenstatWalker {
            initial: 0.1,
            gamma: 0.9,
            alpha: 2.0,
            max: 0.9,
        }
    }
}

/// Settings of [`newton`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Converged when `|F| <= absolute_tolerance` ...
    pub absolute_tolerance: f64,
    /// ... or `|F| <= relative_tolerance |F(x_0)|` (Euclidean norms), or, once no more
    /// progress can be made, at round-off of the problem's own magnitude
    /// ([`NewtonProblem::residual_scale`]).
    pub relative_tolerance: f64,
    /// The most Newton steps.
    pub max_iterations: usize,
    /// The linear forcing terms.
    pub forcing: Forcing,
    /// The most step halvings of the backtracking line search (0: full steps only).
    pub max_backtracks: usize,
}

impl Default for NewtonOptions {
    /// Absolute tolerance 0, relative 1e-10, 30 steps, Eisenstat-Walker, 10 halvings.
    fn default() -> Self {
        Self {
            absolute_tolerance: 0.0,
            relative_tolerance: 1e-10,
            max_iterations: 30,
            forcing: Forcing::eisenstat_walker(),
            max_backtracks: 10,
        }
    }
}

/// What a converged [`newton`] did.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct NewtonReport {
    /// Newton steps taken.
    pub iterations: usize,
    /// Linear iterations over all steps.
    pub linear_iterations: usize,
    /// Residual evaluations (line search trials included; JFNK's products not).
    pub residual_evaluations: usize,
    /// Step halvings of the line search over all steps.
    pub backtracks: usize,
    /// `|F|` after each step (the first entry at `x_0`).
    pub residual_history: Vec<f64>,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// Why Newton's method failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum NewtonFailureReason {
    /// The iteration limit was reached.
    MaxIterations,
    /// No step length reduced the residual enough.
    LineSearch,
    /// The residual is not finite at the initial guess.
    NonFiniteResidual,
}

/// A failed Newton solve, with its residual history.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("Newton's method failed ({reason:?}) after {iterations} step(s); residual norms: {residual_history:?}")]
pub struct NewtonFailure {
    /// Why.
    pub reason: NewtonFailureReason,
    /// Steps taken.
    pub iterations: usize,
    /// `|F|` at `x_0` and after each step.
    pub residual_history: Vec<f64>,
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Solves `F(x) = 0` by Newton's method from the `x` given, with a backtracking line search
/// (Armijo on `|F|`: accept the step length `a` when `|F(x - a dx)| <= (1 - 1e-4 a) |F(x)|`,
/// halving `a` otherwise) and the forcing terms of `options` passed to the problem's linear
/// solver. On success `x` holds the solution.
///
/// # Errors
/// [`PhysicsError::Newton`] (with the residual history) when the iteration limit is reached,
/// the line search fails or the initial residual is not finite; the errors of the problem's
/// residual at `x_0` and of its linear solver.
pub fn newton(
    problem: &mut dyn NewtonProblem,
    x: &mut [f64],
    options: &NewtonOptions,
) -> Result<NewtonReport, PhysicsError> {
    let start = Instant::now();
    let n = x.len();
    let mut r = vec![0.0; n];
    let mut dx = vec![0.0; n];
    let mut trial = vec![0.0; n];
    let mut r_trial = vec![0.0; n];
    problem.residual(x, &mut r)?;
    let mut norm_r = norm(&r);
    let mut report = NewtonReport {
        residual_evaluations: 1,
        residual_history: vec![norm_r],
        ..Default::default()
    };
    let fail = |reason, report: &NewtonReport| {
        PhysicsError::Newton(NewtonFailure {
            reason,
            iterations: report.iterations,
            residual_history: report.residual_history.clone(),
        })
    };
    if !norm_r.is_finite() {
        return Err(fail(NewtonFailureReason::NonFiniteResidual, &report));
    }
    let tol = options
        .absolute_tolerance
        .max(options.relative_tolerance * norm_r);
    // Whether `|F(x)|` is at round-off of the problem's own magnitude: asked when no more
    // progress can be made.
    let at_roundoff = |problem: &mut dyn NewtonProblem, x: &[f64], norm_r: f64| {
        problem
            .residual_scale(x)
            .map(|scale| norm_r <= ROUNDOFF_FLOOR * scale)
    };
    let mut eta = match options.forcing {
        Forcing::Constant(e) => e,
        Forcing::EisenstatWalker { initial, .. } => initial,
    };
    let mut norm_prev = norm_r;
    loop {
        if norm_r <= tol {
            report.seconds = start.elapsed().as_secs_f64();
            return Ok(report);
        }
        if report.iterations >= options.max_iterations {
            if at_roundoff(problem, x, norm_r)? {
                report.seconds = start.elapsed().as_secs_f64();
                return Ok(report);
            }
            return Err(fail(NewtonFailureReason::MaxIterations, &report));
        }
        eta = next_forcing(
            &options.forcing,
            report.iterations,
            eta,
            norm_r,
            norm_prev,
            tol,
        );
        dx.fill(0.0);
        report.linear_iterations += problem.solve_linearized(x, &r, &mut dx, eta)?;
        report.iterations += 1;
        let search = LineSearch {
            x,
            dx: &dx,
            norm_r,
            max_backtracks: options.max_backtracks,
        };
        if let Some(halvings) = search.run(problem, &mut trial, &mut r_trial, &mut report) {
            report.backtracks += halvings;
        } else {
            if at_roundoff(problem, x, norm_r)? {
                report.seconds = start.elapsed().as_secs_f64();
                return Ok(report);
            }
            return Err(fail(NewtonFailureReason::LineSearch, &report));
        }
        x.copy_from_slice(&trial);
        std::mem::swap(&mut r, &mut r_trial);
        norm_prev = norm_r;
        norm_r = norm(&r);
        report.residual_history.push(norm_r);
    }
}

/// The forcing term of the next Newton step after `iterations` steps, from the last one
/// `eta`: constant, or Eisenstat-Walker's of the residual norms `norm_r` (now) and
/// `norm_prev` (before the last step) with its safeguard, kept above `0.5 tol / |F|`.
fn next_forcing(
    forcing: &Forcing,
    iterations: usize,
    mut eta: f64,
    norm_r: f64,
    norm_prev: f64,
    tol: f64,
) -> f64 {
    if let Forcing::EisenstatWalker {
        gamma, alpha, max, ..
    } = *forcing
    {
        if iterations > 0 {
            let mut e = gamma * (norm_r / norm_prev).powf(alpha);
            let safeguard = gamma * eta.powf(alpha);
            if safeguard > 0.1 {
                e = e.max(safeguard);
            }
            eta = e.min(max);
        }
        eta = eta.max(0.5 * tol / norm_r).min(max);
    }
    eta
}

/// The backtracking line search of [`newton`] from `x` along `-dx` (`|F(x)| = norm_r`).
struct LineSearch<'a> {
    x: &'a [f64],
    dx: &'a [f64],
    norm_r: f64,
    max_backtracks: usize,
}

impl LineSearch<'_> {
    /// Tries the step lengths `1, 1/2, ...` (at most `max_backtracks` halvings) until
    /// `|F(x - a dx)| <= (1 - 1e-4 a) |F(x)|`, counting each residual in `report`: the number
    /// of halvings, `trial` the accepted point and `r_trial` its residual; `None` if none is
    /// accepted.
    fn run(
        &self,
        problem: &mut dyn NewtonProblem,
        trial: &mut [f64],
        r_trial: &mut [f64],
        report: &mut NewtonReport,
    ) -> Option<usize> {
        let mut a = 1.0;
        for halving in 0..=self.max_backtracks {
            for i in 0..self.x.len() {
                trial[i] = self.x[i] - a * self.dx[i];
            }
            report.residual_evaluations += 1;
            let ok = problem.residual(trial, r_trial).is_ok();
            let nt = norm(r_trial);
            if ok && nt.is_finite() && nt <= (1.0 - 1e-4 * a) * self.norm_r {
                return Some(halving);
            }
            a *= 0.5;
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `F(x) = (x0^2 - 2, x1^3 - x0)`, solved with the exact 2x2 Jacobian.
    struct Small {
        fail: bool,
    }

    impl NewtonProblem for Small {
        fn residual(&self, x: &[f64], r: &mut [f64]) -> Result<(), PhysicsError> {
            r[0] = x[0] * x[0] - 2.0;
            r[1] = x[1].powi(3) - x[0];
            if self.fail {
                r[0] = x[0] * x[0] + 1.0; // no root
            }
            Ok(())
        }
        fn solve_linearized(
            &mut self,
            x: &[f64],
            r: &[f64],
            dx: &mut [f64],
            _forcing: f64,
        ) -> Result<usize, PhysicsError> {
            let (a, c, d) = (2.0 * x[0], -1.0, 3.0 * x[1] * x[1]);
            dx[0] = r[0] / a;
            dx[1] = (r[1] - c * dx[0]) / d;
            Ok(1)
        }
    }

    #[test]
    fn converges_quadratically_and_fails_with_history() {
        let mut x = [1.0, 1.0];
        let tight = NewtonOptions {
            relative_tolerance: 1e-14,
            ..NewtonOptions::default()
        };
        let rep = newton(&mut Small { fail: false }, &mut x, &tight).unwrap();
        assert!((x[0] - 2f64.sqrt()).abs() < 1e-12);
        assert!((x[1] - 2f64.sqrt().cbrt()).abs() < 1e-12);
        assert!(rep.iterations < 10, "{rep:?}");
        let mut x = [1.0, 1.0];
        match newton(&mut Small { fail: true }, &mut x, &NewtonOptions::default()) {
            Err(PhysicsError::Newton(f)) => {
                assert!(!f.residual_history.is_empty());
                assert!(matches!(
                    f.reason,
                    NewtonFailureReason::LineSearch | NewtonFailureReason::MaxIterations
                ));
            }
            other => panic!("expected a Newton failure, got {other:?}"),
        }
    }
}
