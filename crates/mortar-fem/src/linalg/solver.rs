//! The solver interface: what the finite-element code asks of sparse linear algebra,
//! whichever backend answers. A [`SparseSolver`] factorises a sparse matrix into a
//! [`Factorization`] (solve in place as often as asked, factorise new values of the same
//! pattern reusing the analysis, report what it holds), and solves iteratively with a
//! [`Preconditioner`] (any factorisation is one). [`FaerSolver`](super::FaerSolver) (faer's sparse LU and
//! Cholesky, and this crate's GMRES) implements it; another backend (PETSc, say) implements
//! the same two traits and [`SolverError`] carries its failures as
//! [`SolverError::Backend`].
//!
//! ```
//! use mortar_fem::linalg::{FaerSolver, MatrixKind, SparseSolver, Triplets};
//! let mut t = Triplets::default();
//! t.push(0, 0, 4.0);
//! t.push(0, 1, 1.0);
//! t.push(1, 0, 1.0);
//! t.push(1, 1, 3.0);
//! let a = t.to_csr(2, 2);
//! let solver: &dyn SparseSolver = &FaerSolver;
//! let f = solver.factor(&a, MatrixKind::SymmetricPositiveDefinite).unwrap();
//! let mut x = vec![1.0, 2.0];
//! f.solve_in_place(&mut x).unwrap();
//! assert!((4.0 * x[0] + x[1] - 1.0).abs() < 1e-14 && (x[0] + 3.0 * x[1] - 2.0).abs() < 1e-14);
//! assert_eq!(f.stats().dim, 2);
//! ```

use std::fmt::Debug;

use super::{GmresOptions, GmresReport, LinearOperator, Preconditioner, SparseMatrix, SystemInfo};

/// Why a sparse factorisation or solve failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SolverError {
    /// The matrix is not square, or a vector, an ordering or a constraint count does not match
    /// its size.
    #[error("dimension mismatch: {what}: expected {expected}, found {found}")]
    DimensionMismatch {
        /// The size expected (the matrix's number of rows, or at most that many constraints).
        expected: usize,
        /// The size found.
        found: usize,
        /// What has the wrong size (`"columns of a square matrix"`, `"entries of the
        /// right-hand side"`, ...).
        what: &'static str,
    },
    /// The matrix is singular: no pivot could be found at `pivot`, or the solve produced
    /// non-finite values (`pivot` is then `None`).
    #[error("the matrix is singular{}", match .pivot { Some(p) => format!(" (no pivot at step {p})"), None => " (the solve produced non-finite values)".to_string() })]
    Singular {
        /// The elimination step without a pivot, when known.
        pivot: Option<usize>,
    },
    /// The Cholesky factorisation met a non-positive pivot: the matrix is not symmetric
    /// positive definite (a floating body, a missing Dirichlet condition, a wrong sign).
    #[error("the matrix is not positive definite (non-positive pivot at step {pivot})")]
    NotPositiveDefinite {
        /// The elimination step (in the fill-reducing order).
        pivot: usize,
    },
    /// [`refactor`](Factorization::refactor) was given a matrix whose sparsity pattern
    /// differs from the one analysed.
    #[error("the sparsity pattern differs from the analysed one: {0}")]
    PatternMismatch(String),
    /// An iterative solver did not reach its tolerance.
    #[error("{method} did not converge: relative residual {residual:e} after {iterations} iterations (tolerance {tolerance:e})")]
    NotConverged {
        /// The method, e.g. `"GMRES(30)"`.
        method: String,
        /// Iterations made.
        iterations: usize,
        /// The final relative residual.
        residual: f64,
        /// The requested relative tolerance.
        tolerance: f64,
    },
    /// Any other failure of the backend (out of memory, index overflow).
    #[error("sparse solver backend: {0}")]
    Backend(String),
}

/// What is known of a matrix to factorise: it picks the factorisation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum MatrixKind {
    /// Any square non-singular matrix (LU with partial pivoting).
    General,
    /// Symmetric positive definite (Cholesky): only one triangle is read (for a CSR matrix
    /// the upper one), the caller guarantees the symmetry.
    SymmetricPositiveDefinite,
}

/// What a factorisation holds, for reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FactorStats {
    /// The matrix size.
    pub dim: usize,
    /// The stored entries of the factors, where the backend counts them.
    pub factor_entries: Option<usize>,
    /// The method, e.g. `"sparse LU (partial pivoting)"`.
    pub method: &'static str,
}

/// A factorised square sparse matrix `A`.
pub trait Factorization: Send + Sync + Debug {
    /// Overwrites `x` (the right-hand side) with the solution of `A x = b`.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] for a vector of the wrong size,
    /// [`SolverError::Singular`] if the solution is not finite, and the backend's errors.
    fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError>;

    /// Factorises a new matrix with the sparsity pattern of the one analysed, reusing the
    /// analysis (a Newton step, a new time step size).
    ///
    /// # Errors
    /// [`SolverError::PatternMismatch`] for another pattern, and the errors of the
    /// factorisation; on error the previous factors are kept.
    fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError>;

    /// The size, the factors' entries and the method.
    fn stats(&self) -> FactorStats;

    /// The solution of `A x = b`.
    ///
    /// # Errors
    /// As [`solve_in_place`](Self::solve_in_place).
    fn solve(&self, b: &[f64]) -> Result<Vec<f64>, SolverError> {
        let mut x = b.to_vec();
        self.solve_in_place(&mut x)?;
        Ok(x)
    }
}

impl<F: Factorization + ?Sized> Factorization for Box<F> {
    fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        (**self).solve_in_place(x)
    }
    fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        (**self).refactor(a)
    }
    fn stats(&self) -> FactorStats {
        (**self).stats()
    }
}

/// Every factorisation preconditions by its solve, `M^-1 x` = `A^-1 x`.
impl<F: Factorization + ?Sized> Preconditioner for F {
    fn apply_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        self.solve_in_place(x)
    }
}

/// A backend of sparse linear algebra.
pub trait SparseSolver: Send + Sync + Debug {
    /// Analyses and factorises the square matrix `a`, of the given kind.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] for a non-square matrix, [`SolverError::Singular`]
    /// or [`SolverError::NotPositiveDefinite`], and the backend's errors.
    fn factor(
        &self,
        a: &SparseMatrix,
        kind: MatrixKind,
    ) -> Result<Box<dyn Factorization>, SolverError>;

    /// [`factor`](Self::factor) with what the caller knows of the system (`info`), which a
    /// backend may use (an AMG preconditioner's near null space); by default `factor`.
    ///
    /// # Errors
    /// As [`factor`](Self::factor).
    fn factor_system(
        &self,
        a: &SparseMatrix,
        kind: MatrixKind,
        info: SystemInfo<'_>,
    ) -> Result<Box<dyn Factorization>, SolverError> {
        let _ = info;
        self.factor(a, kind)
    }

    /// Solves `A x = b` iteratively, right-preconditioned by `preconditioner`, from the `x`
    /// given; `a` is an assembled matrix or a matrix-free product. By default this crate's
    /// restarted [`gmres`](super::gmres), which any backend may keep.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] if the sizes disagree, [`SolverError::NotConverged`]
    /// (then `x` holds the last iterate), and the preconditioner's errors.
    fn solve_preconditioned(
        &self,
        a: &dyn LinearOperator,
        preconditioner: &dyn Preconditioner,
        b: &[f64],
        x: &mut [f64],
        options: &GmresOptions,
    ) -> Result<GmresReport, SolverError> {
        super::gmres(a, preconditioner, b, x, options)
    }
}
