//! Helpers shared by the property modules: coupling a pair, reading D and M by node tags, and
//! the slave nodal areas computed independently of the mortar integration.

use std::collections::HashMap;
use std::sync::Arc;

use mortar::core::integration::{
    IntegrationFastPaths, IntegrationStrategy, PairedRule, SegmentBased, SegmentContext,
};
use mortar::core::interface::FaceGeometry;
use mortar::core::linalg::SparseMatrix;
use mortar::core::projector::{NodalNormalField, Projector, ProjectorFastPaths};
use mortar::testing::MeshPair;
use mortar::{assemble_coupling, Coupling, CouplingOptions, Interface, SurfaceMesh};
use nalgebra::Vector3;
use proptest::prelude::*;
use proptest::test_runner::Config;

/// The proptest configuration of a block: `cases` cases, or as many as the environment
/// variable `PROPTEST_CASES` says (to run the suite harder: `PROPTEST_CASES=1000 cargo test`).
pub fn config(cases: u32) -> Config {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(cases);
    Config {
        cases,
        ..Config::default()
    }
}

/// Turns a library error into a test-case failure that names it.
pub fn ok<T, E: std::fmt::Display>(r: Result<T, E>) -> Result<T, TestCaseError> {
    r.map_err(|e| TestCaseError::fail(format!("unexpected error: {e}")))
}

/// Builds the interface of `pair` and couples it.
pub fn couple(
    pair: &MeshPair,
    options: &CouplingOptions,
) -> Result<(Interface, Coupling), TestCaseError> {
    let interface = ok(pair.interface())?;
    let coupling = ok(assemble_coupling(&interface, options))?;
    Ok((interface, coupling))
}

/// The options of segment-based integration with standard or dual multipliers.
pub fn segment_options(dual: bool) -> CouplingOptions {
    let o = CouplingOptions::default();
    if dual {
        o.dual()
    } else {
        o
    }
}

/// `a x` for a CSR matrix.
pub fn mat_vec(a: &SparseMatrix, x: &[f64]) -> Vec<f64> {
    assert_eq!(a.cols(), x.len());
    (0..a.rows())
        .map(|r| {
            a.outer_view(r)
                .map_or(0.0, |row| row.iter().map(|(c, v)| v * x[c]).sum())
        })
        .collect()
}

/// Row sums `a 1`.
pub fn row_sums(a: &SparseMatrix) -> Vec<f64> {
    mat_vec(a, &vec![1.0; a.cols()])
}

/// The largest absolute row sum of `|a|` (the infinity norm).
pub fn norm_inf(a: &SparseMatrix) -> f64 {
    (0..a.rows())
        .map(|r| {
            a.outer_view(r)
                .map_or(0.0, |row| row.iter().map(|(_, v)| v.abs()).sum())
        })
        .fold(0.0, f64::max)
}

/// The largest absolute entry.
pub fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// The entries of a matrix keyed by (row tag, column tag).
pub fn by_tags(a: &SparseMatrix, rows: &[u64], cols: &[u64]) -> HashMap<(u64, u64), f64> {
    let mut out = HashMap::new();
    for (v, (r, c)) in a.iter() {
        *out.entry((rows[r], cols[c])).or_insert(0.0) += *v;
    }
    out
}

/// Checks `b[(map_r(j), map_c(k))] == factor * a[(j, k)]` for every entry of either matrix
/// (a missing entry counts as zero), to `tol` relative to the largest entry of `a` times
/// `factor`. Returns the largest relative deviation.
pub fn compare_mapped(
    a: &HashMap<(u64, u64), f64>,
    b: &HashMap<(u64, u64), f64>,
    map_r: impl Fn(u64) -> u64,
    map_c: impl Fn(u64) -> u64,
    factor: f64,
) -> f64 {
    let scale = a.values().fold(0.0f64, |m, v| m.max(v.abs())) * factor.abs();
    let mut mapped: HashMap<(u64, u64), f64> = HashMap::new();
    for (&(r, c), &v) in a {
        *mapped.entry((map_r(r), map_c(c))).or_insert(0.0) += factor * v;
    }
    let mut worst = 0.0f64;
    for (key, &v) in &mapped {
        let w = b.get(key).copied().unwrap_or(0.0);
        worst = worst.max((v - w).abs() / scale);
    }
    for (key, &w) in b {
        if !mapped.contains_key(key) {
            worst = worst.max(w.abs() / scale);
        }
    }
    worst
}

/// The largest deviations of `b`'s D and M from `a`'s, entry by entry by node tags, relative
/// to the largest entry of `a`'s ([`compare_mapped`]), named `"D"` and `"M"`.
pub fn dm_deviations(a: &Coupling, b: &Coupling) -> [(&'static str, f64); 2] {
    let of = |x: &SparseMatrix, y: &SparseMatrix, ca: &[u64], cb: &[u64]| {
        compare_mapped(
            &by_tags(x, &a.slave_nodes, ca),
            &by_tags(y, &b.slave_nodes, cb),
            |t| t,
            |t| t,
            1.0,
        )
    };
    [
        ("D", of(&a.d, &b.d, &a.slave_nodes, &b.slave_nodes)),
        ("M", of(&a.m, &b.m, &a.master_nodes, &b.master_nodes)),
    ]
}

/// `int N_j` over the slave surface for every node `j` used by a face, keyed by node tag
/// (the public checks' own, independent of the coupling code).
pub use mortar::testing::nodal_areas;

/// The measure of a surface: the sum of its nodal areas.
pub fn surface_measure(mesh: &SurfaceMesh) -> f64 {
    nodal_areas(mesh).values().sum()
}

/// Node values of `f` at the slave (row order) and master (column order) nodes.
pub fn nodal_values(
    coupling: &Coupling,
    interface: &Interface,
    f: impl Fn(&Vector3<f64>) -> f64,
) -> (Vec<f64>, Vec<f64>) {
    let fs = coupling.slave_positions(interface).iter().map(&f).collect();
    let fm = coupling
        .master_positions(interface)
        .iter()
        .map(&f)
        .collect();
    (fs, fm)
}

/// [`SegmentBased`] behind a strategy of one's own, which the coupling does not take for
/// [`SegmentBased`] (it recognises that by its type): the general path (the strategy's points,
/// integrated by the coupling), as a user's strategy reaches it, with the same
/// [`IntegrationFastPaths`] (split over candidates). The reference of the fused 2D kernel and
/// of the 3D closed form.
#[derive(Debug)]
pub struct Plain(pub SegmentBased);

impl IntegrationStrategy for Plain {
    fn name(&self) -> String {
        self.0.name()
    }

    fn paired_rule_into(
        &self,
        ctx: &SegmentContext<'_>,
        slave: &FaceGeometry,
        candidates: &[u32],
        out: &mut PairedRule,
    ) -> mortar::core::Result<()> {
        self.0.paired_rule_into(ctx, slave, candidates, out)
    }

    fn fast_paths(&self) -> Option<&dyn IntegrationFastPaths> {
        self.0.fast_paths()
    }
}

/// `options` with the general path of the default [`SegmentBased`] instead of the fused
/// kernel and the closed form.
pub fn plain(options: &CouplingOptions) -> CouplingOptions {
    plain_with(options, SegmentBased::default())
}

/// `options` with the general path of `strategy`.
pub fn plain_with(options: &CouplingOptions, strategy: SegmentBased) -> CouplingOptions {
    let mut o = options.clone();
    o.integration = Arc::new(Plain(strategy));
    o
}

/// Vertical lines at r = 0.7, of 13 and 19 faces graded differently, the slave facing the
/// master: an axisymmetric (r-z) interface for the 2D line paths.
pub fn vertical_lines() -> Interface {
    let vertical = |n: usize, p: f64| -> Vec<[f64; 2]> {
        (0..=n)
            .map(|i| [0.7, (i as f64 / n as f64).powf(p)])
            .collect()
    };
    let slave = mortar::testing::polyline(&vertical(13, 1.2), 1, true);
    let master = mortar::testing::polyline(&vertical(19, 0.9), 1000, false);
    Interface::new(slave, master).unwrap()
}

/// The nodal normal field without its claim of a uniform direction
/// ([`ProjectorFastPaths::uniform_direction`]), keeping that of an affine one
/// ([`ProjectorFastPaths::direction_is_affine`]): a straight 2D interface then takes the fused
/// kernel with its closed-form projection instead of the sorted merge.
#[derive(Debug)]
pub struct NotUniform;

impl Projector for NotUniform {
    fn name(&self) -> &'static str {
        NodalNormalField.name()
    }

    fn direction(
        &self,
        slave: &FaceGeometry,
        xi: &nalgebra::Vector2<f64>,
    ) -> (Vector3<f64>, [Vector3<f64>; 2]) {
        NodalNormalField.direction(slave, xi)
    }

    fn fast_paths(&self) -> Option<&dyn ProjectorFastPaths> {
        Some(self)
    }
}

impl ProjectorFastPaths for NotUniform {
    fn direction_is_affine(&self, slave: &FaceGeometry) -> bool {
        NodalNormalField.direction_is_affine(slave)
    }
}

/// `options` with the [`NotUniform`] projector: the fused kernel on straight lines.
pub fn not_uniform(options: &CouplingOptions) -> CouplingOptions {
    let mut o = options.clone();
    o.projector = Arc::new(NotUniform);
    o
}

/// Couples `interface` with `options` (of the default [`SegmentBased`]) and by the general
/// path; checks that D and M agree to `1e-13` of their largest entry and that the counts and
/// warnings are the same; returns the run of `options`.
pub fn both_ways(interface: &Interface, options: &CouplingOptions, what: &str) -> Coupling {
    both_ways_with(interface, options, &plain(options), what)
}

/// [`both_ways`] against the given general path.
pub fn both_ways_with(
    interface: &Interface,
    options: &CouplingOptions,
    general: &CouplingOptions,
    what: &str,
) -> Coupling {
    both_ways_within(interface, options, general, 1e-13, what)
}

/// [`both_ways_with`], D and M to `tol` of their largest entry.
pub fn both_ways_within(
    interface: &Interface,
    options: &CouplingOptions,
    general: &CouplingOptions,
    tol: f64,
    what: &str,
) -> Coupling {
    let fused = assemble_coupling(interface, options).unwrap();
    let general = assemble_coupling(interface, general).unwrap();
    assert_eq!(general.stats.fused_line_faces, 0, "{what}");
    assert_eq!(general.stats.straight_line_faces, 0, "{what}");
    assert_eq!(general.stats.closed_form_faces, 0, "{what}");
    for (name, dev) in dm_deviations(&general, &fused) {
        assert!(
            dev <= tol,
            "{what}: {name} deviates by {dev:e} (tolerance {tol:e})"
        );
    }
    assert_eq!(fused.stats.pairs, general.stats.pairs, "{what}");
    assert_eq!(fused.stats.back_facing, general.stats.back_facing, "{what}");
    assert_eq!(
        fused.stats.degrees_used, general.stats.degrees_used,
        "{what}"
    );
    assert_eq!(
        fused.stats.skipped_pairs, general.stats.skipped_pairs,
        "{what}"
    );
    assert_eq!(
        (
            fused.stats.faces_without_partner,
            fused.stats.faces_partly_covered
        ),
        (
            general.stats.faces_without_partner,
            general.stats.faces_partly_covered
        ),
        "{what}"
    );
    let (u, g) = (fused.stats.uncovered_area, general.stats.uncovered_area);
    assert!((u - g).abs() <= 1e-13 * (1.0 + g), "{what}: {u} vs {g}");
    assert_eq!(fused.warnings.len(), general.warnings.len(), "{what}");
    fused
}

/// The bits of D's and M's values and of M's column indices (for comparisons across thread
/// counts).
pub fn dm_bits(c: &Coupling) -> Vec<u64> {
    let mut v: Vec<u64> = c.d.data().iter().map(|x| x.to_bits()).collect();
    v.extend(c.m.data().iter().map(|x| x.to_bits()));
    v.extend(c.m.indices().iter().map(|&i| i as u64));
    v
}
