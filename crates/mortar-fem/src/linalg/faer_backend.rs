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
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::linalg::LuError;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Side};

use super::solver::{FactorStats, Factorization, MatrixKind, SparseSolver};
use super::{SolverError, SparseMatrix};

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
        let n = check_square(a)?;
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

/// The size of the square matrix `a`.
///
/// # Errors
/// [`SolverError::DimensionMismatch`] if `a` is not square.
pub(crate) fn check_square(a: &SparseMatrix) -> Result<usize, SolverError> {
    let (n, m) = a.shape();
    if n != m {
        return Err(SolverError::DimensionMismatch {
            expected: n,
            found: m,
            what: "columns of a square matrix (as many as its rows)",
        });
    }
    Ok(n)
}

fn check_rhs(n: usize, len: usize) -> Result<(), SolverError> {
    if n != len {
        return Err(SolverError::DimensionMismatch {
            expected: n,
            found: len,
            what: "entries of the right-hand side (the matrix's size)",
        });
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
/// use mortar_fem::linalg::{LuFactorization, Triplets};
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

    /// The first half of a solve: `x <- L^-1 P x`, the result in the elimination order
    /// (`P` the fill-reducing permutation). [`backward_in_place`](Self::backward_in_place)
    /// completes it; between them a caller may change the values of the unknowns eliminated
    /// last (see [`SubstructuredCholesky`](super::SubstructuredCholesky)).
    pub(crate) fn forward_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        check_rhs(self.pattern.n, x.len())?;
        self.permute(x, false);
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(sym) => {
                let (mut mem, n) = (supernodal_scratch(sym)?, x.len());
                SupernodalLltRef::new(sym, &self.values).l_solve_with_conj(
                    Conj::No,
                    MatMut::from_column_major_slice_mut(x, n, 1),
                    faer::Par::Seq,
                    MemStack::new(&mut mem),
                );
            }
            SymbolicCholeskyRaw::Simplicial(sym) => {
                let (ptr, idx) = (sym.col_ptr(), sym.row_idx());
                for j in 0..x.len() {
                    let col = ptr[j]..ptr[j + 1];
                    let d = col.clone().find(|&p| idx[p] == j).map(|p| self.values[p]);
                    x[j] /= d.unwrap_or(f64::NAN);
                    let xj = x[j];
                    for p in col.filter(|&p| idx[p] > j) {
                        x[idx[p]] -= self.values[p] * xj;
                    }
                }
            }
        }
        Ok(())
    }

    /// The second half of a solve: `x <- P^T L^-T x` for `x` in the elimination order (see
    /// [`forward_in_place`](Self::forward_in_place)).
    pub(crate) fn backward_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        check_rhs(self.pattern.n, x.len())?;
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(sym) => {
                let (mut mem, n) = (supernodal_scratch(sym)?, x.len());
                SupernodalLltRef::new(sym, &self.values).l_transpose_solve_with_conj(
                    Conj::No,
                    MatMut::from_column_major_slice_mut(x, n, 1),
                    faer::Par::Seq,
                    MemStack::new(&mut mem),
                );
            }
            SymbolicCholeskyRaw::Simplicial(sym) => {
                let (ptr, idx) = (sym.col_ptr(), sym.row_idx());
                for j in (0..x.len()).rev() {
                    let (mut dot, mut d) = (0.0, f64::NAN);
                    for p in ptr[j]..ptr[j + 1] {
                        if idx[p] == j {
                            d = self.values[p];
                        } else if idx[p] > j {
                            dot += self.values[p] * x[idx[p]];
                        }
                    }
                    x[j] = (x[j] - dot) / d;
                }
            }
        }
        self.permute(x, true);
        check_finite(x)
    }

    /// `x <- P x` (into the elimination order), or `x <- P^T x` if `back`.
    fn permute(&self, x: &mut [f64], back: bool) {
        if let Some(perm) = self.symbolic.perm() {
            let (fwd, inv) = perm.arrays();
            let map = if back { inv } else { fwd };
            let old = x.to_vec();
            for (xi, &m) in x.iter_mut().zip(map) {
                *xi = old[m];
            }
        }
    }

    /// Whether faer chose its supernodal factorisation (else the simplicial one).
    #[cfg(test)]
    pub(crate) fn is_supernodal(&self) -> bool {
        matches!(self.symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_))
    }

    /// The last `k` columns and rows of the factor `L` (in the elimination order), as a
    /// dense lower-triangular `k x k` block stored by columns: for an ordering that
    /// eliminates a set of `k` unknowns last, `L_kk L_kk^T` is the Schur complement of the
    /// others in `A` (what [`SubstructuredCholesky`](super::SubstructuredCholesky) combines).
    pub(crate) fn trailing_factor(&self, k: usize) -> Vec<f64> {
        let n = self.pattern.n;
        let k = k.min(n);
        let first = n - k;
        let mut out = vec![0.0; k * k];
        let mut put = |i: usize, j: usize, v: f64| {
            if i >= first && j >= first {
                out[(j - first) * k + (i - first)] = v;
            }
        };
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(sym) => {
                let l = SupernodalLltRef::new(sym, &self.values);
                for s in 0..sym.n_supernodes() {
                    let node = l.supernode(s);
                    let (start, block) = (node.start(), node.val());
                    let cols = block.ncols();
                    if start + cols <= first {
                        continue;
                    }
                    for c in 0..cols {
                        for r in c..cols {
                            put(start + r, start + c, block[(r, c)]);
                        }
                        for (p, &row) in node.pattern().iter().enumerate() {
                            put(row, start + c, block[(cols + p, c)]);
                        }
                    }
                }
            }
            SymbolicCholeskyRaw::Simplicial(sym) => {
                let (ptr, idx) = (sym.col_ptr(), sym.row_idx());
                for j in first..n {
                    for p in ptr[j]..ptr[j + 1] {
                        put(idx[p], j, self.values[p]);
                    }
                }
            }
        }
        out
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

/// Overwrites the dense symmetric positive definite `n x n` matrix `a` (stored by columns,
/// both triangles) with its Cholesky factor `L` (lower triangle; the upper one zeroed).
///
/// # Errors
/// [`SolverError::NotPositiveDefinite`].
pub(crate) fn dense_cholesky(a: &mut [f64], n: usize) -> Result<(), SolverError> {
    // Sequential, so that the factor's bits do not depend on the thread count.
    let par = faer::Par::Seq;
    let mut mem = MemBuffer::try_new(
        faer::linalg::cholesky::llt::factor::cholesky_in_place_scratch::<f64>(
            n,
            par,
            Default::default(),
        ),
    )
    .map_err(|e| SolverError::Backend(format!("{e:?}")))?;
    faer::linalg::cholesky::llt::factor::cholesky_in_place(
        MatMut::from_column_major_slice_mut(a, n, n),
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
    for j in 0..n {
        a[j * n..j * n + j].fill(0.0);
    }
    Ok(())
}

/// The lower triangle of `L L^T` for the dense lower-triangular `n x n` matrix `l` (stored by
/// columns), stored by columns with a zero upper triangle (a third of a full product's work).
pub(crate) fn dense_gram(l: &[f64], n: usize) -> Vec<f64> {
    use faer::linalg::matmul::triangular::{matmul, BlockStructure};
    let l = faer::MatRef::from_column_major_slice(l, n, n);
    let mut out = vec![0.0; n * n];
    matmul(
        MatMut::from_column_major_slice_mut(&mut out, n, n),
        BlockStructure::TriangularLower,
        faer::Accum::Replace,
        l,
        BlockStructure::TriangularLower,
        l.transpose(),
        BlockStructure::TriangularUpper,
        1.0,
        faer::Par::Seq,
    );
    out
}

/// The workspace of one sequential triangular solve with a supernodal factor.
fn supernodal_scratch(
    sym: &faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky<usize>,
) -> Result<MemBuffer, SolverError> {
    MemBuffer::try_new(sym.solve_in_place_scratch::<f64>(1, faer::Par::Seq))
        .map_err(|e| SolverError::Backend(format!("{e:?}")))
}

/// The inverse of the permutation `fwd` of `0..n`.
fn inverse(fwd: &[usize], n: usize) -> Result<Vec<usize>, SolverError> {
    let bad = || SolverError::DimensionMismatch {
        expected: n,
        found: fwd.len(),
        what: "entries of an ordering that is a permutation of the unknowns",
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

/// `a` with every diagonal entry stored (explicit zeros added where the pattern has none):
/// the symmetric factorisations read the pivots' places from the pattern.
fn with_full_diagonal(a: &SparseMatrix) -> std::borrow::Cow<'_, SparseMatrix> {
    let n = a.rows().min(a.cols());
    let missing = (0..n).any(|r| a.outer_view(r).is_none_or(|row| row.get(r).is_none()));
    if !missing {
        return std::borrow::Cow::Borrowed(a);
    }
    let mut indptr = Vec::with_capacity(a.outer_dims() + 1);
    let mut indices = Vec::with_capacity(a.nnz() + n);
    let mut data = Vec::with_capacity(a.nnz() + n);
    indptr.push(0);
    for (r, row) in a.outer_iterator().enumerate() {
        let mut placed = r >= n;
        for (c, v) in row.iter() {
            if !placed && c >= r {
                if c > r {
                    indices.push(r);
                    data.push(0.0);
                }
                placed = true;
            }
            indices.push(c);
            data.push(*v);
        }
        if !placed {
            indices.push(r);
            data.push(0.0);
        }
        indptr.push(indices.len());
    }
    let shape = (a.rows(), a.cols());
    std::borrow::Cow::Owned(if a.is_csr() {
        SparseMatrix::new(shape, indptr, indices, data)
    } else {
        SparseMatrix::new_csc(shape, indptr, indices, data)
    })
}

/// The most steps of iterative refinement of a [`SaddlePointFactorization`] solve.
const MAX_REFINEMENT: usize = 3;

/// A sparse `L D L^T` factorisation (faer, supernodal, no pivoting) of a symmetric
/// saddle-point matrix `[[K, B^T], [B, 0]]` whose last `constraints` unknowns are the
/// multipliers, `K` symmetric positive definite on the rest.
///
/// Without pivoting the elimination order alone must keep every pivot away from zero. The
/// order is the fill-reducing one of the whole matrix ([`fill_reducing_ordering`], as for
/// [`CholeskyFactorization`]: nested dissection for graphs of 3D character, minimum degree
/// otherwise) with each multiplier moved to just after the last of the
/// unknowns its constraint row couples: by then the pivot of the multiplier is the Schur
/// complement `-(B K^-1 B^T)`, negative, and every pivot of `K` positive. The factors are
/// checked on a known solution (`x* = 1 + i / n`, error below `1e-8 |x*|` after
/// refinement); a zero pivot or a failed check (a floating body: `K` singular) refuses
/// the factorisation with [`SolverError::Singular`], and the caller falls back to a
/// factorisation with pivoting ([`LuFactorization`]). Every solve is refined against the
/// matrix (up to 3 steps, while the residual halves).
///
/// Against faer's LU (COLAMD order, partial pivoting) on the tied heat benchmark's saddle
/// point this is the cost of a Cholesky of the same size instead of a general LU.
#[derive(Debug, Clone)]
pub struct SaddlePointFactorization {
    pattern: Pattern,
    symbolic: Arc<SymbolicCholesky<usize>>,
    values: Vec<f64>,
    matrix: SparseMatrix,
}

impl SaddlePointFactorization {
    /// Analyses and factorises `a`, whose last `constraints` unknowns are the multipliers.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] for a non-square matrix or more constraints than
    /// unknowns; [`SolverError::Singular`] if a pivot is zero or the factors fail their check
    /// (fall back to [`LuFactorization`]); [`SolverError::Backend`].
    pub fn try_new(a: &SparseMatrix, constraints: usize) -> Result<Self, SolverError> {
        Self::try_new_with_last(a, constraints, &[])
    }

    /// As [`try_new`](Self::try_new), with the primal unknowns marked in `last` (indexed by
    /// unknown; shorter than the primal part: the rest unmarked) eliminated after every
    /// multiplier, and left out of the multipliers' placement. For a body that only the
    /// constraints hold (no Dirichlet condition), whose own block is singular, mark the
    /// unknowns of a few of its nodes, enough to pin its constant or rigid modes: every other
    /// principal block is then definite, and the marked unknowns' pivots are those of the
    /// constrained problem.
    ///
    /// # Errors
    /// As [`try_new`](Self::try_new).
    pub fn try_new_with_last(
        a: &SparseMatrix,
        constraints: usize,
        last: &[bool],
    ) -> Result<Self, SolverError> {
        let is_last = |i: usize| last.get(i).copied().unwrap_or(false);
        let pattern = Pattern::of(a);
        let a = &*with_full_diagonal(a);
        let view = CscView::of(a)?;
        let n = view.n;
        if constraints > n {
            return Err(SolverError::DimensionMismatch {
                expected: n,
                found: constraints,
                what: "constraints (at most the matrix's size)",
            });
        }
        let primal = n - constraints;
        let (nd, _) = fill_reducing_ordering(a)?;
        let mut position = vec![0usize; n];
        for (new, &old) in nd.iter().enumerate() {
            position[old] = new;
        }
        // Sort key: a primal unknown keeps its place; a multiplier goes right after the last
        // (unmarked) primal unknown of its row; marked unknowns after everything else, in
        // their own order (ties in the nested-dissection order).
        let mut key: Vec<(usize, u8, usize, usize)> = (0..n)
            .map(|i| {
                if i < primal && is_last(i) {
                    (n, 2, position[i], i)
                } else {
                    (position[i], 0, position[i], i)
                }
            })
            .collect();
        let csc = column_major(a);
        for c in primal..n {
            let last = csc
                .outer_view(c)
                .into_iter()
                .flat_map(|col| col.iter().map(|(r, _)| r).collect::<Vec<_>>())
                .filter(|&r| r < primal && !is_last(r))
                .map(|r| position[r])
                .max()
                .unwrap_or(position[c]);
            key[c] = (last, 1, position[c], c);
        }
        key.sort_unstable();
        let fwd: Vec<usize> = key.iter().map(|&(_, _, _, i)| i).collect();
        let inv = inverse(&fwd, n)?;
        let perm = PermRef::new_checked(&fwd, &inv, n);
        let symbolic = factorize_symbolic_cholesky(
            view.symbolic(),
            Side::Lower,
            SymmetricOrdering::Custom(perm),
            Default::default(),
        )
        .map_err(|e| SolverError::Backend(format!("{e:?}")))?;
        let mut this = Self {
            pattern,
            symbolic: Arc::new(symbolic),
            values: Vec::new(),
            matrix: a.clone(),
        };
        this.values = this.numeric(&view)?;
        this.check_factors()?;
        Ok(this)
    }

    /// The numeric factor of `view` on the analysed pattern.
    fn numeric(&self, view: &CscView<'_>) -> Result<Vec<f64>, SolverError> {
        let symbolic = &*self.symbolic;
        let mut values = Vec::new();
        values
            .try_reserve_exact(symbolic.len_val())
            .map_err(|e| SolverError::Backend(format!("the factor does not fit: {e}")))?;
        values.resize(symbolic.len_val(), 0.0);
        // No regularisation: the order is meant to make every pivot nonzero; the factors are
        // checked on a known solution below instead.
        let regularization = faer::linalg::cholesky::ldlt::factor::LdltRegularization {
            dynamic_regularization_signs: None,
            dynamic_regularization_delta: 0.0,
            dynamic_regularization_epsilon: 0.0,
        };
        let par = faer::Par::Seq;
        let mut mem = MemBuffer::try_new(
            symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default()),
        )
        .map_err(|e| SolverError::Backend(format!("{e:?}")))?;
        symbolic
            .factorize_numeric_ldlt::<f64>(
                &mut values,
                view.matrix(),
                Side::Lower,
                regularization,
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| match e {
                faer::linalg::cholesky::ldlt::factor::LdltError::ZeroPivot { index } => {
                    SolverError::Singular { pivot: Some(index) }
                }
            })?;
        Ok(values)
    }

    /// Checks the factors `values` of the matrix on a known solution: `x* = 1 + i / n`, `b =
    /// A x*`, one solve with a refinement step; the error must be below `1e-8` of `|x*|`.
    fn check_factors(&self) -> Result<(), SolverError> {
        let n = self.pattern.n;
        let exact: Vec<f64> = (0..n).map(|i| 1.0 + i as f64 / n as f64).collect();
        let mut x = self.times(&exact);
        self.solve_in_place(&mut x)?;
        let err = x
            .iter()
            .zip(&exact)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt();
        let norm = exact.iter().map(|v| v * v).sum::<f64>().sqrt();
        if err <= 1e-8 * norm {
            Ok(())
        } else {
            Err(SolverError::Singular { pivot: None })
        }
    }

    /// `A x` (the matrix is symmetric: CSR and CSC rows alike).
    fn times(&self, x: &[f64]) -> Vec<f64> {
        self.matrix
            .outer_iterator()
            .map(|row| row.iter().map(|(j, v)| v * x[j]).sum())
            .collect()
    }

    /// Factorises a new matrix with the same sparsity pattern, reusing the analysis.
    ///
    /// # Errors
    /// [`SolverError::PatternMismatch`], and the errors of [`try_new`](Self::try_new); on
    /// error the previous factors are kept.
    pub fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        self.pattern.check(a)?;
        let a = &*with_full_diagonal(a);
        let view = CscView::of(a)?;
        let old = std::mem::replace(&mut self.matrix, a.clone());
        match self.numeric(&view) {
            Ok(values) => {
                let old_values = std::mem::replace(&mut self.values, values);
                self.check_factors().inspect_err(|_| {
                    self.values = old_values;
                    self.matrix = old.clone();
                })
            }
            Err(e) => {
                self.matrix = old;
                Err(e)
            }
        }
    }

    /// The matrix size.
    pub fn dim(&self) -> usize {
        self.pattern.n
    }

    /// The number of stored entries of the factor `L`.
    pub fn factor_entries(&self) -> usize {
        self.symbolic.len_val()
    }

    fn solve_factored(&self, x: &mut [f64]) -> Result<(), SolverError> {
        let n = x.len();
        let rhs = MatMut::from_column_major_slice_mut(x, n, 1);
        let par = faer::Par::Seq;
        let mut mem = MemBuffer::try_new(self.symbolic.solve_in_place_scratch::<f64>(1, par))
            .map_err(|e| SolverError::Backend(format!("{e:?}")))?;
        faer::sparse::linalg::cholesky::LdltRef::new(&self.symbolic, &self.values)
            .solve_in_place_with_conj(Conj::No, rhs, par, MemStack::new(&mut mem));
        check_finite(x)
    }

    /// Overwrites `x` (the right-hand side) with the solution of `A x = b`, iteratively
    /// refined.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`]; [`SolverError::Singular`] if the solution is not
    /// finite.
    pub fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        check_rhs(self.pattern.n, x.len())?;
        let b = x.to_vec();
        self.solve_factored(x)?;
        // Iterative refinement, r = b - A x, x += A^-1 r, while the residual falls by half
        // (at most MAX_REFINEMENT steps): without pivoting, a badly scaled saddle point loses
        // digits that a step or two recovers.
        let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
        let mut last = f64::INFINITY;
        for _ in 0..MAX_REFINEMENT {
            let ax = self.times(x);
            let mut r: Vec<f64> = b.iter().zip(&ax).map(|(b, a)| b - a).collect();
            let rn = norm(&r);
            if rn.is_nan() || rn >= 0.5 * last || rn == 0.0 {
                break;
            }
            last = rn;
            self.solve_factored(&mut r)?;
            for (xi, ri) in x.iter_mut().zip(&r) {
                *xi += ri;
            }
        }
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

/// The faer backend of the solver interface: [`LuFactorization`] for
/// [`MatrixKind::General`], [`CholeskyFactorization`] (its fill-reducing ordering chosen by
/// size) for [`MatrixKind::SymmetricPositiveDefinite`], and the restarted
/// [`gmres`](super::gmres) (the interface's default).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FaerSolver;

impl SparseSolver for FaerSolver {
    fn factor(
        &self,
        a: &SparseMatrix,
        kind: MatrixKind,
    ) -> Result<Box<dyn Factorization>, SolverError> {
        Ok(match kind {
            MatrixKind::General => Box::new(LuFactorization::try_new(a)?),
            MatrixKind::SymmetricPositiveDefinite => Box::new(CholeskyFactorization::try_new(a)?),
        })
    }
}

impl Factorization for LuFactorization {
    fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        LuFactorization::solve_in_place(self, x)
    }
    fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        LuFactorization::refactor(self, a)
    }
    fn stats(&self) -> FactorStats {
        FactorStats {
            dim: self.dim(),
            factor_entries: None,
            method: "sparse LU (partial pivoting)",
        }
    }
}

impl Factorization for CholeskyFactorization {
    fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        CholeskyFactorization::solve_in_place(self, x)
    }
    fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        CholeskyFactorization::refactor(self, a)
    }
    fn stats(&self) -> FactorStats {
        FactorStats {
            dim: self.dim(),
            factor_entries: Some(self.factor_entries()),
            method: "sparse Cholesky",
        }
    }
}

impl Factorization for SaddlePointFactorization {
    fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        SaddlePointFactorization::solve_in_place(self, x)
    }
    fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        SaddlePointFactorization::refactor(self, a)
    }
    fn stats(&self) -> FactorStats {
        FactorStats {
            dim: self.dim(),
            factor_entries: Some(self.factor_entries()),
            method: "sparse LDL^T (saddle point)",
        }
    }
}
