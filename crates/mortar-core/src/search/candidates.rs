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

/// Finds the candidate pairs of an interface with parry's BVH (built over the master faces,
/// queried with each slave face). Runs on the current rayon pool; the result does not depend
/// on the thread count.
pub fn find_candidates(interface: &Interface) -> Candidates {
    let tol = interface.tolerances();
    let planar = interface.dim() == SpatialDim::Two;
    let master_boxes = face_boxes(interface.master(), tol);
    let tree = BoxTree::build(&master_boxes, planar);
    let slave = interface.slave();
    let lists: Vec<Vec<u32>> = (0..slave.face_count())
        .into_par_iter()
        .map_init(Vec::new, |scratch, s| {
            let b = face_box(slave, s, tol);
            tree.intersecting_into(&b, scratch);
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

fn face_boxes(mesh: &SurfaceMesh, tol: &Tolerances) -> Vec<(Vector3<f64>, Vector3<f64>)> {
    (0..mesh.face_count())
        .into_par_iter()
        .map(|f| face_box(mesh, f, tol))
        .collect()
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
