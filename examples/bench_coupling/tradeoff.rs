//! The speed-for-accuracy table: segment-based and element-based integration at degrees 1 to 8,
//! standard and dual multipliers, on a flat and on a curved interface.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use mortar::core::linalg::{solve_sparse_lu, SparseMatrix};
use mortar::core::quadrature::{Quadrature, QuadratureRule};
use mortar::generate::{cylinder_surface, square_quads, square_triangles, Diagonal};
use mortar::{assemble_coupling, Coupling, CouplingOptions, Interface};
use nalgebra::Vector3;

use crate::Res;

/// Errors below this count as equal (round-off) when deciding the Pareto front.
const ROUND_OFF: f64 = 1e-14;
/// A relative error of 100 % or more is no approximation: such options are left off the front.
const NO_ACCURACY: f64 = 1.0;
pub(crate) const DEGREES: std::ops::RangeInclusive<u32> = 1..=8;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Strategy {
    Segment,
    Element,
}

impl Strategy {
    pub(crate) fn name(self) -> &'static str {
        match self {
            Strategy::Segment => "segment-based",
            Strategy::Element => "element-based",
        }
    }
}

/// One option of the dial, measured.
#[derive(Debug, Clone)]
pub(crate) struct Row {
    pub(crate) strategy: Strategy,
    pub(crate) dual: bool,
    /// The quadrature degree; `None` for the default (automatic degree).
    pub(crate) degree: Option<u32>,
    /// The degrees the default picked (from `Coupling::degrees_used`).
    pub(crate) picked: Vec<u32>,
    /// Median total wall seconds (NaN if it failed).
    pub(crate) seconds: f64,
    /// One per metric of the case (NaN if it could not be computed).
    pub(crate) errors: Vec<f64>,
    /// Whether the option is on the Pareto front (time, error), one per metric.
    pub(crate) pareto: Vec<bool>,
    pub(crate) note: String,
}

impl Row {
    pub(crate) fn series(&self) -> String {
        format!(
            "{}, {}",
            self.strategy.name(),
            if self.dual { "dual" } else { "standard" }
        )
    }
}

pub(crate) struct Case {
    pub(crate) title: &'static str,
    pub(crate) metrics: &'static [&'static str],
    pub(crate) rows: Vec<Row>,
}

fn options(strategy: Strategy, dual: bool, degree: Option<u32>) -> Res<CouplingOptions> {
    let o = CouplingOptions::default().threads(1);
    let o = if dual { o.dual() } else { o };
    Ok(match strategy {
        Strategy::Segment => o.segment_based(degree)?,
        Strategy::Element => o.element_based(degree)?,
    })
}

/// The median `total` of `repeats` runs, and the last coupling.
fn timed(i: &Interface, o: &CouplingOptions, repeats: usize) -> Res<(f64, Coupling)> {
    let mut times = Vec::with_capacity(repeats);
    let mut last = None;
    for _ in 0..repeats {
        let c = assemble_coupling(i, o)?;
        times.push(c.stats.seconds.total);
        last = Some(c);
    }
    times.sort_by(f64::total_cmp);
    Ok((times[times.len() / 2], last.ok_or("no run")?))
}

fn spmv(a: &SparseMatrix, x: &[f64]) -> Vec<f64> {
    a.outer_iterator()
        .map(|row| row.iter().map(|(k, v)| v * x[k]).sum())
        .collect()
}

fn abs_spmv(a: &SparseMatrix, x: &[f64]) -> Vec<f64> {
    a.outer_iterator()
        .map(|row| row.iter().map(|(k, v)| v.abs() * x[k].abs()).sum())
        .collect()
}

fn max_abs(v: impl IntoIterator<Item = f64>) -> f64 {
    v.into_iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// The field `f` at the slave nodes (row order) and master nodes (column order).
fn field(c: &Coupling, i: &Interface, f: fn(&Vector3<f64>) -> f64) -> (Vec<f64>, Vec<f64>) {
    let fs = c.slave_positions(i).iter().map(f).collect();
    let fm = c.master_positions(i).iter().map(f).collect();
    (fs, fm)
}

/// `a_l`: the integral of each master shape function over the master surface (column order).
fn master_integrals(i: &Interface) -> Res<Vec<f64>> {
    let mesh = i.master();
    let mut a = vec![0.0; i.master_nodes().len()];
    let mut n = [0.0; 16];
    for f in 0..mesh.face_count() {
        let g = i.master_face(f);
        let el = g.element;
        let k = el.node_count();
        let rule = QuadratureRule::cached(el.domain(), 6)?;
        for (xi, w) in rule.points().iter().zip(rule.weights()) {
            el.shape_values_into(xi, &mut n[..k]);
            let jw = w * el.jacobian_det(&g.nodes[..k], xi);
            for (&node, nv) in mesh.face(f).nodes.iter().zip(&n[..k]) {
                a[i.master_col(node).ok_or("master node off the interface")? as usize] += jw * nv;
            }
        }
    }
    Ok(a)
}

/// `||A - B||_F / ||B||_F`.
fn frobenius_rel(a: &SparseMatrix, b: &SparseMatrix) -> f64 {
    let mut diff: HashMap<(usize, usize), f64> = HashMap::new();
    for (v, (r, c)) in a.iter() {
        *diff.entry((r, c)).or_default() += v;
    }
    for (v, (r, c)) in b.iter() {
        *diff.entry((r, c)).or_default() -= v;
    }
    let num: f64 = diff.values().map(|d| d * d).sum();
    let den: f64 = b.data().iter().map(|d| d * d).sum();
    (num / den).sqrt()
}

fn flat_field(x: &Vector3<f64>) -> f64 {
    1.0 + 2.0 * x.x - 3.0 * x.y
}

fn curved_field(x: &Vector3<f64>) -> f64 {
    1.0 + 2.0 * x.x - 3.0 * x.y + x.z
}

/// Runs every option on `i`; `errors(coupling, dual)` gives the metrics of one coupling.
fn sweep(
    i: &Interface,
    repeats: usize,
    metrics: usize,
    mut errors: impl FnMut(&Coupling, bool) -> Res<Vec<f64>>,
) -> Vec<Row> {
    let mut rows = Vec::new();
    for dual in [false, true] {
        for strategy in [Strategy::Segment, Strategy::Element] {
            // The default (segment-based, automatic degree) is a row of its own.
            let auto = (strategy == Strategy::Segment).then_some(None);
            for degree in auto.into_iter().chain(DEGREES.map(Some)) {
                let result = options(strategy, dual, degree)
                    .and_then(|o| timed(i, &o, repeats))
                    .and_then(|(t, c)| Ok((t, errors(&c, dual)?, c.degrees_used())));
                let (seconds, errs, picked, note) = match result {
                    Ok((t, e, p)) => (t, e, p, String::new()),
                    Err(e) => (
                        f64::NAN,
                        vec![f64::NAN; metrics],
                        Vec::new(),
                        format!("failed: {e}"),
                    ),
                };
                eprintln!(
                    "  {strategy:?} dual={dual} degree {}: {seconds:.2e} s {errs:?} {note}",
                    degree_name(degree)
                );
                rows.push(Row {
                    strategy,
                    dual,
                    degree,
                    picked: if degree.is_none() { picked } else { Vec::new() },
                    seconds,
                    errors: errs,
                    pareto: vec![false; metrics],
                    note,
                });
            }
        }
    }
    mark_pareto(&mut rows, metrics);
    // The default picks one degree per kind of face pair: when it picked a single degree, it
    // is the very computation of that degree's row, and shares its place on the front (their
    // times differ only by measurement noise).
    for a in 0..rows.len() {
        if rows[a].degree.is_some() || rows[a].picked.len() != 1 {
            continue;
        }
        let d = rows[a].picked[0];
        if let Some(b) = rows.iter().position(|r| {
            r.degree == Some(d) && r.strategy == rows[a].strategy && r.dual == rows[a].dual
        }) {
            let same = rows[b].pareto.clone();
            let row = &mut rows[a];
            for (p, s) in row.pareto.iter_mut().zip(same) {
                *p = *p || s;
            }
            row.note = format!("same computation as degree {d}");
        }
    }
    rows
}

/// Times within this fraction of each other count as equal: run-to-run noise on this shared
/// machine is of that order, and options that do the same work must not dominate each other
/// by chance.
const TIME_NOISE: f64 = 0.05;

fn mark_pareto(rows: &mut [Row], metrics: usize) {
    for k in 0..metrics {
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .map(|r| (r.seconds, r.errors[k].max(ROUND_OFF)))
            .collect();
        let eligible = |(t, e): (f64, f64)| t.is_finite() && e < NO_ACCURACY;
        for (i, r) in rows.iter_mut().enumerate() {
            let (t, e) = pts[i];
            // Dominated: another option at least as accurate and clearly faster, or more
            // accurate and not clearly slower.
            let faster = |t2: f64| t2 < t * (1.0 - TIME_NOISE);
            let not_slower = |t2: f64| t2 <= t * (1.0 + TIME_NOISE);
            r.pareto[k] = eligible((t, e))
                && !pts.iter().any(|&(t2, e2)| {
                    eligible((t2, e2)) && ((faster(t2) && e2 <= e) || (not_slower(t2) && e2 < e))
                });
        }
    }
}

fn flat_case(repeats: usize) -> Res<Case> {
    let i = Interface::new(
        square_triangles(24, Diagonal::Main, 0.0, false, 1)?,
        square_quads(37, 0.0, true, 1)?,
    )?;
    let a = master_integrals(&i)?;
    let a_max = max_abs(a.iter().copied());
    let refs = [false, true].map(|dual| {
        options(Strategy::Segment, dual, None).and_then(|o| Ok(assemble_coupling(&i, &o)?))
    });
    let [Ok(ref_std), Ok(ref_dual)] = refs else {
        return Err("the reference assembly failed".into());
    };
    let rows = sweep(&i, repeats, 3, |c, dual| {
        let (fs, fm) = field(c, &i, flat_field);
        let r: Vec<f64> = spmv(&c.d, &fs)
            .iter()
            .zip(spmv(&c.m, &fm))
            .map(|(d, m)| d - m)
            .collect();
        let patch = max_abs(r) / max_abs(abs_spmv(&c.d, &fs));
        let mut mt = vec![0.0; a.len()];
        for (v, (_, col)) in c.m.iter() {
            mt[col] += v;
        }
        let transfer = max_abs(mt.iter().zip(&a).map(|(x, y)| x - y)) / a_max;
        let m_ref = if dual { &ref_dual.m } else { &ref_std.m };
        Ok(vec![patch, transfer, frobenius_rel(&c.m, m_ref)])
    });
    Ok(Case {
        title: "Flat: unit square, slave 24 x 24 cells cut into 1152 Tri3, master 37 x 37 Quad4 \
                (1369 faces), z = 0",
        metrics: &["patch", "transfer", "m_error"],
        rows,
    })
}

fn tied_solution(c: &Coupling, i: &Interface) -> Res<Vec<f64>> {
    let (_, fm) = field(c, i, curved_field);
    let u = solve_sparse_lu(&c.d, &spmv(&c.m, &fm))?;
    Ok(u)
}

fn curved_case(repeats: usize) -> Res<Case> {
    let i = Interface::new(
        cylinder_surface(1.0, 96, 24, false, false, 1)?,
        cylinder_surface(1.0, 145, 37, true, true, 1)?,
    )?;
    let mut refs = Vec::new();
    for dual in [false, true] {
        let c = assemble_coupling(&i, &options(Strategy::Segment, dual, Some(8))?)?;
        let u = tied_solution(&c, &i)?;
        refs.push((c.stats.area, u));
    }
    let rows = sweep(&i, repeats, 2, |c, dual| {
        let (area_ref, u_ref) = &refs[usize::from(dual)];
        let area = (c.stats.area - area_ref).abs() / area_ref;
        let tied = match tied_solution(c, &i) {
            Ok(u) => {
                max_abs(u.iter().zip(u_ref).map(|(a, b)| a - b)) / max_abs(u_ref.iter().copied())
            }
            Err(_) => f64::NAN,
        };
        Ok(vec![area, tied])
    });
    Ok(Case {
        title: "Curved: lateral surface of the unit cylinder (radius 1, height 1), slave 96 x 24 \
                Quad4 (2304 faces), master 145 x 37 cells cut into 10730 Tri3",
        metrics: &["area", "tied"],
        rows,
    })
}

/// The section of the second-order dials (element order, subdivision level, multipliers),
/// from `examples/curved_segmentation.rs`.
fn second_order_section(md: &mut String, rows: &[serde_json::Value]) {
    let faces = |k: &str| rows.first().and_then(|r| r[k].as_u64()).unwrap_or(0);
    let _ = writeln!(
        md,
        "## Curved, second order: {}\n\n\
         The dials of curved interfaces (`examples/curved_segmentation.rs`, n = 8: {} slave \
         faces, {} master faces): element order, the subdivision level of curved faces \
         (`SegmentBased::with_subdivision`, or the default tolerance) and the multipliers. \
         Errors: `area` = |sum(D) - 4 pi r^2| / 4 pi r^2; `M` = the largest entry of M minus \
         the same order's level-16 M, over M's largest entry; `tied` = the slave values \
         D^-1 M u_m of u = 1 + 2x - 3y + z at the master nodes against u at the slave nodes \
         (largest, over the largest |u|).\n\n\
         | order | level | multipliers | ms | area | M | tied |\n| ---: | ---: | --- | ---: | ---: | ---: | ---: |",
        crate::curved_segmentation::CASE,
        faces("slave_faces"),
        faces("master_faces"),
    );
    for r in rows {
        let f = |k: &str| r[k].as_f64().unwrap_or(f64::NAN);
        let m = if r["order"].as_u64() == Some(1) {
            "—".to_string()
        } else {
            fmt_err(f("m_error_vs_level_16"))
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} | {:.1} | {} | {} | {} |",
            r["order"],
            r["level"].as_str().unwrap_or(""),
            r["multipliers"].as_str().unwrap_or(""),
            1e3 * f("seconds"),
            fmt_err(f("area_error")),
            m,
            fmt_err(f("tied_error"))
        );
    }
    md.push_str(
        "\nWithout cutting (level 1) second-order faces transfer no better than flat ones; each \
         doubling of the level costs about 4x and gains about 4x in M and in the tied field; \
         the area is right at every level (the slave is covered whatever the level).\n\n",
    );
}

fn fmt_err(e: f64) -> String {
    if e.is_nan() {
        "n/a".into()
    } else {
        format!("{e:.2e}")
    }
}

/// "3", or "auto (default)".
pub(crate) fn degree_name(degree: Option<u32>) -> String {
    degree.map_or_else(|| "auto (default)".to_string(), |d| d.to_string())
}

/// The degree column: "3", or "auto (default): 3" with the degrees the default picked.
fn degree_cell(r: &Row) -> String {
    match r.degree {
        Some(d) => d.to_string(),
        None if r.picked.is_empty() => "auto (default)".to_string(),
        None => format!(
            "auto (default): {}",
            r.picked
                .iter()
                .map(u32::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

fn table(md: &mut String, case: &Case) {
    let _ = write!(md, "| integration | multipliers | degree | time (ms) |");
    for m in case.metrics {
        let _ = write!(md, " {m} |");
    }
    md.push_str(" Pareto front |\n|---|---|---:|---:|");
    md.push_str(&"---:|".repeat(case.metrics.len()));
    md.push_str("---|\n");
    for r in &case.rows {
        let _ = write!(
            md,
            "| {} | {} | {} | {:.3} |",
            r.strategy.name(),
            if r.dual { "dual" } else { "standard" },
            degree_cell(r),
            r.seconds * 1e3
        );
        for e in &r.errors {
            let _ = write!(md, " {} |", fmt_err(*e));
        }
        let front: Vec<&str> = case
            .metrics
            .iter()
            .zip(&r.pareto)
            .filter(|(_, &p)| p)
            .map(|(m, _)| *m)
            .collect();
        let mark = if front.is_empty() {
            String::new()
        } else {
            format!("**yes** ({})", front.join(", "))
        };
        let _ = writeln!(
            md,
            " {mark}{} |",
            if r.note.is_empty() { "" } else { " " }.to_owned() + &r.note
        );
    }
}

fn summary(md: &mut String, case: &Case) {
    for (k, m) in case.metrics.iter().enumerate() {
        let mut front: Vec<&Row> = case.rows.iter().filter(|r| r.pareto[k]).collect();
        front.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
        let list: Vec<String> = front
            .iter()
            .map(|r| {
                format!(
                    "{} {} degree {} ({:.2} ms, {})",
                    r.strategy.name(),
                    if r.dual { "dual" } else { "standard" },
                    degree_name(r.degree),
                    r.seconds * 1e3,
                    fmt_err(r.errors[k])
                )
            })
            .collect();
        let _ = writeln!(md, "- `{m}`: {}", list.join("; "));
    }
}

pub(crate) fn run(out_dir: &Path, repeats: usize) -> Res<()> {
    let start = Instant::now();
    let load_before = crate::load_average();
    eprintln!("flat case");
    let flat = flat_case(repeats)?;
    eprintln!("curved case");
    let curved = curved_case(repeats)?;
    eprintln!("second-order case");
    let second_order = crate::curved_segmentation::study(8, repeats)?;
    std::fs::create_dir_all(out_dir)?;
    let png = out_dir.join("tradeoff.png");
    crate::plot::draw(&png, &[&flat, &curved])?;
    let elapsed = start.elapsed().as_secs_f64();

    let mut md = String::new();
    md.push_str("# Speed for accuracy of the mortar integration\n\n");
    let _ = writeln!(
        md,
        "Reproduce (writes this file and `tradeoff.png`):\n\n```sh\ncargo run --release \
         --example bench_coupling -- --tradeoff --tradeoff-repeats {repeats}\n```\n"
    );
    let _ = writeln!(
        md,
        "Measured in {elapsed:.0} s on a machine with {} cores shared with other builds (load \
         average over 1 min: {load_before:.2} at the start, {:.2} at the end).\n",
        std::thread::available_parallelism().map_or(0, |n| n.get()),
        crate::load_average()
    );
    md.push_str(
        "Each option assembles D and M with one thread. Time = median wall seconds of \
         `stats.seconds.total` (search, segmentation, integration and sparse assembly; mesh \
         generation excluded) over the repeats, in milliseconds. Errors below 1e-14 count as \
         equal (round-off), and times within 5 % count as equal (run-to-run noise), when the \
         Pareto front (error against time, over all 34 options of the case, the two defaults \
         included) is decided, and an option with an error of 1 (100 %) or more is left off \
         it; the last column names the errors for which the option is on \
         it. Automatic degree (the default, segment-based) is picked per face pair: slave shape \
         degree plus the larger shape degree, plus one for a slave face whose Jacobian varies \
         (3 for Tri3 against Quad4, 4 for the flat rectangular Quad4 of the cylinder against \
         Tri3); element-based integration \
         drops slave quadrature points that land on no master face.\n\n![error against \
         time](tradeoff.png)\n\n",
    );
    let _ = writeln!(md, "## {}\n", flat.title);
    table(&mut md, &flat);
    md.push_str(
        "\nErrors, with the linear field f = 1 + 2x - 3y at the slave nodes (f_s) and the \
         master nodes (f_m):\n\n\
         - `patch` = max_j |(D f_s - M f_m)_j| / max_j (|D| |f_s|)_j, the linear patch test;\n\
         - `transfer` = max_l |(M^T 1)_l - a_l| / max_l a_l where a_l is the integral of the \
         master shape function N_l^m over the master surface: what a uniform multiplier sends \
         to the master;\n\
         - `m_error` = ||M - M_ref||_F / ||M_ref||_F, M_ref from segment-based integration of \
         automatic degree (3) with the same multipliers.\n\n\
         `patch` is round-off for every option, element-based included: at each quadrature \
         point both sides interpolate the linear field exactly, so each point adds \
         Phi_j (f(x) - f(x)) = 0. `transfer` and `m_error` show where element-based \
         integration is inexact: the integrands have kinks at master edges inside a slave face.\n\n",
    );
    let _ = writeln!(md, "## {}\n", curved.title);
    table(&mut md, &curved);
    md.push_str(
        "\nErrors, against segment-based integration of degree 8 on the same meshes with the \
         same multipliers (its own row is the reference, hence 0):\n\n\
         - `area` = |area - area_ref| / area_ref, area = the sum of the entries of D;\n\
         - `tied` = max_j |u_j - u_ref,j| / max_j |u_ref,j| where u solves D u = M f_m (the \
         tied slave values of the linear field f = 1 + 2x - 3y + z), solved by \
         `mortar_fem::linalg::solve_sparse_lu`.\n\n\
         The slave quads are flat rectangles, so every option integrates the slave side (D, \
         and the area) to round-off; the error is in M. Element-based degree 1 has one point \
         per slave face, so D has rank at most 2304 (the face count) < 2400 (the slave nodes): \
         it is singular and its tied \"solution\" means nothing.\n\n",
    );
    second_order_section(&mut md, &second_order);
    md.push_str("## Pareto fronts, fastest first\n\n");
    for case in [&flat, &curved] {
        let _ = writeln!(md, "{}:\n", case.title.split(':').next().unwrap_or(""));
        summary(&mut md, case);
        md.push('\n');
    }
    let path = out_dir.join("tradeoff.md");
    std::fs::write(&path, md)?;
    println!(
        "wrote {} and {} in {elapsed:.1} s",
        path.display(),
        png.display()
    );
    Ok(())
}
