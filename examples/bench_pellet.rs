//! Benchmark of the thermomechanical pellet's solvers: Newton on the
//! assembled Jacobian (sparse LU every Newton step) against JFNK with the block
//! preconditioner kept across steps, on the default scene (30 backward Euler steps through
//! the ramp and hold, then the steady state) in each geometry at several refinements: the
//! data of the `[solver] method = "auto"` rule.
//!
//! ```text
//! cargo run --release --example bench_pellet -- --json docs/bench_pellet.json
//! cargo run --release --example bench_pellet -- --quick
//! ```
//!
//! Each case runs Newton and JFNK alternately, three times each (one run of each with
//! `--quick`), in this process; the figures are the medians of the seconds spent in the
//! Newton solves (setup and output excluded), and the ratio JFNK / Newton is formed from the
//! medians of one session. Prints one JSON record per case and a line a person can read.

use std::path::PathBuf;

use clap::Parser;
use mortar_scenes::pellet::{run, Geometry, PelletScene, SolverMethod};
use serde_json::{json, Value};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

#[derive(Parser, Debug)]
#[command(about = "Newton against JFNK on the thermomechanical pellet")]
struct Args {
    /// Write the records (a JSON array) here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// The default refinement only, one run of each.
    #[arg(long)]
    quick: bool,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Res<()> {
    let args = Args::parse();
    let (cases, repeats) = if args.quick {
        (vec![(Geometry::Plane, 3usize)], 1)
    } else {
        (
            vec![
                (Geometry::Plane, 1usize),
                (Geometry::Plane, 3),
                (Geometry::Plane, 6),
                (Geometry::Axisymmetric, 1),
                (Geometry::Axisymmetric, 3),
                (Geometry::Axisymmetric, 8),
                (Geometry::ThreeD, 1),
                (Geometry::ThreeD, 2),
            ],
            3,
        )
    };
    let out = std::env::temp_dir().join(format!("mortar-bench-pellet-{}", std::process::id()));
    let mut records = Vec::new();
    for &(geometry, r) in &cases {
        let mut seconds = [Vec::new(), Vec::new()];
        let mut last: [Value; 2] = [Value::Null, Value::Null];
        for _ in 0..repeats {
            for (k, method) in [SolverMethod::Newton, SolverMethod::Jfnk]
                .into_iter()
                .enumerate()
            {
                let mut scene = PelletScene::default();
                scene.mesh.refinement = r;
                scene.model.geometry = geometry;
                scene.solver.method = method;
                scene.time.snapshots = 0;
                let rep = run(&scene, &out, false)?;
                seconds[k].push(
                    rep["solver"]["seconds"]["newton_total"]
                        .as_f64()
                        .unwrap_or(f64::NAN),
                );
                last[k] = rep;
            }
        }
        let _ = std::fs::remove_dir_all(&out);
        let (tn, tj) = (median(seconds[0].clone()), median(seconds[1].clone()));
        let centre = |k: usize| last[k]["center_temperature"].as_f64().unwrap_or(f64::NAN);
        let agreement = (centre(0) - centre(1)).abs() / centre(0).abs();
        let solver = |k: usize| {
            let s = &last[k]["solver"];
            json!({
                "seconds_median": if k == 0 { tn } else { tj },
                "seconds_runs": seconds[k],
                "newton_iterations": s["newton_iterations"],
                "linear_iterations": s["linear_iterations"],
                "factorizations": s["factorizations"],
                "reused_preconditioners": s["reused_preconditioners"],
                "assembly_seconds": s["seconds"]["assembly"],
                "linear_seconds": s["seconds"]["linear"],
            })
        };
        let record = json!({
            "geometry": geometry,
            "refinement": r,
            "unknowns": last[0]["mesh"]["unknowns"],
            "time_steps": last[0]["history"]["time"].as_array().map_or(0, |t| t.len() - 1),
            "newton": solver(0),
            "jfnk": solver(1),
            "jfnk_over_newton": tj / tn,
            "centre_temperature_agreement": agreement,
        });
        println!("{record}");
        eprintln!(
            "{geometry:?}, refinement {r} ({} unknowns): Newton {tn:.3} s ({} steps, {} LU), JFNK {tj:.3} s ({} steps, {} GMRES iterations, {} block factorisations): JFNK / Newton = {:.2}, centre temperatures agree to {agreement:.1e}",
            record["unknowns"],
            record["newton"]["newton_iterations"],
            record["newton"]["factorizations"],
            record["jfnk"]["newton_iterations"],
            record["jfnk"]["linear_iterations"],
            record["jfnk"]["factorizations"],
            tj / tn
        );
        records.push(record);
    }
    if let Some(path) = args.json {
        std::fs::write(&path, serde_json::to_string_pretty(&records)? + "\n")?;
        eprintln!("written {}", path.display());
    }
    Ok(())
}
