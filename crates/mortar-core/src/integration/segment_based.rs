//! `SegmentBased`: integration over the exact slave-master overlaps (line segments in 2D,
//! clip polygons in 3D, subdivided for curved second-order faces), exact on affine faces.

use super::curved_3d::{self, subdivision_level, DEFAULT_CURVED_TOLERANCE, MAX_SUBDIVISION};
use std::any::Any;

use super::{
    segments_2d, segments_3d, IntegrationFastPaths, IntegrationStrategy, LineSegments, PairedRule,
    PolygonSegments, SegmentContext,
};
use crate::error::{MortarError, Result};
use crate::interface::{FaceGeometry, SpatialDim};

/// Segment-based integration: exact segmentation of every slave-master overlap (see the
/// module documentation). With the default degree the mortar integrals are exact on affine
/// faces and a linear field is reproduced to round-off.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SegmentBased {
    /// Quadrature degree on each integration cell; `None` picks
    /// [`default_degree`](super::default_degree) per pair, plus what a slave face's
    /// Jacobian needs where the face is integrated in its reference coordinates
    /// ([`FaceGeometry::jacobian_extra_degree`](crate::interface::FaceGeometry::jacobian_extra_degree):
    /// a curved Line3, a non-affine face in 3D).
    pub degree: Option<u32>,
    /// Curved second-order faces in 3D (see [`curved_3d`](super::curved_3d)): the tolerance
    /// that picks each face's subdivision level from its bend; `None` for
    /// [`DEFAULT_CURVED_TOLERANCE`].
    pub curved_tolerance: Option<f64>,
    /// A fixed subdivision level for every curved face instead of the tolerance's (for
    /// studies of the level's effect); `None`: from the tolerance.
    pub subdivision: Option<u32>,
    /// Slave quadrilaterals that are not parallelograms in the auxiliary plane (see
    /// [`with_quad_subdivision`](Self::with_quad_subdivision)): each clip triangle cut into
    /// `m^2` before it is mapped to the slave's reference coordinates; `None`: not cut.
    pub quad_subdivision: Option<u32>,
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
        self.subdivision = Some(in_range("subdivision level", level, MAX_SUBDIVISION)?);
        Ok(self)
    }

    /// Accuracy of M on slave quadrilaterals that are not parallelograms (in the auxiliary
    /// plane: bilinear, not affine). Such a face is integrated in its reference coordinates
    /// (so that D stays exact and the dual D diagonal), into which a master edge, straight in
    /// the plane, maps as a curve; by default each clip polygon is mapped by its vertices, with
    /// straight edges, and points near a master edge take the neighbouring master face's
    /// (extrapolated) shape functions: D, `D 1 = M 1` and `D x = M x` stay exact, M's
    /// distribution over the master nodes is off by the area between the curve and its chord.
    /// With `m > 1` each clip triangle (fan from the polygon's centroid, in the plane) is cut
    /// into `m^2` triangles whose vertices are mapped, so that the chords follow the curves
    /// `m` times closer, at `m^2` times the points on such faces. Measured
    /// (`tests/convergence/quad_subdivision.rs`, one distorted quad against a Tri3 master, M
    /// against adaptive element-based integration): 6.1e-6 of M's largest entry at `m = 1`,
    /// 3.8e-7 at 2, 2.3e-8 at 4 (about `m^-4`); the time per pair 2.8 and 9.1 times that of
    /// `m = 1` at 2 and 4 on a 64 x 64 mesh of randomly distorted quads (one thread).
    /// Parallelograms, triangles and curved second-order faces are not affected.
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] unless `1 <= m <= MAX_QUAD_SUBDIVISION` (16).
    pub fn with_quad_subdivision(mut self, m: u32) -> Result<Self> {
        self.quad_subdivision = Some(in_range("quad subdivision", m, MAX_QUAD_SUBDIVISION)?);
        Ok(self)
    }
}

/// The largest cut of [`SegmentBased::with_quad_subdivision`].
pub const MAX_QUAD_SUBDIVISION: u32 = 16;

/// `value` if `1 <= value <= max`, else [`MortarError::InvalidOption`] naming `option`.
fn in_range(option: &'static str, value: u32, max: u32) -> Result<u32> {
    if (1..=max).contains(&value) {
        Ok(value)
    } else {
        Err(MortarError::InvalidOption {
            option,
            value: value.to_string(),
            reason: format!("out of range 1..={max}"),
        })
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
        let mut name = match self.degree {
            Some(d) => format!("segment-based, degree {d}"),
            None => "segment-based, degree auto".to_string(),
        };
        if let Some(m) = self.quad_subdivision.filter(|&m| m > 1) {
            name.push_str(&format!(", non-parallelogram quads cut {m}x{m}"));
        }
        name
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
                let m = self.quad_subdivision.unwrap_or(1);
                segments_3d::segments_into(ctx, slave, candidates, self.degree, m, out)
            }
        }
    }

    fn fast_paths(&self) -> Option<&dyn IntegrationFastPaths> {
        Some(self)
    }
}

impl IntegrationFastPaths for SegmentBased {
    /// True: the points of each master face come from that face and the slave alone (its
    /// overlap segment or clip polygon).
    fn splits_over_candidates(&self) -> bool {
        true
    }
}

impl SegmentBased {
    /// `strategy` when it is a [`SegmentBased`]: the strategy whose segmentation the
    /// coupling's fused kernels are.
    pub(crate) fn of(strategy: &dyn IntegrationStrategy) -> Option<&Self> {
        (strategy as &dyn Any).downcast_ref::<Self>()
    }

    /// Its 2D segmentation, of its degree, for the fused kernel of straight lines.
    pub(crate) fn line_segments(&self) -> LineSegments {
        LineSegments {
            degree: self.degree,
        }
    }

    /// Its 3D segmentation, of its degree, for the closed form of clip polygons (the quad
    /// and curved-face options do not touch linear triangles, the only faces the closed form
    /// takes).
    pub(crate) fn polygon_segments(&self) -> PolygonSegments {
        PolygonSegments {
            degree: self.degree,
        }
    }
}
