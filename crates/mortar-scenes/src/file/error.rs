//! The error of reading and running a scene file.

use std::path::{Path, PathBuf};

use mortar_physics::PhysicsError;

use mortar::io::IoError;

use crate::parse::parse_toml;

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
    /// The transient solve was interrupted (Ctrl-C, [`crate::interrupt`]); nothing written.
    #[error("{}: interrupted after {done} of {steps} time steps", path.display())]
    Interrupted {
        /// The scene file.
        path: PathBuf,
        /// Steps completed.
        done: usize,
        /// Steps asked for.
        steps: usize,
    },
    /// A pellet scene failed (its own error: a value out of range, a law, a solve that did
    /// not converge, naming its step and time).
    #[error("{}: {source}", path.display())]
    Pellet {
        /// The scene file.
        path: PathBuf,
        /// The pellet's error.
        source: Box<crate::pellet::PelletError>,
    },
    /// The scene file cannot be read, or the scene kind is unknown.
    #[error("{0}")]
    Other(String),
}

impl SceneError {
    /// The scene file `text` (read from `path`) parsed into `T`; a failure names the line and,
    /// for a value that does not fit, the key.
    pub(crate) fn parse<T: serde::de::DeserializeOwned>(
        path: &Path,
        text: &str,
    ) -> Result<T, Self> {
        parse_toml(text).map_err(|f| SceneError::Syntax {
            path: path.to_path_buf(),
            line: f.line,
            message: f.keyed_message(),
        })
    }
}

/// The errors of one scene file, each naming it: the steps of a scene's check and solve make
/// their errors through it rather than each repeating the file's path.
pub(crate) struct Errors<'a> {
    /// The scene file.
    pub(crate) path: &'a Path,
}

impl Errors<'_> {
    /// A mesh file or group that cannot be read, under the key `context` that names it.
    pub(crate) fn mesh(&self, context: String, source: IoError) -> SceneError {
        SceneError::Mesh {
            path: self.path.to_path_buf(),
            context,
            source: Box::new(source),
        }
    }

    /// A problem that cannot be built or solved.
    pub(crate) fn physics(&self, source: PhysicsError) -> SceneError {
        SceneError::Physics {
            path: self.path.to_path_buf(),
            source: Box::new(source),
        }
    }

    /// A value of `key` out of range or inconsistent with others.
    pub(crate) fn invalid(&self, key: String, what: String) -> SceneError {
        SceneError::Invalid {
            path: self.path.to_path_buf(),
            key,
            what,
        }
    }
}
