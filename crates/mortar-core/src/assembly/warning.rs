//! `CouplingWarning`: what a coupling noticed without failing (uncovered slave area, master or
//! slave faces overlapping, skipped pairs, a dual D that is not diagonal), returned with the
//! operators so that nothing is dropped silently.

use std::fmt;

use crate::error::MortarError;

/// Something the coupling noticed that does not stop it: counted, named, and returned with
/// the operators ([`Coupling::warnings`](super::Coupling::warnings)), so that nothing is
/// dropped silently. With
/// [`CouplingOptions::require_full_coverage`](super::CouplingOptions::require_full_coverage)
/// each one about coverage (all but [`DualNotDiagonal`](Self::DualNotDiagonal)) is an error
/// instead ([`MortarError::IncompleteCoverage`]).
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
        /// How far along the slave normals the search looked from the uncovered faces (the
        /// largest of their search radii): a master surface farther away is not coupled.
        reach: f64,
    },
    /// Part of the slave surface is covered by more than one master face: master faces
    /// overlap as seen from the slave (two master layers within the search radius, or a
    /// master surface that folds over). D and M count that area once per master face over
    /// it, so a slave tied to the master follows the mean of the layers there, and D's
    /// entries sum to more than the slave's area. Usually a meshing error (a master surface
    /// meshed twice, a second body behind the first) or a search radius wide enough to reach
    /// a surface behind the nearest one.
    OverlappingMasterFaces {
        /// The area covered more than once, counted once per extra master face over it
        /// (length in 2D): the sum over slave faces of the covered area beyond the face's
        /// own.
        area: f64,
        /// The slave surface's area.
        total: f64,
        /// Slave faces covered more than once.
        faces: usize,
        /// Tags of the first of them (ascending, at most [`CouplingWarning::EXAMPLES`]).
        examples: Vec<u64>,
    },
    /// Part of the master surface is covered by more than one slave face: slave faces overlap
    /// as seen from the master (two slave layers, such as both sides of a thin plate given as
    /// the slave, each turned to face the master). D and M tie each layer to the same master
    /// surface, and D's entries sum to more than the master area they cover. Found from M's
    /// column sums against the master nodes' own integrals (see
    /// [`MASTER_OVERLAP_RATIO`](super::MASTER_OVERLAP_RATIO)).
    OverlappingSlaveFaces {
        /// The master area covered more than once, counted once per extra slave layer (the
        /// excess of M's column sums over the nodal integrals, at the nodes concerned).
        area: f64,
        /// The master surface's area.
        total: f64,
        /// Master nodes covered more than once.
        master_nodes: usize,
        /// Tags of the first of them (ascending, at most [`CouplingWarning::EXAMPLES`]).
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
    /// A space that claims a diagonal D (dual multipliers) gave a D with off-diagonal entries
    /// above round-off (1e-12 of their row's diagonal entry) on
    /// an interface covered once everywhere (the recombined D where the slave faces are
    /// recombined): the quadrature does not reach the biorthogonality of the basis on curved
    /// faces as coarse as these (a Line3 arc of 45 degrees: 7e-10 of the diagonal), or
    /// second-order faces of different kinds share an edge node, so that no one recombination
    /// serves the slave side. A condensation that needs a diagonal D is then not exact.
    DualNotDiagonal {
        /// The off-diagonal entries kept.
        entries: usize,
        /// The largest, relative to its row's diagonal entry.
        largest: f64,
        /// The rows that have them.
        rows: usize,
        /// Tags of the slave nodes of the first of those rows (at most
        /// [`CouplingWarning::EXAMPLES`]).
        examples: Vec<u64>,
    },
}

impl CouplingWarning {
    /// The most face tags a warning lists.
    pub const EXAMPLES: usize = 8;

    /// A short name: `"uncovered slave area"`, `"overlapping master faces"`, `"overlapping
    /// slave faces"`, `"skipped pairs"` or `"dual D not diagonal"`.
    pub fn name(&self) -> &'static str {
        match self {
            CouplingWarning::UncoveredSlaveArea { .. } => "uncovered slave area",
            CouplingWarning::OverlappingMasterFaces { .. } => "overlapping master faces",
            CouplingWarning::OverlappingSlaveFaces { .. } => "overlapping slave faces",
            CouplingWarning::SkippedPairs { .. } => "skipped pairs",
            CouplingWarning::DualNotDiagonal { .. } => "dual D not diagonal",
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
                reach,
            } => {
                write!(
                    f,
                    "uncovered slave area: {area:.3e} of {total:.3e} ({:.3}%): {} without a \
                     master face within the search radius, {} covered in part (slave faces {}); \
                     the search looked {reach:.3e} along the slave normals from them",
                    100.0 * area / total,
                    plural(*faces_without_partner, "face"),
                    plural(*faces_partly_covered, "face"),
                    tag_list(examples, faces_without_partner + faces_partly_covered),
                )
            }
            CouplingWarning::OverlappingMasterFaces {
                area,
                total,
                faces,
                examples,
            } => {
                write!(
                    f,
                    "overlapping master faces: {area:.3e} of {total:.3e} ({:.3}%) of the slave \
                     surface covered more than once (counted once per extra master face), on \
                     {} (slave faces {}): master faces overlap as seen from the slave, and D \
                     and M count each",
                    100.0 * area / total,
                    plural(*faces, "face"),
                    tag_list(examples, *faces),
                )
            }
            CouplingWarning::OverlappingSlaveFaces {
                area,
                total,
                master_nodes,
                examples,
            } => {
                write!(
                    f,
                    "overlapping slave faces: {area:.3e} of {total:.3e} ({:.3}%) of the master \
                     surface covered by more than one slave face (counted once per extra \
                     face), around {} (master nodes {}): slave faces overlap as seen from the \
                     master (two slave layers?), and D and M tie each to it",
                    100.0 * area / total,
                    plural(*master_nodes, "node"),
                    tag_list(examples, *master_nodes),
                )
            }
            CouplingWarning::DualNotDiagonal {
                entries,
                largest,
                rows,
                examples,
            } => write!(
                f,
                "dual D not diagonal: {} above round-off, up to {largest:.1e} of their row's \
                 diagonal entry (rows of slave nodes {}), on an interface covered once \
                 everywhere: curved faces too coarse for the quadrature to keep the dual basis \
                 biorthogonal (a finer mesh of the curve brings them to round-off), or \
                 second-order faces of different kinds side by side (no one recombination); a \
                 condensation needs a diagonal D",
                plural(*entries, "off-diagonal entry"),
                tag_list(examples, *rows),
            ),
            CouplingWarning::SkippedPairs { count, first } => write!(
                f,
                "skipped pairs: {} dropped because a point could not be mapped between the \
                 faces; the first: {first}",
                plural(*count, "pair")
            ),
        }
    }
}

/// The tags of `examples`, comma-separated, with `", ..."` when they are fewer than the
/// `count` faces they stand for.
fn tag_list(examples: &[u64], count: usize) -> String {
    let tags: Vec<String> = examples.iter().map(u64::to_string).collect();
    let more = if count > examples.len() { ", ..." } else { "" };
    format!("{}{more}", tags.join(", "))
}

/// `"1 face"`, `"2 faces"`.
pub(crate) fn plural(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else if let Some(stem) = noun.strip_suffix("ry") {
        format!("{n} {stem}ries")
    } else {
        format!("{n} {noun}s")
    }
}
