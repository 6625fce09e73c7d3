//! Messages and summaries for the user.

use mortar::io::{CouplingSummary, GmshSurface};
use mortar::{MortarError, Side};

/// A core error with the file, group and line of the face it names, or the two surfaces.
pub(super) fn core_error(
    e: &MortarError,
    surfaces: Option<(&GmshSurface, &GmshSurface)>,
) -> String {
    let Some((slave, master)) = surfaces else {
        return e.to_string();
    };
    let face = match e {
        MortarError::DegenerateFace { face, .. }
        | MortarError::InvertedFace { face, .. }
        | MortarError::MultiplierSpace { face, .. }
        | MortarError::ProjectionFailed { face, .. }
        | MortarError::Topology { face, .. }
        | MortarError::WrongNodeCount { face, .. }
        | MortarError::UnknownNode { face, .. } => Some(*face),
        _ => None,
    };
    match face {
        Some(face) => {
            let surface = if face.side == Some(Side::Master) {
                master
            } else {
                slave
            };
            // The other faces a topology error names, where the file has them.
            let others: Vec<String> = match e {
                MortarError::Topology { faces, .. } => faces
                    .iter()
                    .filter(|&&t| t != face.tag)
                    .filter_map(|&t| {
                        surface
                            .face_location(t)
                            .map(|at| format!("face {t} at {at}"))
                    })
                    .collect(),
                _ => Vec::new(),
            };
            let also = if others.is_empty() {
                String::new()
            } else {
                format!(" ({})", others.join(", "))
            };
            match surface.face_location(face.tag) {
                Some(at) => format!("{}, {at}: {e}{also}", surface.label()),
                None => format!("{}: {e}{also}", surface.label()),
            }
        }
        None => format!("slave {} and master {}: {e}", slave.label(), master.label()),
    }
}

/// Prints each coupling warning on one line of stderr: `mortar: warning: NAME: ...`, an
/// uncovered area's with `widen`, what widens the search.
pub(super) fn print_warnings(warnings: &[mortar::CouplingWarning], widen: &str) {
    for w in warnings {
        eprintln!("mortar: warning: {}", mortar::io::warning_text(w, widen));
    }
}

/// Prints the summary as text or JSON on stdout.
pub(super) fn print_summary(summary: &CouplingSummary, json: bool) {
    if json {
        say!("{}", summary.to_json());
    } else {
        say!("{summary}");
    }
}
