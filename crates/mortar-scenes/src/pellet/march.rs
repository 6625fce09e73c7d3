//! The coupled pellet's run as it goes ([`March`]): the initial state, the time steps, the
//! steady state, the history and snapshots, the report, and the outputs of a failure.

use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use mortar_physics::heat::{assemble_conduction, Conductivity};
use mortar_physics::laws::{ConstraintLaw, RelocationModel};
use mortar_physics::nonlinear::NewtonOptions;
use mortar_physics::thermomech::{
    GapThermoMechanics, ThermoMechSolver, ThermoMechSolverState, ThermoMechStats,
};
use mortar_physics::PhysicsError;
use nalgebra::Vector3;
use serde_json::{json, Value};

use super::file_mesh::FileGeometry;
use super::limits::{extremes, LimitWatch, When};
use super::outputs::{nearest_node, pvd, write_scene_outputs};
use super::{PelletError, PelletScene, SolverChoice, SolverMethod};
use crate::linear_solver::PickedSolver;
#[cfg(feature = "plots")]
use crate::plot::{line_chart_png, Chart, Curve};
use mortar::io::vtu::{surface_vtu_string, vtu_string_with_vectors, VtuPiece};

/// The most times a failing time step is halved before the run stops.
pub const MAX_STEP_CUTS: usize = 4;

/// The quantities of one state, for the history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Summary {
    pub(super) center: f64,
    pub(super) pellet_surface: f64,
    pub(super) cladding_inner: f64,
    pub(super) gap: f64,
    pub(super) min_gap: f64,
    pub(super) interface_pressure: f64,
    pub(super) peak_pressure: f64,
    pub(super) contact_pressure: f64,
    pub(super) plenum: f64,
    pub(super) displacement: f64,
    /// A stack's lands (its contact pairs): the smallest gap and the largest contact
    /// pressure (NaN without).
    pub(super) land_min_gap: f64,
    pub(super) land_peak_pressure: f64,
}

fn summary<TL: ConstraintLaw, ML: ConstraintLaw>(
    problem: &GapThermoMechanics<TL, ML>,
    x: &[f64],
    centre: usize,
) -> Summary {
    let f = problem.fields(x);
    let tie = problem.heat().tie();
    let w = &problem.normal_gap().weights;
    let length: f64 = w.iter().sum();
    let mean = |v: &[f64]| v.iter().zip(w).map(|(a, b)| a * b).sum::<f64>() / length;
    let (ts, tm) = (f.temperature[0], f.temperature[1]);
    let node_mean = |nodes: &[u32], t: &[f64]| {
        nodes.iter().map(|&n| t[n as usize]).sum::<f64>() / nodes.len() as f64
    };
    let gaps = problem.gaps(x);
    let p = f.contact_pressure();
    let u = f.displacement(0);
    let coords = problem.heat().bodies()[0].mesh.coords();
    let sn = tie.slave_nodes();
    let dim = problem.elastic_bodies()[0].components();
    let rz = problem.options().elastic.geometry.is_axisymmetric();
    let radial: f64 = sn
        .iter()
        .map(|&n| {
            let (n, x) = (n as usize, coords[n as usize]);
            if rz {
                u[dim * n]
            } else {
                (u[dim * n] * x.x + u[dim * n + 1] * x.y) / x.xy().norm()
            }
        })
        .sum::<f64>()
        / sn.len() as f64;
    Summary {
        center: ts[centre],
        pellet_surface: node_mean(sn, ts),
        cladding_inner: node_mean(tie.master_nodes(), tm),
        gap: mean(&gaps),
        min_gap: gaps.iter().copied().fold(f64::INFINITY, f64::min),
        interface_pressure: f.gas_pressure + mean(&p),
        peak_pressure: f.gas_pressure + p.iter().copied().fold(0.0, f64::max),
        contact_pressure: mean(&p),
        plenum: f.gas_pressure,
        displacement: radial,
        land_min_gap: (0..problem.contact_pairs())
            .flat_map(|k| problem.pair_gaps(k, x))
            .reduce(f64::min)
            .unwrap_or(f64::NAN),
        land_peak_pressure: (0..problem.contact_pairs())
            .flat_map(|k| problem.pair_contact_pressures(k, x))
            .reduce(f64::max)
            .unwrap_or(f64::NAN),
    }
}

/// A row of the history: time, summary, Newton and linear iterations, step cuts.
pub(super) type Row = (f64, Summary, usize, usize, usize);

/// The coupled run as it goes: the problem and its solver (with the fallback of a picked
/// JFNK to Newton), the state, the history, the snapshots and the outputs, the model
/// ranges watched. Each solve that fails ends the run through [`fail`](Self::fail), which
/// writes what was computed with `"status": "failed"`.
pub(super) struct March<'a, TL: ConstraintLaw, ML: ConstraintLaw> {
    pub(super) scene: &'a PelletScene,
    pub(super) problem: &'a GapThermoMechanics<TL, ML>,
    pub(super) choice: &'a SolverChoice,
    /// Where Newton's Jacobians go.
    pub(super) linear: &'a PickedSolver,
    pub(super) out: &'a Path,
    pub(super) newton: NewtonOptions,
    pub(super) solver: ThermoMechSolverState,
    /// A picked JFNK whose solve failed hands the solve, and the rest of the run, to Newton:
    /// when and why.
    pub(super) fallback: Option<Value>,
    pub(super) x: Vec<f64>,
    /// The pellet's centre node (its temperature is the history's).
    pub(super) centre: usize,
    pub(super) time: f64,
    pub(super) cuts_total: usize,
    pub(super) rows: Vec<Row>,
    pub(super) files: Vec<(String, f64)>,
    pub(super) outputs: Vec<(String, Vec<u8>)>,
    pub(super) watch: LimitWatch,
}

impl<'a, TL: ConstraintLaw, ML: ConstraintLaw> March<'a, TL, ML> {
    /// The run of `problem` (of `scene`) by the method of `choice`, Newton's Jacobians to
    /// `linear`, from the uniform outer temperature, writing into `out`.
    pub(super) fn new(
        scene: &'a PelletScene,
        problem: &'a GapThermoMechanics<TL, ML>,
        (choice, linear): (&'a SolverChoice, &'a PickedSolver),
        out: &'a Path,
    ) -> Self {
        let method = match choice.method {
            SolverMethod::Jfnk => ThermoMechSolver::Jfnk(scene.solver.jfnk_options()),
            _ => ThermoMechSolver::Newton,
        };
        let bodies = problem.heat().bodies();
        let t_co = scene.cladding.outer_temperature;
        let t0 = vec![t_co; bodies[0].mesh.node_count()];
        let t1 = vec![t_co; bodies[1].mesh.node_count()];
        Self {
            scene,
            problem,
            choice,
            linear,
            out,
            newton: scene.solver.newton_options(scene.power.linear_power),
            solver: match linear.shared() {
                Some(backend) => ThermoMechSolverState::new(method).with_backend(backend),
                None => ThermoMechSolverState::new(method),
            },
            fallback: None,
            x: problem.state([&t0, &t1]),
            centre: nearest_node(&bodies[0].mesh, Vector3::zeros()),
            time: 0.0,
            cuts_total: 0,
            rows: Vec::new(),
            files: Vec::new(),
            outputs: Vec::new(),
            watch: LimitWatch::default(),
        }
    }

    /// Solves the state at `t` (steady for `transient = None`) from `self.x`; a picked JFNK
    /// that fails is handed to Newton, from the same start.
    fn solve(&mut self, t: f64, transient: Option<(&[f64], f64)>) -> Result<(), PhysicsError> {
        // The start of the solve, kept only while a fallback can use it.
        let start = (self.choice.picked && matches!(self.solver.method, ThermoMechSolver::Jfnk(_)))
            .then(|| self.x.clone());
        let problem = self.problem;
        match (
            problem.solve(&mut self.x, t, transient, &mut self.solver, &self.newton),
            start,
        ) {
            (Ok(_), _) => Ok(()),
            (Err(e), Some(start)) => {
                self.fallback = Some(json!({ "time": t, "cause": e.to_string() }));
                self.solver.method = ThermoMechSolver::Newton;
                self.x.copy_from_slice(&start);
                problem
                    .solve(&mut self.x, t, transient, &mut self.solver, &self.newton)
                    .map(|_| ())
            }
            (Err(e), None) => Err(e),
        }
    }

    /// The model ranges at the state, at `time`, for the step named `step`.
    fn observe(&mut self, time: f64, step: Value) -> Result<(), PelletError> {
        let extremes = extremes(self.problem, &self.x, time)?;
        self.watch.observe(&When { time, step }, &extremes);
        Ok(())
    }

    /// The initial state: mechanical equilibrium at the uniform temperature, no power; its
    /// row and snapshot.
    pub(super) fn initial(&mut self) -> Result<(), PelletError> {
        if let Err(e) = self.solve(0.0, None) {
            let what = "the initial state".to_string();
            let e = located(self.problem, e, what, Some(0), 0.0, &self.x, None);
            return Err(self.fail(e));
        }
        self.observe(0.0, json!("initial"))?;
        let rep0 = self.solver.stats;
        let s = summary(self.problem, &self.x, self.centre);
        let row = (0.0, s, rep0.newton_iterations, rep0.linear_iterations, 0);
        self.record(row, true)
    }

    /// The history's `row` of the time reached, and its snapshot if `snapshot`.
    fn record(&mut self, row: Row, snapshot: bool) -> Result<(), PelletError> {
        self.rows.push(row);
        if !snapshot {
            return Ok(());
        }
        write_snapshot(
            self.out,
            self.problem,
            &self.x,
            self.time,
            &mut self.files,
            &mut self.outputs,
        )
    }

    /// Time step `k`: backward Euler from the time reached to `k dt` (the end at most),
    /// halving the step on a failure up to [`MAX_STEP_CUTS`] times; its row, and its
    /// snapshot when one is due. An interruption asked for stops the run here.
    pub(super) fn step(&mut self, k: usize) -> Result<(), PelletError> {
        let (scene, steps) = (self.scene, self.scene.time.steps());
        if crate::interrupt::requested() {
            let e = PelletError::Interrupted {
                time: self.time,
                steps: k - 1,
            };
            return Err(self.fail(e));
        }
        let target = (k as f64 * scene.time.step).min(scene.time.end);
        let before = self.solver.stats;
        let mut cuts = 0;
        while self.time < target {
            let time = self.time;
            let dt = (target - time).min(scene.time.step / f64::powi(2.0, cuts as i32));
            let old = self.x.clone();
            match self.solve(time + dt, Some((&old, dt))) {
                Ok(_) => self.time += dt,
                Err(e) => {
                    cuts += 1;
                    if cuts > MAX_STEP_CUTS {
                        let what = format!(
                            "time step {k} of {steps} (from t = {time} s, dt = {dt} s after \
                             {MAX_STEP_CUTS} halvings)"
                        );
                        let transient = Some((old.as_slice(), dt));
                        let e = located(
                            self.problem,
                            e,
                            what,
                            Some(k),
                            time + dt,
                            &self.x,
                            transient,
                        );
                        return Err(self.fail(e));
                    }
                    self.x = old;
                }
            }
        }
        self.time = target;
        self.cuts_total += cuts;
        let s = summary(self.problem, &self.x, self.centre);
        self.observe(self.time, json!(k))?;
        let row = (
            self.time,
            s,
            self.solver.stats.newton_iterations - before.newton_iterations,
            self.solver.stats.linear_iterations - before.linear_iterations,
            cuts,
        );
        self.record(
            row,
            k.is_multiple_of(scene.time.snapshot_every()) || k == steps,
        )
    }

    /// The steady state at full power (at the end, or the ramp's end if later); its time.
    pub(super) fn steady(&mut self) -> Result<f64, PelletError> {
        let t_steady = self.time.max(self.scene.power.ramp_time);
        if let Err(e) = self.solve(t_steady, None) {
            let what = "the steady state at full power".to_string();
            let e = located(self.problem, e, what, None, t_steady, &self.x, None);
            return Err(self.fail(e));
        }
        self.observe(t_steady, json!("steady"))?;
        self.outputs
            .push(("pellet.pvd".to_string(), pvd(&self.files).into_bytes()));
        self.outputs.push((
            "interface.pvd".to_string(),
            pvd(&interface_files(&self.files)).into_bytes(),
        ));
        Ok(t_steady)
    }

    /// Ends the run on the error `e`: writes what was computed (the snapshots, the history,
    /// the located failure, `"status": "failed"` or `"interrupted"`) and returns `e` (or,
    /// when those outputs cannot be written, an error saying so too).
    fn fail(&mut self, e: PelletError) -> PelletError {
        let physics = match &e {
            PelletError::Physics(p) => Some(p),
            PelletError::SolveFailed { source, .. } => Some(source.as_ref()),
            _ => None,
        };
        let newton = match physics {
            Some(PhysicsError::Newton(f)) => Some(f),
            _ => None,
        };
        let history = newton.map_or(Vec::new(), |f| f.residual_history.clone());
        let located = match &e {
            PelletError::SolveFailed {
                solve,
                step,
                time,
                block,
                blocks,
                source,
            } => json!({
                "solve": solve,
                "step": step,
                "time": time,
                "reason": newton.map_or_else(|| source.to_string(), |f| format!("{:?}", f.reason)),
                "block": block,
                "blocks": blocks.iter().map(|(n, v)| (n.to_string(), json!(v))).collect::<serde_json::Map<_, _>>(),
            }),
            _ => Value::Null,
        };
        let status = if matches!(e, PelletError::Interrupted { .. }) {
            "interrupted"
        } else {
            "failed"
        };
        let files = &self.files;
        let report = json!({
            "scene": "pellet",
            "status": status,
            "error": e.to_string(),
            "failure": located,
            "residual_history": history,
            "warnings": self.watch.to_json(),
            "valid_steps": self.rows.len(),
            "history": history_json(self.scene, &self.rows),
            "vtu": files.iter().map(|(f, _)| f.clone()).collect::<Vec<_>>(),
            "scene_data": self.scene,
        });
        let mut outputs = std::mem::take(&mut self.outputs);
        outputs.push(("pellet.pvd".to_string(), pvd(files).into_bytes()));
        outputs.push((
            "interface.pvd".to_string(),
            pvd(&interface_files(files)).into_bytes(),
        ));
        outputs.push((
            "report.json".to_string(),
            serde_json::to_string_pretty(&report)
                .expect("JSON values serialise")
                .into_bytes(),
        ));
        match write_scene_outputs(self.out, outputs) {
            Ok(()) => e,
            Err(w) => PelletError::Invalid(format!("{e}; and the outputs of the failure: {w}")),
        }
    }
}

/// What the coupled run's report says besides the march's own state.
pub(super) struct CoupledReport<'a> {
    pub(super) scene: &'a PelletScene,
    pub(super) file: Option<&'a FileGeometry>,
    /// The thermal and contact laws' names.
    pub(super) names: (&'a str, &'a str),
    /// The exponential law's onset gap.
    pub(super) onset: Option<f64>,
    pub(super) relocation: &'a Arc<dyn RelocationModel>,
    pub(super) choice: &'a SolverChoice,
    /// The solver's counts before the steady solve.
    pub(super) transient_stats: ThermoMechStats,
    pub(super) t_steady: f64,
    /// The set-up's seconds, and the run's start.
    pub(super) seconds: (f64, Instant),
}

impl CoupledReport<'_> {
    /// The report of a march that reached its steady state.
    ///
    /// # Errors
    /// [`PelletError::Physics`] where the heat flow or the eigenstrain cannot be evaluated.
    pub(super) fn json<TL: ConstraintLaw, ML: ConstraintLaw>(
        &self,
        march: &March<'_, TL, ML>,
    ) -> Result<Value, PelletError> {
        let (scene, problem, rows) = (self.scene, march.problem, &march.rows);
        let x = &march.x;
        let heat_out = outer_heat_flow(problem, x)?;
        let closure = contact_engaged(rows, self.onset);
        let last = rows.last().expect("the initial row").1;
        let peak = rows.iter().map(|r| r.1.peak_pressure).fold(0.0, f64::max);
        Ok(json!({
            "scene": "pellet",
            "status": if march.watch.is_empty() { "ok" } else { "warnings" },
            // The model ranges the run left, each once (docs/models.md, section 3b).
            "warnings": march.watch.to_json(),
            "models": self.models_json(closure),
            "method": match march.solver.method { ThermoMechSolver::Newton => "newton", ThermoMechSolver::Jfnk(_) => "jfnk" },
            "solver_choice": {
                "asked": scene.solver.method.name(),
                "picked": self.choice.method.name(),
                "why": self.choice.reason,
                "fallback_to_newton": march.fallback,
            },
            "center_temperature": last.center,
            "gap": last.gap,
            // When contact engaged (the mean gap fell below xi, or the exact law's pressure
            // became positive); the key's name is kept for the scripts that read it.
            "gap_closure_time": closure,
            "peak_interface_pressure": peak,
            "plenum_pressure": last.plenum,
            "interface_pressure": last.interface_pressure,
            "history": history_json(scene, rows),
            // Uncovered slave area or skipped pairs of the coupling, named (none on these meshes).
            "coupling_warnings": problem.heat().tie()
                .coupling()
                .warnings
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>(),
            "steady": self.steady_json(march, heat_out)?,
            "solver": self.solver_json(march),
            "linear_solver": march.linear.json(),
            "mesh": self.mesh_json(march),
            "vtu": march.files.iter().map(|(f, _)| f.clone()).collect::<Vec<_>>(),
            "seconds": { "setup": self.seconds.0, "total": self.seconds.1.elapsed().as_secs_f64() },
            "scene_data": scene,
        }))
    }

    /// What was modelled: the geometry, the laws, the plenum, the relocation and burnup, and
    /// whether contact engaged (at `closure`).
    fn models_json(&self, closure: Option<f64>) -> Value {
        let scene = self.scene;
        json!({
            "heat": true,
            "mechanics": true,
            "geometry": scene.model.geometry,
            "axial": scene.model.axial(),
            "contact_law": self.names.1,
            "gap_conductance": self.names.0,
            "plenum": "ideal gas, fixed moles",
            // The pellet's relocation model, and the burnup it sees (MWd/kgU).
            "relocation": self.relocation.name(),
            "burnup": scene.model.burnup,
            "contact_engaged": closure.is_some(),
            // The exponential law's onset gap xi (m), below which its pressure rises.
            "contact_onset_gap": self.onset,
        })
    }

    /// The steady state at full power: its temperatures, gap, pressures, displacement,
    /// relocation and axial strains, and its energy balance (the power in against
    /// `heat_out`, the heat flow out of the cladding).
    ///
    /// # Errors
    /// [`PelletError::Physics`] where the eigenstrain cannot be evaluated.
    fn steady_json<TL: ConstraintLaw, ML: ConstraintLaw>(
        &self,
        march: &March<'_, TL, ML>,
        heat_out: f64,
    ) -> Result<Value, PelletError> {
        let (scene, problem, x, t_steady) = (self.scene, march.problem, &march.x, self.t_steady);
        let steady = summary(problem, x, march.centre);
        // Per unit length in 2D, over the segment in 3D.
        let length = if scene.model.geometry.is_plane() {
            1.0
        } else {
            scene.model.segment_height
        };
        let power_in = scene.power.at(t_steady) * length;
        Ok(json!({
            "time": t_steady,
            "center_temperature": steady.center,
            "pellet_surface_temperature": steady.pellet_surface,
            "cladding_inner_temperature": steady.cladding_inner,
            "gap": steady.gap,
            "interface_pressure": steady.interface_pressure,
            "plenum_pressure": steady.plenum,
            "pellet_surface_displacement": steady.displacement,
            // The pellet's relocation strain across its axis (0 without relocation).
            "relocation_strain": problem.eigenstrain_at(0, t_steady)?.map_or(0.0, |e| e[0]),
            // The bodies' axial strains (null where the axial direction is held).
            "axial_strain": {
                "pellet": problem.fields(x).axial_strain[0],
                "cladding": problem.fields(x).axial_strain[1],
            },
            "power_in": power_in,
            "heat_out": heat_out,
            "relative_imbalance": (heat_out - power_in).abs() / power_in.max(f64::MIN_POSITIVE),
        }))
    }

    /// The solver's counts (the transient's beside them), step cuts and seconds.
    fn solver_json<TL: ConstraintLaw, ML: ConstraintLaw>(
        &self,
        march: &March<'_, TL, ML>,
    ) -> Value {
        let stats = march.solver.stats;
        json!({
            "newton_iterations": stats.newton_iterations,
            "linear_iterations": stats.linear_iterations,
            "factorizations": stats.factorizations,
            "symbolic_analyses": stats.symbolic_analyses,
            "reused_preconditioners": stats.reused_preconditioners,
            "transient_newton_iterations": self.transient_stats.newton_iterations,
            "step_cuts": march.cuts_total,
            "seconds": {
                "newton_total": stats.total_seconds,
                "assembly": stats.assembly_seconds,
                "linear": stats.linear_seconds,
            },
        })
    }

    /// The meshes: the mesh file's geometry (if one), the refinement, each body's size, the
    /// interface's slave nodes and the unknowns.
    fn mesh_json<TL: ConstraintLaw, ML: ConstraintLaw>(&self, march: &March<'_, TL, ML>) -> Value {
        let (scene, problem) = (self.scene, march.problem);
        let bodies = problem.heat().bodies();
        let mesh = |b: usize| {
            json!({
                "nodes": bodies[b].mesh.node_count(),
                "cells": bodies[b].mesh.cell_count(),
            })
        };
        json!({
            "file": self.file.map(|f| json!({
                "path": scene.mesh.file.as_ref().map(|p| p.display().to_string()),
                "pellet_radius": f.pellet_radius,
                "cladding_inner_radius": f.inner_radius,
                "cladding_outer_radius": f.outer_radius,
                "height": f.height,
                "pellet_volume": f.pellet_volume,
                "land_area": f.land_area,
                "end_voids": f.end_voids(),
            })),
            "refinement": scene.mesh.refinement,
            "pellet": mesh(0),
            "cladding": mesh(1),
            "interface_slave_nodes": problem.normal_gap().weights.len(),
            "unknowns": problem.dimension(),
        })
    }
}

/// When contact engaged, from the history: the exponential law's pressure rises where the
/// gap falls below `xi` (the smallest gap, not zero: the gap is not closed; an off-centre
/// pellet engages on its near side first); the exact law's (`onset` `None`) mean contact
/// pressure is positive (above a millionth of the gas pressure: the round-off of an inactive
/// node's pressure is far below it). From the initial state (an off-centre pellet touching
/// at once), or between two rows (interpolated in the exponential law's smallest gap).
fn contact_engaged(rows: &[Row], onset: Option<f64>) -> Option<f64> {
    let touches = |s: &Summary| match onset {
        Some(xi) => s.min_gap <= xi,
        None => s.contact_pressure > 1e-6 * s.plenum,
    };
    rows.iter().position(|r| touches(&r.1)).map(|i| {
        if i == 0 {
            return rows[0].0;
        }
        let (t0, s0, t1, s1) = (rows[i - 1].0, rows[i - 1].1, rows[i].0, rows[i].1);
        match onset {
            Some(xi) if s0.min_gap > s1.min_gap => {
                t0 + (t1 - t0) * (s0.min_gap - xi) / (s0.min_gap - s1.min_gap)
            }
            _ => t1,
        }
    })
}

/// The error of the failed solve `solve` (`step`, to time `time`; `transient` as
/// [`GapThermoMechanics::solve`]), with the block of equations holding the largest residual
/// at its last iterate `x`.
fn located<TL: ConstraintLaw, ML: ConstraintLaw>(
    problem: &GapThermoMechanics<TL, ML>,
    e: PhysicsError,
    solve: String,
    step: Option<usize>,
    time: f64,
    x: &[f64],
    transient: Option<(&[f64], f64)>,
) -> PelletError {
    // A block whose residual is not finite is the one named; else the largest.
    let blocks = problem.residual_blocks(x, time, transient).ok();
    let block = blocks.and_then(|b| {
        b.iter()
            .find(|(_, v)| !v.is_finite())
            .or_else(|| b.iter().max_by(|p, q| p.1.total_cmp(&q.1)))
            .map(|b| b.0)
    });
    PelletError::SolveFailed {
        solve,
        step,
        time,
        block,
        blocks: blocks.map_or(Vec::new(), |b| b.to_vec()),
        source: Box::new(e),
    }
}

/// The heat leaving through the cladding's outer surface (W/m): the reaction of its
/// prescribed temperatures, `sum over them of int k grad T . grad N_a` (the conduction rows
/// of the prescribed nodes, which the residual replaces by their conditions).
fn outer_heat_flow<TL: ConstraintLaw, ML: ConstraintLaw>(
    problem: &GapThermoMechanics<TL, ML>,
    x: &[f64],
) -> Result<f64, PelletError> {
    let cladding = &problem.heat().bodies()[1];
    let t = problem.fields(x).temperature[1];
    let k = Conductivity::Constant(cladding.material.conductivity);
    let (f, _) = assemble_conduction(cladding, &k, t, &problem.options().heat, None)?;
    let (nodes, _) = cladding.dirichlet_nodes();
    Ok(nodes.iter().map(|&n| -f[n as usize]).sum())
}

/// PNG plots of the history: temperatures, gap, pressures (none without the feature
/// `plots`).
#[cfg(not(feature = "plots"))]
pub(super) fn history_plots(
    _: &[(f64, Summary, usize, usize, usize)],
) -> Result<Vec<(String, Vec<u8>)>, PelletError> {
    Ok(Vec::new())
}

/// A history plot: its file, title, y axis and the scale of its values, and its curves'
/// legends and values.
#[cfg(feature = "plots")]
type HistoryPlot = (
    &'static str,
    &'static str,
    &'static str,
    f64,
    &'static [HistoryCurve],
);

/// A curve of a history plot: its legend and its value in a step's summary.
#[cfg(feature = "plots")]
type HistoryCurve = (&'static str, fn(&Summary) -> f64);

/// The history's plots over time.
#[cfg(feature = "plots")]
#[rustfmt::skip]
const HISTORY_PLOTS: [HistoryPlot; 3] = [
    ("temperatures.png", "Pellet temperatures", "temperature (K)", 1.0, &[
        ("centre", |s| s.center),
        ("pellet surface", |s| s.pellet_surface),
        ("cladding inner surface", |s| s.cladding_inner),
    ]),
    ("gap.png", "Pellet-cladding gap", "gap (um)", 1e6, &[
        ("mean gap", |s| s.gap),
        ("smallest gap", |s| s.min_gap),
    ]),
    ("pressures.png", "Pressures", "pressure (MPa)", 1e-6, &[
        ("interface pressure P_c (mean)", |s| s.interface_pressure),
        ("interface pressure (peak)", |s| s.peak_pressure),
        ("plenum pressure P_o", |s| s.plenum),
    ]),
];

/// PNG plots of the history: temperatures, gap, pressures.
#[cfg(feature = "plots")]
pub(super) fn history_plots(
    rows: &[(f64, Summary, usize, usize, usize)],
) -> Result<Vec<(String, Vec<u8>)>, PelletError> {
    let mut out = Vec::new();
    for (file, title, y_label, scale, curves) in HISTORY_PLOTS {
        let curves = curves
            .iter()
            .map(|&(name, value)| Curve {
                name,
                points: rows.iter().map(|r| (r.0, scale * value(&r.1))).collect(),
            })
            .collect();
        let chart = Chart {
            title,
            x_label: "time (s)",
            y_label,
            curves,
        };
        out.push((file.to_string(), line_chart_png(&chart)?));
    }
    Ok(out)
}

/// The interface files beside the bodies' `pellet_NNNN.vtu` files.
fn interface_files(files: &[(String, f64)]) -> Vec<(String, f64)> {
    files
        .iter()
        .map(|(n, t)| (n.replacen("pellet_", "interface_", 1), *t))
        .collect()
}

/// The history as arrays over the time steps.
fn history_json(scene: &PelletScene, rows: &[Row]) -> Value {
    let col = |f: &dyn Fn(&Summary) -> f64| rows.iter().map(|r| f(&r.1)).collect::<Vec<_>>();
    let mut history = json!({
        "time": rows.iter().map(|r| r.0).collect::<Vec<_>>(),
        "linear_power": rows.iter().map(|r| scene.power.at(r.0)).collect::<Vec<_>>(),
        "center_temperature": col(&|s| s.center),
        "pellet_surface_temperature": col(&|s| s.pellet_surface),
        "cladding_inner_temperature": col(&|s| s.cladding_inner),
        "gap": col(&|s| s.gap),
        "min_gap": col(&|s| s.min_gap),
        "interface_pressure": col(&|s| s.interface_pressure),
        "peak_interface_pressure": col(&|s| s.peak_pressure),
        "plenum_pressure": col(&|s| s.plenum),
        "pellet_surface_displacement": col(&|s| s.displacement),
        "newton_iterations": rows.iter().map(|r| r.2).collect::<Vec<_>>(),
        "linear_iterations": rows.iter().map(|r| r.3).collect::<Vec<_>>(),
        "step_cuts": rows.iter().map(|r| r.4).collect::<Vec<_>>(),
    });
    // A stack's lands, where it has them.
    if rows.first().is_some_and(|r| !r.1.land_min_gap.is_nan()) {
        history["land_min_gap"] = json!(col(&|s| s.land_min_gap));
        history["land_peak_contact_pressure"] = json!(col(&|s| s.land_peak_pressure));
    }
    history
}

/// The VTU files of the state `x` at `time`: the bodies (temperature, displacement vector,
/// von Mises stress) in `pellet_NNNN.vtu`, the interface (the pellet's surface: gap, heat
/// flux, contact and interface pressure) in `interface_NNNN.vtu`.
fn write_snapshot<TL: ConstraintLaw, ML: ConstraintLaw>(
    out: &Path,
    problem: &GapThermoMechanics<TL, ML>,
    x: &[f64],
    time: f64,
    files: &mut Vec<(String, f64)>,
    outputs: &mut Vec<(String, Vec<u8>)>,
) -> Result<(), PelletError> {
    let f = problem.fields(x);
    let elastic = problem.elastic_bodies();
    let mut von_mises = Vec::new();
    let mut displacement = Vec::new();
    for b in 0..2 {
        let u = f.displacement(b);
        let dim = elastic[b].components();
        von_mises.push(super::stress::stress_field(problem, &f, b, time)?.von_mises);
        displacement.push(
            u.chunks(dim)
                .flat_map(|c| [c[0], c[1], if dim == 3 { c[2] } else { 0.0 }])
                .collect::<Vec<f64>>(),
        );
    }
    let k = files.len();
    let name = format!("pellet_{k:04}.vtu");
    let pieces: Vec<VtuPiece> = (0..2)
        .map(|b| VtuPiece {
            mesh: &elastic[b].mesh,
            point_data: vec![
                ("temperature", f.temperature[b]),
                ("von_mises", &von_mises[b]),
            ],
        })
        .collect();
    let vectors = [(
        "displacement",
        displacement.iter().map(Vec::as_slice).collect::<Vec<_>>(),
    )];
    let text = vtu_string_with_vectors(&out.join(&name), &pieces, &vectors)?;
    outputs.push((name.clone(), text.into_bytes()));

    // The interface, one value per slave surface node (NaN off the coupling's rows).
    let surface = problem.heat().tie().interface().slave();
    let row_of = |node: usize| {
        problem
            .heat()
            .tie()
            .coupling()
            .slave_nodes
            .binary_search(&surface.node_tags()[node])
            .ok()
    };
    let gaps = problem.gaps(x);
    let (flux, pressure) = (f.flux(), f.contact_pressure());
    let per_node = |v: &dyn Fn(usize) -> f64| -> Vec<f64> {
        (0..surface.node_count())
            .map(|i| row_of(i).map_or(f64::NAN, v))
            .collect()
    };
    let fields = [
        ("gap", per_node(&|j| gaps[j])),
        ("heat_flux", per_node(&|j| flux[j])),
        ("contact_pressure", per_node(&|j| pressure[j])),
        (
            "interface_pressure",
            per_node(&|j| pressure[j] + f.gas_pressure),
        ),
    ];
    let cells: Vec<_> = (0..surface.face_count())
        .map(|i| {
            let face = surface.face(i);
            (face.element, face.nodes.to_vec())
        })
        .collect();
    let data: Vec<(&str, &[f64])> = fields.iter().map(|(n, v)| (*n, v.as_slice())).collect();
    let iname = format!("interface_{k:04}.vtu");
    let text = surface_vtu_string(&out.join(&iname), surface.coords(), &cells, &data)?;
    outputs.push((iname, text.into_bytes()));
    files.push((name, time));
    Ok(())
}
