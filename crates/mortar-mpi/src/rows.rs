//! `RankRows` (a rank's rows of D and M in the global numbering), `RankCounts` and `gather`,
//! which puts every rank's rows together on one rank.

use mortar_core::assembly::CouplingWarning;
use mortar_core::linalg::SparseMatrix;

use crate::error::Result;
use crate::exchange::{agree, Exchange};
use crate::wire::{Reader, Writer};

/// Sparse rows whose columns are node tags (ascending within a row).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TaggedRows {
    /// Row `r`'s entries are `indptr[r]..indptr[r + 1]` of `cols` and `values`.
    pub indptr: Vec<usize>,
    /// Column node tags.
    pub cols: Vec<u64>,
    /// Values.
    pub values: Vec<f64>,
}

impl TaggedRows {
    /// Appends a row.
    pub fn push_row(&mut self, entries: impl IntoIterator<Item = (u64, f64)>) {
        if self.indptr.is_empty() {
            self.indptr.push(0);
        }
        for (c, v) in entries {
            self.cols.push(c);
            self.values.push(v);
        }
        self.indptr.push(self.cols.len());
    }

    /// Row `r`'s entries.
    pub fn row(&self, r: usize) -> impl Iterator<Item = (u64, f64)> + '_ {
        let range = self.indptr[r]..self.indptr[r + 1];
        self.cols[range.clone()]
            .iter()
            .copied()
            .zip(self.values[range].iter().copied())
    }
}

/// What a rank did in a distributed coupling.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RankCounts {
    /// Slave faces the caller gave this rank.
    pub slave_faces: usize,
    /// Slave faces of other ranks coupled here too, for the rows and normals of the nodes on
    /// the part's boundary.
    pub ghost_slave_faces: usize,
    /// Master faces the caller gave this rank.
    pub master_faces: usize,
    /// Master faces of other ranks received, within the search's reach of this rank's slave
    /// faces.
    pub ghost_master_faces: usize,
    /// Slave-master pairs with an overlap coupled here (ghost slave faces included).
    pub pairs: usize,
    /// Messages of faces sent to other ranks.
    pub messages_sent: usize,
    /// Their bytes.
    pub bytes_sent: u64,
    /// This rank's own slave faces when it coupled nothing ([`RankRows::uncoupled_faces`]).
    pub uncoupled_faces: usize,
    /// Exchanges of master faces: 1, or 2 when the widened search of an open gap needed
    /// master faces farther away.
    pub passes: usize,
}

impl RankCounts {
    /// The counts by name (the names of the fields), for a report.
    pub fn named(&self) -> [(&'static str, u64); 9] {
        [
            ("slave_faces", self.slave_faces as u64),
            ("ghost_slave_faces", self.ghost_slave_faces as u64),
            ("master_faces", self.master_faces as u64),
            ("ghost_master_faces", self.ghost_master_faces as u64),
            ("pairs", self.pairs as u64),
            ("messages_sent", self.messages_sent as u64),
            ("bytes_sent", self.bytes_sent),
            ("uncoupled_faces", self.uncoupled_faces as u64),
            ("passes", self.passes as u64),
        ]
    }
}

/// Where a rank's time went in a distributed coupling, in seconds of wall-clock time (the
/// exchanges include the wait for the other ranks).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RankSeconds {
    /// The ranks' boxes and face sizes gathered.
    pub summaries: f64,
    /// Slave faces sent to the ranks they may neighbour.
    pub slave_exchange: f64,
    /// The nodes' owners, the ghost slave faces kept and this rank's slave surface built.
    pub ghosts: f64,
    /// Master faces sent to the ranks whose slave faces they may meet (every pass).
    pub master_exchange: f64,
    /// This rank's interface built and checked ([`Interface::with_tolerances`](mortar_core::Interface::with_tolerances)).
    pub interface: f64,
    /// The core's coupling of this rank's faces.
    pub coupling: f64,
    /// The owned rows taken out in the global numbering.
    pub rows: f64,
    /// Everything.
    pub total: f64,
}

/// One rank's part of a distributed coupling: the rows of D and M of the slave nodes it owns.
#[derive(Debug, Clone)]
pub struct RankRows {
    /// The owned slave nodes' tags, ascending: the rows.
    pub rows: Vec<u64>,
    /// Their rows of D, columns by slave node tag.
    pub d: TaggedRows,
    /// Their rows of M, columns by master node tag.
    pub m: TaggedRows,
    /// The tags of the nodes of this rank's own master faces, ascending.
    pub master_nodes: Vec<u64>,
    /// Counts of this rank's work and messages.
    pub counts: RankCounts,
    /// The warnings of this rank's coupling (its ghost slave faces included, so that a face
    /// near a part's boundary may be reported by two ranks).
    pub warnings: Vec<CouplingWarning>,
    /// The tags of this rank's own slave faces when it coupled nothing (no master face within
    /// the search's reach, or none that overlaps): their rows are zero, as a one-process
    /// coupling leaves uncovered area; empty when the rank coupled. Report them as a warning.
    pub uncoupled_faces: Vec<u64>,
    /// Where this rank's time went.
    pub seconds: RankSeconds,
}

/// D and M put together from every rank's rows: the one-process coupling's layout (rows the
/// slave node tags ascending, columns of M the master node tags ascending).
#[derive(Debug, Clone)]
pub struct GatheredCoupling {
    /// D, slave x slave.
    pub d: SparseMatrix,
    /// M, slave x master.
    pub m: SparseMatrix,
    /// The slave node tags in row order.
    pub slave_nodes: Vec<u64>,
    /// The master node tags in column order.
    pub master_nodes: Vec<u64>,
    /// Every rank's counts, by rank.
    pub counts: Vec<RankCounts>,
}

fn write_rows(w: &mut Writer, rows: &TaggedRows, count: usize) {
    for r in 0..count {
        let n = rows.indptr[r + 1] - rows.indptr[r];
        w.u64(n as u64);
        for (c, v) in rows.row(r) {
            w.u64(c);
            w.f64(v);
        }
    }
}

fn read_rows(r: &mut Reader<'_>, count: usize, out: &mut Vec<Vec<(u64, f64)>>) -> Result<()> {
    for _ in 0..count {
        let n = r.u64()? as usize;
        let mut row = Vec::with_capacity(n.min(1 << 16));
        for _ in 0..n {
            row.push((r.u64()?, r.f64()?));
        }
        out.push(row);
    }
    Ok(())
}

/// The CSR matrix of `rows` (by row) with the columns' tags mapped by `col`.
fn csr(rows: &[Vec<(u64, f64)>], cols: &[u64]) -> SparseMatrix {
    let mut indptr = vec![0usize];
    let mut indices = Vec::new();
    let mut data = Vec::new();
    for row in rows {
        for &(t, v) in row {
            indices.push(cols.binary_search(&t).expect("a column of a gathered node"));
            data.push(v);
        }
        indptr.push(indices.len());
    }
    SparseMatrix::new((rows.len(), cols.len()), indptr, indices, data)
}

/// Every rank's rows put together on `root` (`None` on the others). Collective.
///
/// # Errors
/// A malformed message, on every rank.
pub fn gather(
    ex: &(impl Exchange + ?Sized),
    part: &RankRows,
    root: usize,
) -> Result<Option<GatheredCoupling>> {
    let mut w = Writer::default();
    for (_, v) in part.counts.named() {
        w.u64(v);
    }
    w.u64(part.rows.len() as u64);
    for &t in &part.rows {
        w.u64(t);
    }
    write_rows(&mut w, &part.d, part.rows.len());
    write_rows(&mut w, &part.m, part.rows.len());
    w.u64(part.master_nodes.len() as u64);
    for &t in &part.master_nodes {
        w.u64(t);
    }
    let got = ex.gather(&w.bytes, root);
    let built = got.map(|parts| -> Result<GatheredCoupling> {
        let mut tagged: Vec<(u64, usize)> = Vec::new();
        let (mut d_rows, mut m_rows) = (Vec::new(), Vec::new());
        let mut master_nodes = Vec::new();
        let mut counts = Vec::new();
        for (q, bytes) in parts.iter().enumerate() {
            let mut r = Reader::new(bytes, ex.rank(), q);
            let mut v = [0u64; 9];
            for x in v.iter_mut() {
                *x = r.u64()?;
            }
            counts.push(RankCounts {
                slave_faces: v[0] as usize,
                ghost_slave_faces: v[1] as usize,
                master_faces: v[2] as usize,
                ghost_master_faces: v[3] as usize,
                pairs: v[4] as usize,
                messages_sent: v[5] as usize,
                bytes_sent: v[6],
                uncoupled_faces: v[7] as usize,
                passes: v[8] as usize,
            });
            let n = r.u64()? as usize;
            for _ in 0..n {
                tagged.push((r.u64()?, tagged.len()));
            }
            read_rows(&mut r, n, &mut d_rows)?;
            read_rows(&mut r, n, &mut m_rows)?;
            let k = r.u64()? as usize;
            for _ in 0..k {
                master_nodes.push(r.u64()?);
            }
            if !r.is_done() {
                return Err(r.malformed("bytes after a rank's rows"));
            }
        }
        tagged.sort_unstable();
        let slave_nodes: Vec<u64> = tagged.iter().map(|&(t, _)| t).collect();
        master_nodes.sort_unstable();
        master_nodes.dedup();
        let d_sorted: Vec<_> = tagged
            .iter()
            .map(|&(_, i)| std::mem::take(&mut d_rows[i]))
            .collect();
        let m_sorted: Vec<_> = tagged
            .iter()
            .map(|&(_, i)| std::mem::take(&mut m_rows[i]))
            .collect();
        Ok(GatheredCoupling {
            d: csr(&d_sorted, &slave_nodes),
            m: csr(&m_sorted, &master_nodes),
            slave_nodes,
            master_nodes,
            counts,
        })
    });
    agree(ex, built.transpose())
}
