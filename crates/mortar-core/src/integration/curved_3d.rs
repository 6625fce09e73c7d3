//! 3D segmentation of curved second-order faces: the clip polygon of two
//! curved faces is not polygonal, so each face is cut, in its reference coordinates, into
//! `L^2` sub-triangles (a `Tri6` into the `L^2` of a regular split, a `Quad8`/`Quad9` into
//! `L^2` squares of two triangles each), each replaced by the flat triangle through its mapped
//! corners; the projections of these onto the slave's auxiliary plane are clipped pairwise,
//! and each clip polygon is integrated in the slave's reference coordinates (through the
//! affine map of its slave sub-triangle) with the slave's own curved Jacobian, its points
//! mapped to the master through the affine map of the master sub-triangle. The integrands are
//! those of the curved faces; only the overlap's boundary and the master points follow the
//! sub-triangles, whose chord error falls as `L^-2`.
//!
//! The level `L` of a face comes from its bend `beta` (the largest distance of a node from
//! where the face's corners alone would put it, over the face's diameter) and the tolerance
//! `tol` of the strategy: `L = ceil(sqrt(beta / tol))`, at most [`MAX_SUBDIVISION`]; a face
//! with straight edges and centred nodes (`beta = 0`) is not cut. The slave face takes the
//! level of its own bend; every master face takes the level of the largest bend of the master
//! surface ([`Interface::master_bend`](crate::Interface::master_bend)), so that neighbouring
//! master faces trace their shared curved edges by the same chords and their sub-triangles
//! tile the projection without overlap or gap (with a level per master face they did not:
//! on a sphere the slave area was counted twice along such edges, D 4.1e-4 too large).

use arrayvec::ArrayVec;
use nalgebra::{Matrix2, Vector2, Vector3};

use super::{default_degree, overlap_counts, PairedPoint, PairedRule, SegmentContext};
use crate::element::{ElementRef, ReferenceDomain};
use crate::error::{Inversion, MortarError, Result};
use crate::geometry::{clip_convex, AuxiliaryPlane, Polygon};
use crate::interface::{FaceGeometry, WARPED_EXTRA_DEGREE};
use crate::quadrature::{Quadrature, QuadratureRule};

/// The largest subdivision level (`L^2` sub-triangles per side, twice that for quads).
pub const MAX_SUBDIVISION: u32 = 16;

/// The default tolerance of the curved-face subdivision: the bend left per sub-triangle,
/// `beta / L^2`, relative to the face's size.
pub const DEFAULT_CURVED_TOLERANCE: f64 = 1e-2;

/// The bend of a face: the largest distance of a node from the position its face's corners
/// give it by linear (bilinear) interpolation, over the face's diameter; 0 for a first-order
/// face and for a second-order face with straight edges and centred nodes.
pub fn bend(face: &FaceGeometry) -> f64 {
    let el = face.element;
    let (k, c) = (el.node_count(), el.corner_count());
    if k == c {
        return 0.0;
    }
    let x = face.node_coords();
    let r = el.node_reference_coords();
    let worst = (c..k)
        .map(|i| (x[i] - corner_map(el.domain(), &x[..c], &Vector2::new(r[i][0], r[i][1]))).norm())
        .fold(0.0, f64::max);
    worst / face.diameter().max(f64::MIN_POSITIVE)
}

/// The subdivision level of a face of bend `beta` for the tolerance `tol`.
pub fn subdivision_level(beta: f64, tol: f64) -> u32 {
    if beta <= 1e-12 {
        return 1;
    }
    ((beta / tol).sqrt().ceil() as u32).clamp(1, MAX_SUBDIVISION)
}

/// The point of the corners' linear (triangle) or bilinear (quad) interpolation at `xi`.
fn corner_map(domain: ReferenceDomain, c: &[Vector3<f64>], xi: &Vector2<f64>) -> Vector3<f64> {
    match domain {
        ReferenceDomain::Line => c[0] * (0.5 * (1.0 - xi.x)) + c[1] * (0.5 * (1.0 + xi.x)),
        ReferenceDomain::Triangle => c[0] * (1.0 - xi.x - xi.y) + c[1] * xi.x + c[2] * xi.y,
        ReferenceDomain::Quadrilateral => {
            let (a, b) = (xi.x, xi.y);
            (c[0] * ((1.0 - a) * (1.0 - b))
                + c[1] * ((1.0 + a) * (1.0 - b))
                + c[2] * ((1.0 + a) * (1.0 + b))
                + c[3] * ((1.0 - a) * (1.0 + b)))
                * 0.25
        }
    }
}

/// One flat sub-triangle of a face: its corners in the face's reference coordinates and in the
/// auxiliary plane, and the affine maps between them.
#[derive(Debug, Clone, Copy)]
struct SubTriangle {
    xi: [Vector2<f64>; 3],
    p: [Vector2<f64>; 3],
    /// `xi = xi[0] + to_xi (p - p[0])`.
    to_xi: Matrix2<f64>,
    lo: Vector2<f64>,
    hi: Vector2<f64>,
    /// Signed area in the plane.
    area: f64,
}

/// The sub-triangles of `face` at `level`, projected onto `plane`, into `out` (cleared).
/// Sub-triangles whose projection is degenerate are left out (their area is below `1e-14`
/// of the face's projected size).
fn sub_triangles(
    face: &FaceGeometry,
    plane: &AuxiliaryPlane,
    level: u32,
    out: &mut Vec<SubTriangle>,
) {
    out.clear();
    let l = level as usize;
    let mut push = |xi: [Vector2<f64>; 3]| {
        let p = xi.map(|x| plane.project(&face.map(&x)));
        let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
        let area = 0.5 * (e1.x * e2.y - e1.y * e2.x);
        let (f1, f2) = (xi[1] - xi[0], xi[2] - xi[0]);
        let pm = Matrix2::from_columns(&[e1, e2]);
        let Some(inv) = pm.try_inverse() else { return };
        let lo = p[0].inf(&p[1]).inf(&p[2]);
        let hi = p[0].sup(&p[1]).sup(&p[2]);
        out.push(SubTriangle {
            xi,
            p,
            to_xi: Matrix2::from_columns(&[f1, f2]) * inv,
            lo,
            hi,
            area,
        });
    };
    match face.element.domain() {
        ReferenceDomain::Triangle => {
            let at = |i: usize, j: usize| Vector2::new(i as f64 / l as f64, j as f64 / l as f64);
            for j in 0..l {
                for i in 0..l - j {
                    push([at(i, j), at(i + 1, j), at(i, j + 1)]);
                    if i + j + 1 < l {
                        push([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                    }
                }
            }
        }
        _ => {
            let at = |i: usize, j: usize| {
                Vector2::new(
                    -1.0 + 2.0 * i as f64 / l as f64,
                    -1.0 + 2.0 * j as f64 / l as f64,
                )
            };
            for j in 0..l {
                for i in 0..l {
                    let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                    push([a, b, c]);
                    push([a, c, d]);
                }
            }
        }
    }
}

/// Whether a slave face and its candidates need the curved segmentation: some face among them
/// bends (see [`bend`]).
pub(super) fn needs_subdivision(
    ctx: &SegmentContext<'_>,
    slave: &FaceGeometry,
    candidates: &[u32],
) -> bool {
    // The element type first: first-order faces (the common case) are never gathered.
    let second_order = |el: ElementRef| el.node_count() > el.corner_count();
    (second_order(slave.element) && bend(slave) > 1e-12)
        || candidates.iter().any(|&m| {
            second_order(ctx.masters.element(ctx.interface, m as usize))
                && bend(&ctx.master_face(m)) > 1e-12
        })
}

/// The paired rule of a slave face against its candidates by sub-triangles (see the module
/// documentation).
pub(super) fn segments_into(
    ctx: &SegmentContext<'_>,
    slave: &FaceGeometry,
    candidates: &[u32],
    degree: Option<u32>,
    level: impl Fn(f64) -> u32,
    out: &mut PairedRule,
) -> Result<()> {
    let tol = ctx.interface.tolerances();
    let el = slave.element;
    let (plane, x0) = super::segments_3d::auxiliary_plane(ctx, slave)?;
    let mut subs = Vec::new();
    sub_triangles(slave, &plane, level(bend(slave)), &mut subs);
    let area_s: f64 = subs.iter().map(|s| s.area).sum();
    if subs.iter().any(|s| s.area <= 0.0) || area_s <= 0.0 {
        return Err(MortarError::InvertedFace {
            face: slave.location(),
            kind: Inversion::AgainstProjection,
            reason: "a part of it turns against the projection direction at its centre".into(),
        });
    }
    let size = subs.iter().fold((subs[0].lo, subs[0].hi), |(lo, hi), s| {
        (lo.inf(&s.lo), hi.sup(&s.hi))
    });
    let diameter = (size.1 - size.0).norm();
    let rounding = 8.0 * f64::EPSILON * x0.amax();
    let merge = (tol.merge * diameter).max(rounding);
    let extra = if slave.is_flat() {
        1
    } else {
        WARPED_EXTRA_DEGREE
    };
    // One level for every master face, from the most bent of them: faces cut at different
    // levels would trace their shared curved edge by different chords, which overlap or
    // leave gaps in projection (the slave area counted twice or not at all there).
    let master_level = level(ctx.interface.master_bend());
    let mut msubs = Vec::new();
    let mut clip = Polygon::default();
    let mut tris: ArrayVec<[Vector2<f64>; 3], 16> = ArrayVec::new();
    let mut covered = 0.0;
    for &m in candidates {
        let master = ctx.master_face(m);
        sub_triangles(&master, &plane, master_level, &mut msubs);
        let deg = degree
            .unwrap_or_else(|| default_degree(el, master.element) + extra)
            .min(20);
        let rule = QuadratureRule::cached(ReferenceDomain::Triangle, deg)?;
        let pushed = out.points.len();
        let mut facing_away = false;
        let mut pair_area = 0.0;
        for t in &msubs {
            if t.lo.x > size.1.x + merge
                || t.lo.y > size.1.y + merge
                || t.hi.x < size.0.x - merge
                || t.hi.y < size.0.y - merge
            {
                continue;
            }
            if t.area.abs() <= tol.clip_area * area_s / subs.len() as f64 {
                continue; // seen edge-on
            }
            if t.area > 0.0 {
                facing_away = true;
                continue;
            }
            let mut tpoly = Polygon::from_slice(&t.p);
            tpoly.reverse();
            for s in &subs {
                if t.lo.x > s.hi.x + merge
                    || t.lo.y > s.hi.y + merge
                    || t.hi.x < s.lo.x - merge
                    || t.hi.y < s.lo.y - merge
                {
                    continue;
                }
                clip_convex(&tpoly, &Polygon::from_slice(&s.p), merge, &mut clip);
                let a = clip.signed_area();
                let floor = tol.clip_area * s.area.min(-t.area);
                if clip.len() < 3 || !overlap_counts(a, floor, rounding, diameter, &clip) {
                    continue;
                }
                pair_area += a;
                tris.clear();
                clip.for_each_triangle(|tri| tris.push(tri));
                for q in &tris {
                    // The plane triangle in the slave's reference coordinates (affine).
                    let xi = q.map(|p| s.xi[0] + s.to_xi * (p - s.p[0]));
                    let (f1, f2) = (xi[1] - xi[0], xi[2] - xi[0]);
                    let twice = f1.x * f2.y - f1.y * f2.x;
                    if twice <= 0.0 {
                        continue;
                    }
                    out.cells += 1;
                    let (e1, e2) = (q[1] - q[0], q[2] - q[0]);
                    for (r, w) in rule.points().iter().zip(rule.weights()) {
                        let xi_s = xi[0] + f1 * r.x + f2 * r.y;
                        let p = q[0] + e1 * r.x + e2 * r.y;
                        let xi_m = t.xi[0] + t.to_xi * (p - t.p[0]);
                        out.points.push(PairedPoint {
                            master: m,
                            xi_slave: xi_s,
                            xi_master: xi_m,
                            weight: w * twice * el.jacobian_det(slave.node_coords(), &xi_s),
                        });
                    }
                }
            }
        }
        if out.points.len() > pushed {
            out.pairs += 1;
            out.degrees |= 1 << deg;
            covered += pair_area;
        } else if facing_away {
            out.back_facing += 1;
        }
    }
    out.covered = Some(covered / area_s);
    Ok(())
}
