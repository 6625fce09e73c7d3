//! The LU solve of a sparse matrix bordered by a few dense rows and columns (a global
//! unknown coupled to a whole body, as the axial strain of generalized plane strain): the
//! sparse block is factorised alone and the border eliminated by its Schur complement, so the
//! dense rows and columns never enter the sparse factorisation, whose fill and pivoting they
//! would spoil.

use std::borrow::Cow;

use super::solver::{FactorStats, Factorization};
use super::{LuFactorization, SolverError, SparseMatrix, Triplets};

/// The factorisation of `A = [B C; R D]` with the last `k` rows and columns the border:
/// `B` by the sparse [`LuFactorization`], the `k x k` Schur complement `S = D - R B^-1 C`
/// densely (Gaussian elimination with partial pivoting). A solve costs `k + 1` solves with
/// `B` when factorised and one per right-hand side after. With `k = 0` it is the LU of `A`.
///
/// ```
/// use mortar_fem::linalg::{BorderedLu, Triplets};
/// // A tridiagonal block bordered by one dense row and column.
/// let n = 5;
/// let mut t = Triplets::default();
/// for i in 0..n - 1 {
///     t.push(i as u32, i as u32, 4.0);
///     if i > 0 {
///         t.push(i as u32, i as u32 - 1, -1.0);
///         t.push(i as u32 - 1, i as u32, -1.0);
///     }
///     t.push(i as u32, (n - 1) as u32, 1.0);
///     t.push((n - 1) as u32, i as u32, 1.0);
/// }
/// t.push((n - 1) as u32, (n - 1) as u32, 10.0);
/// let a = t.to_csr(n, n);
/// let x = [1.0, 2.0, 3.0, 4.0, 5.0];
/// let mut b = vec![0.0; n];
/// for (r, row) in a.outer_iterator().enumerate() {
///     b[r] = row.iter().map(|(c, v)| v * x[c]).sum();
/// }
/// let lu = BorderedLu::try_new(&a, 1)?;
/// lu.solve_in_place(&mut b)?;
/// assert!(b.iter().zip(x).all(|(a, b)| (a - b).abs() < 1e-13));
/// # Ok::<(), mortar_fem::linalg::SolverError>(())
/// ```
#[derive(Debug)]
pub struct BorderedLu {
    inner: LuFactorization,
    k: usize,
    /// `B^-1 C`, one vector of the leading size per border column.
    binv_c: Vec<Vec<f64>>,
    /// The border rows restricted to the leading columns, `(column, value)`.
    rows: Vec<Vec<(usize, f64)>>,
    /// The Schur complement, row-major `k x k`.
    schur: Vec<f64>,
}

impl BorderedLu {
    /// Factorises `a` with its last `k` rows and columns as the border.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] for a non-square matrix or a border of `k` at least
    /// its size, [`SolverError::Singular`] for a singular leading block or Schur complement,
    /// and the errors of [`LuFactorization::try_new`].
    pub fn try_new(a: &SparseMatrix, k: usize) -> Result<Self, SolverError> {
        let (block, rows, cols, corner) = split(a, k)?;
        let inner = LuFactorization::try_new(&block)?;
        Self::finish(inner, k, rows, cols, corner)
    }

    /// Factorises a new matrix with the same pattern and border, reusing the leading block's
    /// symbolic analysis.
    ///
    /// # Errors
    /// As [`try_new`](Self::try_new), [`SolverError::PatternMismatch`] for another pattern;
    /// after an error, factorise anew with [`try_new`](Self::try_new).
    pub fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        let (block, rows, cols, corner) = split(a, self.k)?;
        self.inner.refactor(&block)?;
        let (binv_c, schur) = border(&self.inner, self.k, &rows, cols, corner)?;
        self.rows = rows;
        self.binv_c = binv_c;
        self.schur = schur;
        Ok(())
    }

    fn finish(
        inner: LuFactorization,
        k: usize,
        rows: Vec<Vec<(usize, f64)>>,
        cols: Vec<Vec<f64>>,
        corner: Vec<f64>,
    ) -> Result<Self, SolverError> {
        let (binv_c, schur) = border(&inner, k, &rows, cols, corner)?;
        Ok(Self {
            inner,
            k,
            binv_c,
            rows,
            schur,
        })
    }

    /// The matrix size.
    pub fn dim(&self) -> usize {
        self.inner.dim() + self.k
    }

    /// Solves `A x = b` in place.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] for a vector of another size,
    /// [`SolverError::Singular`] if the solution is not finite.
    pub fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        if x.len() != self.dim() {
            return Err(SolverError::DimensionMismatch {
                expected: self.dim(),
                found: x.len(),
                what: "entries of the right-hand side",
            });
        }
        let m = self.inner.dim();
        let (head, tail) = x.split_at_mut(m);
        self.inner.solve_in_place(head)?;
        // The border: S x2 = f2 - R B^-1 f1.
        for (t, row) in tail.iter_mut().zip(&self.rows) {
            *t -= row.iter().map(|&(c, r)| r * head[c]).sum::<f64>();
        }
        dense_solve(&self.schur, self.k, tail)?;
        // x1 = B^-1 f1 - B^-1 C x2.
        for (v, &t) in self.binv_c.iter().zip(tail.iter()) {
            for (h, c) in head.iter_mut().zip(v) {
                *h -= c * t;
            }
        }
        if x.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(SolverError::Singular { pivot: None })
        }
    }
}

/// `B^-1 C` and the Schur complement `D - R B^-1 C` of the factorised leading block `inner`,
/// checked to be non-singular.
fn border(
    inner: &LuFactorization,
    k: usize,
    rows: &[Vec<(usize, f64)>],
    cols: Vec<Vec<f64>>,
    corner: Vec<f64>,
) -> Result<(Vec<Vec<f64>>, Vec<f64>), SolverError> {
    let mut binv_c = Vec::with_capacity(k);
    for mut c in cols {
        inner.solve_in_place(&mut c)?;
        binv_c.push(c);
    }
    let mut schur = corner;
    for (i, row) in rows.iter().enumerate() {
        for (j, v) in binv_c.iter().enumerate() {
            schur[i * k + j] -= row.iter().map(|&(c, r)| r * v[c]).sum::<f64>();
        }
    }
    // A singular complement is caught here rather than at the first solve.
    dense_solve(&schur, k, &mut vec![0.0; k])?;
    Ok((binv_c, schur))
}

/// The leading block of `a` (CSR), the border rows on the leading columns (sparse), the
/// border columns on the leading rows (dense) and the `k x k` corner (row-major).
#[allow(clippy::type_complexity)]
fn split(
    a: &SparseMatrix,
    k: usize,
) -> Result<
    (
        Cow<'_, SparseMatrix>,
        Vec<Vec<(usize, f64)>>,
        Vec<Vec<f64>>,
        Vec<f64>,
    ),
    SolverError,
> {
    let n = a.rows();
    if a.cols() != n || k >= n.max(1) {
        return Err(SolverError::DimensionMismatch {
            expected: n,
            found: if a.cols() != n { a.cols() } else { k },
            what: if a.cols() != n {
                "columns of a square matrix"
            } else {
                "border rows (fewer than the matrix's)"
            },
        });
    }
    if k == 0 {
        return Ok((Cow::Borrowed(a), Vec::new(), Vec::new(), Vec::new()));
    }
    let m = n - k;
    let mut block = Triplets::default();
    let mut rows = vec![Vec::new(); k];
    let mut cols = vec![vec![0.0; m]; k];
    let mut corner = vec![0.0; k * k];
    for (r, row) in a.outer_iterator().enumerate() {
        for (c, &v) in row.iter() {
            match (r < m, c < m) {
                (true, true) => block.push(r as u32, c as u32, v),
                (true, false) => cols[c - m][r] += v,
                (false, true) => rows[r - m].push((c, v)),
                (false, false) => corner[(r - m) * k + (c - m)] += v,
            }
        }
    }
    Ok((Cow::Owned(block.to_csr(m, m)), rows, cols, corner))
}

/// Solves the dense `k x k` system `a x = b` (row-major `a`) in place by Gaussian elimination
/// with partial pivoting.
fn dense_solve(a: &[f64], k: usize, b: &mut [f64]) -> Result<(), SolverError> {
    let mut m = a.to_vec();
    for col in 0..k {
        let p = (col..k)
            .max_by(|&i, &j| m[i * k + col].abs().total_cmp(&m[j * k + col].abs()))
            .expect("a non-empty range");
        let pivot = m[p * k + col];
        if pivot == 0.0 || !pivot.is_finite() {
            return Err(SolverError::Singular { pivot: Some(col) });
        }
        if p != col {
            for j in 0..k {
                m.swap(p * k + j, col * k + j);
            }
            b.swap(p, col);
        }
        for i in col + 1..k {
            let f = m[i * k + col] / pivot;
            for j in col..k {
                m[i * k + j] -= f * m[col * k + j];
            }
            b[i] -= f * b[col];
        }
    }
    for col in (0..k).rev() {
        let s: f64 = (col + 1..k).map(|j| m[col * k + j] * b[j]).sum();
        b[col] = (b[col] - s) / m[col * k + col];
    }
    Ok(())
}

impl Factorization for BorderedLu {
    fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        BorderedLu::solve_in_place(self, x)
    }
    fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        BorderedLu::refactor(self, a)
    }
    fn stats(&self) -> FactorStats {
        FactorStats {
            dim: self.dim(),
            factor_entries: None,
            method: "sparse LU with a dense border (its Schur complement)",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2D Laplacian-like block of `m` unknowns bordered by `k` dense rows and columns
    /// scaled by `s`.
    fn matrix(m: usize, k: usize, s: f64) -> SparseMatrix {
        let n = m + k;
        let mut t = Triplets::default();
        for i in 0..m {
            t.push(i as u32, i as u32, 4.0 + (i % 3) as f64);
            if i > 0 {
                t.push(i as u32, i as u32 - 1, -1.0);
            }
            if i + 1 < m {
                t.push(i as u32, i as u32 + 1, -1.5);
            }
            for b in 0..k {
                let v = s * (1.0 + ((i + b) % 5) as f64);
                t.push(i as u32, (m + b) as u32, v);
                t.push((m + b) as u32, i as u32, 0.5 * v);
            }
        }
        for b in 0..k {
            t.push((m + b) as u32, (m + b) as u32, 50.0 * (b + 1) as f64);
        }
        t.to_csr(n, n)
    }

    fn product(a: &SparseMatrix, x: &[f64]) -> Vec<f64> {
        a.outer_iterator()
            .map(|row| row.iter().map(|(c, v)| v * x[c]).sum())
            .collect()
    }

    /// Source: the exact solution of a manufactured system, and the plain sparse LU of the
    /// same matrix; with any border size, and after a refactorisation.
    #[test]
    fn solves_as_the_plain_lu_does() {
        for k in [0, 1, 2, 3] {
            let a = matrix(40, k, 0.1);
            let x: Vec<f64> = (0..40 + k).map(|i| 1.0 + i as f64 * 0.25).collect();
            // The largest error of the solve of `a x = b` by `lu`.
            let error = |lu: &BorderedLu, a: &SparseMatrix| {
                let mut b = product(a, &x);
                lu.solve_in_place(&mut b).unwrap();
                b.iter()
                    .zip(&x)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max)
            };
            let mut lu = BorderedLu::try_new(&a, k).unwrap();
            let err = error(&lu, &a);
            assert!(err < 1e-12, "k = {k}: {err:e}");
            let a2 = matrix(40, k, 0.3);
            lu.refactor(&a2).unwrap();
            let err = error(&lu, &a2);
            assert!(err < 1e-12, "refactored, k = {k}: {err:e}");
        }
    }

    /// A border whose Schur complement vanishes (a border row and column equal to a leading
    /// row and column, the corner to its diagonal) is refused as singular, not solved.
    #[test]
    fn a_singular_schur_complement_is_refused() {
        let mut t = Triplets::default();
        t.push(0, 0, 2.0);
        t.push(1, 1, 3.0);
        t.push(0, 2, 2.0);
        t.push(2, 0, 2.0);
        t.push(2, 2, 2.0);
        let a = t.to_csr(3, 3);
        assert!(matches!(
            BorderedLu::try_new(&a, 1),
            Err(SolverError::Singular { .. })
        ));
        assert!(matches!(
            BorderedLu::try_new(&a, 3),
            Err(SolverError::DimensionMismatch { .. })
        ));
    }
}
