use super::{segments_2d, segments_3d, IntegrationStrategy, PairedRule, SegmentContext};
use crate::error::{MortarError, Result};
use crate::interface::{FaceGeometry, SpatialDim};

/// Segment-based integration: exact segmentation of every slave-master overlap (see the
/// module documentation). With the default degree the mortar integrals are exact on affine
/// faces and a linear field is reproduced to round-off.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SegmentBased {
    /// Quadrature degree on each integration cell; `None` picks
    /// [`default_degree`](super::default_degree) per pair.
    pub degree: Option<u32>,
}

impl SegmentBased {
    /// Segment-based integration with quadrature of the given degree (`None`: automatic).
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] for a degree of 0 or above 20.
    pub fn new(degree: Option<u32>) -> Result<Self> {
        check_degree(degree)?;
        Ok(Self { degree })
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
