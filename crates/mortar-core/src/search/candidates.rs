use nalgebra::Vector3;
use rayon::prelude::*;

use super::bvh::BoxTree;
use crate::element::MAX_FACE_NODES;
use crate::interface::{Interface, SpatialDim};
use crate::mesh::SurfaceMesh;
use crate::tolerances::Tolerances;

/// Candidate master faces per slave face, in compressed rows: the candidates of slave face `s`
/// are `masters[offsets[s]..offsets[s + 1]]`, ascending.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Candidates {
    /// Row offsets, one more than the slave face count.
    pub offsets: Vec<u32>,
    /// Master face indices.
    pub masters: Vec<u32>,
}

impl Candidates {
    /// The candidates of slave face `s`.
    pub fn of(&self, s: usize) -> &[u32] {
        &self.masters[self.offsets[s] as usize..self.offsets[s + 1] as usize]
    }

    /// Total number of candidate pairs.
    pub fn len(&self) -> usize {
        self.masters.len()
    }

    /// Whether there is no candidate pair.
    pub fn is_empty(&self) -> bool {
        self.masters.is_empty()
    }
}

/// A BVH over the master faces' inflated bounding boxes, queried one slave face at a time.
pub struct MasterTree {
    tree: BoxTree,
}

impl std::fmt::Debug for MasterTree {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("MasterTree")
    }
}

impl MasterTree {
    /// Builds the tree over the master faces of `interface` (boxes computed in parallel on the
    /// current rayon pool).
    pub fn build(interface: &Interface) -> Self {
        let tol = interface.tolerances();
        let master = interface.master();
        let boxes: Vec<_> = (0..master.face_count())
            .into_par_iter()
            .map(|f| face_box(master, f, tol))
            .collect();
        Self {
            tree: BoxTree::build(&boxes, interface.dim() == SpatialDim::Two),
        }
    }

    /// The candidate master faces of slave face `s`, ascending, written into `out` (cleared
    /// first).
    pub fn candidates_into(&self, interface: &Interface, s: usize, out: &mut Vec<u32>) {
        let b = face_box(interface.slave(), s, interface.tolerances());
        self.tree.intersecting_into(&b, out);
    }
}

/// Finds the candidate pairs of a whole interface with parry's BVH (built over the master
/// faces, queried with each slave face). Runs on the current rayon pool; the result does not
/// depend on the thread count. (`assemble_coupling` queries chunk by chunk instead, without
/// storing every candidate.)
pub fn find_candidates(interface: &Interface) -> Candidates {
    let tree = MasterTree::build(interface);
    let lists: Vec<Vec<u32>> = (0..interface.slave().face_count())
        .into_par_iter()
        .map_init(Vec::new, |scratch, s| {
            tree.candidates_into(interface, s, scratch);
            scratch.clone()
        })
        .collect();
    let mut offsets = Vec::with_capacity(lists.len() + 1);
    offsets.push(0u32);
    let mut masters = Vec::with_capacity(lists.iter().map(Vec::len).sum());
    for l in &lists {
        masters.extend_from_slice(l);
        offsets.push(masters.len() as u32);
    }
    Candidates { offsets, masters }
}

/// The face's bounding box, inflated for the search.
fn face_box(mesh: &SurfaceMesh, f: usize, tol: &Tolerances) -> (Vector3<f64>, Vector3<f64>) {
    let mut x = [Vector3::zeros(); MAX_FACE_NODES];
    let k = mesh.face_coords_into(f, &mut x);
    let (mut lo, mut hi) = (x[0], x[0]);
    for p in &x[1..k] {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let pad = tol.search_inflation * (hi - lo).norm() + tol.search_distance;
    let pad = Vector3::repeat(pad);
    (lo - pad, hi + pad)
}
