//! A 2D interface along one straight line, coupled as a sorted merge.
//!
//! When the projection direction is one vector `n` at every point of the slave (the nodal
//! normals of a straight slave line), projecting along `n` is taking the coordinate
//! `t = (x - x0) . tau` along the line (`tau` perpendicular to `n`). Every slave face and every
//! master face is then an interval of `t`, a pair's overlap is the intersection of two
//! intervals, and the shape functions of both faces are affine in `t`. The pairs come from
//! merging the two sorted lists of node coordinates (no search tree, no projection, no
//! segmentation), and each row of D and M is computed and written straight into the
//! matrices (no triplets).
//!
//! What it computes is the segment-based method's D and M: the same Gauss rule at the same
//! reference points of each overlap, the overlap and the master coordinate of each point
//! found from offsets along the line measured from the slave face's first node (so that their
//! rounding is relative to the face, as in the general path) rather than from the cross
//! products of the fused kernel (`segments_2d::fused_line_face`), which for a uniform
//! direction are the same affine functions (so D and M agree to round-off; the tests compare
//! them with the general path's). `t` itself only orders the nodes and finds each face's
//! candidates. The merge takes an interface only when the
//! general path would couple every slave face, in full, with every master face overlapping
//! it:
//! - each side one open chain of straight two-node lines of one element type, the slave's
//!   `t` strictly increasing along its chain, the master's strictly monotone (so that its
//!   faces are disjoint intervals). A side whose faces are stored along its chain (forwards
//!   or backwards, as generators and Gmsh write a line) is read as it is; otherwise its
//!   nodes are sorted along the line and its faces must join consecutive ones (no chain is
//!   walked: a walk over faces numbered at random is a chase of cache misses);
//! - the projector's uniform direction
//!   ([`ProjectorFastPaths::uniform_direction`](crate::projector::ProjectorFastPaths::uniform_direction));
//! - a multiplier space whose basis is the same on every face
//!   ([`MultiplierFastPaths::basis_is_uniform`](crate::multiplier::MultiplierFastPaths::basis_is_uniform));
//! - the master facing the slave;
//! - every master node within the smallest slave face's search radius of the slave line (the
//!   search would then find every master face overlapping a slave face: the part of it over
//!   the face lies in the region the face's search box holds);
//! - every slave face covered to the coverage tolerance.
//!
//! Anything else gives `None`, and the interface takes the chain walk and the fused kernel.
//!
//! Each row is computed from the two slave faces around its node, left face first, whatever
//! the thread count or the block a row falls in: D and M are bit-identical across thread
//! counts.

use std::time::Instant;

use nalgebra::{Vector2, Vector3};
use rayon::prelude::*;

use super::CouplingOptions;
use crate::element::ReferenceDomain;
use crate::error::Result;
use crate::geometry::ModelGeometry;
use crate::integration::segments_2d::add_line_point;
use crate::integration::{default_degree, LineSegments};
use crate::interface::Interface;
use crate::linalg::csr::csr_checked_in_parallel;
use crate::linalg::SparseMatrix;
use crate::memory::{collect_populated, Spare};
use crate::mesh::SurfaceMesh;
use crate::multiplier::{LmBasis, MultiplierFastPaths};
use crate::quadrature::{Quadrature, QuadratureRule};

/// Slave faces (the merge) or rows (the rows) per parallel task.
const BLOCK: usize = 4096;

/// What the merge computed.
pub(super) struct Merged {
    /// D, rows and columns by slave node, before any round-off of a dual D is dropped.
    pub d: SparseMatrix,
    /// M, rows by slave node and columns by master node.
    pub m: SparseMatrix,
    /// Slave-master face pairs with a non-empty overlap.
    pub pairs: usize,
    /// The quadrature degree used.
    pub degree: u32,
    /// When the merge of the node coordinates (pairs and coverage) started.
    pub merge_start: Instant,
    /// When the rows started.
    pub rows_start: Instant,
}

/// How rows follow the slave chain.
enum RowOrder {
    /// Row `r` is chain position `r`.
    Along,
    /// Row `r` is chain position `rows - 1 - r`.
    Against,
    /// Row `r` is chain position `positions[r]`.
    Table(Vec<u32>),
}

/// The interface along its line: both sides' nodes in order of `t`.
struct Line<'a> {
    interface: &'a Interface,
    /// Slave nodes along the chain (`faces + 1`), their `t` (strictly increasing) and rows.
    s_node: Vec<u32>,
    s_t: Vec<f64>,
    s_row: Vec<u32>,
    /// Master nodes in increasing `t`, their `t` and their columns in M.
    m_node: Vec<u32>,
    m_t: Vec<f64>,
    m_col: Vec<u32>,
    /// The unit vector along the line (`t` grows with it).
    tau: Vector3<f64>,
    /// A bound on the rounding of the `t` of any node: `t` orders the nodes and finds a
    /// face's candidates; the overlaps themselves are computed from the coordinates, relative
    /// to the slave face (so that their rounding is relative to the face, not to the line).
    slack: f64,
    basis: LmBasis,
    /// The Gauss rule of the strategy's degree, and that degree.
    rule: &'static QuadratureRule,
    degree: u32,
    geometry: ModelGeometry,
}

/// A slave face read for its pairs: its ends, its length along the line and the factor
/// from an offset along it to its reference coordinate.
struct Frame {
    xa: Vector3<f64>,
    xb: Vector3<f64>,
    length: f64,
    scale: f64,
}

/// One slave face's values ([`Line::face_values`]).
struct FaceValues {
    /// The face (`usize::MAX`: none yet).
    face: usize,
    /// `D[j][k]`, slave nodes `j`, `k` of the face.
    d: [[f64; 2]; 2],
    /// The first master node (in increasing `t`) of `vals`.
    q0: usize,
    /// M's values at master nodes `q0..`, one per slave node of the face.
    vals: Vec<[f64; 2]>,
}

impl Default for FaceValues {
    fn default() -> Self {
        Self {
            face: usize::MAX,
            d: [[0.0; 2]; 2],
            q0: 0,
            vals: Vec::new(),
        }
    }
}

/// D and M of `interface` by the sorted merge (see the module's documentation), with the
/// strategy's 2D segmentation `segments`; `None` when the merge does not apply.
///
/// # Errors
/// A quadrature rule that cannot be built for the strategy's degree.
pub(super) fn couple(
    interface: &Interface,
    options: &CouplingOptions,
    segments: LineSegments,
    spare: &mut Spare,
) -> Result<Option<Merged>> {
    let (smesh, mmesh) = (interface.slave(), interface.master());
    if smesh.element_types().len() != 1 || mmesh.element_types().len() != 1 {
        return Ok(None);
    }
    let uniform_basis = |f: &dyn MultiplierFastPaths| {
        f.basis_is_uniform(smesh.element_types()[0], options.geometry)
    };
    if !options.multipliers.fast_paths().is_some_and(uniform_basis) {
        return Ok(None);
    }
    let (Some(slave_faces), Some(master_faces)) = (two_node_faces(smesh), two_node_faces(mmesh))
    else {
        return Ok(None);
    };
    // The shortest slave face (a two-node face's box diagonal is its length: the search
    // radius is the smallest for it) and the largest coordinate of a slave node.
    let sx = smesh.coords();
    let (shortest, largest) = slave_faces
        .par_iter()
        .map(|&[a, b]| {
            let (a, b) = (&sx[a as usize], &sx[b as usize]);
            ((b - a).norm(), a.amax().max(b.amax()))
        })
        .reduce(|| (f64::INFINITY, 0.0), |p, q| (p.0.min(q.0), p.1.max(q.1)));
    let Some(n) = options
        .projector
        .fast_paths()
        .and_then(|f| f.uniform_direction(interface, direction_resolution(shortest, largest)))
    else {
        return Ok(None);
    };
    let n = n.normalize();
    if !n.iter().all(|v| v.is_finite()) {
        return Ok(None);
    }
    // Each side's nodes along its chain: as its faces are stored, or sorted along the line.
    let tau = Vector3::new(n.y, -n.x, 0.0);
    let along = |mesh: &SurfaceMesh, faces: &[[u32; 2]], nodes: &[u32]| {
        stored_chain(faces).or_else(|| sorted_chain(mesh, faces, nodes, &tau))
    };
    // One side after the other, each in parallel within: side by side (`rayon::join`), the
    // master's temporaries were freed on the other worker, whose memory the rest of the call
    // (all allocated on this one) could not reuse. line2d at 10^6 faces on two threads: peak
    // over (meshes + D, M) 1.37 -> 1.33 in the file order, 1.52 -> 1.36 with the faces
    // shuffled, and 4% faster.
    let (s_node, m_node) = (
        along(smesh, slave_faces, interface.slave_nodes()),
        along(mmesh, master_faces, interface.master_nodes()),
    );
    let (Some(s_node), Some(m_node)) = (s_node, m_node) else {
        return Ok(None);
    };
    let radius = interface.tolerances().search_radius.for_face(shortest);
    let Some(line) = Line::new(interface, options, segments, s_node, m_node, n, radius)? else {
        return Ok(None);
    };
    let merge_start = Instant::now();
    let Some((ranges, pairs)) = line.pairs() else {
        return Ok(None);
    };
    let rows_start = Instant::now();
    let (d, m) = line.rows(&ranges, spare);
    Ok(Some(Merged {
        d,
        m,
        pairs,
        degree: line.degree,
        merge_start,
        rows_start,
    }))
}

/// The two nodes of each face of `mesh`, if every face has two.
fn two_node_faces(mesh: &SurfaceMesh) -> Option<&[[u32; 2]]> {
    let (pairs, rest) = mesh.all_face_nodes().as_chunks::<2>();
    (rest.is_empty() && pairs.len() == mesh.face_count()).then_some(pairs)
}

/// The nodes of two-node `faces` along their chain when the faces are stored along it,
/// forwards (each face starting where the one before it ends) or backwards (each ending where
/// the one before it starts); `None` otherwise. (A chain that closes or crosses itself passes
/// here and fails the strictly increasing `t`.)
fn stored_chain(faces: &[[u32; 2]]) -> Option<Vec<u32>> {
    let n = faces.len();
    let linked = |follows: fn(&[[u32; 2]]) -> bool| faces.par_windows(2).all(follows);
    let mut nodes = Vec::with_capacity(n + 1);
    if linked(|w| w[0][1] == w[1][0]) {
        nodes.par_extend(faces.par_iter().map(|f| f[0]));
        nodes.push(faces.last()?[1]);
    } else if linked(|w| w[0][0] == w[1][1]) {
        nodes.par_extend(faces.par_iter().rev().map(|f| f[0]));
        nodes.push(faces.first()?[1]);
    } else {
        return None;
    }
    Some(nodes)
}

/// The nodes of `mesh`'s two-node `faces` along their chain, found by sorting `nodes` (the
/// side's interface nodes) by their coordinate along `tau`: when the faces join consecutive
/// nodes of that order, each pair once, all oriented alike (one open chain along the line,
/// however its faces and nodes are numbered); `None` otherwise, or where two nodes have the
/// same coordinate.
fn sorted_chain(
    mesh: &SurfaceMesh,
    faces: &[[u32; 2]],
    nodes: &[u32],
    tau: &Vector3<f64>,
) -> Option<Vec<u32>> {
    if faces.len() + 1 != nodes.len() {
        return None;
    }
    let x = mesh.coords();
    let o = x[nodes[0] as usize];
    let mut keyed: Vec<(f64, u32)> = nodes
        .par_iter()
        .map(|&k| ((x[k as usize] - o).dot(tau), k))
        .collect();
    keyed.par_sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    if !keyed.par_windows(2).all(|w| w[0].0 < w[1].0) {
        return None;
    }
    let mut rank = vec![u32::MAX; x.len()];
    for (r, &(_, k)) in keyed.iter().enumerate() {
        rank[k as usize] = r as u32;
    }
    let rank = |k: u32| rank[k as usize];
    let joins = |step: fn(u32, u32) -> bool| faces.par_iter().all(|&[a, b]| step(rank(a), rank(b)));
    let forward = joins(|a, b| b == a.wrapping_add(1));
    if !forward && !joins(|a, b| a == b.wrapping_add(1)) {
        return None;
    }
    // Consecutive nodes joined, each pair once: `faces.len()` distinct pairs cover all.
    let mut joined = vec![false; faces.len()];
    for &[a, b] in faces {
        let first = rank(a).min(rank(b)) as usize;
        if std::mem::replace(&mut joined[first], true) {
            return None;
        }
    }
    let mut chain: Vec<u32> = keyed.into_iter().map(|(_, k)| k).collect();
    if !forward {
        chain.reverse();
    }
    Some(chain)
}

/// How far apart the unit nodal normals of a straight line may be, computed in floating
/// point from nodes of coordinates up to `largest` and faces from `shortest` long: the
/// normal of a face turns by the coordinates' rounding over its length (a few of them, and
/// the averaging at a node: `8 eps |x| / h`, 1e-14 at least; on 3,000 random turned and moved
/// lines of the property test the merge took every one at `2 eps |x| / h` already). The
/// direction of a line is known no better: a slave whose normals differ by less is straight
/// to the resolution of its coordinates; a larger turn (a kink) is not taken.
fn direction_resolution(shortest: f64, largest: f64) -> f64 {
    (8.0 * f64::EPSILON * largest / shortest).max(1e-14)
}

/// Whether `t` strictly increases (`false` where it holds a NaN).
fn increasing(t: &[f64]) -> bool {
    t.par_windows(2).all(|w| w[0] < w[1])
}

/// Whether `v` strictly increases.
fn ascending(v: &[u32]) -> bool {
    v.par_windows(2).all(|w| w[0] < w[1])
}

/// Whether `v` strictly decreases.
fn descending(v: &[u32]) -> bool {
    v.par_windows(2).all(|w| w[0] > w[1])
}

impl<'a> Line<'a> {
    /// The line of `interface` of unit normal `n` through the slave nodes `s_node` and the
    /// master nodes `m_node`, each in chain order, with `radius` the smallest slave face's
    /// search radius; `None` when the merge does not apply.
    fn new(
        interface: &'a Interface,
        options: &CouplingOptions,
        segments: LineSegments,
        s_node: Vec<u32>,
        mut m_node: Vec<u32>,
        n: Vector3<f64>,
        radius: f64,
    ) -> Result<Option<Self>> {
        let (smesh, mmesh) = (interface.slave(), interface.master());
        let (s_el, m_el) = (smesh.element_types()[0], mmesh.element_types()[0]);
        let tol = interface.tolerances();
        let (sx, mx) = (smesh.coords(), mmesh.coords());
        let x0 = sx[s_node[0] as usize];
        // `tau` such that t grows along the slave chain.
        let mut tau = Vector3::new(n.y, -n.x, 0.0);
        if (sx[s_node[1] as usize] - x0).dot(&tau) < 0.0 {
            tau = -tau;
        }
        let along = |x: &Vector3<f64>| (x - x0).dot(&tau);
        let s_t: Vec<f64> = collect_populated(s_node.par_iter().map(|&k| along(&sx[k as usize])));
        if !increasing(&s_t) {
            return Ok(None);
        }
        // The master faces face the slave: the first one as the general path tests it; the
        // others, traversed in the same sense of `t` (strictly monotone below), have their
        // normals on the same side.
        let first = [mx[m_node[0] as usize], mx[m_node[1] as usize]];
        if m_el.unit_normal(&first, &Vector2::zeros()).dot(&n) >= 0.0 {
            return Ok(None);
        }
        if along(&first[1]) < along(&first[0]) {
            m_node.reverse();
        }
        // A node beyond the search radius becomes a NaN, which fails the increasing test.
        let m_t: Vec<f64> = collect_populated(m_node.par_iter().map(|&k| {
            let x = &mx[k as usize];
            let near = (x - x0).dot(&n).abs() <= radius;
            if near {
                along(x)
            } else {
                f64::NAN
            }
        }));
        if !increasing(&m_t) {
            return Ok(None);
        }
        let s_row: Vec<u32> = collect_populated(s_node.par_iter().map(|&k| {
            interface
                .slave_row(k)
                .expect("face nodes are on the interface")
        }));
        if s_row.len() != interface.slave_nodes().len() {
            return Ok(None);
        }
        let m_col = collect_populated(m_node.par_iter().map(|&k| {
            interface
                .master_col(k)
                .expect("face nodes are on the interface")
        }));
        let first = interface.slave_face(0);
        let Ok(basis) = options.multipliers.basis_for(&first, tol, options.geometry) else {
            return Ok(None);
        };
        let degree = segments
            .degree
            .unwrap_or_else(|| default_degree(s_el, m_el));
        let rule = QuadratureRule::cached(ReferenceDomain::Line, degree)?;
        // `t` is `(x - x0) . tau` rounded: within a few roundings of `|x - x0|`.
        let reach = s_t[s_t.len() - 1]
            .abs()
            .max(s_t[0].abs())
            .max(m_t[0].abs())
            .max(m_t[m_t.len() - 1].abs());
        let slack = 16.0 * f64::EPSILON * reach;
        Ok(Some(Self {
            interface,
            s_node,
            s_t,
            s_row,
            m_node,
            m_t,
            m_col,
            tau,
            slack,
            basis,
            rule,
            degree,
            geometry: options.geometry,
        }))
    }

    /// Slave face `f` as [`overlap`](Self::overlap) and the integration read it.
    #[inline]
    fn frame(&self, f: usize) -> Frame {
        let sx = self.interface.slave().coords();
        let (xa, xb) = (sx[self.s_node[f] as usize], sx[self.s_node[f + 1] as usize]);
        let length = (xb - xa).dot(&self.tau);
        Frame {
            xa,
            xb,
            length,
            scale: 2.0 / length,
        }
    }

    /// Where master node `q` is along slave face `frame`: `(y - xa) . tau`, from the face's
    /// first node.
    #[inline]
    fn offset(&self, frame: &Frame, q: usize) -> f64 {
        let y = &self.interface.master().coords()[self.m_node[q] as usize];
        (y - frame.xa).dot(&self.tau)
    }

    /// The overlap of slave face `frame` with the master face from offset `uj` to `uk`, in
    /// the slave face's reference coordinate, the master nodes' projections clamped to the
    /// face as the general path clamps them.
    #[inline]
    fn overlap(frame: &Frame, uj: f64, uk: f64) -> (f64, f64) {
        let xi = |u: f64| (-1.0 + u * frame.scale).clamp(-1.0, 1.0);
        let (a, b) = (xi(uj), xi(uk));
        (a.min(b), a.max(b))
    }

    /// The master faces (by index in increasing `t`) that slave face `f` meets, as the first
    /// and one past the last with an overlap longer than the clipping tolerance, starting the
    /// merge at master face `k`; with the count of such faces and the covered length in the
    /// face's reference coordinate. `k` moves to the first face not wholly before `f` (by
    /// `t`, to its rounding).
    fn partners(&self, f: usize, k: &mut usize) -> ((u32, u32), usize, f64) {
        let clip = self.interface.tolerances().clip_area * 2.0;
        let (ta, tb) = (self.s_t[f] - self.slack, self.s_t[f + 1] + self.slack);
        let last = self.m_t.len() - 1;
        while *k + 1 < last && self.m_t[*k + 1] <= ta {
            *k += 1;
        }
        let frame = self.frame(f);
        let (mut first, mut end, mut count, mut covered) = (u32::MAX, 0, 0, 0.0);
        let mut j = *k;
        let mut uj = self.offset(&frame, j);
        while j < last && self.m_t[j] < tb {
            let uk = self.offset(&frame, j + 1);
            let (lo, hi) = Self::overlap(&frame, uj, uk);
            if hi - lo > clip {
                first = first.min(j as u32);
                end = j as u32 + 1;
                count += 1;
                covered += hi - lo;
            }
            (j, uj) = (j + 1, uk);
        }
        ((first, end), count, covered)
    }

    /// Per slave face, its master faces ([`partners`](Self::partners)), and the pair count;
    /// `None` if a face is not covered to the tolerance (the general path then reports it).
    fn pairs(&self) -> Option<(Vec<(u32, u32)>, usize)> {
        let faces = self.s_t.len() - 1;
        let coverage = self.interface.tolerances().coverage;
        let mut ranges = vec![(0u32, 0u32); faces];
        let pairs = ranges
            .par_chunks_mut(BLOCK)
            .enumerate()
            .map(|(b, out)| {
                let f0 = b * BLOCK;
                // The master face holding the block's first slave node.
                let from = self.s_t[f0] - self.slack;
                let mut k = self.m_t.partition_point(|&t| t <= from).max(1) - 1;
                let mut pairs = 0;
                for (i, r) in out.iter_mut().enumerate() {
                    let (range, count, covered) = self.partners(f0 + i, &mut k);
                    if count == 0 || 1.0 - 0.5 * covered > coverage {
                        return None;
                    }
                    *r = range;
                    pairs += count;
                }
                Some(pairs)
            })
            .try_reduce(|| 0, |a, b| Some(a + b))?;
        Some((ranges, pairs))
    }

    /// The values of slave face `f` against its master faces `range` into `out`: D's block,
    /// and M's columns `range.0 ..= range.1` (master nodes in increasing `t`) for each of the
    /// face's two nodes; the segment-based method's sums at the rule's points of each
    /// overlap.
    fn face_values(&self, f: usize, range: (u32, u32), out: &mut FaceValues) {
        let clip = self.interface.tolerances().clip_area * 2.0;
        let axisymmetric = self.geometry.is_axisymmetric();
        let frame = self.frame(f);
        let det = 0.5 * (frame.xb - frame.xa).norm();
        out.face = f;
        out.q0 = range.0 as usize;
        out.vals.clear();
        out.vals
            .resize(range.1 as usize - range.0 as usize + 1, [0.0; 2]);
        let mut dl = [[0.0; 2]; 2];
        let mut uj = self.offset(&frame, out.q0);
        for j in range.0 as usize..range.1 as usize {
            let uk = self.offset(&frame, j + 1);
            let (lo, hi) = Self::overlap(&frame, uj, uk);
            let (u0, to_eta) = (uj, 2.0 / (uk - uj));
            uj = uk;
            if hi - lo <= clip {
                continue;
            }
            let half = 0.5 * (hi - lo);
            let mut mb = [[0.0; 2]; 2];
            for (g, w) in self.rule.points().iter().zip(self.rule.weights()) {
                let xi = lo + half * (g.x + 1.0);
                let s = 0.5 * (xi + 1.0);
                let eta = (-1.0 + (s * frame.length - u0) * to_eta).clamp(-1.0, 1.0);
                let mut weight = w * half * det;
                if axisymmetric {
                    weight *= self
                        .geometry
                        .weight(&(frame.xa + (frame.xb - frame.xa) * s));
                }
                add_line_point(&self.basis, weight, xi, eta, &mut dl, &mut mb);
            }
            let at = j - out.q0;
            for l in 0..2 {
                for jj in 0..2 {
                    out.vals[at + l][jj] += mb[jj][l];
                }
            }
        }
        out.d = dl;
    }

    /// The slave faces whose values enter the row of chain node `p`: the face before it
    /// (where the node is the face's second and carries a multiplier) and the one after it.
    #[inline]
    fn sides(&self, p: usize) -> (Option<usize>, Option<usize>) {
        let faces = self.s_t.len() - 1;
        let left = (p > 0 && self.basis.carries(1)).then(|| p - 1);
        let right = (p < faces && self.basis.carries(0)).then_some(p);
        (left, right)
    }

    /// D and M row by row: each row's length from the faces' master ranges, then each row
    /// computed from its two faces and written in place, blocks of rows in parallel.
    fn rows(&self, ranges: &[(u32, u32)], spare: &mut Spare) -> (SparseMatrix, SparseMatrix) {
        let interface = self.interface;
        let (ns, nm) = (
            interface.slave_nodes().len(),
            interface.master_nodes().len(),
        );
        let order = if ascending(&self.s_row) {
            RowOrder::Along
        } else if descending(&self.s_row) {
            RowOrder::Against
        } else {
            let mut positions = vec![0u32; ns];
            for (p, &r) in self.s_row.iter().enumerate() {
                positions[r as usize] = p as u32;
            }
            RowOrder::Table(positions)
        };
        let position = |r: usize| match &order {
            RowOrder::Along => r,
            RowOrder::Against => ns - 1 - r,
            RowOrder::Table(positions) => positions[r] as usize,
        };
        // Row lengths: D's from the faces about the node, M's from their master ranges.
        let d_len = |r: usize| match self.sides(position(r)) {
            (Some(_), Some(_)) => 3,
            (None, None) => 0,
            _ => 2,
        };
        let m_len = |r: usize| {
            let (left, right) = self.sides(position(r));
            let nodes = |f: Option<usize>| f.map(|f| ranges[f]);
            let len = match (nodes(left), nodes(right)) {
                (Some((a0, a1)), Some((b0, b1))) if b0 <= a1 + 1 => a1.max(b1) - a0 + 1,
                (a, b) => [a, b].iter().flatten().map(|(q0, q1)| q1 - q0 + 1).sum(),
            };
            len as usize
        };
        let (mut d_ptr, mut m_ptr) = (spare.zeroed_usize(ns + 1), spare.zeroed_usize(ns + 1));
        rayon::join(
            || row_pointer(&mut d_ptr, d_len),
            || row_pointer(&mut m_ptr, m_len),
        );
        let mut d_idx = spare.zeroed_usize(d_ptr[ns]);
        let mut d_val = spare.zeroed_f64(d_ptr[ns]);
        let mut m_idx = spare.zeroed_usize(m_ptr[ns]);
        let mut m_val = spare.zeroed_f64(m_ptr[ns]);
        let d_blocks = split_rows(&d_ptr, &mut d_idx, &mut d_val);
        let m_blocks = split_rows(&m_ptr, &mut m_idx, &mut m_val);
        d_blocks
            .into_par_iter()
            .zip(m_blocks)
            .enumerate()
            .for_each(|(b, (d, m))| {
                let rows = b * BLOCK..((b + 1) * BLOCK).min(ns);
                self.fill_block(ranges, rows.map(position), d, m);
            });
        (
            csr_checked_in_parallel((ns, ns), d_ptr, d_idx, d_val),
            csr_checked_in_parallel((ns, nm), m_ptr, m_idx, m_val),
        )
    }

    /// The rows of chain nodes `positions` (in row order) of D and M into their slices.
    fn fill_block(
        &self,
        ranges: &[(u32, u32)],
        positions: impl Iterator<Item = usize>,
        d: (&mut [usize], &mut [f64]),
        m: (&mut [usize], &mut [f64]),
    ) {
        let mut cache: [FaceValues; 2] = Default::default();
        let mut unsorted: Vec<(usize, f64)> = Vec::new();
        let (mut d, mut m) = (RowWriter::new(d), RowWriter::new(m));
        for p in positions {
            let (left, right) = self.sides(p);
            // Each face computed into the slot the other does not hold.
            let keep = |f: Option<usize>| f.unwrap_or(usize::MAX);
            let l = left.map(|f| self.cached(&mut cache, f, keep(right), ranges));
            let r = right.map(|f| self.cached(&mut cache, f, keep(left), ranges));
            let (l, r) = (l.map(|i| &cache[i]), r.map(|i| &cache[i]));
            // D: columns of nodes p - 1, p, p + 1; the left face's values first.
            let row = |q: usize| self.s_row[q] as usize;
            match (l, r) {
                (Some(l), Some(r)) => {
                    d.push(row(p - 1), l.d[1][0]);
                    d.push(row(p), l.d[1][1] + r.d[0][0]);
                    d.push(row(p + 1), r.d[0][1]);
                }
                (Some(l), None) => {
                    d.push(row(p - 1), l.d[1][0]);
                    d.push(row(p), l.d[1][1]);
                }
                (None, Some(r)) => {
                    d.push(row(p), r.d[0][0]);
                    d.push(row(p + 1), r.d[0][1]);
                }
                (None, None) => {}
            }
            d.end_row(&mut unsorted);
            // M: master nodes in increasing t (the left face's start at or before the right
            // one's, its end at or before the right one's end); the left face's values first.
            let col = |q: usize| self.m_col[q] as usize;
            match (l, r) {
                (Some(l), Some(r)) => {
                    for (i, v) in l.vals.iter().enumerate() {
                        let q = l.q0 + i;
                        let val = match q.checked_sub(r.q0) {
                            Some(at) => v[1] + r.vals[at][0],
                            None => v[1],
                        };
                        m.push(col(q), val);
                    }
                    let from = (l.q0 + l.vals.len()).max(r.q0) - r.q0;
                    for (i, v) in r.vals.iter().enumerate().skip(from) {
                        m.push(col(r.q0 + i), v[0]);
                    }
                }
                (Some(l), None) => {
                    for (i, v) in l.vals.iter().enumerate() {
                        m.push(col(l.q0 + i), v[1]);
                    }
                }
                (None, Some(r)) => {
                    for (i, v) in r.vals.iter().enumerate() {
                        m.push(col(r.q0 + i), v[0]);
                    }
                }
                (None, None) => {}
            }
            m.end_row(&mut unsorted);
        }
        debug_assert!(d.at == d.idx.len() && m.at == m.idx.len());
    }

    /// The slot of `cache` holding face `f`'s values, computed into the slot not holding
    /// face `keep` when neither holds it.
    fn cached(
        &self,
        cache: &mut [FaceValues; 2],
        f: usize,
        keep: usize,
        ranges: &[(u32, u32)],
    ) -> usize {
        if let Some(i) = cache.iter().position(|v| v.face == f) {
            return i;
        }
        let i = usize::from(cache[0].face == keep);
        self.face_values(f, ranges[f], &mut cache[i]);
        i
    }
}

/// Writes rows into a block's slices of a matrix's column indices and values.
struct RowWriter<'s> {
    idx: &'s mut [usize],
    val: &'s mut [f64],
    /// Where the current row starts, and where its next entry goes.
    start: usize,
    at: usize,
}

impl<'s> RowWriter<'s> {
    fn new((idx, val): (&'s mut [usize], &'s mut [f64])) -> Self {
        Self {
            idx,
            val,
            start: 0,
            at: 0,
        }
    }

    /// The next entry of the current row.
    #[inline]
    fn push(&mut self, col: usize, val: f64) {
        self.idx[self.at] = col;
        self.val[self.at] = val;
        self.at += 1;
    }

    /// Ends the current row (of distinct columns), putting its entries in increasing column
    /// order: as they came when they are, reversed when they came the other way (a side
    /// numbered against the slave's chain), sorted (through `scratch`) otherwise.
    fn end_row(&mut self, scratch: &mut Vec<(usize, f64)>) {
        let (idx, val) = (
            &mut self.idx[self.start..self.at],
            &mut self.val[self.start..self.at],
        );
        self.start = self.at;
        if idx.windows(2).all(|w| w[0] < w[1]) {
            return;
        }
        if idx.windows(2).all(|w| w[0] > w[1]) {
            idx.reverse();
            val.reverse();
            return;
        }
        scratch.clear();
        scratch.extend(idx.iter().copied().zip(val.iter().copied()));
        scratch.sort_unstable_by_key(|e| e.0);
        for ((i, v), &(c, x)) in idx.iter_mut().zip(val.iter_mut()).zip(scratch.iter()) {
            *i = c;
            *v = x;
        }
    }
}

/// The row pointer `ptr` of `ptr.len() - 1` rows of lengths `len(r)`, written: sums by
/// block, then each block's pointers from its start, blocks in parallel.
fn row_pointer(ptr: &mut [usize], len: impl Fn(usize) -> usize + Sync) {
    let rows = ptr.len() - 1;
    let block = |b: usize| b * BLOCK..((b + 1) * BLOCK).min(rows);
    let sums: Vec<usize> = (0..rows.div_ceil(BLOCK))
        .into_par_iter()
        .map(|b| block(b).map(&len).sum())
        .collect();
    ptr[0] = 0;
    let mut start = 0;
    let starts: Vec<usize> = sums
        .iter()
        .map(|s| {
            start += s;
            start - s
        })
        .collect();
    ptr[1..]
        .par_chunks_mut(BLOCK)
        .zip(starts)
        .enumerate()
        .for_each(|(b, (out, mut at))| {
            for (o, r) in out.iter_mut().zip(block(b)) {
                at += len(r);
                *o = at;
            }
        });
}

/// The index and value slices of each block of [`BLOCK`] rows of a matrix with row pointer
/// `ptr`.
fn split_rows<'s>(
    ptr: &[usize],
    mut idx: &'s mut [usize],
    mut val: &'s mut [f64],
) -> Vec<(&'s mut [usize], &'s mut [f64])> {
    let rows = ptr.len() - 1;
    (0..rows.div_ceil(BLOCK))
        .map(|b| {
            let (r0, r1) = (b * BLOCK, ((b + 1) * BLOCK).min(rows));
            let len = ptr[r1] - ptr[r0];
            let (i, rest_i) = std::mem::take(&mut idx).split_at_mut(len);
            let (v, rest_v) = std::mem::take(&mut val).split_at_mut(len);
            (idx, val) = (rest_i, rest_v);
            (i, v)
        })
        .collect()
}
