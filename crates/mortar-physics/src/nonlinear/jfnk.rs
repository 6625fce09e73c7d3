//! Jacobian-free Newton-Krylov: the Jacobian applied by finite differences of the residual
//! (`FiniteDifferenceJacobian`) and solved by preconditioned GMRES (`jfnk_solve`).

use std::cell::RefCell;

use mortar_fem::linalg::{GmresOptions, GmresReport, LinearOperator, Preconditioner, SolverError};

use crate::error::PhysicsError;
use crate::SOLVER;

/// A residual function `r <- F(x)`.
type Residual<'a> = &'a dyn Fn(&[f64], &mut [f64]) -> Result<(), PhysicsError>;

/// Settings of the Jacobian-free Newton-Krylov linear solves ([`jfnk_solve`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JfnkOptions {
    /// GMRES restart length `m`.
    pub restart: usize,
    /// The most GMRES iterations per Newton step.
    pub max_iterations: usize,
    /// `b` in the finite-difference step `h = b (1 + |x|) / |v|` (about the square root of
    /// the relative precision of `F`).
    pub difference_step: f64,
}

impl Default for JfnkOptions {
    /// GMRES(30), 300 iterations, `b = 1e-8`.
    fn default() -> Self {
        Self {
            restart: 30,
            max_iterations: 300,
            difference_step: 1e-8,
        }
    }
}

/// The finite-difference Jacobian-vector product `J(x) v ~ (F(x + h v) - F(x)) / h`, with
/// `h = b (1 + |x|) / |v|`, as a [`LinearOperator`] for GMRES. The first failure of `F` is
/// kept (see [`take_error`](Self::take_error)) and the product is then zero.
pub struct FiniteDifferenceJacobian<'a> {
    residual: Residual<'a>,
    x: &'a [f64],
    r: &'a [f64],
    b: f64,
    x_norm: f64,
    scratch: RefCell<(Vec<f64>, Option<PhysicsError>, usize)>,
}

impl<'a> FiniteDifferenceJacobian<'a> {
    /// The product at `x`, where `r = F(x)`.
    pub fn new(residual: Residual<'a>, x: &'a [f64], r: &'a [f64], difference_step: f64) -> Self {
        Self {
            residual,
            x,
            r,
            b: difference_step,
            x_norm: x.iter().map(|v| v * v).sum::<f64>().sqrt(),
            scratch: RefCell::new((vec![0.0; x.len()], None, 0)),
        }
    }

    /// The first error of a residual evaluation, if any.
    pub fn take_error(&self) -> Option<PhysicsError> {
        self.scratch.borrow_mut().1.take()
    }

    /// The residual evaluations done.
    pub fn evaluations(&self) -> usize {
        self.scratch.borrow().2
    }
}

impl LinearOperator for FiniteDifferenceJacobian<'_> {
    fn dim(&self) -> usize {
        self.x.len()
    }

    fn apply(&self, v: &[f64], y: &mut [f64]) {
        let v_norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        y.fill(0.0);
        let mut s = self.scratch.borrow_mut();
        if v_norm == 0.0 || s.1.is_some() {
            return;
        }
        let h = self.b * (1.0 + self.x_norm) / v_norm;
        let xp = &mut s.0;
        for i in 0..xp.len() {
            xp[i] = self.x[i] + h * v[i];
        }
        s.2 += 1;
        let xp = std::mem::take(&mut s.0);
        match (self.residual)(&xp, y) {
            Ok(()) => {
                for (yi, ri) in y.iter_mut().zip(self.r) {
                    *yi = (*yi - ri) / h;
                }
            }
            Err(e) => {
                y.fill(0.0);
                s.1 = Some(e);
            }
        }
        s.0 = xp;
    }
}

/// One Jacobian-free Newton-Krylov linear solve: `J(x) dx = r` by restarted GMRES on the
/// finite-difference products of [`FiniteDifferenceJacobian`], right-preconditioned by
/// `preconditioner` (typically the sparse LU of an assembled approximate Jacobian), to the
/// relative residual `forcing`. `dx` is the initial guess (zero it for none).
///
/// GMRES stopped by its iteration limit with the residual reduced (relative residual below
/// one) is not an error: the inexact step is returned (its report says how far it got) and
/// Newton's line search judges it; the finite-difference products cannot reach relative
/// residuals much below the square root of the precision of `F`.
///
/// # Errors
/// The first error of a residual evaluation, and the errors of [`gmres`](mortar_fem::linalg::gmres) (a failing
/// preconditioner, no reduction at all within `options.max_iterations`) as
/// [`PhysicsError::Solver`].
pub fn jfnk_solve(
    residual: Residual<'_>,
    x: &[f64],
    r: &[f64],
    preconditioner: &dyn Preconditioner,
    dx: &mut [f64],
    forcing: f64,
    options: &JfnkOptions,
) -> Result<GmresReport, PhysicsError> {
    let op = FiniteDifferenceJacobian::new(residual, x, r, options.difference_step);
    let gm = GmresOptions {
        restart: options.restart,
        max_iterations: options.max_iterations,
        relative_tolerance: forcing,
    };
    let out = SOLVER.solve_preconditioned(&op, preconditioner, r, dx, &gm);
    if let Some(e) = op.take_error() {
        return Err(e);
    }
    match out {
        Err(SolverError::NotConverged {
            iterations,
            residual,
            ..
        }) if residual < 1.0 => Ok(GmresReport {
            iterations,
            cycles: iterations.div_ceil(gm.restart.max(1)),
            relative_residual: residual,
        }),
        other => Ok(other?),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mortar_fem::linalg::{LuFactorization, Triplets};

    /// On a linear residual `F(x) = A x - b`, JFNK's solve equals the direct solve.
    #[test]
    fn matches_the_direct_solve_on_a_linear_problem() {
        let n = 20;
        let mut t = Triplets::default();
        for i in 0..n as u32 {
            t.push(i, i, 4.0 + i as f64 * 0.1);
            if i > 0 {
                t.push(i, i - 1, -1.0);
            }
            if i + 1 < n as u32 {
                t.push(i, i + 1, -1.5);
            }
        }
        let a = t.to_csr(n, n);
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let f = |x: &[f64], r: &mut [f64]| {
            a.apply(x, r);
            for (ri, bi) in r.iter_mut().zip(&b) {
                *ri -= bi;
            }
            Ok(())
        };
        let x = vec![0.5; n];
        let mut r = vec![0.0; n];
        f(&x, &mut r).unwrap();
        // A poor preconditioner (the diagonal) so that GMRES iterates.
        let mut d = Triplets::default();
        for i in 0..n as u32 {
            d.push(i, i, 4.0);
        }
        let p = LuFactorization::try_new(&d.to_csr(n, n)).unwrap();
        let mut dx = vec![0.0; n];
        let rep = jfnk_solve(&f, &x, &r, &p, &mut dx, 1e-10, &JfnkOptions::default()).unwrap();
        assert!(rep.iterations > 1);
        let exact = LuFactorization::try_new(&a).unwrap().solve(&r).unwrap();
        for (u, v) in dx.iter().zip(&exact) {
            assert!((u - v).abs() < 1e-6 * (1.0 + v.abs()), "{u} vs {v}");
        }
    }
}
