//! Scene files' TOML read into their types, naming the line and, for a value that does not
//! fit, its key (through `serde_path_to_error`).

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
