//! `run_scene_text`: a scene (TOML text, as `mortar run` reads it) run through the library's
//! scene runners, its report returned as JSON text.

use std::path::{Path, PathBuf};

use mortar::extend::Registries;
use mortar::io::write_outputs;
use mortar_scenes::file::{
    contact::ContactSpec, scene_kind, tied_heat::TiedHeatSpec, FileSystem, SceneOutput,
};
use mortar_scenes::pellet;
use pyo3::prelude::*;

use crate::errors::{self, Kind};

/// A scene's failure: the exception class and the message.
type Failure = (Kind, String);

fn scene_error(e: impl std::fmt::Display) -> Failure {
    (Kind::Scene, e.to_string())
}

/// The report of a file scene (tied heat, contact), its files written into `out` if given.
fn run_file_scene(
    output: SceneOutput,
    out: Option<&Path>,
) -> Result<(String, Vec<String>), Failure> {
    if let Some(dir) = out {
        let files: Vec<(&str, Vec<u8>)> = output
            .files
            .iter()
            .map(|(n, b)| (n.as_str(), b.clone()))
            .collect();
        write_outputs(dir, &files).map_err(|e| (Kind::MeshFile, e.to_string()))?;
    }
    let report = output
        .files
        .iter()
        .find(|(n, _)| n == "report.json")
        .map(|(_, b)| String::from_utf8_lossy(b).into_owned())
        .ok_or_else(|| scene_error("the scene wrote no report.json"))?;
    Ok((report, output.warnings))
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

/// Runs a scene named `path` in messages, its mesh paths relative to `base`.
fn run(
    text: &str,
    path: &Path,
    base: &Path,
    out: Option<&Path>,
) -> Result<(String, Vec<String>), Failure> {
    let registries = Registries::default();
    let kind = scene_kind(text, path).map_err(scene_error)?;
    match kind.as_str() {
        "pellet" => {
            let (dir, scratch) = match out {
                Some(d) => (d.to_path_buf(), false),
                None => (scratch_dir()?, true),
            };
            let report = pellet::run_from_toml_with(text, base, &dir, false, &registries.laws)
                .map_err(|e| scene_error(format!("{}: {e}", path.display())));
            if scratch {
                // Best effort: a scratch folder left behind is only untidy.
                let _ = std::fs::remove_dir_all(&dir);
            }
            Ok((report?.to_string(), Vec::new()))
        }
        "tied_heat" => {
            let spec = TiedHeatSpec::parse(text, path).map_err(scene_error)?;
            let output = spec
                .run_with(path, base, &FileSystem, &registries)
                .map_err(scene_error)?;
            run_file_scene(output, out)
        }
        "contact" => {
            let spec = ContactSpec::parse(text, path).map_err(scene_error)?;
            let output = spec
                .run_with(path, base, &FileSystem, &registries)
                .map_err(scene_error)?;
            run_file_scene(output, out)
        }
        other => Err(scene_error(format!(
            "{}: kind: unknown scene kind \"{other}\" (known kinds: tied_heat, contact, pellet)",
            path.display()
        ))),
    }
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
