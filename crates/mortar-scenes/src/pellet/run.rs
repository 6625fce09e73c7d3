//! Running the pellet scene: meshes, problem, time loop, outputs.

use std::path::Path;

use serde_json::Value;

use super::thermal::run_thermal;
use super::{PelletError, PelletScene};

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
