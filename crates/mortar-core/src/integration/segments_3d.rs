//! 3D segment-based integration: auxiliary plane, clipping, triangulation, quadrature.

use arrayvec::ArrayVec;
use nalgebra::{Vector2, Vector3};

use super::{default_degree, overlap_counts, PairedPoint, PairedRule, SegmentContext};
use crate::element::{ElementRef, ReferenceDomain, MAX_FACE_NODES};
use crate::error::{FaceLocation, MortarError, Result, Side};
use crate::geometry::{
    polygon_diameter, signed_area, AuxiliaryPlane, ClipBuffers, ConvexClipper, InverseMapFailure,
    PlanarMap, Polygon, MAX_POLYGON_VERTICES,
};
use crate::interface::{FaceGeometry, WARPED_EXTRA_DEGREE};
use crate::quadrature::{Quadrature, QuadratureRule};

/// A slave face's set-up in its auxiliary plane, shared by the strategy's segmentation
/// ([`segments_into`]) and the closed form ([`closed_form`](super::closed_form)): the plane,
/// the face's projection and the measures the clipping of each candidate needs.
pub(crate) struct SlavePlane {
    /// The auxiliary plane through the face's centre.
    pub plane: AuxiliaryPlane,
    /// The face's nodes in the plane.
    pub sp: [Vector2<f64>; MAX_FACE_NODES],
    /// Its area in the plane (positive).
    pub area_s: f64,
    /// The largest distance between two of its corners in the plane.
    pub diameter: f64,
    /// The face's map into the plane.
    pub slave_map: PlanarMap,
    /// Whether the face is integrated in its reference coordinates (its map into space or
    /// its projection is not affine).
    pub in_reference: bool,
    /// The degree added to the integrands' for a face integrated in its reference coordinates.
    pub extra_degree: u32,
    /// The ratio of the face's area element to the plane's (an affine face; 1 otherwise).
    pub measure: f64,
    /// The in-plane bounding box of the face.
    s_lo: Vector2<f64>,
    s_hi: Vector2<f64>,
    /// The clipping's merge tolerance.
    merge: f64,
    /// The absolute rounding of the coordinates in the plane (a few ulps of their magnitude).
    rounding: f64,
    /// The smallest overlap area, relative to the smaller face's, that counts.
    clip_area: f64,
    /// The clipper of `spoly`.
    clipper: ConvexClipper,
    /// The clipper's buffers.
    bufs: ClipBuffers,
}

impl SlavePlane {
    /// The set-up of `slave`.
    ///
    /// # Errors
    /// [`MortarError::DegenerateFace`] when the projection direction at the centre is zero;
    /// [`MortarError::InvertedFace`] when the face's projection turns against the plane's
    /// normal.
    pub fn new(ctx: &SegmentContext<'_>, slave: &FaceGeometry) -> Result<Self> {
        let zero = Vector3::zeros();
        let mut setup = Self {
            plane: AuxiliaryPlane {
                origin: zero,
                normal: zero,
                t1: zero,
                t2: zero,
            },
            sp: [Vector2::zeros(); MAX_FACE_NODES],
            area_s: 0.0,
            diameter: 0.0,
            slave_map: PlanarMap::unset(slave.element),
            in_reference: false,
            extra_degree: 0,
            measure: 1.0,
            s_lo: Vector2::zeros(),
            s_hi: Vector2::zeros(),
            merge: 0.0,
            rounding: 0.0,
            clip_area: 0.0,
            clipper: ConvexClipper::default(),
            bufs: ClipBuffers::default(),
        };
        setup.set(ctx, slave)?;
        Ok(setup)
    }

    /// The set-up of `slave` in `slot`: the one there reset in place (its clip buffers kept),
    /// or a new one where there is none. A worker that sets up one slave face after another
    /// neither moves a new set-up (about 1.7 KB) into place nor clears its buffers per face.
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn reuse<'a>(
        slot: &'a mut Option<SlavePlane>,
        ctx: &SegmentContext<'_>,
        slave: &FaceGeometry,
    ) -> Result<&'a mut SlavePlane> {
        match slot {
            Some(setup) => {
                setup.set(ctx, slave)?;
                Ok(setup)
            }
            None => Ok(slot.insert(Self::new(ctx, slave)?)),
        }
    }

    /// Makes this the set-up of `slave`, in place (the clip buffers are kept: each clipping
    /// fills what it reads). After an error the set-up is unusable until set again.
    ///
    /// # Errors
    /// As [`new`](Self::new).
    fn set(&mut self, ctx: &SegmentContext<'_>, slave: &FaceGeometry) -> Result<()> {
        let tol = ctx.interface.tolerances();
        let el = slave.element;
        let centre = el.domain().centre();
        let (plane, x0) = auxiliary_plane(ctx, slave)?;
        self.plane = plane;

        let ks = slave.node_count();
        let sp = &mut self.sp;
        for i in 0..ks {
            sp[i] = plane.project(&slave.nodes[i]);
        }
        sp[ks..].fill(Vector2::zeros());
        let corners = &sp[..el.corner_count()];
        let area_s = signed_area(corners);
        if area_s <= 0.0 {
            return Err(MortarError::InvertedFace {
                face: slave.location(),
                kind: crate::error::Inversion::AgainstProjection,
                reason: "its normal points against the projection direction at its centre".into(),
            });
        }
        // A face affine in space projects to an affine map: its planar map needs no check at
        // the nodes.
        let affine_in_space = slave.is_affine();
        if affine_in_space {
            self.slave_map.set_affine(el, &sp[..ks]);
        } else {
            self.slave_map.set(el, &sp[..ks]);
        }
        // A slave face is integrated in the plane only when both its map into space and its
        // projection are affine (a triangle, a flat parallelogram): then the plane's area
        // element differs from the face's by one constant factor, `measure`, the ratio of the
        // face's Jacobian to its projection's (1 when the face lies in the plane; `1 / cos` of
        // the tilt on a curved surface, where the plane follows the averaged nodal normals).
        // Any other slave face is integrated in its reference coordinates with its own
        // Jacobian.
        let in_reference = !(self.slave_map.is_affine() && affine_in_space);
        // The degree added to the integrands' for a slave face integrated in its reference
        // coordinates: one for a flat face (its Jacobian a polynomial), WARPED_EXTRA_DEGREE
        // for a warped or curved one (its Jacobian the norm of a polynomial vector).
        self.extra_degree = if !in_reference {
            0
        } else if slave.is_flat() {
            1
        } else {
            WARPED_EXTRA_DEGREE
        };
        self.measure = if in_reference {
            1.0
        } else {
            let (_, jac_plane) = self.slave_map.eval(&centre);
            el.jacobian_det(slave.node_coords(), &centre) / jac_plane
        };
        self.in_reference = in_reference;
        let (s_lo, s_hi) = corners
            .iter()
            .fold((corners[0], corners[0]), |(lo, hi), p| {
                (lo.inf(p), hi.sup(p))
            });
        // Coordinates far from the origin carry an absolute rounding of a few ulps of their
        // magnitude: the merge tolerance cannot be finer than that.
        let rounding = 8.0 * f64::EPSILON * x0.amax();
        let diameter = polygon_diameter(corners);
        self.merge = (tol.merge * diameter).max(rounding);
        self.rounding = rounding;
        self.diameter = diameter;
        self.area_s = area_s;
        self.s_lo = s_lo;
        self.s_hi = s_hi;
        self.clip_area = tol.clip_area;
        self.clipper.set(corners);
        Ok(())
    }

    /// Projects the master face in slot `m` into the plane (its nodes into `mp`) and clips it
    /// against the slave face into `clip`: its element, its node count and the clip polygon's
    /// area when the overlap counts, `None` when the face is out of the slave's box, seen
    /// edge-on, facing the same way as the slave (counted in `back_facing`) or overlapping by
    /// less than the tolerance.
    pub fn clip_master(
        &mut self,
        ctx: &SegmentContext<'_>,
        m: u32,
        mp: &mut [Vector2<f64>; MAX_FACE_NODES],
        clip: &mut Polygon,
        back_facing: &mut u32,
    ) -> Option<(ElementRef, usize, f64)> {
        let mut xm = [Vector3::zeros(); MAX_FACE_NODES];
        let (mel, km) = ctx.masters.coords_into(ctx.interface, m as usize, &mut xm);
        self.clip_face(mel, &xm[..km], mp, clip, back_facing)
    }

    /// [`clip_master`](Self::clip_master) of a master face given by its element type and
    /// node coordinates `xm`.
    pub fn clip_face(
        &mut self,
        mel: ElementRef,
        xm: &[Vector3<f64>],
        mp: &mut [Vector2<f64>; MAX_FACE_NODES],
        clip: &mut Polygon,
        back_facing: &mut u32,
    ) -> Option<(ElementRef, usize, f64)> {
        let area_m = self.clip_face_unmeasured(mel, xm, mp, clip, back_facing)?;
        let area = clip.signed_area();
        self.overlap_counts(area, area_m, clip)
            .then_some((mel, xm.len(), area))
    }

    /// [`clip_face`](Self::clip_face) up to the clip polygon's area: the master face's area
    /// in the plane (its absolute value) when `clip` has at least three vertices, for
    /// [`overlap_counts`](Self::overlap_counts) with the polygon's area measured by the
    /// caller (the closed form has it from its moments).
    pub fn clip_face_unmeasured(
        &mut self,
        mel: ElementRef,
        xm: &[Vector3<f64>],
        mp: &mut [Vector2<f64>; MAX_FACE_NODES],
        clip: &mut Polygon,
        back_facing: &mut u32,
    ) -> Option<f64> {
        for (p, x) in mp.iter_mut().zip(xm) {
            *p = self.plane.project(x);
        }
        // Quick rejection by in-plane bounding boxes before clipping.
        let corners = &mp[..mel.corner_count()];
        let (lo, hi) = corners
            .iter()
            .fold((corners[0], corners[0]), |(lo, hi), p| {
                (lo.inf(p), hi.sup(p))
            });
        let (s_lo, s_hi, merge) = (self.s_lo, self.s_hi, self.merge);
        if lo.x > s_hi.x + merge
            || lo.y > s_hi.y + merge
            || hi.x < s_lo.x - merge
            || hi.y < s_lo.y - merge
        {
            return None;
        }
        let area_m = signed_area(corners);
        if area_m.abs() <= self.clip_area * self.area_s {
            return None; // seen edge-on from the plane
        }
        if area_m > 0.0 {
            // Counter-clockwise about the slave normal: the master face looks the same way as
            // the slave, so it is not the surface facing it.
            *back_facing += 1;
            return None;
        }
        // Clockwise about the slave normal: reversed, it is the subject of the clipping.
        self.clipper
            .clip_reversed_in(corners, merge, &mut self.bufs, clip);
        (clip.len() >= 3).then_some(-area_m)
    }

    /// Whether the clip polygon `clip` of (signed) `area` counts as an overlap of the slave
    /// face with a master face of area `area_m` in the plane: more than the smallest fraction
    /// of the smaller face, and not a sliver of the coordinates' rounding
    /// ([`overlap_counts`](super::overlap_counts)).
    #[inline]
    pub fn overlap_counts(&self, area: f64, area_m: f64, clip: &Polygon) -> bool {
        let floor = self.clip_area * self.area_s.min(area_m);
        overlap_counts(area, floor, self.rounding, self.diameter, clip)
    }
}

/// `quad_subdivision`: see [`SegmentBased::with_quad_subdivision`](super::SegmentBased::with_quad_subdivision).
pub(super) fn segments_into(
    ctx: &SegmentContext<'_>,
    slave: &FaceGeometry,
    candidates: &[u32],
    degree: Option<u32>,
    quad_subdivision: u32,
    out: &mut PairedRule,
) -> Result<()> {
    let el = slave.element;
    let mut setup = SlavePlane::new(ctx, slave)?;
    let mut mp = [Vector2::zeros(); MAX_FACE_NODES];
    let mut clip = Polygon::default();
    let mut cells = CellBuffers {
        // The cut triangles of a non-parallelogram quad (`quad_subdivision > 1`), in the
        // slave's reference coordinates.
        cut: quad_subdivision > 1 && setup.in_reference && !setup.slave_map.is_affine(),
        quad_subdivision,
        tris: ArrayVec::new(),
        cut_tris: Vec::new(),
    };
    let mut covered = 0.0;

    for &m in candidates {
        let Some((mel, km, area)) =
            setup.clip_master(ctx, m, &mut mp, &mut clip, &mut out.back_facing)
        else {
            continue;
        };
        // A slave face whose Jacobian varies is integrated in its reference coordinates with
        // the Jacobian as a factor: `extra_degree` more.
        let deg = degree.unwrap_or_else(|| default_degree(el, mel) + setup.extra_degree);
        let rule = QuadratureRule::cached(ReferenceDomain::Triangle, deg)?;
        let pair = PairMaps {
            ctx,
            slave,
            setup: &setup,
            master_map: PlanarMap::new(mel, &mp[..km]),
            master: m,
        };
        // Both maps affine and the degree at least the integrands': integrated exactly on
        // any triangulation.
        let exact = pair.master_map.is_affine() && deg >= default_degree(el, mel);
        let pushed = out.points.len();
        let cells_before = out.cells;
        // A point that cannot be mapped back drops the pair (counted, never silently).
        let emitted = if deg == 2 && !setup.in_reference {
            pair.midpoint_points(&clip, exact, out)
        } else {
            cells
                .triangulate(&pair, &clip, exact)
                .and_then(|()| pair.triangle_points(cells.list(), rule, out))
        };
        if let Err(e) = emitted {
            out.points.truncate(pushed);
            out.cells = cells_before;
            out.skip(e);
            continue;
        }
        let any = out.points.len() > pushed;
        if any {
            out.pairs += 1;
            out.degrees |= 1 << deg;
            covered += area;
        }
    }
    out.covered = Some(covered / setup.area_s);
    Ok(())
}

/// The maps of one slave/master pair of [`segments_into`]: where a point of the clip polygon
/// lies on each face, and its quadrature weight.
///
/// An affine slave is integrated on the clip triangles in the plane. A non-affine slave
/// (bilinear quad) is integrated in its reference coordinates: the clip polygon's vertices
/// are mapped back and triangulated there, and the weights carry the surface Jacobian, so
/// that on a planar face `Phi_j N_k J` stays a polynomial and D is exact on a covered face.
struct PairMaps<'a, 'c> {
    ctx: &'a SegmentContext<'c>,
    slave: &'a FaceGeometry,
    setup: &'a SlavePlane,
    master_map: PlanarMap,
    /// The master face's slot.
    master: u32,
}

impl PairMaps<'_, '_> {
    /// The projection failure of the point `p` of the plane onto the face on `side`.
    #[cold]
    fn fail(&self, f: InverseMapFailure, p: &Vector2<f64>, side: Side, tag: u64) -> MortarError {
        MortarError::ProjectionFailed {
            face: FaceLocation {
                side: Some(side),
                tag,
            },
            point: self.setup.plane.lift(p).into(),
            iterations: f.iterations,
            residual: f.residual,
        }
    }

    /// The slave's reference coordinates of the point `v` of the plane.
    #[inline]
    fn slave_xi(&self, v: &Vector2<f64>) -> Result<Vector2<f64>> {
        let tol = self.ctx.interface.tolerances();
        self.setup
            .slave_map
            .invert(v, tol.newton, tol.newton_max_iterations)
            .map_err(|f| self.fail(f, v, Side::Slave, self.slave.tag))
    }

    /// One paired point at `c` (in-plane coordinates for an affine slave, the slave's
    /// reference coordinates otherwise) with quadrature weight `weight`.
    #[inline]
    fn point_at(&self, c: Vector2<f64>, weight: f64) -> Result<PairedPoint> {
        let tol = self.ctx.interface.tolerances();
        let setup = self.setup;
        let (p, xi_s, jac) = if setup.in_reference {
            // The surface's own measure (not the plane's): the measure the dual basis is
            // built with, so D stays diagonal on warped faces too.
            let (p, _) = setup.slave_map.eval(&c);
            let el = self.slave.element;
            (p, c, el.jacobian_det(self.slave.node_coords(), &c))
        } else {
            (c, self.slave_xi(&c)?, setup.measure)
        };
        let xi_m = self
            .master_map
            .invert(&p, tol.newton, tol.newton_max_iterations)
            .map_err(|f| self.fail(f, &p, Side::Master, self.ctx.master_tag(self.master)))?;
        Ok(PairedPoint {
            master: self.master,
            xi_slave: xi_s,
            xi_master: xi_m,
            weight: weight * jac,
        })
    }

    /// Degree 2 on an affine slave: the edge-midpoint rule on each fan triangle of `clip`.
    /// Its points on the spokes (centroid to vertex) are shared by neighbouring triangles, so
    /// an n-gon needs 2n points instead of 3n; still exact for degree 2. Where the integrands
    /// are of degree 2 at most (`exact`), any triangulation integrates them exactly and the
    /// fan from a vertex serves: n - 2 triangles, 2n - 3 points.
    fn midpoint_points(&self, clip: &Polygon, exact: bool, out: &mut PairedRule) -> Result<()> {
        let push = |c, weight, cells| {
            out.cells += cells;
            if weight > 0.0 {
                out.points.push(self.point_at(c, weight)?);
            }
            Ok(())
        };
        if exact {
            vertex_fan_midpoints(clip, push)
        } else {
            fan_midpoints(clip, push)
        }
    }

    /// The triangle rule `rule` on each triangle of `list` of positive area.
    fn triangle_points(
        &self,
        list: &[[Vector2<f64>; 3]],
        rule: &QuadratureRule,
        out: &mut PairedRule,
    ) -> Result<()> {
        for t in list {
            let e1 = t[1] - t[0];
            let e2 = t[2] - t[0];
            let twice_area = e1.x * e2.y - e1.y * e2.x;
            if twice_area <= 0.0 {
                continue;
            }
            out.cells += 1;
            for (q, w) in rule.points().iter().zip(rule.weights()) {
                out.points
                    .push(self.point_at(t[0] + e1 * q.x + e2 * q.y, w * twice_area)?);
            }
        }
        Ok(())
    }
}

/// The triangles a clip polygon is integrated on, kept between the pairs of one slave face.
struct CellBuffers {
    /// Whether each plane triangle is cut into `quad_subdivision^2` (a non-parallelogram quad
    /// integrated in its reference coordinates).
    cut: bool,
    quad_subdivision: u32,
    tris: ArrayVec<[Vector2<f64>; 3], MAX_POLYGON_VERTICES>,
    cut_tris: Vec<[Vector2<f64>; 3]>,
}

impl CellBuffers {
    /// The triangles of the last [`triangulate`](Self::triangulate).
    fn list(&self) -> &[[Vector2<f64>; 3]] {
        if self.cut {
            &self.cut_tris
        } else {
            &self.tris
        }
    }

    /// Triangulates `clip` for the pair `pair` (`exact`: the quadrature integrates the
    /// pair's integrands exactly on any triangulation).
    fn triangulate(&mut self, pair: &PairMaps<'_, '_>, clip: &Polygon, exact: bool) -> Result<()> {
        self.tris.clear();
        self.cut_tris.clear();
        if self.cut {
            // Each plane triangle of the centroid fan cut into m^2, its vertices mapped back:
            // the chords m times closer to the curved edges.
            let mut plane_tris: ArrayVec<[Vector2<f64>; 3], MAX_POLYGON_VERTICES> = ArrayVec::new();
            clip.for_each_triangle(|t| plane_tris.push(t));
            for t in &plane_tris {
                cut_triangle(
                    t,
                    self.quad_subdivision,
                    |v| pair.slave_xi(v),
                    &mut self.cut_tris,
                )?;
            }
        } else if pair.setup.in_reference {
            let mut xi_poly = Polygon::default();
            for v in &clip.vertices {
                xi_poly.vertices.push(pair.slave_xi(v)?);
            }
            xi_poly.for_each_triangle(|t| self.tris.push(t));
        } else if exact {
            // The cheapest triangulation serves: the fan from a vertex of the (convex) clip
            // polygon, n - 2 triangles instead of n.
            clip.for_each_fan_triangle(|t| self.tris.push(t));
        } else {
            // The quadrature is not exact: the fan from the centroid, whose triangles do not
            // depend on which vertex the polygon starts at (so that relabelling the faces
            // permutes D and M to round-off).
            clip.for_each_triangle(|t| self.tris.push(t));
        }
        Ok(())
    }
}

/// The auxiliary plane of a slave face: through its centre `x0` (returned too), normal to
/// the projection direction there, its first axis along the face's first edge.
///
/// # Errors
/// [`MortarError::DegenerateFace`] when the projection direction at the centre is zero.
pub(super) fn auxiliary_plane(
    ctx: &SegmentContext<'_>,
    slave: &FaceGeometry,
) -> Result<(AuxiliaryPlane, Vector3<f64>)> {
    let centre = slave.element.domain().centre();
    let x0 = slave.map(&centre);
    let (dir, _) = ctx.projector.direction(slave, &centre);
    let plane = AuxiliaryPlane::new(x0, dir, slave.nodes[1] - slave.nodes[0])
        .or_else(|| AuxiliaryPlane::from_normal(x0, dir))
        .ok_or_else(|| MortarError::DegenerateFace {
            face: slave.location(),
            reason: "the projection direction at its centre is zero".into(),
        })?;
    Ok((plane, x0))
}

/// The degree-2 edge-midpoint rule on the triangulation of `poly` (itself if a triangle,
/// else the fan from its vertex centroid), with the points on the spokes merged: calls `f`
/// with each point, its weight (zero for a point of degenerate triangles only) and the number
/// of cells (triangles of positive area) it completes.
fn fan_midpoints(
    poly: &Polygon,
    mut f: impl FnMut(Vector2<f64>, f64, u32) -> Result<()>,
) -> Result<()> {
    let v = &poly.vertices;
    let n = v.len();
    let area = clamped_area;
    if n == 3 {
        let a = area(&v[0], &v[1], &v[2]);
        let cells = u32::from(a > 0.0);
        for i in 0..3 {
            f(
                0.5 * (v[i] + v[(i + 1) % 3]),
                a / 3.0,
                if i == 0 { cells } else { 0 },
            )?;
        }
        return Ok(());
    }
    let c = poly.vertex_centroid();
    let tri_area = |i: usize| area(&c, &v[i % n], &v[(i + 1) % n]);
    for i in 0..n {
        let (prev, this) = (tri_area(i + n - 1), tri_area(i));
        // Spoke c - v_i, shared by triangles i - 1 and i; then the outer edge of triangle i.
        f(0.5 * (c + v[i]), (prev + this) / 3.0, u32::from(this > 0.0))?;
        f(0.5 * (v[i] + v[(i + 1) % n]), this / 3.0, 0)?;
    }
    Ok(())
}

/// The area of the triangle `a b c`, clamped at zero (a triangle turning the wrong way counts
/// as degenerate).
fn clamped_area(a: &Vector2<f64>, b: &Vector2<f64>, c: &Vector2<f64>) -> f64 {
    let (e1, e2) = (b - a, c - a);
    (0.5 * (e1.x * e2.y - e1.y * e2.x)).max(0.0)
}

/// The degree-2 edge-midpoint rule on the fan of `poly` from its first vertex (triangles
/// `v0 v_i v_i+1`), with the points on the diagonals merged: `2n - 3` points for an n-gon.
/// Calls `f` as [`fan_midpoints`] does. Exact for degree 2, like the centroid fan, but its
/// triangles depend on the first vertex: only for integrands the rule integrates exactly, so
/// that relabelling the faces changes D and M by round-off only.
fn vertex_fan_midpoints(
    poly: &Polygon,
    mut f: impl FnMut(Vector2<f64>, f64, u32) -> Result<()>,
) -> Result<()> {
    let v = &poly.vertices;
    let n = v.len();
    if n < 4 {
        return fan_midpoints(poly, f);
    }
    // Triangle i (1 <= i <= n - 2) is v0 v_i v_i+1.
    let tri = |i: usize| clamped_area(&v[0], &v[i], &v[i + 1]);
    let first = tri(1);
    f(0.5 * (v[0] + v[1]), first / 3.0, u32::from(first > 0.0))?;
    let mut prev = first;
    for i in 1..n - 1 {
        // The outer edge v_i v_i+1 of triangle i, then the diagonal v0 v_i+1 it shares with
        // triangle i + 1 (none after the last).
        f(0.5 * (v[i] + v[i + 1]), prev / 3.0, 0)?;
        if i + 1 < n - 1 {
            let next = tri(i + 1);
            f(
                0.5 * (v[0] + v[i + 1]),
                (prev + next) / 3.0,
                u32::from(next > 0.0),
            )?;
            prev = next;
        }
    }
    f(0.5 * (v[n - 1] + v[0]), prev / 3.0, 0)
}

/// Cuts the triangle `t` into `m^2` (the vertices `t0 + (i e1 + j e2) / m`, each mapped once by
/// `map`) and appends the mapped triangles to `out`, in `t`'s orientation.
fn cut_triangle(
    t: &[Vector2<f64>; 3],
    m: u32,
    map: impl Fn(&Vector2<f64>) -> Result<Vector2<f64>>,
    out: &mut Vec<[Vector2<f64>; 3]>,
) -> Result<()> {
    let m = m as usize;
    let (e1, e2) = ((t[1] - t[0]) / m as f64, (t[2] - t[0]) / m as f64);
    // Vertex (i, j), i + j <= m, row by row.
    let at = |i: usize, j: usize| j * (m + 1) - j * j.saturating_sub(1) / 2 + i;
    let mut v = Vec::with_capacity((m + 1) * (m + 2) / 2);
    for j in 0..=m {
        for i in 0..=m - j {
            v.push(map(&(t[0] + e1 * i as f64 + e2 * j as f64))?);
        }
    }
    for j in 0..m {
        for i in 0..m - j {
            out.push([v[at(i, j)], v[at(i + 1, j)], v[at(i, j + 1)]]);
            if i + j + 1 < m {
                out.push([v[at(i + 1, j)], v[at(i + 1, j + 1)], v[at(i, j + 1)]]);
            }
        }
    }
    Ok(())
}
