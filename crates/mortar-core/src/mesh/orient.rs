//! Orientation of surfaces: consistent within each connected piece, then turned so that the
//! slave and the master face each other.
//!
//! Mesh generators do not promise outward normals on a surface given alone (Gmsh orients the
//! curves of an OpenCASCADE disc and of the hole of an annulus the same way round). When the
//! bodies are known, orient from them (the facade's readers do); otherwise:
//!
//! 1. [`orient_consistently`]: in each connected piece of a surface (faces joined across
//!    shared edges, lines across shared nodes), every face is turned to agree with the piece's
//!    first face. A non-manifold edge (three faces on it) or a non-orientable piece (a Moebius
//!    strip) is an error naming the faces.
//! 2. [`face_each_other`]: each slave piece is turned so that its normals point to the master
//!    across an open gap (kept as given where the surfaces touch: nothing tells the sides
//!    apart there), then each master piece so that its normals oppose the slave's.

use nalgebra::Vector3;

use super::SurfaceMesh;
use crate::element::{ReferenceDomain, MAX_FACE_NODES};
use crate::error::{FaceLocation, MortarError, Result, Side};
use crate::geometry::{stable_norm, stable_normalize};

/// What orienting a surface did.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct OrientationReport {
    /// Connected pieces of the surface.
    pub components: usize,
    /// Faces whose node order was reversed.
    pub flipped: usize,
    /// Pieces whose sense could not be decided (they touch the other surface without a gap)
    /// and were kept as given (after being made consistent).
    pub kept_as_given: usize,
}

/// A face's unit normal, centre and measure.
type FaceFrame = (Vector3<f64>, Vector3<f64>, f64);

/// The unit normal and the centre of each face, and its measure.
fn face_frames(mesh: &SurfaceMesh) -> Vec<FaceFrame> {
    (0..mesh.face_count())
        .map(|f| {
            let view = mesh.face(f);
            let el = view.element;
            let mut x = [Vector3::zeros(); MAX_FACE_NODES];
            let k = mesh.face_coords_into(f, &mut x);
            let c = el.domain().centre();
            let n = el.scaled_normal(&x[..k], &c);
            let centre = el.map(&x[..k], &c);
            (
                stable_normalize(&n).unwrap_or_default(),
                centre,
                stable_norm(&n) * el.domain().measure(),
            )
        })
        .collect()
}

/// The directed "edges" of face `f`: consecutive corners for a face, the nodes of a line
/// (its start counts as `(node, out)`, its end as `(node, in)`).
fn directed_edges(mesh: &SurfaceMesh, f: usize, out: &mut Vec<(u32, u32)>) {
    out.clear();
    let view = mesh.face(f);
    let el = view.element;
    let c = el.corner_count();
    if el.domain() == ReferenceDomain::Line {
        // A line is an edge from its start to its end; neighbours meet at nodes.
        out.push((view.nodes[0], u32::MAX));
        out.push((u32::MAX, view.nodes[1]));
    } else {
        for i in 0..c {
            out.push((view.nodes[i], view.nodes[(i + 1) % c]));
        }
    }
}

/// A face across an edge of another (see [`EdgeNeighbours`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Neighbour {
    /// The neighbouring face.
    pub face: u32,
    /// Whether both faces traverse the shared edge the same way (both lines start, or both
    /// end, at the shared node): then they are oriented against each other.
    pub same_direction: bool,
    /// The shared edge's nodes, lower index first (a line's shared node twice).
    pub edge: (u32, u32),
}

/// The faces that share an edge with each face (lines: a node), in compressed rows: the
/// connectivity that orientation follows. Two faces sharing an edge are consistently oriented
/// if and only if they traverse it in opposite directions; two lines sharing a node if and
/// only if one ends where the other starts.
#[derive(Debug, Clone, Default)]
pub(crate) struct EdgeNeighbours {
    offsets: Vec<u32>,
    entries: Vec<Neighbour>,
}

impl EdgeNeighbours {
    /// The neighbours of every face of `mesh`.
    ///
    /// # Errors
    /// [`MortarError::Topology`] for an edge shared by more than two faces (a fin: the
    /// surface is not a manifold there), or a node shared by more than two lines (a T
    /// junction), naming the faces, the last of them (in face order) as the location.
    pub(crate) fn build(mesh: &SurfaceMesh, side: Option<Side>) -> Result<Self> {
        let n = mesh.face_count();
        // Undirected edge key -> (face, direction) incidences; a line's "edge" is a node.
        let key = |(a, b): (u32, u32)| {
            if a == u32::MAX {
                ((b, b), false)
            } else if b == u32::MAX {
                ((a, a), true)
            } else if a < b {
                ((a, b), true)
            } else {
                ((b, a), false)
            }
        };
        // Sorted by key: bucketed by the key's lower node (a counting sort, linear), then each
        // bucket (the few edges at one node) sorted on its own.
        let mut start = vec![0u32; mesh.node_count() + 1];
        let mut edges = Vec::new();
        for f in 0..n {
            directed_edges(mesh, f, &mut edges);
            for &e in &edges {
                start[key(e).0 .0 as usize + 1] += 1;
            }
        }
        for i in 0..mesh.node_count() {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut incidences = vec![((0u32, 0u32), 0u32, false); start[mesh.node_count()] as usize];
        for f in 0..n {
            directed_edges(mesh, f, &mut edges);
            for &e in &edges {
                let (k, forward) = key(e);
                let slot = &mut fill[k.0 as usize];
                incidences[*slot as usize] = (k, f as u32, forward);
                *slot += 1;
            }
        }
        for w in start.windows(2) {
            incidences[w[0] as usize..w[1] as usize].sort_unstable();
        }
        let mut count = vec![0u32; n + 1];
        for group in incidences.chunk_by(|a, b| a.0 == b.0) {
            match group {
                [_] => {}
                [(_, f, _), (_, g, _)] => {
                    if f != g {
                        count[*f as usize] += 1;
                        count[*g as usize] += 1;
                    }
                }
                _ => return Err(non_manifold(mesh, side, group)),
            }
        }
        let mut offsets = vec![0u32; n + 1];
        for f in 0..n {
            offsets[f + 1] = offsets[f] + count[f];
        }
        let mut fill = offsets.clone();
        let mut entries = vec![
            Neighbour {
                face: 0,
                same_direction: false,
                edge: (0, 0),
            };
            offsets[n] as usize
        ];
        for group in incidences.chunk_by(|a, b| a.0 == b.0) {
            if let [(edge, f, df), (_, g, dg)] = group {
                if f == g {
                    continue;
                }
                for (a, b) in [(*f, *g), (*g, *f)] {
                    entries[fill[a as usize] as usize] = Neighbour {
                        face: b,
                        same_direction: df == dg,
                        edge: *edge,
                    };
                    fill[a as usize] += 1;
                }
            }
        }
        Ok(Self { offsets, entries })
    }

    /// The neighbours of face `f`.
    pub(crate) fn of(&self, f: usize) -> &[Neighbour] {
        &self.entries[self.offsets[f] as usize..self.offsets[f + 1] as usize]
    }
}

/// The topology error of more than two faces on one edge (lines on one node): `group` holds
/// their incidences.
fn non_manifold(
    mesh: &SurfaceMesh,
    side: Option<Side>,
    group: &[((u32, u32), u32, bool)],
) -> MortarError {
    let tags = mesh.node_tags();
    let (a, b) = group[0].0;
    let mut faces: Vec<u32> = group.iter().map(|(_, f, _)| *f).collect();
    faces.sort_unstable();
    let names: Vec<String> = faces
        .iter()
        .map(|&f| mesh.face(f as usize).tag.to_string())
        .collect();
    let last = faces.last().copied().unwrap_or(group[0].1);
    let prefix = side.map(|s| format!("{s} ")).unwrap_or_default();
    let reason = if a == b {
        format!(
            "node {} is shared by {} {prefix}lines ({}): a T junction (a line interface is a \
             chain, each node joining at most two lines); split the interface there or remove \
             the extra line",
            tags[a as usize],
            group.len(),
            names.join(", ")
        )
    } else {
        format!(
            "the edge between nodes {} and {} is shared by {} {prefix}faces ({}): a fin, the \
             surface is not a manifold there (each edge joins at most two faces); remove the \
             extra face",
            tags[a as usize],
            tags[b as usize],
            group.len(),
            names.join(", ")
        )
    };
    MortarError::Topology {
        face: FaceLocation {
            side,
            tag: mesh.face(last as usize).tag,
        },
        faces: faces.iter().map(|&f| mesh.face(f as usize).tag).collect(),
        reason,
    }
}

/// Each face's connected piece (faces joined across shared edges, numbered in order of their
/// first face) and whether it must be reversed to agree with the first face of its piece:
/// breadth-first over each piece, a neighbour across an edge traversed the same way is turned
/// relative to its parent.
///
/// # Errors
/// [`MortarError::Topology`] for a piece that cannot be oriented (a Moebius strip).
pub(crate) fn consistent_flips(
    mesh: &SurfaceMesh,
    side: Option<Side>,
    neighbours: &EdgeNeighbours,
) -> Result<(Vec<u32>, Vec<bool>)> {
    let n = mesh.face_count();
    let face_tag = |f: u32| mesh.face(f as usize).tag;
    const UNSEEN: u32 = u32::MAX;
    let mut component = vec![UNSEEN; n];
    let mut flip = vec![false; n];
    let mut pieces = 0u32;
    let mut queue = std::collections::VecDeque::new();
    for start in 0..n {
        if component[start] != UNSEEN {
            continue;
        }
        component[start] = pieces;
        queue.push_back(start as u32);
        while let Some(f) = queue.pop_front() {
            for nb in neighbours.of(f as usize) {
                let g = nb.face;
                let want = flip[f as usize] ^ nb.same_direction;
                if component[g as usize] == UNSEEN {
                    component[g as usize] = pieces;
                    flip[g as usize] = want;
                    queue.push_back(g);
                } else if flip[g as usize] != want {
                    return Err(MortarError::Topology {
                        face: FaceLocation { side, tag: face_tag(g) },
                        faces: Box::new([face_tag(f), face_tag(g)]),
                        reason: format!(
                            "the connected surface through faces {} and {} cannot be oriented (it is one-sided, like a Moebius strip)",
                            face_tag(f),
                            face_tag(g)
                        ),
                    });
                }
            }
        }
        pieces += 1;
    }
    Ok((component, flip))
}

/// Makes every connected piece of `mesh` consistently oriented (each face agreeing with the
/// first face of its piece, in face order) and returns each face's piece (numbered in order of
/// first face) and whether it was reversed.
///
/// # Errors
/// [`MortarError::DegenerateFace`] for a face that lists a node twice (checked first: such a
/// face would otherwise look like a fin); [`MortarError::Topology`] for an edge shared by
/// more than two faces (three lines at a node in 2D), or a piece that cannot be oriented (a
/// Moebius strip); the error of [`SurfaceMesh::reverse_face`] for an element that cannot be
/// reversed.
pub fn orient_consistently(
    mesh: &mut SurfaceMesh,
    side: Option<Side>,
) -> Result<(Vec<u32>, Vec<bool>)> {
    for f in 0..mesh.face_count() {
        let face = mesh.face(f);
        if let Some((_, a)) = face
            .nodes
            .iter()
            .enumerate()
            .find(|(i, a)| face.nodes[i + 1..].contains(a))
        {
            return Err(MortarError::DegenerateFace {
                face: FaceLocation {
                    side,
                    tag: face.tag,
                },
                reason: format!("node {} appears twice", mesh.node_tags()[*a as usize]),
            });
        }
    }
    let neighbours = EdgeNeighbours::build(mesh, side)?;
    let (component, flip) = consistent_flips(mesh, side, &neighbours)?;
    for (f, &turn) in flip.iter().enumerate() {
        if turn {
            mesh.reverse_face(f)?;
        }
    }
    Ok((component, flip))
}

/// Orients the slave and the master surface to face each other (see the module
/// documentation): each made consistent piece by piece, each slave piece turned to point at
/// the master across the gap, each master piece turned against the slave. Pairs of faces are
/// those whose centres lie within `reach` times the slave face's size of each other along the
/// slave normal and within its size across it; of those, each slave face heeds the nearest
/// along its normal. `keep_slave` and `keep_master` keep the sense
/// of a side already oriented (from its bodies, say): it is made consistent but not turned.
///
/// # Errors
/// The errors of [`orient_consistently`].
pub fn face_each_other(
    slave: &mut SurfaceMesh,
    master: &mut SurfaceMesh,
    reach: f64,
    keep_slave: bool,
    keep_master: bool,
) -> Result<[OrientationReport; 2]> {
    let (slave_pieces, slave_flips) = orient_consistently(slave, Some(Side::Slave))?;
    let (master_pieces, master_flips) = orient_consistently(master, Some(Side::Master))?;
    let ns = slave_pieces
        .iter()
        .map(|&c| c as usize + 1)
        .max()
        .unwrap_or(0);
    let nm = master_pieces
        .iter()
        .map(|&c| c as usize + 1)
        .max()
        .unwrap_or(0);
    let fs = face_frames(slave);
    let fm = face_frames(master);
    let sizes = face_sizes(slave);
    let near = nearby_pairs(&fs, &fm, &sizes, reach);
    // Slave pieces: the master on the normal's side (a positive gap) or the other.
    let mut votes = vec![(0.0f64, 0.0f64); ns];
    for &(s, _, along) in &near {
        let s = s as usize;
        let tol = 1e-3 * sizes[s];
        let piece = slave_pieces[s] as usize;
        if along > tol {
            votes[piece].0 += fs[s].2;
        } else if along < -tol {
            votes[piece].1 += fs[s].2;
        }
    }
    let mut slave_report = OrientationReport {
        components: ns,
        ..Default::default()
    };
    let mut turn_slave = vec![false; ns];
    for (p, &(ahead, behind)) in votes.iter().enumerate() {
        if keep_slave {
            continue;
        }
        if behind > 2.0 * ahead {
            turn_slave[p] = true;
        } else if ahead <= 2.0 * behind {
            slave_report.kept_as_given += 1;
        }
    }
    let mut fs = fs;
    for (f, frame) in fs.iter_mut().enumerate() {
        let p = slave_pieces[f] as usize;
        if turn_slave[p] {
            slave.reverse_face(f)?;
            frame.0 = -frame.0;
        }
    }
    // Master pieces: normals against the slave's.
    let mut agree = vec![0.0f64; nm];
    for &(s, m, _) in &near {
        let (s, m) = (s as usize, m as usize);
        agree[master_pieces[m] as usize] += fs[s].0.dot(&fm[m].0) * fs[s].2;
    }
    let turn_master: Vec<bool> = agree.iter().map(|&a| a > 0.0 && !keep_master).collect();
    for f in 0..master.face_count() {
        if turn_master[master_pieces[f] as usize] {
            master.reverse_face(f)?;
        }
    }
    slave_report.flipped = net_flips(&slave_flips, &slave_pieces, &turn_slave);
    Ok([
        slave_report,
        OrientationReport {
            components: nm,
            flipped: net_flips(&master_flips, &master_pieces, &turn_master),
            kept_as_given: agree.iter().filter(|&&a| a == 0.0).count(),
        },
    ])
}

/// The size of each face of `mesh`: the largest distance between two of its nodes.
fn face_sizes(mesh: &SurfaceMesh) -> Vec<f64> {
    (0..mesh.face_count())
        .map(|f| {
            let mut x = [Vector3::zeros(); MAX_FACE_NODES];
            let k = mesh.face_coords_into(f, &mut x);
            (0..k)
                .flat_map(|i| (i + 1..k).map(move |j| (i, j)))
                .map(|(i, j)| (x[i] - x[j]).norm())
                .fold(0.0, f64::max)
        })
        .collect()
}

/// The nearby pairs (slave face, master face, distance along the slave normal) of the
/// slave faces' and master faces' frames `fs`, `fm` (normal, centre, area), the slave faces
/// of sizes `sizes`: centres within `reach` times the slave face's size of each other along
/// its normal and within its size across it.
fn nearby_pairs(
    fs: &[FaceFrame],
    fm: &[FaceFrame],
    sizes: &[f64],
    reach: f64,
) -> Vec<(u32, u32, f64)> {
    // Nearby pairs by a grid of master centres. A pair's centres lie within
    // `sqrt(1 + reach^2)` times the largest slave size of each other, so with cells that wide
    // a slave face's partners are in the 27 cells around its own.
    let largest = sizes.iter().copied().fold(0.0, f64::max);
    let cell = largest * (1.0 + reach * reach).sqrt() * (1.0 + 1e-9);
    let key = |x: &Vector3<f64>| {
        (
            (x.x / cell).floor() as i64,
            (x.y / cell).floor() as i64,
            (x.z / cell).floor() as i64,
        )
    };
    let mut grid: rustc_hash::FxHashMap<(i64, i64, i64), Vec<u32>> = Default::default();
    if cell > 0.0 && cell.is_finite() {
        for (m, (_, c, _)) in fm.iter().enumerate() {
            grid.entry(key(c)).or_default().push(m as u32);
        }
    }
    // Nearby pairs (slave face, master face, distance along the slave normal), the slave
    // faces in chunks on all threads, concatenated in face order. Each slave face heeds the
    // nearest master faces along its normal only (within a thousandth of its size of the
    // nearest): where the surfaces touch, the faces behind them must not decide, neither those
    // of the next facet of a coarse closed surface (a triangle's sides turn by 120 degrees:
    // the master faces near a corner lie behind the next side) nor those of the far side of a
    // thin body within reach (a short prism's caps).
    {
        use rayon::prelude::*;
        const CHUNK: usize = 4096;
        let chunks: Vec<Vec<(u32, u32, f64)>> = fs
            .par_chunks(CHUNK)
            .enumerate()
            .map(|(chunk, frames)| {
                let mut out = Vec::new();
                let mut pairs = Vec::new();
                for (i, (n, c, _)) in frames.iter().enumerate() {
                    let s = chunk * CHUNK + i;
                    let (i, j, k) = key(c);
                    pairs.clear();
                    for di in -1..=1 {
                        for dj in -1..=1 {
                            for dk in -1..=1 {
                                let cell = grid.get(&(i + di, j + dj, k + dk));
                                for &m in cell.into_iter().flatten() {
                                    let d = fm[m as usize].1 - c;
                                    let along = n.dot(&d);
                                    let across = (d - n * along).norm();
                                    if across <= sizes[s] && along.abs() <= reach * sizes[s] {
                                        pairs.push((s as u32, m, along));
                                    }
                                }
                            }
                        }
                    }
                    let closest = pairs
                        .iter()
                        .map(|p| p.2.abs())
                        .fold(f64::INFINITY, f64::min);
                    let tol = 1e-3 * sizes[s];
                    out.extend(pairs.iter().filter(|p| p.2.abs() <= closest + tol));
                }
                out
            })
            .collect();
        chunks.concat()
    }
}

/// The faces reversed overall: for consistency, or with their piece, not both.
fn net_flips(consistency: &[bool], pieces: &[u32], turned: &[bool]) -> usize {
    consistency
        .iter()
        .zip(pieces)
        .filter(|(&c, &p)| c != turned[p as usize])
        .count()
}
