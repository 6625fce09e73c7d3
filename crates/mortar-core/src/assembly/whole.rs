//! `WholeInterface`: what a part of a larger interface must know of the whole so that the rows
//! of D and M it computes are the whole's, bit for bit.
//!
//! A coupling takes every sum in an order fixed by the faces and their places in space, never
//! by the files' numbering beyond the faces' order, nor by threads or work split:
//! - the slave faces are processed in the Morton order of their first nodes, in the box of
//!   those nodes, ties by face index;
//! - they are cut into chunks at fixed cells of that order: the codes' leading bits
//!   (buckets, about [`BUCKET_FACES`] faces each), consecutive buckets grouped until a chunk
//!   holds [`CHUNK`] faces; each entry of D and M is summed face after face within a chunk,
//!   and chunk after chunk (a chunk keyed by its first bucket);
//! - a face meets its master candidates by ascending master face index;
//! - the nodal normals sum the faces at a node by ascending face index;
//! - the paths (closed forms in 3D, the chain walk and the fused kernel in 2D) are chosen from
//!   the element types of both sides and from whether both sides are chains of lines.
//!
//! An entry of D or M in a slave node's row has contributions from the faces around that node
//! only. A part that holds every face around its nodes and around their neighbours (for the
//! normals), its faces in the whole's relative order (by tag, when the whole's faces ascend by
//! tag), and that orders, chunks and chooses by the whole's box, buckets, element types and
//! chains, therefore sums each entry of those nodes' rows over the same faces in the same
//! order, grouped in the same chunks: the same bits. `mortar-mpi` builds one per distributed
//! coupling from what the ranks exchange.

use std::ops::Range;

use nalgebra::Vector3;

use crate::element::ElementRef;
use crate::interface::{Interface, SpatialDim};
use crate::mesh::SurfaceMesh;
use crate::search::{bounds_of, morton_code};

/// Slave faces per work chunk (at least, but for the last: a chunk is whole buckets).
pub(crate) const CHUNK: usize = 256;

/// Slave faces per bucket of the Morton order, on average over a surface (3D) or a line (2D)
/// whose faces are of one size.
pub const BUCKET_FACES: u64 = 32;

/// Where the chunks of a coupling start in the Morton order of its slave faces: buckets are
/// the codes shifted right by `shift`, and a chunk starts at each bucket of `starts`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct ChunkPlan {
    shift: u32,
    /// The first bucket of each chunk, ascending.
    starts: Vec<u64>,
}

impl ChunkPlan {
    /// The shift of the buckets of an interface of `faces` slave faces: in 3D, `b` bits per
    /// axis with `4^b` about `faces / BUCKET_FACES` (the faces of a surface fill a square of
    /// cells); in 2D, `2^b` about that (a line's fill a row).
    fn shift(faces: u64, dim: SpatialDim) -> u32 {
        let cells = (faces / BUCKET_FACES).max(1);
        let log2 = 63 - cells.leading_zeros(); // floor(log2(cells))
        match dim {
            SpatialDim::Three => 63 - 3 * log2.div_ceil(2).min(21),
            SpatialDim::Two => 64 - 2 * log2.min(32),
        }
    }

    /// The bucket of the code `code`.
    #[inline]
    fn bucket(&self, code: u64) -> u64 {
        code.checked_shr(self.shift).unwrap_or(0)
    }

    /// The plan of the buckets `counts` (`(bucket, faces)`, buckets ascending, each once) of
    /// an interface of `faces` slave faces: a chunk closes after the bucket that takes it to
    /// [`CHUNK`] faces.
    fn of_counts(shift: u32, counts: impl IntoIterator<Item = (u64, u64)>) -> Self {
        let mut starts = Vec::new();
        let mut open = 0u64;
        for (bucket, n) in counts {
            if open == 0 {
                starts.push(bucket);
            }
            open += n;
            if open >= CHUNK as u64 {
                open = 0;
            }
        }
        Self { shift, starts }
    }

    /// The buckets of the sorted codes `codes`, each with its count.
    fn counts_of(shift: u32, codes: impl IntoIterator<Item = u64>) -> Vec<(u64, u64)> {
        let mut counts: Vec<(u64, u64)> = Vec::new();
        for code in codes {
            let b = code.checked_shr(shift).unwrap_or(0);
            match counts.last_mut() {
                Some((last, n)) if *last == b => *n += 1,
                _ => counts.push((b, 1)),
            }
        }
        counts
    }

    /// The plan of an interface that is whole: from its own sorted keys.
    pub(crate) fn of_keys(keys: &[u128], dim: SpatialDim) -> Self {
        let shift = Self::shift(keys.len() as u64, dim);
        let counts = Self::counts_of(shift, keys.iter().map(|&k| (k >> 32) as u64));
        Self::of_counts(shift, counts)
    }

    /// The chunk (its index in the plan) of the code `code`.
    #[inline]
    pub(crate) fn chunk_of(&self, code: u64) -> usize {
        let b = self.bucket(code);
        self.starts.partition_point(|&s| s <= b).saturating_sub(1)
    }

    /// The chunks of faces in the processing order `order` whose chunk indices are
    /// `chunk(p)` at position `p` (ascending along the order): each chunk's key (its first
    /// bucket) and its positions.
    pub(crate) fn ranges(
        &self,
        n: usize,
        chunk: impl Fn(usize) -> usize,
    ) -> Vec<(u64, Range<usize>)> {
        let mut out: Vec<(u64, Range<usize>)> = Vec::new();
        let mut current = usize::MAX;
        for p in 0..n {
            let c = chunk(p);
            if c != current {
                debug_assert!(current == usize::MAX || c > current, "chunks ascend");
                current = c;
                out.push((self.starts.get(c).copied().unwrap_or(0), p..p + 1));
            } else if let Some(last) = out.last_mut() {
                last.1.end = p + 1;
            }
        }
        out
    }
}

/// What a part of an interface must know of the whole interface so that its slave nodes'
/// rows of D and M are the whole's bit for bit (see the module's text): set
/// [`CouplingOptions::whole`](super::CouplingOptions::whole) on the part's coupling.
///
/// Built from what each part contributes ([`anchor_box`](Self::anchor_box),
/// [`bucket_counts`](Self::bucket_counts), [`lines_are_chains`](Self::lines_are_chains) and
/// the element types), which a distributed coupling exchanges; the whole interface itself
/// never needs to be in one place.
///
/// ```
/// # use mortar_core::assembly::WholeInterface;
/// # use mortar_core::{Interface, SpatialDim};
/// # fn demo(interface: &Interface) {
/// // The whole from a single part: the plan the coupling takes by itself.
/// let slave = interface.slave();
/// let anchors = WholeInterface::anchor_box(slave).expect("a slave face");
/// let faces = slave.face_count() as u64;
/// let counts = WholeInterface::bucket_counts(slave, &anchors, faces, interface.dim());
/// let whole = WholeInterface::new(
///     anchors,
///     faces,
///     interface.dim(),
///     &counts,
///     slave.element_types().to_vec(),
///     interface.master().element_types().to_vec(),
///     WholeInterface::lines_are_chains(interface),
/// );
/// # let _ = whole;
/// # }
/// ```
#[derive(Debug, Clone)]
pub struct WholeInterface {
    pub(crate) anchors: (Vector3<f64>, Vector3<f64>),
    pub(crate) plan: ChunkPlan,
    pub(crate) slave_types: Vec<ElementRef>,
    pub(crate) master_types: Vec<ElementRef>,
    pub(crate) chains: bool,
}

impl WholeInterface {
    /// The box of the first nodes of `slave`'s faces (`None` without a face): the whole's is
    /// the union of its parts' (the least and greatest coordinates, exact).
    pub fn anchor_box(slave: &SurfaceMesh) -> Option<([f64; 3], [f64; 3])> {
        if slave.face_count() == 0 {
            return None;
        }
        let (lo, hi) = bounds_of(slave.face_count(), |f| anchor(slave, f));
        Some((lo.into(), hi.into()))
    }

    /// The buckets of `slave`'s faces, `(bucket, faces)` ascending, in the whole's anchor box
    /// `anchors` for a whole of `faces` slave faces in dimension `dim`: the whole's are its
    /// parts' summed bucket by bucket (each face counted in one part).
    pub fn bucket_counts(
        slave: &SurfaceMesh,
        anchors: &([f64; 3], [f64; 3]),
        faces: u64,
        dim: SpatialDim,
    ) -> Vec<(u64, u64)> {
        let (lo, hi) = (Vector3::from(anchors.0), Vector3::from(anchors.1));
        let planar = dim == SpatialDim::Two;
        let mut codes: Vec<u64> = (0..slave.face_count())
            .map(|f| morton_code(&anchor(slave, f), &lo, &hi, planar))
            .collect();
        codes.sort_unstable();
        ChunkPlan::counts_of(ChunkPlan::shift(faces, dim), codes)
    }

    /// Whether both sides of `interface` are chains of lines (no node starting or ending two
    /// faces), the condition of the 2D chain walk: the whole's sides are chains when every
    /// part's are, each part holding every face around its nodes.
    pub fn lines_are_chains(interface: &Interface) -> bool {
        interface.dim() == SpatialDim::Two
            && crate::search::LineChains::of(interface.slave()).is_some()
            && crate::search::LineChains::of(interface.master()).is_some()
    }

    /// The whole interface: the box of its slave faces' first nodes (`anchors`), its slave
    /// face count and dimension, its buckets (`counts`, `(bucket, faces)` ascending, each
    /// once: its parts' [`bucket_counts`](Self::bucket_counts) summed), the element types of
    /// its slave and master faces, and whether both its sides are chains of lines.
    pub fn new(
        anchors: ([f64; 3], [f64; 3]),
        faces: u64,
        dim: SpatialDim,
        counts: &[(u64, u64)],
        slave_types: Vec<ElementRef>,
        master_types: Vec<ElementRef>,
        chains: bool,
    ) -> Self {
        let shift = ChunkPlan::shift(faces, dim);
        Self {
            anchors: (anchors.0.into(), anchors.1.into()),
            plan: ChunkPlan::of_counts(shift, counts.iter().copied()),
            slave_types,
            master_types,
            chains,
        }
    }

    /// Says whether both sides of the whole are chains of lines (the AND of its parts'
    /// [`lines_are_chains`](Self::lines_are_chains)).
    pub fn set_chains(&mut self, chains: bool) {
        self.chains = chains;
    }

    /// Chunks in the whole's plan.
    pub fn chunks(&self) -> usize {
        self.plan.starts.len()
    }
}

/// The point a slave face is ordered by: its first node.
#[inline]
pub(crate) fn anchor(slave: &SurfaceMesh, f: usize) -> Vector3<f64> {
    slave.coords()[slave.face_nodes(f)[0] as usize]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_close_at_whole_buckets() {
        let counts = [(0, 100), (3, 100), (4, 100), (9, 300), (12, 10)];
        let plan = ChunkPlan::of_counts(0, counts);
        assert_eq!(plan.starts, [0, 9, 12]);
        assert_eq!(plan.chunk_of(4), 0);
        assert_eq!(plan.chunk_of(10), 1);
        assert_eq!(plan.chunk_of(12), 2);
        assert_eq!(plan.chunk_of(u64::MAX), 2);
        let codes = [0u64, 3, 3, 9, 12, 12];
        let ranges = plan.ranges(codes.len(), |p| plan.chunk_of(codes[p]));
        assert_eq!(ranges, [(0, 0..3), (9, 3..4), (12, 4..6)]);
    }

    #[test]
    fn buckets_hold_about_bucket_faces() {
        // 3D: 1e6 faces -> 4^b about 31250 -> b = 7 bits per axis (the codes' top 21).
        assert_eq!(ChunkPlan::shift(1_000_000, SpatialDim::Three), 63 - 21);
        assert_eq!(ChunkPlan::shift(10, SpatialDim::Three), 63);
        // 2D: 1e6 faces -> 2^b about 31250 -> b = 14 (the codes' top 28 bits).
        assert_eq!(ChunkPlan::shift(1_000_000, SpatialDim::Two), 64 - 28);
        assert_eq!(ChunkPlan::shift(10, SpatialDim::Two), 64);
    }
}
