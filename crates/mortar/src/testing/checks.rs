//! The checks of a patch test, with the exact answers they are held against, public so that a
//! user's own element, multiplier space or integration strategy is checked the way the
//! library's are.

use std::collections::HashMap;

use mortar_core::element::ReferenceDomain;
use mortar_core::mesh::SurfaceMesh;
use mortar_core::quadrature::{Quadrature, QuadratureRule};
use mortar_core::{Coupling, Interface};
use nalgebra::{Vector2, Vector3};

/// How far a coupling is from the exact answers of a covered interface, each relative to the
/// scale it names ([`patch_test`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchReport {
    /// `max_j |(D 1 - M 1)_j|` over the slave area: constants are reproduced.
    pub constants: f64,
    /// `max_j |(D x_s - M x_m)_j|` for the coordinate fields `x`, `y`, `z`, over the slave
    /// area times the interface's size: linear fields are reproduced (the linear patch test).
    pub linear: f64,
    /// `max_j |(D 1)_j - int N_j|` over the largest nodal area, the nodal areas computed face
    /// by face by quadrature ([`nodal_areas`]), independently of the coupling.
    pub row_sums: f64,
    /// For a multiplier space that claims a diagonal D (dual): the largest off-diagonal entry
    /// of D over its largest diagonal entry (biorthogonality); 0 otherwise.
    pub biorthogonality: f64,
}

impl PatchReport {
    /// The largest of the four.
    pub fn worst(&self) -> f64 {
        self.constants
            .max(self.linear)
            .max(self.row_sums)
            .max(self.biorthogonality)
    }
}

/// `int N_j` over `mesh` for every node `j` used by a face, keyed by node tag: face by face
/// with a quadrature of degree 20 and the Jacobian from the shape gradients directly (not
/// through the coupling code), so it is an independent reference for the row sums of D on a
/// covered interface.
pub fn nodal_areas(mesh: &SurfaceMesh) -> HashMap<u64, f64> {
    let mut out = HashMap::new();
    let tags = mesh.node_tags();
    for f in 0..mesh.face_count() {
        let face = mesh.face(f);
        let el = face.element;
        let k = el.node_count();
        let x: Vec<Vector3<f64>> = face
            .nodes
            .iter()
            .map(|&n| mesh.coords()[n as usize])
            .collect();
        let Ok(rule) = QuadratureRule::for_domain(el.domain(), 20) else {
            continue;
        };
        let mut n = vec![0.0; k];
        let mut g = vec![[0.0; 2]; k];
        for (xi, w) in rule.points().iter().zip(rule.weights()) {
            el.shape_values_into(&Vector2::new(xi.x, xi.y), &mut n);
            el.shape_gradients_into(&Vector2::new(xi.x, xi.y), &mut g);
            let (mut t1, mut t2) = (Vector3::zeros(), Vector3::zeros());
            for i in 0..k {
                t1 += x[i] * g[i][0];
                t2 += x[i] * g[i][1];
            }
            let det = if el.domain() == ReferenceDomain::Line {
                t1.norm()
            } else {
                t1.cross(&t2).norm()
            };
            for i in 0..k {
                *out.entry(tags[face.nodes[i] as usize]).or_insert(0.0) += w * det * n[i];
            }
        }
    }
    out
}

/// The patch test of a coupling on a *covered* interface (every slave point has a master
/// point, as the pairs of [`covered_pair`](super::covered_pair) are): constants and linear
/// fields reproduced, row sums of D equal to the slave nodal areas, and D diagonal when the
/// multiplier space says so (`dual`). Exact answers, so every figure is round-off for flat
/// faces integrated exactly. The row sums hold for the standard and dual spaces
/// (`int Phi_j = int N_j`), not for linear multipliers on second-order faces, whose rows sum
/// to the corners' first-order areas: there, read [`PatchReport::constants`] and
/// [`PatchReport::linear`].
pub fn patch_test(interface: &Interface, coupling: &Coupling, dual: bool) -> PatchReport {
    let (d, m) = (&coupling.d, &coupling.m);
    let row = |a: &mortar_core::linalg::SparseMatrix, j: usize, x: &[f64]| -> f64 {
        a.outer_view(j)
            .map_or(0.0, |r| r.iter().map(|(c, v)| v * x[c]).sum())
    };
    let area = coupling.stats.area.abs().max(f64::MIN_POSITIVE);
    let xs = coupling.slave_positions(interface);
    let xm = coupling.master_positions(interface);
    let size = xs
        .iter()
        .chain(&xm)
        .fold(0.0f64, |s, p| s.max(p.amax()))
        .max(f64::MIN_POSITIVE);
    let (ones_s, ones_m) = (vec![1.0; d.cols()], vec![1.0; m.cols()]);
    let mut report = PatchReport {
        constants: 0.0,
        linear: 0.0,
        row_sums: 0.0,
        biorthogonality: 0.0,
    };
    let areas = nodal_areas(interface.slave());
    let largest = areas.values().fold(0.0f64, |a, v| a.max(v.abs()));
    for j in 0..d.rows() {
        let (ds, ms) = (row(d, j, &ones_s), row(m, j, &ones_m));
        report.constants = report.constants.max((ds - ms).abs() / area);
        for k in 0..3 {
            let fs: Vec<f64> = xs.iter().map(|p| p[k]).collect();
            let fm: Vec<f64> = xm.iter().map(|p| p[k]).collect();
            let r = (row(d, j, &fs) - row(m, j, &fm)).abs() / (area * size);
            report.linear = report.linear.max(r);
        }
        if let Some(a) = areas.get(&coupling.slave_nodes[j]) {
            report.row_sums = report.row_sums.max((ds - a).abs() / largest);
        }
    }
    if dual {
        let (mut off, mut diag) = (0.0f64, 0.0f64);
        for (j, r) in d.outer_iterator().enumerate() {
            for (k, v) in r.iter() {
                if k == j {
                    diag = diag.max(v.abs());
                } else {
                    off = off.max(v.abs());
                }
            }
        }
        report.biorthogonality = off / diag.max(f64::MIN_POSITIVE);
    }
    report
}
