//! Adaptive element-based integration: a reference for the other strategies where no exact
//! segmentation exists (curved faces), built without clipping.

use nalgebra::{Vector2, Vector3};

use super::element_based::find_master;
use super::segment_based::check_degree;
use super::{IntegrationStrategy, PairedPoint, PairedRule, SegmentContext};
use crate::element::ReferenceDomain;
use crate::error::{MortarError, Result};
use crate::interface::FaceGeometry;
use crate::quadrature::{Quadrature, QuadratureRule};

/// The deepest refinement [`AdaptiveElementBased`] accepts (`4^30` leaves per face at most,
/// a bound never reached: only leaves that a master edge crosses are split).
pub const MAX_ADAPTIVE_DEPTH: u32 = 30;

/// Adaptive element-based integration: the slave face's reference domain (a triangle, a
/// quadrilateral as two triangles, a line) is split recursively into halves (lines) or
/// quarters (triangles, through the edge midpoints). On each leaf, the points of a rule of
/// degree [`degree`](Self::degree) and the leaf's vertices are projected onto the master
/// faces as in [`ElementBased`](super::ElementBased) (along the projector's direction from
/// each point, or from the face centre: see
/// [`along_centre_direction`](Self::along_centre_direction)). A leaf whose points and
/// vertices all land on the same master face (or all on none) is integrated with its rule
/// once it is at least [`min_depth`](Self::min_depth) deep; a leaf with points on different
/// master faces is split again, down to [`max_depth`](Self::max_depth), where its points are
/// kept where they land.
///
/// The integrands are the slave's own (curved Jacobian, slave shape functions) and the
/// master's shape functions at the exact projection of each point (a Newton solve on the
/// curved master face), so the result converges to the exact mortar integrals of curved
/// faces as the depths grow, with no polygon and no flat approximation of either face. Its
/// error has two parts: the rule on leaves inside one master face (smooth integrands: small
/// for a high degree), and the leaves a master edge crosses at the maximum depth, where the
/// assembled integrand of `M` (continuous across master edges, with a kink) is integrated by
/// a rule that does not see the kink: each such leaf of size `h` (relative to the face) is
/// off by about `h^3`, and about `1/h` of them line each master edge, so `M` is off by
/// about `4^-max_depth` of its entries. `D` sees only the coverage (exact on a covered
/// interface). Measure the error as the change of `M` from one maximum depth to the next.
///
/// Whether a leaf is inside one master face is decided from its sampled points only: a
/// master corner poking into a leaf between its points goes unseen; finer leaves (a larger
/// `min_depth`) make that rarer. Meant as a reference for studies and tests
/// (`examples/curved_segmentation.rs`), not for production couplings: it costs tens to
/// hundreds of times [`SegmentBased`](super::SegmentBased).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AdaptiveElementBased {
    /// The degree of the rule on each leaf (1 to 20).
    pub degree: u32,
    /// Leaves are split at least this many times before they are integrated.
    pub min_depth: u32,
    /// Leaves that a master edge crosses are split at most this many times.
    pub max_depth: u32,
    /// Project every point along the projector's direction at the slave face's centre (as
    /// the 3D [`SegmentBased`](super::SegmentBased) strategy does: it is the normal of its
    /// auxiliary plane) instead of the direction at the point (as
    /// [`ElementBased`](super::ElementBased) and the 2D segmentation do). The two give the
    /// same integrals on flat interfaces; on curved ones they differ by the gap between the
    /// faces times the turn of the direction across the face.
    pub along_centre_direction: bool,
}

impl Default for AdaptiveElementBased {
    /// Degree 12, depths 2 to 10, along the direction at each point.
    fn default() -> Self {
        Self {
            degree: 12,
            min_depth: 2,
            max_depth: 10,
            along_centre_direction: false,
        }
    }
}

impl AdaptiveElementBased {
    /// Adaptive element-based integration with a rule of `degree` on each leaf and leaves
    /// split `min_depth` to `max_depth` times.
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] for a degree of 0 or above 20, or depths that are not
    /// `min_depth <= max_depth <= MAX_ADAPTIVE_DEPTH`.
    pub fn new(degree: u32, min_depth: u32, max_depth: u32) -> Result<Self> {
        check_degree(Some(degree))?;
        if min_depth > max_depth || max_depth > MAX_ADAPTIVE_DEPTH {
            return Err(MortarError::InvalidOption {
                option: "adaptive depths",
                value: format!("{min_depth}..={max_depth}"),
                reason: format!("not min <= max <= {MAX_ADAPTIVE_DEPTH}"),
            });
        }
        Ok(Self {
            degree,
            min_depth,
            max_depth,
            along_centre_direction: false,
        })
    }

    /// The same, projecting along the direction at the slave face's centre (see
    /// [`along_centre_direction`](Self::along_centre_direction)).
    pub fn along_centre_direction(mut self) -> Self {
        self.along_centre_direction = true;
        self
    }
}

/// A leaf: its vertices in the slave's reference coordinates (two for a line, the third
/// unused), its depth, and where its vertices landed.
#[derive(Debug, Clone, Copy)]
struct Leaf {
    xi: [Vector2<f64>; 3],
    depth: u32,
    landed: [Option<u32>; 3],
}

impl Leaf {
    /// The leaves a face of `domain` starts from: the line, the triangle, or the
    /// quadrilateral's two triangles, with where their vertices land.
    fn roots(domain: ReferenceDomain, lander: &mut Lander<'_, '_>) -> Vec<Leaf> {
        let v = Vector2::new;
        let roots: &[[Vector2<f64>; 3]] = match domain {
            ReferenceDomain::Line => &[[v(-1.0, 0.0), v(1.0, 0.0), v(0.0, 0.0)]],
            ReferenceDomain::Triangle => &[[v(0.0, 0.0), v(1.0, 0.0), v(0.0, 1.0)]],
            ReferenceDomain::Quadrilateral => &[
                [v(-1.0, -1.0), v(1.0, -1.0), v(1.0, 1.0)],
                [v(-1.0, -1.0), v(1.0, 1.0), v(-1.0, 1.0)],
            ],
        };
        let corners = if domain == ReferenceDomain::Line {
            2
        } else {
            3
        };
        let mut stack: Vec<Leaf> = Vec::new();
        for xi in roots {
            let mut landed = [None; 3];
            for i in 0..corners {
                landed[i] = lander.land(&xi[i]).map(|h| h.0);
            }
            stack.push(Leaf {
                xi: *xi,
                depth: 0,
                landed,
            });
        }
        stack
    }

    /// Splits the leaf onto `stack`: halves of a line, quarters of a triangle through its
    /// edge midpoints, with where the new vertices land.
    fn split(&self, line: bool, lander: &mut Lander<'_, '_>, stack: &mut Vec<Leaf>) {
        let [a, b, c] = self.xi;
        let depth = self.depth + 1;
        if line {
            let mid = 0.5 * (a + b);
            let lm = lander.land(&mid).map(|h| h.0);
            let [la, lb, _] = self.landed;
            stack.push(Leaf {
                xi: [a, mid, mid],
                depth,
                landed: [la, lm, None],
            });
            stack.push(Leaf {
                xi: [mid, b, mid],
                depth,
                landed: [lm, lb, None],
            });
        } else {
            let (ab, bc, ca) = (0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a));
            let (lab, lbc, lca) = (
                lander.land(&ab).map(|h| h.0),
                lander.land(&bc).map(|h| h.0),
                lander.land(&ca).map(|h| h.0),
            );
            let [la, lb, lc] = self.landed;
            for (xi, landed) in [
                ([a, ab, ca], [la, lab, lca]),
                ([ab, b, bc], [lab, lb, lbc]),
                ([ca, bc, c], [lca, lbc, lc]),
                ([bc, ca, ab], [lbc, lca, lab]),
            ] {
                stack.push(Leaf { xi, depth, landed });
            }
        }
    }
}

/// A master face (slot) and the reference coordinates of a projected point on it.
type Hit = (u32, Vector2<f64>);

/// Where the points of a slave face land, remembering the last master face hit (tried
/// first: neighbouring points mostly land on the same one).
struct Lander<'a, 'b> {
    ctx: &'a SegmentContext<'b>,
    slave: &'a FaceGeometry,
    candidates: &'a [u32],
    centre_direction: Option<Vector3<f64>>,
    last: Option<u32>,
}

impl Lander<'_, '_> {
    fn land(&mut self, xi: &Vector2<f64>) -> Option<Hit> {
        let x = self.slave.map(xi);
        let d = self
            .centre_direction
            .unwrap_or_else(|| self.ctx.projector.direction(self.slave, xi).0);
        if let Some(m) = self.last {
            if let Some(hit) = find_master(self.ctx, &x, &d, &[m]) {
                return Some(hit);
            }
        }
        let hit = find_master(self.ctx, &x, &d, self.candidates);
        if let Some((m, _)) = hit {
            self.last = Some(m);
        }
        hit
    }
}

impl IntegrationStrategy for AdaptiveElementBased {
    fn name(&self) -> String {
        format!(
            "adaptive element-based, degree {}, depth {}..={}{}",
            self.degree,
            self.min_depth,
            self.max_depth,
            if self.along_centre_direction {
                ", along the centre direction"
            } else {
                ""
            }
        )
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
        let domain = el.domain();
        let line = domain == ReferenceDomain::Line;
        let rule = QuadratureRule::cached(
            if line {
                ReferenceDomain::Line
            } else {
                ReferenceDomain::Triangle
            },
            self.degree,
        )?;
        let centre_direction = self
            .along_centre_direction
            .then(|| ctx.projector.direction(slave, &domain.centre()).0);
        let mut lander = Lander {
            ctx,
            slave,
            candidates,
            centre_direction,
            last: None,
        };
        let v = Vector2::new;
        let corners = if line { 2 } else { 3 };
        let mut stack = Leaf::roots(domain, &mut lander);
        // The rule's points on the current leaf: slave coordinates, weight, landing.
        let mut points: Vec<(Vector2<f64>, f64, Option<Hit>)> = Vec::new();
        let (mut landed_measure, mut measure) = (0.0, 0.0);
        while let Some(leaf) = stack.pop() {
            let [a, b, c] = leaf.xi;
            // The leaf's measure in reference coordinates.
            let size = if line {
                0.5 * (b.x - a.x)
            } else {
                let (e1, e2) = (b - a, c - a);
                (e1.x * e2.y - e1.y * e2.x).abs()
            };
            let one_master = leaf.landed[..corners].iter().all(|m| *m == leaf.landed[0]);
            if leaf.depth >= self.min_depth {
                points.clear();
                let mut pure = one_master;
                for (r, w) in rule.points().iter().zip(rule.weights()) {
                    let xi = if line {
                        v(0.5 * (a.x + b.x) + 0.5 * (b.x - a.x) * r.x, 0.0)
                    } else {
                        a + (b - a) * r.x + (c - a) * r.y
                    };
                    let hit = lander.land(&xi);
                    pure &= hit.map(|h| h.0) == leaf.landed[0];
                    points.push((xi, w * size, hit));
                }
                if pure || leaf.depth >= self.max_depth {
                    out.cells += 1;
                    for &(xi, w, hit) in &points {
                        measure += w;
                        let Some((m, eta)) = hit else { continue };
                        landed_measure += w;
                        out.points.push(PairedPoint {
                            master: m,
                            xi_slave: xi,
                            xi_master: eta,
                            weight: w * el.jacobian_det(slave.node_coords(), &xi),
                        });
                    }
                    continue;
                }
            }
            leaf.split(line, &mut lander, &mut stack);
        }
        // Points of one master face together (stable: in the order of the leaves).
        out.points.sort_by_key(|p| p.master);
        let mut last = None;
        for p in &out.points {
            if last != Some(p.master) {
                out.pairs += 1;
                last = Some(p.master);
            }
        }
        if !out.points.is_empty() {
            out.degrees |= 1 << self.degree;
        }
        out.covered = Some(if measure > 0.0 {
            landed_measure / measure
        } else {
            0.0
        });
        Ok(())
    }
}
