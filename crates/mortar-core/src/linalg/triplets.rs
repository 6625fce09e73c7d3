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
}

/// Rows per parallel work block when sorting rows.
const ROW_BLOCK: usize = 4096;

impl Triplets {
    /// Adds one entry.
    #[inline]
    pub fn push(&mut self, row: u32, col: u32, val: f64) {
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
    }

    /// The `nrows x ncols` CSR matrix of all `parts`, duplicates summed (see the type's
    /// documentation for the order).
    ///
    /// # Panics
    /// If an index is out of range.
    pub fn to_csr_from_parts(parts: &[Triplets], nrows: usize, ncols: usize) -> SparseMatrix {
        // 1. Stable counting sort by row: entries of one row keep part order, then insertion
        //    order.
        let mut indptr = vec![0usize; nrows + 1];
        for p in parts {
            for e in &p.entries {
                indptr[e.row as usize + 1] += 1;
            }
        }
        for r in 0..nrows {
            indptr[r + 1] += indptr[r];
        }
        let total = indptr[nrows];
        let mut cols = vec![0u32; total];
        let mut vals = vec![0.0f64; total];
        let mut next = indptr.clone();
        for p in parts {
            for e in &p.entries {
                assert!((e.col as usize) < ncols, "column {} out of range", e.col);
                let at = &mut next[e.row as usize];
                cols[*at] = e.col;
                vals[*at] = e.val;
                *at += 1;
            }
        }
        drop(next);

        // 2. Per row: stable sort by column and sum duplicates in order; rows in parallel
        //    blocks (each row is summed by one thread, in a fixed order).
        let mut blocks = Vec::new();
        {
            let (mut c_rest, mut v_rest) = (&mut cols[..], &mut vals[..]);
            let mut start = 0usize;
            while start < nrows {
                let end = (start + ROW_BLOCK).min(nrows);
                let len = indptr[end] - indptr[start];
                let (c, cr) = c_rest.split_at_mut(len);
                let (v, vr) = v_rest.split_at_mut(len);
                blocks.push((start..end, c, v));
                c_rest = cr;
                v_rest = vr;
                start = end;
            }
        }
        let merged: Vec<Vec<usize>> = blocks
            .into_par_iter()
            .map(|(rows, c, v)| {
                let base = indptr[rows.start];
                let mut lens = Vec::with_capacity(rows.len());
                for r in rows {
                    let (a, b) = (indptr[r] - base, indptr[r + 1] - base);
                    lens.push(merge_row(&mut c[a..b], &mut v[a..b]));
                }
                lens
            })
            .collect();

        // 3. Compact the merged rows.
        let mut out_ptr = Vec::with_capacity(nrows + 1);
        out_ptr.push(0usize);
        let mut indices = Vec::new();
        let mut data = Vec::new();
        let mut r = 0usize;
        for lens in &merged {
            for &len in lens {
                let a = indptr[r];
                indices.extend(cols[a..a + len].iter().map(|&c| c as usize));
                data.extend_from_slice(&vals[a..a + len]);
                out_ptr.push(indices.len());
                r += 1;
            }
        }
        SparseMatrix::new((nrows, ncols), out_ptr, indices, data)
    }

    /// The `nrows x ncols` CSR matrix of these triplets.
    ///
    /// # Panics
    /// If an index is out of range.
    pub fn to_csr(self, nrows: usize, ncols: usize) -> SparseMatrix {
        Self::to_csr_from_parts(std::slice::from_ref(&self), nrows, ncols)
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
