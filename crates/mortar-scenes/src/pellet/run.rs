//! Running the pellet scene: meshes, problem, time loop, outputs.

use std::path::Path;
use std::time::Instant;

use mortar_core::{CouplingOptions, SearchRadius, Tolerances};
use mortar_fem::mesh::VolumeMesh;
use mortar_physics::heat::{
    Conductivity, GapHeat, GapSolver, GapSolverState, HeatBody, HeatMaterial,
};
use serde_json::{json, Value};

use super::{annulus_mesh, pellet_mesh, PelletError, PelletScene, SolverMethod};
use mortar::io::vtu::{vtu_string, VtuPiece};
use mortar::io::{remove_stale_outputs, write_outputs};

/// Parses the scene file `text` (see the [module documentation](super)) and runs it,
/// writing VTU snapshots and `report.json` into `out` (created if needed). Shows a progress
/// bar on stderr when `progress` is true and stderr is a terminal.
///
/// Returns the report (what was written to `out/report.json`).
///
/// # Errors
/// [`PelletError::Parse`] / [`PelletError::Invalid`] for a bad file, and the errors of
/// [`run`].
pub fn run_from_toml(text: &str, out: &Path, progress: bool) -> Result<Value, PelletError> {
    run(&PelletScene::from_toml(text)?, out, progress)
}

/// [`run_from_toml`] of a scene file in the folder `base` (a relative `[mesh] file` is
/// there), with the laws its `[laws]` tables name made by `laws` (the shipped laws and a
/// program's own; see [`run_with_registry`](super::run_with_registry)).
///
/// # Errors
/// As [`run_from_toml`]; [`PelletError::Law`] for a law `laws` cannot make.
pub fn run_from_toml_with(
    text: &str,
    base: &Path,
    out: &Path,
    progress: bool,
    laws: &mortar_physics::laws::LawRegistry,
) -> Result<Value, PelletError> {
    run_with_laws(&PelletScene::from_toml_in(text, base)?, laws, out, progress)
}

/// Runs `scene` (thermomechanical, or thermal only with `[model] mechanics = false`) with the
/// laws its `[laws]` tables name made by `laws`, writing into `out` (as [`run`]).
///
/// # Errors
/// As [`run_from_toml_with`].
pub fn run_with_laws(
    scene: &PelletScene,
    laws: &mortar_physics::laws::LawRegistry,
    out: &Path,
    progress: bool,
) -> Result<Value, PelletError> {
    if scene.model.mechanics {
        super::run_coupled_in(scene, laws, out, progress)
    } else {
        run_thermal(scene, out, progress)
    }
}

/// Runs the built-in scene (the defaults of [`PelletScene`]), as [`run_from_toml`].
///
/// # Errors
/// As [`run`].
pub fn run_builtin(out: &Path, progress: bool) -> Result<Value, PelletError> {
    run(&PelletScene::default(), out, progress)
}

/// The area of a 2D mesh (shoelace formula per cell; Gmsh node order is cyclic for Tri3 and
/// Quad4).
pub(super) fn mesh_area(mesh: &VolumeMesh) -> f64 {
    (0..mesh.cell_count())
        .map(|c| {
            let nodes = mesh.cell(c).nodes;
            let x = mesh.coords();
            let mut a = 0.0;
            for i in 0..nodes.len() {
                let (p, q) = (
                    x[nodes[i] as usize],
                    x[nodes[(i + 1) % nodes.len()] as usize],
                );
                a += p.x * q.y - q.x * p.y;
            }
            0.5 * a
        })
        .sum()
}

/// Runs `scene` (see [`run_from_toml`]): the thermomechanical scene
/// ([`run_coupled`](super::run_coupled)) when `[model] mechanics` is true (the default), the
/// thermal one with the gap held open otherwise.
///
/// # Errors
/// As [`run_thermal`] and [`run_coupled`](super::run_coupled).
pub fn run(scene: &PelletScene, out: &Path, progress: bool) -> Result<Value, PelletError> {
    scene.check()?;
    if scene.model.mechanics {
        super::run_coupled(scene, out, progress)
    } else {
        run_thermal(scene, out, progress)
    }
}

/// Runs `scene` thermal only, the gap held at its as-built width.
///
/// The pellet's heat source is `Q = q'(t) / A_h`, with `A_h` the area of the pellet mesh
/// (a polygon slightly smaller than the disc), so that the discrete linear power is exactly
/// `q'(t) = q' min(t / ramp_time, 1)`.
///
/// # Errors
/// [`PelletError::Invalid`] for values out of range, [`PelletError::Physics`] for a failed
/// solve (a Newton failure carries its residual history), [`PelletError::Io`] /
/// [`PelletError::Write`] for outputs that cannot be written.
pub fn run_thermal(scene: &PelletScene, out: &Path, progress: bool) -> Result<Value, PelletError> {
    let start = Instant::now();
    scene.check()?;
    let (p, c) = (&scene.pellet, &scene.cladding);
    let r = scene.mesh.refinement;

    // Meshes: the pellet's circle has 16 r edges, the cladding's 21 r + 1, rotated by half a
    // cell: the interface does not match.
    let pellet_mesh = pellet_mesh(p.radius, 4 * r, 2 * r)?;
    let around = 21 * r + 1;
    let cladding_mesh = annulus_mesh(
        c.inner_radius,
        c.outer_radius,
        around,
        2 * r,
        std::f64::consts::PI / around as f64,
    )?;
    let area = mesh_area(&pellet_mesh);
    let (q, ramp) = (scene.power.linear_power, scene.power.ramp_time);
    let power = move |t: f64| {
        if ramp > 0.0 {
            q * (t / ramp).clamp(0.0, 1.0)
        } else {
            q
        }
    };
    let k_pellet = Conductivity::InverseLinear {
        a: p.conductivity_a,
        b: p.conductivity_b,
    };
    let t_co = c.outer_temperature;
    let pellet = HeatBody::new(
        "pellet",
        pellet_mesh,
        HeatMaterial::new(k_pellet.at(t_co).0, p.heat_capacity),
    )
    .with_source(move |_x, t| power(t) / area);
    let mid = 0.5 * (c.inner_radius + c.outer_radius);
    let cladding = HeatBody::new(
        "cladding",
        cladding_mesh,
        HeatMaterial::new(c.conductivity, c.heat_capacity),
    )
    .with_dirichlet_where(|f| f.centroid.norm() > mid, move |_x, _t| t_co)?;
    let slave_surface = pellet.mesh.boundary_surface(|_| true)?;
    let master_surface = cladding
        .mesh
        .boundary_surface(|f| f.centroid.norm() < mid)?;
    let law = scene.gap_law()?;
    let gap = c.inner_radius - p.radius;
    // Twice the gap, whatever the mesh size.
    let tolerances = Tolerances {
        search_radius: SearchRadius::Distance(2.0 * gap),
        ..Tolerances::default()
    };
    let problem = GapHeat::new(
        (pellet, k_pellet),
        (cladding, Conductivity::Constant(c.conductivity)),
        slave_surface,
        master_surface,
        &CouplingOptions::default().dual(),
        tolerances,
        law,
        &Default::default(),
    )?
    // Multipliers in kelvin-like units: lambda = mu / R_ref.
    .with_multiplier_scale(1.0 / law.reference_resistance)?;
    let setup_seconds = start.elapsed().as_secs_f64();

    let choice = scene.solver.choose(false, true, 0);
    let method = match choice.method {
        SolverMethod::Jfnk => GapSolver::Jfnk(scene.solver.jfnk_options()),
        _ => GapSolver::Newton,
    };
    let mut solver = GapSolverState::new(method);
    let newton = scene.solver.newton_options(q);

    let [pellet, cladding] = problem.bodies();
    let centre = nearest_node(&pellet.mesh, nalgebra::Vector3::zeros());
    let t0 = vec![t_co; pellet.mesh.node_count()];
    let t1 = vec![t_co; cladding.mesh.node_count()];
    let mut x = problem.state([&t0, &t1]);

    let steps = scene.time.steps();
    let bar = progress_bar(progress, steps as u64 + 1);
    let snapshot_every = scene.time.snapshot_every();
    // Every output is kept in memory and written at the end, all or none: a run that fails
    // leaves no half-written folder.
    let mut outputs: Vec<(String, Vec<u8>)> = Vec::new();
    let mut files = Vec::new();
    let mut history = Vec::new();
    let mut time = 0.0;
    write_snapshot(out, &problem, &x, time, &mut files, &mut outputs)?;
    for k in 1..=steps {
        if crate::interrupt::requested() {
            bar.finish_and_clear();
            // All or none: an interrupted thermal run writes nothing.
            return Err(PelletError::Interrupted { time, steps: k - 1 });
        }
        let dt = scene.time.step.min(scene.time.end - time);
        let old = x.clone();
        let rep = problem.solve(&mut x, time + dt, Some((&old, dt)), &mut solver, &newton)?;
        time += dt;
        let s = summary(&problem, &x, centre);
        history.push(json!({
            "time": time,
            "linear_power": power(time),
            "center_temperature": s[0],
            "pellet_surface_temperature": s[1],
            "cladding_inner_temperature": s[2],
            "newton_iterations": rep.iterations,
            "linear_iterations": rep.linear_iterations,
        }));
        if k % snapshot_every == 0 || k == steps {
            write_snapshot(out, &problem, &x, time, &mut files, &mut outputs)?;
        }
        bar.set_message(format!("t = {time:.1} s, T0 = {:.1} K", s[0]));
        bar.inc(1);
    }
    let transient = solver.stats;
    // Steady state at full power.
    let t_steady = time.max(ramp);
    let rep = problem.solve(&mut x, t_steady, None, &mut solver, &newton)?;
    bar.inc(1);
    bar.finish_and_clear();
    write_snapshot(out, &problem, &x, f64::INFINITY, &mut files, &mut outputs)?;
    outputs.push(("pellet.pvd".to_string(), pvd(&files).into_bytes()));

    let s = summary(&problem, &x, centre);
    let cf = scene.closed_form()?;
    let span = cf.center_temperature - t_co;
    let stats = solver.stats;
    let report = json!({
        "scene": "pellet",
        "status": "ok",
        "models": { "heat": true, "mechanics": false, "gap": "held at its as-built width" },
        "method": choice.method.name(),
        "solver_choice": {
            "asked": scene.solver.method.name(),
            "picked": choice.method.name(),
            "why": choice.reason,
        },
        "center_temperature": s[0],
        "pellet_surface_temperature": s[1],
        "cladding_inner_temperature": s[2],
        "closed_form": cf,
        "error": {
            "center_temperature": s[0] - cf.center_temperature,
            "pellet_surface_temperature": s[1] - cf.pellet_surface_temperature,
            "cladding_inner_temperature": s[2] - cf.cladding_inner_temperature,
            "center_relative_to_span": (s[0] - cf.center_temperature).abs() / span,
            "span": span,
        },
        "steady": {
            "time": t_steady,
            "newton_iterations": rep.iterations,
            "linear_iterations": rep.linear_iterations,
            "residual_history": rep.residual_history,
        },
        "solver": {
            "newton_iterations": stats.newton_iterations,
            "linear_iterations": stats.linear_iterations,
            "factorizations": stats.factorizations,
            "symbolic_analyses": stats.symbolic_analyses,
            "transient_newton_iterations": transient.newton_iterations,
            "transient_linear_iterations": transient.linear_iterations,
            "seconds": {
                "newton_total": stats.total_seconds,
                "jacobian_assembly": stats.assembly_seconds,
                "linear": stats.linear_seconds,
            },
        },
        "mesh": {
            "refinement": r,
            "pellet_nodes": pellet.mesh.node_count(),
            "pellet_cells": pellet.mesh.cell_count(),
            "cladding_nodes": cladding.mesh.node_count(),
            "cladding_cells": cladding.mesh.cell_count(),
            "pellet_interface_edges": 16 * r,
            "cladding_interface_edges": around,
            "unknowns": problem.dimension(),
        },
        "transient": history,
        // Uncovered slave area or skipped pairs of the coupling, named (none on these meshes).
        "coupling_warnings": problem.tie()
            .coupling()
            .warnings
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>(),
        "vtu": files.iter().map(|(f, _)| f.clone()).collect::<Vec<_>>(),
        "seconds": { "setup": setup_seconds, "total": start.elapsed().as_secs_f64() },
        "scene_data": scene,
    });
    let text = serde_json::to_string_pretty(&report).expect("JSON values serialise");
    outputs.push(("report.json".to_string(), text.into_bytes()));
    write_scene_outputs(out, outputs)?;
    Ok(report)
}

/// Whether `name` is one of the pellet scenes' own output files.
pub fn is_output(name: &str) -> bool {
    let numbered = |prefix: &str| {
        name.strip_prefix(prefix)
            .and_then(|rest| rest.strip_suffix(".vtu"))
            .is_some_and(|n| n.len() == 4 && n.bytes().all(|b| b.is_ascii_digit()))
    };
    numbered("pellet_")
        || numbered("interface_")
        || [
            "pellet_steady.vtu",
            "pellet.pvd",
            "interface.pvd",
            "temperatures.png",
            "gap.png",
            "pressures.png",
            "report.json",
        ]
        .contains(&name)
}

/// Writes a pellet run's `outputs` into `out`, all or none, then removes the pellet outputs of
/// an earlier run that this one did not write (so that the folder holds one run).
pub(super) fn write_scene_outputs(
    out: &Path,
    outputs: Vec<(String, Vec<u8>)>,
) -> Result<(), PelletError> {
    let (names, bytes): (Vec<String>, Vec<Vec<u8>>) = outputs.into_iter().unzip();
    let files: Vec<(&str, Vec<u8>)> = names.iter().map(String::as_str).zip(bytes).collect();
    write_outputs(out, &files)?;
    let written: Vec<&str> = names.iter().map(String::as_str).collect();
    remove_stale_outputs(out, &written, is_output)?;
    Ok(())
}

/// The run's progress display: the caller's ([`crate::progress::set_display`]) when asked.
pub(super) fn progress_bar(progress: bool, len: u64) -> Box<dyn crate::progress::Progress> {
    crate::progress::display(progress, len, "pellet")
}

/// The node nearest to `point`.
pub(super) fn nearest_node(mesh: &VolumeMesh, point: nalgebra::Vector3<f64>) -> usize {
    let mut best = (f64::INFINITY, 0);
    for (i, x) in mesh.coords().iter().enumerate() {
        let d = (x - point).norm();
        if d < best.0 {
            best = (d, i);
        }
    }
    best.1
}

/// Centre temperature, mean pellet surface temperature, mean cladding inner temperature.
fn summary<L: mortar_physics::laws::ConstraintLaw>(
    problem: &GapHeat<L>,
    x: &[f64],
    centre: usize,
) -> [f64; 3] {
    let [ts, tm, _] = problem.split(x);
    let mean = |nodes: &[u32], t: &[f64]| {
        nodes.iter().map(|&n| t[n as usize]).sum::<f64>() / nodes.len() as f64
    };
    let tie = problem.tie();
    [
        ts[centre],
        mean(tie.slave_nodes(), ts),
        mean(tie.master_nodes(), tm),
    ]
}

/// The VTU of the state `x` at `time` (`INFINITY`: the steady state), kept in `outputs` and
/// listed in `files`.
fn write_snapshot<L: mortar_physics::laws::ConstraintLaw>(
    out: &Path,
    problem: &GapHeat<L>,
    x: &[f64],
    time: f64,
    files: &mut Vec<(String, f64)>,
    outputs: &mut Vec<(String, Vec<u8>)>,
) -> Result<(), PelletError> {
    let [ts, tm, _] = problem.split(x);
    let [pellet, cladding] = problem.bodies();
    let name = if time.is_finite() {
        format!("pellet_{:04}.vtu", files.len())
    } else {
        "pellet_steady.vtu".to_string()
    };
    let text = vtu_string(
        &out.join(&name),
        &[
            VtuPiece {
                mesh: &pellet.mesh,
                point_data: vec![("temperature", ts)],
            },
            VtuPiece {
                mesh: &cladding.mesh,
                point_data: vec![("temperature", tm)],
            },
        ],
    )?;
    outputs.push((name.clone(), text.into_bytes()));
    files.push((name, time));
    Ok(())
}

/// A ParaView collection of the transient snapshots (the steady one at the last time + 1).
pub(super) fn pvd(files: &[(String, f64)]) -> String {
    let last = files
        .iter()
        .map(|f| f.1)
        .filter(|t| t.is_finite())
        .fold(0.0, f64::max);
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n",
    );
    for (name, t) in files {
        let t = if t.is_finite() { *t } else { last + 1.0 };
        s.push_str(&format!(
            "    <DataSet timestep=\"{t}\" part=\"0\" file=\"{name}\"/>\n"
        ));
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    s
}
