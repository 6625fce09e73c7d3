//! Scene files: a problem described in TOML (meshes, physical groups, materials, boundary
//! conditions, the interface, the solve), run by `mortar run SCENE.toml --out DIR`.
//!
//! Every scene file starts with `kind = "..."`, which picks the problem; this build knows
//! [`tied_heat`] (`kind = "tied_heat"`) and [`contact`] (`kind = "contact"`). Unknown keys
//! are errors naming the key and its line; mesh paths are relative to the scene file's
//! folder.
//!
//! ```toml
//! kind = "tied_heat"
//!
//! [bodies.left]
//! mesh = "left.msh"          # Gmsh 4.1, ASCII or binary
//! group = "left"             # physical group of the cells (dimension 2 or 3)
//! conductivity = 1.0         # k, W/m/K
//! dirichlet = [{ group = "left_end", value = 0.0 }]
//!
//! [bodies.right]
//! mesh = "right.msh"
//! group = "right"
//! conductivity = 2.0
//! neumann = [{ group = "right_end", flux = 1.3333333333333333 }]
//!
//! [interface]
//! slave = { body = "right", group = "right_cut" }
//! master = { body = "left", group = "left_cut" }
//! multipliers = "dual"       # or "standard", or "linear" (second-order faces: corners only)
//! integration = "segment"    # or "element"
//!
//! [solve]
//! mode = "steady"            # or "transient", with dt and steps
//! ```

mod builtin;
mod builtin_contact;
pub mod contact;
pub mod contact_files;
pub(crate) mod error;
mod file_scene;
pub(crate) mod solve_keys;
pub mod tied_heat;
mod two_bodies;

use std::path::{Path, PathBuf};

pub use builtin::{
    builtin_scene, tied_block, tied_block_exact, BuiltinScene, BUILTIN_CONTACT_SCENES,
    BUILTIN_SCENES,
};
pub use builtin_contact::{run_builtin_contact, run_builtin_contact_on, HERTZ_ARC_CELLS};
pub use error::SceneError;
pub use file_scene::{FileScene, ReadScene, SolvedScene};

use mortar::io::IoError;

/// Where a scene's mesh files come from: the file system, or files held in memory (a
/// built-in scene, a test).
pub trait SceneSource {
    /// The bytes of the file at `path`.
    ///
    /// # Errors
    /// [`IoError::Read`] naming the file.
    fn read(&self, path: &Path) -> Result<Vec<u8>, IoError>;
}

/// Files read from the file system.
#[derive(Debug, Clone, Copy, Default)]
pub struct FileSystem;

impl SceneSource for FileSystem {
    fn read(&self, path: &Path) -> Result<Vec<u8>, IoError> {
        std::fs::read(path).map_err(|source| IoError::Read {
            path: path.to_path_buf(),
            source,
        })
    }
}

/// Files held in memory, by path.
#[derive(Debug, Clone, Default)]
pub struct InMemory {
    /// `(path, contents)`.
    pub files: Vec<(PathBuf, Vec<u8>)>,
}

impl SceneSource for InMemory {
    fn read(&self, path: &Path) -> Result<Vec<u8>, IoError> {
        self.files
            .iter()
            .find(|(p, _)| p == path)
            .map(|(_, b)| b.clone())
            .ok_or_else(|| IoError::Read {
                path: path.to_path_buf(),
                source: std::io::Error::new(std::io::ErrorKind::NotFound, "no such file"),
            })
    }
}

/// The output of a scene run: files to write into the output folder (all or none, see
/// [`write_outputs`](mortar::io::write_outputs)) and a readable summary.
#[derive(Debug, Clone)]
pub struct SceneOutput {
    /// `(file name, contents)`.
    pub files: Vec<(String, Vec<u8>)>,
    /// A few lines for the terminal.
    pub summary: String,
    /// The coupling's warnings (uncovered slave area, overlapping master faces, skipped
    /// pairs), also in `report.json`: the program prints them as `mortar: warning: ...`.
    pub warnings: Vec<String>,
}

/// The `kind` of a scene file's text: its `kind`, or else its `scene` (the pellet scene's
/// other spelling of the key, the name of its field).
///
/// # Errors
/// [`SceneError::Syntax`] for text that is not TOML, [`SceneError::Invalid`] without a
/// string `kind` (or `scene`) at the top level.
pub fn scene_kind(text: &str, path: &Path) -> Result<String, SceneError> {
    let table: toml::Table = SceneError::parse(path, text)?;
    let (key, value) = match (table.get("kind"), table.get("scene")) {
        (None, Some(scene)) => ("scene", Some(scene)),
        (kind, _) => ("kind", kind),
    };
    match value {
        Some(toml::Value::String(kind)) => Ok(kind.clone()),
        Some(other) => Err(SceneError::Invalid {
            path: path.to_path_buf(),
            key: key.into(),
            what: format!("must be a string such as \"tied_heat\", found {other}"),
        }),
        None => Err(SceneError::Invalid {
            path: path.to_path_buf(),
            key: key.into(),
            what: "missing: the scene file must start with kind = \"tied_heat\" (or another kind)"
                .into(),
        }),
    }
}

/// The node indices of some faces, ascending, each once.
pub(crate) fn face_nodes(faces: &[mortar_fem::mesh::BoundaryFace]) -> Vec<u32> {
    let mut nodes: Vec<u32> = faces.iter().flat_map(|f| f.nodes.iter().copied()).collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}

/// The core's options and tolerances for a scene's coupling keys (under `section`,
/// `interface` or `contact`): a value the core refuses is an error naming its key.
///
/// # Errors
/// [`SceneError::Invalid`] naming `section.degree`, `section.curved_tolerance`,
/// `section.subdivision`, `section.quad_subdivision` or `section.search_radius`.
pub(crate) fn coupling_of(
    settings: &mortar::io::CouplingSettings,
    section: &str,
    path: &Path,
) -> Result<(mortar_core::CouplingOptions, mortar_core::Tolerances), SceneError> {
    let invalid = |e: mortar_core::MortarError| {
        let key = match &e {
            mortar_core::MortarError::InvalidOption { option, .. } => match *option {
                "quadrature degree" => "degree",
                "curved tolerance" => "curved_tolerance",
                "subdivision level" => "subdivision",
                "quad subdivision" => "quad_subdivision",
                "search radius" => "search_radius",
                _ => "",
            },
            _ => "",
        };
        SceneError::Invalid {
            path: path.to_path_buf(),
            key: if key.is_empty() {
                section.to_string()
            } else {
                format!("{section}.{key}")
            },
            what: e.to_string(),
        }
    };
    Ok((
        settings.options().map_err(invalid)?,
        settings.tolerances().map_err(invalid)?,
    ))
}

/// What widens a scene's search: its `search_radius` key under `section`, larger than
/// `radius` when one was given.
pub(crate) fn widen_hint(section: &str, radius: Option<f64>) -> String {
    match radius {
        Some(r) => format!("[{section}] search_radius above {r}"),
        None => format!("[{section}] search_radius (a distance)"),
    }
}
