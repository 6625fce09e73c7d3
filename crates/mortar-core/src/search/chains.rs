//! The 1D interface searched as a merge: the faces of a two-node line mesh as chains (each
//! face followed by the one that starts where it ends), and the master's candidates of
//! consecutive slave faces found by walking along the master chains from those of the
//! previous slave face, instead of querying a tree.

use std::sync::Arc;

use nalgebra::Vector3;
use rayon::prelude::*;

use super::bvh::{overlaps, union, Box3, BoxTree};
use super::candidates::{points_box, slave_search_box, EMPTY};
use super::master_cache::MasterLineCache;
use crate::element::MAX_FACE_NODES;
use crate::interface::{FaceGeometry, Interface, MasterFaces};
use crate::mesh::SurfaceMesh;

/// No face (the end of an open chain).
pub(crate) const NONE: u32 = u32::MAX;

/// The faces of a mesh of two-node lines in chain order: each open chain from its first face
/// (the one no face ends into) to its last, then each closed chain from its lowest-numbered
/// face round to it. Built only when every node starts at most one face and ends at most one
/// (no branch, and the faces oriented alike along each chain, as the interface's orientation
/// leaves them).
#[derive(Debug, Clone, Default)]
pub(crate) struct LineChains {
    /// Face indices in chain order.
    pub order: Vec<u32>,
    /// Per position in `order`, the position of the next face of its chain (`NONE` at the
    /// end of an open chain; the last face of a closed chain names its first).
    pub next: Vec<u32>,
    /// Per position, the position of the previous face (`NONE` at the start of an open
    /// chain).
    pub prev: Vec<u32>,
}

impl LineChains {
    /// The chains of `mesh`, or `None` if a face does not have two distinct nodes or a node
    /// starts or ends two faces.
    pub(crate) fn of(mesh: &SurfaceMesh) -> Option<Self> {
        let n = mesh.face_count();
        let nodes = mesh.coords().len();
        // Each face's two nodes, read once (in parallel).
        let ends: Vec<(u32, u32)> = (0..n)
            .into_par_iter()
            .map(|f| match mesh.face(f).nodes {
                &[a, b] if a != b => (a, b),
                _ => (NONE, NONE),
            })
            .collect();
        let (mut starting, mut ending) = (vec![NONE; nodes], vec![NONE; nodes]);
        for (f, &(a, b)) in ends.iter().enumerate() {
            if a == NONE || starting[a as usize] != NONE || ending[b as usize] != NONE {
                return None;
            }
            starting[a as usize] = f as u32;
            ending[b as usize] = f as u32;
        }
        // Each face's neighbours along its chain, looked up in parallel (a file in random
        // order makes these cache misses; in parallel they overlap), so that the walk below
        // follows one array.
        let next_face: Vec<u32> = ends
            .par_iter()
            .map(|&(_, b)| starting[b as usize])
            .collect();
        let prev_face: Vec<u32> = ends.par_iter().map(|&(a, _)| ending[a as usize]).collect();
        drop((starting, ending, ends));
        let mut pos = vec![NONE; n];
        let mut order = Vec::with_capacity(n);
        let walk = |first: usize, pos: &mut Vec<u32>, order: &mut Vec<u32>| {
            let mut f = first;
            loop {
                pos[f] = order.len() as u32;
                order.push(f as u32);
                let next = next_face[f];
                if next == NONE || next as usize == first {
                    break;
                }
                f = next as usize;
            }
        };
        for f in 0..n {
            if prev_face[f] == NONE {
                walk(f, &mut pos, &mut order);
            }
        }
        for f in 0..n {
            if pos[f] == NONE {
                walk(f, &mut pos, &mut order);
            }
        }
        debug_assert_eq!(order.len(), n);
        let link = |face: u32| {
            if face == NONE {
                NONE
            } else {
                pos[face as usize]
            }
        };
        let next = order
            .par_iter()
            .map(|&f| link(next_face[f as usize]))
            .collect();
        let prev = order
            .par_iter()
            .map(|&f| link(prev_face[f as usize]))
            .collect();
        Some(Self { order, next, prev })
    }
}

/// Master faces per block of [`ChainSearch`]'s exhaustive query.
const BLOCK: usize = 32;

/// A walk that reaches this many candidates hands over to the exhaustive query (a slave
/// face far coarser than its master), and such a face goes to the integration strategy: the
/// fused kernel merges its columns by a linear search.
pub(crate) const WALK_LIMIT: usize = 64;

/// The master side of the merge: the master faces' chains by slot (a face's slot is its
/// position in chain order, the order of the [`MasterFaces`] built from
/// [`LineChains::order`]), and an exhaustive query over blocks of consecutive slots for the
/// first face of a walk and for faces the walk does not settle.
///
/// Both queries test the same boxes as [`MasterTree`](super::MasterTree) (each master face's
/// node box against the slave face's search box, padded as the coupling's [`Padding`](super::Padding) says: a two-node
/// line lies in its nodes' box, so the master's are never inflated), in `f64` where the tree compares
/// its boxes rounded outward to `f32`: the exhaustive query finds the tree's candidates but
/// those whose boxes miss the search box by less than that rounding (which cannot overlap the
/// slave face within the search radius), the walk those of them connected along the master
/// chain to the previous slave face's.
pub(crate) struct ChainSearch {
    next: Vec<u32>,
    prev: Vec<u32>,
    blocks: BoxTree,
    /// The slot of each chain's first face, ascending (the chains are consecutive runs of
    /// slots).
    chain_starts: Vec<u32>,
    /// The inflation of the slave faces' search boxes.
    slave_inflation: f64,
    /// Each slave face's search radius by face index, where the coupling set them one by
    /// one; else the tolerances'.
    radii: Option<Arc<[f64]>>,
}

impl ChainSearch {
    /// The search over `masters` (in the chain order of `chains`, the master's chains), the
    /// slave faces' search boxes inflated by `slave_inflation` of their diameters.
    pub(crate) fn new(
        interface: &Interface,
        masters: &MasterFaces,
        chains: LineChains,
        slave_inflation: f64,
        radii: Option<Arc<[f64]>>,
    ) -> Self {
        let blocks: Vec<Box3> = (0..masters.len().div_ceil(BLOCK))
            .into_par_iter()
            .map(|b| {
                let mut x = [Vector3::zeros(); MAX_FACE_NODES];
                let slots = b * BLOCK..((b + 1) * BLOCK).min(masters.len());
                slots.fold(EMPTY, |acc, s| {
                    let k = masters.node_coords_into(interface, s, &mut x);
                    union(&acc, &points_box(&x[..k], 0.0))
                })
            })
            .collect();
        // A chain starts where the slot before does not lead to it.
        let chain_starts = (0..chains.next.len() as u32)
            .filter(|&p| p == 0 || chains.next[p as usize - 1] != p)
            .collect();
        Self {
            next: chains.next,
            prev: chains.prev,
            blocks: BoxTree::build(blocks, true),
            chain_starts,
            slave_inflation,
            radii,
        }
    }

    /// The search box of slave face `face`.
    fn search_box(&self, interface: &Interface, face: &FaceGeometry) -> Box3 {
        let radius = self.radii.as_ref().map(|r| r[face.index as usize]);
        slave_search_box(interface, face, self.slave_inflation, radius)
    }

    /// The chain of the face in slot `s` (its index in `chain_starts`).
    #[inline]
    fn chain_of(&self, s: u32) -> usize {
        self.chain_starts.partition_point(|&c| c <= s) - 1
    }

    /// Whether a face of a chain other than `chain` meets the search box `b`: the blocks
    /// that meet it, and in those that hold another chain's faces, those faces one by one.
    #[cold]
    #[inline(never)]
    fn other_chain_meets(
        &self,
        interface: &Interface,
        masters: &MasterFaces,
        chain: usize,
        b: &Box3,
        blocks: &mut Vec<u32>,
    ) -> bool {
        blocks.clear();
        self.blocks.append_intersecting(b, blocks);
        blocks.iter().any(|&k| {
            let first = k * BLOCK as u32;
            let last = ((k as usize + 1) * BLOCK).min(self.next.len()) as u32 - 1;
            if self.chain_of(first) == chain && self.chain_of(last) == chain {
                return false;
            }
            (first..=last)
                .any(|s| self.chain_of(s) != chain && self.meets(interface, masters, s, b))
        })
    }

    /// The box of the master face in slot `s`.
    #[inline]
    fn face_box(&self, interface: &Interface, masters: &MasterFaces, s: u32) -> Box3 {
        let mut x = [Vector3::zeros(); MAX_FACE_NODES];
        let k = masters.node_coords_into(interface, s as usize, &mut x);
        points_box(&x[..k], 0.0)
    }

    /// Whether the master face in slot `s` meets the search box `b`.
    #[inline]
    fn meets(&self, interface: &Interface, masters: &MasterFaces, s: u32, b: &Box3) -> bool {
        overlaps(b, &self.face_box(interface, masters, s), true)
    }

    /// Every master face whose box meets the search box of `face` (the tree's candidates),
    /// ascending, into `out` (cleared first).
    pub(crate) fn exhaustive(
        &self,
        interface: &Interface,
        masters: &MasterFaces,
        face: &FaceGeometry,
        out: &mut Vec<u32>,
    ) {
        let b = self.search_box(interface, face);
        out.clear();
        self.blocks.append_intersecting(&b, out);
        let hits = out.len();
        for i in 0..hits {
            let first = out[i] as usize * BLOCK;
            let last = (first + BLOCK).min(self.next.len());
            for s in first as u32..last as u32 {
                if self.meets(interface, masters, s, &b) {
                    out.push(s);
                }
            }
        }
        out.drain(..hits);
        out.sort_unstable();
    }

    /// A run of master faces whose boxes meet the search box of `face`, connected along
    /// their chain: from the first of `seeds` (the previous slave face's candidates) that
    /// meets it, or else the first of their neighbours that does, back and forth along the
    /// chain as far as the faces meet it, into `out` (cleared first; in walk order). The master
    /// lines are read through `lines`.
    /// `false` when neither the seeds nor their neighbours meet the box, or the run passes
    /// [`WALK_LIMIT`] faces: the caller then asks [`exhaustive`](Self::exhaustive).
    ///
    /// The run holds every candidate of a slave face whose master partners are one stretch
    /// of one chain, the common case; where they are not (two master bodies meet under the
    /// face, a master that leaves the box and comes back), the faces left out show as
    /// uncovered slave area, and the caller takes the exhaustive query for such a face. What
    /// the run cannot show is a second master layer over a face it covers: so where the
    /// master has other chains, a face of another chain that meets the search box (found by
    /// the blocks' tree) also returns `false`. A second layer of the same chain (a master
    /// that spirals round to face the slave face again within the search radius) is not
    /// looked for.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn walk(
        &self,
        interface: &Interface,
        masters: &MasterFaces,
        lines: &mut MasterLineCache,
        face: &FaceGeometry,
        seeds: &[u32],
        out: &mut Vec<u32>,
        blocks: &mut Vec<u32>,
    ) -> bool {
        let b = self.search_box(interface, face);
        let mut meets = |s: u32| overlaps(&b, &lines.get(interface, masters, s).bx, true);
        out.clear();
        let first = seeds.iter().copied().find(|&s| meets(s)).or_else(|| {
            seeds.iter().find_map(|&s| {
                [self.next[s as usize], self.prev[s as usize]]
                    .into_iter()
                    .find(|&t| t != NONE && meets(t))
            })
        });
        let Some(first) = first else {
            return false;
        };
        out.push(first);
        // Back along the chain; round a closed chain at most once.
        let mut t = self.prev[first as usize];
        while t != NONE && t != first && meets(t) {
            if out.len() == WALK_LIMIT {
                return false;
            }
            out.push(t);
            t = self.prev[t as usize];
        }
        if t == first {
            return self.alone(interface, masters, first, &b, blocks);
        }
        // Forward: it stops at the face that stopped the walk back at the latest.
        let mut t = self.next[first as usize];
        while t != NONE && meets(t) {
            if out.len() == WALK_LIMIT {
                return false;
            }
            out.push(t);
            t = self.next[t as usize];
        }
        self.alone(interface, masters, first, &b, blocks)
    }

    /// Whether no face of another chain than the face in slot `first`'s meets the search box
    /// `b` (at once where the master is one chain).
    #[inline]
    fn alone(
        &self,
        interface: &Interface,
        masters: &MasterFaces,
        first: u32,
        b: &Box3,
        blocks: &mut Vec<u32>,
    ) -> bool {
        self.chain_starts.len() == 1
            || !self.other_chain_meets(interface, masters, self.chain_of(first), b, blocks)
    }
}
