//! Benchmark of repeated couplings of small interfaces: the time of a whole
//! [`assemble_coupling`] call against the time its statistics report.
//!
//! ```text
//! cargo run --release --example bench_small_calls -- --json docs/bench_small_calls.json
//! ```
//!
//! A contact or gap law couples its interface again at every Newton step, so the cost of a
//! call that the phases inside it do not see (starting the worker pool, checking the options)
//! counts once per step. Each case is coupled `--calls` times per thread count (1, 2 and
//! rayon's default) in this process; the record gives the medians of the call's wall time
//! (`call_ms`) and of [`CouplingStats::seconds`](mortar::CouplingStats)'s total (`inside_ms`),
//! and their difference. The cases, at about 10^3 slave faces:
//! - `line2d`: two straight lines (the sorted merge);
//! - `arc2d`: two half circles (the chain walk and the fused kernel);
//! - `plane3d`: a square of triangles against another (the closed forms);
//! - `cylinder`: quads against triangles on a cylinder (curved, the general path).
//!
//! Prints one JSON record per (case, threads) and a line a person can read for each.

use std::path::PathBuf;
use std::time::Instant;

use clap::Parser;
use mortar::generate::{cylinder_surface, half_circle_mesh, line_mesh, square_triangles, Diagonal};
use mortar::{assemble_coupling, CouplingOptions, Interface};
use serde_json::{json, Value};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// Repeated couplings of small interfaces.
#[derive(Parser)]
struct Args {
    /// Calls per (case, threads); the medians are reported.
    #[arg(long, default_value_t = 101)]
    calls: usize,
    /// Write the records (a JSON array) here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Run only these cases (comma-separated: line2d, arc2d, plane3d, cylinder).
    #[arg(long, value_delimiter = ',')]
    cases: Vec<String>,
    /// Run only these thread counts (comma-separated; 0 for rayon's default).
    #[arg(long, value_delimiter = ',')]
    threads: Vec<usize>,
}

/// The interfaces of the cases: the slave at about 10^3 faces, the master 1.5 times finer.
fn cases() -> Res<Vec<(&'static str, Interface)>> {
    Ok(vec![
        (
            "line2d",
            Interface::new(line_mesh(1000, false, 1)?, line_mesh(1501, true, 1)?)?,
        ),
        (
            "arc2d",
            Interface::new(
                half_circle_mesh(1000, false, 1)?,
                half_circle_mesh(1501, true, 1)?,
            )?,
        ),
        (
            "plane3d",
            Interface::new(
                square_triangles(22, Diagonal::Main, 0.0, false, 1)?,
                square_triangles(34, Diagonal::Anti, 0.0, true, 1)?,
            )?,
        ),
        (
            "cylinder",
            Interface::new(
                cylinder_surface(1.0, 64, 16, false, false, 1)?,
                cylinder_surface(1.0, 97, 25, true, true, 1)?,
            )?,
        ),
    ])
}

/// The median of `v` (sorted in place).
fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Res<()> {
    let args = Args::parse();
    if args.calls == 0 {
        return Err("--calls must be at least 1".into());
    }
    let mut records: Vec<Value> = Vec::new();
    for (case, interface) in cases()? {
        if !args.cases.is_empty() && !args.cases.iter().any(|c| c == case) {
            continue;
        }
        for threads in [Some(1), Some(2), None] {
            if !args.threads.is_empty() && !args.threads.contains(&threads.unwrap_or(0)) {
                continue;
            }
            let options = CouplingOptions {
                threads,
                ..CouplingOptions::default()
            };
            let (mut call, mut inside) = (Vec::new(), Vec::new());
            let mut pairs = 0;
            for _ in 0..args.calls {
                let t = Instant::now();
                let c = assemble_coupling(&interface, &options)?;
                call.push(t.elapsed().as_secs_f64() * 1e3);
                inside.push(c.stats.seconds.total * 1e3);
                pairs = c.stats.pairs;
            }
            let (call_ms, inside_ms) = (median(&mut call), median(&mut inside));
            let record = json!({
                "case": case,
                "slave_faces": interface.slave().face_count(),
                "pairs": pairs,
                "threads": threads.map_or(Value::from("default"), Value::from),
                "calls": args.calls,
                "call_ms": call_ms,
                "inside_ms": inside_ms,
                "outside_ms": call_ms - inside_ms,
                "note": "medians over the calls; inside: the coupling's own phases \
                         (CouplingStats::seconds.total); outside: the rest of the call",
            });
            println!("{record}");
            println!(
                "{case} ({} slave faces, {pairs} pairs), threads {}: a call {call_ms:.3} ms, \
                 {inside_ms:.3} ms of it inside the coupling's phases, {:.3} ms outside",
                interface.slave().face_count(),
                threads.map_or("default".to_string(), |t| t.to_string()),
                call_ms - inside_ms,
            );
            records.push(record);
        }
    }
    if let Some(path) = &args.json {
        std::fs::write(path, serde_json::to_string_pretty(&records)? + "\n")?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
