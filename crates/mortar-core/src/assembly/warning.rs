use std::fmt;

use crate::error::MortarError;

/// Something the coupling noticed that does not stop it: counted, named, and returned with
/// the operators ([`Coupling::warnings`](super::Coupling::warnings)), so that nothing is
/// dropped silently. With
/// [`CouplingOptions::require_full_coverage`](super::CouplingOptions::require_full_coverage)
/// each one is an error instead ([`MortarError::IncompleteCoverage`]).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum CouplingWarning {
    /// Part of the slave surface has no master face within the search radius: its rows of D
    /// and M are short (or empty) there. Expected where the slave surface extends beyond the
    /// master; otherwise a gap wider than the search radius, or a master oriented the wrong
    /// way.
    UncoveredSlaveArea {
        /// The uncovered area (length in 2D).
        area: f64,
        /// The slave surface's area.
        total: f64,
        /// Slave faces with no master face at all.
        faces_without_partner: usize,
        /// Slave faces covered in part.
        faces_partly_covered: usize,
        /// Tags of the first uncovered slave faces (ascending, at most
        /// [`CouplingWarning::EXAMPLES`]).
        examples: Vec<u64>,
    },
    /// Slave-master pairs dropped because a point could not be mapped between the two faces;
    /// their area is part of the uncovered area.
    SkippedPairs {
        /// How many.
        count: usize,
        /// The first failure (in the order the faces were processed).
        first: Box<MortarError>,
    },
}

impl CouplingWarning {
    /// The most face tags a warning lists.
    pub const EXAMPLES: usize = 8;

    /// A short name: `"uncovered slave area"` or `"skipped pairs"`.
    pub fn name(&self) -> &'static str {
        match self {
            CouplingWarning::UncoveredSlaveArea { .. } => "uncovered slave area",
            CouplingWarning::SkippedPairs { .. } => "skipped pairs",
        }
    }
}

impl fmt::Display for CouplingWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CouplingWarning::UncoveredSlaveArea {
                area,
                total,
                faces_without_partner,
                faces_partly_covered,
                examples,
            } => {
                let tags: Vec<String> = examples.iter().map(u64::to_string).collect();
                let more = faces_without_partner + faces_partly_covered > examples.len();
                write!(
                    f,
                    "uncovered slave area: {area:.3e} of {total:.3e} ({:.3}%): {} without a \
                     master face within the search radius, {} covered in part (slave faces {}{})",
                    100.0 * area / total,
                    plural(*faces_without_partner, "face"),
                    plural(*faces_partly_covered, "face"),
                    tags.join(", "),
                    if more { ", ..." } else { "" }
                )
            }
            CouplingWarning::SkippedPairs { count, first } => write!(
                f,
                "skipped pairs: {} dropped because a point could not be mapped between the \
                 faces; the first: {first}",
                plural(*count, "pair")
            ),
        }
    }
}

/// `"1 face"`, `"2 faces"`.
pub(crate) fn plural(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}
