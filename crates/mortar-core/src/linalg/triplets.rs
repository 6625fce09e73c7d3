use rayon::prelude::*;

use super::SparseMatrix;

/// One `(row, column, value)` entry.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Entry {
    row: u32,
    col: u32,
    val: f64,
}

/// `(row, column, value)` triplets, assembled into a CSR matrix with duplicates summed in a
/// fixed order: within a part in insertion order, then across parts in the order the parts
/// are given. The same parts give the same matrix bit for bit, whatever the thread count.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Triplets {
    entries: Vec<Entry>,
    /// Whether `entries` is sorted by (row, column) without duplicates.
    compressed: bool,
}

/// Rows per parallel work block when sorting rows.
const ROW_BLOCK: usize = 4096;

impl Triplets {
    /// Adds one entry.
    #[inline]
    pub fn push(&mut self, row: u32, col: u32, val: f64) {
        self.compressed = false;
        self.entries.push(Entry { row, col, val });
    }

    /// Number of triplets.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether there is no triplet.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Sums duplicate entries (in insertion order) and sorts by row, then column. Shrinks the
    /// list before it is kept: a slave face chunk's triplets repeat each (row, column) several
    /// times.
    pub fn compress(&mut self) {
        let Some(first) = self.entries.first() else {
            return;
        };
        let (lo, hi) = self
            .entries
            .iter()
            .fold((first.row, first.row), |(lo, hi), e| {
                (lo.min(e.row), hi.max(e.row))
            });
        let span = (hi - lo) as usize + 1;
        if span > 4 * self.entries.len() + 1024 {
            // Rows too scattered for a counting sort: a stable comparison sort keeps equal keys
            // in insertion order.
            self.entries
                .sort_by_key(|e| ((e.row as u64) << 32) | e.col as u64);
        } else {
            // Stable counting sort by row.
            let mut start = vec![0u32; span + 1];
            for e in &self.entries {
                start[(e.row - lo) as usize + 1] += 1;
            }
            for r in 0..span {
                start[r + 1] += start[r];
            }
            let mut sorted = vec![
                Entry {
                    row: 0,
                    col: 0,
                    val: 0.0
                };
                self.entries.len()
            ];
            for e in &self.entries {
                let at = &mut start[(e.row - lo) as usize];
                sorted[*at as usize] = *e;
                *at += 1;
            }
            // `start[r]` is now the end of row r; sort each row by column (stable).
            let mut a = 0usize;
            for &end in &start[..span] {
                let row = &mut sorted[a..end as usize];
                insertion_sort_by_col(row);
                a = end as usize;
            }
            self.entries = sorted;
        }
        let mut w = 0usize;
        for r in 0..self.entries.len() {
            let e = self.entries[r];
            if w > 0 && self.entries[w - 1].row == e.row && self.entries[w - 1].col == e.col {
                self.entries[w - 1].val += e.val;
            } else {
                self.entries[w] = e;
                w += 1;
            }
        }
        self.entries.truncate(w);
        self.entries.shrink_to_fit();
        self.compressed = true;
    }

    /// The `nrows x ncols` CSR matrix of all `parts`, duplicates summed (see the type's
    /// documentation for the order). Parts not yet compressed are compressed first. Rows are
    /// built in parallel blocks on the current rayon pool; each entry's sum is taken in the
    /// same order whatever the thread count.
    ///
    /// # Panics
    /// If an index is out of range.
    pub fn to_csr_from_parts(parts: &mut [Triplets], nrows: usize, ncols: usize) -> SparseMatrix {
        parts
            .par_iter_mut()
            .filter(|p| !p.compressed)
            .for_each(Triplets::compress);
        for p in parts.iter() {
            if let Some(e) = p
                .entries
                .iter()
                .find(|e| e.row as usize >= nrows || e.col as usize >= ncols)
            {
                panic!(
                    "entry ({}, {}) outside a {nrows}x{ncols} matrix",
                    e.row, e.col
                );
            }
        }
        let parts: &[Triplets] = parts;
        let blocks: Vec<(Vec<usize>, Vec<u32>, Vec<f64>)> = (0..nrows.div_ceil(ROW_BLOCK))
            .into_par_iter()
            .map(|b| {
                let (r0, r1) = (b * ROW_BLOCK, ((b + 1) * ROW_BLOCK).min(nrows));
                // This block's entries, part after part (each part sorted by row).
                let mut local: Vec<Entry> = Vec::new();
                for p in parts {
                    let e = &p.entries;
                    let a = e.partition_point(|x| (x.row as usize) < r0);
                    let z = e.partition_point(|x| (x.row as usize) < r1);
                    local.extend_from_slice(&e[a..z]);
                }
                // Stable counting sort by row, then per row a stable sort by column and the
                // sums in that order.
                let rows = r1 - r0;
                let mut start = vec![0usize; rows + 1];
                for e in &local {
                    start[e.row as usize - r0 + 1] += 1;
                }
                for r in 0..rows {
                    start[r + 1] += start[r];
                }
                let mut cols = vec![0u32; local.len()];
                let mut vals = vec![0.0f64; local.len()];
                let mut next = start.clone();
                for e in &local {
                    let at = &mut next[e.row as usize - r0];
                    cols[*at] = e.col;
                    vals[*at] = e.val;
                    *at += 1;
                }
                drop(local);
                let mut lens = Vec::with_capacity(rows);
                let mut w = 0usize;
                for r in 0..rows {
                    let (a, z) = (start[r], start[r + 1]);
                    let len = merge_row(&mut cols[a..z], &mut vals[a..z]);
                    cols.copy_within(a..a + len, w);
                    vals.copy_within(a..a + len, w);
                    w += len;
                    lens.push(len);
                }
                cols.truncate(w);
                vals.truncate(w);
                (lens, cols, vals)
            })
            .collect();
        let nnz: usize = blocks.iter().map(|b| b.1.len()).sum();
        let mut indptr = Vec::with_capacity(nrows + 1);
        indptr.push(0usize);
        let mut indices = Vec::with_capacity(nnz);
        let mut data = Vec::with_capacity(nnz);
        for (lens, cols, vals) in blocks {
            for len in lens {
                indptr.push(indptr[indptr.len() - 1] + len);
            }
            indices.extend(cols.iter().map(|&c| c as usize));
            data.extend_from_slice(&vals);
        }
        SparseMatrix::new((nrows, ncols), indptr, indices, data)
    }

    /// The `nrows x ncols` CSR matrix of these triplets.
    ///
    /// # Panics
    /// If an index is out of range.
    pub fn to_csr(self, nrows: usize, ncols: usize) -> SparseMatrix {
        Self::to_csr_from_parts(&mut [self], nrows, ncols)
    }
}

/// Stable sort of one row's entries by column (insertion sort for short rows).
fn insertion_sort_by_col(row: &mut [Entry]) {
    if row.len() > 32 {
        row.sort_by_key(|e| e.col);
        return;
    }
    for i in 1..row.len() {
        let e = row[i];
        let mut j = i;
        while j > 0 && row[j - 1].col > e.col {
            row[j] = row[j - 1];
            j -= 1;
        }
        row[j] = e;
    }
}

/// Sorts one row by column (stable insertion sort: rows are short) and sums duplicates in
/// order; returns the merged length.
fn merge_row(cols: &mut [u32], vals: &mut [f64]) -> usize {
    if cols.len() > 32 {
        let mut pairs: Vec<(u32, f64)> = cols.iter().copied().zip(vals.iter().copied()).collect();
        pairs.sort_by_key(|p| p.0);
        for (i, (c, v)) in pairs.into_iter().enumerate() {
            cols[i] = c;
            vals[i] = v;
        }
    }
    for i in 1..cols.len() {
        let (c, v) = (cols[i], vals[i]);
        let mut j = i;
        while j > 0 && cols[j - 1] > c {
            cols[j] = cols[j - 1];
            vals[j] = vals[j - 1];
            j -= 1;
        }
        cols[j] = c;
        vals[j] = v;
    }
    let mut w = 0usize;
    for r in 0..cols.len() {
        if w > 0 && cols[w - 1] == cols[r] {
            vals[w - 1] += vals[r];
        } else {
            cols[w] = cols[r];
            vals[w] = vals[r];
            w += 1;
        }
    }
    w
}
