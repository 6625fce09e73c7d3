//! The 3D Hertz verification: an elastic sphere pressed onto an elastic block, frictionless
//! mortar contact, against the closed form of Johnson, *Contact Mechanics* (1985), sec. 4.2,
//! at one or more refinement levels.
//!
//! ```text
//! cargo run --release --example hertz3d                          # JSON on stdout
//! cargo run --release --example hertz3d -- --json hertz3d.json --n 10 --levels 2 --profile
//! ```
//!
//! The scene is `mortar_scenes::hertz::sphere` (its documentation has the model): the
//! symmetric quarter, the lower octant of a ball (slave, `R = 1`, centre `(0, 0, R)`, Hex8) on
//! the block `[0, 8R]^2 x [-8R, 0]` (master, Hex8), both refined towards the contact point,
//! `E = 200 GPa`, `nu = 0.3`; the sphere's equator moved down by the approach `d` (free to
//! slide), `u_x = 0` on `x = 0` and `u_y = 0` on `y = 0` for both, the block's bottom held.
//! Dual multipliers, segment-based integration, the exact complementarity law with automatic
//! `c`.
//!
//! Compared with the closed form twice: at the imposed approach `d` (`a = sqrt(R d)`,
//! `p0 = 2 E* a / (pi R)`, `P = 4 E* a^3 / (3 R)`; the finite bodies' own compliance enters)
//! and at the computed load `P` (four times the quarter model's vertical contact force, equal
//! to the reactions, which is checked; `a = (3 P R / (4 E*))^(1/3)`, `p0 = 3 P / (2 pi a^2)`).
//! The contact radius: the last slave node in contact and the next one by distance from the
//! axis bracket it (over all slave nodes, and along the symmetry line `y = 0`, where the
//! bracket is one element); the estimate is the bracket's midpoint. The peak: the pressure of
//! the node at the pole. Each level doubles the cells of both bodies (eight times the cells:
//! the default's second level, 28 cells, 2.8e5 unknowns, took 4.6 min and 5.4 GB here, five
//! Newton steps of about 54 s, each a new sparse Cholesky; the L2 profile error went from
//! 5.5e-2 to 2.4e-2 and the peak at `P` from 1.0 % to 0.6 %).
//!
//! The JSON report: the inputs, `levels` (per level: mesh sizes, `unknowns`, the computed and
//! closed-form values at `d` and at `P` with relative errors, the brackets, `profile_l2`,
//! `newton_steps`, `settled_at`, `seconds`, the forces and reactions) and `targets` (`p0`
//! within 3 % and `a` within one element at the first level, at most 10 Newton steps per load
//! step), each at `d` and at `P`.

use std::path::PathBuf;

use clap::Parser;
use mortar::physics::elastic::ElasticMaterial;
use mortar_scenes::hertz::{HertzSphereRun, HertzSphereScene, DEFAULT_SPHERE_CELLS};
use serde_json::{json, Value};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// 3D Hertz contact against the closed form.
#[derive(Parser, Debug)]
#[command(about = "3D Hertz contact against the closed form")]
pub struct Args {
    /// Write the JSON report here (default: stdout).
    #[arg(long)]
    json: Option<PathBuf>,
    /// The sphere octant's cells per direction at the first level.
    #[arg(long)]
    n: Option<usize>,
    /// Refinement levels (each doubles the cells per direction).
    #[arg(long, default_value_t = 1)]
    levels: usize,
    /// The approach d (m); default: the scene's, a = sqrt(R d) = 0.1 R.
    #[arg(long)]
    approach: Option<f64>,
    /// The sphere's radius R (m).
    #[arg(long, default_value_t = 1.0)]
    radius: f64,
    /// Young's modulus of the sphere and of the block (Pa).
    #[arg(long, default_value_t = 200e9)]
    youngs_modulus: f64,
    /// Poisson's ratio of both.
    #[arg(long, default_value_t = 0.3)]
    poisson_ratio: f64,
    /// The block's width and depth over R.
    #[arg(long)]
    block_size: Option<f64>,
    /// The sphere octant's grading.
    #[arg(long)]
    grading: Option<f64>,
    /// The block's grading.
    #[arg(long)]
    block_grading: Option<f64>,
    /// The block's first cell over the sphere's.
    #[arg(long)]
    block_cell_ratio: Option<f64>,
    /// The slave surface's extent from the axis over R.
    #[arg(long)]
    contact_zone: Option<f64>,
    /// Load steps of the contact solve.
    #[arg(long)]
    load_steps: Option<usize>,
    /// Add each level's nodal pressures and the closed form's to the report.
    #[arg(long)]
    profile: bool,
    /// Where the Newton systems go: `direct` (the sparse direct solves) or `petsc` (CG with
    /// GAMG told the bodies' rigid motions, relative tolerance 1e-12; a build with
    /// `--features mortar-petsc/petsc`).
    #[arg(long, default_value = "direct")]
    backend: String,
    /// Further PETSc options with `--backend petsc` (`-pc_gamg_threshold 0.02`).
    #[arg(long, default_value = "")]
    petsc_options: String,
}

fn main() -> Res<()> {
    run(Args::parse())
}

/// Runs the example with the command line `args` (tests run it with a small one).
pub fn run(args: Args) -> Res<()> {
    let n0 = args.n.unwrap_or(DEFAULT_SPHERE_CELLS);
    let mut base = HertzSphereScene::new(n0);
    base.radius = args.radius;
    base.sphere = ElasticMaterial::new(args.youngs_modulus, args.poisson_ratio);
    base.block = base.sphere;
    base.approach = args.approach.unwrap_or(base.approach * args.radius);
    if let Some(v) = args.block_size {
        base.block_size = v;
    }
    if let Some(v) = args.grading {
        base.grading = v;
    }
    if let Some(v) = args.block_grading {
        base.block_grading = v;
    }
    if let Some(v) = args.block_cell_ratio {
        base.block_cell_ratio = v;
    }
    if let Some(v) = args.contact_zone {
        base.contact_zone = v;
    }
    if let Some(v) = args.load_steps {
        base.contact.load_steps = v.max(1);
    }

    let petsc = mortar::petsc::PetscBackend::automatic(1e-12, args.petsc_options.clone());
    let backend: Option<&dyn mortar::fem::linalg::SparseSolver> = match args.backend.as_str() {
        "direct" => None,
        "petsc" => Some(&petsc),
        other => return Err(format!("--backend {other:?}: direct or petsc").into()),
    };
    let mut runs: Vec<HertzSphereRun> = Vec::new();
    for level in 0..args.levels.max(1) {
        let mut scene = base.clone();
        scene.cells = n0 << level;
        // The block's cells double too (nested meshes).
        scene.block_cells = Some(base.block_cell_count() << level);
        let run = scene.run_on(backend)?;
        eprintln!(
            "n = {:3}: {:7} unknowns, {:3} of {:3} slave nodes in contact, h = {:.2e} R; \
             at d: a_h/a = {:.4}, p0_h/p0 = {:.4}, P_h/P = {:.4}; at P: a_h/a = {:.4}, \
             p0_h/p0 = {:.4}, L2 {:.2e}; Newton {:?} (settled after {:?}), {:.1} s",
            run.cells,
            run.unknowns,
            run.active,
            run.slave_nodes,
            run.contact_cell / base.radius,
            run.contact_radius.estimate / run.at_approach.radius,
            run.peak / run.at_approach.peak,
            run.load / run.at_approach.load,
            run.contact_radius.estimate / run.at_load.radius,
            run.peak / run.at_load.peak,
            run.profile_l2,
            run.steps.iter().map(|s| s.newton_steps).collect::<Vec<_>>(),
            run.steps.iter().map(|s| s.settled_at).collect::<Vec<_>>(),
            run.seconds,
        );
        runs.push(run);
    }

    let first = &runs[0];
    let within_element = |a: f64| (first.contact_radius.estimate - a).abs() <= first.edge_cell;
    let targets = json!({
        "peak_within_3_percent_at_d": first.peak_error_at_approach().abs() <= 0.03,
        "peak_within_3_percent_at_P": first.peak_error_at_load().abs() <= 0.03,
        "radius_within_one_element_at_d": within_element(first.at_approach.radius),
        "radius_within_one_element_at_P": within_element(first.at_load.radius),
        "radius_bracketed_at_d": first.contact_radius.brackets(first.at_approach.radius),
        "radius_bracketed_at_P": first.contact_radius.brackets(first.at_load.radius),
        "newton_steps_at_most_10": runs.iter().all(|r| r.max_newton_steps() <= 10),
        "equilibrium_1e-8": runs.iter().all(|r| r.equilibrium_error() <= 1e-8),
    });
    let report = json!({
        "problem": "3D Hertz contact: the lower octant of a ball (slave, radius R, centre \
                    (0, 0, R), equator moved by -d, free to slide) on the block [0, W]^2 x \
                    [-H, 0] (master; u_z = 0 at z = -H); u_x = 0 on x = 0, u_y = 0 on y = 0 for \
                    both; Hex8, frictionless, dual multipliers, segment-based integration, \
                    exact complementarity with automatic c",
        "source": "K. L. Johnson, Contact Mechanics, Cambridge University Press, 1985, sec. 4.2: \
                   a = sqrt(R d), p0 = 2 E* a / (pi R), P = 4 E* a^3 / (3 R), \
                   p = p0 sqrt(1 - r^2/a^2)",
        "radius": base.radius,
        "youngs_modulus": base.sphere.youngs_modulus,
        "poisson_ratio": base.sphere.poisson_ratio,
        "contact_modulus": base.closed_form().contact_modulus,
        "block_size": base.block_size * base.radius,
        "approach": base.approach,
        "grading": base.grading,
        "block_grading": base.block_grading,
        "contact_zone": base.contact_zone * base.radius,
        "load": "P = 4 x the vertical contact force of the quarter model (= the bottom reaction)",
        "a_estimator": "midpoint of the last slave node with positive pressure and the next \
                        node by distance from the axis, which bracket the computed contact zone",
        "load_steps": base.contact.load_steps,
        "levels": runs.iter().map(|r| level_json(r, args.profile)).collect::<Vec<Value>>(),
        "targets": targets,
        "backend": args.backend,
        "krylov_iterations": petsc.reports().iter().map(|r| r.iterations).collect::<Vec<_>>(),
        "peak_memory_bytes": peak_memory(),
    });
    let text = serde_json::to_string_pretty(&report)?;
    match &args.json {
        Some(path) => std::fs::write(path, text + "\n")?,
        None => println!("{text}"),
    }
    eprintln!(
        "Hertz 3D, d = {:.3e} R (a = {:.4} R by the closed form): at n = {} the peak pressure \
         is {:+.2} % off p0 at d and {:+.2} % at the computed P ({:+.2} % off the closed \
         form's load at d); the contact radius is {:+.2} % off a at d ({:.2} elements) and \
         {:+.2} % at P, the last slave node in contact and the next at {:.4} and {:.4} R \
         (bracketing a at d: {}, at P: {}); at most {} Newton steps per load step; \
         equilibrium to {:.1e}.",
        base.approach / base.radius,
        first.at_approach.radius / base.radius,
        first.cells,
        100.0 * first.peak_error_at_approach(),
        100.0 * first.peak_error_at_load(),
        100.0 * first.load_error_at_approach(),
        100.0 * first.radius_error_at_approach(),
        (first.contact_radius.estimate - first.at_approach.radius) / first.edge_cell,
        100.0 * first.radius_error_at_load(),
        first.contact_radius.last_in_contact / base.radius,
        first.contact_radius.first_open / base.radius,
        first.contact_radius.brackets(first.at_approach.radius),
        first.contact_radius.brackets(first.at_load.radius),
        runs.iter()
            .map(HertzSphereRun::max_newton_steps)
            .max()
            .unwrap_or(0),
        runs.iter()
            .map(HertzSphereRun::equilibrium_error)
            .fold(0.0, f64::max),
    );
    Ok(())
}

fn closed_json(c: &mortar_scenes::hertz::HertzContact) -> Value {
    json!({ "a": c.radius, "p0": c.peak, "P": c.load, "d": c.approach })
}

/// The process's resident high-water mark (bytes), from /proc/self/status (Linux).
fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    Some(line.split_whitespace().nth(1)?.parse::<u64>().ok()? * 1024)
}

fn level_json(r: &HertzSphereRun, profile: bool) -> Value {
    let bracket = |h: &mortar_scenes::hertz::HalfWidth| {
        json!({
            "estimate": h.estimate,
            "last_in_contact": h.last_in_contact,
            "first_open": h.first_open,
            "squared_extrapolation": h.squared,
            "contiguous": h.contiguous,
        })
    };
    let mut v = json!({
        "cells": r.cells,
        "block_cells": r.block_cells,
        "sphere_nodes": r.sphere_nodes,
        "block_nodes": r.block_nodes,
        "unknowns": r.unknowns,
        "slave_nodes": r.slave_nodes,
        "in_contact": r.active,
        "contact_cell": r.contact_cell,
        "edge_cell": r.edge_cell,
        "load": r.load,
        "a_h": bracket(&r.contact_radius),
        "a_h_along_y0": bracket(&r.contact_radius_axis),
        "p0_h": r.peak,
        "at_d": closed_json(&r.at_approach),
        "at_P": closed_json(&r.at_load),
        "errors_at_d": {
            "p0": r.peak_error_at_approach(),
            "a": r.radius_error_at_approach(),
            "a_in_elements": (r.contact_radius.estimate - r.at_approach.radius) / r.edge_cell,
            "a_bracketed": r.contact_radius.brackets(r.at_approach.radius),
            "P": r.load_error_at_approach(),
        },
        "errors_at_P": {
            "p0": r.peak_error_at_load(),
            "a": r.radius_error_at_load(),
            "a_in_elements": (r.contact_radius.estimate - r.at_load.radius) / r.edge_cell_at_load,
            "a_bracketed": r.contact_radius.brackets(r.at_load.radius),
            "profile_l2": r.profile_l2,
        },
        "newton_steps": r.steps.iter().map(|s| s.newton_steps).collect::<Vec<_>>(),
        "settled_at": r.steps.iter().map(|s| s.settled_at).collect::<Vec<_>>(),
        "residuals": r.steps.iter().map(|s| s.residuals.clone()).collect::<Vec<_>>(),
        "in_contact_per_step": r.steps.iter().map(|s| s.active).collect::<Vec<_>>(),
        "linear_seconds": r.steps.iter().map(|s| s.linear_seconds.clone()).collect::<Vec<_>>(),
        "complementarity_c": r.complementarity,
        "force": r.force,
        "vertical_force": r.vertical_force(),
        "reaction_bottom": r.reaction_bottom,
        "reaction_top": r.reaction_top,
        "equilibrium_error": r.equilibrium_error(),
        "force_over_vertical_minus_1": r.force / r.vertical_force() - 1.0,
        "seconds": { "build": r.seconds_build, "total": r.seconds },
    });
    if profile {
        v["profile"] = json!({
            "x": r.profile.iter().map(|n| n.position[0]).collect::<Vec<_>>(),
            "y": r.profile.iter().map(|n| n.position[1]).collect::<Vec<_>>(),
            "r": r.profile.iter().map(|n| n.r).collect::<Vec<_>>(),
            "p_h": r.profile.iter().map(|n| n.pressure).collect::<Vec<_>>(),
            "p_at_P": r.profile.iter().map(|n| r.at_load.pressure(n.r)).collect::<Vec<_>>(),
            "p_at_d": r.profile.iter().map(|n| r.at_approach.pressure(n.r)).collect::<Vec<_>>(),
        });
    }
    v
}
