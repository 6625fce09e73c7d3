//! The 2D Hertz verification (plane strain): an elastic cylinder pressed onto an elastic
//! block, frictionless mortar contact, against the closed form of Johnson, *Contact
//! Mechanics* (1985), sec. 4.3 and 5.6, at three refinement levels.
//!
//! ```text
//! cargo run --release --example hertz2d                        # JSON on stdout
//! cargo run --release --example hertz2d -- --json hertz2d.json --n 24 --levels 3 --profile
//! ```
//!
//! The scene is `mortar_scenes::hertz` (its documentation has the model): the symmetric half,
//! a quarter disc (slave, `R = 1`, centre `(0, R)`) on the block `[0, 8R] x [-8R, 0]`
//! (master), both refined towards the contact point, `E = 200 GPa`, `nu = 0.3`; the disc's top
//! moved down by the approach `d` (free to slide), `u_x = 0` on `x = 0`, the block's bottom
//! held. Dual multipliers, segment-based integration, the exact complementarity law with
//! automatic `c`.
//!
//! Compared with the closed form at the computed load `P` (twice the half model's vertical
//! contact force, equal to the reaction at the block's bottom, which is checked):
//! the half-width `a` (estimate: the midpoint between the last node with positive pressure
//! and the next node, which bracket it; the bracket and a `p^2`-in-`x^2` extrapolation are
//! reported too), the peak `p0` (the pressure of the node
//! at `x = 0`) and the profile (the L2 error of the piecewise linear nodal pressure over the
//! contact zone, relative to `p0 sqrt(a)`). Each level doubles the cells of both bodies.
//!
//! The JSON report: `levels` (per level: `unknowns`, `slave_nodes`, `in_contact`, `a_h`,
//! `a_exact`, `contact_cell` (the slave element at `x = 0`), `edge_cell` (the one in which
//! `a` falls), `p0_h`, `p0_exact`, relative errors, `profile_l2`, `newton_steps`,
//! `settled_at`, `seconds`, the forces and reactions), `rates` (observed, against the contact
//! cell) and `targets` (peak within 2 %, half-width within one slave element at
//! the first level, the L2 error decreasing, at most 10 Newton steps per load step).

use std::path::PathBuf;

use clap::Parser;
use mortar::physics::elastic::ElasticMaterial;
use mortar_scenes::hertz::{HertzRun, HertzScene, DEFAULT_ARC_CELLS};
use mortar_scenes::tied_heat::rate;
use serde_json::{json, Value};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// 2D Hertz contact against the closed form, three refinement levels.
#[derive(Parser, Debug)]
#[command(about = "2D Hertz contact against the closed form, three refinement levels")]
pub struct Args {
    /// Write the JSON report here (default: stdout).
    #[arg(long)]
    json: Option<PathBuf>,
    /// Cells along the quarter disc's arc at the first level.
    #[arg(long)]
    n: Option<usize>,
    /// Refinement levels (each doubles the cells).
    #[arg(long, default_value_t = 3)]
    levels: usize,
    /// The approach d (m); default: the scene's, about a = 0.1 R.
    #[arg(long)]
    approach: Option<f64>,
    /// The cylinder's radius R (m).
    #[arg(long, default_value_t = 1.0)]
    radius: f64,
    /// Young's modulus of the cylinder and of the block (Pa).
    #[arg(long, default_value_t = 200e9)]
    youngs_modulus: f64,
    /// Poisson's ratio of both.
    #[arg(long, default_value_t = 0.3)]
    poisson_ratio: f64,
    /// The block's width and depth over R.
    #[arg(long)]
    block_size: Option<f64>,
    /// The quarter disc's grading (last arc cell over the first, about).
    #[arg(long)]
    grading: Option<f64>,
    /// The block's grading.
    #[arg(long)]
    block_grading: Option<f64>,
    /// The block's first cell over the disc's.
    #[arg(long)]
    block_cell_ratio: Option<f64>,
    /// Load steps of the contact solve.
    #[arg(long)]
    load_steps: Option<usize>,
    /// Standard multipliers instead of dual ones (D not diagonal: the Newton systems are
    /// solved as saddle points).
    #[arg(long)]
    standard: bool,
    /// Add each level's nodal pressures and the closed form's to the report.
    #[arg(long)]
    profile: bool,
}

fn main() -> Res<()> {
    run(Args::parse())
}

/// Runs the example with the command line `args` (tests run it with a small one).
pub fn run(args: Args) -> Res<()> {
    let n0 = args.n.unwrap_or(DEFAULT_ARC_CELLS);
    let mut base = HertzScene::new(n0);
    base.radius = args.radius;
    base.cylinder = ElasticMaterial::new(args.youngs_modulus, args.poisson_ratio);
    base.block = base.cylinder;
    if let Some(d) = args.approach {
        base.approach = d;
    } else {
        base.approach *= args.radius;
    }
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
    if args.standard {
        base.coupling = mortar::CouplingOptions::default();
    }
    if let Some(v) = args.load_steps {
        base.contact.load_steps = v.max(1);
    }

    let mut runs: Vec<HertzRun> = Vec::new();
    for level in 0..args.levels.max(1) {
        let mut scene = base.clone();
        scene.arc_cells = n0 << level;
        // The block's cells double too (nested meshes, also along the arc).
        scene.block_cells = Some(base.block_cell_count() << level);
        let run = scene.run()?;
        eprintln!(
            "n = {:4}: {:6} unknowns, {:3} of {:3} slave nodes in contact, h = {:.2e} R, \
             a_h/a = {:.4}, p0_h/p0 = {:.4}, L2 {:.3e}, Newton {:?}, {:.2} s",
            run.arc_cells,
            run.unknowns,
            run.active,
            run.slave_nodes,
            run.contact_cell / base.radius,
            run.half_width.estimate / run.a_exact,
            run.peak / run.p0_exact,
            run.profile_l2,
            run.steps.iter().map(|s| s.newton_steps).collect::<Vec<_>>(),
            run.seconds,
        );
        runs.push(run);
    }

    let first = &runs[0];
    let rates = |e: &dyn Fn(&HertzRun) -> f64| -> Vec<f64> {
        runs.windows(2)
            .map(|w| {
                rate(
                    w[0].contact_cell,
                    e(&w[0]).abs(),
                    w[1].contact_cell,
                    e(&w[1]).abs(),
                )
            })
            .collect()
    };
    let targets = json!({
        "peak_within_2_percent": first.peak_error().abs() <= 0.02,
        "half_width_within_one_slave_element": (first.half_width.estimate - first.a_exact).abs() <= first.contact_cell,
        "profile_l2_decreasing": runs.windows(2).all(|w| w[1].profile_l2 < w[0].profile_l2),
        "newton_steps_at_most_10": runs.iter().all(|r| r.steps.iter().all(|s| s.newton_steps <= 10)),
        "equilibrium_1e-8": runs.iter().all(|r| r.equilibrium_error() <= 1e-8),
    });
    let report = json!({
        "problem": "2D Hertz contact, plane strain: quarter disc (slave, radius R, centre (0, R), \
                    top moved by -d, free to slide; u_x = 0 on x = 0) on the block [0, W] x [-H, 0] \
                    (master; u_x = 0 on x = 0, u_y = 0 at y = -H), frictionless, dual multipliers, \
                    segment-based integration, exact complementarity with automatic c",
        "source": "K. L. Johnson, Contact Mechanics, Cambridge University Press, 1985, sec. 4.3 \
                   and 5.6: a = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi a), p = p0 sqrt(1 - x^2/a^2)",
        "radius": base.radius,
        "youngs_modulus": base.cylinder.youngs_modulus,
        "poisson_ratio": base.cylinder.poisson_ratio,
        "contact_modulus": base.closed_form().contact_modulus,
        "block_size": base.block_size * base.radius,
        "approach": base.approach,
        "grading": base.grading,
        "block_grading": base.block_grading,
        "load": "P = 2 x the vertical contact force of the half model (= the bottom reaction)",
        "a_estimator": "midpoint of the last node with positive pressure and the next node \
                        (zero pressure), which bracket the computed contact zone",
        "profile_l2_norm": "||p_h - p||_L2 / (p0 sqrt(a)) over the contact zone, p_h piecewise \
                            linear in the nodal pressures on the slave segments",
        "load_steps": base.contact.load_steps,
        "multipliers": if args.standard { "standard" } else { "dual" },
        "levels": runs.iter().map(|r| level_json(&base, r, args.profile)).collect::<Vec<Value>>(),
        "rates": {
            "against": "contact_cell",
            "profile_l2": rates(&|r| r.profile_l2),
            "p0": rates(&|r| r.peak_error()),
            "a": rates(&|r| r.half_width_error()),
        },
        "targets": targets,
    });
    let text = serde_json::to_string_pretty(&report)?;
    match &args.json {
        Some(path) => std::fs::write(path, text + "\n")?,
        None => println!("{text}"),
    }
    eprintln!(
        "Hertz 2D, a = {:.4} R: at n = {} the peak pressure is {:+.2} % off p0 and the \
         half-width {:+.2} % off a ({:.2} contact elements); the profile's L2 error goes {} \
         over {} levels; at most {} Newton steps per load step; equilibrium to {:.1e}.",
        first.a_exact / base.radius,
        first.arc_cells,
        100.0 * first.peak_error(),
        100.0 * first.half_width_error(),
        (first.half_width.estimate - first.a_exact) / first.contact_cell,
        runs.iter()
            .map(|r| format!("{:.2e}", r.profile_l2))
            .collect::<Vec<_>>()
            .join(" -> "),
        runs.len(),
        runs.iter()
            .flat_map(|r| r.steps.iter().map(|s| s.newton_steps))
            .max()
            .unwrap_or(0),
        runs.iter()
            .map(HertzRun::equilibrium_error)
            .fold(0.0, f64::max),
    );
    Ok(())
}

fn level_json(scene: &HertzScene, r: &HertzRun, profile: bool) -> Value {
    let mut v = json!({
        "arc_cells": r.arc_cells,
        "block_cells": r.block_cells,
        "unknowns": r.unknowns,
        "slave_nodes": r.slave_nodes,
        "in_contact": r.active,
        "contact_cell": r.contact_cell,
        "edge_cell": r.edge_cell,
        "load": r.load,
        "a_h": r.half_width.estimate,
        "a_exact": r.a_exact,
        "a_error": r.half_width_error(),
        "a_error_in_contact_cells": (r.half_width.estimate - r.a_exact) / r.contact_cell,
        "a_last_in_contact": r.half_width.last_in_contact,
        "a_first_open": r.half_width.first_open,
        "a_bracketed": r.half_width.brackets(r.a_exact),
        "a_squared_extrapolation": r.half_width.squared,
        "contact_contiguous": r.half_width.contiguous,
        "p0_h": r.peak,
        "p0_exact": r.p0_exact,
        "p0_error": r.peak_error(),
        "profile_l2": r.profile_l2,
        "newton_steps": r.steps.iter().map(|s| s.newton_steps).collect::<Vec<_>>(),
        "settled_at": r.steps.iter().map(|s| s.settled_at).collect::<Vec<_>>(),
        "residuals": r.steps.iter().map(|s| s.residuals.clone()).collect::<Vec<_>>(),
        "in_contact_per_step": r.steps.iter().map(|s| s.active).collect::<Vec<_>>(),
        "complementarity_c": r.complementarity,
        "force": r.force,
        "vertical_force": r.vertical_force(),
        "reaction_bottom": r.reaction_bottom,
        "reaction_top": r.reaction_top,
        "equilibrium_error": r.equilibrium_error(),
        "force_over_vertical_minus_1": r.force / r.vertical_force() - 1.0,
        "seconds": r.seconds,
    });
    if profile {
        let hertz = scene.closed_form();
        v["profile"] = json!({
            "x": r.profile.iter().map(|n| n.x).collect::<Vec<_>>(),
            "p_h": r.profile.iter().map(|n| n.pressure).collect::<Vec<_>>(),
            "p_exact": r.profile.iter().map(|n| hertz.pressure(r.load, n.x)).collect::<Vec<_>>(),
        });
    }
    v
}
