//! The local blocks of one slave face: its D block and one M block per master face it meets,
//! integrated from the paired quadrature points the integration strategy hands over.

use super::key_index::KeyIndex;
use crate::element::{ElementRef, MAX_FACE_NODES};
use crate::integration::PairedPoint;
use crate::interface::{FaceGeometry, Interface, MasterFaces};
use crate::multiplier::LmBasis;

type Block = [[f64; MAX_FACE_NODES]; MAX_FACE_NODES];

/// The local D block of one slave face and one M block per master face it meets.
#[derive(Debug, Clone, Default)]
pub struct LocalBlocks {
    /// `d[j][k] = int Phi_j N_k^s` over the face's overlap.
    pub d: Block,
    /// `(master face, master node count, offset into vals)` per M block.
    masters: Vec<(u32, usize, usize)>,
    /// The M blocks, each `ks x km` row-major: `m[j][l] = int Phi_j N_l^m`.
    vals: Vec<f64>,
    ks: usize,
    /// Where each master face is in `masters`.
    index: KeyIndex,
}

impl LocalBlocks {
    /// Starts a slave face with `ks` nodes: D and the M blocks zero.
    pub fn start_face(&mut self, ks: usize) {
        self.d = [[0.0; MAX_FACE_NODES]; MAX_FACE_NODES];
        self.ks = ks;
        self.clear_m_blocks();
    }

    /// Forgets the M blocks (once they have been scattered), keeping D: the next batch of
    /// the same face's points then adds to D and starts new M blocks.
    pub fn clear_m_blocks(&mut self) {
        self.masters.clear();
        self.vals.clear();
        self.index.clear();
    }

    /// The offset of the block of `master` (with `km` nodes), created zero if new.
    fn block_offset(&mut self, master: u32, km: usize) -> usize {
        let masters = &self.masters;
        match self.index.find(masters.len(), |i| masters[i].0, master) {
            Some(i) => self.masters[i].2,
            None => {
                let off = self.vals.len();
                self.vals.resize(off + self.ks * km, 0.0);
                self.masters.push((master, km, off));
                self.index.pushed(master, self.masters.len() - 1);
                off
            }
        }
    }

    /// The M blocks: `(master face, its node count km, the ks x km block row-major)`.
    pub fn m_blocks(&self) -> impl Iterator<Item = (u32, usize, &[f64])> + '_ {
        self.masters
            .iter()
            .map(|&(f, km, off)| (f, km, &self.vals[off..off + self.ks * km]))
    }
}

/// Integrates one slave face's paired points (against the faces of `masters`, built for
/// `interface`) into local
/// blocks (cleared first):
/// `D += w Phi_j(xi_s) N_k(xi_s)`, `M += w Phi_j(xi_s) N_l^m(xi_m)`.
pub fn integrate_face_into(
    interface: &Interface,
    masters: &MasterFaces,
    slave: &FaceGeometry,
    basis: &LmBasis,
    points: &[PairedPoint],
    out: &mut LocalBlocks,
) {
    out.start_face(slave.node_count());
    integrate_batch_into(interface, masters, slave, basis, points, out);
}

/// Adds one batch of a slave face's paired points to `out` (started with
/// [`LocalBlocks::start_face`]): D goes on summing point after point, in the order of the
/// batches (so a face integrated in batches gets the bits of the face integrated at once),
/// and each master face of the batch gets a new M block, or adds to its block if `out`
/// still holds it. The points of one master face must all be in one batch for its M block
/// to be complete.
pub fn integrate_batch_into(
    interface: &Interface,
    masters: &MasterFaces,
    slave: &FaceGeometry,
    basis: &LmBasis,
    points: &[PairedPoint],
    out: &mut LocalBlocks,
) {
    debug_assert_eq!(out.ks, slave.node_count(), "start_face first");
    // Fixed-size kernels for the common node counts let the compiler unroll the products.
    match (
        slave.node_count(),
        common_master_nodes(interface, masters, points),
    ) {
        (3, Some(3)) => kernel::<3, 3>(interface, masters, slave, basis, points, out),
        (3, Some(4)) => kernel::<3, 4>(interface, masters, slave, basis, points, out),
        (4, Some(3)) => kernel::<4, 3>(interface, masters, slave, basis, points, out),
        (4, Some(4)) => kernel::<4, 4>(interface, masters, slave, basis, points, out),
        (2, Some(2)) => kernel::<2, 2>(interface, masters, slave, basis, points, out),
        _ => general(interface, masters, slave, basis, points, out),
    }
}

/// The node count shared by every master face of `points`, if they all have the same.
fn common_master_nodes(
    interface: &Interface,
    masters: &MasterFaces,
    points: &[PairedPoint],
) -> Option<usize> {
    let mut count = None;
    let mut last = u32::MAX;
    for p in points {
        if p.master != last {
            last = p.master;
            let k = masters.element(interface, p.master as usize).node_count();
            if count.is_some_and(|c| c != k) {
                return None;
            }
            count = Some(k);
        }
    }
    count
}

fn kernel<const KS: usize, const KM: usize>(
    interface: &Interface,
    masters: &MasterFaces,
    slave: &FaceGeometry,
    basis: &LmBasis,
    points: &[PairedPoint],
    out: &mut LocalBlocks,
) {
    // D goes on from the earlier batches of the face (zero for the first).
    let mut d = [[0.0; KS]; KS];
    for j in 0..KS {
        for k in 0..KS {
            d[j][k] = out.d[j][k];
        }
    }
    let mut ns = [0.0; MAX_FACE_NODES];
    let mut phi = [0.0; MAX_FACE_NODES];
    let mut nm = [0.0; MAX_FACE_NODES];
    let mut i = 0usize;
    while i < points.len() {
        // One run of points on the same master face.
        let master = points[i].master;
        let mel = masters.element(interface, master as usize);
        let mut m = [[0.0; KM]; KS];
        while i < points.len() && points[i].master == master {
            let p = &points[i];
            slave.element.shape_values_into(&p.xi_slave, &mut ns[..KS]);
            if basis.identity {
                // A copy of KS values known at compile time (not a call to memcpy).
                phi[..KS].copy_from_slice(&ns[..KS]);
            } else {
                basis.eval_into(&ns, &mut phi);
            }
            mel.shape_values_into(&p.xi_master, &mut nm[..KM]);
            for j in 0..KS {
                let wp = p.weight * phi[j];
                for k in 0..KS {
                    d[j][k] += wp * ns[k];
                }
                for l in 0..KM {
                    m[j][l] += wp * nm[l];
                }
            }
            i += 1;
        }
        let off = out.block_offset(master, KM);
        let block = &mut out.vals[off..off + KS * KM];
        for j in 0..KS {
            for l in 0..KM {
                block[j * KM + l] += m[j][l];
            }
        }
    }
    for j in 0..KS {
        for k in 0..KS {
            out.d[j][k] = d[j][k];
        }
    }
}

fn general(
    interface: &Interface,
    masters: &MasterFaces,
    slave: &FaceGeometry,
    basis: &LmBasis,
    points: &[PairedPoint],
    out: &mut LocalBlocks,
) {
    let ks = slave.node_count();
    let mut ns = [0.0; MAX_FACE_NODES];
    let mut phi = [0.0; MAX_FACE_NODES];
    let mut nm = [0.0; MAX_FACE_NODES];
    // Points of one master face usually come together: remember the last one's block.
    let mut last: Option<(u32, usize, ElementRef)> = None;
    for p in points {
        slave.element.shape_values_into(&p.xi_slave, &mut ns[..ks]);
        basis.eval_into(&ns, &mut phi);
        let (off, master_el) = match last {
            Some((m, off, el)) if m == p.master => (off, el),
            _ => {
                let el = masters.element(interface, p.master as usize);
                let off = out.block_offset(p.master, el.node_count());
                last = Some((p.master, off, el));
                (off, el)
            }
        };
        let km = master_el.node_count();
        master_el.shape_values_into(&p.xi_master, &mut nm[..km]);
        for j in 0..ks {
            let wp = p.weight * phi[j];
            for k in 0..ks {
                out.d[j][k] += wp * ns[k];
            }
            for l in 0..km {
                out.vals[off + j * km + l] += wp * nm[l];
            }
        }
    }
}
