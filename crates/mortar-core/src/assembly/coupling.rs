//! The mortar coupling of an interface: `Coupling` (D, M, node maps, nodal normals, statistics),
//! `assemble_coupling` and `assemble_coupling_reusing`, which search, segment, integrate and
//! assemble slave face by slave face on a rayon pool.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::Instant;

use arrayvec::ArrayVec;
use nalgebra::Vector3;
use rayon::prelude::*;

use super::key_index::KeyIndex;
use super::local::{integrate_batch_into, LocalBlocks};
use super::master_coverage;
use super::straight_line;
use super::{anchor, ChunkPlan, CouplingOptions, CouplingWarning};
use crate::element::{ElementRef, MAX_FACE_NODES};
use crate::error::{MortarError, Result, Side};
use crate::integration::affine_moments::{affine_moments_into, PendingBlock};
use crate::integration::closed_form::{self, closed_form_into, ClosedForm, ClosedFormScratch};
use crate::integration::segments_2d::{fused_line_face, is_linear_line, LineFace};
use crate::integration::{
    IntegrationFastPaths, LineSegments, PairedRule, SegmentBased, SegmentContext, CANDIDATE_BATCH,
};
use crate::interface::{FaceGeometry, Interface, MasterFaces, SpatialDim};
use crate::linalg::{sort_short_by_key, PartList, RowAccumulator, SparseMatrix};
use crate::memory::{collect_populated, populated, Spare};
use crate::multiplier::{slave_recombination, LmBasis, MultiplierSpace};
use crate::search::{
    face_search_radius, keep_within_radius, nearest_master_radii, spatial_keys, ChainSearch,
    GroupScratch, LineChains, MasterLineCache, MasterTree, Padding, WALK_LIMIT,
};
use crate::tolerances::SearchRadius;

/// Seconds per phase. The phases `tree`, `faces`, `assembly` and `total` are wall-clock
/// time; [`ThreadSeconds`] splits the per-face work by kind, summed over the threads (with
/// several threads their sum exceeds `faces`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PhaseSeconds {
    /// The search tree over the master faces and the spatial order of the slave faces.
    pub tree: f64,
    /// The per-face work on all threads: search queries, segmentation, integration.
    pub faces: f64,
    /// Assembly of the sparse matrices.
    pub assembly: f64,
    /// Everything.
    pub total: f64,
    /// The per-face work by kind, in thread-seconds.
    pub thread: ThreadSeconds,
}

/// The per-face work of a coupling run by kind, in seconds summed over the threads.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ThreadSeconds {
    /// Search queries.
    pub search: f64,
    /// Segmentation (clipping, triangulation, point pairing); with the closed form
    /// ([`CouplingStats::closed_form_faces`]) also its integration and the merge of its M
    /// blocks by master node, which it does in the same loop.
    pub segments: f64,
    /// Integration of the local blocks.
    pub integration: f64,
}

/// Counts and timings of a coupling run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CouplingStats {
    /// Candidate pairs from the search.
    pub candidates: usize,
    /// Slave-master face pairs with a non-empty overlap.
    pub pairs: usize,
    /// Integration cells (clip triangles, 2D segments, or slave faces for element-based).
    pub segments: usize,
    /// Candidate pairs skipped because the master face faces away from the slave.
    pub back_facing: usize,
    /// Candidate pairs dropped because a point could not be mapped between the faces (see
    /// [`CouplingWarning::SkippedPairs`]).
    pub skipped_pairs: usize,
    /// Slave area (length in 2D, also with the axisymmetric measure: the length of the
    /// meridian) with no master face within the search radius (see
    /// [`CouplingWarning::UncoveredSlaveArea`]).
    pub uncovered_area: f64,
    /// Slave faces with no master face at all.
    pub faces_without_partner: usize,
    /// Slave faces coupled by the fused kernel for straight two-node lines (2D; see
    /// [`assemble_coupling`]); the others went through the integration strategy.
    pub fused_line_faces: usize,
    /// Slave faces coupled by the sorted merge of a straight 2D interface (both sides one
    /// chain of straight two-node lines along one line, a uniform projection direction; see
    /// [`assemble_coupling`]): all of them or none.
    pub straight_line_faces: usize,
    /// Slave faces whose clip polygons were integrated in closed form (3D: linear triangles on
    /// both sides by vertex formulas, flat bilinear quads on either side by the polygons'
    /// moments; with [`SegmentBased`](crate::integration::SegmentBased) of a degree exact for
    /// them, see [`assemble_coupling`]); the others went through the integration strategy's
    /// points.
    pub closed_form_faces: usize,
    /// Slave faces covered in part.
    pub faces_partly_covered: usize,
    /// Slave area covered by more than one master face, once per extra face (see
    /// [`CouplingWarning::OverlappingMasterFaces`]).
    pub overlapped_area: f64,
    /// Slave faces covered by more than one master face.
    pub faces_overlapped: usize,
    /// Off-diagonal entries of a dual D at most 1e-12 times their row's diagonal entry,
    /// added to the diagonal (so that `D 1` is kept) and dropped: the round-off of the
    /// biorthogonal basis, which would otherwise make a diagonal D look full.
    pub d_roundoff_dropped: usize,
    /// The largest of them, relative to its diagonal entry.
    pub d_roundoff_largest: f64,
    /// With a space that claims a diagonal D
    /// ([`MultiplierFastPaths::diagonal_d`](crate::multiplier::MultiplierFastPaths::diagonal_d)): the
    /// off-diagonal entries kept (above 1e-12 of their row's diagonal entry), counted
    /// on the recombined D ([`Coupling::recombined`]) where the slave faces are recombined.
    /// None on a covered interface; partly covered faces keep some, and so do curved faces
    /// too coarse for the quadrature to reach the biorthogonality of the basis (see
    /// [`CouplingWarning::DualNotDiagonal`]). 0 for other spaces.
    pub d_off_diagonal: usize,
    /// The largest of them, relative to its row's diagonal entry.
    pub d_off_diagonal_largest: f64,
    /// Sum of the entries of D: the integrated overlap measure (area in 3D, length in 2D,
    /// the area of the revolved surface, `int 2 pi r ds`, with the axisymmetric measure).
    pub area: f64,
    /// Threads used.
    pub threads: usize,
    /// The quadrature degrees actually used (with automatic degree, those picked per face
    /// pair: 2 for Tri3-Tri3, 3 for Tri3-Quad4, 4 for a parallelogram Quad4 slave, 5 for other
    /// Quad4 slaves), as flags indexed by degree.
    pub degrees_used: [bool; 21],
    /// The inflation of the slave faces' search boxes, as a fraction of each face's diameter:
    /// 0 where the slave faces and the projector bound what the search must find by the nodes
    /// and nodal normals alone, else [`Tolerances::search_inflation`](crate::Tolerances::search_inflation)
    /// (see [`Padding`](crate::search::Padding)). 0 for the sorted merge, which uses no boxes.
    pub slave_box_inflation: f64,
    /// The same for the master faces' boxes: 0 where every master face lies in the convex hull
    /// of its nodes.
    pub master_box_inflation: f64,
    /// Slave faces whose search radius was widened beyond one face diameter to reach the
    /// nearest master surface ([`SearchRadius::Nearest`](crate::SearchRadius::Nearest), the
    /// default, when one face diameter left slave area uncovered); 0 otherwise.
    pub widened_search_faces: usize,
    /// The largest of those widened radii (0 when none was widened).
    pub widest_search: f64,
    /// Timings.
    pub seconds: PhaseSeconds,
}

/// The mortar coupling of an interface: D, M, the node maps and the slave nodal normals.
#[derive(Debug, Clone)]
pub struct Coupling {
    /// `D[j,k] = int Phi_j N_k^s` (slave x slave, CSR).
    pub d: SparseMatrix,
    /// `M[j,l] = int Phi_j N_l^m` (slave x master, CSR).
    pub m: SparseMatrix,
    /// Slave node tags in row order (ascending).
    pub slave_nodes: Vec<u64>,
    /// Master node tags in column order (ascending).
    pub master_nodes: Vec<u64>,
    /// Unit averaged nodal normals of the slave nodes, in row order.
    pub slave_normals: Vec<Vector3<f64>>,
    /// What was computed: multipliers, integration, projector.
    pub formulation: String,
    /// Counts and timings.
    pub stats: CouplingStats,
    /// What the coupling noticed without stopping: uncovered slave area, slave area covered
    /// more than once, skipped pairs, a dual D that is not diagonal.
    pub warnings: Vec<CouplingWarning>,
    /// With a space that recombines second-order slave faces
    /// ([`MultiplierFastPaths::recombines`](crate::multiplier::MultiplierFastPaths::recombines):
    /// dual multipliers on Tri6 or Quad8 faces), D in the
    /// recombined basis and the recombination; `None` where no slave face is recombined (or
    /// second-order faces of different kinds share an edge node, so that no one recombination
    /// serves: see [`slave_recombination`]).
    pub recombined: Option<Recombined>,
}

/// The mortar coupling in the recombined basis of second-order slave faces (Popp, Gee and
/// Wall 2012; see [`DualMultipliers`](crate::multiplier::DualMultipliers)): with the slave
/// shape functions `N~ = T N` and the slave unknowns `u~ = T^-T u` (so `u = T^T u~`), the
/// constraint `D u_s - M u_m = 0` reads `D~ u~_s - M u_m = 0` with `D~ = D T^T`, M unchanged.
/// For dual multipliers `D~` is diagonal on a covered interface, so that
/// `u_s = T^T D~^-1 M u_m`.
#[derive(Debug, Clone)]
pub struct Recombined {
    /// `D~ = D T^T` (slave x slave, CSR), its off-diagonal round-off (at most 1e-12 of the
    /// diagonal) lumped into the diagonal as a dual D's.
    pub d: SparseMatrix,
    /// `T` of `N~ = T N` over the slave rows (slave x slave, CSR): the identity on the rows of
    /// nodes of faces not recombined; on those of recombined faces, `1 - 2 alpha` on the
    /// diagonal of an edge node and `alpha`
    /// ([`RECOMBINATION_ALPHA`](crate::multiplier::RECOMBINATION_ALPHA)) from each of its
    /// corners.
    pub t: SparseMatrix,
    /// Off-diagonal entries of `D~` lumped into its diagonal, those of D included.
    pub d_roundoff_dropped: usize,
    /// The largest of them, relative to its diagonal entry.
    pub d_roundoff_largest: f64,
}

impl Coupling {
    /// The weighted gap vectors `G = D x_s - M x_m`, one per slave node (row order), for slave
    /// positions `x_s` (row order) and master positions `x_m` (column order). Its entries are
    /// products of three lengths (an area and a position in 3D): finite for coordinates up to
    /// about 1e100, a narrower range than D and M's
    /// ([`MAX_COORDINATE`](crate::tolerances::MAX_COORDINATE)).
    ///
    /// # Panics
    /// If the lengths of `x_s` and `x_m` do not match the node counts.
    pub fn weighted_gap(&self, x_s: &[Vector3<f64>], x_m: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
        assert_eq!(
            x_s.len(),
            self.slave_nodes.len(),
            "one slave position per row"
        );
        assert_eq!(
            x_m.len(),
            self.master_nodes.len(),
            "one master position per column"
        );
        let mut g = vec![Vector3::zeros(); self.slave_nodes.len()];
        for (row, gj) in g.iter_mut().enumerate() {
            if let Some(r) = self.d.outer_view(row) {
                for (k, v) in r.iter() {
                    *gj += x_s[k] * *v;
                }
            }
            if let Some(r) = self.m.outer_view(row) {
                for (l, v) in r.iter() {
                    *gj -= x_m[l] * *v;
                }
            }
        }
        g
    }

    /// The weighted normal gaps `g_j = -n_j . G_j`, positive where the surfaces are apart
    /// (the slave normal points out of the slave body, towards the master).
    pub fn normal_gaps(&self, x_s: &[Vector3<f64>], x_m: &[Vector3<f64>]) -> Vec<f64> {
        self.weighted_gap(x_s, x_m)
            .iter()
            .zip(&self.slave_normals)
            .map(|(g, n)| -n.dot(g))
            .collect()
    }

    /// The quadrature degrees used, ascending.
    pub fn degrees_used(&self) -> Vec<u32> {
        (0..21u32)
            .filter(|&d| self.stats.degrees_used[d as usize])
            .collect()
    }

    /// The current slave node positions of `interface`, in row order.
    pub fn slave_positions(&self, interface: &Interface) -> Vec<Vector3<f64>> {
        let c = interface.slave().coords();
        interface
            .slave_nodes()
            .iter()
            .map(|&n| c[n as usize])
            .collect()
    }

    /// The current master node positions of `interface`, in column order.
    pub fn master_positions(&self, interface: &Interface) -> Vec<Vector3<f64>> {
        let c = interface.master().coords();
        interface
            .master_nodes()
            .iter()
            .map(|&n| c[n as usize])
            .collect()
    }
}

/// Buffers a worker reuses from chunk to chunk, so that only the compressed results grow.
#[derive(Default)]
struct ChunkWorkspace {
    geometry: Vec<FaceGeometry>,
    /// Per face of the chunk, the rows in D of its nodes.
    rows: Vec<[u32; MAX_FACE_NODES]>,
    offsets: Vec<usize>,
    all: Vec<u32>,
    scratch: Vec<u32>,
    /// The chain walk's blocks of master faces met by a search box.
    blocks: Vec<u32>,
    /// The tree's buffers for a group of slave faces.
    group: GroupScratch,
    face: FaceBuffers,
}

impl ChunkWorkspace {
    /// Gathers the slave faces `faces` of a chunk and the rows in D of their nodes, and
    /// clears what a chunk that failed may have left behind.
    ///
    /// The faces are gathered first, in a loop of independent reads (a file whose nodes are
    /// numbered far apart then costs its cache misses in parallel rather than one after the
    /// other between tree queries), and kept for the per-face work: into the faces of the
    /// chunk before, where there is one (a face is ~460 bytes, most of them unused).
    fn gather(&mut self, interface: &Interface, faces: &[u32]) {
        self.face.d.clear();
        self.face.m.clear();
        let slave_mesh = interface.slave();
        for (i, &s) in faces.iter().enumerate() {
            match self.geometry.get_mut(i) {
                Some(g) => interface.slave_face_into(s as usize, g),
                None => self.geometry.push(interface.slave_face(s as usize)),
            }
        }
        self.geometry.truncate(faces.len());
        self.rows.clear();
        self.rows.extend(faces.iter().map(|&s| {
            let mut rows = [0u32; MAX_FACE_NODES];
            for (r, &n) in rows.iter_mut().zip(slave_mesh.face(s as usize).nodes) {
                *r = interface
                    .slave_row(n)
                    .expect("face nodes are on the interface");
            }
            rows
        }));
    }

    /// The master candidates of each gathered face, `all[offsets[i]..offsets[i + 1]]`:
    /// the tree's, or the chain walk's (from the previous face's candidates when it is this
    /// face's neighbour; `start` is the chunk's first position in the processing order),
    /// kept within each face's radius along its normal for a widened search (`radii`).
    fn candidates(
        &mut self,
        interface: &Interface,
        ctx: &SegmentContext<'_>,
        search: &Search,
        radii: Option<&[f64]>,
        start: usize,
    ) {
        let Self {
            geometry,
            offsets,
            all,
            scratch,
            blocks,
            group,
            face: buffers,
            ..
        } = self;
        offsets.clear();
        offsets.push(0usize);
        all.clear();
        match search {
            Search::Tree { tree, .. } => {
                tree.candidates_of_group(interface, geometry, group, all, offsets);
            }
            Search::Lines {
                search, follows, ..
            } => {
                for (i, face) in geometry.iter().enumerate() {
                    let seeds = if i > 0 && follows[start + i] {
                        &all[offsets[i - 1]..offsets[i]]
                    } else {
                        &[]
                    };
                    let lines = &mut buffers.lines;
                    if seeds.is_empty()
                        || !search.walk(interface, ctx.masters, lines, face, seeds, scratch, blocks)
                    {
                        search.exhaustive(interface, ctx.masters, face, scratch);
                    }
                    all.extend_from_slice(scratch);
                    offsets.push(all.len());
                }
            }
        }
        if let Some(radii) = radii {
            // The boxes reach farther at a slant; see `keep_within_radius`.
            let mut kept = 0;
            for i in 0..geometry.len() {
                scratch.clear();
                scratch.extend_from_slice(&all[offsets[i]..offsets[i + 1]]);
                let face = &geometry[i];
                let radius = radii[face.index as usize];
                keep_within_radius(interface, ctx.masters, face, radius, scratch);
                all[kept..kept + scratch.len()].copy_from_slice(scratch);
                offsets[i] = kept;
                kept += scratch.len();
            }
            offsets[geometry.len()] = kept;
            all.truncate(kept);
        }
        // Each face meets its candidates by ascending master face index: its blocks are then
        // summed in an order the tree's layout (slabs and slots of this interface's master
        // faces) does not decide, the same in a part of the interface as in the whole.
        for i in 0..geometry.len() {
            sort_short_by_key(&mut all[offsets[i]..offsets[i + 1]], |&slot| {
                ctx.masters.face_index(slot as usize)
            });
        }
    }
}

/// The buffers of one slave face's work, and the chunk's entries of D and M, summed as they come.
#[derive(Default)]
struct FaceBuffers {
    rule: PairedRule,
    blocks: LocalBlocks,
    /// The face's M entries merged by master node.
    columns: MergedColumns,
    /// The fused kernel's result.
    line: LineFace,
    /// The master lines of the chain walk and the fused kernel.
    lines: MasterLineCache,
    /// The master faces and the slave face's set-up of the closed forms.
    closed: ClosedFormScratch,
    /// The M blocks of a face by moments, until it is known to be integrated so.
    pending: Vec<PendingBlock>,
    /// Positions of a face's columns by ascending column ([`push_face_rows`]).
    order: Vec<u32>,
    d: RowAccumulator,
    m: RowAccumulator,
}

/// Fills `order` with the positions of `keys` by ascending key.
fn ascending_positions(keys: &[u32], order: &mut Vec<u32>) {
    order.clear();
    order.extend(0..keys.len() as u32);
    sort_short_by_key(order, |&p| keys[p as usize]);
}

/// Pushes one slave face's rows of D and M: for each node `j` of the face whose multiplier it
/// carries, the row `rows[j]` of D, `d(j, k)` in the column `rows[k]`, and of M, `m(j, p)` in
/// the column `cols[p]`. Each entry is pushed once per face, so the order of the face's
/// pushes does not change the sums. A face of more than [`RowAccumulator::SHORT`] columns
/// (3D) pushes its rows of M with their columns ascending, as the accumulator merges such
/// rows; `order` is scratch.
fn push_face_rows(
    (d, m): (&mut RowAccumulator, &mut RowAccumulator),
    order: &mut Vec<u32>,
    rows: &[u32],
    carries: impl Fn(usize) -> bool,
    d_of: impl Fn(usize, usize) -> f64,
    cols: &[u32],
    m_of: impl Fn(usize, usize) -> f64,
) {
    for (j, &r) in rows.iter().enumerate().filter(|(j, _)| carries(*j)) {
        d.push_row(r, rows.iter().enumerate().map(|(k, &c)| (c, d_of(j, k))));
    }
    if cols.len() > RowAccumulator::SHORT {
        ascending_positions(cols, order);
        for (j, &r) in rows.iter().enumerate().filter(|(j, _)| carries(*j)) {
            let entries = order.iter().map(|&p| p as usize);
            m.push_sorted_row(r, entries.map(|p| (cols[p], m_of(j, p))));
        }
    } else {
        for (j, &r) in rows.iter().enumerate().filter(|(j, _)| carries(*j)) {
            m.push_row(r, cols.iter().enumerate().map(|(p, &c)| (c, m_of(j, p))));
        }
    }
}

/// One slave face's M entries merged by master node: a slave face meets ~10 master faces
/// sharing far fewer nodes, so this cuts the entries about threefold. Columns in the order
/// first met (found through `index`), so the sums are the same whatever the count.
#[derive(Default)]
struct MergedColumns {
    /// The master columns the face meets, in the order first met.
    cols: Vec<u32>,
    /// Their M values, `ks` per column (one per node of the face).
    vals: Vec<f64>,
    /// Where each column is in `cols`.
    index: KeyIndex,
    /// The face's node count.
    ks: usize,
}

impl MergedColumns {
    /// Starts a slave face of `ks` nodes.
    fn start_face(&mut self, ks: usize) {
        self.cols.clear();
        self.vals.clear();
        self.index.clear();
        self.ks = ks;
    }

    /// Adds the `ks x km` block (row-major) of the master face in slot `mf` to its columns.
    fn add(&mut self, ctx: &SegmentContext<'_>, mf: u32, km: usize, block: &[f64]) {
        let mut mcols = [0u32; MAX_FACE_NODES];
        let kc = ctx
            .masters
            .columns_into(ctx.interface, mf as usize, &mut mcols);
        debug_assert_eq!(kc, km);
        self.add_cols(&mcols[..kc], block);
    }

    /// Adds the `ks x km` block (row-major) of a master face whose nodes have the columns
    /// `mcols` (`km` of them).
    fn add_cols(&mut self, mcols: &[u32], block: &[f64]) {
        let (ks, km) = (self.ks, mcols.len());
        for (l, &c) in mcols.iter().enumerate() {
            let at = match self.index.find_in(&self.cols, c) {
                Some(at) => at,
                None => {
                    // The new column's sums start from zero (`0.0 + b`, as `+=` on a zeroed
                    // entry gives: a block's -0.0 becomes 0.0).
                    self.cols.push(c);
                    for j in 0..ks {
                        self.vals.push(0.0 + block[j * km + l]);
                    }
                    self.index.pushed(c, self.cols.len() - 1);
                    continue;
                }
            };
            let vals = &mut self.vals[at * ks..(at + 1) * ks];
            for (j, v) in vals.iter_mut().enumerate() {
                *v += block[j * km + l];
            }
        }
    }
}

/// How a coupling finds each slave face's master faces.
enum Search {
    /// The tree over the master faces, queried face by face; with the strategy's exact
    /// segmentation when the clip polygons are integrated in closed form (3D, linear
    /// triangles and bilinear quads).
    Tree {
        tree: MasterTree,
        closed_form: Option<ClosedForm>,
    },
    /// Straight two-node lines in chains on both sides, with a strategy that segments them
    /// exactly: a walk along the master's chains, and the fused kernel.
    Lines {
        search: ChainSearch,
        /// Per position in the processing order, whether the slave face before it is its
        /// neighbour along the slave's chain (so that the walk may start from its
        /// candidates).
        follows: Vec<bool>,
        rule: LineSegments,
    },
}

/// The order in which a coupling processes its slave faces, cut into chunks.
struct FaceOrder {
    /// Face indices in processing order.
    faces: Vec<u32>,
    /// Each chunk's key and its positions in `faces`.
    chunks: Vec<(u64, std::ops::Range<usize>)>,
}

impl Search {
    /// The search of `interface` for `options`, the master faces by slot and the order in
    /// which the slave faces are processed, in chunks.
    /// `lines` are [`line_chains`]'s.
    ///
    /// The chunks are cells of the Morton order of the slave faces' first nodes (in the whole
    /// interface's box and buckets, for a part: see [`WholeInterface`](super::WholeInterface)),
    /// so that which faces share a chunk depends on where they are, not on how many faces the
    /// interface has elsewhere. The tree takes the faces in that order: the queries of a chunk
    /// then walk the same branches of the tree, whatever the file's numbering (by their first
    /// nodes: one read of the node coordinates per face, in the file's order, which may be
    /// random). The chain walk takes each chunk's faces along their chains.
    fn build(
        interface: &Interface,
        options: &CouplingOptions,
        lines: Option<(LineSegments, LineChains, LineChains)>,
        padding: Padding,
        radii: Option<Arc<[f64]>>,
    ) -> (Self, MasterFaces, FaceOrder) {
        let slave = interface.slave();
        let planar = interface.dim() == SpatialDim::Two;
        let whole = options.whole.as_deref();
        let keys = spatial_keys(
            slave.face_count(),
            |f| anchor(slave, f),
            planar,
            whole.map(|w| &w.anchors),
        );
        let own_plan;
        let plan = match whole {
            Some(w) => &w.plan,
            None => {
                own_plan = ChunkPlan::of_keys(&keys, interface.dim());
                &own_plan
            }
        };
        if let Some((rule, slave_chains, master)) = lines {
            let masters = MasterFaces::new(interface, master.order.iter().copied());
            debug_assert_eq!(
                padding.master, 0.0,
                "two-node lines lie in their nodes' box"
            );
            let search = ChainSearch::new(interface, &masters, master, padding.slave, radii);
            // Each face's chunk, then the chain positions by chunk (stable: along the chains
            // within a chunk).
            let mut chunk_of = vec![0u32; slave.face_count()];
            for &k in &keys {
                chunk_of[k as u32 as usize] = plan.chunk_of((k >> 32) as u64) as u32;
            }
            drop(keys);
            let mut positions: Vec<u32> = (0..slave_chains.order.len() as u32).collect();
            positions.sort_by_key(|&p| chunk_of[slave_chains.order[p as usize] as usize]);
            let follows = (0..positions.len())
                .map(|q| q > 0 && slave_chains.prev[positions[q] as usize] == positions[q - 1])
                .collect();
            let faces: Vec<u32> = positions
                .iter()
                .map(|&p| slave_chains.order[p as usize])
                .collect();
            let chunks = plan.ranges(faces.len(), |q| chunk_of[faces[q] as usize] as usize);
            let lines = Search::Lines {
                search,
                follows,
                rule,
            };
            return (lines, masters, FaceOrder { faces, chunks });
        }
        let (tree, masters) = MasterTree::build_with_faces(interface, padding);
        let tree = tree.with_radii(radii);
        let chunks = plan.ranges(keys.len(), |p| plan.chunk_of((keys[p] >> 32) as u64));
        let faces = keys.into_iter().map(|k| k as u32).collect();
        let closed_form = SegmentBased::of(options.integration.as_ref()).and_then(|s| {
            closed_form::applies(interface, s.polygon_segments(), whole_types(options))
        });
        let search = Search::Tree { tree, closed_form };
        (search, masters, FaceOrder { faces, chunks })
    }
}

/// The element types of both sides of the whole interface, where the interface is a part.
fn whole_types(options: &CouplingOptions) -> Option<(&[ElementRef], &[ElementRef])> {
    options
        .whole
        .as_deref()
        .map(|w| (&w.slave_types[..], &w.master_types[..]))
}

/// The strategy's rule when the fused kernel (and the sorted merge of a straight interface)
/// may apply: a 2D interface whose faces are all straight two-node lines with linear shape
/// functions, and a strategy that segments such lines exactly.
fn line_rule(interface: &Interface, options: &CouplingOptions) -> Option<LineSegments> {
    if interface.dim() != SpatialDim::Two {
        return None;
    }
    let rule = SegmentBased::of(options.integration.as_ref())?.line_segments();
    let (slave, master) = whole_types(options).unwrap_or((
        interface.slave().element_types(),
        interface.master().element_types(),
    ));
    let types = slave.iter().chain(master);
    types.copied().all(is_linear_line).then_some(rule)
}

/// The chains of both sides, if both are chains (no branch, oriented alike).
fn line_chains(
    interface: &Interface,
    options: &CouplingOptions,
) -> Option<(LineChains, LineChains)> {
    // A part of a whole whose sides are not both chains searches as the whole does.
    if options.whole.as_ref().is_some_and(|w| !w.chains) {
        return None;
    }
    // Both sides at once: each chain walk is sequential.
    let (slave, master) = rayon::join(
        || LineChains::of(interface.slave()),
        || LineChains::of(interface.master()),
    );
    slave.zip(master)
}

/// Counts and timings summed over chunks.
#[derive(Default, Clone, Copy)]
struct ChunkStats {
    candidates: usize,
    pairs: usize,
    segments: usize,
    back_facing: usize,
    skipped: usize,
    uncovered_area: f64,
    without_partner: usize,
    partly_covered: usize,
    overlapped: usize,
    overlapped_area: f64,
    fused: usize,
    straight: usize,
    closed_form: usize,
    degrees: u32,
    seconds_search: f64,
    seconds_segments: f64,
    seconds_integration: f64,
    /// The largest search radius of an uncovered slave face.
    uncovered_reach: f64,
}

impl ChunkStats {
    fn add(&mut self, o: &ChunkStats) {
        self.uncovered_reach = self.uncovered_reach.max(o.uncovered_reach);
        self.candidates += o.candidates;
        self.pairs += o.pairs;
        self.segments += o.segments;
        self.back_facing += o.back_facing;
        self.skipped += o.skipped;
        self.uncovered_area += o.uncovered_area;
        self.without_partner += o.without_partner;
        self.partly_covered += o.partly_covered;
        self.overlapped += o.overlapped;
        self.overlapped_area += o.overlapped_area;
        self.fused += o.fused;
        self.straight += o.straight;
        self.closed_form += o.closed_form;
        self.degrees |= o.degrees;
        self.seconds_search += o.seconds_search;
        self.seconds_segments += o.seconds_segments;
        self.seconds_integration += o.seconds_integration;
    }

    /// Counts one batch's paired rule (its pairs, cells, back-facing and skipped pairs, and
    /// degrees), and keeps the face's first skipped pair.
    #[inline]
    fn tally(&mut self, rule: &mut PairedRule, first_skipped: &mut Option<MortarError>) {
        self.pairs += rule.pairs as usize;
        self.segments += rule.cells as usize;
        self.back_facing += rule.back_facing as usize;
        self.skipped += rule.skipped as usize;
        self.degrees |= rule.degrees;
        if first_skipped.is_none() {
            *first_skipped = rule.first_skipped.take();
        }
    }

    /// Counts a slave face whose points miss the fraction `missing` of it (negative: cover
    /// it more than once) beyond the tolerance `coverage`, and notes its tag.
    fn count_coverage(
        &mut self,
        face: &FaceGeometry,
        missing: f64,
        coverage: f64,
        notes: &mut FaceNotes,
    ) {
        if missing > coverage {
            self.partly_covered += 1;
            self.uncovered_area += missing * face.measure();
            note(&mut notes.uncovered, face.tag);
        } else if -missing > coverage {
            self.overlapped += 1;
            self.overlapped_area += -missing * face.measure();
            note(&mut notes.overlapped, face.tag);
        }
    }
}

/// What one worker accumulates: its buffers, its compressed parts of D and M (keyed by chunk),
/// its counts, the first error it met (with its chunk), the first skipped pair (with its
/// position in the processing order) and the smallest tags of uncovered and of doubly
/// covered slave faces.
#[derive(Default)]
struct Accumulator {
    ws: ChunkWorkspace,
    d: PartList,
    m: PartList,
    stats: ChunkStats,
    error: Option<(usize, MortarError)>,
    first_skipped: Option<(usize, MortarError)>,
    uncovered: Vec<u64>,
    overlapped: Vec<u64>,
}

impl Accumulator {
    /// An accumulator for about `chunks` chunks.
    fn expecting(chunks: usize) -> Self {
        Self {
            d: PartList::expecting(chunks),
            m: PartList::expecting(chunks),
            ..Self::default()
        }
    }

    /// The workers' accumulators as one: the first error and the first skipped pair in
    /// slave-face order, the smallest tags, the summed counts and every part of D and M.
    fn merged(accs: Vec<Accumulator>) -> Self {
        let mut total = Accumulator::default();
        for acc in accs {
            if let Some((c, e)) = acc.error {
                if total.error.as_ref().is_none_or(|(k, _)| c < *k) {
                    total.error = Some((c, e));
                }
            }
            if let Some((at, e)) = acc.first_skipped {
                total.keep_first_skipped(at, e);
            }
            total.add_notes(&acc.uncovered, &acc.overlapped);
            total.stats.add(&acc.stats);
            total.d.append(acc.d);
            total.m.append(acc.m);
        }
        total
    }

    /// Keeps the earlier of two first-skipped records.
    fn keep_first_skipped(&mut self, at: usize, e: MortarError) {
        if self.first_skipped.as_ref().is_none_or(|(k, _)| at < *k) {
            self.first_skipped = Some((at, e));
        }
    }

    /// Adds a chunk's (or a worker's) tags of uncovered and of doubly covered slave
    /// faces, keeping the smallest few of each.
    fn add_notes(&mut self, uncovered: &[u64], overlapped: &[u64]) {
        for (kept, tags) in [
            (&mut self.uncovered, uncovered),
            (&mut self.overlapped, overlapped),
        ] {
            kept.extend_from_slice(tags);
            kept.sort_unstable();
            kept.dedup();
            kept.truncate(CouplingWarning::EXAMPLES);
        }
    }
}

/// With dual multipliers, off-diagonal entries of D at most this times their row's diagonal
/// entry are round-off of the biorthogonal basis (1e-16 to 1e-14 in practice): they are
/// added to the diagonal and dropped. Larger ones (a partly covered face, a warped quad)
/// are kept.
pub const ROUNDOFF: f64 = 1e-12;

/// What [`drop_roundoff`] did.
#[derive(Debug, Clone, Copy, Default)]
struct RoundoffDropped {
    count: usize,
    largest: f64,
}

/// The off-diagonal entries of a matrix.
#[derive(Debug, Clone, Default)]
struct OffDiagonal {
    /// How many.
    count: usize,
    /// The largest relative to its row's diagonal entry (infinite on a row without one).
    largest: f64,
    /// The rows that have them.
    rows: usize,
    /// The first of those rows (at most [`CouplingWarning::EXAMPLES`]).
    examples: Vec<usize>,
}

fn off_diagonal(d: &SparseMatrix) -> OffDiagonal {
    let mut out = OffDiagonal::default();
    for (r, row) in d.outer_iterator().enumerate() {
        let diag = row.get(r).copied().unwrap_or(0.0).abs();
        let before = out.count;
        for (c, v) in row.iter() {
            if c != r {
                out.count += 1;
                out.largest = out.largest.max(v.abs() / diag);
            }
        }
        if out.count > before {
            out.rows += 1;
            if out.examples.len() < CouplingWarning::EXAMPLES {
                out.examples.push(r);
            }
        }
    }
    out
}

/// `d` with the off-diagonal entries at most `tol` times their row's diagonal entry added to
/// the diagonal and removed.
fn drop_roundoff(d: &SparseMatrix, tol: f64) -> (SparseMatrix, RoundoffDropped) {
    let mut out = RoundoffDropped::default();
    let (mut indptr, mut indices, mut data) = (vec![0usize], Vec::new(), Vec::new());
    for (r, row) in d.outer_iterator().enumerate() {
        let diag = row.get(r).copied().unwrap_or(0.0);
        let mut lumped = 0.0;
        let mut diag_at = None;
        for (c, &v) in row.iter() {
            if c != r && v.abs() <= tol * diag.abs() {
                lumped += v;
                out.count += 1;
                out.largest = out.largest.max(v.abs() / diag.abs());
                continue;
            }
            if c == r {
                diag_at = Some(data.len());
            }
            indices.push(c);
            data.push(v);
        }
        if let Some(at) = diag_at {
            data[at] += lumped;
        }
        indptr.push(data.len());
    }
    (SparseMatrix::new(d.shape(), indptr, indices, data), out)
}

/// Computes D and M for an interface.
///
/// The master faces are found by a search tree, and each slave face is segmented and
/// integrated by `options.integration`, except on a 2D interface whose faces are all straight
/// two-node lines in chains (as `Interface::new` leaves a line interface: no branch, faces
/// oriented alike) with the strategy [`SegmentBased`](crate::integration::SegmentBased) (found
/// by its type: a strategy of one's own, a wrapper of it included, takes the general path):
/// there the search is a merge, a walk along the master's chains from the previous slave
/// face's partners (slave faces in chain order), and each face is segmented and integrated in
/// one fused loop, without the paired points in between. The fused kernel does the strategy's
/// operations on the same numbers (D and M agree with the general path's to round-off, about
/// 1e-16 of their largest entry; only the order of summation differs). A face it does not
/// settle (covered in part by the walk's partners, or more than once, a failed projection,
/// a direction field that is not affine) goes through the strategy with every candidate of
/// the exhaustive query, so warnings and skipped pairs are those of the general path. Where
/// the master has more than one chain, each walk also asks the master blocks' tree whether a
/// face of another chain meets the slave face's search box, and if one does the face takes the
/// exhaustive query: a second master layer over a face is found and reported
/// ([`CouplingWarning::OverlappingMasterFaces`]) as on the general path (arc2d at 10^6 with its
/// master in two chains: 1.13x the time of one chain). Not looked for: a master of one chain
/// that spirals round to face the same slave face again within the search radius.
/// [`CouplingStats::fused_line_faces`] says how many faces the fused kernel took (line2d at
/// 10^6 slave faces, one thread: 1.44x faster end to end).
///
/// A straight 2D interface goes before that to a sorted merge: both sides one open chain of
/// such lines, a projector whose direction is one vector on the whole slave
/// ([`ProjectorFastPaths::uniform_direction`](crate::projector::ProjectorFastPaths::uniform_direction):
/// the built-in ones on a straight slave), a multiplier space with one basis for every face
/// ([`MultiplierFastPaths::basis_is_uniform`](crate::multiplier::MultiplierFastPaths::basis_is_uniform):
/// standard, and dual in the Cartesian measure), the master facing the slave within the
/// search radius and covering every slave face. Projection is then a coordinate along the
/// line: the pairs come from merging the two sides' sorted node coordinates, and each row of
/// D and M is computed from the two slave faces about its node and written in place (the
/// same Gauss points of each overlap as the general path; D and M agree with it to
/// round-off). [`CouplingStats::straight_line_faces`] says whether it ran (all the slave
/// faces or none; line2d at 10^6 slave faces, one thread: 3.1x faster than the fused kernel
/// end to end).
///
/// A 3D interface whose faces are all linear triangles or flat bilinear quads, with the
/// strategy [`SegmentBased`](crate::integration::SegmentBased) (found by its type) of a degree
/// that integrates the integrands exactly, has the clip polygons of each pair integrated in
/// closed form instead of the strategy's points (the integrals of any exact quadrature, to
/// round-off; [`CouplingStats::closed_form_faces`]).
///
/// What the fast paths read of the plug-ins: the strategy's type (above) and whether it
/// splits over candidates
/// ([`IntegrationFastPaths`](crate::integration::IntegrationFastPaths)); the projector's
/// affine, uniform and bounded directions
/// ([`ProjectorFastPaths`](crate::projector::ProjectorFastPaths)); the space's diagonal D,
/// recombination and uniform basis
/// ([`MultiplierFastPaths`](crate::multiplier::MultiplierFastPaths)). A plug-in that states
/// none of these gets the same D and M, to round-off, on the general path.
///
/// # Errors
/// [`MortarError::NoOverlap`] when no slave face overlaps a master face; the errors of the
/// integration strategy and the multiplier space (the first in slave-face order);
/// [`MortarError::InvalidOption`] for a thread count of zero or above
/// [`MAX_THREADS_PER_CORE`] per core, or a pool that cannot start.
///
/// The pool of each thread count is built on the first call that asks for it and kept for
/// the next calls (a few thread counts at a time): a coupling repeated at every Newton step
/// does not start threads each time. With [`CouplingOptions::threads`] `None`, a call made
/// on a rayon pool's thread runs on that pool: an application that runs the library inside
/// its own pool keeps to that pool's threads.
pub fn assemble_coupling(interface: &Interface, options: &CouplingOptions) -> Result<Coupling> {
    assemble_with(interface, options, Spare::default())
}

/// [`assemble_coupling`], writing D and M into the arrays of `previous` (an earlier
/// coupling, of this interface or another) where it can: the same result, bit for bit,
/// without asking the system for fresh memory.
///
/// A coupling repeated at every step of a moving interface (contact, a Newton loop on the
/// deformed geometry) otherwise gets fresh pages for its output each time. On a virtual
/// machine each 4 KiB page costs a trap, its allocation and its zeroing: a fifth of a
/// coupling of 10^6 straight line faces on this project's benchmark machine, which this
/// takes away (`bench_coupling --reuse`: 89 -> 70 ns per pair on one thread, the same
/// peak memory; see `docs/performance.md`).
///
/// Which couplings write into `previous`'s arrays: those of a straight 2D interface taken
/// by the sorted merge ([`CouplingStats::straight_line_faces`]), which writes D and M in
/// place, each array into the smallest of `previous` that holds it (a fresh one where none
/// does). Every other coupling frees `previous` first and runs as [`assemble_coupling`]:
/// it holds its parts while it works and frees them before D and M take their memory, so
/// spare arrays held beside the parts would raise its peak by their size (plane3d at 10^6
/// slave faces: memory ratio 1.39 -> 1.82) for 1.5-7 % of its time. `previous`'s node lists
/// are freed too: written from memory the call has just freed, they cost no fresh pages.
///
/// ```
/// use mortar_core::{assemble_coupling, assemble_coupling_reusing};
/// use mortar_core::{Coupling, CouplingOptions, Interface, Result};
///
/// /// The coupling of each geometry in turn, each written into the previous one's arrays.
/// fn couple_each(
///     steps: impl IntoIterator<Item = Interface>,
///     options: &CouplingOptions,
/// ) -> Result<Option<Coupling>> {
///     let mut last: Option<Coupling> = None;
///     for interface in steps {
///         last = Some(match last {
///             Some(previous) => assemble_coupling_reusing(&interface, options, previous)?,
///             None => assemble_coupling(&interface, options)?,
///         });
///     }
///     Ok(last)
/// }
/// ```
///
/// # Errors
/// As [`assemble_coupling`] (`previous` is then dropped).
pub fn assemble_coupling_reusing(
    interface: &Interface,
    options: &CouplingOptions,
    previous: Coupling,
) -> Result<Coupling> {
    assemble_with(interface, options, spare_of(previous))
}

/// The arrays of `previous`'s D and M, for the next coupling to write into. Its node lists
/// are dropped: the coupling's own buffers, freed before the node lists are written, give
/// them memory already resident, and held through the call they would add to its peak
/// (line2d at 10^6 slave faces, later calls: 77 ns per pair kept, 70.5 dropped; memory
/// ratio 1.48 kept, 1.35 dropped).
fn spare_of(previous: Coupling) -> Spare {
    let mut spare = Spare::default();
    for matrix in [previous.d, previous.m] {
        let (indptr, indices, data) = matrix.into_raw_storage();
        spare.keep_usize(indptr);
        spare.keep_usize(indices);
        spare.keep_f64(data);
    }
    spare
}

/// [`assemble_coupling`] into the arrays of `spare`.
fn assemble_with(
    interface: &Interface,
    options: &CouplingOptions,
    spare: Spare,
) -> Result<Coupling> {
    check_geometry(interface, options)?;
    if options.threads.is_none() && rayon::current_thread_index().is_some() {
        return assemble_on_pool(interface, options, rayon::current_num_threads(), spare);
    }
    let pool = super::pool::pool(options.threads)?;
    pool.install(|| assemble_on_pool(interface, options, pool.current_num_threads(), spare))
}

/// Refuses the axisymmetric measure on a 3D interface or with a node at a negative radius.
fn check_geometry(interface: &Interface, options: &CouplingOptions) -> Result<()> {
    if !options.geometry.is_axisymmetric() {
        return Ok(());
    }
    if interface.dim() == SpatialDim::Three {
        return Err(MortarError::AxisymmetricNeeds2D {
            slave_faces: interface.slave().face_count(),
        });
    }
    for (mesh, side) in [
        (interface.slave(), Side::Slave),
        (interface.master(), Side::Master),
    ] {
        if let Some((i, radius)) = options.geometry.first_negative_radius(mesh.coords()) {
            return Err(MortarError::NegativeRadius {
                side,
                node: mesh.node_tags()[i],
                radius,
            });
        }
    }
    Ok(())
}

/// The most worker threads per core [`assemble_coupling`] accepts: more only costs thread
/// start-up and memory (100000 threads took over a minute before any work).
pub const MAX_THREADS_PER_CORE: usize = 16;

fn assemble_on_pool(
    interface: &Interface,
    options: &CouplingOptions,
    threads: usize,
    mut spare: Spare,
) -> Result<Coupling> {
    let start = Instant::now();
    // A straight interface by the sorted merge; else the chains for the walk.
    let mut lines = None;
    if let Some(rule) = line_rule(interface, options) {
        let merged = straight_line::couple(interface, options, rule, &mut spare)?;
        if let Some(merged) = merged {
            drop(spare); // what D and M did not take
            return Ok(merged_coupling(interface, options, merged, threads, start));
        }
        lines = line_chains(interface, options).map(|(s, m)| (rule, s, m));
    }
    // The general path holds its parts while it works and frees them before D and M take
    // their memory: spare arrays held beside the parts would add their size to the peak
    // (plane3d n=708 reusing its own arrays: memory ratio 1.39 -> 1.82, for 1.5 % of the
    // time on one thread).
    drop(spare);
    let first = general_path(interface, options, threads, lines, None, start);
    let SearchRadius::Nearest { bound } = interface.tolerances().search_radius else {
        return first;
    };
    if !leaves_area_uncovered(&first) {
        return first;
    }
    // One face diameter left slave area uncovered: each slave face's radius widened to the
    // nearest master surface, and the interface coupled again with those radii.
    let padding = Padding::of(interface, Some(options.projector.as_ref()));
    let radii = nearest_master_radii(interface, padding, bound);
    let widened = radii.iter().filter(|r| r.is_some()).count();
    if widened == 0 {
        return first;
    }
    drop(first);
    let widest = radii.iter().flatten().fold(0.0f64, |a, r| a.max(*r));
    let radii: Arc<[f64]> = radii
        .iter()
        .enumerate()
        .map(|(f, r)| {
            r.unwrap_or_else(|| face_search_radius(interface, &interface.slave_face(f), None))
        })
        .collect();
    let lines = line_rule(interface, options)
        .and_then(|rule| line_chains(interface, options).map(|(s, m)| (rule, s, m)));
    let mut coupling = general_path(interface, options, threads, lines, Some(radii), start)?;
    coupling.stats.widened_search_faces = widened;
    coupling.stats.widest_search = widest;
    Ok(coupling)
}

/// Whether a coupling's result says that slave area was left uncovered: a warning of it, or
/// the error of no overlap at all or of incomplete coverage (with
/// [`CouplingOptions::require_full_coverage`]) for it.
fn leaves_area_uncovered(result: &Result<Coupling>) -> bool {
    let uncovered = |w: &CouplingWarning| matches!(w, CouplingWarning::UncoveredSlaveArea { .. });
    match result {
        Ok(c) => c.warnings.iter().any(uncovered),
        Err(MortarError::NoOverlap { .. }) => true,
        Err(MortarError::IncompleteCoverage(w)) => uncovered(w),
        Err(_) => false,
    }
}

/// The general path of [`assemble_coupling`]: the search (the tree, or the walk along the
/// chains of straight lines `lines`), then each chunk of slave faces segmented, integrated
/// and scattered; with `radii`, each slave face's search radius by face index.
fn general_path(
    interface: &Interface,
    options: &CouplingOptions,
    threads: usize,
    lines: Option<(LineSegments, LineChains, LineChains)>,
    radii: Option<Arc<[f64]>>,
    start: Instant,
) -> Result<Coupling> {
    let padding = Padding::of(interface, Some(options.projector.as_ref()));
    let (search, masters, order) = Search::build(interface, options, lines, padding, radii.clone());
    let FaceOrder {
        faces: order,
        chunks: chunk_ranges,
    } = order;
    let ctx = SegmentContext {
        interface,
        projector: options.projector.as_ref(),
        masters: &masters,
    };
    let faces = interface.slave().face_count();
    let tree_seconds = start.elapsed().as_secs_f64();
    // Each worker folds its chunks into one accumulator (its buffers and its part lists); the
    // first failing chunk in slave-face order decides the error, and chunks after a known
    // failure are skipped. Parts are keyed by chunk, so which worker took which chunk does not
    // change a bit of D and M.
    let first_error = AtomicUsize::new(usize::MAX);
    let chunks = chunk_ranges.len();
    // One accumulator per worker, the chunks handed out one at a time from a counter (each
    // worker takes the next as it finishes one, whatever the faces cost), so that each
    // worker's part buffers can be sized for its share at once.
    let share = chunks.div_ceil(threads);
    let next = AtomicUsize::new(0);
    let accs: Vec<Accumulator> = rayon::broadcast(|_| {
        let mut acc = Accumulator::expecting(share);
        loop {
            let c = next.fetch_add(1, Ordering::Relaxed);
            if c >= chunks {
                return acc;
            }
            if c > first_error.load(Ordering::Relaxed) {
                continue;
            }
            let (key, range) = chunk_ranges[c].clone();
            if let Err(e) = chunk(
                interface,
                options,
                &ctx,
                &search,
                radii.as_deref(),
                &order,
                range,
                key,
                &mut acc,
            ) {
                first_error.fetch_min(c, Ordering::Relaxed);
                if acc.error.as_ref().is_none_or(|(k, _)| c < *k) {
                    acc.error = Some((c, e));
                }
            }
        }
    });

    // What only the per-face work needed goes before the matrices are built.
    drop((search, order, chunk_ranges, masters));
    let t_asm = Instant::now();
    let faces_seconds = (t_asm - start).as_secs_f64() - tree_seconds;
    let total = Accumulator::merged(accs);
    if let Some((_, e)) = total.error {
        return Err(e);
    }
    let stats = total.stats;
    let examples = (total.uncovered, total.overlapped);
    let warnings = coupling_warnings(interface, &stats, total.first_skipped, examples);
    if options.require_full_coverage {
        if let Some(w) = warnings.first() {
            return Err(MortarError::IncompleteCoverage(Box::new(w.clone())));
        }
    }
    if stats.pairs == 0 {
        return Err(MortarError::NoOverlap {
            slave_faces: faces,
            master_faces: interface.master().face_count(),
            candidates: stats.candidates,
            back_facing: stats.back_facing,
        });
    }
    let ns = interface.slave_nodes().len();
    let nm = interface.master_nodes().len();
    let d = total.d.to_csr(ns, ns);
    let m = total.m.to_csr(ns, nm);
    let mut warnings = warnings;
    if let Some(w) = master_coverage::overlapping_slave_faces(interface, options, &m) {
        if options.require_full_coverage {
            return Err(MortarError::IncompleteCoverage(Box::new(w)));
        }
        warnings.push(w);
    }
    let seconds = PhaseSeconds {
        tree: tree_seconds,
        faces: faces_seconds,
        assembly: 0.0,
        total: 0.0,
        thread: ThreadSeconds {
            search: stats.seconds_search,
            segments: stats.seconds_segments,
            integration: stats.seconds_integration,
        },
    };
    let mut coupling = finish(
        interface, options, d, m, &stats, warnings, threads, seconds, start, t_asm,
    );
    coupling.stats.slave_box_inflation = padding.slave;
    coupling.stats.master_box_inflation = padding.master;
    Ok(coupling)
}

/// The coupling of a straight 2D interface from the sorted merge's D and M.
fn merged_coupling(
    interface: &Interface,
    options: &CouplingOptions,
    merged: straight_line::Merged,
    threads: usize,
    start: Instant,
) -> Coupling {
    let faces = interface.slave().face_count();
    let merge = (merged.rows_start - merged.merge_start).as_secs_f64();
    let stats = ChunkStats {
        candidates: merged.pairs,
        pairs: merged.pairs,
        segments: merged.pairs,
        straight: faces,
        degrees: 1 << merged.degree,
        ..ChunkStats::default()
    };
    let seconds = PhaseSeconds {
        tree: (merged.merge_start - start).as_secs_f64(),
        faces: merge,
        assembly: 0.0,
        total: 0.0,
        thread: ThreadSeconds {
            search: merge,
            segments: 0.0,
            integration: 0.0,
        },
    };
    let t_asm = merged.rows_start;
    finish(
        interface,
        options,
        merged.d,
        merged.m,
        &stats,
        Vec::new(),
        threads,
        seconds,
        start,
        t_asm,
    )
}

/// The coupling from D and M (a dual D's round-off dropped here), the counts, the warnings
/// and the phases' seconds (`assembly` and `total` measured here from `t_asm` and `start`).
#[allow(clippy::too_many_arguments)]
fn finish(
    interface: &Interface,
    options: &CouplingOptions,
    mut d: SparseMatrix,
    m: SparseMatrix,
    stats: &ChunkStats,
    warnings: Vec<CouplingWarning>,
    threads: usize,
    mut seconds: PhaseSeconds,
    start: Instant,
    t_asm: Instant,
) -> Coupling {
    let mut roundoff = RoundoffDropped::default();
    let mut recombined = None;
    let mut off = OffDiagonal::default();
    if options
        .multipliers
        .fast_paths()
        .is_some_and(|f| f.diagonal_d())
    {
        (d, roundoff) = drop_roundoff(&d, ROUNDOFF);
        recombined = recombine(interface, options.multipliers.as_ref(), &d, roundoff);
        off = off_diagonal(recombined.as_ref().map_or(&d, |r| &r.d));
    }
    let mut warnings = warnings;
    if off.count > 0 && warnings.is_empty() {
        // Uncovered or overlapped area explains a D that is not diagonal; otherwise say so.
        let tags = interface.slave().node_tags();
        warnings.push(CouplingWarning::DualNotDiagonal {
            entries: off.count,
            largest: off.largest,
            rows: off.rows,
            examples: off
                .examples
                .iter()
                .map(|&r| tags[interface.slave_nodes()[r] as usize])
                .collect(),
        });
    }
    seconds.assembly = t_asm.elapsed().as_secs_f64();
    let slave_tags = interface.slave().node_tags();
    let master_tags = interface.master().node_tags();
    let normals = interface.slave_nodal_normals();
    let area = ordered_sum(d.data());
    // The slave's tags and normals in one pass; the normals (the larger) allocated first,
    // so that they take the memory the call has just freed rather than fresh pages. Above
    // the allocator's mmap threshold the memory is fresh whatever the order: its pages are
    // then faulted in by the kernel a block per task before they are written.
    let ns = interface.slave_nodes().len();
    let mut slave_normals = populated(ns);
    let mut slave_nodes = populated(ns);
    interface
        .slave_nodes()
        .par_iter()
        .map(|&n| (slave_tags[n as usize], normals[n as usize]))
        .unzip_into_vecs(&mut slave_nodes, &mut slave_normals);
    Coupling {
        slave_nodes,
        master_nodes: collect_populated(
            interface
                .master_nodes()
                .par_iter()
                .map(|&n| master_tags[n as usize]),
        ),
        slave_normals,
        d,
        m,
        formulation: options.describe(),
        stats: CouplingStats {
            candidates: stats.candidates,
            pairs: stats.pairs,
            segments: stats.segments,
            back_facing: stats.back_facing,
            skipped_pairs: stats.skipped,
            d_roundoff_dropped: roundoff.count,
            d_roundoff_largest: roundoff.largest,
            d_off_diagonal: off.count,
            d_off_diagonal_largest: off.largest,
            uncovered_area: stats.uncovered_area,
            overlapped_area: stats.overlapped_area,
            faces_overlapped: stats.overlapped,
            faces_without_partner: stats.without_partner,
            faces_partly_covered: stats.partly_covered,
            fused_line_faces: stats.fused,
            straight_line_faces: stats.straight,
            closed_form_faces: stats.closed_form,
            area,
            threads,
            degrees_used: { std::array::from_fn(|d| stats.degrees & (1 << d) != 0) },
            // The general path sets the search's below; the merge uses no boxes.
            slave_box_inflation: 0.0,
            master_box_inflation: 0.0,
            widened_search_faces: 0,
            widest_search: 0.0,
            seconds: PhaseSeconds {
                total: start.elapsed().as_secs_f64(),
                ..seconds
            },
        },
        warnings,
        recombined,
    }
}

/// D in the recombined basis of the slave faces ([`Recombined`]), for a space that recombines
/// them; `None` where none is recombined or no one recombination serves the slave side (then
/// D keeps its off-diagonal entries, which the coupling counts and reports).
fn recombine(
    interface: &Interface,
    space: &dyn MultiplierSpace,
    d: &SparseMatrix,
    nodal: RoundoffDropped,
) -> Option<Recombined> {
    if !space.fast_paths().is_some_and(|f| f.recombines()) {
        return None;
    }
    let t = slave_recombination(interface).ok()??;
    let dt = d * &t.transpose_view().to_csr();
    let (d, roundoff) = drop_roundoff(&dt, ROUNDOFF);
    Some(Recombined {
        d,
        t,
        d_roundoff_dropped: nodal.count + roundoff.count,
        d_roundoff_largest: nodal.largest.max(roundoff.largest),
    })
}

/// Entries summed per block of [`SUM_BLOCK`] (four running sums each, added in a fixed
/// order), the blocks in parallel and their sums added in order: the bits do not depend on the
/// thread count (rayon's own `sum` would), and no pass waits on one chain of 10^6 additions.
/// line2d at 10^6 slave faces: `CouplingStats::area` 1 + 3.3e-15 instead of the plain loop's
/// 1 + 2.1e-11, in 1.4 ms on one thread and 0.9 ms on two instead of 2.9 ms.
fn ordered_sum(values: &[f64]) -> f64 {
    let blocks: Vec<f64> = values
        .par_chunks(SUM_BLOCK)
        .map(|block| {
            let mut lanes = [0.0; 4];
            let mut quads = block.chunks_exact(4);
            for q in &mut quads {
                for (lane, v) in lanes.iter_mut().zip(q) {
                    *lane += v;
                }
            }
            let rest: f64 = quads.remainder().iter().sum();
            (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) + rest
        })
        .collect();
    blocks.iter().sum()
}

/// The entries per block of [`ordered_sum`].
const SUM_BLOCK: usize = 1 << 14;

/// The warnings of a run: uncovered slave area and area covered more than once, each above
/// the coverage tolerance (relative to the slave face's area), with the smallest tags of
/// such faces (`examples`: uncovered, overlapped), and skipped pairs.
fn coupling_warnings(
    interface: &Interface,
    stats: &ChunkStats,
    first_skipped: Option<(usize, MortarError)>,
    examples: (Vec<u64>, Vec<u64>),
) -> Vec<CouplingWarning> {
    let mut out = Vec::new();
    let uncovered = stats.without_partner + stats.partly_covered > 0;
    let total = if uncovered || stats.overlapped > 0 {
        (0..interface.slave().face_count())
            .into_par_iter()
            .map(|f| interface.slave_face(f).measure())
            .sum()
    } else {
        0.0
    };
    if uncovered {
        out.push(CouplingWarning::UncoveredSlaveArea {
            area: stats.uncovered_area,
            total,
            faces_without_partner: stats.without_partner,
            faces_partly_covered: stats.partly_covered,
            examples: examples.0,
            reach: stats.uncovered_reach,
        });
    }
    if stats.overlapped > 0 {
        out.push(CouplingWarning::OverlappingMasterFaces {
            area: stats.overlapped_area,
            total,
            faces: stats.overlapped,
            examples: examples.1,
        });
    }
    if let Some((_, first)) = first_skipped {
        out.push(CouplingWarning::SkippedPairs {
            count: stats.skipped,
            first: Box::new(first),
        });
    }
    out
}

/// Segments, integrates and scatters one chunk of slave faces. The paired points of the whole
/// chunk go into one flat vector, so the per-face work allocates nothing once the buffers
/// have grown.
#[allow(clippy::too_many_arguments)]
fn chunk(
    interface: &Interface,
    options: &CouplingOptions,
    ctx: &SegmentContext<'_>,
    search: &Search,
    radii: Option<&[f64]>,
    order: &[u32],
    positions: std::ops::Range<usize>,
    key: u64,
    acc: &mut Accumulator,
) -> Result<()> {
    let faces = &order[positions.clone()];
    let mut out = ChunkStats::default();
    let t_search = Instant::now();
    acc.ws.gather(interface, faces);
    acc.ws
        .candidates(interface, ctx, search, radii, positions.start);
    let ChunkWorkspace {
        geometry,
        rows: face_rows,
        offsets,
        all,
        scratch,
        face: buffers,
        ..
    } = &mut acc.ws;
    out.candidates = all.len();
    let t0 = Instant::now();
    out.seconds_search = (t0 - t_search).as_secs_f64();
    // Each face is segmented and integrated at once, while its points are in cache.
    let mut notes = FaceNotes::default();
    let closed_form = match search {
        Search::Tree { closed_form, .. } => *closed_form,
        Search::Lines { .. } => None,
    };
    for i in 0..faces.len() {
        let mut cands = &all[offsets[i]..offsets[i + 1]];
        let face = &geometry[i];
        let rows = &face_rows[i][..face.node_count()];
        if let (Search::Lines { search, rule, .. }, false) = (search, cands.is_empty()) {
            // More candidates than a walk follows came from the exhaustive query: such a
            // coarse face goes to the strategy (batched, its columns merged through an index).
            let few = cands.len() <= WALK_LIMIT;
            if few && fused_face(options, ctx, face, rows, cands, *rule, buffers)? {
                let line = &buffers.line;
                out.pairs += line.pairs as usize;
                out.segments += line.pairs as usize;
                out.back_facing += line.back_facing as usize;
                out.degrees |= 1 << line.degree;
                out.fused += 1;
                continue;
            }
            // Not settled by the walk's candidates: the general path, with every candidate
            // the tree would give.
            if few {
                search.exhaustive(interface, ctx.masters, face, scratch);
                if let Some(radii) = radii {
                    let radius = radii[face.index as usize];
                    keep_within_radius(interface, ctx.masters, face, radius, scratch);
                }
                out.candidates = out.candidates + scratch.len() - cands.len();
                cands = scratch;
            }
        }
        if cands.is_empty() {
            out.without_partner += 1;
            out.uncovered_area += face.measure();
            out.uncovered_reach = out
                .uncovered_reach
                .max(face_search_radius(interface, face, radii));
            note(&mut notes.uncovered, face.tag);
            continue;
        }
        let uncovered_before = out.without_partner + out.partly_covered;
        general_face(
            options,
            ctx,
            closed_form,
            face,
            rows,
            cands,
            buffers,
            &mut out,
            &mut acc.first_skipped,
            positions.start + i,
            &mut notes,
        )?;
        if out.without_partner + out.partly_covered > uncovered_before {
            out.uncovered_reach = out
                .uncovered_reach
                .max(face_search_radius(interface, face, radii));
        }
    }
    acc.d.push_rows(key, &mut buffers.d);
    acc.m.push_rows(key, &mut buffers.m);
    out.seconds_integration = t0.elapsed().as_secs_f64() - out.seconds_segments;
    acc.stats.add(&out);
    acc.add_notes(&notes.uncovered, &notes.overlapped);
    Ok(())
}

/// The first slave faces of a chunk with too little or too much master area over them.
#[derive(Default)]
struct FaceNotes {
    uncovered: ArrayVec<u64, { CouplingWarning::EXAMPLES }>,
    overlapped: ArrayVec<u64, { CouplingWarning::EXAMPLES }>,
}

/// Keeps `tag` among the first faces of a chunk in `list`.
fn note(list: &mut ArrayVec<u64, { CouplingWarning::EXAMPLES }>, tag: u64) {
    if !list.is_full() {
        list.push(tag);
    }
}

/// One slave face of straight two-node lines by the fused kernel, its triplets pushed;
/// `false` (nothing pushed) when the kernel leaves it to the general path, or the multiplier
/// space cannot be built on it (the general path then reports that, if the face has any
/// overlap).
fn fused_face(
    options: &CouplingOptions,
    ctx: &SegmentContext<'_>,
    face: &FaceGeometry,
    rows: &[u32],
    cands: &[u32],
    rule: LineSegments,
    buffers: &mut FaceBuffers,
) -> Result<bool> {
    let tol = ctx.interface.tolerances();
    let Ok(basis) = options.multipliers.basis_for(face, tol, options.geometry) else {
        return Ok(false);
    };
    let line = &mut buffers.line;
    if !fused_line_face(
        ctx,
        face,
        cands,
        rule.degree,
        &basis,
        options.geometry,
        &mut buffers.lines,
        line,
    )? {
        return Ok(false);
    }
    push_face_rows(
        (&mut buffers.d, &mut buffers.m),
        &mut buffers.order,
        rows,
        |j| basis.carries(j),
        |j, k| line.d[j][k],
        &line.cols,
        |j, p| line.vals[p][j],
    );
    Ok(true)
}

/// One slave face through the integration strategy: segmented and integrated a batch of
/// candidates at a time, its triplets pushed, its coverage counted.
#[allow(clippy::too_many_arguments)]
fn general_face(
    options: &CouplingOptions,
    ctx: &SegmentContext<'_>,
    closed_form: Option<ClosedForm>,
    face: &FaceGeometry,
    rows: &[u32],
    cands: &[u32],
    buffers: &mut FaceBuffers,
    out: &mut ChunkStats,
    first_skipped_of_worker: &mut Option<(usize, MortarError)>,
    at: usize,
    notes: &mut FaceNotes,
) -> Result<()> {
    let interface = ctx.interface;
    let tol = interface.tolerances();
    let FaceBuffers {
        rule,
        blocks,
        columns,
        closed: scratch,
        pending,
        order,
        d,
        m,
        ..
    } = buffers;
    // A strategy that splits over candidates gets them a batch at a time: each batch is
    // segmented, integrated (D summed on, point after point, across batches) and its M
    // blocks merged by master node before the next, so that the memory of a face's
    // points stays bounded however many partners it has. Every bit of D and M is the
    // one of the face done at once: the same sums in the same order.
    let splits = |f: &dyn IntegrationFastPaths| f.splits_over_candidates();
    let batch = if options.integration.fast_paths().is_some_and(splits) {
        CANDIDATE_BATCH
    } else {
        cands.len()
    };
    blocks.start_face(face.node_count());
    let ks = rows.len();
    columns.start_face(ks);
    // The closed form needs the basis first; a face whose basis cannot be built goes to the
    // strategy (which reports that if the face has any overlap).
    // (The basis, 664 bytes, is built in place and borrowed, not moved along.)
    let mut basis: Option<LmBasis> = None;
    let mut closed_form = closed_form.filter(|_| {
        basis = options
            .multipliers
            .basis_for(face, tol, options.geometry)
            .ok();
        basis.is_some()
    });
    let mut any_points = false;
    let mut coverage = Coverage::default();
    let mut first_skipped = None;
    for part in cands.chunks(batch) {
        let ta = Instant::now();
        // The closed form does the segmentation and the integration at once (its time counts
        // as segmentation); a face it leaves (not integrated in the plane) goes to the
        // strategy.
        // Its M blocks go straight to the columns (each master face once per face: the
        // same sums as through the blocks).
        let closed = match (&closed_form, &basis) {
            (Some(cf), Some(b)) => {
                let add = |cols: &[u32], block: &[f64]| columns.add_cols(cols, block);
                let d = &mut blocks.d;
                closed_form_batch(ctx, cf, face, part, b, d, scratch, pending, add, rule)?
            }
            _ => false,
        };
        if !closed {
            closed_form = None;
            options
                .integration
                .paired_rule_into(ctx, face, part, rule)?;
        }
        out.tally(rule, &mut first_skipped);
        coverage.add(rule);
        out.seconds_segments += ta.elapsed().as_secs_f64();
        if closed {
            any_points |= rule.pairs > 0;
        } else {
            if rule.points.is_empty() {
                continue;
            }
            any_points = true;
            integrate_strategy_points(options, ctx, face, &mut basis, rule, blocks)?;
        }
        // The M blocks merged by master node (see `MergedColumns`).
        for (mf, km, block) in blocks.m_blocks() {
            columns.add(ctx, mf, km, block);
        }
        blocks.clear_m_blocks();
    }
    if let Some(e) = first_skipped {
        *first_skipped_of_worker = first_skipped_of_worker
            .take()
            .filter(|(k, _)| *k < at)
            .or(Some((at, e)));
    }
    let missing = coverage.missing(face);
    if !any_points {
        out.without_partner += 1;
        out.uncovered_area += face.measure();
        note(&mut notes.uncovered, face.tag);
        return Ok(());
    }
    if closed_form.is_some() {
        out.closed_form += 1;
    }
    out.count_coverage(face, missing, tol.coverage, notes);
    // Rows of nodes without a multiplier (linear multipliers on second-order faces)
    // stay empty.
    let carries = |j: usize| basis.as_ref().is_none_or(|b| b.carries(j));
    push_face_rows(
        (d, m),
        order,
        rows,
        carries,
        |j, k| blocks.d[j][k],
        &columns.cols,
        |j, p| columns.vals[p * ks + j],
    );
    Ok(())
}

/// How much of a slave face its batches' points cover.
struct Coverage {
    /// The covered fraction, summed over batches (`None` if a batch did not measure it).
    covered: Option<f64>,
    /// The sum of the weights, for when `covered` is `None`.
    weights: f64,
}

impl Default for Coverage {
    fn default() -> Self {
        Self {
            covered: Some(0.0),
            weights: 0.0,
        }
    }
}

impl Coverage {
    /// Adds one batch's paired rule.
    #[inline]
    fn add(&mut self, rule: &PairedRule) {
        self.covered = self.covered.zip(rule.covered).map(|(a, c)| a + c);
        if self.covered.is_none() {
            self.weights += rule.points.iter().map(|p| p.weight).sum::<f64>();
        }
    }

    /// The fraction of `face` its points miss (negative: cover more than once): as the
    /// strategy measured it, or the sum of the weights against the face's measure.
    fn missing(&self, face: &FaceGeometry) -> f64 {
        match self.covered {
            Some(c) => 1.0 - c,
            None => 1.0 - self.weights / face.measure(),
        }
    }
}

/// Integrates the strategy's paired points `rule` of `face` into `blocks`: weighted by the
/// revolved surface's measure in an axisymmetric geometry, with the face's multiplier basis
/// (built here if the closed form did not build it).
#[inline]
fn integrate_strategy_points(
    options: &CouplingOptions,
    ctx: &SegmentContext<'_>,
    face: &FaceGeometry,
    basis: &mut Option<LmBasis>,
    rule: &mut PairedRule,
    blocks: &mut LocalBlocks,
) -> Result<()> {
    if options.geometry.is_axisymmetric() {
        // The measure of the revolved surface, 2 pi r at the slave point (after the coverage,
        // which compares lengths of the meridian).
        for p in rule.points.iter_mut() {
            p.weight *= options.geometry.weight(&face.map(&p.xi_slave));
        }
    }
    let tol = ctx.interface.tolerances();
    let basis = match basis {
        Some(b) => b,
        None => basis.insert(options.multipliers.basis_for(face, tol, options.geometry)?),
    };
    integrate_batch_into(
        ctx.interface,
        ctx.masters,
        face,
        basis,
        &rule.points,
        blocks,
    );
    Ok(())
}

/// The closed form's segmentation and integration of the candidates `part` of `face` at once
/// ([`closed_form_into`] on triangles, [`affine_moments_into`] on the shapes it takes):
/// whether it did them (a face it leaves, not integrated in the plane, goes to the strategy).
#[allow(clippy::too_many_arguments)]
#[inline]
fn closed_form_batch(
    ctx: &SegmentContext<'_>,
    cf: &ClosedForm,
    face: &FaceGeometry,
    part: &[u32],
    basis: &LmBasis,
    d: &mut [[f64; MAX_FACE_NODES]; MAX_FACE_NODES],
    tris: &mut ClosedFormScratch,
    pending: &mut Vec<PendingBlock>,
    add: impl FnMut(&[u32], &[f64]),
    rule: &mut PairedRule,
) -> Result<bool> {
    let degree = cf.rule.degree;
    match (cf.triangles, cf.shape(face.element)) {
        (true, _) => closed_form_into(ctx, face, part, degree, basis, d, tris, add, rule),
        (false, Some(shape)) => affine_moments_into(
            ctx, face, shape, part, cf, basis, d, tris, pending, add, rule,
        ),
        (false, None) => Ok(false),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The blocked sum gives the same bits on one thread and on three, for lengths that end
    /// mid-block and mid-lane, and the exact sum where every partial sum is exact (integers
    /// below 2^53: the closed form n (n - 1) / 2).
    #[test]
    fn ordered_sum_is_exact_on_integers_and_independent_of_threads() {
        for n in [0usize, 1, 3, 5, SUM_BLOCK - 1, SUM_BLOCK, 3 * SUM_BLOCK + 7] {
            let ints: Vec<f64> = (0..n).map(|i| i as f64).collect();
            let want = (n * n.saturating_sub(1) / 2) as f64;
            assert_eq!(ordered_sum(&ints), want, "n = {n}");
            let values: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin() * 1e-3).collect();
            let on = |threads| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap()
                    .install(|| ordered_sum(&values))
            };
            assert_eq!(on(1).to_bits(), on(3).to_bits(), "n = {n}");
        }
    }
}
