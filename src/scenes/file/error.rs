//! The error of reading and running a scene file.

use std::path::{Path, PathBuf};

use mortar_physics::PhysicsError;

use crate::io::IoError;

/// Errors of a scene file: each names the scene file and the key, or the mesh file and
/// physical group, or the body.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The file is not valid TOML, or does not fit the scene's schema (an unknown key, a
    /// missing key, a value of the wrong type).
    #[error("{}, line {line}: {message}", path.display())]
    Syntax {
        /// The scene file.
        path: PathBuf,
        /// The 1-based line.
        line: usize,
        /// What is wrong (the TOML parser's message).
        message: String,
    },
    /// A value is out of range or inconsistent with others.
    #[error("{}: {key}: {what}", path.display())]
    Invalid {
        /// The scene file.
        path: PathBuf,
        /// The key, such as `bodies.left.conductivity`.
        key: String,
        /// What is wrong.
        what: String,
    },
    /// A mesh file cannot be read, or a group selected in it.
    #[error("{}: {context}: {source}", path.display())]
    Mesh {
        /// The scene file.
        path: PathBuf,
        /// The key that names the mesh or group, such as `bodies.left.dirichlet[0]`.
        context: String,
        /// The file error (naming the mesh file, the group and the place).
        source: Box<IoError>,
    },
    /// The problem cannot be built or solved.
    #[error("{}: {source}", path.display())]
    Physics {
        /// The scene file.
        path: PathBuf,
        /// The physics error (naming the body and cell where it applies).
        source: Box<PhysicsError>,
    },
    /// The scene file cannot be read, or the scene kind is unknown.
    #[error("{0}")]
    Other(String),
}

impl SceneError {
    /// A TOML error with the line of its span.
    pub(crate) fn from_toml(path: &Path, text: &str, e: &toml::de::Error) -> Self {
        let line = e
            .span()
            .map(|s| {
                1 + text.as_bytes()[..s.start.min(text.len())]
                    .iter()
                    .filter(|&&b| b == b'\n')
                    .count()
            })
            .unwrap_or(1);
        SceneError::Syntax {
            path: path.to_path_buf(),
            line,
            message: e.message().trim().to_string(),
        }
    }
}
