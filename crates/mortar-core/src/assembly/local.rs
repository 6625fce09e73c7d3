use crate::element::MAX_FACE_NODES;
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

    fn block_of(&mut self, master: u32) -> &mut Block {
        let pos = self.m.iter().position(|(f, _)| *f == master);
        let i = match pos {
            Some(i) => i,
            None => {
                self.m
                    .push((master, [[0.0; MAX_FACE_NODES]; MAX_FACE_NODES]));
                self.m.len() - 1
            }
        };
        &mut self.m[i].1
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
    let ks = slave.node_count();
    let master_mesh = interface.master();
    let mut ns = [0.0; MAX_FACE_NODES];
    let mut phi = [0.0; MAX_FACE_NODES];
    let mut nm = [0.0; MAX_FACE_NODES];
    for p in points {
        slave.element.shape_values_into(&p.xi_slave, &mut ns[..ks]);
        basis.eval_into(&ns, &mut phi);
        let master_el = master_mesh.face(p.master as usize).element;
        let km = master_el.node_count();
        master_el.shape_values_into(&p.xi_master, &mut nm[..km]);
        for j in 0..ks {
            let wp = p.weight * phi[j];
            for k in 0..ks {
                out.d[j][k] += wp * ns[k];
            }
        }
        let mb = out.block_of(p.master);
        for j in 0..ks {
            let wp = p.weight * phi[j];
            for l in 0..km {
                mb[j][l] += wp * nm[l];
            }
        }
    }
}
