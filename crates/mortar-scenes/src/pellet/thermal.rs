//! The thermal pellet scene (`[model] mechanics = false`), the gap held at its as-built
//! width, as named steps: the problem built on the toolkit's meshes, the backward Euler
//! march with its snapshots and history, the steady state at full power, and the report
//! against the closed form.

use std::path::Path;
use std::time::Instant;

use mortar_core::{CouplingOptions, SearchRadius, Tolerances};
use mortar_physics::heat::{
    Conductivity, GapHeat, GapSolver, GapSolverState, GapSolverStats, HeatBody, HeatMaterial,
};
use mortar_physics::laws::GapConductance;
use mortar_physics::nonlinear::{NewtonOptions, NewtonReport};
use serde_json::{json, Value};

use super::outputs::{mesh_area, nearest_node, progress_bar, pvd, write_scene_outputs};
use super::{annulus_mesh, pellet_mesh, PelletError, PelletScene, SolverChoice, SolverMethod};
use crate::progress::Progress;
use mortar::io::vtu::{vtu_string, VtuPiece};

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
    let (problem, around) = thermal_problem(scene)?;
    let setup_seconds = start.elapsed().as_secs_f64();

    let choice = scene.solver.choose(false, true, 0);
    let bar = progress_bar(progress, scene.time.steps() as u64 + 1);
    let mut march = ThermalMarch::new(scene, &problem, &choice, out)?;
    march.transient(bar.as_ref())?;
    let transient = march.solver.stats;
    let (t_steady, steady) = march.steady(bar.as_ref())?;

    let report = ThermalReport {
        choice: &choice,
        transient,
        t_steady,
        steady: &steady,
        around,
        seconds: (setup_seconds, start),
    }
    .json(&march)?;
    let text = serde_json::to_string_pretty(&report).expect("JSON values serialise");
    let mut outputs = march.outputs;
    outputs.push(("report.json".to_string(), text.into_bytes()));
    write_scene_outputs(out, outputs)?;
    Ok(report)
}

/// The thermal problem of `scene`, and the cladding's edges around its bore. The meshes are
/// the toolkit's: the pellet's circle has 16 r edges, the cladding's 21 r + 1, rotated by
/// half a cell, so that the interface does not match; the pellet's source makes its discrete
/// linear power exactly `q'(t)`; the cladding's outer surface is held at its temperature.
fn thermal_problem(scene: &PelletScene) -> Result<(GapHeat<GapConductance>, usize), PelletError> {
    let (p, c) = (&scene.pellet, &scene.cladding);
    let r = scene.mesh.refinement;
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
    let power = scene.power;
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
    .with_source(move |_x, t| power.at(t) / area);
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
    Ok((problem, around))
}

/// The thermal run as it goes: the state, the time, the snapshots and the history.
/// Every output is kept in memory and written at the end, all or none: a run that fails
/// leaves no half-written folder.
struct ThermalMarch<'a> {
    scene: &'a PelletScene,
    problem: &'a GapHeat<GapConductance>,
    out: &'a Path,
    solver: GapSolverState,
    newton: NewtonOptions,
    /// The pellet's node nearest its centre.
    centre: usize,
    x: Vec<f64>,
    time: f64,
    /// The snapshots written, with their times.
    files: Vec<(String, f64)>,
    outputs: Vec<(String, Vec<u8>)>,
    history: Vec<Value>,
}

impl<'a> ThermalMarch<'a> {
    /// The initial state (both bodies at the cladding's outer temperature) and its snapshot,
    /// with the solver `choice` picked.
    fn new(
        scene: &'a PelletScene,
        problem: &'a GapHeat<GapConductance>,
        choice: &SolverChoice,
        out: &'a Path,
    ) -> Result<Self, PelletError> {
        let method = match choice.method {
            SolverMethod::Jfnk => GapSolver::Jfnk(scene.solver.jfnk_options()),
            _ => GapSolver::Newton,
        };
        let t_co = scene.cladding.outer_temperature;
        let [pellet, cladding] = problem.bodies();
        let t0 = vec![t_co; pellet.mesh.node_count()];
        let t1 = vec![t_co; cladding.mesh.node_count()];
        let mut march = Self {
            scene,
            problem,
            out,
            solver: GapSolverState::new(method),
            newton: scene.solver.newton_options(scene.power.linear_power),
            centre: nearest_node(&pellet.mesh, nalgebra::Vector3::zeros()),
            x: problem.state([&t0, &t1]),
            time: 0.0,
            files: Vec::new(),
            outputs: Vec::new(),
            history: Vec::new(),
        };
        march.snapshot(march.time)?;
        Ok(march)
    }

    /// The state's VTU at `time` (`INFINITY`: the steady state), kept with the outputs.
    fn snapshot(&mut self, time: f64) -> Result<(), PelletError> {
        write_snapshot(
            self.out,
            self.problem,
            &self.x,
            time,
            &mut self.files,
            &mut self.outputs,
        )
    }

    /// The backward Euler steps to `[time] end`, each with a row of the history, a
    /// snapshot every `snapshot_every` steps and at the last; an interrupt between steps
    /// stops the run, which then writes nothing.
    fn transient(&mut self, bar: &dyn Progress) -> Result<(), PelletError> {
        let scene = self.scene;
        let steps = scene.time.steps();
        let snapshot_every = scene.time.snapshot_every();
        for k in 1..=steps {
            if crate::interrupt::requested() {
                bar.finish_and_clear();
                // All or none: an interrupted thermal run writes nothing.
                return Err(PelletError::Interrupted {
                    time: self.time,
                    steps: k - 1,
                });
            }
            let time = self.time;
            let dt = scene.time.step.min(scene.time.end - time);
            let old = self.x.clone();
            let rep = self.problem.solve(
                &mut self.x,
                time + dt,
                Some((&old, dt)),
                &mut self.solver,
                &self.newton,
            )?;
            self.time += dt;
            let time = self.time;
            let s = summary(self.problem, &self.x, self.centre);
            self.history.push(json!({
                "time": time,
                "linear_power": scene.power.at(time),
                "center_temperature": s[0],
                "pellet_surface_temperature": s[1],
                "cladding_inner_temperature": s[2],
                "newton_iterations": rep.iterations,
                "linear_iterations": rep.linear_iterations,
            }));
            if k % snapshot_every == 0 || k == steps {
                self.snapshot(time)?;
            }
            bar.set_message(format!("t = {time:.1} s, T0 = {:.1} K", s[0]));
            bar.inc(1);
        }
        Ok(())
    }

    /// The steady state at full power (at the end time, or the end of the ramp if later),
    /// its snapshot and the snapshots' ParaView collection; its time and Newton report.
    fn steady(&mut self, bar: &dyn Progress) -> Result<(f64, NewtonReport), PelletError> {
        let t_steady = self.time.max(self.scene.power.ramp_time);
        let rep =
            self.problem
                .solve(&mut self.x, t_steady, None, &mut self.solver, &self.newton)?;
        bar.inc(1);
        bar.finish_and_clear();
        self.snapshot(f64::INFINITY)?;
        self.outputs
            .push(("pellet.pvd".to_string(), pvd(&self.files).into_bytes()));
        Ok((t_steady, rep))
    }
}

/// What the thermal run's report says besides the march's own state.
struct ThermalReport<'a> {
    choice: &'a SolverChoice,
    /// The solver's counts before the steady solve.
    transient: GapSolverStats,
    t_steady: f64,
    /// The steady solve's Newton report.
    steady: &'a NewtonReport,
    /// The cladding's edges around its bore.
    around: usize,
    /// The set-up's seconds, and the run's start.
    seconds: (f64, Instant),
}

impl ThermalReport<'_> {
    /// The report of a march that reached its steady state: the steady temperatures
    /// against the closed form, the solver and its counts, the meshes, the history.
    ///
    /// # Errors
    /// [`PelletError::Law`] for gap parameters out of range (the closed form's).
    fn json(&self, march: &ThermalMarch) -> Result<Value, PelletError> {
        let (scene, problem) = (march.scene, march.problem);
        let s = summary(problem, &march.x, march.centre);
        let cf = scene.closed_form()?;
        let span = cf.center_temperature - scene.cladding.outer_temperature;
        let rep = self.steady;
        Ok(json!({
            "scene": "pellet",
            "status": "ok",
            "models": { "heat": true, "mechanics": false, "gap": "held at its as-built width" },
            "method": self.choice.method.name(),
            "solver_choice": {
                "asked": scene.solver.method.name(),
                "picked": self.choice.method.name(),
                "why": self.choice.reason,
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
                "time": self.t_steady,
                "newton_iterations": rep.iterations,
                "linear_iterations": rep.linear_iterations,
                "residual_history": rep.residual_history,
            },
            "solver": self.solver_json(&march.solver.stats),
            "mesh": self.mesh_json(march),
            "transient": march.history,
            // Uncovered slave area or skipped pairs of the coupling, named (none on these meshes).
            "coupling_warnings": problem.tie()
                .coupling()
                .warnings
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>(),
            "vtu": march.files.iter().map(|(f, _)| f.clone()).collect::<Vec<_>>(),
            "seconds": { "setup": self.seconds.0, "total": self.seconds.1.elapsed().as_secs_f64() },
            "scene_data": scene,
        }))
    }

    /// The solver's counts (`stats`, after the steady solve; the transient's beside them)
    /// and seconds.
    fn solver_json(&self, stats: &GapSolverStats) -> Value {
        json!({
            "newton_iterations": stats.newton_iterations,
            "linear_iterations": stats.linear_iterations,
            "factorizations": stats.factorizations,
            "symbolic_analyses": stats.symbolic_analyses,
            "transient_newton_iterations": self.transient.newton_iterations,
            "transient_linear_iterations": self.transient.linear_iterations,
            "seconds": {
                "newton_total": stats.total_seconds,
                "jacobian_assembly": stats.assembly_seconds,
                "linear": stats.linear_seconds,
            },
        })
    }

    /// The meshes' sizes and the unknowns.
    fn mesh_json(&self, march: &ThermalMarch) -> Value {
        let r = march.scene.mesh.refinement;
        let [pellet, cladding] = march.problem.bodies();
        json!({
            "refinement": r,
            "pellet_nodes": pellet.mesh.node_count(),
            "pellet_cells": pellet.mesh.cell_count(),
            "cladding_nodes": cladding.mesh.node_count(),
            "cladding_cells": cladding.mesh.cell_count(),
            "pellet_interface_edges": 16 * r,
            "cladding_interface_edges": self.around,
            "unknowns": march.problem.dimension(),
        })
    }
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
