//! Helpers shared by the property modules: coupling a pair, reading D and M by node tags, and
//! the slave nodal areas computed independently of the mortar integration.

use std::collections::HashMap;

use mortar::core::linalg::SparseMatrix;
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
