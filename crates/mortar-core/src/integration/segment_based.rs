use super::curved_3d::{self, subdivision_level, DEFAULT_CURVED_TOLERANCE, MAX_SUBDIVISION};
use super::{segments_2d, segments_3d, IntegrationStrategy, PairedRule, SegmentContext};
use crate::error::{MortarError, Result};
use crate::interface::{FaceGeometry, SpatialDim};

/// Segment-based integration: exact segmentation of every slave-master overlap (see the
/// module documentation). With the default degree the mortar integrals are exact on affine
/// faces and a linear field is reproduced to round-off.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SegmentBased {
    /// Quadrature degree on each integration cell; `None` picks
    /// [`default_degree`](super::default_degree) per pair.
    pub degree: Option<u32>,
    /// Curved second-order faces in 3D (see [`curved_3d`](super::curved_3d)): the tolerance
    /// that picks each face's subdivision level from its bend; `None` for
    /// [`DEFAULT_CURVED_TOLERANCE`].
    pub curved_tolerance: Option<f64>,
    /// A fixed subdivision level for every curved face instead of the tolerance's (for
    /// studies of the level's effect); `None`: from the tolerance.
    pub subdivision: Option<u32>,
}

impl SegmentBased {
    /// Segment-based integration with quadrature of the given degree (`None`: automatic).
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] for a degree of 0 or above 20.
    pub fn new(degree: Option<u32>) -> Result<Self> {
        check_degree(degree)?;
        Ok(Self {
            degree,
            ..Self::default()
        })
    }

    /// The tolerance of the curved-face subdivision: each curved face is cut into sub-
    /// triangles until its bend per sub-triangle, relative to its size, is at most
    /// `tolerance`.
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] unless `1e-12 <= tolerance <= 1`.
    pub fn with_curved_tolerance(mut self, tolerance: f64) -> Result<Self> {
        if !(1e-12..=1.0).contains(&tolerance) {
            return Err(MortarError::InvalidOption {
                option: "curved tolerance",
                value: tolerance.to_string(),
                reason: "out of range 1e-12..=1".into(),
            });
        }
        self.curved_tolerance = Some(tolerance);
        Ok(self)
    }

    /// A fixed subdivision level of curved faces (`level^2` sub-triangles per triangle side).
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] unless `1 <= level <= MAX_SUBDIVISION`.
    pub fn with_subdivision(mut self, level: u32) -> Result<Self> {
        if !(1..=MAX_SUBDIVISION).contains(&level) {
            return Err(MortarError::InvalidOption {
                option: "subdivision level",
                value: level.to_string(),
                reason: format!("out of range 1..={MAX_SUBDIVISION}"),
            });
        }
        self.subdivision = Some(level);
        Ok(self)
    }
}

pub(super) fn check_degree(degree: Option<u32>) -> Result<()> {
    match degree {
        Some(d) if d == 0 || d > 20 => Err(MortarError::InvalidOption {
            option: "quadrature degree",
            value: d.to_string(),
            reason: "out of range 1..=20".into(),
        }),
        _ => Ok(()),
    }
}

impl IntegrationStrategy for SegmentBased {
    fn name(&self) -> String {
        match self.degree {
            Some(d) => format!("segment-based, degree {d}"),
            None => "segment-based, degree auto".to_string(),
        }
    }

    fn paired_rule_into(
        &self,
        ctx: &SegmentContext<'_>,
        slave: &FaceGeometry,
        candidates: &[u32],
        out: &mut PairedRule,
    ) -> Result<()> {
        out.clear();
        match ctx.interface.dim() {
            SpatialDim::Two => segments_2d::segments_into(ctx, slave, candidates, self.degree, out),
            SpatialDim::Three if curved_3d::needs_subdivision(ctx, slave, candidates) => {
                let tol = self.curved_tolerance.unwrap_or(DEFAULT_CURVED_TOLERANCE);
                let fixed = self.subdivision;
                let level = |bend: f64| fixed.unwrap_or_else(|| subdivision_level(bend, tol));
                curved_3d::segments_into(ctx, slave, candidates, self.degree, level, out)
            }
            SpatialDim::Three => {
                segments_3d::segments_into(ctx, slave, candidates, self.degree, out)
            }
        }
    }

    /// True: the points of each master face come from that face and the slave alone (its
    /// overlap segment or clip polygon).
    fn splits_over_candidates(&self) -> bool {
        true
    }
}
