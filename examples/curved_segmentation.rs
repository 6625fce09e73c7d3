//! Speed for accuracy on a curved interface with second-order faces (issue 10 items 2 and
//! 5): the sphere of radius 0.3 between a ball (Hex8 or Hex27 cells, master) and the box
//! around it (Tet4 or Tet10, slave), meshed independently (2:3), the second-order nodes on the
//! sphere. The dials: element order (1 or 2), the curved-face subdivision level (1, 2, 4, 8,
//! or from the default tolerance) and the multiplier space (standard, dual).
//!
//! Reported per option (one thread, median of `--repeats` couplings): the time of the
//! coupling; the error of the interface area, sum(D) against 4 pi r^2; the error of M
//! against the same order's level-16 M (largest entry difference over the largest entry);
//! the error of the tied field: the slave values `D^-1 M u_m` of the master's nodal values of
//! `u = 1 + 2x - 3y + z`, against `u` at the slave nodes (largest, over the largest `|u|`).
//! Prints a table and, with `--json FILE`, writes it.
//!
//! ```sh
//! cargo run --release --example curved_segmentation -- [--n 8] [--repeats 3] [--json FILE]
//! ```

use std::time::Instant;

use mortar::core::integration::curved_3d::DEFAULT_CURVED_TOLERANCE;
use mortar::core::integration::SegmentBased;
use mortar::core::linalg::solve_sparse_lu;
use mortar::generate::{
    ball_mesh, box_with_hole_mesh, onto_sphere, second_order_mesh, CellShape, Inclusion,
    SecondOrder,
};
use mortar::{assemble_coupling, Coupling, CouplingOptions, Interface, VolumeMesh};
use nalgebra::Vector3;
use serde_json::json;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

fn main() -> Res<()> {
    run(&std::env::args().skip(1).collect::<Vec<_>>())
}

/// The largest entry of `a - b` over the largest entry of `b`.
fn difference(a: &sprs::CsMat<f64>, b: &sprs::CsMat<f64>) -> f64 {
    let scale = b.data().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = a - b;
    diff.data().iter().fold(0.0f64, |m, v| m.max(v.abs())) / scale
}

fn field(x: &Vector3<f64>) -> f64 {
    1.0 + 2.0 * x.x - 3.0 * x.y + x.z
}

/// The interface of the two bodies raised to `order`.
fn interface(n: usize, order: u32) -> Res<Interface> {
    let g = Inclusion::unit(3, 0.3);
    let (nb, mb) = (n / 2, 3 * n / 4);
    let raise = |m: VolumeMesh| -> Res<VolumeMesh> {
        Ok(match order {
            1 => m,
            _ => second_order_mesh(&m, SecondOrder::Complete, onto_sphere(g.centre, g.radius))?,
        })
    };
    let master = raise(ball_mesh(&g, nb, (nb / 2).max(1), 1)?)?;
    let slave = raise(box_with_hole_mesh(
        &g,
        mb,
        (mb / 2).max(1),
        CellShape::Simplex,
        1_000_001,
    )?)?;
    let c = Vector3::from(g.centre);
    let near = |f: &mortar::core::mesh::BoundaryFace| (f.centroid - c).norm() < 0.4;
    Ok(Interface::new(
        slave.boundary_surface(near)?,
        master.boundary_surface(near)?,
    )?)
}

/// The tied field's error: `D^-1 M u_m` against `u` at the slave nodes.
fn tied_error(c: &Coupling, i: &Interface) -> Res<f64> {
    let at = |mesh: &mortar::SurfaceMesh, tags: &[u64]| -> Vec<f64> {
        tags.iter()
            .map(|t| field(&mesh.coords()[mesh.node_index(*t).expect("tag") as usize]))
            .collect()
    };
    let (us, um) = (
        at(i.slave(), &c.slave_nodes),
        at(i.master(), &c.master_nodes),
    );
    let mu: Vec<f64> =
        c.m.outer_iterator()
            .map(|row| row.iter().map(|(j, v)| v * um[j]).sum())
            .collect();
    let u = solve_sparse_lu(&c.d, &mu)?;
    let scale = us.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    Ok(u.iter()
        .zip(&us)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale)
}

/// Runs the study with the arguments `[--n N] [--repeats R] [--json FILE]`.
pub fn run(args: &[String]) -> Res<()> {
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
    };
    let n: usize = value("--n").map_or(Ok(8), |v| v.parse())?;
    let repeats: usize = value("--repeats").map_or(Ok(3), |v| v.parse())?;
    let rows = study(n, repeats)?;
    if let Some(path) = value("--json") {
        let report = json!({
            "case": CASE,
            "n": n, "repeats": repeats, "threads": 1, "rows": rows,
        });
        std::fs::write(path, serde_json::to_string_pretty(&report)?)?;
    }
    Ok(())
}

/// What [`study`] measures, in a sentence.
pub const CASE: &str = "sphere r = 0.3: box of Tet4/Tet10 (slave) around a ball of Hex8/Hex27 (master), O-grids, n per unit length";

/// Every option of the dials at size `n`, each timed as the median of `repeats` couplings:
/// one JSON object per option (order, level, multipliers, faces, pairs, seconds, area error,
/// M against level 16, tied-field error), printed as a table as it goes.
pub fn study(n: usize, repeats: usize) -> Res<Vec<serde_json::Value>> {
    let exact_area = 4.0 * std::f64::consts::PI * 0.09;
    let couple = |i: &Interface, strategy: SegmentBased, dual: bool| -> Res<(Coupling, f64)> {
        let mut options = CouplingOptions::default().threads(1);
        if dual {
            options = options.dual();
        }
        options.integration = std::sync::Arc::new(strategy);
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..repeats.max(1) {
            let t = Instant::now();
            last = Some(assemble_coupling(i, &options)?);
            times.push(t.elapsed().as_secs_f64());
        }
        times.sort_by(f64::total_cmp);
        Ok((last.expect("one run"), times[times.len() / 2]))
    };
    println!(
        "{:>5} {:>11} {:>9} {:>7} {:>9} {:>10} {:>10} {:>10}",
        "order", "level", "mult.", "faces", "seconds", "area err", "M err", "tied err"
    );
    let mut rows = Vec::new();
    for order in [1u32, 2] {
        let i = interface(n, order)?;
        let levels: Vec<Option<u32>> = match order {
            1 => vec![None],
            _ => vec![Some(1), Some(2), Some(4), Some(8), None],
        };
        for dual in [false, true] {
            let (reference, _) = couple(&i, SegmentBased::default().with_subdivision(16)?, dual)?;
            for level in &levels {
                let strategy = match level {
                    Some(l) => SegmentBased::default().with_subdivision(*l)?,
                    None => SegmentBased::default(),
                };
                let (c, seconds) = couple(&i, strategy, dual)?;
                let name = level.map_or(format!("tol {DEFAULT_CURVED_TOLERANCE:e}"), |l| {
                    l.to_string()
                });
                let (area, m_err, tied) = (
                    (c.stats.area - exact_area).abs() / exact_area,
                    difference(&c.m, &reference.m),
                    tied_error(&c, &i)?,
                );
                let mult = if dual { "dual" } else { "standard" };
                println!(
                    "{order:>5} {name:>11} {mult:>9} {:>7} {seconds:>9.4} {area:>10.2e} {m_err:>10.2e} {tied:>10.2e}",
                    i.slave().face_count()
                );
                rows.push(json!({
                    "order": order, "level": name, "multipliers": mult,
                    "slave_faces": i.slave().face_count(), "master_faces": i.master().face_count(),
                    "pairs": c.stats.pairs, "seconds": seconds, "area_error": area,
                    "m_error_vs_level_16": m_err, "tied_error": tied,
                }));
            }
        }
    }
    Ok(rows)
}
