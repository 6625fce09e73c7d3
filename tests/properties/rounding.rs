//! Rounding relative to the faces, not to the coordinates: a 2D interface far from the
//! origin (x about 1e4, faces about 1e-2 long) gets the mortar matrix M to a few units of
//! rounding of its entries.
//!
//! Source of the expected values: closed form. The interface is flat, so the segments are the
//! intervals between the merged node coordinates, and on each segment `[a, b]` the product of
//! the two linear hats integrates to `(b - a) / 6 (2 f_a g_a + f_a g_b + f_b g_a + 2 f_b g_b)`,
//! evaluated here from differences of nearby coordinates (exact in floating point), so
//! rounded only at the level of the entries themselves. Before the 2D segmentation worked in
//! offsets from the slave face, M carried errors of order `eps |x| / h`: 9.9e-11 of a row here.

use std::collections::HashMap;

use mortar::elements::LINE2;
use mortar::{assemble_coupling, CouplingOptions, Interface, SurfaceMesh};

use super::common::by_tags;

/// Nodes `origin + i h` for `i = 0..=n` along x at height `y`, lines in order (or reversed,
/// for the master's opposite normal), node tags from `first`.
fn line(origin: f64, h: f64, n: usize, y: f64, reversed: bool, first: u64) -> SurfaceMesh {
    let mut mesh = SurfaceMesh::new();
    for i in 0..=n {
        mesh.add_node(first + i as u64, [origin + h * i as f64, y, 0.0])
            .unwrap();
    }
    for i in 0..n as u64 {
        let (a, b) = (first + i, first + i + 1);
        let nodes = if reversed { [b, a] } else { [a, b] };
        mesh.add_face(&LINE2, &nodes).unwrap();
    }
    mesh
}

/// The value at `x` of the hat of node `k` of the sorted coordinates `grid`.
fn hat(grid: &[f64], k: usize, x: f64) -> f64 {
    let mut v: f64 = 0.0;
    if k > 0 && grid[k - 1] <= x && x <= grid[k] {
        v = v.max((x - grid[k - 1]) / (grid[k] - grid[k - 1]));
    }
    if k + 1 < grid.len() && grid[k] <= x && x <= grid[k + 1] {
        v = v.max((grid[k + 1] - x) / (grid[k + 1] - grid[k]));
    }
    v
}

#[test]
fn line_interface_far_from_the_origin_has_m_to_rounding() {
    let origin = 1.0e4;
    let (ns, hs) = (7, 1.0e-2);
    // The master overhangs the slave at both ends and its nodes fall between the slave's.
    let (nm, hm) = (6, 1.3e-2);
    let m_origin = origin - 0.4e-2;
    let slave = line(origin, hs, ns, 0.0, false, 1);
    let master = line(m_origin, hm, nm, 0.0, true, 101);
    let xs: Vec<f64> = (0..=ns).map(|i| origin + hs * i as f64).collect();
    let xm: Vec<f64> = (0..=nm).map(|j| m_origin + hm * j as f64).collect();

    let interface = Interface::new(slave, master).unwrap();
    let c = assemble_coupling(&interface, &CouplingOptions::default()).unwrap();
    let got = by_tags(&c.m, &c.slave_nodes, &c.master_nodes);

    // The segments: the merged coordinates within the slave.
    let mut cuts: Vec<f64> = xs
        .iter()
        .chain(xm.iter().filter(|&&x| x > xs[0] && x < xs[ns]))
        .copied()
        .collect();
    cuts.sort_by(f64::total_cmp);
    let mut exact: HashMap<(u64, u64), f64> = HashMap::new();
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let i = xs.partition_point(|&x| x <= a) - 1;
        let j = xm.partition_point(|&x| x <= a) - 1;
        for ii in [i, i + 1] {
            for jj in [j, j + 1] {
                let (fa, fb) = (hat(&xs, ii, a), hat(&xs, ii, b));
                let (ga, gb) = (hat(&xm, jj, a), hat(&xm, jj, b));
                let v = (b - a) / 6.0 * (2.0 * fa * ga + fa * gb + fb * ga + 2.0 * fb * gb);
                if v != 0.0 {
                    *exact.entry((1 + ii as u64, 101 + jj as u64)).or_default() += v;
                }
            }
        }
    }
    let mut worst: f64 = 0.0;
    for i in 0..=ns as u64 {
        let row = |m: &HashMap<(u64, u64), f64>| -> Vec<((u64, u64), f64)> {
            m.iter()
                .filter(|((r, _), _)| *r == 1 + i)
                .map(|(k, v)| (*k, *v))
                .collect()
        };
        let (g, e) = (row(&got), row(&exact));
        let scale = g.iter().chain(&e).fold(0.0f64, |s, (_, v)| s.max(v.abs()));
        for (k, v) in g.iter().chain(&e) {
            let d = (got.get(k).unwrap_or(&0.0) - exact.get(k).unwrap_or(&0.0)).abs();
            assert!(v.is_finite());
            worst = worst.max(d / scale);
        }
    }
    assert!(
        worst <= 1e-14,
        "M off the closed form by {worst:.2e} of its row's largest entry"
    );
}
