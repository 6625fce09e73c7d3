//! CSR matrices from arrays the toolkit filled itself, their structure checked in parallel.
//!
//! `sprs::CsMat::new` checks a matrix's structure in one pass on one thread: at 10^6 rows,
//! 1.5 % of a two-thread coupling of 10^6 lines (a profile of arc2d), 6.2 ms of a 141 ms
//! two-thread call on line2d. The assembly writes its arrays row block by
//! row block in parallel, so it checks them the same way: every check `CsMat::new` makes,
//! each block on its own thread, then the matrix built unchecked. A structure that fails
//! goes to `CsMat::new`, which says what is wrong.

use rayon::prelude::*;

use super::SparseMatrix;

/// Rows per parallel task of [`rows_are_sound`].
const CHECK_ROWS: usize = 1 << 14;

/// Whether the rows `rows` of the CSR arrays `(indptr, indices)` are sound: each row's range
/// `indptr[r]..indptr[r + 1]` ascending and within `indices`, its columns strictly ascending
/// and below `ncols`. `indptr` must have an entry after the last row of `rows`.
fn rows_in_range_are_sound(
    rows: std::ops::Range<usize>,
    indptr: &[usize],
    indices: &[usize],
    ncols: usize,
) -> bool {
    rows.into_iter().all(|r| {
        let (a, z) = (indptr[r], indptr[r + 1]);
        a <= z
            && z <= indices.len()
            && indices[a..z].windows(2).all(|w| w[0] < w[1])
            && indices[a..z].last().is_none_or(|&c| c < ncols)
    })
}

/// Whether every row of the CSR arrays `(indptr, indices)` with `ncols` columns is sound (as
/// [`rows_in_range_are_sound`]), checked in parallel over blocks of rows; `false` if
/// `indptr` is empty.
fn rows_are_sound(indptr: &[usize], indices: &[usize], ncols: usize) -> bool {
    let Some(nrows) = indptr.len().checked_sub(1) else {
        return false;
    };
    (0..nrows.div_ceil(CHECK_ROWS)).into_par_iter().all(|b| {
        let rows = b * CHECK_ROWS..((b + 1) * CHECK_ROWS).min(nrows);
        rows_in_range_are_sound(rows, indptr, indices, ncols)
    })
}

/// The `shape` CSR matrix of `(indptr, indices, data)`, whose rows the caller has found
/// sound (`rows_sound`: every row's columns strictly ascending and below the column count,
/// `indptr` non-decreasing): the rest of `CsMat::new`'s checks (O(1)) made here, the matrix
/// then built without its serial pass. Anything unsound goes to `CsMat::new`, which panics
/// with its reason.
pub(crate) fn csr_of_sound_rows(
    shape: (usize, usize),
    indptr: Vec<usize>,
    indices: Vec<usize>,
    data: Vec<f64>,
    rows_sound: bool,
) -> SparseMatrix {
    let (nrows, _) = shape;
    let nnz = indices.len();
    if !rows_sound
        || indptr.len() != nrows + 1
        || indptr[0] != 0
        || indptr[nrows] != nnz
        || data.len() != nnz
    {
        // sprs says what is wrong.
        return SparseMatrix::new(shape, indptr, indices, data);
    }
    // SAFETY: the structure is what `CsMat::new` checks before it calls this: `indptr` has
    // `nrows + 1` entries, starts at 0 and ends at `nnz`, the length of `indices` and `data`
    // (checked here); it never decreases, and every row's columns are strictly ascending and
    // below the column count (checked by the caller: `rows_sound`). The indices are `usize`,
    // so every count fits them.
    #[allow(unsafe_code)]
    unsafe {
        SparseMatrix::new_unchecked(sprs::CompressedStorage::CSR, shape, indptr, indices, data)
    }
}

/// The `shape` CSR matrix of `(indptr, indices, data)`, checked as `CsMat::new` checks it
/// but in parallel over blocks of rows.
///
/// # Panics
/// As `CsMat::new`, if the structure is not that of a CSR matrix of `shape`.
pub(crate) fn csr_checked_in_parallel(
    shape: (usize, usize),
    indptr: Vec<usize>,
    indices: Vec<usize>,
    data: Vec<f64>,
) -> SparseMatrix {
    let sound = rows_are_sound(&indptr, &indices, shape.1);
    csr_of_sound_rows(shape, indptr, indices, data, sound)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Random CSR arrays of up to 3 * CHECK_ROWS rows (several parallel blocks), some of
    /// them broken in one place: the parallel check accepts exactly what sprs's own check
    /// accepts, and a sound matrix is the same as `CsMat::new`'s.
    #[test]
    fn the_parallel_check_accepts_what_sprs_accepts() {
        // 48 cases, or as many as `PROPTEST_CASES` says, as in the other property tests.
        let cases = std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(48);
        let mut runner = proptest::test_runner::TestRunner::new(ProptestConfig {
            cases,
            ..ProptestConfig::default()
        });
        let strategy = (1usize..3 * CHECK_ROWS, 1usize..50, any::<u64>(), 0usize..6);
        runner
            .run(&strategy, |(nrows, ncols, seed, fault)| {
                // A simple generator of rows: each row a few ascending columns.
                let mut state = seed | 1;
                let mut next = || {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    state
                };
                let mut indptr = vec![0usize];
                let mut indices = Vec::new();
                for _ in 0..nrows {
                    let mut c = (next() % 3) as usize;
                    while c < ncols && next() % 4 != 0 {
                        indices.push(c);
                        c += 1 + (next() % 3) as usize;
                    }
                    indptr.push(indices.len());
                }
                let nnz = indices.len();
                let pick = |k: u64, n: usize| (k % n.max(1) as u64) as usize;
                let r = next();
                match fault {
                    // A column repeated.
                    1 if nnz > 1 => {
                        let i = 1 + pick(r, nnz - 1);
                        indices[i] = indices[i - 1];
                    }
                    // A column out of range.
                    2 if nnz > 0 => indices[pick(r, nnz)] = ncols,
                    // A row pointer that goes down.
                    3 if nrows > 1 => {
                        let i = 1 + pick(r, nrows - 1);
                        indptr[i] = indptr[i + 1] + 1;
                    }
                    // The last row pointer short of nnz.
                    4 if nnz > 0 => indptr[nrows] = nnz - 1,
                    // Fewer row pointers.
                    5 => {
                        indptr.pop();
                    }
                    _ => {}
                }
                let data: Vec<f64> = (0..indices.len()).map(|i| i as f64 + 0.5).collect();
                let shape = (nrows, ncols);
                let theirs =
                    SparseMatrix::try_new(shape, indptr.clone(), indices.clone(), data.clone());
                let ours = std::panic::catch_unwind(|| {
                    csr_checked_in_parallel(shape, indptr.clone(), indices.clone(), data.clone())
                });
                match (theirs, ours) {
                    (Ok(m), Ok(p)) => prop_assert_eq!(m, p),
                    (Err(_), Err(_)) => {}
                    (t, o) => prop_assert!(
                        false,
                        "sprs {:?}, ours {:?} (fault {})",
                        t.is_ok(),
                        o.is_ok(),
                        fault
                    ),
                }
                Ok(())
            })
            .unwrap();
    }
}
