//! The thermomechanical pellet's dials, speed against accuracy: the default scene (free axial
//! expansion, 30 backward Euler steps through the ramp and hold, then the steady state) over
//! its geometry (2D cross-section, r-z, 3D segment), contact law (exponential, exact),
//! refinement and solver (Newton, JFNK), each case's seconds in the Newton solves against its
//! errors at 30 s.
//!
//! ```text
//! cargo run --release --example bench_pellet_dials -- --json docs/bench_pellet_dials.json
//! cargo run --release --example bench_pellet_dials -- --quick
//! ```
//!
//! The reference is the independent 1D radial model of the tests (`tests/pellet/radial.rs`,
//! compiled in here: finite volumes exact for the steady profiles, Timoshenko-Goodier
//! cylinders in generalized plane strain, the same gap, contact and plenum laws, 400 + 60
//! radial cells, the same time steps), run once per law on the scene's data. The errors, as
//! `tests/pellet/coupled.rs` defines them, at the last step (30 s): the centre temperature and
//! the peak interface pressure `P_c` (gas included; the radial model's is uniform) relative to
//! the reference's, and the mean gap relative to the larger of the reference's and the
//! exponential law's onset `xi` (under the exact law it may close to zero). Newton and JFNK
//! solve the same equations: each record also gives its difference to the other solver's
//! run of the same dials (centre temperature and peak interface pressure, the larger).
//!
//! The cases run in rounds, each round every case once in turn (three rounds, one with
//! `--quick`), in this process; the seconds are the medians over the rounds of the seconds
//! spent in the Newton solves (setup, output and the reference excluded). The machine's load
//! average before and after and the benchmark's wall time are recorded with them. Prints one
//! JSON record per case and a line a person can read.

use std::path::PathBuf;
use std::time::Instant;

use clap::Parser;
use mortar_scenes::pellet::{run, ContactLawName, Geometry, PelletScene, SolverMethod};
use serde_json::{json, Value};

/// The independent radial reference of the tests; its tests are compiled only there.
#[allow(dead_code)]
#[path = "../tests/pellet/radial.rs"]
mod radial;

use radial::{RadialPellet, RadialRow};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

#[derive(Parser, Debug)]
#[command(about = "The thermomechanical pellet's speed against its accuracy, dial by dial")]
struct Args {
    /// Write the records (a JSON object: the conditions, the references, the cases) here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// The smallest meshes only, one round.
    #[arg(long)]
    quick: bool,
}

/// One setting of the dials.
#[derive(Debug, Clone, Copy)]
struct Case {
    geometry: Geometry,
    law: ContactLawName,
    refinement: usize,
    method: SolverMethod,
}

impl Case {
    /// The default scene with these dials.
    fn scene(&self) -> PelletScene {
        let mut scene = PelletScene::default();
        scene.model.geometry = self.geometry;
        scene.contact.law = self.law;
        scene.mesh.refinement = self.refinement;
        scene.solver.method = self.method;
        scene.time.snapshots = 0;
        scene
    }

    /// A name for the JSON's selectors: `plane-exponential-3-jfnk`.
    fn id(&self) -> String {
        format!(
            "{}-{}-{}-{}",
            name(&self.geometry),
            name(&self.law),
            self.refinement,
            self.method.name()
        )
    }
}

/// A value's scene-file name.
fn name<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_value(v)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

/// The cases: each geometry at a few refinements under each law, each by Newton and by JFNK.
fn cases(quick: bool) -> Vec<Case> {
    use ContactLawName::{Exact, Exponential};
    use Geometry::{Axisymmetric, Plane, ThreeD};
    let list: &[(Geometry, ContactLawName, usize)] = if quick {
        &[
            (Plane, Exponential, 1),
            (Plane, Exact, 1),
            (Axisymmetric, Exponential, 1),
            (Axisymmetric, Exponential, 3),
            (Axisymmetric, Exact, 3),
            (ThreeD, Exponential, 1),
        ]
    } else {
        &[
            (Plane, Exponential, 1),
            (Plane, Exponential, 3),
            (Plane, Exponential, 6),
            (Plane, Exact, 1),
            (Plane, Exact, 3),
            (Plane, Exact, 6),
            (Axisymmetric, Exponential, 1),
            (Axisymmetric, Exponential, 3),
            (Axisymmetric, Exponential, 8),
            (Axisymmetric, Exact, 1),
            (Axisymmetric, Exact, 3),
            (Axisymmetric, Exact, 8),
            (ThreeD, Exponential, 1),
            (ThreeD, Exponential, 2),
            (ThreeD, Exact, 1),
            (ThreeD, Exact, 2),
        ]
    };
    list.iter()
        .flat_map(|&(geometry, law, refinement)| {
            [SolverMethod::Newton, SolverMethod::Jfnk]
                .into_iter()
                .map(move |method| Case {
                    geometry,
                    law,
                    refinement,
                    method,
                })
        })
        .collect()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The 1-minute load average (Linux), or `None`.
fn load_average() -> Option<f64> {
    std::fs::read_to_string("/proc/loadavg")
        .ok()?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// The last value of the report's history `key`.
fn last(rep: &Value, key: &str) -> f64 {
    rep["history"][key]
        .as_array()
        .and_then(|a| a.last())
        .and_then(Value::as_f64)
        .unwrap_or(f64::NAN)
}

/// The reference's figures at 30 s.
fn reference_json(law: ContactLawName, row: &RadialRow, cells: [usize; 2]) -> Value {
    json!({
        "law": law,
        "model": "the 1D radial model of tests/pellet/radial.rs (generalized plane strain)",
        "pellet_cells": cells[0],
        "cladding_cells": cells[1],
        "time": row.time,
        "center_temperature": row.center_temperature,
        "interface_pressure": row.interface_pressure,
        "plenum_pressure": row.plenum_pressure,
        "gap": row.gap,
    })
}

fn main() -> Res<()> {
    let args = Args::parse();
    let started = Instant::now();
    let load_before = load_average();
    let rounds = if args.quick { 1 } else { 3 };
    let cases = cases(args.quick);

    // The references, one per law, on the default scene's data (they do not depend on the
    // geometry, the refinement or the solver).
    let mut references = Vec::new();
    for law in [ContactLawName::Exponential, ContactLawName::Exact] {
        let mut scene = PelletScene::default();
        scene.contact.law = law;
        let model = RadialPellet::from_scene(&scene);
        let history = model.simulate()?;
        let row = *history.rows.last().ok_or("the radial model ran no step")?;
        eprintln!(
            "reference ({law:?}): centre {:.3} K, P_c {:.4} MPa, gap {:.4} um at {} s",
            row.center_temperature,
            row.interface_pressure * 1e-6,
            row.gap * 1e6,
            row.time
        );
        references.push((
            law,
            row,
            reference_json(law, &row, [model.pellet_cells, model.cladding_cells]),
        ));
    }

    let out =
        std::env::temp_dir().join(format!("mortar-bench-pellet-dials-{}", std::process::id()));
    let mut seconds = vec![Vec::new(); cases.len()];
    let mut reports = vec![Value::Null; cases.len()];
    for round in 0..rounds {
        for (k, case) in cases.iter().enumerate() {
            let rep = run(&case.scene(), &out, false)?;
            let _ = std::fs::remove_dir_all(&out);
            let s = rep["solver"]["seconds"]["newton_total"]
                .as_f64()
                .unwrap_or(f64::NAN);
            eprintln!("round {}: {} {s:.3} s", round + 1, case.id());
            seconds[k].push(s);
            reports[k] = rep;
        }
    }

    let mut records = Vec::new();
    for (k, ((case, rep), runs)) in cases.iter().zip(&reports).zip(seconds).enumerate() {
        let (_, r, _) = references
            .iter()
            .find(|(law, _, _)| *law == case.law)
            .expect("a reference per law");
        let onset = case.scene().contact.onset_gap;
        let (centre, pressure, gap) = (
            last(rep, "center_temperature"),
            last(rep, "peak_interface_pressure"),
            last(rep, "gap"),
        );
        // The same dials by the other solver: the largest relative difference of the centre
        // temperature and the peak interface pressure at 30 s.
        let other = cases.iter().zip(&reports).enumerate().find(|(j, (c, _))| {
            *j != k
                && (c.geometry, c.law, c.refinement) == (case.geometry, case.law, case.refinement)
        });
        let solver_difference = other.map(|(_, (_, o))| {
            ["center_temperature", "peak_interface_pressure"]
                .iter()
                .map(|key| ((last(rep, key) - last(o, key)) / last(o, key)).abs())
                .fold(0.0, f64::max)
        });
        let s = &rep["solver"];
        let t = median(runs.clone());
        let record = json!({
            "case": case.id(),
            "geometry": case.geometry,
            "law": case.law,
            "refinement": case.refinement,
            "solver": case.method.name(),
            "unknowns": rep["mesh"]["unknowns"],
            "time_steps": rep["history"]["time"].as_array().map_or(0, |t| t.len() - 1),
            "seconds_median": t,
            "seconds_runs": runs,
            "newton_iterations": s["newton_iterations"],
            "linear_iterations": s["linear_iterations"],
            "factorizations": s["factorizations"],
            "time": last(rep, "time"),
            "center_temperature": centre,
            "peak_interface_pressure": pressure,
            "plenum_pressure": last(rep, "plenum_pressure"),
            "gap": gap,
            "center_temperature_error": (centre - r.center_temperature).abs() / r.center_temperature,
            "pressure_error": (pressure - r.interface_pressure).abs() / r.interface_pressure,
            "gap_error": (gap - r.gap).abs() / r.gap.abs().max(onset),
            "gap_error_um": (gap - r.gap).abs() * 1e6,
            "other_solver_difference": solver_difference,
        });
        println!("{record}");
        eprintln!(
            "{}: {} unknowns, {t:.3} s; at 30 s centre {centre:.3} K (error {:.2e}), peak P_c {:.4} MPa (error {:.2e}), gap {:.4} um (error {:.2e})",
            record["case"].as_str().unwrap_or_default(),
            record["unknowns"],
            record["center_temperature_error"].as_f64().unwrap_or(f64::NAN),
            pressure * 1e-6,
            record["pressure_error"].as_f64().unwrap_or(f64::NAN),
            gap * 1e6,
            record["gap_error"].as_f64().unwrap_or(f64::NAN),
        );
        records.push(record);
    }
    let wall = started.elapsed().as_secs_f64();
    let load_after = load_average();
    eprintln!(
        "{} cases, {rounds} round(s), {wall:.0} s in all; load average {load_before:?} before, {load_after:?} after",
        cases.len()
    );
    if let Some(path) = args.json {
        let doc = json!({
            "rounds": rounds,
            "wall_seconds": wall,
            "load_average_before": load_before,
            "load_average_after": load_after,
            "cpus": std::thread::available_parallelism().map_or(0, |n| n.get()),
            "references": references.iter().map(|(_, _, j)| j).collect::<Vec<_>>(),
            "cases": records,
        });
        std::fs::write(&path, serde_json::to_string_pretty(&doc)? + "\n")?;
        eprintln!("written {}", path.display());
    }
    Ok(())
}
