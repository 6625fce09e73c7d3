//! Sparse assembly in a fixed summation order: `Triplets` and `RowAccumulator` gather
//! `(row, column, value)` entries and build CSR matrices that are the same bit for bit
//! whatever the thread count.

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

    /// Renumbers the row of every triplet by `f` (several rows mapped to one are summed
    /// there, in insertion order, when the matrix is built).
    pub fn map_rows(&mut self, f: impl Fn(u32) -> u32) {
        for e in &mut self.entries {
            e.row = f(e.row);
        }
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
    /// appending the result to `out` as a part that starts at `run0` (its first run);
    /// empties `self` (keeping its allocation).
    fn compress_into(&mut self, ws: &mut CompressWorkspace, out: &mut RunBuffer, run0: usize) {
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
                sort_short_by_key(&mut sorted[a..end as usize], |e| e.col);
                a = end as usize;
            }
        }
        self.entries.clear();
        for e in sorted.iter() {
            out.push_merged(run0, e.row, e.col, e.val);
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
/// in the same row as the one before (push a face's entries row by row). A row then goes
/// through up to three states as it grows:
/// - up to [`Self::SHORT`] columns, each pushed column is searched for linearly among the
///   row's (in the order first met; sorted when the part is stored);
/// - beyond that, up to [`Self::LINEAR`] columns (a slave node's row of M in 3D meets a few
///   dozen in a chunk of faces), the row's columns are kept ascending and a push of several
///   entries ([`push_row`](Self::push_row), sorted by column first if they are not) is
///   merged into it in one walk over both: `L + K` steps for a push of `K` into a row of
///   `L`, where the search took about `L * K / 2`;
/// - beyond that (a coarse slave face against a million master faces, where even a walk per
///   push would be quadratic in the row's length) the row takes its further entries as they
///   come, and they are merged when the part is stored: a stable sort by column and the sums
///   in insertion order, as [`PartList::push_compressed`] does.
///
/// Each entry's value is the sum of the values pushed to it, left to right in the order
/// pushed, whatever the state of the row and the order of the columns within a push: the
/// first value as it is, the next ones added to it.
#[derive(Debug, Clone, Default)]
pub struct RowAccumulator {
    /// The slot in `rows` of each row touched.
    slot_of_row: FxHashMap<u32, usize>,
    /// The row of the last push, and its slot.
    last: Option<(u32, usize)>,
    /// The rows touched, in the order first touched.
    rows: Vec<u32>,
    /// Per slot, the row's `(column, sum)` entries (the vectors are kept from part to part,
    /// so that accumulating allocates nothing once they have grown).
    entries: Vec<Vec<(u32, f64)>>,
    /// Per slot, the row's state.
    state: Vec<RowState>,
    /// The entries of the push being merged, sorted by column.
    incoming: Vec<(u32, f64)>,
    /// Those of its columns the row does not have yet, each once.
    fresh: Vec<(u32, f64)>,
    /// Comparisons made by the searches and steps taken by the merges (tests check that they
    /// stay linear in the pushes).
    #[cfg(test)]
    probes: u64,
}

/// How a [`RowAccumulator`] row takes its entries.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
enum RowState {
    /// Columns in the order first met, searched linearly.
    #[default]
    Short,
    /// Columns ascending, pushes merged in.
    Sorted,
    /// Sorted columns followed by unmerged entries.
    Long,
}

impl RowAccumulator {
    /// Adds `val` to the entry `(row, col)`.
    #[inline]
    pub fn push(&mut self, row: u32, col: u32, val: f64) {
        self.push_row(row, std::iter::once((col, val)));
    }

    /// Adds each `(col, val)` of `entries` to the entry `(row, col)`, in order: what
    /// [`push`](Self::push) of each does, with the row looked up once (and, in a row of more
    /// than [`Self::SHORT`] columns, the entries merged into it in one walk, after a stable
    /// sort by column if they are not sorted).
    #[inline]
    pub fn push_row(&mut self, row: u32, entries: impl IntoIterator<Item = (u32, f64)>) {
        self.push_row_as(row, entries, false);
    }

    /// [`push_row`](Self::push_row) of entries whose columns ascend (not strictly: a column
    /// may repeat), merged as they come, without a copy or a sort.
    ///
    /// Entries out of order would leave the row's columns unsorted: the caller sorts them
    /// (checked in debug builds).
    #[inline]
    pub(crate) fn push_sorted_row(
        &mut self,
        row: u32,
        entries: impl IntoIterator<Item = (u32, f64)>,
    ) {
        self.push_row_as(row, entries, true);
    }

    /// [`push_row`](Self::push_row), the entries known to be sorted by column or not.
    #[inline]
    fn push_row_as(
        &mut self,
        row: u32,
        entries: impl IntoIterator<Item = (u32, f64)>,
        sorted: bool,
    ) {
        let slot = self.slot_of(row);
        let mut entries = entries.into_iter();
        let row_entries = &mut self.entries[slot];
        if self.state[slot] == RowState::Short {
            for (col, val) in entries.by_ref() {
                #[cfg(test)]
                {
                    self.probes += row_entries.len() as u64;
                }
                match row_entries.iter_mut().find(|(c, _)| *c == col) {
                    Some((_, v)) => *v += val,
                    None => row_entries.push((col, val)),
                }
                if row_entries.len() > Self::SHORT {
                    break;
                }
            }
            if row_entries.len() <= Self::SHORT {
                return;
            }
            // Each column once: any sort gives the same order. The rest of the push, if any,
            // is merged.
            row_entries.sort_unstable_by_key(|e| e.0);
            self.state[slot] = RowState::Sorted;
        }
        if self.state[slot] == RowState::Long {
            row_entries.extend(entries);
            return;
        }
        let _steps = if sorted {
            merge_sorted(row_entries, entries, &mut self.fresh)
        } else {
            self.incoming.clear();
            self.incoming.extend(entries);
            if !self.incoming.is_sorted_by_key(|e| e.0) {
                // Stable: a column pushed twice keeps the order of its values.
                sort_short_by_key(&mut self.incoming, |e| e.0);
            }
            merge_sorted(row_entries, self.incoming.iter().copied(), &mut self.fresh)
        };
        #[cfg(test)]
        {
            self.probes += _steps as u64;
        }
        self.state[slot] = self.state_after_merge(slot);
    }

    /// The state of the sorted row in `slot`: sorted, or long if it has outgrown the merge.
    #[inline]
    fn state_after_merge(&self, slot: usize) -> RowState {
        if self.entries[slot].len() > Self::LINEAR {
            RowState::Long
        } else {
            RowState::Sorted
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
                        self.state.push(RowState::Short);
                    }
                    self.entries[slot].clear();
                    self.state[slot] = RowState::Short;
                }
                self.last = Some((row, slot));
                slot
            }
        }
    }

    /// Columns of a row searched linearly (a slave node's row of D, or of M in 2D, has fewer).
    pub const SHORT: usize = 8;

    /// Columns a row keeps merged and sorted as it grows; beyond them its entries are
    /// appended and merged when the part is stored.
    pub const LINEAR: usize = 64;

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

/// Compressed entries stored row by row: a run per row of each part, `(row, end)` (the row's
/// entries end at `end` in `cols` and `vals`, and start where the run before ends), so that an
/// entry takes 12 bytes and a row 8, where `(row, column, value)` took 16 an entry.
#[derive(Debug, Clone, Default)]
struct RunBuffer {
    runs: Vec<(u32, u32)>,
    cols: Vec<u32>,
    vals: Vec<f64>,
}

impl RunBuffer {
    /// Entries a buffer holds at most (its run ends are `u32`).
    const MAX_ENTRIES: usize = u32::MAX as usize;

    /// Where the entries of run `i` start.
    #[inline]
    fn run_start(&self, i: usize) -> usize {
        if i == 0 {
            0
        } else {
            self.runs[i - 1].1 as usize
        }
    }

    /// Appends the entry `(row, col, val)` to the part whose first run is `run0` (rows
    /// ascending, columns ascending within a row), or adds it to the part's last entry if that
    /// has the same row and column.
    ///
    /// # Panics
    /// If the buffer would hold more than [`Self::MAX_ENTRIES`] entries.
    #[inline]
    fn push_merged(&mut self, run0: usize, row: u32, col: u32, val: f64) {
        let n = self.runs.len();
        if n > run0 && self.runs[n - 1].0 == row {
            let last = self.cols.len() - 1;
            if self.cols[last] == col {
                self.vals[last] += val;
                return;
            }
        } else {
            self.runs.push((row, 0));
        }
        self.cols.push(col);
        self.vals.push(val);
        self.runs.last_mut().expect("a run was opened").1 = self.end();
    }

    /// Where the next entry goes, as a run's end.
    ///
    /// # Panics
    /// If the buffer holds more than [`Self::MAX_ENTRIES`] entries.
    #[inline]
    fn end(&self) -> u32 {
        u32::try_from(self.cols.len()).expect("fewer than 2^32 entries in a part buffer")
    }

    /// Appends the row `row` of a part (a new run), its columns ascending and distinct.
    #[inline]
    fn push_row(&mut self, row: u32, entries: &[(u32, f64)]) {
        self.cols.extend(entries.iter().map(|e| e.0));
        self.vals.extend(entries.iter().map(|e| e.1));
        self.runs.push((row, self.end()));
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
    buffers: Vec<RunBuffer>,
    /// `(key, buffer, first run, end of runs)`.
    parts: Vec<(u64, u32, usize, usize)>,
    /// Parts this list expects (0: unknown).
    expected: usize,
}

impl PartList {
    /// A list that expects about `parts` parts of about the same size: its buffers are sized
    /// after the first part for all of them at once, instead of doubling as they fill (a large
    /// buffer then comes straight from the system, and goes straight back when the list is
    /// dropped; grown by doubling, glibc keeps the smaller copies it leaves behind). More parts
    /// than expected, or larger ones, grow the buffers as before.
    pub fn expecting(parts: usize) -> Self {
        Self {
            expected: parts,
            ..Self::default()
        }
    }

    /// Compresses `raw` (emptying it, keeping its allocation) and stores it as part `key`.
    pub fn push_compressed(&mut self, key: u64, raw: &mut Triplets, ws: &mut CompressWorkspace) {
        let more = raw.len();
        self.push_part(key, more, |buf, run0| raw.compress_into(ws, buf, run0));
    }

    /// Stores as part `key` the runs `fill` appends to the last buffer (given the part's first
    /// run), a new buffer when `more` entries could take the last past
    /// [`RunBuffer::MAX_ENTRIES`].
    fn push_part(&mut self, key: u64, more: usize, fill: impl FnOnce(&mut RunBuffer, usize)) {
        if self
            .buffers
            .last()
            .is_none_or(|b| b.cols.len() + more > RunBuffer::MAX_ENTRIES)
        {
            self.buffers.push(RunBuffer::default());
        }
        let b = self.buffers.len() - 1;
        let buf = &mut self.buffers[b];
        let run0 = buf.runs.len();
        fill(buf, run0);
        if self.parts.is_empty() && self.expected > 1 {
            // Room for the expected parts, a tenth more, as large as the first (where the
            // system grants it: the buffers grow as needed otherwise).
            let times = self.expected + self.expected.div_ceil(10);
            let entries = buf.cols.len().saturating_mul(times);
            let entries = entries.min(RunBuffer::MAX_ENTRIES);
            let runs = buf.runs.len().saturating_mul(times);
            let _ = buf.cols.try_reserve_exact(entries - buf.cols.len());
            let _ = buf.vals.try_reserve_exact(entries - buf.vals.len());
            let _ = buf.runs.try_reserve_exact(runs - buf.runs.len());
        }
        self.parts.push((key, b as u32, run0, buf.runs.len()));
    }

    /// Stores the entries of `acc` as part `key` (rows ascending, columns ascending within a
    /// row) and clears `acc`.
    pub fn push_rows(&mut self, key: u64, acc: &mut RowAccumulator) {
        let mut order: Vec<(u32, usize)> = acc.rows.iter().copied().zip(0..).collect();
        order.sort_unstable();
        let more = order.iter().map(|&(_, slot)| acc.entries[slot].len()).sum();
        self.push_part(key, more, |buf, run0| {
            for (row, slot) in order {
                let entries = &mut acc.entries[slot];
                match acc.state[slot] {
                    RowState::Long => {
                        // Columns may repeat: a stable sort keeps them in insertion order,
                        // and they are summed in that order.
                        entries.sort_by_key(|e| e.0);
                        for &(col, val) in entries.iter() {
                            buf.push_merged(run0, row, col, val);
                        }
                    }
                    RowState::Short => {
                        // Each column once in a row: any sort gives the same order.
                        entries.sort_unstable_by_key(|e| e.0);
                        buf.push_row(row, entries);
                    }
                    RowState::Sorted => {
                        debug_assert!(entries.is_sorted_by(|a, b| a.0 < b.0));
                        buf.push_row(row, entries);
                    }
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

    /// The runs of the part `(key, buffer, first run, end of runs)`.
    fn runs_of(&self, &(_, b, r0, r1): &(u64, u32, usize, usize)) -> PartRuns<'_> {
        PartRuns {
            buf: &self.buffers[b as usize],
            runs: r0..r1,
        }
    }

    /// Number of stored triplets.
    pub fn len(&self) -> usize {
        self.parts
            .iter()
            .map(|p| {
                let p = self.runs_of(p);
                p.end() - p.start()
            })
            .sum()
    }

    /// Whether no triplet is stored.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Bytes the part buffers hold (their capacity).
    fn bytes(&self) -> usize {
        use std::mem::size_of;
        self.buffers
            .iter()
            .map(|b| {
                b.runs.capacity() * size_of::<(u32, u32)>()
                    + b.cols.capacity() * size_of::<u32>()
                    + b.vals.capacity() * size_of::<f64>()
            })
            .sum()
    }

    /// Every stored entry, `(key, row, column, value)`, part after part in the order stored.
    #[cfg(test)]
    fn entries(&self) -> Vec<(u64, u32, u32, f64)> {
        let mut out = Vec::new();
        for part in &self.parts {
            let PartRuns { buf, runs } = self.runs_of(part);
            for i in runs {
                let row = buf.runs[i].0;
                for e in buf.run_start(i)..buf.run_start(i + 1) {
                    out.push((part.0, row, buf.cols[e], buf.vals[e]));
                }
            }
        }
        out
    }

    /// The `nrows x ncols` CSR matrix of the parts in key order, duplicates summed in that
    /// order. The parts are freed before the matrix arrays are filled (and, from
    /// `RELEASE_BYTES` of them, their pages given back to the system).
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
            let parts: Vec<PartRuns> = self.parts.iter().map(|p| self.runs_of(p)).collect();
            // Every index checked first, the parts in parallel (the first bad part's
            // reported).
            let bad = parts.par_iter().find_map_first(|p| {
                let (runs, a, z) = (&p.buf.runs[p.runs.clone()], p.start(), p.end());
                if let Some(r) = runs.iter().find(|r| r.0 as usize >= nrows) {
                    return Some(format!(
                        "entry in row {} outside a {nrows}x{ncols} matrix",
                        r.0
                    ));
                }
                let i = (a..z).find(|&i| p.buf.cols[i] as usize >= ncols)?;
                let row = runs[runs.partition_point(|r| (r.1 as usize) <= i)].0;
                Some(format!(
                    "entry ({row}, {}) outside a {nrows}x{ncols} matrix",
                    p.buf.cols[i]
                ))
            });
            if let Some(message) = bad {
                panic!("{message}");
            }
            row_blocks(&parts, nrows)
        };
        let bytes = self.bytes();
        drop(self);
        // The parts' pages back to the system before the matrix arrays take theirs (glibc
        // would keep them: see `crate::memory`).
        if bytes >= crate::memory::RELEASE_BYTES {
            crate::memory::release_free_memory();
        }
        concat_blocks(blocks, nrows, ncols)
    }
}

/// One part's runs in its buffer.
struct PartRuns<'a> {
    buf: &'a RunBuffer,
    runs: std::ops::Range<usize>,
}

impl PartRuns<'_> {
    /// Where the part's entries start in its buffer.
    fn start(&self) -> usize {
        self.buf.run_start(self.runs.start)
    }

    /// Where the part's entries end in its buffer.
    fn end(&self) -> usize {
        self.buf.run_start(self.runs.end)
    }
}

/// Rows of one block of the matrix: merged row lengths, columns, values.
type RowBlock = (Vec<usize>, Vec<u32>, Vec<f64>);

/// Per-thread buffers of the row blocks.
#[derive(Default)]
struct BlockWorkspace {
    /// The block's runs, in part order: `(row, index of the part, start and end of its
    /// entries in the part's buffer)`.
    local: Vec<(u32, u32, usize, usize)>,
    start: Vec<usize>,
    next: Vec<usize>,
    /// Runs per row of the block.
    count: Vec<u32>,
    cols: Vec<u32>,
    vals: Vec<f64>,
}

/// Merges the row-sorted `parts` into blocks of [`ROW_BLOCK`] rows, in parallel; within a
/// row, entries are summed in part order, then in their order within a part.
fn row_blocks(parts: &[PartRuns<'_>], nrows: usize) -> Vec<RowBlock> {
    (0..nrows.div_ceil(ROW_BLOCK))
        .into_par_iter()
        .map_init(BlockWorkspace::default, |ws, b| {
            let (r0, r1) = (b * ROW_BLOCK, ((b + 1) * ROW_BLOCK).min(nrows));
            let rows = r1 - r0;
            // This block's runs, part after part (each sorted by row).
            ws.local.clear();
            for (k, p) in parts.iter().enumerate() {
                let runs = &p.buf.runs[p.runs.clone()];
                // Most parts (the entries of a chunk of cells) lie in a few rows: skip those
                // outside the block without searching them.
                match (runs.first(), runs.last()) {
                    (Some(f), Some(l)) if (l.0 as usize) >= r0 && (f.0 as usize) < r1 => {}
                    _ => continue,
                }
                let a = runs.partition_point(|x| (x.0 as usize) < r0);
                let z = runs.partition_point(|x| (x.0 as usize) < r1);
                for i in p.runs.start + a..p.runs.start + z {
                    let (row, end) = p.buf.runs[i];
                    ws.local
                        .push((row, k as u32, p.buf.run_start(i), end as usize));
                }
            }
            // Each row's runs copied into its place, in part order (a stable counting sort
            // of the runs by row), then per row a stable sort by column and the sums in that
            // order where more than one part reaches it.
            ws.start.clear();
            ws.start.resize(rows + 1, 0);
            ws.count.clear();
            ws.count.resize(rows, 0);
            for &(row, _, a, z) in &ws.local {
                ws.start[row as usize - r0 + 1] += z - a;
                ws.count[row as usize - r0] += 1;
            }
            for r in 0..rows {
                ws.start[r + 1] += ws.start[r];
            }
            let n = ws.start[rows];
            ws.cols.clear();
            ws.cols.resize(n, 0);
            ws.vals.clear();
            ws.vals.resize(n, 0.0);
            ws.next.clear();
            ws.next.extend_from_slice(&ws.start[..rows]);
            for &(row, k, a, z) in &ws.local {
                let buf = parts[k as usize].buf;
                let at = &mut ws.next[row as usize - r0];
                ws.cols[*at..*at + z - a].copy_from_slice(&buf.cols[a..z]);
                ws.vals[*at..*at + z - a].copy_from_slice(&buf.vals[a..z]);
                *at += z - a;
            }
            let mut lens = Vec::with_capacity(rows);
            let mut w = 0usize;
            for r in 0..rows {
                let (a, z) = (ws.start[r], ws.start[r + 1]);
                // A row of one part is sorted, each column once.
                let len = if ws.count[r] > 1 {
                    merge_row(&mut ws.cols[a..z], &mut ws.vals[a..z])
                } else {
                    z - a
                };
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
    let rows: usize = blocks.iter().map(|b| b.0.len()).sum();
    // The row pointers too are written block by block: pushed on one thread into fresh
    // pages, they were most of the 10.8 ms that a two-thread coupling of arc2d at 10^6 spent
    // on one thread building its CSR (0.8 ms since). `indptr[0]` stays 0.
    let mut indptr = crate::memory::zeroed_in_parallel::<usize>(rows + 1);
    let mut indices = crate::memory::zeroed_in_parallel::<usize>(nnz);
    let mut data = crate::memory::zeroed_in_parallel::<f64>(nnz);
    let mut targets = Vec::with_capacity(blocks.len());
    let (mut rest_p, mut rest_i, mut rest_d) = (&mut indptr[1..], &mut indices[..], &mut data[..]);
    let mut first = 0;
    for (lens, cols, _) in &blocks {
        let (head_p, tail_p) = rest_p.split_at_mut(lens.len());
        let (head_i, tail_i) = rest_i.split_at_mut(cols.len());
        let (head_d, tail_d) = rest_d.split_at_mut(cols.len());
        targets.push((first, head_p, head_i, head_d));
        first += cols.len();
        (rest_p, rest_i, rest_d) = (tail_p, tail_i, tail_d);
    }
    // Each block copied, and its rows checked as `SparseMatrix::new` would check them
    // (columns strictly ascending, below `ncols`), in parallel: sprs's check is one pass on
    // one thread, 1.5 % of a two-thread coupling of 10^6 lines.
    let sound = blocks
        .into_par_iter()
        .zip(targets)
        .map(|((lens, cols, vals), (first, to_p, to_i, to_d))| {
            let mut end = first;
            for (p, &len) in to_p.iter_mut().zip(&lens) {
                end += len;
                *p = end;
            }
            for (t, &c) in to_i.iter_mut().zip(&cols) {
                *t = c as usize;
            }
            to_d.copy_from_slice(&vals);
            // The rows' lengths add up to the block's entries, so that the row pointers of
            // consecutive blocks join (they never decrease).
            let mut at = 0;
            let rows_sound = lens.iter().all(|&len| {
                let row = &cols[at..at + len];
                at += len;
                row.windows(2).all(|w| w[0] < w[1])
                    && row.last().is_none_or(|&c| (c as usize) < ncols)
            });
            rows_sound && at == cols.len()
        })
        .reduce(|| true, |a, b| a && b);
    super::csr::csr_of_sound_rows((nrows, ncols), indptr, indices, data, sound)
}

/// Sorts `items` by `key`, stably: up to 32 items (a face's or a row's entries) by
/// insertion, which beats the library's sort on so few, more by `sort_by_key`.
pub(crate) fn sort_short_by_key<T: Copy, K: Ord>(items: &mut [T], key: impl Fn(&T) -> K) {
    if items.len() > 32 {
        items.sort_by_key(|e| key(e));
        return;
    }
    for i in 1..items.len() {
        let e = items[i];
        let mut j = i;
        while j > 0 && key(&items[j - 1]) > key(&e) {
            items[j] = items[j - 1];
            j -= 1;
        }
        items[j] = e;
    }
}

/// Merges `incoming` (sorted by column, a column possibly repeated) into `row` (columns
/// ascending and distinct), which stays so: a value whose column `row` has is added to it,
/// the others (each repeated column's values summed in order, the first as it is) inserted
/// in place. Returns the steps the walk took (`row`'s entries passed and `incoming`'s).
/// `fresh` is scratch.
#[inline]
fn merge_sorted(
    row: &mut Vec<(u32, f64)>,
    incoming: impl Iterator<Item = (u32, f64)>,
    fresh: &mut Vec<(u32, f64)>,
) -> usize {
    fresh.clear();
    let n = row.len();
    let (mut i, mut taken) = (0, 0);
    let mut last_col = 0;
    for (c, v) in incoming {
        debug_assert!(taken == 0 || c >= last_col, "columns pushed out of order");
        last_col = c;
        taken += 1;
        while i < n && row[i].0 < c {
            i += 1;
        }
        if i < n && row[i].0 == c {
            row[i].1 += v;
        } else {
            match fresh.last_mut() {
                Some(last) if last.0 == c => last.1 += v,
                _ => fresh.push((c, v)),
            }
        }
    }
    let steps = i + taken;
    if fresh.is_empty() {
        return steps;
    }
    // From the back: each slot is written after the entry it held was moved up (new columns
    // all after the row's are written in place and the walk stops).
    let m = fresh.len();
    row.resize(n + m, (0, 0.0));
    let (mut a, mut b) = (n, m);
    for w in (0..n + m).rev() {
        if b == 0 {
            break;
        }
        if a > 0 && row[a - 1].0 > fresh[b - 1].0 {
            row[w] = row[a - 1];
            a -= 1;
        } else {
            row[w] = fresh[b - 1];
            b -= 1;
        }
    }
    steps
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
        /// summation shows in the bits). Rows of up to 100 columns, so that rows go through
        /// every state (searched, merged, appended and merged when stored), and pushes of
        /// one entry, of a run of equal rows, and of up to `chunk` entries of a row at a time
        /// (unsorted, columns repeated, a push crossing from the search to the merge; and the
        /// same sorted by column, through `push_sorted_row`).
        #[test]
        fn accumulated_rows_are_the_compressed_triplets(
            parts in prop::collection::vec(
                prop::collection::vec((0u32..8, 0u32..100, -1e3..1e3f64, -8i32..8), 0..1200),
                1..3,
            ),
            chunk in 1usize..24,
        ) {
            let (mut sorted, mut summed) = (PartList::default(), PartList::default());
            // Sized for the parts after the first (`expecting`): the same entries.
            let mut by_rows = PartList::expecting(parts.len());
            let mut by_chunks = PartList::default();
            let (mut ws, mut acc) = (CompressWorkspace::default(), RowAccumulator::default());
            let (mut row_acc, mut chunk_acc) = (RowAccumulator::default(), RowAccumulator::default());
            let (mut by_sorted_chunks, mut sorted_acc) = (PartList::default(), RowAccumulator::default());
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
                // Grouped by row (a stable sort: each entry's values keep their order), then
                // `chunk` entries of a row at a time.
                let mut grouped = scaled.clone();
                grouped.sort_by_key(|e| e.0);
                for run in grouped.chunk_by(|a, b| a.0 == b.0) {
                    for push in run.chunks(chunk) {
                        chunk_acc.push_row(push[0].0, push.iter().map(|&(_, c, v)| (c, v)));
                        // Sorted by column first (stably: a column's values keep their order).
                        let mut ascending = push.to_vec();
                        ascending.sort_by_key(|e| e.1);
                        sorted_acc.push_sorted_row(push[0].0, ascending.iter().map(|&(_, c, v)| (c, v)));
                    }
                }
                sorted.push_compressed(k as u64, &mut raw, &mut ws);
                summed.push_rows(k as u64, &mut acc);
                by_rows.push_rows(k as u64, &mut row_acc);
                by_chunks.push_rows(k as u64, &mut chunk_acc);
                by_sorted_chunks.push_rows(k as u64, &mut sorted_acc);
                prop_assert!(acc.is_empty());
            }
            let bits = |l: &PartList| -> Vec<(u64, u32, u32, u64)> {
                l.entries().into_iter().map(|(k, r, c, v)| (k, r, c, v.to_bits())).collect()
            };
            prop_assert_eq!(bits(&sorted), bits(&summed));
            prop_assert_eq!(bits(&sorted), bits(&by_rows));
            prop_assert_eq!(bits(&sorted), bits(&by_chunks));
            prop_assert_eq!(bits(&sorted), bits(&by_sorted_chunks));
        }
    }

    proptest! {
        /// The matrix of parts spread over several row blocks (rows reached by one part and
        /// by several) has the structure sprs checks (`check_compressed_structure`, which the
        /// build no longer calls itself), and is the matrix of its dense sums.
        #[test]
        fn matrices_of_parts_have_sound_structure(
            parts in prop::collection::vec(
                prop::collection::vec((0u32..3 * ROW_BLOCK as u32, 0u32..40, -1.0..1.0f64), 0..300),
                1..4,
            ),
        ) {
            let (nrows, ncols) = (3 * ROW_BLOCK + 5, 40);
            let mut list = PartList::default();
            let mut ws = CompressWorkspace::default();
            let mut dense = std::collections::BTreeMap::new();
            for (k, part) in parts.iter().enumerate() {
                let mut raw = Triplets::default();
                for &(r, c, v) in part {
                    raw.push(r, c, v);
                    *dense.entry((r as usize, c as usize)).or_insert(0.0) += v;
                }
                list.push_compressed(k as u64, &mut raw, &mut ws);
            }
            let a = list.to_csr(nrows, ncols);
            prop_assert!(a.check_compressed_structure().is_ok());
            prop_assert_eq!(a.nnz(), dense.len());
            for ((r, c), v) in dense {
                let got = *a.get(r, c).expect("every entry pushed is stored");
                prop_assert!((got - v).abs() <= 1e-12, "({}, {}): {} against {}", r, c, got, v);
            }
        }
    }

    /// An entry outside the matrix is reported, the first part's (in key order) when several
    /// have one: the parts are checked in parallel.
    #[test]
    #[should_panic(expected = "entry (2, 7) outside a 4x5 matrix")]
    fn the_first_entry_outside_is_reported() {
        let mut list = PartList::default();
        let mut ws = CompressWorkspace::default();
        for (key, (row, col)) in [(5, (3, 9)), (1, (2, 7)), (0, (1, 1))] {
            let mut raw = Triplets::default();
            raw.push(row, col, 1.0);
            list.push_compressed(key, &mut raw, &mut ws);
        }
        let _ = list.to_csr(4, 5);
    }

    /// Regression: a row of many columns (one coarse slave face against 20,000 master faces)
    /// made the accumulator's linear column search quadratic (2e8 comparisons here, seconds
    /// for 1e5 columns); the merges now stay within a few steps per push, and the part is
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
        let bits = |l: &PartList| -> Vec<(u64, u32, u32, u64)> {
            l.entries()
                .into_iter()
                .map(|(k, r, c, v)| (k, r, c, v.to_bits()))
                .collect()
        };
        assert_eq!(bits(&a), bits(&b));
    }
}
