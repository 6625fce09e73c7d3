//! Heat conduction in two bodies meshed independently (2:3 size ratio) and tied by mortar,
//! with a manufactured solution: refinement study, patch test, the two solution paths, VTU
//! files for ParaView and a PNG plot of the errors against h.
//!
//! ```text
//! cargo run --release --example tied_heat -- --dim 2 --json tied_heat_2d.json --vtu out/
//! cargo run --release --example tied_heat -- --dim 3 --json tied_heat_3d.json --vtu out/
//! cargo run --release --example tied_heat -- --dim 2 --quick          # a smoke run (seconds)
//! ```
//!
//! Scenes (see `mortar_scenes::tied_heat`): the unit square (cube) cut at x = 0.5 into a left
//! body of Quad4 (Hex8) cells, n per unit length, and a right body of Tri3 (Tet4) cells, 3n/2
//! per unit length; and a curved variant, a disc (ball) of radius 0.3 inside the rest of the
//! square (cube), both O-grids with the same 2:3 ratio. Exact solution
//! u = sin(pi x) sin(pi y) (sin(pi z)), with the matching source and Dirichlet data on the
//! outer boundary. Dual multipliers (or `--multipliers standard|linear`), segment-based
//! integration; the toolkit condenses the
//! slave unknowns (SPD, Cholesky) when D is diagonal and says so. On the curved 3D interface
//! the faces are warped quads, on which the core's D is diagonal only up to O(h^2), so the
//! toolkit keeps the saddle point there, and says why.
//!
//! The JSON report: the straight scene's `levels` (`n`, `h`, `dofs`, `l2`, `h1`,
//! `max_nodal`, `flux`, `seconds`), `l2_rate`, `h1_rate` and `flux_rate` over the last two
//! levels, `formulation` and its reason, `patch_test_error` (a linear field, max nodal error,
//! both paths, and element-based integration for comparison), `paths` (the finest level
//! solved condensed, as a saddle point with the same dual multipliers, and as a saddle point
//! with standard multipliers: timings and differences), and `curved` (its levels and rates).

#[path = "tied_heat/plot.rs"]
mod plot;

use std::path::PathBuf;

use clap::Parser;
use mortar::generate::SecondOrder;
use mortar::io::vtu::{write_vtu, VtuPiece};
use mortar::physics::tied::{FormulationChoice, TiedOptions};
use mortar::CouplingOptions;
use mortar_scenes::tied_heat::{rate, Exact, Geometry, TiedHeatRun, TiedHeatScene};
use serde_json::{json, Value};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// Tied heat conduction: refinement study, patch test, VTU and PNG output.
#[derive(Parser, Debug)]
#[command(about = "Tied heat conduction: refinement study, patch test, VTU and PNG output")]
pub struct Args {
    /// Spatial dimension, 2 or 3.
    #[arg(long, default_value_t = 2)]
    dim: usize,
    /// Write the JSON report here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write VTU files of the finest levels into this directory.
    #[arg(long)]
    vtu: Option<PathBuf>,
    /// Write the error plot here (default: the JSON path with extension .png).
    #[arg(long)]
    png: Option<PathBuf>,
    /// The refinement levels: n, cells per unit length of the coarse body (multiples of 4).
    #[arg(long, value_delimiter = ',')]
    levels: Option<Vec<usize>>,
    /// A small smoke run.
    #[arg(long)]
    quick: bool,
    /// Skip the curved-interface scene.
    #[arg(long)]
    skip_curved: bool,
    /// Element order: 1 (Quad4/Tri3, Hex8/Tet4) or 2 (Quad9/Tri6, Hex27/Tet10; the curved
    /// interface's new nodes on its circle or sphere).
    #[arg(long, default_value_t = 1)]
    order: u32,
    /// With --order 2: the serendipity cells (Quad8, Hex20) instead of Quad9, Hex27.
    #[arg(long)]
    serendipity: bool,
    /// The multipliers of the refinement studies: dual, standard, or linear (on the corner
    /// nodes of second-order faces).
    #[arg(long, default_value = "dual")]
    multipliers: String,
}

fn main() -> Res<()> {
    run(Args::parse())
}

/// Runs the example with the command line `args` (tests run it with a small one).
pub fn run(args: Args) -> Res<()> {
    let dim = args.dim;
    if dim != 2 && dim != 3 {
        return Err(format!("--dim {dim}: 2 or 3").into());
    }
    let levels = args
        .levels
        .clone()
        .unwrap_or_else(|| match (dim, args.quick) {
            (2, false) => vec![8, 16, 32, 64, 128, 256],
            (2, true) => vec![8, 16, 32],
            (_, false) => vec![4, 8, 16, 32],
            (_, true) => vec![4, 8, 12],
        });
    if levels.len() < 2 {
        return Err("give at least two levels".into());
    }
    let order = match (args.order, args.serendipity) {
        (1, false) => None,
        (2, false) => Some(SecondOrder::Complete),
        (2, true) => Some(SecondOrder::Serendipity),
        (o, s) => {
            return Err(format!(
                "--order {o}{}: 1 or 2 (serendipity with 2)",
                if s { " --serendipity" } else { "" }
            )
            .into())
        }
    };
    let coupling = match args.multipliers.as_str() {
        "dual" => CouplingOptions::default().dual(),
        "standard" => CouplingOptions::default(),
        "linear" => CouplingOptions::default().linear(),
        m => return Err(format!("--multipliers {m}: dual, standard or linear").into()),
    };
    let scene = |geometry, n| {
        let mut s = TiedHeatScene::new(dim, geometry, n);
        s.order = order;
        s.coupling = coupling.clone();
        s
    };

    // 1. The patch test: a linear field on the straight interface, both paths, and
    //    element-based integration for comparison.
    let linear = Exact::Linear {
        a: 0.3,
        b: [1.0, -2.0, 0.5],
    };
    let patch = |tied: TiedOptions, coupling: CouplingOptions| -> Res<TiedHeatRun> {
        let mut s = scene(Geometry::Straight, 8);
        s.exact = linear;
        s.tied = tied;
        s.coupling = coupling;
        Ok(s.run()?)
    };
    let p_cond = patch(TiedOptions::default(), CouplingOptions::default().dual())?;
    let p_saddle = patch(
        TiedOptions::default().with_formulation(FormulationChoice::SaddlePoint),
        CouplingOptions::default().dual(),
    )?;
    let p_standard = patch(TiedOptions::default(), CouplingOptions::default())?;
    let p_element = patch(
        TiedOptions::default(),
        CouplingOptions::default().dual().element_based(None)?,
    )?;
    println!(
        "patch test (u = a + b.x, n = 8): max nodal error {:.2e} condensed, {:.2e} saddle \
         point, {:.2e} standard multipliers, {:.2e} element-based integration",
        p_cond.max_nodal, p_saddle.max_nodal, p_standard.max_nodal, p_element.max_nodal
    );

    // 2. The refinement studies.
    let straight = study(&levels, &|n| scene(Geometry::Straight, n))?;
    let finest = straight.last().expect("two levels or more");

    // 3. The finest straight level solved by the other paths.
    let n = *levels.last().expect("levels");
    let mut saddle_scene = scene(Geometry::Straight, n);
    saddle_scene.tied = TiedOptions::default().with_formulation(FormulationChoice::SaddlePoint);
    let saddle = saddle_scene.run()?;
    let mut standard_scene = scene(Geometry::Straight, n);
    standard_scene.coupling = CouplingOptions::default();
    let standard = standard_scene.run()?;
    let max_diff = |a: &TiedHeatRun, b: &TiedHeatRun| -> f64 {
        (0..2)
            .flat_map(|k| {
                a.solution.temperatures[k]
                    .iter()
                    .zip(&b.solution.temperatures[k])
                    .map(|(x, y)| (x - y).abs())
            })
            .fold(0.0, f64::max)
    };
    let flux_diff = finest
        .solution
        .flux
        .iter()
        .zip(&saddle.solution.flux)
        .filter(|(a, _)| a.is_finite())
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let path_json = |r: &TiedHeatRun| {
        let s = r.solution.seconds;
        json!({
            "formulation": r.solution.formulation.formulation.describe(),
            "reason": r.solution.formulation.reason,
            "unknowns": r.solution.formulation.unknowns,
            "nonzeros": r.solution.formulation.nonzeros,
            "seconds_system": s.system,
            "seconds_factorisation": s.factorisation,
            "seconds_solve": s.solve,
            "seconds_linear_algebra": s.linear_algebra(),
            "seconds_total": r.seconds,
            "l2": r.l2,
            "h1": r.h1,
        })
    };
    println!(
        "finest straight level n = {n}: condensed {:.3} s ({} unknowns), saddle point {:.3} s \
         ({} unknowns), standard saddle point {:.3} s; max |T_condensed - T_saddle| = {:.2e}, \
         max |lambda difference| = {:.2e}",
        finest.solution.seconds.linear_algebra(),
        finest.solution.formulation.unknowns,
        saddle.solution.seconds.linear_algebra(),
        saddle.solution.formulation.unknowns,
        standard.solution.seconds.linear_algebra(),
        max_diff(finest, &saddle),
        flux_diff,
    );

    let curved = if args.skip_curved {
        Vec::new()
    } else {
        study(&levels, &|n| scene(Geometry::Curved, n))?
    };

    // 4. The report.
    let (l2_rate, h1_rate, flux_rate) = rates(&straight);
    let mut report = json!({
        "dim": dim,
        "order": args.order,
        "second_order_family": format!("{order:?}"),
        "scene": "straight interface at x = 0.5, left Quad4/Hex8 (n per unit length), right Tri3/Tet4 (3n/2), u = prod sin(pi x_d)",
        "levels": levels_json(&straight),
        "l2_rate": l2_rate,
        "h1_rate": h1_rate,
        "flux_rate": flux_rate,
        "h1_norm": "H1 seminorm of the error",
        "flux_norm": "sqrt(sum_j d_j (lambda_j - lambda(x_j))^2), d_j the row sums of D, lambda = -k grad u . n_s",
        "formulation": finest.solution.formulation.formulation.describe(),
        "formulation_reason": finest.solution.formulation.reason,
        "multipliers": format!("{}, segment-based integration", coupling.multipliers.name()),
        "redistributed_dirichlet_slave_nodes": finest.solution.formulation.redistributed,
        "patch_test_error": p_cond.max_nodal,
        "patch_test": {
            "field": "u = 0.3 + x - 2 y (+ 0.5 z), n = 8",
            "condensed": p_cond.max_nodal,
            "saddle_point": p_saddle.max_nodal,
            "standard_multipliers": p_standard.max_nodal,
            "element_based_integration": p_element.max_nodal,
            "flux_error_condensed": p_cond.flux_error,
        },
        "paths": {
            "n": n,
            "condensed": path_json(finest),
            "saddle_point": path_json(&saddle),
            "saddle_point_standard_multipliers": path_json(&standard),
            "max_temperature_difference_condensed_vs_saddle": max_diff(finest, &saddle),
            "max_flux_difference_condensed_vs_saddle": flux_diff,
        },
    });
    if !curved.is_empty() {
        let (l2c, h1c, fc) = rates(&curved);
        let last = curved.last().expect("levels");
        report["curved"] = json!({
            "scene": "inclusion of radius 0.3 at the centre (master, O-grid, n/2 cells per block side) in the rest of the box (slave, 3n/4), u = prod sin(pi x_d)",
            "levels": levels_json(&curved),
            "l2_rate": l2c,
            "h1_rate": h1c,
            "flux_rate": fc,
            "formulation": last.solution.formulation.formulation.describe(),
            "formulation_reason": last.solution.formulation.reason,
        });
    }
    let text = serde_json::to_string_pretty(&report)?;
    if let Some(path) = &args.json {
        std::fs::write(path, &text)?;
        println!("wrote {}", path.display());
    }
    println!(
        "straight: L2 rate {l2_rate:.3}, H1 rate {h1_rate:.3}, flux rate {flux_rate:.3}; {}",
        finest.solution.formulation
    );
    if let Some(c) = report.get("curved") {
        println!(
            "curved: L2 rate {:.3}, H1 rate {:.3}, flux rate {:.3}",
            c["l2_rate"].as_f64().unwrap_or(f64::NAN),
            c["h1_rate"].as_f64().unwrap_or(f64::NAN),
            c["flux_rate"].as_f64().unwrap_or(f64::NAN)
        );
    }

    // 5. VTU of the finest levels, and the plot.
    if let Some(dir) = &args.vtu {
        std::fs::create_dir_all(dir)?;
        for (name, runs) in [("straight", &straight), ("curved", &curved)] {
            if let Some(r) = runs.last() {
                let path = dir.join(format!("tied_heat_{dim}d_{name}.vtu"));
                write_run_vtu(&path, dim, r)?;
                println!("wrote {}", path.display());
            }
        }
    }
    let png = args
        .png
        .clone()
        .or_else(|| args.json.as_ref().map(|j| j.with_extension("png")));
    if let Some(png) = png {
        let mut series = vec![
            plot::Series {
                name: "L2, straight".into(),
                points: straight.iter().map(|r| (r.h, r.l2)).collect(),
            },
            plot::Series {
                name: "H1 seminorm, straight".into(),
                points: straight.iter().map(|r| (r.h, r.h1)).collect(),
            },
        ];
        if !curved.is_empty() {
            series.push(plot::Series {
                name: "L2, curved".into(),
                points: curved.iter().map(|r| (r.h, r.l2)).collect(),
            });
            series.push(plot::Series {
                name: "H1 seminorm, curved".into(),
                points: curved.iter().map(|r| (r.h, r.h1)).collect(),
            });
        }
        plot::draw(
            &png,
            &format!(
                "Tied heat conduction, {dim}D: error against h ({} mortar, 2:3 meshes)",
                coupling.multipliers.name()
            ),
            &series,
        )?;
        println!("wrote {}", png.display());
    }
    // The example's own checks (after the report is printed, so that a failure keeps it):
    // the patch test to rounding on every exact path, and the straight study's rates those
    // of the element order (`p + 1` in L2, `p` in H1; 0.2 of slack for the coarse levels).
    let patch_worst = p_cond
        .max_nodal
        .max(p_saddle.max_nodal)
        .max(p_standard.max_nodal);
    if patch_worst > 1e-12 {
        return Err(format!("patch test: max nodal error {patch_worst:e} above 1e-12").into());
    }
    let p = f64::from(args.order);
    if l2_rate < p + 0.8 || h1_rate < p - 0.2 {
        return Err(format!(
            "straight study: L2 rate {l2_rate:.3}, H1 rate {h1_rate:.3}, expected about {} and {p}",
            p + 1.0
        )
        .into());
    }
    Ok(())
}

/// Runs the levels of a scene (`scene(n)`) and prints a table.
fn study(levels: &[usize], scene: &dyn Fn(usize) -> TiedHeatScene) -> Res<Vec<TiedHeatRun>> {
    let first = scene(levels[0]);
    println!(
        "\n{:?} interface, {}D, {:?}, {} multipliers",
        first.geometry,
        first.dim,
        first.order,
        first.coupling.multipliers.name()
    );
    println!(
        "{:>5} {:>9} {:>9} {:>11} {:>11} {:>11} {:>9}",
        "n", "h", "dofs", "L2", "H1", "flux", "seconds"
    );
    let mut runs: Vec<TiedHeatRun> = Vec::new();
    for &n in levels {
        let r = scene(n).run()?;
        let rates = runs
            .last()
            .map(|p| {
                format!(
                    "  rates {:.2} {:.2}",
                    rate(p.h, p.l2, r.h, r.l2),
                    rate(p.h, p.h1, r.h, r.h1)
                )
            })
            .unwrap_or_default();
        println!(
            "{n:>5} {:>9.5} {:>9} {:>11.4e} {:>11.4e} {:>11.4e} {:>9.3}{rates}",
            r.h, r.dofs, r.l2, r.h1, r.flux_error, r.seconds
        );
        runs.push(r);
    }
    Ok(runs)
}

/// L2, H1 and flux rates over the last two levels.
fn rates(runs: &[TiedHeatRun]) -> (f64, f64, f64) {
    let (a, b) = (&runs[runs.len() - 2], &runs[runs.len() - 1]);
    (
        rate(a.h, a.l2, b.h, b.l2),
        rate(a.h, a.h1, b.h, b.h1),
        rate(a.h, a.flux_error, b.h, b.flux_error),
    )
}

fn levels_json(runs: &[TiedHeatRun]) -> Value {
    Value::Array(
        runs.iter()
            .map(|r| {
                json!({
                    "n": (1.0 / r.h).round() as usize,
                    "h": r.h,
                    "dofs": r.dofs,
                    "l2": r.l2,
                    "h1": r.h1,
                    "max_nodal": r.max_nodal,
                    "flux": r.flux_error,
                    "seconds": r.seconds,
                    "seconds_linear_algebra": r.solution.seconds.linear_algebra(),
                })
            })
            .collect(),
    )
}

/// The two bodies of a run as two pieces: temperature, exact solution and pointwise error.
fn write_run_vtu(path: &std::path::Path, dim: usize, r: &TiedHeatRun) -> Res<()> {
    let bodies = r.problem.bodies();
    let fields: Vec<(Vec<f64>, Vec<f64>)> = (0..2)
        .map(|b| {
            let exact: Vec<f64> = bodies[b]
                .mesh
                .coords()
                .iter()
                .map(|x| Exact::Sine.value(dim, x))
                .collect();
            let error = r.solution.temperatures[b]
                .iter()
                .zip(&exact)
                .map(|(t, e)| t - e)
                .collect();
            (exact, error)
        })
        .collect();
    let pieces: Vec<VtuPiece<'_>> = (0..2)
        .map(|b| VtuPiece {
            mesh: &bodies[b].mesh,
            point_data: vec![
                ("temperature", &r.solution.temperatures[b][..]),
                ("exact", &fields[b].0[..]),
                ("error", &fields[b].1[..]),
            ],
        })
        .collect();
    write_vtu(path, &pieces)?;
    Ok(())
}
