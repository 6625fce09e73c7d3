//! The summary of a coupling run: counts, node maps, timings, as JSON or readable text.

use std::fmt;

use mortar_core::{Coupling, CouplingOptions, Interface, MortarError, SpatialDim};
use serde::{Deserialize, Serialize};

/// The Lagrange-multiplier space.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Multipliers {
    /// Standard multipliers (the slave shape functions).
    #[default]
    Standard,
    /// Dual (biorthogonal) multipliers: D is diagonal.
    Dual,
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

/// The choices of a coupling run, as a user states them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct CouplingSettings {
    /// The multiplier space.
    pub multipliers: Multipliers,
    /// The integration strategy.
    pub integration: Integration,
    /// The quadrature degree (`None`: automatic, exact on affine faces for segment-based).
    pub degree: Option<u32>,
    /// Worker threads (`None`: rayon's default).
    pub threads: Option<usize>,
}

impl CouplingSettings {
    /// The core's options for these settings.
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] for a degree out of range or zero threads.
    pub fn options(&self) -> Result<CouplingOptions, MortarError> {
        if self.threads == Some(0) {
            return Err(MortarError::InvalidOption(
                "thread count must be at least 1".into(),
            ));
        }
        let mut o = CouplingOptions::default();
        o = match self.multipliers {
            Multipliers::Standard => o.standard(),
            Multipliers::Dual => o.dual(),
        };
        o = match self.integration {
            Integration::Segment => o.segment_based(self.degree)?,
            Integration::Element => o.element_based(self.degree)?,
        };
        if let Some(t) = self.threads {
            o = o.threads(t);
        }
        Ok(o)
    }
}

/// Seconds per phase (see [`mortar_core::assembly::PhaseSeconds`]).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PhaseSummary {
    /// Bounding-box search.
    pub search: f64,
    /// Segmentation, summed over threads.
    pub segments: f64,
    /// Integration, summed over threads.
    pub integration: f64,
    /// Sparse assembly.
    pub assembly: f64,
    /// Everything, wall-clock.
    pub total: f64,
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
    /// The quadrature degree, `null` for automatic.
    pub degree: Option<u32>,
    /// Worker threads used.
    pub threads: usize,
    /// The slave surface (`file#group`), if read from a file.
    pub slave: Option<String>,
    /// The master surface (`file#group`), if read from a file.
    pub master: Option<String>,
    /// Slave faces.
    pub slave_faces: usize,
    /// Master faces.
    pub master_faces: usize,
    /// Slave node tags in row order (the rows of D and M, the columns of D).
    pub slave_nodes: Vec<u64>,
    /// Master node tags in column order (the columns of M).
    pub master_nodes: Vec<u64>,
    /// Stored entries of D.
    pub d_nonzeros: usize,
    /// Stored entries of M.
    pub m_nonzeros: usize,
    /// Candidate pairs from the search.
    pub candidates: usize,
    /// Slave-master pairs with an overlap.
    pub pairs: usize,
    /// Integration cells.
    pub segments: usize,
    /// The sum of the entries of D: the area (3D) or length (2D) of the slave side coupled.
    pub area: f64,
    /// Total seconds of the coupling (wall-clock).
    pub seconds: f64,
    /// Seconds per phase.
    pub seconds_by_phase: PhaseSummary,
}

impl CouplingSummary {
    /// The summary of `coupling`, computed on `interface` with `settings`.
    pub fn new(interface: &Interface, coupling: &Coupling, settings: &CouplingSettings) -> Self {
        let s = &coupling.stats;
        let p = s.seconds;
        Self {
            dimension: match interface.dim() {
                SpatialDim::Two => 2,
                SpatialDim::Three => 3,
            },
            formulation: coupling.formulation.clone(),
            multipliers: settings.multipliers,
            integration: settings.integration,
            degree: settings.degree,
            threads: s.threads,
            slave: None,
            master: None,
            slave_faces: interface.slave().face_count(),
            master_faces: interface.master().face_count(),
            slave_nodes: coupling.slave_nodes.clone(),
            master_nodes: coupling.master_nodes.clone(),
            d_nonzeros: coupling.d.nnz(),
            m_nonzeros: coupling.m.nnz(),
            candidates: s.candidates,
            pairs: s.pairs,
            segments: s.segments,
            area: s.area,
            seconds: p.total,
            seconds_by_phase: PhaseSummary {
                search: p.search,
                segments: p.segments,
                integration: p.integration,
                assembly: p.assembly,
                total: p.total,
            },
        }
    }

    /// Pretty-printed JSON.
    pub fn to_json(&self) -> String {
        // Serialising plain numbers, strings and vectors cannot fail; NaN becomes `null`.
        serde_json::to_string_pretty(self).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    }
}

/// A few readable lines: sizes, pairs, segments, area, time, formulation.
impl fmt::Display for CouplingSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = &self.seconds_by_phase;
        let side = |label: &Option<String>, faces: usize, nodes: usize| match label {
            Some(l) => format!("{faces} faces, {nodes} nodes ({l})"),
            None => format!("{faces} faces, {nodes} nodes"),
        };
        let (ns, nm) = (self.slave_nodes.len(), self.master_nodes.len());
        let lines = [
            ("slave", side(&self.slave, self.slave_faces, ns)),
            ("master", side(&self.master, self.master_faces, nm)),
            ("problem", format!("{}D, {}", self.dimension, self.formulation)),
            ("D", format!("{ns} x {ns}, {} nonzeros", self.d_nonzeros)),
            ("M", format!("{ns} x {nm}, {} nonzeros", self.m_nonzeros)),
            (
                "pairs",
                format!(
                    "{} of {} candidates, {} segments",
                    self.pairs, self.candidates, self.segments
                ),
            ),
            (
                if self.dimension == 2 { "length" } else { "area" },
                format!("{:.15} (sum of D)", self.area),
            ),
            (
                "time",
                format!(
                    "{:.4} s on {} threads (search {:.4}, segments {:.4}, integration {:.4}, assembly {:.4})",
                    self.seconds, self.threads, p.search, p.segments, p.integration, p.assembly
                ),
            ),
        ];
        for (i, (key, value)) in lines.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{key:<9}{value}")?;
        }
        Ok(())
    }
}
