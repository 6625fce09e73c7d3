//! `modelled_counts`: what each rank of a distributed coupling would hold and send, counted in
//! one process from the ranks' parts, by the same rules as [`couple_distributed`]: the slave
//! faces each rank receives and keeps, the master faces it receives, the messages and their
//! bytes (the messages themselves encoded). No coupling is computed: this is how a partition
//! of a large interface into many parts is measured on one machine.

use mortar_core::SurfaceMesh;

use crate::couple::{master_need, search_reach, slave_reach, with_ghost_faces, DistributedOptions};
use crate::error::Result;
use crate::wire::{Bounds, FaceSource, Faces};

/// What one rank of a modelled distributed coupling holds and sends.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ModelledRank {
    /// Slave faces of its part.
    pub slave_faces: usize,
    /// Slave faces other ranks send it.
    pub received_slave_faces: usize,
    /// Of those, the ones it keeps (two layers around its owned nodes) and couples.
    pub ghost_slave_faces: usize,
    /// Master faces of its part.
    pub master_faces: usize,
    /// Master faces other ranks send it.
    pub ghost_master_faces: usize,
    /// Messages of faces it sends (slave and master).
    pub messages_sent: usize,
    /// Their bytes.
    pub bytes_sent: u64,
}

/// The bounding box of every face of `mesh` and its largest face diameter.
fn extent(mesh: &SurfaceMesh) -> (Bounds, f64, Vec<Bounds>) {
    let boxes: Vec<Bounds> = (0..mesh.face_count()).map(|f| mesh.face_box(f)).collect();
    let mut all = Bounds::EMPTY;
    let mut d = 0.0f64;
    for b in &boxes {
        all.union(b);
        d = d.max(b.diagonal());
    }
    (all, d, boxes)
}

/// The counts of every rank of a distributed coupling whose rank `r` holds `slave[r]` and
/// `master[r]`, with the first pass's search (the widened search of an open gap, which needs a
/// second exchange of master faces, is not modelled).
///
/// # Errors
/// A rank's faces that [`couple_distributed`](crate::couple_distributed) would refuse: node
/// tags with different coordinates in two parts, faces it cannot add.
///
/// # Panics
/// If `slave` and `master` have different lengths.
pub fn modelled_counts(
    slave: &[SurfaceMesh],
    master: &[SurfaceMesh],
    options: &DistributedOptions,
) -> Result<Vec<ModelledRank>> {
    assert_eq!(
        slave.len(),
        master.len(),
        "a slave and a master part per rank"
    );
    let p = slave.len();
    let slave_ext: Vec<_> = slave.iter().map(extent).collect();
    let master_ext: Vec<_> = master.iter().map(extent).collect();
    let ds = slave_ext.iter().fold(0.0f64, |a, e| a.max(e.1));
    let dm = master_ext.iter().fold(0.0f64, |a, e| a.max(e.1));
    let mut out: Vec<ModelledRank> = (0..p)
        .map(|r| ModelledRank {
            slave_faces: slave[r].face_count(),
            master_faces: master[r].face_count(),
            ..ModelledRank::default()
        })
        .collect();
    let reach_of = search_reach(&options.tolerances, ds);
    for r in 0..p {
        // The slave faces the others send here.
        let reach = slave_reach(&slave_ext[r].0, ds);
        let mut received = Faces::default();
        let mut from = Vec::new();
        for q in (0..p).filter(|&q| q != r && slave_ext[q].0.meets(&reach)) {
            let boxes = &slave_ext[q].2;
            let which = (0..boxes.len()).filter(|&f| boxes[f].meets(&reach));
            if which.clone().next().is_none() {
                continue;
            }
            let message = slave[q].write(which);
            out[q].messages_sent += 1;
            out[q].bytes_sent += message.len() as u64;
            received.read(&message, r, q, &options.elements)?;
            from.resize(received.len(), q);
        }
        out[r].received_slave_faces = received.len();
        let (local, _) = with_ghost_faces(r, &slave[r], &received, &from)?;
        out[r].ghost_slave_faces = local.face_count() - slave[r].face_count();
        // The master faces the others send here.
        let mut local_box = Bounds::EMPTY;
        for f in 0..local.face_count() {
            local_box.union(&local.face_box(f));
        }
        let need = master_need(&local_box, reach_of, ds, dm);
        for q in (0..p).filter(|&q| q != r && master_ext[q].0.meets(&need)) {
            let boxes = &master_ext[q].2;
            let which = (0..boxes.len()).filter(|&f| boxes[f].meets(&need));
            let count = which.clone().count();
            if count == 0 {
                continue;
            }
            let message = master[q].write(which);
            out[q].messages_sent += 1;
            out[q].bytes_sent += message.len() as u64;
            out[r].ghost_master_faces += count;
        }
    }
    Ok(out)
}
