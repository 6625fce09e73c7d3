//! `NamedLaw`: a law named in a scene file with its parameters, made by a `LawRegistry`.

use std::collections::BTreeMap;

use mortar_physics::laws::{DynLaw, LawError, LawRegistry};
use serde::{Deserialize, Serialize};

/// A law named in a scene file: `name` and its parameters (numbers, SI units), as a
/// [`LawRegistry`] makes it:
///
/// ```
/// let law: mortar_scenes::NamedLaw =
///     toml::from_str("name = \"exponential_contact\"\nstiffness = 1e12\nonset = 5e-6").unwrap();
/// let made = law.make(&mortar::physics::laws::LawRegistry::with_shipped()).unwrap();
/// assert_eq!(made.name(), "exponential_contact");
/// ```
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
pub struct NamedLaw {
    /// The registry's name of the law.
    pub name: String,
    /// Its parameters.
    #[serde(flatten)]
    pub parameters: BTreeMap<String, f64>,
}

impl NamedLaw {
    /// The law, made by `registry`.
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] for an unknown name (listing the known ones), a missing
    /// parameter, or a value the law refuses.
    pub fn make(&self, registry: &LawRegistry) -> Result<DynLaw, LawError> {
        registry.make(&self.name, &self.parameters)
    }
}
