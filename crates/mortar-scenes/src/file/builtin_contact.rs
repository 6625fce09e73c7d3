//! The built-in contact scenes (`mortar run --scene hertz2d|hertz3d|shrink_fit`): each made
//! as a scene file and its meshes ([`ContactSceneFiles`]), solved from those files, written
//! with them (`scene.toml`, `NAME.msh`), with a VTU per body and `interface.vtu`, and with a
//! `report.json` that compares the solution with its closed form.

use std::path::Path;
use std::time::Instant;

use mortar_physics::contact::ContactStep;
use mortar_physics::PhysicsError;

use super::contact::{steps_json, ContactSpec, SolvedContact};
use super::contact_files::ContactSceneFiles;
use super::contact_files::SCENE_FILE;
use super::two_bodies::report_bytes;
use super::FileScene;
use super::{SceneError, SceneOutput, SolvedScene};
use crate::hertz::{HertzProblem, HertzRun, HertzSphereRun};
use crate::linear_solver::{with_backend, BackendChoice};
use crate::shrink_fit::{ShrinkFitRun, ShrinkFitSolved};

/// The built-in contact scenes ([`BUILTIN_CONTACT_SCENES`](super::BUILTIN_CONTACT_SCENES)),
/// made as scene files with meshes and solved from them: `hertz2d`
/// ([`crate::hertz::HertzScene::new`]`(HERTZ_ARC_CELLS)`), `hertz3d`
/// ([`crate::hertz::HertzSphereScene::default`], compared with the closed form both at
/// the imposed approach and at the computed load) and `shrink_fit`
/// ([`crate::shrink_fit::ShrinkFitScene::new`]`(32, 32)`). `None` for another name.
/// Their `report.json` carries the inputs and the closed-form values beside the computed
/// ones, the contact steps, and under `"scene"` the report of the scene file's run; the
/// files are that run's (a VTU per body, `interface.vtu`), the scene file `scene.toml` and
/// the meshes.
///
/// # Errors
/// [`SceneError::Other`] if the scene cannot be built or solved.
pub fn run_builtin_contact(name: &str) -> Result<Option<SceneOutput>, SceneError> {
    run_builtin_contact_on(name, None)
}

/// [`run_builtin_contact`] with the scene file's `[solve] backend` set to `backend` (`None`:
/// the scene's own, `"auto"`), in the scene file written beside the results too.
///
/// # Errors
/// As [`run_builtin_contact`]; [`SceneError::Invalid`] (key `solve.backend`) for PETSc in a
/// build without it.
pub fn run_builtin_contact_on(
    name: &str,
    backend: Option<BackendChoice>,
) -> Result<Option<SceneOutput>, SceneError> {
    let t = Instant::now();
    let run = match name {
        "hertz2d" => hertz2d(t, backend)?,
        "hertz3d" => hertz3d(t, backend)?,
        "shrink_fit" => shrink_fit(t, backend)?,
        _ => return Ok(None),
    };
    run.into_output(t).map(Some)
}

/// A built-in contact scene run from its files: the files, the scene file's outputs, and
/// the built-in's own report and summary.
struct BuiltinRun {
    files: ContactSceneFiles,
    output: SceneOutput,
    report: serde_json::Value,
    summary: String,
}

impl BuiltinRun {
    /// The outputs of the built-in scene (started at `t`): the scene file's own, its report
    /// under `"scene"` of the built-in's report; the scene file and meshes beside them.
    fn into_output(self, t: Instant) -> Result<SceneOutput, SceneError> {
        let Self {
            files,
            output,
            mut report,
            summary,
        } = self;
        // The scene file's own report goes under "scene"; its warnings are the built-in's.
        let mut out = Vec::with_capacity(output.files.len() + files.meshes.len() + 1);
        for (name, bytes) in output.files {
            if name == "report.json" {
                let scene: serde_json::Value = serde_json::from_slice(&bytes)
                    .map_err(|e| SceneError::Other(format!("report.json: {e}")))?;
                report["scene"] = scene;
            } else {
                out.push((name, bytes));
            }
        }
        out.extend(files.files());
        report["warnings"] = serde_json::json!(output.warnings);
        report["seconds"]["total"] = serde_json::json!(t.elapsed().as_secs_f64());
        let json =
            report_bytes(&report).map_err(|e| SceneError::Other(format!("report.json: {e}")))?;
        out.push(("report.json".to_string(), json));
        Ok(SceneOutput {
            files: out,
            summary,
            warnings: output.warnings,
        })
    }
}

/// A built-in scene's physics error, naming the scene.
fn fail(name: &str) -> impl Fn(PhysicsError) -> SceneError + '_ {
    move |e| SceneError::Other(format!("built-in scene {name}: {e}"))
}

/// `hertz2d` (started at `t`): the cylinder on the block, its half-width, peak pressure and
/// profile against the closed form.
fn hertz2d(t: Instant, backend: Option<BackendChoice>) -> Result<BuiltinRun, SceneError> {
    let fail = fail("hertz2d");
    let scene = crate::hertz::HertzScene::new(HERTZ_ARC_CELLS);
    let closed = scene.closed_form();
    let (files, solved, output) = solve(scene.scene_files(), backend)?;
    let seconds = t.elapsed().as_secs_f64();
    let (problem, sol) =
        HertzProblem::from_solved(solved, scene.block_cell_count()).map_err(fail)?;
    let run = scene.evaluate(&problem, &sol, seconds);
    let mut report = serde_json::json!({
        "kind": "contact",
        "scene": "hertz2d",
        "title": "2D Hertz contact: a cylinder on a block (plane strain, half model)",
        "dimension": 2,
        "inputs": {
            "R": scene.radius,
            "E_star": closed.contact_modulus,
            "d": scene.approach,
            "arc_cells": run.arc_cells,
            "block_cells": run.block_cells,
        },
        "P": run.load,
        "computed": {
            "a": run.half_width.estimate,
            "a_bracket": [run.half_width.last_in_contact, run.half_width.first_open],
            "a_squared": run.half_width.squared,
            "p0": run.peak,
        },
        "closed_form": { "a": run.a_exact, "p0": run.p0_exact },
        "error": {
            "a": run.half_width_error(),
            "a_squared": (run.half_width.squared - run.a_exact) / run.a_exact,
            "p0": run.peak_error(),
            "profile_l2": run.profile_l2,
            "equilibrium": run.equilibrium_error(),
        },
        "contact_force": run.force,
    });
    solve_figures(&mut report, &run);
    let summary = format!(
        "hertz2d: P = {:.6e} N/m; a = {:.6e} m (closed form {:.6e}, {:+.2e}); p0 = {:.6e} Pa (closed form {:.6e}, {:+.2e})",
        run.load,
        run.half_width.estimate,
        run.a_exact,
        run.half_width_error(),
        run.peak,
        run.p0_exact,
        run.peak_error()
    );
    Ok(BuiltinRun {
        files,
        output,
        report,
        summary,
    })
}

/// `hertz3d` (started at `t`): the sphere on the block, compared with the closed form at the
/// imposed approach and at the computed load.
fn hertz3d(t: Instant, backend: Option<BackendChoice>) -> Result<BuiltinRun, SceneError> {
    let fail = fail("hertz3d");
    let scene = crate::hertz::HertzSphereScene::default();
    let closed = scene.closed_form();
    let (files, solved, output) = solve(scene.scene_files(), backend)?;
    let seconds = t.elapsed().as_secs_f64();
    // Building: reading the files, the coupling and the assembly.
    let build: f64 = solved.seconds()[..3].iter().map(|(_, s)| s).sum();
    let (problem, sol) =
        HertzProblem::from_solved(solved, scene.block_cell_count()).map_err(fail)?;
    let run = scene.evaluate(&problem, &sol, [build, seconds]);
    let bracket = |h: &crate::hertz::HalfWidth| [h.last_in_contact, h.first_open];
    let closed_json = |c: &crate::hertz::HertzContact| serde_json::json!({ "a": c.radius, "p0": c.peak, "P": c.load, "d": c.approach });
    let mut report = serde_json::json!({
        "kind": "contact",
        "scene": "hertz3d",
        "title": "3D Hertz contact: a sphere on a block (quarter model, Hex8)",
        "dimension": 3,
        "inputs": {
            "R": scene.radius,
            "E_star": closed.contact_modulus,
            "d": scene.approach,
            "E": scene.sphere.youngs_modulus,
            "nu": scene.sphere.poisson_ratio,
            "block_size": scene.block_size * scene.radius,
            "cells": run.cells,
            "block_cells": run.block_cells,
        },
        "P": run.load,
        "computed": {
            "a": run.contact_radius.estimate,
            "a_bracket": bracket(&run.contact_radius),
            "a_bracket_along_y0": bracket(&run.contact_radius_axis),
            "a_squared": run.contact_radius.squared,
            "p0": run.peak,
            "P": run.load,
        },
        "closed_form": {
            "at_d": closed_json(&run.at_approach),
            "at_P": closed_json(&run.at_load),
        },
        "element_at_a": { "at_d": run.edge_cell, "at_P": run.edge_cell_at_load },
        "error": {
            "at_d": {
                "a": run.radius_error_at_approach(),
                "a_in_elements": (run.contact_radius.estimate - run.at_approach.radius) / run.edge_cell,
                "p0": run.peak_error_at_approach(),
                "P": run.load_error_at_approach(),
            },
            "at_P": {
                "a": run.radius_error_at_load(),
                "a_in_elements": (run.contact_radius.estimate - run.at_load.radius) / run.edge_cell_at_load,
                "p0": run.peak_error_at_load(),
                "profile_l2": run.profile_l2,
            },
            "equilibrium": run.equilibrium_error(),
        },
        "slave_nodes": run.slave_nodes,
        "unknowns": run.unknowns,
        "contact_force": run.force,
        "seconds": { "build": run.seconds_build },
    });
    solve_figures(&mut report, &run);
    let summary = format!(
        "hertz3d: d = {:.6e} m, P = {:.6e} N ({:+.2e} off the closed form at d); a = {:.6e} m (closed form {:.6e} at d, {:.6e} at P); p0 = {:.6e} Pa (closed form {:.6e} at d, {:+.2e}; {:.6e} at P, {:+.2e})",
        scene.approach,
        run.load,
        run.load_error_at_approach(),
        run.contact_radius.estimate,
        run.at_approach.radius,
        run.at_load.radius,
        run.peak,
        run.at_approach.peak,
        run.peak_error_at_approach(),
        run.at_load.peak,
        run.peak_error_at_load()
    );
    Ok(BuiltinRun {
        files,
        output,
        report,
        summary,
    })
}

/// `shrink_fit` (started at `t`): the disc in the ring, its contact pressure against Lamé's.
fn shrink_fit(t: Instant, backend: Option<BackendChoice>) -> Result<BuiltinRun, SceneError> {
    let scene = crate::shrink_fit::ShrinkFitScene::new(32, 32);
    let (files, solved, output) = solve(scene.scene_files(), backend)?;
    let seconds = t.elapsed().as_secs_f64();
    let run = scene.evaluate(
        ShrinkFitSolved {
            slave: &solved.bodies[0],
            master_nodes: solved.bodies[1].mesh.node_count(),
            tie: &solved.tie,
            gap: &solved.gap,
            complementarity: solved
                .complementarity
                .ok_or_else(|| SceneError::Other("shrink_fit: solved with another law".into()))?,
        },
        solved.solution.clone(),
        seconds,
    );
    let fit = scene.fit;
    let mut report = serde_json::json!({
        "kind": "contact",
        "scene": "shrink_fit",
        "title": "shrink fit: a disc in a ring (plane strain, quarter model)",
        "dimension": 2,
        "inputs": {
            "b": fit.inner,
            "c": fit.outer,
            "delta": fit.interference,
            "E": fit.material.youngs_modulus,
            "nu": fit.material.poisson_ratio,
            "slave_cells": scene.slave_cells,
            "master_cells": scene.master_cells,
        },
        "computed": { "p_mean": run.mean, "p_min": run.min, "p_max": run.max },
        "closed_form": { "p": run.exact, "p_faceted": run.faceted_pressure },
        "error": { "worst": run.worst_error(), "mean": run.mean_error() },
    });
    solve_figures(&mut report, &run);
    let summary = format!(
        "shrink_fit: p mean {:.6e} Pa in [{:.6e}, {:.6e}] (closed form {:.6e}, mean error {:+.2e})",
        run.mean,
        run.min,
        run.max,
        run.exact,
        run.mean_error()
    );
    Ok(BuiltinRun {
        files,
        output,
        report,
        summary,
    })
}

/// A built-in contact scene's evaluated run: its load steps, its active slave nodes, its
/// complementarity residual and its solve's seconds.
trait ContactRun {
    fn figures(&self) -> (&[ContactStep], usize, f64, f64);
}

/// [`ContactRun`] of run types with the fields `steps`, `active`, `complementarity`, `seconds`.
macro_rules! contact_run {
    ($($run:ty),*) => {
        $(impl ContactRun for $run {
            fn figures(&self) -> (&[ContactStep], usize, f64, f64) {
                (&self.steps, self.active, self.complementarity, self.seconds)
            }
        })*
    };
}

contact_run!(HertzRun, HertzSphereRun, ShrinkFitRun);

/// The figures of the solve that every built-in contact scene reports, added to `report`: the
/// load steps, the active slave nodes, the complementarity residual and the solve's seconds
/// (the total is added with the outputs).
fn solve_figures(report: &mut serde_json::Value, run: &impl ContactRun) {
    let (steps, active, complementarity, seconds) = run.figures();
    report["load_steps"] = serde_json::json!(steps_json(steps));
    report["active"] = serde_json::json!(active);
    report["complementarity"] = serde_json::json!(complementarity);
    report["seconds"]["run"] = serde_json::json!(seconds);
}

/// The scene files made, solved from and rendered.
fn solve(
    files: Result<ContactSceneFiles, SceneError>,
    backend: Option<BackendChoice>,
) -> Result<(ContactSceneFiles, SolvedContact, SceneOutput), SceneError> {
    let mut files = files?;
    if let Some(b) = backend {
        files.toml = with_backend(&files.toml, b).map_err(SceneError::Other)?;
        files.spec = ContactSpec::parse(&files.toml, Path::new(SCENE_FILE))?;
    }
    let solved = files.solve()?;
    let output = solved.output()?;
    Ok((files, solved, output))
}

/// Arc cells of the built-in `hertz2d`: fine enough for the half-width estimate (the midpoint
/// of the bracketing slave face) to be within 2 % of the closed form.
pub const HERTZ_ARC_CELLS: usize = 96;
