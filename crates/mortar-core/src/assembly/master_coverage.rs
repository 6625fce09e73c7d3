//! Master area covered by more than one slave face: two slave layers over one master surface
//! (both sides of a thin plate given as the slave, each turned to face the master), which
//! the slave-side coverage cannot see (each slave face is covered once).
//!
//! The multipliers sum to one (`sum_j Phi_j = 1`: standard, dual and linear alike), so the
//! column sum of M at master node `l` is `int N_l` over the master area the slave covers,
//! counted once per slave face over it. Compared with the node's own integral `int N_l` over
//! the master surface, it is at most 1 where the slave covers the master once (less at the
//! edge of the slave), and about 2 where two slave layers do.

use nalgebra::{Vector2, Vector3};

use super::CouplingWarning;
use crate::element::{ElementRef, ReferenceDomain, MAX_FACE_NODES};
use crate::linalg::SparseMatrix;
use crate::quadrature::{Quadrature, QuadratureRule};
use crate::{CouplingOptions, Interface};

/// A master node counts as covered by more than one slave layer where M's column sum exceeds
/// its integral by this factor. Well above 1: across a gap the slave measures a curved
/// surface at another radius than the master (a pellet's 80 um gap: a factor 1.02), and
/// element-based integration sums M with its quadrature error; two layers give about 2.
pub const MASTER_OVERLAP_RATIO: f64 = 1.25;

/// A node's integral counts as positive above this fraction of the measure of the faces
/// around it: the corners of Tri6 faces integrate to zero, which rounding leaves at either
/// sign (1e-17 of the area), and a column sum of the same size must not read as overlap.
const SIGNIFICANT_SHARE: f64 = 1e-9;

/// The warning of master area covered by more than one slave layer, if any: the master
/// nodes whose column sum of `m` exceeds [`MASTER_OVERLAP_RATIO`] times their integral `int
/// N_l` (nodes whose integral is not positive, the corners of Tri6 and Quad8 faces, are
/// judged by the others of their faces; "positive" is relative to the faces' measure, see
/// [`SIGNIFICANT_SHARE`]).
pub(super) fn overlapping_slave_faces(
    interface: &Interface,
    options: &CouplingOptions,
    m: &SparseMatrix,
) -> Option<CouplingWarning> {
    let covered = column_sums(m);
    let (own, reach) = master_nodal_integrals(interface, options);
    let mut extra = 0.0;
    let mut nodes = 0usize;
    let mut examples = Vec::new();
    let tags = interface.master().node_tags();
    for (col, (&c, &a)) in covered.iter().zip(&own).enumerate() {
        if a > SIGNIFICANT_SHARE * reach[col] && c > MASTER_OVERLAP_RATIO * a {
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
        total: own
            .iter()
            .zip(&reach)
            .filter(|(a, r)| **a > SIGNIFICANT_SHARE * **r)
            .map(|(a, _)| a)
            .sum(),
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
/// for the axisymmetric one). A face of a type that is always affine in the Cartesian
/// measure adds its measure times each node's share of its reference domain (`int N_l /
/// |ref|`); other faces integrate by a rule of degree `2 p + 2`. A mesh of two-node lines or
/// linear triangles alone (the common case) has its measures computed inline: on the coupling
/// benchmark's plane3d (2.3e6 master triangles) this takes 19 ms on one thread, as long as
/// the column sums of M. One pass over the faces in their order, so that the sums do not
/// depend on the thread count. Second, by column, the summed measure of the faces around the
/// node (the scale its integral is judged against).
fn master_nodal_integrals(
    interface: &Interface,
    options: &CouplingOptions,
) -> (Vec<f64>, Vec<f64>) {
    let mut out = vec![0.0; interface.master_nodes().len()];
    let mut reach = vec![0.0; out.len()];
    let master = interface.master();
    let coords = master.coords();
    let cartesian = !options.geometry.is_axisymmetric();
    let col = |node: u32| {
        interface
            .master_col(node)
            .expect("a master face's nodes have columns") as usize
    };
    let simple = cartesian
        && master.element_types().iter().all(|el| {
            el.is_affine()
                && matches!(
                    (el.domain(), el.node_count()),
                    (ReferenceDomain::Line, 2) | (ReferenceDomain::Triangle, 3)
                )
        });
    if simple {
        for f in 0..master.face_count() {
            match *master.face_nodes(f) {
                [a, b] => {
                    let half = 0.5 * (coords[b as usize] - coords[a as usize]).norm();
                    for node in [a, b] {
                        out[col(node)] += half;
                        reach[col(node)] += 2.0 * half;
                    }
                }
                [a, b, c] => {
                    let (xa, xb, xc) = (coords[a as usize], coords[b as usize], coords[c as usize]);
                    let third = (xb - xa).cross(&(xc - xa)).norm() / 6.0;
                    for node in [a, b, c] {
                        out[col(node)] += third;
                        reach[col(node)] += 3.0 * third;
                    }
                }
                _ => unreachable!("two-node lines and three-node triangles"),
            }
        }
        return (out, reach);
    }
    let shares: Vec<Option<[f64; MAX_FACE_NODES]>> = master
        .element_types()
        .iter()
        .map(|el| {
            if cartesian && el.is_affine() {
                reference_shares(*el)
            } else {
                None
            }
        })
        .collect();
    let mut x = [Vector3::zeros(); MAX_FACE_NODES];
    let mut n = [0.0; MAX_FACE_NODES];
    for f in 0..master.face_count() {
        let view = master.face(f);
        let el = view.element;
        let k = view.nodes.len();
        for (xi, &node) in x.iter_mut().zip(view.nodes) {
            *xi = coords[node as usize];
        }
        let mut sums = [0.0; MAX_FACE_NODES];
        match shares[master.face_type_index(f) as usize] {
            Some(share) => {
                let domain = el.domain();
                let measure = el.jacobian_det(&x[..k], &domain.centre()) * domain.measure();
                for (s, w) in sums[..k].iter_mut().zip(&share[..k]) {
                    *s = measure * w;
                }
            }
            None => {
                let degree = 2 * el.shape_degree() + 2;
                let Ok(rule) = QuadratureRule::cached(el.domain(), degree) else {
                    continue;
                };
                for (xi, w) in rule.points().iter().zip(rule.weights()) {
                    let xi = Vector2::new(xi.x, xi.y);
                    el.shape_values_into(&xi, &mut n[..k]);
                    let at = el.map(&x[..k], &xi);
                    let dw = w * el.jacobian_det(&x[..k], &xi) * options.geometry.weight(&at);
                    for (s, ni) in sums[..k].iter_mut().zip(&n[..k]) {
                        *s += dw * ni;
                    }
                }
            }
        }
        let measure: f64 = sums[..k].iter().sum();
        for (&node, s) in view.nodes.iter().zip(&sums[..k]) {
            out[col(node)] += s;
            reach[col(node)] += measure.abs();
        }
    }
    (out, reach)
}

/// Each node's share `int N_l / |ref|` of the reference domain of `el`; `None` if no rule
/// integrates its shape functions.
fn reference_shares(el: ElementRef) -> Option<[f64; MAX_FACE_NODES]> {
    let domain = el.domain();
    let rule = QuadratureRule::cached(domain, 2 * el.shape_degree()).ok()?;
    let k = el.node_count();
    let mut n = [0.0; MAX_FACE_NODES];
    let mut out = [0.0; MAX_FACE_NODES];
    for (xi, w) in rule.points().iter().zip(rule.weights()) {
        el.shape_values_into(&Vector2::new(xi.x, xi.y), &mut n[..k]);
        for (o, ni) in out[..k].iter_mut().zip(&n[..k]) {
            *o += w * ni / domain.measure();
        }
    }
    Some(out)
}
