//! Benchmark of the frictionless contact solve.
//!
//! ```text
//! cargo run --release --example bench_contact -- --json docs/bench_contact.json
//! cargo run --release --example bench_contact -- --quick
//! ```
//!
//! Cases, each size in a child process (this program re-executed with the hidden
//! `--single CASE N`) so that its peak memory (`VmHWM`) is its own:
//! - `blocks3d`: the pressure patch of two stacked unit cubes, the lower `n^3` Hex8, the upper
//!   `(4n/3)^3` cubes cut into Tet4 (non-matching contact faces), `u_y = 0` at the bottom,
//!   symmetry on `x = 0` and `z = 0`, 50 MPa on top; dual multipliers (the pressures condensed
//!   out), the exact law with automatic `c`. Phases: meshes, assembly (stiffness and loads),
//!   coupling (D, M), then per Newton step the linear solve (building the condensed system,
//!   Cholesky, solve) and the rest (residuals, law).
//! - `blocks3d_petsc`: the same with the Newton systems solved by PETSc
//!   (`PetscBackend::automatic`: CG with GAMG, the bodies' rigid motions as its near null
//!   space, relative tolerance `mortar_scenes::linear_solver::DEFAULT_LINEAR_TOLERANCE`), in
//!   a build with the `petsc` feature (`--features petsc`); the record adds PETSc's
//!   iterations per solve.
//! - `hertz2d`: the 2D Hertz scene (`mortar_scenes::hertz`) with `n` arc cells; its build
//!   (meshes, coupling, assembly) is timed as one phase.
//!
//! Prints one JSON record per case and size, and a table.

use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

use clap::Parser;
use mortar::core::mesh::BoundaryFace;
use mortar::fem::linalg::SparseSolver;
use mortar::generate::{box_mesh, CellShape};
use mortar::petsc::PetscBackend;
use mortar::physics::contact::{
    automatic_complementarity, solve_contact, solve_contact_on, ContactOptions, ContactSolution,
    NormalGap,
};
use mortar::physics::elastic::{
    assemble_elastic_load, assemble_elastic_stiffness, ComponentSet, ElasticBody, ElasticMaterial,
    ElasticOptions,
};
use mortar::physics::laws::ContactComplementarity;
use mortar::physics::tied::Tie;
use mortar::physics::LinearSolve;
use mortar::CouplingOptions;
use mortar_scenes::hertz::HertzScene;
use nalgebra::Vector3;
use serde_json::{json, Value};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

#[derive(Parser, Debug)]
#[command(about = "Benchmark of the frictionless contact solve")]
struct Args {
    /// Write the records (a JSON array) here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Small sizes only (seconds).
    #[arg(long)]
    quick: bool,
    /// Internal: run one case in this process and print one JSON line.
    #[arg(long, num_args = 2, value_names = ["CASE", "N"], hide = true)]
    single: Option<Vec<String>>,
}

/// The peak resident set size of this process (`VmHWM`), in bytes.
fn peak_memory() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .unwrap_or_default()
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        .map_or(0, |kb| kb * 1024)
}

/// The phases of the Newton iteration of a solution.
fn newton_record(sol: &ContactSolution) -> Value {
    let linear: Vec<f64> = sol
        .steps
        .iter()
        .flat_map(|s| s.linear_seconds.iter().copied())
        .collect();
    let total: f64 = sol.steps.iter().map(|s| s.seconds).sum();
    json!({
        "newton_steps": sol.steps.iter().map(|s| s.newton_steps).collect::<Vec<_>>(),
        "settled_at": sol.steps.iter().map(|s| s.settled_at).collect::<Vec<_>>(),
        "active": sol.steps.last().map_or(0, |s| s.active),
        "linear_solve_seconds": linear,
        "newton_seconds": total,
        "residuals_and_law_seconds": total - linear.iter().sum::<f64>(),
        "formulation": sol.formulation,
    })
}

/// The stacked blocks at size `n`, the Newton systems solved by `petsc` if given (else by
/// the direct solves).
fn blocks3d(n: usize, petsc: Option<&PetscBackend>) -> Res<Value> {
    let t0 = Instant::now();
    let m = (4 * n).div_ceil(3);
    let lower = box_mesh([0.0; 3], [1.0; 3], [n, n, n], CellShape::Tensor, 1)?;
    let upper = box_mesh(
        [0.0, 1.0, 0.0],
        [1.0, 2.0, 1.0],
        [m, m, m],
        CellShape::Simplex,
        10_000_000,
    )?;
    let t_mesh = t0.elapsed().as_secs_f64();
    let material = ElasticMaterial::new(210e9, 0.3);
    let near = |a: f64, b: f64| (a - b).abs() < 1e-9;
    let zero = |_: &Vector3<f64>| Vector3::zeros();
    let master = ElasticBody::new("lower", lower, material)
        .with_dirichlet_where(|f| near(f.centroid.y, 0.0), ComponentSet::One(1), zero)?
        .with_dirichlet_where(|f| near(f.centroid.x, 0.0), ComponentSet::One(0), zero)?
        .with_dirichlet_where(|f| near(f.centroid.z, 0.0), ComponentSet::One(2), zero)?;
    let slave = ElasticBody::new("upper", upper, material)
        .with_dirichlet_where(|f| near(f.centroid.x, 0.0), ComponentSet::One(0), zero)?
        .with_dirichlet_where(|f| near(f.centroid.z, 0.0), ComponentSet::One(2), zero)?
        .with_traction_where(
            |f| near(f.centroid.y, 2.0),
            |_| Vector3::new(0.0, -50e6, 0.0),
        )?;
    let t1 = Instant::now();
    let options = ElasticOptions::default();
    let k = [
        assemble_elastic_stiffness(&slave, &options)?,
        assemble_elastic_stiffness(&master, &options)?,
    ];
    let f = [
        assemble_elastic_load(&slave, &options)?,
        assemble_elastic_load(&master, &options)?,
    ];
    let t_assembly = t1.elapsed().as_secs_f64();
    let t2 = Instant::now();
    let on = |f: &BoundaryFace| near(f.centroid.y, 1.0);
    let tie = Tie::new(
        &slave.mesh,
        &master.mesh,
        slave.mesh.boundary_surface(on)?,
        master.mesh.boundary_surface(on)?,
        &CouplingOptions::default().dual(),
    )?;
    let gap = NormalGap::new(&tie, 3, slave.mesh.node_count(), master.mesh.node_count())?;
    let t_coupling = t2.elapsed().as_secs_f64();
    let dir = [slave.dirichlet_dofs(), master.dirichlet_dofs()];
    let law = ContactComplementarity::try_new(automatic_complementarity(&k[0], &tie, &gap, 3))?;
    let linear = match petsc {
        Some(p) => LinearSolve::on(
            p as &dyn SparseSolver,
            [slave.mesh.coords(), master.mesh.coords()],
        ),
        None => LinearSolve::default(),
    };
    let sol = solve_contact_on(
        [&k[0], &k[1]],
        [&f[0], &f[1]],
        [(&dir[0].0, &dir[0].1), (&dir[1].0, &dir[1].1)],
        &gap,
        &law,
        &ContactOptions::default(),
        linear,
    )?;
    let reports = petsc.map(PetscBackend::reports).unwrap_or_default();
    let worst = sol
        .pressure
        .iter()
        .map(|p| (p - 50e6).abs() / 50e6)
        .fold(0.0f64, f64::max);
    Ok(json!({
        "case": "blocks3d", "n": n,
        "unknowns": k[0].rows() + k[1].rows(),
        "slave_interface_nodes": sol.pressure.len(),
        "seconds": {"meshes": t_mesh, "assembly": t_assembly, "coupling": t_coupling,
                    "total": t0.elapsed().as_secs_f64()},
        "newton": newton_record(&sol),
        "pressure_error": worst,
        "backend": if petsc.is_some() { "petsc" } else { "direct" },
        "krylov_iterations": reports.iter().map(|r| r.iterations).collect::<Vec<_>>(),
        "krylov_setup_seconds": reports.iter().map(|r| r.setup_seconds).collect::<Vec<_>>(),
        "krylov_solve_seconds": reports.iter().map(|r| r.solve_seconds).collect::<Vec<_>>(),
        "krylov_methods": reports.first().map(|r| format!("{}+{}{}", r.ksp_type, r.pc_type,
            if r.near_null_space { " (rigid body modes)" } else { "" })),
        "peak_memory_bytes": peak_memory(),
    }))
}

fn hertz2d(n: usize) -> Res<Value> {
    let t0 = Instant::now();
    let scene = HertzScene::new(n);
    let p = scene.build()?;
    let t_build = t0.elapsed().as_secs_f64();
    let sol = solve_contact(
        [&p.stiffness[0], &p.stiffness[1]],
        [&p.load[0], &p.load[1]],
        [
            (&p.dirichlet[0].0, &p.dirichlet[0].1),
            (&p.dirichlet[1].0, &p.dirichlet[1].1),
        ],
        &p.gap,
        &p.law,
        &scene.contact,
    )?;
    Ok(json!({
        "case": "hertz2d", "n": n,
        "unknowns": p.stiffness[0].rows() + p.stiffness[1].rows(),
        "slave_interface_nodes": sol.pressure.len(),
        "seconds": {"build": t_build, "total": t0.elapsed().as_secs_f64()},
        "backend": "direct",
        "newton": newton_record(&sol),
        "peak_memory_bytes": peak_memory(),
    }))
}

fn main() -> Res<()> {
    let args = Args::parse();
    if let Some(s) = &args.single {
        let n: usize = s[1].parse()?;
        let record = match s[0].as_str() {
            "blocks3d" => blocks3d(n, None)?,
            "blocks3d_petsc" => {
                let rtol = mortar_scenes::linear_solver::DEFAULT_LINEAR_TOLERANCE;
                blocks3d(n, Some(&PetscBackend::automatic(rtol, "")))?
            }
            "hertz2d" => hertz2d(n)?,
            c => return Err(format!("unknown case {c:?}").into()),
        };
        println!("{record}");
        return Ok(());
    }
    let sizes: Vec<(&str, Vec<usize>)> = if args.quick {
        vec![
            ("blocks3d", vec![6, 12]),
            ("blocks3d_petsc", vec![6, 12]),
            ("hertz2d", vec![48, 96]),
        ]
    } else {
        vec![
            ("blocks3d", vec![12, 20, 30]),
            ("blocks3d_petsc", vec![12, 20, 30, 46, 66]),
            ("hertz2d", vec![96, 192, 384, 640]),
        ]
    };
    let exe = std::env::current_exe()?;
    let mut records = Vec::new();
    for (case, ns) in &sizes {
        for &n in ns {
            eprint!("{case} n={n} ... ");
            let out = Command::new(&exe)
                .args(["--single", case, &n.to_string()])
                .output()?;
            let line = String::from_utf8_lossy(&out.stdout);
            match line.lines().last().map(serde_json::from_str::<Value>) {
                Some(Ok(r)) if out.status.success() => {
                    eprintln!(
                        "{:.2} s",
                        r["seconds"]["total"].as_f64().unwrap_or(f64::NAN)
                    );
                    records.push(r);
                }
                _ => eprintln!(
                    "failed ({}): {}",
                    out.status,
                    String::from_utf8_lossy(&out.stderr).trim()
                ),
            }
        }
    }
    println!(
        "{:<9} {:>5} {:>9} {:>7} {:>8} {:>8} {:>9} {:>7} {:>9}",
        "case", "n", "unknowns", "active", "setup s", "newton s", "lin s", "steps", "peak MB"
    );
    for r in &records {
        let s = &r["seconds"];
        let setup = s["total"].as_f64().unwrap_or(0.0)
            - r["newton"]["newton_seconds"].as_f64().unwrap_or(0.0);
        let lin: f64 = r["newton"]["linear_solve_seconds"]
            .as_array()
            .map_or(0.0, |v| v.iter().filter_map(Value::as_f64).sum());
        println!(
            "{:<9} {:>5} {:>9} {:>7} {:>8.2} {:>8.2} {:>9.2} {:>7} {:>9.0}",
            r["case"].as_str().unwrap_or("?"),
            r["n"],
            r["unknowns"],
            r["newton"]["active"],
            setup,
            r["newton"]["newton_seconds"].as_f64().unwrap_or(f64::NAN),
            lin,
            r["newton"]["newton_steps"],
            r["peak_memory_bytes"].as_f64().unwrap_or(0.0) / 1e6,
        );
    }
    println!("setup: meshes, assembly, coupling; lin: the Newton steps' linear solves");
    if let Some(path) = &args.json {
        std::fs::write(path, serde_json::to_string_pretty(&records)? + "\n")?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
