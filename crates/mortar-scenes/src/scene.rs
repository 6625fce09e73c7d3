//! One interface for every scene: a [`Scene`] is parsed and checked from its scene file, then
//! run in a [`SceneContext`] (where its meshes come from, the elements and laws it may name,
//! where it writes, whether it shows progress), giving a [`SceneRun`] (its report, the files
//! it wrote, a readable summary, the coupling's warnings). Tied heat, contact and the pellet
//! implement it; [`run_scene`] picks the implementation by the file's `kind`, the one dispatch
//! of the `mortar` command and of Python. A run stops at its next step when
//! [`interrupt::request`](crate::interrupt::request) is called, and shows its progress
//! through [`progress::display`](crate::progress::display) when asked.
//!
//! ```no_run
//! use std::path::Path;
//! use mortar::extend::Registries;
//! use mortar_scenes::file::FileSystem;
//! use mortar_scenes::{run_scene, SceneContext};
//!
//! let path = Path::new("examples/scenes/tied_square.toml");
//! let text = std::fs::read_to_string(path)?;
//! let registries = Registries::default();
//! let ctx = SceneContext {
//!     path,
//!     base: Path::new("examples/scenes"),
//!     source: &FileSystem,
//!     registries: &registries,
//!     out: Path::new("out/tied_square"),
//!     progress: false,
//! };
//! let run = run_scene(&text, &ctx)?;
//! println!("{} wrote {:?}", run.kind, run.files);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::path::Path;

use mortar::extend::Registries;
use mortar::io::write_outputs;
use serde_json::Value;

use crate::file::contact::ContactSpec;
use crate::file::tied_heat::TiedHeatSpec;
use crate::file::{scene_kind, FileScene, SceneError, SceneOutput, SceneSource};
use crate::pellet::PelletScene;

/// Where and how a scene runs.
#[derive(Clone, Copy)]
pub struct SceneContext<'a> {
    /// The scene file, named in messages and in the report.
    pub path: &'a Path,
    /// The folder its mesh paths are relative to (the scene file's).
    pub base: &'a Path,
    /// Where its mesh files come from (the file system, or files in memory).
    pub source: &'a dyn SceneSource,
    /// The elements, cells and laws it may name (the shipped ones and a program's own).
    pub registries: &'a Registries,
    /// The folder it writes its outputs into (created if needed).
    pub out: &'a Path,
    /// Whether to show its progress ([`progress::display`](crate::progress::display)).
    pub progress: bool,
}

/// What a run gave.
#[derive(Debug, Clone)]
pub struct SceneRun {
    /// The scene's kind (`"tied_heat"`, `"contact"`, `"pellet"`).
    pub kind: &'static str,
    /// The report, as written to `report.json`.
    pub report: Value,
    /// The report's text, as written to `report.json` (to the last digit: a value read back
    /// from the text may differ from it in its last bit).
    pub report_json: String,
    /// The names of the files written into the output folder.
    pub files: Vec<String>,
    /// A few lines for the terminal (empty where the report says it all: the pellet).
    pub summary: String,
    /// The coupling's warnings (uncovered slave area, overlapping master faces, skipped
    /// pairs), also in the report.
    pub warnings: Vec<String>,
}

/// A problem described by a scene file of `kind = KIND`.
pub trait Scene: Sized {
    /// The scene files' `kind`.
    const KIND: &'static str;

    /// Parses and checks the scene file's `text` (named `ctx.path`; relative paths against
    /// `ctx.base`).
    ///
    /// # Errors
    /// [`SceneError`] naming the key or the line of what does not fit.
    fn parse_in(text: &str, ctx: &SceneContext) -> Result<Self, SceneError>;

    /// Runs the scene, writing its outputs into `ctx.out`.
    ///
    /// # Errors
    /// [`SceneError`] naming the file, the key, the mesh and group, or the solve that failed.
    fn run_in(&self, ctx: &SceneContext) -> Result<SceneRun, SceneError>;
}

/// Writes a scene's output held in memory (its files, among them `report.json`) into
/// `ctx.out`, all or none, as the run of a scene of `kind`: what [`Scene::run_in`] gives for the
/// scene files, and for a built-in scene run apart (the contact benchmarks of
/// [`run_builtin_contact`](crate::file::run_builtin_contact)).
///
/// # Errors
/// [`SceneError::Other`] for a file that cannot be written.
pub fn write_scene_output(
    kind: &'static str,
    output: SceneOutput,
    ctx: &SceneContext,
) -> Result<SceneRun, SceneError> {
    let files: Vec<(&str, Vec<u8>)> = output
        .files
        .iter()
        .map(|(n, b)| (n.as_str(), b.clone()))
        .collect();
    write_outputs(ctx.out, &files).map_err(|e| SceneError::Other(e.to_string()))?;
    let report_json = output
        .files
        .iter()
        .find(|(n, _)| n == "report.json")
        .map(|(_, b)| String::from_utf8_lossy(b).into_owned())
        .unwrap_or_default();
    Ok(SceneRun {
        kind,
        report: serde_json::from_str(&report_json).unwrap_or(Value::Null),
        report_json,
        files: output.files.into_iter().map(|(n, _)| n).collect(),
        summary: output.summary,
        warnings: output.warnings,
    })
}

/// Every scene file of two bodies is a scene: parsed and checked by [`FileScene::parse`], run
/// by [`FileScene::run_with`] with the context's cells and laws, its output written into
/// `ctx.out`.
impl<S: FileScene> Scene for S {
    const KIND: &'static str = <S as FileScene>::KIND;

    fn parse_in(text: &str, ctx: &SceneContext) -> Result<Self, SceneError> {
        <S as FileScene>::parse(text, ctx.path)
    }

    fn run_in(&self, ctx: &SceneContext) -> Result<SceneRun, SceneError> {
        let output =
            <S as FileScene>::run_with(self, ctx.path, ctx.base, ctx.source, ctx.registries)?;
        write_scene_output(<S as Scene>::KIND, output, ctx)
    }
}

impl Scene for PelletScene {
    const KIND: &'static str = "pellet";

    fn parse_in(text: &str, ctx: &SceneContext) -> Result<Self, SceneError> {
        PelletScene::from_toml_in(text, ctx.base).map_err(|e| pellet_error(ctx, e))
    }

    /// The pellet writes as it goes (its snapshots over time, and on a failure what it had
    /// with `"status": "failed"`); its mesh file, if any, is read from the file system.
    fn run_in(&self, ctx: &SceneContext) -> Result<SceneRun, SceneError> {
        let report =
            crate::pellet::run_with_laws(self, &ctx.registries.laws, ctx.out, ctx.progress)
                .map_err(|e| pellet_error(ctx, e))?;
        let mut files: Vec<String> = std::fs::read_dir(ctx.out)
            .map(|d| {
                d.filter_map(|e| e.ok().map(|e| e.file_name().to_string_lossy().into_owned()))
                    .filter(|n| crate::pellet::is_output(n))
                    .collect()
            })
            .unwrap_or_default();
        files.sort();
        let warnings = report["coupling_warnings"]
            .as_array()
            .map(|a| {
                a.iter()
                    .filter_map(|w| w.as_str().map(str::to_string))
                    .collect()
            })
            .unwrap_or_default();
        Ok(SceneRun {
            kind: Self::KIND,
            report_json: report.to_string(),
            report,
            files,
            summary: String::new(),
            warnings,
        })
    }
}

/// A pellet scene's error as a scene error, naming the scene file.
fn pellet_error(ctx: &SceneContext, e: crate::pellet::PelletError) -> SceneError {
    SceneError::Pellet {
        path: ctx.path.to_path_buf(),
        source: Box::new(e),
    }
}

/// Parses and runs `text` as the scene its `kind` names: the one dispatch over the kinds.
///
/// # Errors
/// [`SceneError::Invalid`] (key `kind`) for a missing or unknown kind, listing the known
/// ones; the errors of the scene's [`Scene::parse_in`] and [`Scene::run_in`].
pub fn run_scene(text: &str, ctx: &SceneContext) -> Result<SceneRun, SceneError> {
    fn go<S: Scene>(text: &str, ctx: &SceneContext) -> Result<SceneRun, SceneError> {
        S::parse_in(text, ctx)?.run_in(ctx)
    }
    match scene_kind(text, ctx.path)?.as_str() {
        <TiedHeatSpec as Scene>::KIND => go::<TiedHeatSpec>(text, ctx),
        <ContactSpec as Scene>::KIND => go::<ContactSpec>(text, ctx),
        <PelletScene as Scene>::KIND => go::<PelletScene>(text, ctx),
        other => Err(SceneError::Invalid {
            path: ctx.path.to_path_buf(),
            key: "kind".into(),
            what: format!(
                "unknown scene kind \"{other}\" (known kinds: {}, {}, {})",
                <TiedHeatSpec as Scene>::KIND,
                <ContactSpec as Scene>::KIND,
                <PelletScene as Scene>::KIND
            ),
        }),
    }
}
