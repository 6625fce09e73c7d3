//! The summary of a coupling run: counts, node maps, timings, as JSON or readable text.

use std::fmt;

use mortar_core::{Coupling, Interface, SearchRadius, SpatialDim};
use serde::{Deserialize, Serialize};

use crate::settings::{CouplingSettings, Integration, Multipliers};

/// The file `T` of a coupling in the recombined slave basis is written to, beside `D.mtx`.
pub const RECOMBINATION_FILE: &str = "T.mtx";

/// `"nodal"`: the slave basis of a summary that does not name one.
fn nodal() -> String {
    "nodal".to_string()
}

/// Seconds per phase (see [`mortar_core::assembly::PhaseSeconds`]): wall-clock, with the
/// per-face work split by kind in thread-seconds.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PhaseSummary {
    /// Wall-clock: the search tree and the spatial order of the slave faces.
    pub tree: f64,
    /// Wall-clock: the per-face work (search queries, segmentation, integration).
    pub faces: f64,
    /// Wall-clock: sparse assembly.
    pub assembly: f64,
    /// Wall-clock: everything.
    pub total: f64,
    /// The per-face work by kind, in seconds summed over the threads.
    pub thread_seconds: ThreadSecondsSummary,
}

/// The per-face work by kind, in seconds summed over the threads.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ThreadSecondsSummary {
    /// Search queries.
    pub search: f64,
    /// Segmentation.
    pub segments: f64,
    /// Integration.
    pub integration: f64,
}

/// How the sense of a surface's faces was decided.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OrientationMethod {
    /// Outward from the cells of its file (every face bounds one cell).
    Cells,
    /// Each connected piece made consistent, then turned to face the other surface.
    Facing,
    /// Each connected piece made consistent, its sense kept as given: the surfaces touch, so
    /// no gap tells the sides apart.
    Consistent,
}

impl OrientationMethod {
    /// A phrase for a person.
    pub fn describe(self) -> &'static str {
        match self {
            Self::Cells => "outward from the cells of its file",
            Self::Facing => "made consistent, turned to face the other side",
            Self::Consistent => {
                "made consistent, sense kept as given (the surfaces touch: no gap tells the \
                 sides apart)"
            }
        }
    }
}

/// How one surface was oriented before coupling.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct SideOrientation {
    /// How the sense was decided.
    pub method: OrientationMethod,
    /// Connected pieces of the surface (`null` when not looked at).
    pub components: Option<usize>,
    /// Faces whose node order was reversed.
    pub flipped: usize,
}

/// How both surfaces were oriented.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct OrientationSummary {
    /// The slave surface.
    pub slave: SideOrientation,
    /// The master surface.
    pub master: SideOrientation,
}

/// A warning of the coupling, by name and in words.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WarningSummary {
    /// `"uncovered slave area"`, `"overlapping master faces"` or `"skipped pairs"`.
    pub name: String,
    /// What and where.
    pub message: String,
}

/// A coupling warning in words, with what widens the search where it reports uncovered slave
/// area: `widen` names the option or key of the entry point (`--search-radius DISTANCE`,
/// `[contact] search_radius`, `search_radius=`).
pub fn warning_text(w: &mortar_core::CouplingWarning, widen: &str) -> String {
    match w {
        mortar_core::CouplingWarning::UncoveredSlaveArea { .. } => {
            format!("{w}; to look farther, set {widen}")
        }
        _ => w.to_string(),
    }
}

/// The normal gap at the covered slave nodes: the weighted normal gap `-n_j . (D x_s - M
/// x_m)_j` over the node's share of the slave area (its row sum of D), positive where the
/// surfaces are apart, in the coordinates' units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GapSummary {
    /// Slave nodes with a positive share of the coupled area.
    pub nodes: usize,
    /// The smallest gap (negative: penetration).
    pub min: f64,
    /// The largest gap.
    pub max: f64,
    /// The mean over those nodes.
    pub mean: f64,
}

impl GapSummary {
    /// The gap statistics of `coupling` on `interface`'s coordinates; `None` when no slave
    /// node has a positive share of the coupled area.
    pub fn of(interface: &Interface, coupling: &Coupling) -> Option<Self> {
        let x_s = coupling.slave_positions(interface);
        let x_m = coupling.master_positions(interface);
        let gaps = coupling.normal_gaps(&x_s, &x_m);
        let mut out = Self {
            nodes: 0,
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            mean: 0.0,
        };
        for (j, row) in coupling.d.outer_iterator().enumerate() {
            let w: f64 = row.iter().map(|(_, v)| v).sum();
            if w.is_nan() || w <= 0.0 {
                continue;
            }
            let g = gaps[j] / w;
            out.nodes += 1;
            out.min = out.min.min(g);
            out.max = out.max.max(g);
            out.mean += g;
        }
        (out.nodes > 0).then(|| Self {
            mean: out.mean / out.nodes as f64,
            ..out
        })
    }
}

/// What `summary.json` holds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CouplingSummary {
    /// 2 (lines) or 3 (faces).
    pub dimension: u8,
    /// The core's description of what was computed.
    pub formulation: String,
    /// `"standard"` or `"dual"`.
    pub multipliers: Multipliers,
    /// `"segment"` or `"element"`.
    pub integration: Integration,
    /// The quadrature degree asked for, `null` for automatic.
    pub degree: Option<u32>,
    /// The quadrature degrees actually used, ascending.
    pub degrees_used: Vec<u32>,
    /// How far along the slave normals the search looked: `"1 x face size"` or a distance.
    pub search_radius: String,
    /// How the search's boxes were padded: `"exact"` where the nodes bound both sides' faces,
    /// else which side's were inflated and by what fraction of a face's diameter (see
    /// `CouplingStats::slave_box_inflation`).
    #[serde(default)]
    pub search_boxes: String,
    /// Worker threads used.
    pub threads: usize,
    /// The slave surface (`file#group`), if read from a file.
    pub slave: Option<String>,
    /// The master surface (`file#group`), if read from a file.
    pub master: Option<String>,
    /// How the surfaces were oriented, if the program oriented them.
    pub orientation: Option<OrientationSummary>,
    /// Slave faces.
    pub slave_faces: usize,
    /// Master faces.
    pub master_faces: usize,
    /// Slave node tags in row order (the rows of D and M, the columns of D).
    pub slave_nodes: Vec<u64>,
    /// Master node tags in column order (the columns of M).
    pub master_nodes: Vec<u64>,
    /// Which basis of the slave unknowns D and M are in: `"nodal"` (the slave nodes' own
    /// values), or `"recombined"` (dual multipliers on Tri6 or Quad8 slave faces: D is
    /// `D T^T`, diagonal, and the slave unknowns are `u~ = T^-T u`, `u = T^T u~`, with `T`
    /// in the file named by `recombination`; Popp, Gee and Wall 2012).
    #[serde(default = "nodal")]
    pub slave_basis: String,
    /// The file of `T` (`"T.mtx"`, slave x slave, rows and columns as D's) when
    /// `slave_basis` is `"recombined"`, else `null`.
    #[serde(default)]
    pub recombination: Option<String>,
    /// Stored entries of D.
    pub d_nonzeros: usize,
    /// Stored entries of M.
    pub m_nonzeros: usize,
    /// Off-diagonal entries of a dual D below round-off of their diagonal (at most 1e-12 of
    /// it), added to the diagonal and not written.
    pub d_roundoff_dropped: usize,
    /// The largest of them, relative to its diagonal entry.
    pub d_roundoff_largest: f64,
    /// Off-diagonal entries of a dual D kept (above round-off): none on an interface covered
    /// everywhere, unless a warning `dual D not diagonal` says why.
    #[serde(default)]
    pub d_off_diagonal: usize,
    /// The largest of them, relative to its row's diagonal entry.
    #[serde(default)]
    pub d_off_diagonal_largest: f64,
    /// Candidate pairs from the search.
    pub candidates: usize,
    /// Slave-master pairs with an overlap.
    pub pairs: usize,
    /// Integration cells.
    pub segments: usize,
    /// Pairs dropped because a point could not be mapped between the faces.
    pub skipped_pairs: usize,
    /// Slave area (length in 2D) without a master face within the search radius.
    pub uncovered_area: f64,
    /// Slave faces with no master face at all.
    pub faces_without_partner: usize,
    /// Slave faces covered in part.
    pub faces_partly_covered: usize,
    /// Slave area covered by more than one master face, once per extra face.
    #[serde(default)]
    pub overlapped_area: f64,
    /// Slave faces covered by more than one master face.
    #[serde(default)]
    pub faces_overlapped: usize,
    /// Slave faces coupled by the fused kernel for straight two-node lines (2D,
    /// segment-based), the others by the integration strategy.
    #[serde(default)]
    pub fused_line_faces: usize,
    /// Slave faces coupled by the sorted merge of a straight 2D interface (all or none).
    #[serde(default)]
    pub straight_line_faces: usize,
    /// Slave faces whose clip polygons were integrated in closed form (3D linear triangles and
    /// flat bilinear quads, segment-based), the others by the integration strategy's points.
    #[serde(default)]
    pub closed_form_faces: usize,
    /// The sum of the entries of D as written: the area (3D) or length (2D) of the slave side
    /// coupled.
    pub area: f64,
    /// The normal gap at the covered slave nodes (min, max, mean), `null` when none is
    /// covered.
    #[serde(default)]
    pub gap: Option<GapSummary>,
    /// Slave faces whose search reached beyond one face diameter to the nearest master
    /// surface (the default search, where one face diameter left area uncovered).
    #[serde(default)]
    pub widened_search_faces: usize,
    /// The largest of their search radii (0 when none was widened).
    #[serde(default)]
    pub widest_search: f64,
    /// The warnings, also printed on standard error.
    pub warnings: Vec<WarningSummary>,
    /// Total seconds of the coupling (wall-clock).
    pub seconds: f64,
    /// Seconds per phase.
    pub seconds_by_phase: PhaseSummary,
}

impl CouplingSummary {
    /// Which code computed the slave faces: the sorted merge of a straight 2D interface, the
    /// fused kernel of straight 2D lines, the closed form of flat 3D faces, the integration
    /// strategy's points for the others but those without a master face.
    pub fn path(&self) -> String {
        let n = self.slave_faces;
        let fast = [
            (
                self.straight_line_faces,
                "the sorted merge of a straight line",
            ),
            (self.fused_line_faces, "the fused line kernel"),
            (self.closed_form_faces, "the closed form"),
        ];
        let mut parts: Vec<String> = fast
            .iter()
            .filter(|(k, _)| *k > 0)
            .map(|(k, what)| format!("{what} for {k} of {n} slave faces"))
            .collect();
        // Faces without a master face are integrated by nothing.
        let alone = self.faces_without_partner;
        let rest = n.saturating_sub(fast.iter().map(|(k, _)| k).sum::<usize>() + alone);
        if parts.is_empty() && alone == 0 {
            return format!("the integration strategy's points for all {n} slave faces");
        }
        if rest > 0 {
            parts.push(format!("the integration strategy's points for {rest}"));
        }
        if alone > 0 {
            parts.push(format!("no master face for {alone}"));
        }
        parts.join("; ")
    }

    /// The summary of `coupling`, computed on `interface` with `settings`: of its D as
    /// [`write_coupling`](super::write_coupling) writes it (in the recombined basis where the
    /// coupling has one).
    pub fn new(interface: &Interface, coupling: &Coupling, settings: &CouplingSettings) -> Self {
        let s = &coupling.stats;
        let p = s.seconds;
        let (d, dropped, dropped_largest, basis) = match &coupling.recombined {
            Some(r) => (
                &r.d,
                r.d_roundoff_dropped,
                r.d_roundoff_largest,
                Some(RECOMBINATION_FILE),
            ),
            None => (
                &coupling.d,
                s.d_roundoff_dropped,
                s.d_roundoff_largest,
                None,
            ),
        };
        Self {
            dimension: match interface.dim() {
                SpatialDim::Two => 2,
                SpatialDim::Three => 3,
            },
            formulation: coupling.formulation.clone(),
            multipliers: settings.multipliers,
            integration: settings.integration,
            degree: settings.degree,
            degrees_used: coupling.degrees_used(),
            search_radius: match interface.tolerances().search_radius {
                SearchRadius::FaceSize(k) => format!("{k} x face size"),
                SearchRadius::Nearest { bound } => format!(
                    "1 x face size, to the nearest master surface where that leaves area \
                     uncovered (within {bound} x the interface's size)"
                ),
                SearchRadius::Distance(d) => format!("{d}"),
            },
            search_boxes: search_boxes(s.slave_box_inflation, s.master_box_inflation),
            threads: s.threads,
            slave: None,
            master: None,
            orientation: None,
            slave_faces: interface.slave().face_count(),
            master_faces: interface.master().face_count(),
            slave_nodes: coupling.slave_nodes.clone(),
            master_nodes: coupling.master_nodes.clone(),
            slave_basis: if basis.is_some() {
                "recombined"
            } else {
                "nodal"
            }
            .to_string(),
            recombination: basis.map(str::to_string),
            d_nonzeros: d.nnz(),
            m_nonzeros: coupling.m.nnz(),
            d_roundoff_dropped: dropped,
            d_roundoff_largest: dropped_largest,
            d_off_diagonal: s.d_off_diagonal,
            d_off_diagonal_largest: s.d_off_diagonal_largest,
            candidates: s.candidates,
            pairs: s.pairs,
            segments: s.segments,
            skipped_pairs: s.skipped_pairs,
            uncovered_area: s.uncovered_area,
            faces_without_partner: s.faces_without_partner,
            faces_partly_covered: s.faces_partly_covered,
            overlapped_area: s.overlapped_area,
            faces_overlapped: s.faces_overlapped,
            fused_line_faces: s.fused_line_faces,
            straight_line_faces: s.straight_line_faces,
            closed_form_faces: s.closed_form_faces,
            // D T^T sums as D does (T's columns sum to 1), to round-off: the sum as written.
            area: match &coupling.recombined {
                Some(r) => r.d.data().iter().sum(),
                None => s.area,
            },
            gap: GapSummary::of(interface, coupling),
            widened_search_faces: s.widened_search_faces,
            widest_search: s.widest_search,
            warnings: coupling
                .warnings
                .iter()
                .map(|w| WarningSummary {
                    name: w.name().to_string(),
                    message: warning_text(w, &settings.widen_search_hint()),
                })
                .collect(),
            seconds: p.total,
            seconds_by_phase: PhaseSummary {
                tree: p.tree,
                faces: p.faces,
                assembly: p.assembly,
                total: p.total,
                thread_seconds: ThreadSecondsSummary {
                    search: p.thread.search,
                    segments: p.thread.segments,
                    integration: p.thread.integration,
                },
            },
        }
    }

    /// JSON, indented, with arrays of numbers (the node tags) on one line each.
    pub fn to_json(&self) -> String {
        // Serialising plain numbers, strings and vectors cannot fail; NaN becomes `null`.
        match serde_json::to_value(self) {
            Ok(v) => super::json::compact_pretty(&v),
            Err(e) => format!("{{\"error\": \"{e}\"}}"),
        }
    }
}

impl CouplingSummary {
    /// The summary's line on D: its size and nonzeros, the recombination and the entries off
    /// its diagonal.
    fn d_line(&self) -> String {
        let ns = self.slave_nodes.len();
        let mut d = format!("{ns} x {ns}, {}", plural(self.d_nonzeros, "nonzero"));
        if let Some(t) = &self.recombination {
            d.push_str(&format!(
                " in the recombined slave basis (u = T^T u~, T in {t})"
            ));
        }
        if self.d_off_diagonal > 0 {
            d.push_str(&format!(
                " ({} kept, up to {:.1e} of the diagonal)",
                plural(self.d_off_diagonal, "off-diagonal entry"),
                self.d_off_diagonal_largest
            ));
        }
        if self.d_roundoff_dropped > 0 {
            d.push_str(&format!(
                " ({} below round-off of the diagonal, at most {:.1e} of it, lumped into it)",
                plural(self.d_roundoff_dropped, "off-diagonal entry"),
                self.d_roundoff_largest
            ));
        }
        d
    }

    /// The summary's line on the time taken, by phase.
    fn time_line(&self) -> String {
        let p = &self.seconds_by_phase;
        format!(
            "{:.4} s on {} (tree {:.4}, faces {:.4}, assembly {:.4}; per-face work in \
             thread-seconds: search {:.4}, segments {:.4}, integration {:.4})",
            self.seconds,
            plural(self.threads, "thread"),
            p.tree,
            p.faces,
            p.assembly,
            p.thread_seconds.search,
            p.thread_seconds.segments,
            p.thread_seconds.integration
        )
    }
}

/// The summary's line on how the surfaces were oriented.
fn orientation_line(o: &OrientationSummary) -> String {
    let one = |s: &SideOrientation| match s.components {
        Some(c) => format!(
            "{} ({}, {} reversed)",
            s.method.describe(),
            plural(c, "piece"),
            plural(s.flipped, "face")
        ),
        None => format!(
            "{} ({} reversed)",
            s.method.describe(),
            plural(s.flipped, "face")
        ),
    };
    format!("slave {}; master {}", one(&o.slave), one(&o.master))
}

/// A few readable lines: sizes, pairs, segments, area, time, formulation.
impl fmt::Display for CouplingSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let side = |label: &Option<String>, faces: usize, nodes: usize| {
            let counts = format!("{}, {}", plural(faces, "face"), plural(nodes, "node"));
            match label {
                Some(l) => format!("{counts} ({l})"),
                None => counts,
            }
        };
        let (ns, nm) = (self.slave_nodes.len(), self.master_nodes.len());
        let mut lines = vec![
            ("slave", side(&self.slave, self.slave_faces, ns)),
            ("master", side(&self.master, self.master_faces, nm)),
        ];
        if let Some(o) = &self.orientation {
            lines.push(("oriented", orientation_line(o)));
        }
        let degrees: Vec<String> = self.degrees_used.iter().map(u32::to_string).collect();
        lines.push((
            "problem",
            format!(
                "{}D, {}; quadrature degree {} used; search radius {}, boxes {}",
                self.dimension,
                self.formulation,
                degrees.join(", "),
                self.search_radius,
                self.search_boxes
            ),
        ));
        lines.push(("D", self.d_line()));
        lines.push((
            "M",
            format!("{ns} x {nm}, {}", plural(self.m_nonzeros, "nonzero")),
        ));
        lines.push(("path", self.path()));
        lines.push((
            "pairs",
            format!(
                "{} of {} candidates, {}{}",
                self.pairs,
                self.candidates,
                plural(self.segments, "segment"),
                if self.skipped_pairs > 0 {
                    format!(", {} skipped", plural(self.skipped_pairs, "pair"))
                } else {
                    String::new()
                }
            ),
        ));
        lines.push((
            if self.dimension == 2 {
                "length"
            } else {
                "area"
            },
            format!(
                "{:.15} (sum of D); uncovered {:.3e}",
                self.area, self.uncovered_area
            ),
        ));
        if let Some(g) = &self.gap {
            lines.push((
                "gap",
                format!(
                    "normal gap at {}: min {:.6e}, max {:.6e}, mean {:.6e}",
                    plural(g.nodes, "covered slave node"),
                    g.min,
                    g.max,
                    g.mean
                ),
            ));
        }
        if self.widened_search_faces > 0 {
            lines.push((
                "search",
                format!(
                    "widened to the nearest master surface for {} (radius up to {:.3e})",
                    plural(self.widened_search_faces, "slave face"),
                    self.widest_search
                ),
            ));
        }
        lines.push(("time", self.time_line()));
        for (i, (key, value)) in lines.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{key:<9}{value}")?;
        }
        Ok(())
    }
}

/// `"1 face"`, `"2 faces"`; a noun ending in "y" after a consonant takes "ies".
/// The summary's words for the search's padding: `"exact"`, or which side's boxes were
/// inflated and by how much.
fn search_boxes(slave: f64, master: f64) -> String {
    let by = |k: f64| format!("inflated by {k} x face size");
    match (slave > 0.0, master > 0.0) {
        (false, false) => "exact".to_string(),
        (true, true) if slave == master => by(slave),
        (true, false) => format!("slave {}, master exact", by(slave)),
        (false, true) => format!("slave exact, master {}", by(master)),
        (true, true) => format!("slave {}, master {}", by(slave), by(master)),
    }
}

pub(crate) fn plural(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else if let Some(stem) = noun.strip_suffix("ry") {
        format!("{n} {stem}ries")
    } else {
        format!("{n} {noun}s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::line_mesh;
    use mortar_core::{assemble_coupling, SurfaceMesh};

    /// The summary's words for the search's padding, per side.
    #[test]
    fn search_boxes_say_which_side_was_inflated() {
        assert_eq!(search_boxes(0.0, 0.0), "exact");
        assert_eq!(search_boxes(0.1, 0.1), "inflated by 0.1 x face size");
        assert_eq!(
            search_boxes(0.0, 0.1),
            "slave exact, master inflated by 0.1 x face size"
        );
        assert_eq!(
            search_boxes(0.1, 0.0),
            "slave inflated by 0.1 x face size, master exact"
        );
    }

    /// The summary's path line names what computed each slave face: the sorted merge on a
    /// straight line; the fused kernel, the strategy and nothing on a slave that reaches past
    /// its master (faces without a master face are integrated by nothing).
    #[test]
    fn the_path_line_names_what_computed_the_faces() {
        let settings = CouplingSettings::default();
        let summary = |slave: SurfaceMesh, master: SurfaceMesh| {
            let interface = Interface::new(slave, master).unwrap();
            let c = assemble_coupling(&interface, &settings.options().unwrap()).unwrap();
            CouplingSummary::new(&interface, &c, &settings).path()
        };
        let straight = summary(
            line_mesh(6, false, 1).unwrap(),
            line_mesh(7, true, 100).unwrap(),
        );
        assert_eq!(
            straight,
            "the sorted merge of a straight line for 6 of 6 slave faces"
        );
        // The slave [0, 2] in 8 faces over the master [0, 1]: 4 faces covered, 4 beyond (the
        // one from x = 1 only touches the master).
        let mut long = SurfaceMesh::new();
        for i in 0..=8u64 {
            long.add_node(1 + i, [0.25 * i as f64, 0.0, 0.0]).unwrap();
        }
        for i in 1..=8u64 {
            long.add_face(&mortar_elements::LINE2, &[i, i + 1]).unwrap();
        }
        let partial = summary(long, line_mesh(7, true, 100).unwrap());
        assert_eq!(
            partial,
            "the fused line kernel for 4 of 8 slave faces; no master face for 4"
        );
    }
}
