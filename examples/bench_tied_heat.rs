//! Benchmark (not a test): a 2D tied heat problem with about 10^6 unknowns, end to end
//! (assembly, coupling, system build and factorisation, solve; mesh generation excluded),
//! solved both ways: the dual-condensed SPD system (sparse Cholesky, by body) and the saddle-point
//! system (sparse LDL^T in an order that needs no pivoting, LU if refused). Time and peak
//! memory per phase. With `--dim 3` the same scene in 3D (Hex8 against Tet4), and the path
//! `petsc`: the condensed system through PETSc's CG with GAMG (a build with `--features
//! mortar-petsc/petsc`), against the direct `dual` at one size and alone at the sizes the
//! direct solve cannot reach.
//!
//! ```text
//! cargo run --release --example bench_tied_heat -- --json docs/bench_tied_heat.json
//! cargo run --release --example bench_tied_heat -- --n 256            # a smaller problem
//! cargo run --release --features mortar-petsc/petsc --example bench_tied_heat -- \
//!     --dim 3 --sizes 48,80,164 --paths dual,petsc --json docs/bench_tied_heat_3d.json
//! ```
//!
//! The scene is `mortar_scenes::tied_heat`'s straight 2D one: the unit square cut at
//! x = 1/2, a left body of `n/2 x n` Quad4 (master) and a right body of `3n/4 x 3n/2` squares
//! cut into Tri3 (slave), a 2:3 size ratio; u = sin(pi x) sin(pi y) with its source and
//! Dirichlet data on the outer boundary; dual multipliers, segment-based integration. The
//! default `n = 784` gives 1,001,758 temperature unknowns.
//!
//! Each path runs in its own child process (this program re-executed with `--child PATH`), so
//! that the peaks are its own. Peak memory is the kernel's resident high-water mark (VmHWM of
//! /proc/self/status), reset before each phase by writing 5 to /proc/self/clear_refs, so each
//! phase's figure is the peak during that phase (where the kernel allows the reset; else the
//! peak so far, and the report says so). The saddle-point path uses the same dual multipliers
//! and solves the same discrete problem.

use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

use clap::Parser;
use mortar::core::mesh::BoundaryFace;
use mortar::fem::linalg::SparseSolver;
use mortar::petsc::PetscBackend;
use mortar::physics::heat::{
    assemble_heat_load, assemble_heat_stiffness, HeatBody, HeatMaterial, HeatOptions,
};
use mortar::physics::tied::{FormulationChoice, Tie, TiedOptions, TiedSystem};
use mortar::physics::LinearSolve;
use mortar_scenes::linear_solver::DEFAULT_LINEAR_TOLERANCE;
use mortar_scenes::tied_heat::{straight_blocks, Exact, Geometry, TiedHeatScene};
use serde_json::{json, Value};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

#[derive(Parser, Debug)]
#[command(about = "Tied heat conduction with 10^6 unknowns: time and peak memory per phase")]
struct Args {
    /// Cells per unit length of the coarse body (a multiple of 4); 784 gives 1,001,758
    /// unknowns.
    #[arg(long, default_value_t = 784)]
    n: usize,
    /// The dimension (2 or 3).
    #[arg(long, default_value_t = 2)]
    dim: usize,
    /// Several sizes `n` in one run (each path at each; the direct paths are skipped above
    /// `--direct-max` unknowns' worth of `n`).
    #[arg(long, value_delimiter = ',')]
    sizes: Vec<usize>,
    /// The largest `n` the direct paths run at, with `--sizes`.
    #[arg(long, default_value_t = usize::MAX)]
    direct_max: usize,
    /// Write the JSON report here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Which paths to run (dual, saddle, petsc).
    #[arg(long, value_delimiter = ',', default_value = "dual,saddle")]
    paths: Vec<String>,
    /// Internal: run one path in this process and print its JSON on stdout.
    #[arg(long, hide = true)]
    child: Option<String>,
}

fn main() -> Res<()> {
    let args = Args::parse();
    if let Some(path) = &args.child {
        let report = run_path(path, args.n, args.dim)?;
        println!("{report}");
        return Ok(());
    }
    let load_average = std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default();
    let exe = std::env::current_exe()?;
    let mut runs = Vec::new();
    let sizes = if args.sizes.is_empty() {
        vec![args.n]
    } else {
        args.sizes.clone()
    };
    for &n in &sizes {
        for path in &args.paths {
            if path != "petsc" && n > args.direct_max {
                continue;
            }
            eprintln!("running the {path} path (n = {n}) in a child process ...");
            let out = Command::new(&exe)
                .args(["--child", path, "--n", &n.to_string()])
                .args(["--dim", &args.dim.to_string()])
                .output()?;
            if !out.status.success() {
                // Kept in the report (a child killed for its memory, say), the other runs
                // go on.
                let why = format!(
                    "{} {}",
                    out.status,
                    String::from_utf8_lossy(&out.stderr).trim()
                );
                eprintln!("the {path} path failed at n = {n}: {why}");
                runs.push(json!({ "path": path, "n": n, "dim": args.dim, "failed": why }));
                continue;
            }
            let v: Value = serde_json::from_slice(&out.stdout)?;
            runs.push(v);
        }
    }
    print_table(&runs);
    let report = json!({
        "benchmark": format!(
            "tied heat conduction, {}D, end to end (mesh generation excluded)",
            args.dim
        ),
        "machine": machine(),
        "threads": rayon_threads(),
        "load_average_at_start": load_average,
        "n": args.n,
        "dim": args.dim,
        "target": { "dual_seconds": 4.0, "saddle_over_dual": 2.0, "issue": 13 },
        "paths": runs,
        "how": "cargo run --release --example bench_tied_heat -- --json docs/bench_tied_heat.json",
    });
    if let Some(p) = &args.json {
        std::fs::write(p, serde_json::to_string_pretty(&report)? + "\n")?;
        eprintln!("wrote {}", p.display());
    }
    Ok(())
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    format!("{cpu}, {} threads", rayon_threads())
}

/// The resident high-water mark (bytes), from /proc/self/status.
fn vm_hwm() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Resets the high-water mark to the current resident size; false if the kernel refuses.
fn reset_hwm() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// One phase: its seconds and its peak resident memory.
struct Phases {
    list: Vec<Value>,
    reset_ok: bool,
}

impl Phases {
    fn measure<T>(&mut self, name: &str, f: impl FnOnce() -> Res<T>) -> Res<(T, f64)> {
        self.reset_ok &= reset_hwm();
        let t0 = Instant::now();
        let out = f()?;
        let s = t0.elapsed().as_secs_f64();
        self.list.push(json!({
            "phase": name,
            "seconds": s,
            "peak_bytes": vm_hwm(),
        }));
        Ok((out, s))
    }
}

fn run_path(path: &str, n: usize, dim: usize) -> Res<Value> {
    let choice = match path {
        "dual" | "petsc" => FormulationChoice::DualCondensed,
        "saddle" => FormulationChoice::SaddlePoint,
        _ => return Err(format!("unknown path {path:?} (dual, saddle, petsc)").into()),
    };
    let petsc = PetscBackend::automatic(DEFAULT_LINEAR_TOLERANCE, "");
    let linear = LinearSolve {
        backend: (path == "petsc").then_some(&petsc as &dyn SparseSolver),
        ..LinearSolve::default()
    };
    let mut scene = TiedHeatScene::new(dim, Geometry::Straight, n);
    scene.exact = Exact::Sine;
    let tied = TiedOptions::default().with_formulation(choice);

    // Mesh generation and boundary data (not timed as a phase): build the bodies as the
    // scene does, without assembling.
    let t_mesh = Instant::now();
    let (slave, master) = bodies(&scene)?;
    let mesh_seconds = t_mesh.elapsed().as_secs_f64();
    let mut phases = Phases {
        list: Vec::new(),
        reset_ok: true,
    };
    let options = HeatOptions::default();

    let ((matrices, loads), _) = phases.measure("assembly", || {
        // A steady problem: the stiffness alone.
        let m = [
            assemble_heat_stiffness(&slave, &options)?,
            assemble_heat_stiffness(&master, &options)?,
        ];
        let f = [
            assemble_heat_load(&slave, 0.0, &options)?,
            assemble_heat_load(&master, 0.0, &options)?,
        ];
        Ok((m, f))
    })?;
    let (tie, _) = phases.measure("coupling", || {
        let ss = slave.mesh.boundary_surface(on_interface)?;
        let ms = master.mesh.boundary_surface(on_interface)?;
        Ok(Tie::new(
            &slave.mesh,
            &master.mesh,
            ss,
            ms,
            &scene.coupling,
        )?)
    })?;
    let dirichlet = [slave.dirichlet_nodes(), master.dirichlet_nodes()];
    let g = [
        slave.dirichlet_values(&dirichlet[0].0, &dirichlet[0].1, 0.0),
        master.dirichlet_values(&dirichlet[1].0, &dirichlet[1].1, 0.0),
    ];
    let (system, _) = phases.measure("system and factorisation", || {
        Ok(TiedSystem::new_on(
            [&matrices[0], &matrices[1]],
            &tie,
            [&dirichlet[0].0, &dirichlet[1].0],
            &tied,
            &linear,
        )?)
    })?;
    let (fields, _) = phases.measure("solve", || {
        Ok(system.solve([&loads[0], &loads[1]], [&g[0], &g[1]])?)
    })?;

    // Check the solution (not timed).
    let exact = scene.exact;
    let mut max_err: f64 = 0.0;
    for (b, body) in [&slave, &master].iter().enumerate() {
        for (x, t) in body.mesh.coords().iter().zip(&fields.fields[b]) {
            max_err = max_err.max((t - exact.value(dim, x)).abs());
        }
    }
    let report = system.report();
    let s = system.seconds();
    let total: f64 = phases
        .list
        .iter()
        .map(|p| p["seconds"].as_f64().unwrap_or(0.0))
        .sum();
    let peak = phases
        .list
        .iter()
        .filter_map(|p| p["peak_bytes"].as_u64())
        .max();
    Ok(json!({
        "path": path,
        "formulation": report.formulation.describe(),
        "factorisation": report.factorisation,
        "reason": report.reason,
        "unknowns": slave.mesh.node_count() + master.mesh.node_count(),
        "system_unknowns": report.unknowns,
        "system_nonzeros": report.nonzeros,
        "multipliers": report.multipliers,
        "mesh_generation_seconds": mesh_seconds,
        "phases": phases.list,
        "system_build_seconds": s.build,
        "factorisation_seconds": s.factorisation,
        "total_seconds": total,
        "peak_bytes": peak,
        "per_phase_peaks": phases.reset_ok,
        "max_nodal_error": max_err,
        "dim": dim,
        "n": n,
        "krylov": petsc.reports().iter().map(|r| json!({
            "method": format!("{}+{}", r.ksp_type, r.pc_type),
            "iterations": r.iterations,
            "relative_residual": r.relative_residual,
            "setup_seconds": r.setup_seconds,
            "solve_seconds": r.solve_seconds,
        })).collect::<Vec<_>>(),
    }))
}

fn on_interface(f: &BoundaryFace) -> bool {
    (f.centroid.x - 0.5).abs() < 1e-9
}

/// The two bodies of the straight scene (as `TiedHeatScene::build` makes them), with the
/// source and the Dirichlet data of the exact solution; slave first.
fn bodies(scene: &TiedHeatScene) -> Res<(HeatBody, HeatBody)> {
    let dim = scene.dim;
    let (master, slave) = straight_blocks(dim, scene.n, 1_000_001)?;
    let (k, exact) = (scene.conductivity, scene.exact);
    let body = |name: &str, mesh| -> Res<HeatBody> {
        let b = HeatBody::new(name, mesh, HeatMaterial::new(k, 1.0))
            .with_source(move |x, _| exact.source(dim, k, x));
        let outer = b.mesh.boundary_nodes(|f| !on_interface(f))?;
        Ok(b.with_dirichlet_nodes(outer, move |x, _| exact.value(dim, x)))
    };
    Ok((body("slave", slave)?, body("master", master)?))
}

fn print_table(runs: &[Value]) {
    let gib = |v: &Value| v.as_u64().map(|b| b as f64 / (1u64 << 30) as f64);
    println!(
        "{:<8} {:<26} {:>9} {:>10}",
        "path", "phase", "seconds", "peak GiB"
    );
    for r in runs {
        let path = r["path"].as_str().unwrap_or("?");
        if let Some(why) = r["failed"].as_str() {
            println!("{path:<8} failed at n = {}: {why}", r["n"]);
            continue;
        }
        for p in r["phases"].as_array().into_iter().flatten() {
            println!(
                "{:<8} {:<26} {:>9.3} {:>10.3}",
                path,
                p["phase"].as_str().unwrap_or("?"),
                p["seconds"].as_f64().unwrap_or(f64::NAN),
                gib(&p["peak_bytes"]).unwrap_or(f64::NAN)
            );
        }
        println!(
            "{:<8} {:<26} {:>9.3} {:>10.3}   ({} unknowns; system {} x {}, {} nonzeros; max error {:.2e}{})",
            path,
            "total",
            r["total_seconds"].as_f64().unwrap_or(f64::NAN),
            gib(&r["peak_bytes"]).unwrap_or(f64::NAN),
            r["unknowns"],
            r["system_unknowns"],
            r["system_unknowns"],
            r["system_nonzeros"],
            r["max_nodal_error"].as_f64().unwrap_or(f64::NAN),
            r["krylov"]
                .as_array()
                .and_then(|k| k.first())
                .map(|k| format!("; {} {} iterations", k["method"], k["iterations"]))
                .unwrap_or_default(),
        );
    }
}
