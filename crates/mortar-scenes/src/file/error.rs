//! The error of reading and running a scene file.

use std::path::{Path, PathBuf};

use mortar_physics::PhysicsError;

use mortar::io::IoError;

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

/// Why a scene file's text does not parse: its line, the key of a value that does not fit
/// (`bodies.left.conductivity`; `None` for a syntax error) and the parser's message.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TomlFailure {
    pub line: usize,
    pub key: Option<String>,
    pub message: String,
}

impl TomlFailure {
    fn new(text: &str, e: &toml::de::Error, key: Option<String>) -> Self {
        let line = e
            .span()
            .map(|s| {
                1 + text.as_bytes()[..s.start.min(text.len())]
                    .iter()
                    .filter(|&&b| b == b'\n')
                    .count()
            })
            .unwrap_or(1);
        let message = e.message().trim().to_string();
        Self {
            line,
            key: key.filter(|k| !k.is_empty() && k != "."),
            message,
        }
    }

    /// `KEY: MESSAGE` (or the message alone).
    pub fn keyed_message(&self) -> String {
        match &self.key {
            Some(k) => format!("{k}: {}", self.message),
            None => self.message.clone(),
        }
    }
}

/// Parses the TOML `text` into `T`, tracking the key of the value being read (through
/// `serde_path_to_error`), so that a value of the wrong type is named by its key as well as
/// its line.
pub(crate) fn parse_toml<T: serde::de::DeserializeOwned>(text: &str) -> Result<T, TomlFailure> {
    let de = toml::Deserializer::parse(text).map_err(|e| TomlFailure::new(text, &e, None))?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let key = e.path().to_string();
        TomlFailure::new(text, e.inner(), Some(key))
    })
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
