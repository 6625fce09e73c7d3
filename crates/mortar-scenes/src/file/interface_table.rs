//! The coupling keys of a scene file's interface table, declared once: `interface_table!`
//! writes a table's struct with its own fields first and then the coupling vocabulary
//! ([`CouplingSettings`](mortar::io::CouplingSettings): `multipliers`, `integration`,
//! `degree`, `curved_tolerance`, `subdivision`, `quad_subdivision`, `search_radius`,
//! `require_full_coverage`), with `settings()`. A macro rather than a flattened struct: serde's
//! `flatten` under `deny_unknown_fields` loses the line of a bad value and the list of the
//! accepted keys in the error for an unknown one, which the scene files' messages give.

/// Declares the interface table `$name` (serde, unknown keys refused) with the fields given
/// and then the coupling keys, and its `settings()`.
macro_rules! interface_table {
    (
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
            /// The multiplier space (default dual, the vocabulary's:
            /// [`Multipliers::default`](mortar::io::Multipliers::default)).
            #[serde(default)]
            pub multipliers: mortar::io::Multipliers,
            /// The integration strategy.
            #[serde(default)]
            pub integration: mortar::io::Integration,
            /// The quadrature degree (default automatic).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub degree: Option<u32>,
            /// Segment-based: the curved-face subdivision tolerance (see
            /// [`CouplingSettings::curved_tolerance`](mortar::io::CouplingSettings::curved_tolerance)).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub curved_tolerance: Option<f64>,
            /// Segment-based: a fixed curved-face subdivision level.
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub subdivision: Option<u32>,
            /// Segment-based: the cut of non-parallelogram slave quads (see
            /// [`CouplingSettings::quad_subdivision`](mortar::io::CouplingSettings::quad_subdivision)).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub quad_subdivision: Option<u32>,
            /// How far along the slave normals the search looks for master faces, a distance
            /// (see [`CouplingSettings::search_radius`](mortar::io::CouplingSettings::search_radius);
            /// default: as far as the nearest master surface, within a bound relative to the
            /// interface's size).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub search_radius: Option<f64>,
            /// Make uncovered slave area, overlapping master faces and skipped pairs errors
            /// instead of warnings.
            #[serde(default, skip_serializing_if = "std::ops::Not::not")]
            pub require_full_coverage: bool,
        }

        impl $name {
            /// The coupling settings of these keys.
            pub fn settings(&self) -> mortar::io::CouplingSettings {
                mortar::io::CouplingSettings {
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
}

pub(crate) use interface_table;
