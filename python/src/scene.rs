//! `run_scene_text`: a scene (TOML text, as `mortar run` reads it) run through the library's
//! scene runners, its report returned as JSON text.

use std::path::{Path, PathBuf};

use mortar::extend::Registries;
use mortar_scenes::file::FileSystem;
use mortar_scenes::{run_scene, SceneContext};
use pyo3::prelude::*;

use crate::errors::{self, Kind};

/// A scene's failure: the exception class and the message.
type Failure = (Kind, String);

fn scene_error(e: impl std::fmt::Display) -> Failure {
    (Kind::Scene, e.to_string())
}

/// A fresh folder under the system's temporary folder, for a scene that must write its
/// outputs somewhere when the caller wants none kept.
fn scratch_dir() -> Result<PathBuf, Failure> {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let dir = std::env::temp_dir().join(format!("mortar-scene-{}-{nanos}", std::process::id()));
    std::fs::create_dir_all(&dir)
        .map_err(|e| scene_error(format!("cannot create {}: {e}", dir.display())))?;
    Ok(dir)
}

/// Runs a scene named `path` in messages, its mesh paths relative to `base`, through the
/// scenes' one dispatch ([`run_scene`]): its outputs are written into `out`, or into a scratch
/// folder removed afterwards when `out` is `None`. Returns the report as JSON text and the
/// coupling's warnings.
fn run(
    text: &str,
    path: &Path,
    base: &Path,
    out: Option<&Path>,
) -> Result<(String, Vec<String>), Failure> {
    let registries = Registries::default();
    let (dir, scratch) = match out {
        Some(d) => (d.to_path_buf(), false),
        None => (scratch_dir()?, true),
    };
    let ctx = SceneContext {
        path,
        base,
        source: &FileSystem,
        registries: &registries,
        out: &dir,
        progress: false,
    };
    let run = run_scene(text, &ctx).map_err(scene_error);
    if scratch {
        // Best effort: a scratch folder left behind is only untidy.
        let _ = std::fs::remove_dir_all(&dir);
    }
    let run = run?;
    Ok((run.report_json, run.warnings))
}

/// Runs the scene `text` (TOML, or JSON when `json` is true: a dict from Python) named `path`
/// in messages and the report, whose mesh paths are relative to `base` (the folder of `path`
/// when not given); writes its outputs into `out` if given. Returns the report as JSON text
/// and the coupling warnings.
#[pyfunction]
#[pyo3(signature = (text, path, out = None, json = false, base = None))]
pub(crate) fn run_scene_text(
    py: Python<'_>,
    text: String,
    path: PathBuf,
    out: Option<PathBuf>,
    json: bool,
    base: Option<PathBuf>,
) -> PyResult<(String, Vec<String>)> {
    let base = base.unwrap_or_else(|| path.parent().unwrap_or(Path::new("")).to_path_buf());
    let result = py.detach(|| {
        errors::no_panic(|| {
            let text = if json {
                let value: toml::Value = serde_json::from_str(&text)
                    .map_err(|e| (Kind::InvalidInput, format!("scene dict: {e}")))?;
                toml::to_string(&value)
                    .map_err(|e| (Kind::InvalidInput, format!("scene dict: {e}")))?
            } else {
                text
            };
            run(&text, &path, &base, out.as_deref())
        })
        .unwrap_or_else(|m| Err((Kind::Base, m)))
    });
    result.map_err(|(k, m)| errors::raise(k, m))
}
