//! The bridge to faer's sparse direct solvers: the one module of the toolkit that names faer.
//!
//! [`LuFactorization`] (general square matrices, partial pivoting) and
//! [`CholeskyFactorization`] (symmetric positive definite) keep their symbolic analysis (fill
//! reducing ordering, elimination tree, supernodes), so that a new matrix with the same
//! sparsity pattern (a Newton step, a new time step size) is factorised numerically only, by
//! [`refactor`](LuFactorization::refactor).
//!
//! Matrices are this toolkit's [`SparseMatrix`] (sprs, CSR or CSC); they are handed to faer
//! without copying: the CSR arrays of `A` are the CSC arrays of `A^T`, so a CSR matrix is
//! factorised as `A^T` and solved with the transposed factors.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::solvers::SolveCore;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::linalg::LuError;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Side};

use super::SparseMatrix;

/// Why a sparse factorisation or solve failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SolverError {
    /// The matrix is not square, or a vector does not match its size.
    #[error("dimension mismatch: {0}")]
    DimensionMismatch(String),
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
    /// [`refactor`](LuFactorization::refactor) was given a matrix whose sparsity pattern
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

/// The former name of [`SolverError`].
pub type FaerError = SolverError;

/// The compressed arrays of a matrix as faer sees them (CSC: `A^T` for a CSR matrix).
struct CscView<'a> {
    n: usize,
    col_ptr: std::borrow::Cow<'a, [usize]>,
    row_idx: &'a [usize],
    values: &'a [f64],
}

impl<'a> CscView<'a> {
    fn of(a: &'a SparseMatrix) -> Result<Self, SolverError> {
        let (n, m) = a.shape();
        if n != m {
            return Err(SolverError::DimensionMismatch(format!(
                "a {n}x{m} matrix is not square"
            )));
        }
        Ok(Self {
            n,
            col_ptr: a.proper_indptr(),
            row_idx: a.indices(),
            values: a.data(),
        })
    }

    fn symbolic(&self) -> SymbolicSparseColMatRef<'_, usize> {
        // sprs guarantees sorted, in-range indices and a monotone pointer array.
        SymbolicSparseColMatRef::new_checked(self.n, self.n, &self.col_ptr, None, self.row_idx)
    }

    fn matrix(&self) -> SparseColMatRef<'_, usize, f64> {
        SparseColMatRef::new(self.symbolic(), self.values)
    }
}

/// `a` in column-major (CSC) storage: borrowed if it is, copied if it is CSR.
fn column_major(a: &SparseMatrix) -> std::borrow::Cow<'_, SparseMatrix> {
    if a.is_csr() {
        std::borrow::Cow::Owned(a.to_csc())
    } else {
        std::borrow::Cow::Borrowed(a)
    }
}

/// The sparsity pattern a factorisation was analysed for (CSR/CSC arrays and storage).
#[derive(Debug, Clone, PartialEq)]
struct Pattern {
    n: usize,
    csr: bool,
    ptr: Vec<usize>,
    idx: Vec<usize>,
}

impl Pattern {
    fn of(a: &SparseMatrix) -> Self {
        Self {
            n: a.rows(),
            csr: a.is_csr(),
            ptr: a.proper_indptr().into_owned(),
            idx: a.indices().to_vec(),
        }
    }

    fn check(&self, a: &SparseMatrix) -> Result<(), SolverError> {
        if a.rows() != self.n || a.cols() != self.n {
            return Err(SolverError::PatternMismatch(format!(
                "analysed {0}x{0}, got {1}x{2}",
                self.n,
                a.rows(),
                a.cols()
            )));
        }
        if a.is_csr() != self.csr {
            return Err(SolverError::PatternMismatch(
                "storage order (CSR/CSC) changed".into(),
            ));
        }
        if a.proper_indptr()[..] != self.ptr[..] || a.indices() != &self.idx[..] {
            return Err(SolverError::PatternMismatch(format!(
                "{} stored entries, analysed {}",
                a.nnz(),
                self.idx.len()
            )));
        }
        Ok(())
    }
}

fn check_rhs(n: usize, len: usize) -> Result<(), SolverError> {
    if n != len {
        return Err(SolverError::DimensionMismatch(format!(
            "a {n}x{n} matrix cannot be solved against a vector of {len}"
        )));
    }
    Ok(())
}

fn check_finite(x: &[f64]) -> Result<(), SolverError> {
    if x.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(SolverError::Singular { pivot: None })
    }
}

fn lu_error(e: LuError) -> SolverError {
    match e {
        LuError::SymbolicSingular { index } => SolverError::Singular { pivot: Some(index) },
        LuError::Generic(e) => SolverError::Backend(format!("{e:?}")),
    }
}

/// A sparse LU factorisation with partial pivoting (faer, supernodal or simplicial), for
/// square non-singular matrices such as the saddle-point systems of mesh tying.
///
/// ```
/// use mortar_core::linalg::{LuFactorization, Triplets};
/// let mut t = Triplets::default();
/// t.push(0, 0, 2.0);
/// t.push(0, 1, 1.0);
/// t.push(1, 0, 1.0); // a zero diagonal entry: pivoting handles it
/// let a = t.to_csr(2, 2);
/// let lu = LuFactorization::try_new(&a).unwrap();
/// let x = lu.solve(&[4.0, 1.0]).unwrap();
/// assert!((x[0] - 1.0).abs() < 1e-14 && (x[1] - 2.0).abs() < 1e-14);
/// ```
#[derive(Debug, Clone)]
pub struct LuFactorization {
    pattern: Pattern,
    symbolic: SymbolicLu<usize>,
    numeric: Lu<usize, f64>,
}

impl LuFactorization {
    /// Analyses and factorises `a`.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] for a non-square matrix, [`SolverError::Singular`]
    /// for a structurally singular one, [`SolverError::Backend`] otherwise.
    pub fn try_new(a: &SparseMatrix) -> Result<Self, SolverError> {
        // A CSR matrix is factorised as itself (copied to CSC), not as the transpose its
        // arrays describe in CSC: partial pivoting then chooses among the rows of A, which
        // keeps a badly row-scaled system (a contact Newton matrix) accurate.
        let csc = column_major(a);
        let view = CscView::of(&csc)?;
        let symbolic = SymbolicLu::try_new(view.symbolic())
            .map_err(|e| SolverError::Backend(format!("{e:?}")))?;
        let numeric =
            Lu::try_new_with_symbolic(symbolic.clone(), view.matrix()).map_err(lu_error)?;
        Ok(Self {
            pattern: Pattern::of(a),
            symbolic,
            numeric,
        })
    }

    /// Factorises a new matrix with the same sparsity pattern, reusing the symbolic analysis.
    ///
    /// # Errors
    /// [`SolverError::PatternMismatch`], and the errors of [`try_new`](Self::try_new); on
    /// error the previous factors are kept.
    pub fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        self.pattern.check(a)?;
        let csc = column_major(a);
        let view = CscView::of(&csc)?;
        self.numeric =
            Lu::try_new_with_symbolic(self.symbolic.clone(), view.matrix()).map_err(lu_error)?;
        Ok(())
    }

    /// The matrix size.
    pub fn dim(&self) -> usize {
        self.pattern.n
    }

    /// Overwrites `x` (the right-hand side) with the solution of `A x = b`.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`]; [`SolverError::Singular`] if the solution is not
    /// finite (a numerically singular matrix).
    pub fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        check_rhs(self.pattern.n, x.len())?;
        let n = x.len();
        let rhs = MatMut::from_column_major_slice_mut(x, n, 1);
        self.numeric.solve_in_place_with_conj(Conj::No, rhs);
        check_finite(x)
    }

    /// The solution of `A x = b`.
    ///
    /// # Errors
    /// As [`solve_in_place`](Self::solve_in_place).
    pub fn solve(&self, b: &[f64]) -> Result<Vec<f64>, SolverError> {
        let mut x = b.to_vec();
        self.solve_in_place(&mut x)?;
        Ok(x)
    }
}

/// A sparse Cholesky factorisation `A = L L^T` (faer) of a symmetric positive definite matrix.
/// Only one triangle of `A` is read (for a CSR matrix the upper one, `col >= row`; for CSC the
/// lower one); the caller guarantees the symmetry.
///
/// The fill-reducing ordering is nested dissection (METIS, see [`nested_dissection`]) for
/// matrices of [`NESTED_DISSECTION_MIN`] unknowns or more, approximate minimum degree (faer's)
/// below that or if METIS fails; [`ordering`](Self::ordering) says which. Factors of
/// [`PARALLEL_MIN_COLUMN`] entries per column or more are computed on faer's global
/// parallelism, smaller ones sequentially.
///
/// [`nested_dissection`]: super::nested_dissection
#[derive(Debug, Clone)]
pub struct CholeskyFactorization {
    pattern: Pattern,
    symbolic: Arc<SymbolicCholesky<usize>>,
    values: Vec<f64>,
    ordering: &'static str,
}

/// The size from which [`CholeskyFactorization`] orders by nested dissection: below it,
/// minimum degree costs about as much fill and less time to compute.
pub const NESTED_DISSECTION_MIN: usize = 20_000;

/// The mean entries per column of a Cholesky factor from which it is factorised and solved
/// in parallel (see [`CholeskyFactorization`]).
pub const PARALLEL_MIN_COLUMN: usize = 256;

impl CholeskyFactorization {
    /// Analyses and factorises `a`.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] for a non-square matrix,
    /// [`SolverError::NotPositiveDefinite`], [`SolverError::Backend`].
    pub fn try_new(a: &SparseMatrix) -> Result<Self, SolverError> {
        let (perm, ordering) = fill_reducing_ordering(a)?;
        Self::build(a, &perm, ordering)
    }

    /// Analyses and factorises `a` in the given elimination order (`perm[new] = old`, a
    /// permutation of the unknowns): an ordering computed once for a family of matrices
    /// (the Newton systems of a contact solve, whose patterns differ in a few rows) and
    /// reused, instead of one per matrix.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] if `perm` is not a permutation of the unknowns, and
    /// the errors of [`try_new`](Self::try_new).
    pub fn try_new_ordered(a: &SparseMatrix, perm: &[usize]) -> Result<Self, SolverError> {
        Self::build(a, perm, "given")
    }

    fn build(a: &SparseMatrix, fwd: &[usize], ordering: &'static str) -> Result<Self, SolverError> {
        let view = CscView::of(a)?;
        let inv = inverse(fwd, view.n)?;
        let perm = PermRef::new_checked(fwd, &inv, view.n);
        let symbolic = factorize_symbolic_cholesky(
            view.symbolic(),
            Side::Lower,
            SymmetricOrdering::Custom(perm),
            Default::default(),
        )
        .map_err(|e| SolverError::Backend(format!("{e:?}")))?;
        let mut this = Self {
            pattern: Pattern::of(a),
            symbolic: Arc::new(symbolic),
            values: Vec::new(),
            ordering,
        };
        this.values = this.numeric(&view)?;
        Ok(this)
    }

    /// The numeric factor of the matrix `view` on the analysed pattern.
    fn numeric(&self, view: &CscView<'_>) -> Result<Vec<f64>, SolverError> {
        let symbolic = &*self.symbolic;
        let mut values = Vec::new();
        values
            .try_reserve_exact(symbolic.len_val())
            .map_err(|e| SolverError::Backend(format!("the factor does not fit: {e}")))?;
        values.resize(symbolic.len_val(), 0.0);
        let par = self.parallelism();
        let mut mem = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        )
        .map_err(|e| SolverError::Backend(format!("{e:?}")))?;
        symbolic
            .factorize_numeric_llt::<f64>(
                &mut values,
                view.matrix(),
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| match e {
                faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                    SolverError::NotPositiveDefinite { pivot: index }
                }
            })?;
        Ok(values)
    }

    /// Factorises a new matrix with the same sparsity pattern, reusing the symbolic analysis.
    ///
    /// # Errors
    /// [`SolverError::PatternMismatch`], and the errors of [`try_new`](Self::try_new); on
    /// error the previous factors are kept.
    pub fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        self.pattern.check(a)?;
        let view = CscView::of(a)?;
        self.values = self.numeric(&view)?;
        Ok(())
    }

    /// The matrix size.
    pub fn dim(&self) -> usize {
        self.pattern.n
    }

    /// faer's global parallelism for a factor of [`PARALLEL_MIN_COLUMN`] entries per column
    /// or more (large dense blocks, as in 3D), sequential below: the many small supernodes of
    /// a 2D factor cost more in thread wake-ups than they gain (`bench_contact`, 2D Hertz at
    /// 3.7e5 unknowns: 1.73 s per Newton step sequential against 2.15 s on two threads; the
    /// 3D patch at 9.4e4: 4.55 s on two threads against 4.94 s sequential).
    fn parallelism(&self) -> faer::Par {
        if self.symbolic.len_val() >= PARALLEL_MIN_COLUMN * self.pattern.n.max(1) {
            faer::get_global_parallelism()
        } else {
            faer::Par::Seq
        }
    }

    /// The fill-reducing ordering used: `"nested dissection (METIS)"`, `"approximate minimum
    /// degree"` or `"given"` ([`try_new_ordered`](Self::try_new_ordered)).
    pub fn ordering(&self) -> &'static str {
        self.ordering
    }

    /// The number of stored entries of the factor `L`.
    pub fn factor_entries(&self) -> usize {
        self.symbolic.len_val()
    }

    /// Overwrites `x` (the right-hand side) with the solution of `A x = b`.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`]; [`SolverError::Singular`] if the solution is not
    /// finite.
    pub fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        check_rhs(self.pattern.n, x.len())?;
        let n = x.len();
        let rhs = MatMut::from_column_major_slice_mut(x, n, 1);
        let par = self.parallelism();
        let mut mem = MemBuffer::try_new(self.symbolic.solve_in_place_scratch::<f64>(1, par))
            .map_err(|e| SolverError::Backend(format!("{e:?}")))?;
        // Symmetric: A = A^T, whichever storage the arrays came from.
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            par,
            MemStack::new(&mut mem),
        );
        check_finite(x)
    }

    /// The solution of `A x = b`.
    ///
    /// # Errors
    /// As [`solve_in_place`](Self::solve_in_place).
    pub fn solve(&self, b: &[f64]) -> Result<Vec<f64>, SolverError> {
        let mut x = b.to_vec();
        self.solve_in_place(&mut x)?;
        Ok(x)
    }
}

/// The inverse of the permutation `fwd` of `0..n`.
fn inverse(fwd: &[usize], n: usize) -> Result<Vec<usize>, SolverError> {
    let bad = || {
        SolverError::DimensionMismatch(format!(
            "an ordering of {} entries is not a permutation of {n} unknowns",
            fwd.len()
        ))
    };
    if fwd.len() != n {
        return Err(bad());
    }
    let mut inv = vec![usize::MAX; n];
    for (new, &old) in fwd.iter().enumerate() {
        if old >= n || inv[old] != usize::MAX {
            return Err(bad());
        }
        inv[old] = new;
    }
    Ok(inv)
}

/// A fill-reducing elimination order of the symmetric matrix `a` (`perm[new] = old`) and its
/// name: nested dissection (METIS, see [`nested_dissection`](super::nested_dissection)) for
/// [`NESTED_DISSECTION_MIN`] unknowns or more when the graph is of 3D character, approximate
/// minimum degree (faer's) otherwise. What [`CholeskyFactorization::try_new`] uses.
///
/// # Errors
/// [`SolverError::DimensionMismatch`] for a non-square matrix, [`SolverError::Backend`].
pub fn fill_reducing_ordering(a: &SparseMatrix) -> Result<(Vec<usize>, &'static str), SolverError> {
    let view = CscView::of(a)?;
    if view.n >= NESTED_DISSECTION_MIN {
        if let Some(perm) = super::nested_dissection::nested_dissection(a) {
            return Ok((perm, "nested dissection (METIS)"));
        }
    }
    let n = view.n;
    let mut fwd = vec![0usize; n];
    let mut inv = vec![0usize; n];
    let mut mem = MemBuffer::try_new(faer::sparse::linalg::amd::order_scratch::<usize>(
        n,
        a.nnz(),
    ))
    .map_err(|e| SolverError::Backend(format!("{e:?}")))?;
    faer::sparse::linalg::amd::order(
        &mut fwd,
        &mut inv,
        view.symbolic(),
        Default::default(),
        MemStack::new(&mut mem),
    )
    .map_err(|e| SolverError::Backend(format!("{e:?}")))?;
    Ok((fwd, "approximate minimum degree"))
}

/// Solves `a x = b` by faer's sparse LU factorisation (analysis, factorisation and solve in
/// one call; keep a [`LuFactorization`] to solve again).
///
/// # Errors
/// The errors of [`LuFactorization`].
pub fn solve_sparse_lu(a: &SparseMatrix, b: &[f64]) -> Result<Vec<f64>, SolverError> {
    let (n, _) = a.shape();
    check_rhs(n, b.len())?;
    LuFactorization::try_new(a)?.solve(b)
}
