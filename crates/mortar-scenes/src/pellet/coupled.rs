//! The thermomechanical pellet: expansion, contact across the gap, gap conductance on the
//! mechanical gap, plenum pressure (docs/models.md, section 3a).

use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use mortar_physics::laws::{
    ConstraintLaw, ContactComplementarity, DynLaw, LawRegistry, RelocationModel,
};
use serde_json::Value;

use super::march::{history_plots, CoupledReport, March};
use super::outputs::{progress_bar, write_scene_outputs};
use super::problem::{complementarity, exponential_contact_law, problem_of, thermal_law};
use super::{ContactLawName, PelletError, PelletScene};

/// Runs the coupled scene (see [`run`](super::run)).
///
/// # Errors
/// As [`run`](super::run).
pub fn run_coupled(scene: &PelletScene, out: &Path, progress: bool) -> Result<Value, PelletError> {
    run_coupled_in(scene, &LawRegistry::with_shipped(), out, progress)
}

/// [`run_coupled`] with the laws and relocation models of `registry`: the laws the scene's
/// `[laws]` tables name ([`run_with_registry`]), else the scene's built-in ones under their
/// descriptive names, as [`run_coupled`] reports them.
///
/// # Errors
/// As [`run_with_registry`].
pub fn run_coupled_in(
    scene: &PelletScene,
    registry: &LawRegistry,
    out: &Path,
    progress: bool,
) -> Result<Value, PelletError> {
    if scene.laws.thermal.is_some() || scene.laws.contact.is_some() {
        return run_with_registry(scene, registry, out, progress);
    }
    let relocation = registry.relocation(&scene.model.relocation)?;
    match scene.contact.law {
        ContactLawName::Exponential => {
            let law = exponential_contact_law(scene)?;
            let onset = law.onset();
            let names = (
                "Ross-Stoute on the mechanical gap, plus h_contact p_contact",
                "exponential",
            );
            run_with(
                scene,
                (thermal_law(scene)?, law),
                names,
                Some(onset),
                &relocation,
                out,
                progress,
            )
        }
        ContactLawName::Exact => {
            let law = ContactComplementarity::try_new(complementarity(scene))?;
            let names = (
                "Ross-Stoute on the mechanical gap, plus h_contact p_contact",
                "exact",
            );
            run_with(
                scene,
                (thermal_law(scene)?, law),
                names,
                None,
                &relocation,
                out,
                progress,
            )
        }
    }
}

/// Runs the coupled scene with the laws of its `[laws]` tables made by `registry` (the shipped
/// laws and a program's own; see [`LawsData`](super::LawsData)); a law not named there is the
/// scene's built-in one, made by name too (`mechanical_gap_conductance` from `[gap]`,
/// `exponential_contact` or `contact_complementarity` from `[contact]`).
///
/// # Errors
/// [`PelletError::Law`] for an unknown name (listing the known ones), a missing parameter or
/// a value the law refuses; otherwise as [`run`](super::run).
pub fn run_with_registry(
    scene: &PelletScene,
    registry: &LawRegistry,
    out: &Path,
    progress: bool,
) -> Result<Value, PelletError> {
    // A law the scene does not name is its built-in one, under its registry name.
    let thermal = match &scene.laws.thermal {
        Some(spec) => spec.make(registry)?,
        None => DynLaw::new("mechanical_gap_conductance", thermal_law(scene)?),
    };
    let (contact, onset) = match &scene.laws.contact {
        Some(spec) => {
            let law = spec.make(registry)?;
            let onset = (spec.name == "exponential_contact")
                .then(|| spec.parameters.get("onset").copied())
                .flatten();
            (law, onset)
        }
        None => {
            let ct = &scene.contact;
            match ct.law {
                ContactLawName::Exponential => (
                    DynLaw::new("exponential_contact", exponential_contact_law(scene)?),
                    Some(ct.onset_gap),
                ),
                ContactLawName::Exact => (
                    DynLaw::new(
                        "contact_complementarity",
                        ContactComplementarity::try_new(complementarity(scene))?,
                    ),
                    None,
                ),
            }
        }
    };
    let names = (thermal.name().to_string(), contact.name().to_string());
    let relocation = registry.relocation(&scene.model.relocation)?;
    run_with(
        scene,
        (thermal, contact),
        (&names.0, &names.1),
        onset,
        &relocation,
        out,
        progress,
    )
}

/// Runs the coupled scene with a program's own interface laws in place of the scene's
/// (`[gap]` and `[contact]` then serve only the gap's search radius): everything else, the
/// solver, the report, the VTU and plots, as [`run_coupled`]. The report names the laws by
/// their Rust types; contact counts as engaged once the mean contact pressure exceeds a
/// millionth of the gas pressure.
///
/// # Errors
/// As [`run`](super::run).
pub fn run_coupled_with<TL: ConstraintLaw + Clone, ML: ConstraintLaw + Clone>(
    scene: &PelletScene,
    thermal: TL,
    contact: ML,
    out: &Path,
    progress: bool,
) -> Result<Value, PelletError> {
    let names = (std::any::type_name::<TL>(), std::any::type_name::<ML>());
    let relocation = LawRegistry::with_shipped().relocation(&scene.model.relocation)?;
    run_with(
        scene,
        (thermal, contact),
        names,
        None,
        &relocation,
        out,
        progress,
    )
}

/// The time stepping, reports and outputs of the coupled scene with contact law `law`
/// (`onset`: the exponential law's `xi`, for the time contact engages): the initial state,
/// the backward Euler steps and the steady state at full power ([`March`]), then the
/// report and the outputs.
fn run_with<TL: ConstraintLaw + Clone, ML: ConstraintLaw + Clone>(
    scene: &PelletScene,
    laws: (TL, ML),
    names: (&str, &str),
    onset: Option<f64>,
    relocation: &Arc<dyn RelocationModel>,
    out: &Path,
    progress: bool,
) -> Result<Value, PelletError> {
    let start = Instant::now();
    // A mesh file's radii and height replace the scene's everywhere below.
    let (scene, file) = scene.resolved()?;
    let scene = &scene;
    let problem = problem_of(scene, file.as_ref(), laws.0, laws.1, relocation)?;
    let setup_seconds = start.elapsed().as_secs_f64();
    let linear = scene.solver.linear_solver(problem.dimension())?;
    let choice = scene.solver.choose_with(
        scene
            .solver
            .choose(true, scene.model.geometry.is_plane(), problem.dimension()),
        &linear,
    );
    let steps = scene.time.steps();
    let bar = progress_bar(progress, steps as u64 + 1);
    let mut march = March::new(scene, &problem, (&choice, &linear), out);
    march.initial()?;
    for k in 1..=steps {
        if let Err(e) = march.step(k) {
            bar.finish_and_clear();
            return Err(e);
        }
        let s = march.rows.last().expect("the step's row").1;
        bar.set_message(format!(
            "t = {:.1} s, T0 = {:.0} K, gap = {:.2} um",
            march.time,
            s.center,
            s.gap * 1e6
        ));
        bar.inc(1);
    }
    let transient_stats = march.solver.stats;
    let steady = march.steady();
    bar.inc(1);
    bar.finish_and_clear();
    let t_steady = steady?;
    let report = CoupledReport {
        scene,
        file: file.as_ref(),
        names,
        onset,
        relocation,
        choice: &choice,
        transient_stats,
        t_steady,
        seconds: (setup_seconds, start),
    }
    .json(&march)?;
    let March {
        mut outputs, rows, ..
    } = march;
    outputs.extend(history_plots(&rows)?);
    let text = serde_json::to_string_pretty(&report).expect("JSON values serialise");
    outputs.push(("report.json".to_string(), text.into_bytes()));
    write_scene_outputs(out, outputs)?;
    Ok(report)
}
