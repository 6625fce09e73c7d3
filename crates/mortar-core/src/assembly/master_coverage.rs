//! Master area covered by more than one slave face: two slave layers over one master surface
//! (both sides of a thin plate given as the slave, each turned to face the master), which
//! the slave-side coverage cannot see (each slave face is covered once).
//!
//! The multipliers sum to one (`sum_j Phi_j = 1`: standard, dual and linear alike), so the
//! column sum of M at master node `l` is `int N_l` over the master area the slave covers,
//! counted once per slave face over it. Compared with the node's own integral `int N_l` over
//! the master surface, it is at most 1 where the slave covers the master once (less at the
//! edge of the slave), and about 2 where two slave layers do.

use nalgebra::Vector2;

use super::CouplingWarning;
use crate::linalg::SparseMatrix;
use crate::quadrature::{Quadrature, QuadratureRule};
use crate::{CouplingOptions, Interface};

/// A master node counts as covered by more than one slave layer where M's column sum exceeds
/// its integral by this factor. Well above 1: across a gap the slave measures a curved
/// surface at another radius than the master (a pellet's 80 um gap: a factor 1.02), and
/// element-based integration sums M with its quadrature error; two layers give about 2.
pub const MASTER_OVERLAP_RATIO: f64 = 1.25;

/// The warning of master area covered by more than one slave layer, if any: the master
/// nodes whose column sum of `m` exceeds [`MASTER_OVERLAP_RATIO`] times their integral `int
/// N_l` (nodes whose integral is not positive, the corners of Tri6 and Quad8 faces, are
/// judged by the others of their faces).
pub(super) fn overlapping_slave_faces(
    interface: &Interface,
    options: &CouplingOptions,
    m: &SparseMatrix,
) -> Option<CouplingWarning> {
    let covered = column_sums(m);
    let own = master_nodal_integrals(interface, options);
    let mut extra = 0.0;
    let mut nodes = 0usize;
    let mut examples = Vec::new();
    let tags = interface.master().node_tags();
    for (col, (&c, &a)) in covered.iter().zip(&own).enumerate() {
        if a > 0.0 && c > MASTER_OVERLAP_RATIO * a {
            extra += c - a;
            nodes += 1;
            if examples.len() < CouplingWarning::EXAMPLES {
                examples.push(tags[interface.master_nodes()[col] as usize]);
            }
        }
    }
    if nodes == 0 {
        return None;
    }
    examples.sort_unstable();
    Some(CouplingWarning::OverlappingSlaveFaces {
        area: extra,
        total: own.iter().filter(|a| **a > 0.0).sum(),
        master_nodes: nodes,
        examples,
    })
}

/// The column sums of `m`, in column order.
fn column_sums(m: &SparseMatrix) -> Vec<f64> {
    let mut out = vec![0.0; m.cols()];
    for (&c, &v) in m.indices().iter().zip(m.data()) {
        out[c] += v;
    }
    out
}

/// `int N_l` over the master surface, by master column (with the coupling's measure: `2 pi r`
/// for the axisymmetric one); exact for affine faces, by a rule of degree `2 p + 2` otherwise.
fn master_nodal_integrals(interface: &Interface, options: &CouplingOptions) -> Vec<f64> {
    let mut out = vec![0.0; interface.master_nodes().len()];
    let master = interface.master();
    let mut n = [0.0; crate::element::MAX_FACE_NODES];
    for f in 0..master.face_count() {
        let face = interface.master_face(f);
        let el = face.element;
        let k = face.node_count();
        let x = face.node_coords();
        let degree = 2 * el.shape_degree() + 2;
        let Ok(rule) = QuadratureRule::cached(el.domain(), degree) else {
            continue;
        };
        let cols = master.face(f).nodes.iter().map(|&node| {
            interface
                .master_col(node)
                .expect("a master face's nodes have columns") as usize
        });
        let mut sums = [0.0; crate::element::MAX_FACE_NODES];
        for (xi, w) in rule.points().iter().zip(rule.weights()) {
            let xi = Vector2::new(xi.x, xi.y);
            el.shape_values_into(&xi, &mut n[..k]);
            let dw = w * el.jacobian_det(x, &xi) * options.geometry.weight(&face.map(&xi));
            for (s, ni) in sums[..k].iter_mut().zip(&n[..k]) {
                *s += dw * ni;
            }
        }
        for (col, s) in cols.zip(&sums[..k]) {
            out[col] += s;
        }
    }
    out
}
