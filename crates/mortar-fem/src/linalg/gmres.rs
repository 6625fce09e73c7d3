//! Restarted GMRES(m) with right preconditioning (Saad, *Iterative Methods for Sparse Linear
//! Systems*, 2nd ed., Algorithm 9.5), modified Gram-Schmidt and Givens rotations.
//!
//! With right preconditioning `A M^-1 y = b`, `x = M^-1 y`, the residual that GMRES minimises
//! is the true residual `b - A x`, so the stopping test is on the quantity the caller cares
//! about. The operator is a trait, so a Jacobian-free Newton-Krylov method passes its
//! finite-difference Jacobian-vector product and an assembled approximate Jacobian's
//! factorisation as the preconditioner.

use super::{SolverError, SparseMatrix};

/// A square linear operator `y = A x`.
pub trait LinearOperator {
    /// The size `n` of the `n x n` operator.
    fn dim(&self) -> usize;
    /// Writes `A x` into `y` (both of length [`dim`](LinearOperator::dim)).
    fn apply(&self, x: &[f64], y: &mut [f64]);
}

impl LinearOperator for SparseMatrix {
    fn dim(&self) -> usize {
        self.rows()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        if self.is_csr() {
            for (r, row) in self.outer_iterator().enumerate() {
                y[r] = row.iter().map(|(c, v)| v * x[c]).sum();
            }
        } else {
            for (c, col) in self.outer_iterator().enumerate() {
                for (r, v) in col.iter() {
                    y[r] += v * x[c];
                }
            }
        }
    }
}

/// A preconditioner `x <- M^-1 x`.
pub trait Preconditioner {
    /// Overwrites `x` with `M^-1 x`.
    ///
    /// # Errors
    /// A failure of the preconditioner's solve.
    fn apply_in_place(&self, x: &mut [f64]) -> Result<(), SolverError>;
}

/// No preconditioning: `M = I`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct IdentityPreconditioner;

impl Preconditioner for IdentityPreconditioner {
    fn apply_in_place(&self, _x: &mut [f64]) -> Result<(), SolverError> {
        Ok(())
    }
}

/// Settings of [`gmres`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GmresOptions {
    /// The Krylov subspace size between restarts (`m` in GMRES(m)).
    pub restart: usize,
    /// The largest total number of iterations (operator applications) over all cycles.
    pub max_iterations: usize,
    /// Stop when `||b - A x|| <= relative_tolerance * ||b||`.
    pub relative_tolerance: f64,
}

impl Default for GmresOptions {
    /// GMRES(30), at most 1000 iterations, relative tolerance 1e-10.
    fn default() -> Self {
        Self {
            restart: 30,
            max_iterations: 1000,
            relative_tolerance: 1e-10,
        }
    }
}

/// What a converged [`gmres`] run did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GmresReport {
    /// Total iterations (operator applications in the Arnoldi process).
    pub iterations: usize,
    /// Restart cycles begun.
    pub cycles: usize,
    /// The final relative residual `||b - A x|| / ||b||`, computed from `x`.
    pub relative_residual: f64,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// Reduces column `j` of the Hessenberg matrix `h` to upper triangular form: the previous
/// Givens rotations `(cs, sn)` applied to it, then a new one that zeroes `h[j + 1][j]`, also
/// applied to the residual's coordinates `g`. Returns the new diagonal entry, or `None`
/// where the column vanishes.
fn rotate_column(
    h: &mut [Vec<f64>],
    cs: &mut [f64],
    sn: &mut [f64],
    g: &mut [f64],
    j: usize,
) -> Option<f64> {
    for i in 0..j {
        let t = cs[i] * h[i][j] + sn[i] * h[i + 1][j];
        h[i + 1][j] = -sn[i] * h[i][j] + cs[i] * h[i + 1][j];
        h[i][j] = t;
    }
    let r = h[j][j].hypot(h[j + 1][j]);
    if r == 0.0 {
        return None;
    }
    cs[j] = h[j][j] / r;
    sn[j] = h[j + 1][j] / r;
    h[j][j] = r;
    h[j + 1][j] = 0.0;
    g[j + 1] = -sn[j] * g[j];
    g[j] *= cs[j];
    Some(r)
}

/// `z = V y` of the first `k` Krylov vectors `v`, with `y = H^-1 g` by back substitution on
/// the upper triangular `k x k` part of `h`: the cycle's correction before preconditioning.
fn krylov_combination(h: &[Vec<f64>], g: &[f64], v: &[Vec<f64>], k: usize, z: &mut [f64]) {
    let mut y = vec![0.0; k];
    for i in (0..k).rev() {
        let s: f64 = (i + 1..k).map(|l| h[i][l] * y[l]).sum();
        y[i] = (g[i] - s) / h[i][i];
    }
    z.fill(0.0);
    for (yi, vi) in y.iter().zip(v) {
        for (zl, vl) in z.iter_mut().zip(vi) {
            *zl += yi * vl;
        }
    }
}

/// Solves `A x = b` by right-preconditioned restarted GMRES(m), starting from the `x` given
/// (zero it for no initial guess).
///
/// # Errors
/// [`SolverError::DimensionMismatch`] if the sizes disagree, [`SolverError::NotConverged`]
/// after `max_iterations` iterations (then `x` holds the last iterate), and the errors of the
/// preconditioner.
pub fn gmres(
    a: &dyn LinearOperator,
    m: &dyn Preconditioner,
    b: &[f64],
    x: &mut [f64],
    options: &GmresOptions,
) -> Result<GmresReport, SolverError> {
    let n = a.dim();
    for (len, what) in [
        (b.len(), "entries of b in GMRES (the operator's size)"),
        (x.len(), "entries of x in GMRES (the operator's size)"),
    ] {
        if len != n {
            return Err(SolverError::DimensionMismatch {
                expected: n,
                found: len,
                what,
            });
        }
    }
    let restart = options.restart.max(1).min(n.max(1));
    let tol = options.relative_tolerance;
    let bnorm = norm(b);
    if bnorm == 0.0 {
        x.fill(0.0);
        return Ok(GmresReport {
            iterations: 0,
            cycles: 0,
            relative_residual: 0.0,
        });
    }
    let mut v: Vec<Vec<f64>> = vec![vec![0.0; n]; restart + 1];
    let mut h = vec![vec![0.0; restart]; restart + 1];
    let (mut cs, mut sn) = (vec![0.0; restart], vec![0.0; restart]);
    let mut g = vec![0.0; restart + 1];
    let mut w = vec![0.0; n];
    let mut z = vec![0.0; n];
    let mut iterations = 0usize;
    let mut cycles = 0usize;
    loop {
        // r = b - A x
        a.apply(x, &mut w);
        for i in 0..n {
            w[i] = b[i] - w[i];
        }
        let beta = norm(&w);
        let rel = beta / bnorm;
        if rel <= tol {
            return Ok(GmresReport {
                iterations,
                cycles,
                relative_residual: rel,
            });
        }
        if iterations >= options.max_iterations || !rel.is_finite() {
            return Err(SolverError::NotConverged {
                method: format!("GMRES({restart})"),
                iterations,
                residual: rel,
                tolerance: tol,
            });
        }
        cycles += 1;
        for i in 0..n {
            v[0][i] = w[i] / beta;
        }
        g.fill(0.0);
        g[0] = beta;
        let mut k = 0usize;
        for j in 0..restart {
            z.copy_from_slice(&v[j]);
            m.apply_in_place(&mut z)?;
            a.apply(&z, &mut w);
            for i in 0..=j {
                let hij = dot(&w, &v[i]);
                h[i][j] = hij;
                for (wl, vl) in w.iter_mut().zip(&v[i]) {
                    *wl -= hij * vl;
                }
            }
            let hnext = norm(&w);
            h[j + 1][j] = hnext;
            let Some(r) = rotate_column(&mut h, &mut cs, &mut sn, &mut g, j) else {
                // Cannot happen for a non-singular operator: the new direction and the
                // projection both vanish.
                k = j;
                break;
            };
            iterations += 1;
            k = j + 1;
            let breakdown = hnext <= f64::EPSILON * r;
            if !breakdown {
                for (vl, wl) in v[j + 1].iter_mut().zip(&w) {
                    *vl = wl / hnext;
                }
            }
            if g[j + 1].abs() / bnorm <= tol || iterations >= options.max_iterations || breakdown {
                break;
            }
        }
        // x += M^-1 (V y), y = H^-1 g.
        krylov_combination(&h, &g, &v, k, &mut z);
        m.apply_in_place(&mut z)?;
        for (xl, zl) in x.iter_mut().zip(&z) {
            *xl += zl;
        }
        if k == 0 {
            // No progress possible (a singular operator): report the residual.
            a.apply(x, &mut w);
            let rel = b
                .iter()
                .zip(&w)
                .map(|(bi, wi)| (bi - wi) * (bi - wi))
                .sum::<f64>()
                .sqrt()
                / bnorm;
            return Err(SolverError::NotConverged {
                method: format!("GMRES({restart})"),
                iterations,
                residual: rel,
                tolerance: tol,
            });
        }
    }
}
