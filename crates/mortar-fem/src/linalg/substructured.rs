//! A sparse Cholesky factorisation of a matrix whose unknowns split into two domains that
//! touch only through a separator (two bodies tied along their interface), with the two
//! domains factorised side by side.
//!
//! A supernodal factorisation visits its elimination tree one supernode after the other, so
//! on a 2D mesh, whose supernodes are small, it uses one thread however many there are. With
//! the separator `s` eliminated last, the two domains' subtrees are independent:
//!
//! ```text
//! A = [A_00  0     A_0s]      S_d = A_ss - A_sd A_dd^-1 A_ds   (d = 0, 1)
//!     [0     A_11  A_1s]      S   = A_ss - A_s0 A_00^-1 A_0s - A_s1 A_11^-1 A_1s
//!     [A_s0  A_s1  A_ss]          = S_0 + S_1 - A_ss
//! ```
//!
//! Each domain's principal submatrix `B_d = [A_dd A_ds; A_sd A_ss]` (positive definite, as
//! every principal submatrix of a positive definite matrix) is factorised with the separator
//! last, on its own thread; the trailing block of its factor gives `S_d = L_ss L_ss^T`, and
//! the dense `S` (positive definite: the Schur complement of `A`) is factorised once. A solve
//! takes two solves with each `B_d` (the domains again side by side) and one with `S`:
//! with `[u; v] = B_d^-1 [b_d; c]`, `S_d v = c - A_sd A_dd^-1 b_d` and
//! `u = A_dd^-1 (b_d - A_ds v)`, so `c = 0` gives `g_d = A_sd A_dd^-1 b_d = -S_d v`,
//! `S x_s = b_s - g_0 - g_1`, and `c = S_d x_s + g_d` gives `u = x_d`.
//!
//! This is the first level of a nested dissection with the separator the problem provides;
//! it pays where the separator is small (a 2D interface: `S` is dense, `n_s^3 / 3` flops).
//! [`SubstructuredCholesky::balanced_split`] evens out two domains of unequal size by moving
//! layers of the larger one next to the separator to the other side, so that both threads
//! take about as long.

use rayon::prelude::*;

use super::faer_backend::{check_square, dense_cholesky, dense_gram, fill_reducing_ordering};
use super::solver::{FactorStats, Factorization};
use super::{CholeskyFactorization, SolverError, SparseMatrix};

/// The number of unknowns from which [`SubstructuredCholesky::try_new_if_worthwhile`]
/// factorises by domain. Measured on the straight 2D tied-heat scene (`bench_tied_heat --n N`,
/// build and factorisation, medians of 3, both factorisations in one session): 1,786 unknowns
/// 3 ms by body against 2 ms as one matrix; 6,898: 9 against 10 ms; 27,106: 27 against 37 ms;
/// 107,458: 0.14 against 0.18 s; 996,661: 1.7 against 2.4 s.
pub const SUBSTRUCTURED_MIN: usize = 5_000;

/// One domain: its unknowns, the factor of its principal submatrix with the separator
/// (separator last), and that factor's trailing block `L_ss` (`S_d = L_ss L_ss^T`; dense,
/// lower, by columns).
#[derive(Debug, Clone)]
struct Domain {
    /// Global indices of the domain's own unknowns, ascending.
    own: Vec<usize>,
    factor: CholeskyFactorization,
    lss: Vec<f64>,
    /// `S_d = L_ss L_ss^T` (lower triangle), made on the domain's thread; emptied once `S`
    /// is formed.
    gram: Vec<f64>,
}

/// `A = L L^T` for a symmetric positive definite matrix whose unknowns form two domains
/// coupled only through a separator, the domains factorised in parallel (see the module
/// documentation). Deterministic: the same bits whatever the thread count (each domain is
/// factorised as a whole on one thread, and the pieces are combined in a fixed order).
#[derive(Debug, Clone)]
pub struct SubstructuredCholesky {
    n: usize,
    /// Global indices of the separator, ascending.
    separator: Vec<usize>,
    domains: [Domain; 2],
    /// The Cholesky factor of `S` (dense, lower, by columns).
    schur_factor: Vec<f64>,
}

impl SubstructuredCholesky {
    /// The separator of the split `second` (per unknown: whether it belongs to the second
    /// domain): the unknowns of the second domain that share a stored entry with one of the
    /// first (in either triangle, so that an entry stored on one side only is not lost), in
    /// ascending order.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] if `a` is not square or `second` has another length.
    pub fn separator(a: &SparseMatrix, second: &[bool]) -> Result<Vec<usize>, SolverError> {
        check_split(a, second)?;
        let mut mark = vec![false; second.len()];
        for (r, row) in a.outer_iterator().enumerate() {
            for (c, _) in row.iter() {
                if second[r] != second[c] {
                    mark[if second[r] { r } else { c }] = true;
                }
            }
        }
        Ok((0..second.len()).filter(|&i| mark[i]).collect())
    }

    /// [`try_new`](Self::try_new) where it pays, `None` where it does not: below
    /// [`SUBSTRUCTURED_MIN`] unknowns, without separator (a caller factorising the domains
    /// apart would do better), or with a separator of more than `2 sqrt(n)` unknowns (its
    /// dense Schur complement costs `k^3 / 3`, at most the sparse factors' `O(n^1.5)` of a 2D
    /// mesh; a 3D interface at scale is larger).
    ///
    /// # Errors
    /// Those of [`try_new`](Self::try_new).
    pub fn try_new_if_worthwhile(
        a: &SparseMatrix,
        second: &[bool],
    ) -> Result<Option<Self>, SolverError> {
        let n = check_square(a)?;
        if n < SUBSTRUCTURED_MIN {
            return Ok(None);
        }
        let k = Self::separator(a, second)?.len();
        if k == 0 || k * k > 4 * n {
            return Ok(None);
        }
        Self::try_new(a, &Self::balanced_split(a, second)?).map(Some)
    }

    /// The split `second` made more even: whole layers of the larger domain next to the
    /// smaller one (breadth-first levels of the matrix graph, from the unknowns that touch
    /// the other domain) move to the smaller domain while that brings the two closer in size
    /// and the separator, which moves with them (the last layer moved, or the next where the
    /// second domain gives), stays within `2 sqrt(n)` unknowns. Two bodies of unequal size, as a tied
    /// pair usually is, then take about as long each on their threads. Deterministic.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] if `a` is not square or `second` has another length.
    pub fn balanced_split(a: &SparseMatrix, second: &[bool]) -> Result<Vec<bool>, SolverError> {
        check_split(a, second)?;
        let n = second.len();
        let mut split = second.to_vec();
        let in_second = split.iter().filter(|&&b| b).count();
        // The larger domain gives layers to the smaller one.
        let larger = in_second > n - in_second;
        let gap = in_second.abs_diff(n - in_second);
        let limit = 2.0 * (n as f64).sqrt();
        let (ptr, idx) = (a.proper_indptr(), a.indices());
        let neighbours = |i: usize| &idx[ptr[i]..ptr[i + 1]];
        // Layer 1: the larger domain's unknowns with a neighbour in the smaller one.
        let mut layer: Vec<usize> = (0..n)
            .filter(|&i| split[i] == larger && neighbours(i).iter().any(|&c| split[c] != larger))
            .collect();
        let mut moved = 0usize;
        // Moving a layer of m unknowns changes the difference by 2 m: worth it while it does
        // not overshoot the balance by more than it gains.
        while !layer.is_empty()
            && (layer.len() as f64) <= limit
            && 2 * (moved + layer.len()) <= gap + layer.len()
        {
            for &i in &layer {
                split[i] = !larger;
            }
            // The next layer: unmoved unknowns of the larger domain next to this one.
            let mut next: Vec<usize> = layer
                .iter()
                .flat_map(|&i| neighbours(i).iter().copied())
                .filter(|&c| split[c] == larger)
                .collect();
            next.sort_unstable();
            next.dedup();
            // Where the second domain gives, the separator (its unknowns next to the first)
            // becomes the next layer: not a move that makes it larger than the bound.
            if larger && (next.len() as f64) > limit {
                for &i in &layer {
                    split[i] = larger;
                }
                break;
            }
            moved += layer.len();
            layer = next;
        }
        Ok(split)
    }

    /// Factorises `a` (symmetric positive definite, both triangles stored) split into the
    /// unknowns with `second[i] == false` and those with `true`; the separator is
    /// [`separator`](Self::separator). Each domain is ordered by
    /// [`fill_reducing_ordering`] with the separator moved last.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] for a non-square matrix or a split of another
    /// length; [`SolverError::NotPositiveDefinite`]; [`SolverError::Backend`].
    pub fn try_new(a: &SparseMatrix, second: &[bool]) -> Result<Self, SolverError> {
        let separator = Self::separator(a, second)?;
        let n = second.len();
        let (d0, d1) = rayon::join(
            || {
                Domain::new(
                    a,
                    (0..n).filter(|&i| !second[i] && !in_sorted(&separator, i)),
                    &separator,
                )
            },
            || {
                Domain::new(
                    a,
                    (0..n).filter(|&i| second[i] && !in_sorted(&separator, i)),
                    &separator,
                )
            },
        );
        let mut domains = [d0?, d1?];
        let schur_factor = schur_factor(a, &separator, &mut domains)?;
        Ok(Self {
            n,
            separator,
            domains,
            schur_factor,
        })
    }

    /// Factorises a new matrix with the same sparsity pattern and the same split, reusing
    /// the orderings and symbolic analyses.
    ///
    /// # Errors
    /// [`SolverError::PatternMismatch`], and the errors of [`try_new`](Self::try_new); on
    /// error the previous factors are kept.
    pub fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        if a.rows() != self.n || a.cols() != self.n {
            return Err(SolverError::PatternMismatch(format!(
                "a {}x{} matrix for a factorisation of size {}",
                a.rows(),
                a.cols(),
                self.n
            )));
        }
        // The same split: an entry between the domains outside the separator would be lost.
        let mut second = vec![false; self.n];
        for &i in self.domains[1].own.iter().chain(&self.separator) {
            second[i] = true;
        }
        if Self::separator(a, &second)? != self.separator {
            return Err(SolverError::PatternMismatch(
                "the unknowns that couple the two domains differ from the analysed ones".into(),
            ));
        }
        let sep = &self.separator;
        let [d0, d1] = &self.domains;
        let (r0, r1) = rayon::join(|| d0.refactored(a, sep), || d1.refactored(a, sep));
        let mut domains = [r0?, r1?];
        let schur_factor = schur_factor(a, sep, &mut domains)?;
        self.domains = domains;
        self.schur_factor = schur_factor;
        Ok(())
    }

    /// The matrix size.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// The separator's size.
    pub fn separator_len(&self) -> usize {
        self.separator.len()
    }

    /// Stored entries of the factors: both domains' sparse factors and the dense separator's
    /// lower triangle.
    pub fn factor_entries(&self) -> usize {
        let k = self.separator.len();
        self.domains
            .iter()
            .map(|d| d.factor.factor_entries())
            .sum::<usize>()
            + k * (k + 1) / 2
    }

    /// Overwrites `x` (the right-hand side) with the solution of `A x = b`.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`]; [`SolverError::Singular`] if the solution is not
    /// finite.
    pub fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        if x.len() != self.n {
            return Err(SolverError::DimensionMismatch {
                expected: self.n,
                found: x.len(),
                what: "entries of the right-hand side (the matrix's size)",
            });
        }
        let k = self.separator.len();
        let b: &[f64] = x;
        // Forward: y = L^-1 P [b_d; 0]; its separator part y_s = -L_ss^-1 L_sd y_d, so that
        // g_d = A_sd A_dd^-1 b_d = L_sd y_d = -L_ss y_s.
        let forward = self
            .domains
            .par_iter()
            .map(|d| -> Result<(Vec<f64>, Vec<f64>), SolverError> {
                let mut y = d.local(b);
                d.factor.forward_in_place(&mut y)?;
                let mut g = vec![0.0; k];
                lower_mul_add(&d.lss, k, &y[y.len() - k..], -1.0, &mut g);
                Ok((y, g))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut xs: Vec<f64> = self.separator.iter().map(|&i| b[i]).collect();
        for (t, v) in xs.iter_mut().enumerate() {
            *v -= forward[0].1[t] + forward[1].1[t];
        }
        lower_solve(&self.schur_factor, k, &mut xs);
        lower_transpose_solve(&self.schur_factor, k, &mut xs);
        // Backward from [y_d; L_ss^T x_s]: L^-T gives [L_dd^-T (y_d - L_sd^T x_s); x_s], whose
        // domain part is x_d = A_dd^-1 (b_d - A_ds x_s).
        let parts = self
            .domains
            .par_iter()
            .zip(forward)
            .map(|(d, (mut y, _))| -> Result<Vec<f64>, SolverError> {
                let m = y.len() - k;
                let z = &mut y[m..];
                z.fill(0.0);
                lower_transpose_mul_add(&d.lss, k, &xs, z);
                d.factor.backward_in_place(&mut y)?;
                y.truncate(d.own.len());
                Ok(y)
            })
            .collect::<Result<Vec<_>, _>>()?;
        for (d, part) in self.domains.iter().zip(&parts) {
            for (&i, &v) in d.own.iter().zip(part) {
                x[i] = v;
            }
        }
        for (&i, &v) in self.separator.iter().zip(&xs) {
            x[i] = v;
        }
        if x.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(SolverError::Singular { pivot: None })
        }
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

impl Domain {
    /// The domain of the unknowns `own` (ascending) with the separator `sep`: its principal
    /// submatrix ordered, analysed and factorised.
    fn new(
        a: &SparseMatrix,
        own: impl Iterator<Item = usize>,
        sep: &[usize],
    ) -> Result<Self, SolverError> {
        let own: Vec<usize> = own.collect();
        let b = principal_submatrix(a, &own, sep);
        let (order, _) = fill_reducing_ordering(&b)?;
        // The separator (local indices from own.len()) last, each part in the order found.
        let m = own.len();
        let mut perm: Vec<usize> = order.iter().copied().filter(|&i| i < m).collect();
        perm.extend(m..m + sep.len());
        let factor = CholeskyFactorization::try_new_ordered(&b, &perm)?;
        let lss = factor.trailing_factor(sep.len());
        let gram = dense_gram(&lss, sep.len());
        Ok(Self {
            own,
            factor,
            lss,
            gram,
        })
    }

    /// This domain factorised anew for the matrix `a` of the same pattern.
    fn refactored(&self, a: &SparseMatrix, sep: &[usize]) -> Result<Self, SolverError> {
        let b = principal_submatrix(a, &self.own, sep);
        let mut factor = self.factor.clone();
        factor.refactor(&b)?;
        let lss = factor.trailing_factor(sep.len());
        let gram = dense_gram(&lss, sep.len());
        Ok(Self {
            own: self.own.clone(),
            factor,
            lss,
            gram,
        })
    }

    /// `[b_own; 0]` in the domain's local numbering.
    fn local(&self, b: &[f64]) -> Vec<f64> {
        let mut r: Vec<f64> = self.own.iter().map(|&i| b[i]).collect();
        r.resize(self.factor.dim(), 0.0);
        r
    }
}

/// The dense Cholesky factor of `S = S_0 + S_1 - A_ss` (the lower triangles read; the
/// domains' `S_d` freed).
fn schur_factor(
    a: &SparseMatrix,
    sep: &[usize],
    domains: &mut [Domain; 2],
) -> Result<Vec<f64>, SolverError> {
    let k = sep.len();
    let mut s: Vec<f64> = domains[0]
        .gram
        .iter()
        .zip(&domains[1].gram)
        .map(|(a, b)| a + b)
        .collect();
    for d in domains.iter_mut() {
        d.gram = Vec::new();
    }
    for (t, &i) in sep.iter().enumerate() {
        let row = a.outer_view(i).expect("separator row in range");
        for (c, v) in row.iter() {
            if let Ok(u) = sep.binary_search(&c) {
                s[u * k + t] -= v;
            }
        }
    }
    dense_cholesky(&mut s, k)?;
    Ok(s)
}

/// The principal submatrix of `a` on the unknowns `own` then `sep` (both ascending), in that
/// local numbering (CSR, columns sorted).
fn principal_submatrix(a: &SparseMatrix, own: &[usize], sep: &[usize]) -> SparseMatrix {
    const NONE: u32 = u32::MAX;
    let mut local = vec![NONE; a.rows()];
    for (l, &g) in own.iter().chain(sep).enumerate() {
        local[g] = l as u32;
    }
    let size = own.len() + sep.len();
    let mut indptr = Vec::with_capacity(size + 1);
    let mut indices = Vec::new();
    let mut data = Vec::new();
    let mut row: Vec<(u32, f64)> = Vec::new();
    indptr.push(0);
    for &g in own.iter().chain(sep) {
        row.clear();
        let view = a.outer_view(g).expect("row in range");
        row.extend(
            view.iter()
                .filter(|(c, _)| local[*c] != NONE)
                .map(|(c, &v)| (local[c], v)),
        );
        row.sort_unstable_by_key(|e| e.0);
        indices.extend(row.iter().map(|e| e.0 as usize));
        data.extend(row.iter().map(|e| e.1));
        indptr.push(indices.len());
    }
    SparseMatrix::new((size, size), indptr, indices, data)
}

fn check_split(a: &SparseMatrix, second: &[bool]) -> Result<(), SolverError> {
    let n = check_square(a)?;
    if second.len() != n {
        return Err(SolverError::DimensionMismatch {
            expected: n,
            found: second.len(),
            what: "entries of the split into two domains (the matrix's size)",
        });
    }
    Ok(())
}

fn in_sorted(list: &[usize], i: usize) -> bool {
    list.binary_search(&i).is_ok()
}

/// `y += alpha L v` for the dense lower-triangular `k x k` matrix `l` (by columns).
fn lower_mul_add(l: &[f64], k: usize, v: &[f64], alpha: f64, y: &mut [f64]) {
    for (j, &vj) in v.iter().enumerate() {
        let w = alpha * vj;
        for (yi, lij) in y[j..].iter_mut().zip(&l[j * k + j..(j + 1) * k]) {
            *yi += lij * w;
        }
    }
}

/// `y += L^T v` for the dense lower-triangular `k x k` matrix `l` (by columns).
fn lower_transpose_mul_add(l: &[f64], k: usize, v: &[f64], y: &mut [f64]) {
    for (j, yj) in y.iter_mut().enumerate() {
        let col = &l[j * k + j..(j + 1) * k];
        *yj += col.iter().zip(&v[j..]).map(|(a, b)| a * b).sum::<f64>();
    }
}

/// `x <- L^-1 x` for the dense lower-triangular `k x k` factor `l` (by columns).
fn lower_solve(l: &[f64], k: usize, x: &mut [f64]) {
    for j in 0..k {
        let col = &l[j * k..(j + 1) * k];
        x[j] /= col[j];
        let xj = x[j];
        for i in j + 1..k {
            x[i] -= col[i] * xj;
        }
    }
}

/// `x <- L^-T x` for the dense lower-triangular `k x k` factor `l` (by columns).
fn lower_transpose_solve(l: &[f64], k: usize, x: &mut [f64]) {
    for j in (0..k).rev() {
        let col = &l[j * k..(j + 1) * k];
        let dot: f64 = (j + 1..k).map(|i| col[i] * x[i]).sum();
        x[j] = (x[j] - dot) / col[j];
    }
}

impl Factorization for SubstructuredCholesky {
    fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        SubstructuredCholesky::solve_in_place(self, x)
    }
    fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        SubstructuredCholesky::refactor(self, a)
    }
    fn stats(&self) -> FactorStats {
        FactorStats {
            dim: self.dim(),
            factor_entries: Some(self.factor_entries()),
            method: "sparse Cholesky by domain (the separator last)",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::Triplets;

    /// The graph Laplacian of an `nx x ny` grid (5-point stencil) plus `shift` on the
    /// diagonal and 1 more on the nodes of the first column (a Dirichlet-like pin there).
    fn grid(nx: usize, ny: usize, shift: f64) -> SparseMatrix {
        let id = |i: usize, j: usize| (j * nx + i) as u32;
        let mut t = Triplets::default();
        for j in 0..ny {
            for i in 0..nx {
                let pin = if i == 0 { 1.0 } else { 0.0 };
                t.push(id(i, j), id(i, j), shift + pin);
                let mut link = |a: u32, b: u32| {
                    t.push(a, a, 1.0);
                    t.push(b, b, 1.0);
                    t.push(a, b, -1.0);
                    t.push(b, a, -1.0);
                };
                if i > 0 {
                    link(id(i, j), id(i - 1, j));
                }
                if j > 0 {
                    link(id(i, j), id(i, j - 1));
                }
            }
        }
        t.to_csr(nx * ny, nx * ny)
    }

    fn max_diff(a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    }

    fn mul(a: &SparseMatrix, x: &[f64]) -> Vec<f64> {
        a.outer_iterator()
            .map(|row| row.iter().map(|(c, v)| v * x[c]).sum())
            .collect()
    }

    /// Against the closed form: `A x` for a known `x`, solved back; the separator is the
    /// grid column right of the cut.
    #[test]
    fn solves_a_split_grid_to_round_off() {
        let (nx, ny, cut) = (23, 17, 9);
        let a = grid(nx, ny, 0.01);
        let second: Vec<bool> = (0..nx * ny).map(|k| k % nx >= cut).collect();
        let sep = SubstructuredCholesky::separator(&a, &second).unwrap();
        assert_eq!(sep, (0..ny).map(|j| j * nx + cut).collect::<Vec<_>>());
        let f = SubstructuredCholesky::try_new(&a, &second).unwrap();
        let x: Vec<f64> = (0..nx * ny)
            .map(|k| ((k * 7919) % 101) as f64 - 50.0)
            .collect();
        let b = mul(&a, &x);
        let y = f.solve(&b).unwrap();
        let err = max_diff(&x, &y);
        assert!(err < 1e-11, "error {err}");
        // Against the global factorisation.
        let g = CholeskyFactorization::try_new(&a)
            .unwrap()
            .solve(&b)
            .unwrap();
        let diff = max_diff(&g, &y);
        assert!(diff < 1e-11, "difference {diff}");
    }

    /// Two domains without coupling: an empty separator, solved per domain. An entry
    /// stored in one triangle only still puts its unknown in the separator; a new matrix
    /// that couples the domains elsewhere is refused by `refactor`.
    #[test]
    fn separators_empty_one_sided_and_changed() {
        let (nx, ny) = (8, 6);
        let a = grid(nx, ny, 1.0);
        let pick = |k: usize| k >= nx * ny / 2;
        // The two halves of the grid, decoupled: drop the entries between them.
        let mut t = Triplets::default();
        for (v, (i, j)) in a.iter() {
            if pick(i) == pick(j) {
                t.push(i as u32, j as u32, *v);
            }
        }
        let split = t.to_csr(nx * ny, nx * ny);
        let second: Vec<bool> = (0..nx * ny).map(pick).collect();
        let f = SubstructuredCholesky::try_new(&split, &second).unwrap();
        assert_eq!(f.separator_len(), 0);
        let x: Vec<f64> = (0..nx * ny).map(|k| k as f64).collect();
        let y = f.solve(&mul(&split, &x)).unwrap();
        let err = max_diff(&x, &y);
        assert!(err < 1e-11, "error {err}");
        // One entry (0, last) stored above the diagonal only.
        let mut t = Triplets::default();
        for (v, (i, j)) in split.iter() {
            t.push(i as u32, j as u32, *v);
        }
        t.push(0, (nx * ny - 1) as u32, -0.1);
        let one_sided = t.to_csr(nx * ny, nx * ny);
        let sep = SubstructuredCholesky::separator(&one_sided, &second).unwrap();
        assert_eq!(sep, vec![nx * ny - 1]);
        let mut f = f;
        assert!(matches!(
            f.refactor(&a),
            Err(SolverError::PatternMismatch(_))
        ));
    }

    /// A grid cut near its left side: whole columns of the larger right part move to the
    /// left until the two are within a column of each other, the separator stays one grid
    /// column, and the solve by the balanced split is exact. A balanced split is kept.
    #[test]
    fn balanced_split_moves_layers_to_the_smaller_domain() {
        let (nx, ny, cut) = (30, 12, 4);
        let a = grid(nx, ny, 0.0);
        let second: Vec<bool> = (0..nx * ny).map(|k| k % nx >= cut).collect();
        let split = SubstructuredCholesky::balanced_split(&a, &second).unwrap();
        let left = split.iter().filter(|&&b| !b).count();
        assert!(
            left.abs_diff(nx * ny - left) <= 2 * ny,
            "{left} of {}",
            nx * ny
        );
        // Whole columns moved: the split is by column.
        for k in 0..nx * ny {
            assert_eq!(split[k], split[k % nx], "unknown {k}");
        }
        let sep = SubstructuredCholesky::separator(&a, &split).unwrap();
        assert_eq!(sep.len(), ny);
        let again = SubstructuredCholesky::balanced_split(&a, &split).unwrap();
        assert_eq!(again, split);
        let f = SubstructuredCholesky::try_new(&a, &split).unwrap();
        let x: Vec<f64> = (0..nx * ny).map(|k| (k as f64 * 0.21).sin()).collect();
        let y = f.solve(&mul(&a, &x)).unwrap();
        assert!(max_diff(&x, &y) < 1e-10, "error {}", max_diff(&x, &y));
    }

    /// The second domain gives a layer of one unknown, behind which a layer of fifty would
    /// become the separator: that move is not made (the separator stays one unknown), while
    /// the same graph with the domains swapped moves the hub (the separator is then the hub
    /// itself, the last layer moved).
    #[test]
    fn balancing_keeps_the_separator_within_its_bound() {
        // A path 0..10 (first domain), a hub 10 joined to its end, and fifty leaves on the
        // hub: n = 61, bound 2 sqrt(61) = 15.6.
        let (path, leaves) = (10u32, 50u32);
        let n = (path + 1 + leaves) as usize;
        let mut t = Triplets::default();
        let mut link = |a: u32, b: u32| {
            for (i, j, v) in [(a, a, 1.0), (b, b, 1.0), (a, b, -1.0), (b, a, -1.0)] {
                t.push(i, j, v);
            }
        };
        for i in 1..=path {
            link(i - 1, i);
        }
        for l in 0..leaves {
            link(path, path + 1 + l);
        }
        for i in 0..n as u32 {
            t.push(i, i, 1.0);
        }
        let a = t.to_csr(n, n);
        let second: Vec<bool> = (0..n).map(|i| i >= path as usize).collect();
        let split = SubstructuredCholesky::balanced_split(&a, &second).unwrap();
        assert_eq!(split, second, "the hub stays");
        assert_eq!(
            SubstructuredCholesky::separator(&a, &split).unwrap(),
            vec![path as usize]
        );
        // Swapped: the first domain is the larger one and gives the hub.
        let swapped: Vec<bool> = second.iter().map(|b| !b).collect();
        let split = SubstructuredCholesky::balanced_split(&a, &swapped).unwrap();
        assert!(split[path as usize], "the hub moved");
        assert_eq!(
            SubstructuredCholesky::separator(&a, &split).unwrap(),
            vec![path as usize]
        );
    }

    /// Both of faer's factor layouts (simplicial on a small grid, supernodal on a larger
    /// one): the Schur complements read from the trailing blocks solve the system.
    #[test]
    fn reads_simplicial_and_supernodal_factors() {
        let mut seen = [false; 2];
        for (nx, ny) in [(6, 5), (160, 120)] {
            let a = grid(nx, ny, 0.0);
            let second: Vec<bool> = (0..nx * ny).map(|k| k % nx >= nx / 2).collect();
            let f = SubstructuredCholesky::try_new(&a, &second).unwrap();
            for d in &f.domains {
                seen[usize::from(d.factor.is_supernodal())] = true;
            }
            let x: Vec<f64> = (0..nx * ny).map(|k| (k as f64 * 0.1).sin()).collect();
            let y = f.solve(&mul(&a, &x)).unwrap();
            let err = max_diff(&x, &y);
            assert!(err < 1e-9, "{nx} x {ny}: error {err}");
        }
        assert_eq!(seen, [true, true], "both layouts met");
    }

    /// A new matrix of the same pattern: the refactored factors solve it, the old ones not.
    #[test]
    fn refactor_takes_new_values() {
        let (nx, ny, cut) = (12, 10, 5);
        let second: Vec<bool> = (0..nx * ny).map(|k| k % nx >= cut).collect();
        let mut f = SubstructuredCholesky::try_new(&grid(nx, ny, 0.0), &second).unwrap();
        let a = grid(nx, ny, 3.0);
        let x: Vec<f64> = (0..nx * ny).map(|k| (k as f64).sin()).collect();
        let b = mul(&a, &x);
        let stale = f.solve(&b).unwrap();
        assert!(x.iter().zip(&stale).any(|(a, b)| (a - b).abs() > 1e-3));
        f.refactor(&a).unwrap();
        let y = f.solve(&b).unwrap();
        let err = max_diff(&x, &y);
        assert!(err < 1e-12, "error {err}");
        assert!(f.refactor(&grid(nx, ny + 1, 0.0)).is_err());
    }

    /// A floating second domain (pinned only through the first: its own block plus the
    /// separator's is singular alone) is solved: only the principal submatrices with the
    /// separator must be definite, and they are whenever `A` is. An indefinite `A` is refused.
    #[test]
    fn definiteness_is_that_of_the_whole() {
        let (nx, ny, cut) = (10, 8, 4);
        let second: Vec<bool> = (0..nx * ny).map(|k| k % nx >= cut).collect();
        let a = grid(nx, ny, 0.0);
        let f = SubstructuredCholesky::try_new(&a, &second).unwrap();
        let x: Vec<f64> = (0..nx * ny).map(|k| (k as f64 * 0.37).cos()).collect();
        let y = f.solve(&mul(&a, &x)).unwrap();
        let err = max_diff(&x, &y);
        assert!(err < 1e-10, "error {err}");
        let bad = grid(nx, ny, -3.5);
        assert!(matches!(
            SubstructuredCholesky::try_new(&bad, &second),
            Err(SolverError::NotPositiveDefinite { .. })
        ));
        let wrong = vec![false; 3];
        assert!(matches!(
            SubstructuredCholesky::try_new(&grid(nx, ny, 0.0), &wrong),
            Err(SolverError::DimensionMismatch { .. })
        ));
    }
}
