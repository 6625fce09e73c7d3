use rayon::prelude::*;
use rustc_hash::FxHashMap;

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

/// Reusable sort buffers for compressing triplets.
#[derive(Debug, Clone, Default)]
pub struct CompressWorkspace {
    sorted: Vec<Entry>,
    start: Vec<u32>,
}

/// Rows per parallel work block when building the CSR arrays.
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

    /// Removes every triplet, keeping the allocation.
    pub fn clear(&mut self) {
        self.entries.clear();
    }

    /// Whether there is no triplet.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Sorts the triplets by row, then column, and sums duplicates in insertion order,
    /// appending the result to `out`; empties `self` (keeping its allocation).
    fn compress_into(&mut self, ws: &mut CompressWorkspace, out: &mut Vec<Entry>) {
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
        let sorted = &mut ws.sorted;
        sorted.clear();
        if span > 4 * self.entries.len() + 1024 {
            // Rows too scattered for a counting sort: a stable comparison sort keeps equal keys
            // in insertion order.
            sorted.extend_from_slice(&self.entries);
            sorted.sort_by_key(|e| ((e.row as u64) << 32) | e.col as u64);
        } else {
            // Stable counting sort by row, then a stable sort of each row by column.
            let start = &mut ws.start;
            start.clear();
            start.resize(span + 1, 0);
            for e in &self.entries {
                start[(e.row - lo) as usize + 1] += 1;
            }
            for r in 0..span {
                start[r + 1] += start[r];
            }
            sorted.resize(
                self.entries.len(),
                Entry {
                    row: 0,
                    col: 0,
                    val: 0.0,
                },
            );
            for e in &self.entries {
                let at = &mut start[(e.row - lo) as usize];
                sorted[*at as usize] = *e;
                *at += 1;
            }
            // `start[r]` is now the end of row r.
            let mut a = 0usize;
            for &end in &start[..span] {
                insertion_sort_by_col(&mut sorted[a..end as usize]);
                a = end as usize;
            }
        }
        self.entries.clear();
        let base = out.len();
        for e in sorted.iter() {
            push_merged(out, base, *e);
        }
    }

    /// The `nrows x ncols` CSR matrix of all `parts`, duplicates summed (see the type's
    /// documentation for the order). Rows are built in parallel blocks on the current rayon
    /// pool; each entry's sum is taken in the same order whatever the thread count.
    ///
    /// # Panics
    /// If an index is out of range.
    pub fn to_csr_from_parts(parts: Vec<Triplets>, nrows: usize, ncols: usize) -> SparseMatrix {
        let mut list = PartList::default();
        let mut ws = CompressWorkspace::default();
        for (k, mut p) in parts.into_iter().enumerate() {
            list.push_compressed(k as u64, &mut p, &mut ws);
        }
        list.to_csr(nrows, ncols)
    }

    /// The `nrows x ncols` CSR matrix of these triplets.
    ///
    /// # Panics
    /// If an index is out of range.
    pub fn to_csr(self, nrows: usize, ncols: usize) -> SparseMatrix {
        Self::to_csr_from_parts(vec![self], nrows, ncols)
    }
}

/// The triplets of one part summed as they come, row by row: what
/// [`PartList::push_compressed`] makes of the same triplets (rows ascending, columns
/// ascending within a row, duplicates summed in insertion order), bit for bit, without
/// storing and sorting them. A triplet finds its row through a hash map, skipped when it is
/// in the same row as the one before (push a face's entries row by row), and its column by a
/// linear search of the row's columns so far while the row has at most [`Self::LINEAR`] of
/// them (a slave node's row meets a few dozen columns in a chunk of faces). A longer row (a
/// coarse slave face against a million master faces, where the search would be quadratic in
/// the row's length) takes its further entries as they come, and they are merged when the
/// part is stored: a stable sort by column and the sums in insertion order, as
/// [`PartList::push_compressed`] does.
#[derive(Debug, Clone, Default)]
pub struct RowAccumulator {
    /// The slot in `rows` of each row touched.
    slot_of_row: FxHashMap<u32, usize>,
    /// The row of the last push, and its slot.
    last: Option<(u32, usize)>,
    /// The rows touched, in the order first touched.
    rows: Vec<u32>,
    /// Per slot, the row's `(column, sum)` entries in the order first met (the vectors are
    /// kept from part to part, so that accumulating allocates nothing once they have grown).
    entries: Vec<Vec<(u32, f64)>>,
    /// Per slot, whether the row outgrew the linear search (its entries after the first
    /// [`Self::LINEAR`] are unmerged).
    long: Vec<bool>,
    /// Comparisons and lookups made by the column searches (tests check that they stay
    /// linear in the pushes).
    #[cfg(test)]
    probes: u64,
}

impl RowAccumulator {
    /// Adds `val` to the entry `(row, col)`.
    #[inline]
    pub fn push(&mut self, row: u32, col: u32, val: f64) {
        let slot = self.slot_of(row);
        self.add(slot, col, val);
    }

    /// Adds each `(col, val)` of `entries` to the entry `(row, col)`, in order: what
    /// [`push`](Self::push) of each does, with the row looked up once.
    #[inline]
    pub fn push_row(&mut self, row: u32, entries: impl IntoIterator<Item = (u32, f64)>) {
        let slot = self.slot_of(row);
        for (col, val) in entries {
            self.add(slot, col, val);
        }
    }

    /// The slot of `row`, opened if it is new.
    #[inline]
    fn slot_of(&mut self, row: u32) -> usize {
        match self.last {
            Some((r, slot)) if r == row => slot,
            _ => {
                let next = self.rows.len();
                let slot = *self.slot_of_row.entry(row).or_insert(next);
                if slot == next {
                    self.rows.push(row);
                    if self.entries.len() == next {
                        self.entries.push(Vec::new());
                        self.long.push(false);
                    }
                    self.entries[slot].clear();
                    self.long[slot] = false;
                }
                self.last = Some((row, slot));
                slot
            }
        }
    }

    /// Adds `val` to the column `col` of the row in `slot`.
    #[inline]
    fn add(&mut self, slot: usize, col: u32, val: f64) {
        let row_entries = &mut self.entries[slot];
        if self.long[slot] {
            row_entries.push((col, val));
            return;
        }
        #[cfg(test)]
        {
            self.probes += row_entries.len() as u64;
        }
        match row_entries.iter_mut().find(|(c, _)| *c == col) {
            Some((_, v)) => *v += val,
            None => {
                row_entries.push((col, val));
                self.long[slot] = row_entries.len() > Self::LINEAR;
            }
        }
    }

    /// Columns of a row searched linearly.
    pub const LINEAR: usize = 32;

    /// Forgets every entry (keeping the allocations).
    pub fn clear(&mut self) {
        self.slot_of_row.clear();
        self.last = None;
        self.rows.clear();
    }

    /// Whether no entry was pushed since the last clear.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }
}

/// Appends `e` to `out`, or adds it to the last entry if that has the same row and column and
/// lies at or after `base` (merges stay within one part: `out` may hold earlier parts).
#[inline]
fn push_merged(out: &mut Vec<Entry>, base: usize, e: Entry) {
    let n = out.len();
    if n > base && out[n - 1].row == e.row && out[n - 1].col == e.col {
        out[n - 1].val += e.val;
    } else {
        out.push(e);
    }
}

/// Compressed triplet parts, each with a key, stored back to back in a few large buffers.
///
/// Parallel assembly gives each worker one `PartList` and merges the lists at the end; the
/// matrix is then built from the parts in key order, so it does not depend on which worker
/// built which part. A few large buffers, rather than one small allocation per part, keep
/// the allocator from fragmenting and go back to the system as soon as they are dropped.
#[derive(Debug, Clone, Default)]
pub struct PartList {
    buffers: Vec<Vec<Entry>>,
    /// `(key, buffer, start, end)`.
    parts: Vec<(u64, u32, usize, usize)>,
}

impl PartList {
    /// Compresses `raw` (emptying it, keeping its allocation) and stores it as part `key`.
    pub fn push_compressed(&mut self, key: u64, raw: &mut Triplets, ws: &mut CompressWorkspace) {
        self.push_part(key, |buf| raw.compress_into(ws, buf));
    }

    /// Stores as part `key` the entries `fill` appends to the last buffer.
    fn push_part(&mut self, key: u64, fill: impl FnOnce(&mut Vec<Entry>)) {
        if self.buffers.is_empty() {
            self.buffers.push(Vec::new());
        }
        let b = self.buffers.len() - 1;
        let buf = &mut self.buffers[b];
        let start = buf.len();
        fill(buf);
        self.parts.push((key, b as u32, start, buf.len()));
    }

    /// Stores the entries of `acc` as part `key` (rows ascending, columns ascending within a
    /// row) and clears `acc`.
    pub fn push_rows(&mut self, key: u64, acc: &mut RowAccumulator) {
        let mut order: Vec<(u32, usize)> = acc.rows.iter().copied().zip(0..).collect();
        order.sort_unstable();
        self.push_part(key, |buf| {
            for (row, slot) in order {
                let entries = &mut acc.entries[slot];
                if acc.long[slot] {
                    // Columns may repeat: a stable sort keeps them in insertion order, and
                    // they are summed in that order.
                    entries.sort_by_key(|e| e.0);
                    let base = buf.len();
                    for &(col, val) in entries.iter() {
                        push_merged(buf, base, Entry { row, col, val });
                    }
                } else {
                    // Each column once in a row: any sort gives the same order.
                    entries.sort_unstable_by_key(|e| e.0);
                    buf.extend(entries.iter().map(|&(col, val)| Entry { row, col, val }));
                }
            }
        });
        acc.clear();
    }

    /// Moves the parts of `other` into this list.
    pub fn append(&mut self, other: PartList) {
        let shift = self.buffers.len() as u32;
        self.buffers.extend(other.buffers);
        self.parts.extend(
            other
                .parts
                .into_iter()
                .map(|(k, b, s, e)| (k, b + shift, s, e)),
        );
    }

    /// Number of stored triplets.
    pub fn len(&self) -> usize {
        self.parts.iter().map(|p| p.3 - p.2).sum()
    }

    /// Whether no triplet is stored.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The `nrows x ncols` CSR matrix of the parts in key order, duplicates summed in that
    /// order. The parts are freed before the matrix arrays are filled.
    ///
    /// # Panics
    /// If an index is out of range, or two parts have the same key.
    pub fn to_csr(mut self, nrows: usize, ncols: usize) -> SparseMatrix {
        self.parts.sort_unstable_by_key(|p| p.0);
        assert!(
            self.parts.windows(2).all(|w| w[0].0 != w[1].0),
            "two triplet parts with the same key"
        );
        let blocks = {
            let slices: Vec<&[Entry]> = self
                .parts
                .iter()
                .map(|&(_, b, s, e)| &self.buffers[b as usize][s..e])
                .collect();
            for sl in &slices {
                if let Some(e) = sl
                    .iter()
                    .find(|e| e.row as usize >= nrows || e.col as usize >= ncols)
                {
                    panic!(
                        "entry ({}, {}) outside a {nrows}x{ncols} matrix",
                        e.row, e.col
                    );
                }
            }
            row_blocks(&slices, nrows)
        };
        drop(self);
        concat_blocks(blocks, nrows, ncols)
    }
}

/// Rows of one block of the matrix: merged row lengths, columns, values.
type RowBlock = (Vec<usize>, Vec<u32>, Vec<f64>);

/// Per-thread buffers of the row blocks.
#[derive(Default)]
struct BlockWorkspace {
    local: Vec<Entry>,
    start: Vec<usize>,
    next: Vec<usize>,
    cols: Vec<u32>,
    vals: Vec<f64>,
}

/// Merges the row-sorted `slices` into blocks of [`ROW_BLOCK`] rows, in parallel; within a
/// row, entries are summed in slice order, then in their order within a slice.
fn row_blocks(slices: &[&[Entry]], nrows: usize) -> Vec<RowBlock> {
    (0..nrows.div_ceil(ROW_BLOCK))
        .into_par_iter()
        .map_init(BlockWorkspace::default, |ws, b| {
            let (r0, r1) = (b * ROW_BLOCK, ((b + 1) * ROW_BLOCK).min(nrows));
            // This block's entries, slice after slice (each sorted by row).
            ws.local.clear();
            for e in slices {
                // Most slices (the entries of a chunk of cells) lie in a few rows: skip those
                // outside the block without searching them.
                match (e.first(), e.last()) {
                    (Some(f), Some(l)) if (l.row as usize) >= r0 && (f.row as usize) < r1 => {}
                    _ => continue,
                }
                let a = e.partition_point(|x| (x.row as usize) < r0);
                let z = e.partition_point(|x| (x.row as usize) < r1);
                ws.local.extend_from_slice(&e[a..z]);
            }
            // Stable counting sort by row, then per row a stable sort by column and the sums
            // in that order.
            let rows = r1 - r0;
            ws.start.clear();
            ws.start.resize(rows + 1, 0);
            for e in &ws.local {
                ws.start[e.row as usize - r0 + 1] += 1;
            }
            for r in 0..rows {
                ws.start[r + 1] += ws.start[r];
            }
            ws.cols.clear();
            ws.cols.resize(ws.local.len(), 0);
            ws.vals.clear();
            ws.vals.resize(ws.local.len(), 0.0);
            ws.next.clear();
            ws.next.extend_from_slice(&ws.start);
            for e in &ws.local {
                let at = &mut ws.next[e.row as usize - r0];
                ws.cols[*at] = e.col;
                ws.vals[*at] = e.val;
                *at += 1;
            }
            let mut lens = Vec::with_capacity(rows);
            let mut w = 0usize;
            for r in 0..rows {
                let (a, z) = (ws.start[r], ws.start[r + 1]);
                let len = merge_row(&mut ws.cols[a..z], &mut ws.vals[a..z]);
                ws.cols.copy_within(a..a + len, w);
                ws.vals.copy_within(a..a + len, w);
                w += len;
                lens.push(len);
            }
            (lens, ws.cols[..w].to_vec(), ws.vals[..w].to_vec())
        })
        .collect()
}

/// Concatenates the row blocks into the CSR arrays, in parallel (each block into its own
/// range of the arrays), freeing each block once copied.
fn concat_blocks(blocks: Vec<RowBlock>, nrows: usize, ncols: usize) -> SparseMatrix {
    let nnz: usize = blocks.iter().map(|b| b.1.len()).sum();
    let mut indptr = Vec::with_capacity(nrows + 1);
    indptr.push(0usize);
    for (lens, _, _) in &blocks {
        for len in lens {
            indptr.push(indptr[indptr.len() - 1] + len);
        }
    }
    let mut indices = vec![0usize; nnz];
    let mut data = vec![0.0; nnz];
    let mut targets = Vec::with_capacity(blocks.len());
    let (mut rest_i, mut rest_d) = (&mut indices[..], &mut data[..]);
    for (_, cols, _) in &blocks {
        let (head_i, tail_i) = rest_i.split_at_mut(cols.len());
        let (head_d, tail_d) = rest_d.split_at_mut(cols.len());
        targets.push((head_i, head_d));
        (rest_i, rest_d) = (tail_i, tail_d);
    }
    blocks
        .into_par_iter()
        .zip(targets)
        .for_each(|((_, cols, vals), (to_i, to_d))| {
            for (t, &c) in to_i.iter_mut().zip(&cols) {
                *t = c as usize;
            }
            to_d.copy_from_slice(&vals);
        });
    SparseMatrix::new((nrows, ncols), indptr, indices, data)
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

/// Sorts one row by column (stable) and sums duplicates in order; returns the merged length.
fn merge_row(cols: &mut [u32], vals: &mut [f64]) -> usize {
    if cols.len() > 32 {
        let mut pairs: Vec<(u32, f64)> = cols.iter().copied().zip(vals.iter().copied()).collect();
        pairs.sort_by_key(|p| p.0);
        for (i, (c, v)) in pairs.into_iter().enumerate() {
            cols[i] = c;
            vals[i] = v;
        }
    } else {
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The rows of a [`RowAccumulator`] (fed by `push` or by `push_row`) are bit for bit
        /// the part that [`PartList::push_compressed`] makes of the same triplets (rows and
        /// columns ascending, duplicates summed in insertion order), over two parts in a row (the
        /// accumulator reused), whatever the values' magnitudes (so that the order of
        /// summation shows in the bits); rows of up to 60 columns, so that some outgrow the
        /// linear search and merge their repeated columns when stored.
        #[test]
        fn accumulated_rows_are_the_compressed_triplets(
            parts in prop::collection::vec(
                prop::collection::vec((0u32..8, 0u32..60, -1e3..1e3f64, -8i32..8), 0..400),
                1..3,
            ),
        ) {
            let (mut sorted, mut summed) = (PartList::default(), PartList::default());
            let mut by_rows = PartList::default();
            let (mut ws, mut acc) = (CompressWorkspace::default(), RowAccumulator::default());
            let mut row_acc = RowAccumulator::default();
            for (k, part) in parts.iter().enumerate() {
                let mut raw = Triplets::default();
                let scaled: Vec<(u32, u32, f64)> = part
                    .iter()
                    .map(|&(r, c, v, e)| (r, c, v * 2f64.powi(6 * e)))
                    .collect();
                for &(r, c, v) in &scaled {
                    raw.push(r, c, v);
                    acc.push(r, c, v);
                }
                // The same triplets through push_row, a run of equal rows at a time.
                for run in scaled.chunk_by(|a, b| a.0 == b.0) {
                    row_acc.push_row(run[0].0, run.iter().map(|&(_, c, v)| (c, v)));
                }
                sorted.push_compressed(k as u64, &mut raw, &mut ws);
                summed.push_rows(k as u64, &mut acc);
                by_rows.push_rows(k as u64, &mut row_acc);
                prop_assert!(acc.is_empty());
            }
            let bits = |l: &PartList| -> Vec<(u64, u32, u32, u64)> {
                l.parts
                    .iter()
                    .flat_map(|&(k, b, s, e)| {
                        l.buffers[b as usize][s..e]
                            .iter()
                            .map(move |x| (k, x.row, x.col, x.val.to_bits()))
                    })
                    .collect()
            };
            prop_assert_eq!(bits(&sorted), bits(&summed));
            prop_assert_eq!(bits(&sorted), bits(&by_rows));
        }
    }

    /// Regression: a row of many columns (one coarse slave face against 20,000 master faces)
    /// made the accumulator's linear column search quadratic (2e8 comparisons here, seconds
    /// for 1e5 columns); the searches now stay within a few probes per push, and the part is
    /// still the sorted triplets'.
    #[test]
    fn long_rows_stay_linear() {
        let n = 20_000u32;
        let (mut acc, mut raw) = (RowAccumulator::default(), Triplets::default());
        for pass in 0..2 {
            for row in 0..2 {
                for k in 0..n {
                    let col = (k * 7919) % n;
                    let val = f64::from(k + pass) * 0.5;
                    acc.push(row, col, val);
                    raw.push(row, col, val);
                }
            }
        }
        let pushes = 4 * u64::from(n);
        assert!(acc.probes <= 2 * pushes, "{} probes", acc.probes);
        let (mut a, mut b) = (PartList::default(), PartList::default());
        a.push_rows(0, &mut acc);
        b.push_compressed(0, &mut raw, &mut CompressWorkspace::default());
        assert_eq!(a.parts, b.parts);
        assert_eq!(a.buffers, b.buffers);
    }
}
