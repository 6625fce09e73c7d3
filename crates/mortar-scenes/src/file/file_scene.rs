//! What the two-body scene files ([`TiedHeatSpec`](super::tied_heat::TiedHeatSpec) and
//! [`ContactSpec`](super::contact::ContactSpec)) have in common as types: a scene parsed and
//! checked from its TOML text, written back as TOML, solved from its meshes, and the solved
//! scene rendered into its output files. Each kind gives its check, its solve and its
//! rendering; the wrappers around them are written once here.
//!
//! ```no_run
//! use std::path::Path;
//! use mortar_scenes::file::tied_heat::TiedHeatSpec;
//! use mortar_scenes::file::{FileScene, FileSystem};
//!
//! let path = Path::new("examples/scenes/tied_square.toml");
//! let spec = TiedHeatSpec::parse(&std::fs::read_to_string(path)?, path)?;
//! let output = spec.run(path, Path::new("examples/scenes"), &FileSystem)?;
//! println!("{}", output.summary);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Every `FileScene` is also a [`Scene`](crate::Scene), whose methods have other names
//! ([`parse_in`](crate::Scene::parse_in), [`run_in`](crate::Scene::run_in)) so that both
//! traits may be imported together; their constants `KIND` are the same.

use std::path::Path;
use std::time::Instant;

use mortar::extend::Registries;
use mortar::io::GmshVolume;
use serde::de::DeserializeOwned;
use serde::Serialize;

use super::error::Errors;
use super::two_bodies::MeshSource;
use super::{SceneError, SceneOutput, SceneSource};

/// A two-body scene's meshes, read: what [`FileScene::solve_read`] solves.
pub struct ReadScene<'a> {
    /// The scene file, named in messages and in the report.
    pub path: &'a Path,
    /// The two bodies' names and cells, slave first, of one dimension.
    pub volumes: [(String, GmshVolume); 2],
    /// The cells and laws (the shipped ones and a program's own).
    pub registries: &'a Registries,
    /// When the solve started: the meshes' reading counts in the scene's timings.
    pub started: Instant,
}

/// A solved scene, ready to render.
pub trait SolvedScene {
    /// The files to write into the output folder (among them `report.json`), a readable
    /// summary and the coupling's warnings.
    ///
    /// # Errors
    /// [`SceneError::Other`] if a file cannot be rendered.
    fn output(&self) -> Result<SceneOutput, SceneError>;
}

/// A scene file of two bodies read from Gmsh files: its check and its solve, and the parse,
/// TOML text, solve and run built on them.
pub trait FileScene: Serialize + DeserializeOwned {
    /// The scene files' `kind`.
    const KIND: &'static str;

    /// The solved scene.
    type Solved: SolvedScene;

    /// Checks values and cross-references that do not need the meshes.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming the key.
    fn check(&self, path: &Path) -> Result<(), SceneError>;

    /// The two bodies' `(name, mesh file, physical group)`, slave first, as the scene names
    /// them (the mesh paths relative to the scene file's folder).
    fn sides(&self) -> [(&str, &Path, &str); 2];

    /// Builds and solves the problem from the bodies' meshes, read and of one dimension,
    /// without rendering.
    ///
    /// # Errors
    /// [`SceneError`] naming the key, the file and the group, or the solve that failed (see
    /// each kind).
    fn solve_read(&self, read: ReadScene<'_>) -> Result<Self::Solved, SceneError>;

    /// Reads the meshes of [`sides`](Self::sides) (through `source`, paths relative to
    /// `base`, the scene file's folder) with the cells of `registries` (the shipped ones and
    /// a program's own), checks that they are of one dimension and
    /// [`solve_read`](Self::solve_read)s them with the laws of `registries`. `path` names the
    /// scene file in messages and in the report.
    ///
    /// # Errors
    /// [`SceneError::Mesh`] for a missing mesh file, a missing group or a group of the wrong
    /// dimension (naming the key, the file and the group); [`SceneError::Invalid`] (key
    /// `bodies`) for bodies of different dimensions; as [`solve_read`](Self::solve_read)
    /// otherwise.
    fn solve_with(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
        registries: &Registries,
    ) -> Result<Self::Solved, SceneError> {
        let started = Instant::now();
        let errors = Errors { path };
        let volumes =
            MeshSource::new(base, source, registries).read_sides(&errors, self.sides())?;
        self.solve_read(ReadScene {
            path,
            volumes,
            registries,
            started,
        })
    }

    /// Parses a scene file's text and [`check`](Self::check)s it; `path` names it in
    /// messages.
    ///
    /// # Errors
    /// [`SceneError::Syntax`] for bad TOML, an unknown or missing key or a wrong type (with
    /// its line); [`SceneError::Invalid`] for values out of range or inconsistent (see
    /// [`check`](Self::check)).
    fn parse(text: &str, path: &Path) -> Result<Self, SceneError> {
        let spec: Self = SceneError::parse(path, text)?;
        spec.check(path)?;
        Ok(spec)
    }

    /// The TOML text of the scene.
    ///
    /// # Errors
    /// [`SceneError::Other`] if a value cannot be written as TOML (a NaN, say).
    fn to_toml(&self) -> Result<String, SceneError> {
        toml::to_string(self).map_err(|e| SceneError::Other(format!("scene as TOML: {e}")))
    }

    /// [`solve_with`](Self::solve_with) the shipped cells and laws.
    ///
    /// # Errors
    /// As [`solve_with`](Self::solve_with).
    fn solve(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
    ) -> Result<Self::Solved, SceneError> {
        self.solve_with(path, base, source, &Registries::default())
    }

    /// Reads the meshes, solves with the shipped cells and laws, and renders the outputs
    /// (see each kind's module).
    ///
    /// # Errors
    /// As [`solve_with`](Self::solve_with) and [`SolvedScene::output`].
    fn run(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
    ) -> Result<SceneOutput, SceneError> {
        self.solve(path, base, source)?.output()
    }

    /// [`run`](Self::run) with the cells and laws of `registries` (the shipped ones and a
    /// program's own).
    ///
    /// # Errors
    /// As [`solve_with`](Self::solve_with) and [`SolvedScene::output`].
    fn run_with(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
        registries: &Registries,
    ) -> Result<SceneOutput, SceneError> {
        self.solve_with(path, base, source, registries)?.output()
    }
}
