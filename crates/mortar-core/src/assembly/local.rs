use crate::element::{ElementRef, MAX_FACE_NODES};
use crate::integration::PairedPoint;
use crate::interface::{FaceGeometry, Interface};
use crate::multiplier::LmBasis;

type Block = [[f64; MAX_FACE_NODES]; MAX_FACE_NODES];

/// The local D block of one slave face and one M block per master face it meets.
#[derive(Debug, Clone, Default)]
pub struct LocalBlocks {
    /// `d[j][k] = int Phi_j N_k^s` over the face's overlap.
    pub d: Block,
    /// `(master face, m)` with `m[j][l] = int Phi_j N_l^m`.
    pub m: Vec<(u32, Block)>,
}

impl LocalBlocks {
    fn clear(&mut self) {
        self.d = [[0.0; MAX_FACE_NODES]; MAX_FACE_NODES];
        self.m.clear();
    }

    fn block_index(&mut self, master: u32) -> usize {
        match self.m.iter().position(|(f, _)| *f == master) {
            Some(i) => i,
            None => {
                self.m
                    .push((master, [[0.0; MAX_FACE_NODES]; MAX_FACE_NODES]));
                self.m.len() - 1
            }
        }
    }
}

/// Integrates one slave face's paired points into local blocks (cleared first):
/// `D += w Phi_j(xi_s) N_k(xi_s)`, `M += w Phi_j(xi_s) N_l^m(xi_m)`.
pub fn integrate_face_into(
    interface: &Interface,
    slave: &FaceGeometry,
    basis: &LmBasis,
    points: &[PairedPoint],
    out: &mut LocalBlocks,
) {
    out.clear();
    // Fixed-size kernels for the common node counts let the compiler unroll the products.
    match (slave.node_count(), common_master_nodes(interface, points)) {
        (3, Some(3)) => kernel::<3, 3>(interface, slave, basis, points, out),
        (3, Some(4)) => kernel::<3, 4>(interface, slave, basis, points, out),
        (4, Some(3)) => kernel::<4, 3>(interface, slave, basis, points, out),
        (4, Some(4)) => kernel::<4, 4>(interface, slave, basis, points, out),
        (2, Some(2)) => kernel::<2, 2>(interface, slave, basis, points, out),
        _ => general(interface, slave, basis, points, out),
    }
}

/// The node count shared by every master face of `points`, if they all have the same.
fn common_master_nodes(interface: &Interface, points: &[PairedPoint]) -> Option<usize> {
    let mesh = interface.master();
    let mut count = None;
    let mut last = u32::MAX;
    for p in points {
        if p.master != last {
            last = p.master;
            let k = mesh.face(p.master as usize).element.node_count();
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
    slave: &FaceGeometry,
    basis: &LmBasis,
    points: &[PairedPoint],
    out: &mut LocalBlocks,
) {
    let master_mesh = interface.master();
    let mut d = [[0.0; KS]; KS];
    let mut ns = [0.0; MAX_FACE_NODES];
    let mut phi = [0.0; MAX_FACE_NODES];
    let mut nm = [0.0; MAX_FACE_NODES];
    let mut i = 0usize;
    while i < points.len() {
        // One run of points on the same master face.
        let master = points[i].master;
        let mel = master_mesh.face(master as usize).element;
        let mut m = [[0.0; KM]; KS];
        while i < points.len() && points[i].master == master {
            let p = &points[i];
            slave.element.shape_values_into(&p.xi_slave, &mut ns[..KS]);
            basis.eval_into(&ns, &mut phi);
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
        let bi = out.block_index(master);
        let block = &mut out.m[bi].1;
        for j in 0..KS {
            for l in 0..KM {
                block[j][l] += m[j][l];
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
    slave: &FaceGeometry,
    basis: &LmBasis,
    points: &[PairedPoint],
    out: &mut LocalBlocks,
) {
    let ks = slave.node_count();
    let master_mesh = interface.master();
    let mut ns = [0.0; MAX_FACE_NODES];
    let mut phi = [0.0; MAX_FACE_NODES];
    let mut nm = [0.0; MAX_FACE_NODES];
    // Points of one master face usually come together: remember the last one's block.
    let mut last: Option<(u32, usize, ElementRef)> = None;
    for p in points {
        slave.element.shape_values_into(&p.xi_slave, &mut ns[..ks]);
        basis.eval_into(&ns, &mut phi);
        let (bi, master_el) = match last {
            Some((m, bi, el)) if m == p.master => (bi, el),
            _ => {
                let el = master_mesh.face(p.master as usize).element;
                let bi = out.block_index(p.master);
                last = Some((p.master, bi, el));
                (bi, el)
            }
        };
        let km = master_el.node_count();
        master_el.shape_values_into(&p.xi_master, &mut nm[..km]);
        let mb = &mut out.m[bi].1;
        for j in 0..ks {
            let wp = p.weight * phi[j];
            for k in 0..ks {
                out.d[j][k] += wp * ns[k];
            }
            for l in 0..km {
                mb[j][l] += wp * nm[l];
            }
        }
    }
}
