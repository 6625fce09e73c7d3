//! Element-based integration: slave quadrature points projected onto the master.

use nalgebra::{Vector2, Vector3};

use super::segment_based::check_degree;
use super::{default_degree, IntegrationStrategy, PairedPoint, PairedRule, SegmentContext};
use crate::element::MAX_FACE_NODES;
use crate::error::Result;
use crate::geometry::{invert_line_map, invert_surface_map, AuxiliaryPlane};
use crate::interface::{FaceGeometry, SpatialDim};
use crate::quadrature::{Quadrature, QuadratureRule};

/// Element-based integration: the quadrature points of each slave face are projected along the
/// projector's direction onto the candidate master faces; the first master face (lowest
/// index) whose reference domain contains the projection receives the point. Points that land
/// on no master face are dropped from both D and M, so `D 1 = M 1` holds row by row.
///
/// No clipping: cheap, but the integrands have kinks where master edges cross the slave face,
/// so the result converges only as the degree grows. The cheap end of the dial.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ElementBased {
    /// Quadrature degree on the slave face; `None` uses the slave-slave integrand degree
    /// plus what the face's Jacobian needs
    /// ([`FaceGeometry::jacobian_extra_degree`](crate::interface::FaceGeometry::jacobian_extra_degree)).
    pub degree: Option<u32>,
}

impl ElementBased {
    /// Element-based integration of the given degree (`None`: automatic).
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`](crate::error::MortarError::InvalidOption) for a degree of
    /// 0 or above 20.
    pub fn new(degree: Option<u32>) -> Result<Self> {
        check_degree(degree)?;
        Ok(Self { degree })
    }
}

impl IntegrationStrategy for ElementBased {
    fn name(&self) -> String {
        match self.degree {
            Some(d) => format!("element-based, degree {d}"),
            None => "element-based, degree auto".to_string(),
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
        let el = slave.element;
        // The automatic degree integrates the face's own measure as the dual basis does
        // (a curved face's Jacobian is not a polynomial), so that a covered face's dual D
        // stays diagonal.
        let deg = self
            .degree
            .unwrap_or_else(|| (default_degree(el, el) + slave.jacobian_extra_degree()).min(20));
        let rule = QuadratureRule::cached(el.domain(), deg)?;
        // Distinct master faces hit, for the pair count (a handful per slave face).
        let mut hit: Vec<u32> = Vec::new();
        let (mut landed, mut all) = (0.0, 0.0);
        for (xi, w) in rule.points().iter().zip(rule.weights()) {
            all += w;
            let x = slave.map(xi);
            let (d, _) = ctx.projector.direction(slave, xi);
            let Some((m, eta)) = find_master(ctx, &x, &d, candidates) else {
                continue;
            };
            landed += w;
            if !hit.contains(&m) {
                hit.push(m);
            }
            out.points.push(PairedPoint {
                master: m,
                xi_slave: *xi,
                xi_master: eta,
                weight: w * el.jacobian_det(slave.node_coords(), xi),
            });
        }
        out.pairs = hit.len() as u32;
        out.covered = Some(landed / all);
        out.cells = u32::from(!out.points.is_empty());
        if out.cells > 0 {
            out.degrees |= 1 << deg;
        }
        Ok(())
    }
}

/// The first candidate whose projection along `d` from `x` lies in its reference domain
/// (and whose normal there opposes `d`), with the reference coordinates of the projection.
pub(super) fn find_master(
    ctx: &SegmentContext<'_>,
    x: &Vector3<f64>,
    d: &Vector3<f64>,
    candidates: &[u32],
) -> Option<(u32, Vector2<f64>)> {
    let tol = ctx.interface.tolerances();
    let planar = ctx.interface.dim() == SpatialDim::Two;
    let plane = if planar {
        None
    } else {
        Some(AuxiliaryPlane::from_normal(*x, *d)?)
    };
    let mut p = [Vector2::zeros(); MAX_FACE_NODES];
    let mut s = [0.0; MAX_FACE_NODES];
    for &m in candidates {
        let master = ctx.master_face(m);
        let el = master.element;
        let k = master.node_count();
        let eta = match &plane {
            None => {
                for i in 0..k {
                    let r = master.nodes[i] - x;
                    s[i] = r.x * d.y - r.y * d.x;
                }
                // Affine from the type or from the node positions (a straight Line3 with its
                // middle node at the centre; see `FaceGeometry::is_affine`).
                invert_line_map(
                    el,
                    master.is_affine(),
                    &s[..k],
                    0.0,
                    tol.newton,
                    tol.newton_max_iterations,
                )
                .ok()
                .map(|e| Vector2::new(e, 0.0))
            }
            Some(plane) => {
                for i in 0..k {
                    p[i] = plane.project(&master.nodes[i]);
                }
                invert_surface_map(
                    el,
                    el.is_affine(),
                    &p[..k],
                    &Vector2::zeros(),
                    tol.newton,
                    tol.newton_max_iterations,
                )
                .ok()
            }
        };
        if let Some(eta) = eta {
            // Only a master face that faces the slave (normal against the direction) counts.
            if el.domain().contains(&eta, tol.reference_inside)
                && el.unit_normal(master.node_coords(), &eta).dot(d) < 0.0
            {
                return Some((m, eta));
            }
        }
    }
    None
}
