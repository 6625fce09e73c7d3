//! The coupling vocabulary a user states, in one place with one default: the multiplier
//! space, the integration strategy, its degree and dials, the search radius, the coverage
//! rule. `mortar couple`, the scene files and the Python package all read it through serde
//! ([`parse_name`] for a single name on a command line), and [`CouplingSettings::options`]
//! turns it into the core's [`CouplingOptions`].
//!
//! ```
//! use mortar::settings::{parse_name, CouplingSettings, Multipliers};
//! let settings = CouplingSettings::default();
//! assert_eq!(settings.multipliers, Multipliers::Dual);
//! assert_eq!(parse_name::<Multipliers>("standard"), Ok(Multipliers::Standard));
//! assert!(parse_name::<Multipliers>("mortar").unwrap_err().contains("dual"));
//! assert!(settings.options().is_ok());
//! ```

use std::fmt;

use mortar_core::integration::SegmentBased;
use mortar_core::{CouplingOptions, MortarError, SearchRadius, Tolerances};
use serde::de::{value::StrDeserializer, DeserializeOwned, IntoDeserializer};
use serde::{Deserialize, Serialize};

/// The Lagrange-multiplier space.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Multipliers {
    /// Standard multipliers (the slave shape functions).
    Standard,
    /// Dual (biorthogonal) multipliers: D is diagonal. The default: exact to the same order
    /// as standard multipliers, and the tie condenses to a smaller symmetric positive
    /// definite system (the cheapest exact formulation); well defined on second-order faces
    /// too (recombined).
    #[default]
    Dual,
    /// Linear multipliers on second-order faces (on the corner nodes only; standard on
    /// first-order faces): see [`mortar_core::multiplier::LinearMultipliers`].
    Linear,
}

/// The integration strategy.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Integration {
    /// Exact segmentation of each slave-master pair.
    #[default]
    Segment,
    /// Quadrature points of the slave face projected onto the master.
    Element,
}

/// Declares a struct (serde, unknown keys refused, every key optional) with the fields given
/// and then the keys of the coupling vocabulary, the fields of [`CouplingSettings`]:
/// `multipliers`, `integration`, `degree`, `curved_tolerance`, `subdivision`,
/// `quad_subdivision`, `search_radius`, `require_full_coverage`; and its `settings()`, those
/// keys as [`CouplingSettings`] (with `threads` unset). The scene files' interface tables are
/// declared so, so that they and `mortar couple` and Python share one list and one default.
/// The calling crate depends on `serde`.
///
/// A macro rather than a struct flattened into the table: serde's `flatten` under
/// `deny_unknown_fields` loses the line of a bad value and the list of the accepted keys in
/// the error for an unknown one, which the scene files' messages give.
///
/// ```
/// mortar::coupling_keys! {
///     /// An interface table of a program's own scene.
///     pub struct Glue {
///         /// The slave side's group.
///         pub slave: String,
///     }
/// }
/// let glue: Glue = serde_json::from_str(r#"{"slave": "top", "multipliers": "standard"}"#)
///     .unwrap();
/// assert_eq!(glue.settings().multipliers, mortar::settings::Multipliers::Standard);
/// assert_eq!(glue.settings().integration, mortar::settings::Integration::Segment);
/// ```
#[macro_export]
macro_rules! coupling_keys {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $( $(#[$field_meta:meta])* pub $field:ident : $ty:ty, )*
        }
    ) => {
        $crate::coupling_keys! {
            @struct
            $(#[$meta])*
            pub struct $name {
                $( $(#[$field_meta])* pub $field: $ty, )*
            }
        }

        impl $name {
            /// The coupling settings of these keys (`threads` unset: rayon's default).
            pub fn settings(&self) -> $crate::settings::CouplingSettings {
                $crate::settings::CouplingSettings {
                    multipliers: self.multipliers,
                    integration: self.integration,
                    degree: self.degree,
                    curved_tolerance: self.curved_tolerance,
                    subdivision: self.subdivision,
                    quad_subdivision: self.quad_subdivision,
                    search_radius: self.search_radius,
                    require_full_coverage: self.require_full_coverage,
                    threads: None,
                }
            }
        }
    };
    (
        @struct
        $(#[$meta:meta])*
        pub struct $name:ident {
            $( $(#[$field_meta:meta])* pub $field:ident : $ty:ty, )*
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct $name {
            $( $(#[$field_meta])* pub $field: $ty, )*
            /// The multiplier space (default dual: [`Multipliers::default`]).
            ///
            /// [`Multipliers::default`]: $crate::settings::Multipliers
            #[serde(default)]
            pub multipliers: $crate::settings::Multipliers,
            /// The integration strategy (default segment-based).
            #[serde(default)]
            pub integration: $crate::settings::Integration,
            /// The quadrature degree (`None`: automatic, exact on affine faces for
            /// segment-based).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub degree: Option<u32>,
            /// Segment-based, curved second-order faces in 3D: the subdivision tolerance
            /// (`None`: `mortar_core::integration::curved_3d::DEFAULT_CURVED_TOLERANCE`;
            /// see `SegmentBased::with_curved_tolerance`).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub curved_tolerance: Option<f64>,
            /// Segment-based, curved second-order faces in 3D: a fixed subdivision level
            /// instead of the tolerance's (see `SegmentBased::with_subdivision`).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub subdivision: Option<u32>,
            /// Segment-based, slave quads that are not parallelograms: each clip triangle
            /// cut into `m^2` (see `SegmentBased::with_quad_subdivision`).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub quad_subdivision: Option<u32>,
            /// How far along the slave normals the search looks for master faces, in the
            /// coordinates' units (`None`: as far as the nearest master surface, within a
            /// quarter of the interface's size).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub search_radius: Option<f64>,
            /// Make uncovered slave area, overlapping master faces and skipped pairs errors
            /// instead of warnings.
            #[serde(default, skip_serializing_if = "std::ops::Not::not")]
            pub require_full_coverage: bool,
        }
    };
}

coupling_keys! {
    @struct
    /// The choices of a coupling run, as a user states them: the coupling vocabulary's keys
    /// (see [`coupling_keys!`](crate::coupling_keys)) and the worker threads.
    #[derive(Copy, Default)]
    pub struct CouplingSettings {
        /// Worker threads (`None`: rayon's default).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub threads: Option<usize>,
    }
}

impl CouplingSettings {
    /// The core's options for these settings.
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] for a degree out of range, zero threads, a dial of the
    /// segment-based integration out of its range, or given with element-based integration.
    pub fn options(&self) -> Result<CouplingOptions, MortarError> {
        if self.threads == Some(0) {
            return Err(MortarError::InvalidOption {
                option: "threads",
                value: "0".into(),
                reason: "at least 1".into(),
            });
        }
        let mut o = CouplingOptions::default();
        o = match self.multipliers {
            Multipliers::Standard => o.standard(),
            Multipliers::Dual => o.dual(),
            Multipliers::Linear => o.linear(),
        };
        o = match self.integration {
            Integration::Segment => {
                let mut s = SegmentBased::new(self.degree)?;
                if let Some(t) = self.curved_tolerance {
                    s = s.with_curved_tolerance(t)?;
                }
                if let Some(l) = self.subdivision {
                    s = s.with_subdivision(l)?;
                }
                if let Some(m) = self.quad_subdivision {
                    s = s.with_quad_subdivision(m)?;
                }
                o.integration = std::sync::Arc::new(s);
                o
            }
            Integration::Element => {
                let dials = [
                    (
                        "curved tolerance",
                        self.curved_tolerance.map(|t| t.to_string()),
                    ),
                    ("subdivision level", self.subdivision.map(|l| l.to_string())),
                    (
                        "quad subdivision",
                        self.quad_subdivision.map(|m| m.to_string()),
                    ),
                ];
                if let Some((option, Some(value))) = dials.into_iter().find(|d| d.1.is_some()) {
                    return Err(MortarError::InvalidOption {
                        option,
                        value,
                        reason: "a dial of segment-based integration, not element-based".into(),
                    });
                }
                o.element_based(self.degree)?
            }
        };
        if let Some(t) = self.threads {
            o = o.threads(t);
        }
        Ok(o.require_full_coverage(self.require_full_coverage))
    }

    /// What widens the search, as `mortar couple` takes it: `--search-radius DISTANCE`
    /// (larger than the one in use, when one was given).
    pub fn widen_search_hint(&self) -> String {
        match self.search_radius {
            Some(r) => format!("--search-radius above {r}"),
            None => "--search-radius DISTANCE".to_string(),
        }
    }

    /// The tolerances for these settings (the search radius).
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] for a negative or non-finite search radius.
    pub fn tolerances(&self) -> Result<Tolerances, MortarError> {
        let mut t = Tolerances::default();
        if let Some(r) = self.search_radius {
            t.search_radius = SearchRadius::Distance(r);
            if !t.search_radius.is_valid() {
                return Err(MortarError::InvalidOption {
                    option: "search radius",
                    value: r.to_string(),
                    reason: "not a non-negative finite distance".into(),
                });
            }
        }
        Ok(t)
    }
}

/// A name of the vocabulary ([`Multipliers`], [`Integration`]) read as serde reads it from a
/// scene file: `"dual"`, `"segment"`, ...; the error lists the names it takes.
///
/// # Errors
/// The message of serde for an unknown name (`unknown variant ..., expected one of ...`).
pub fn parse_name<T: DeserializeOwned>(name: &str) -> Result<T, String> {
    let de: StrDeserializer<'_, serde::de::value::Error> = name.into_deserializer();
    T::deserialize(de).map_err(|e| e.to_string())
}

/// [`parse_name`] of `name` when given, the type's default (the vocabulary's) when not.
///
/// # Errors
/// As [`parse_name`].
pub fn parse_or_default<T: DeserializeOwned + Default>(name: Option<&str>) -> Result<T, String> {
    name.map_or_else(|| Ok(T::default()), parse_name)
}

/// The name serde writes for `value` (a unit variant of the vocabulary).
fn name_of<T: Serialize>(value: &T) -> String {
    serde_json::to_value(value)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

impl fmt::Display for Multipliers {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&name_of(self))
    }
}

impl fmt::Display for Integration {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&name_of(self))
    }
}
