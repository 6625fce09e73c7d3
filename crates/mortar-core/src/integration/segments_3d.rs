//! 3D segment-based integration: auxiliary plane, clipping, triangulation, quadrature.

use arrayvec::ArrayVec;
use nalgebra::Vector2;

use super::{default_degree, PairedPoint, PairedRule, SegmentContext};
use crate::element::{ReferenceDomain, MAX_FACE_NODES};
use crate::error::{FaceLocation, MortarError, Result, Side};
use crate::geometry::{
    clip_convex, AuxiliaryPlane, InverseMapFailure, PlanarMap, Polygon, MAX_POLYGON_VERTICES,
};
use crate::interface::FaceGeometry;
use crate::quadrature::{Quadrature, QuadratureRule};

pub(super) fn segments_into(
    ctx: &SegmentContext<'_>,
    slave: &FaceGeometry,
    candidates: &[u32],
    degree: Option<u32>,
    out: &mut PairedRule,
) -> Result<()> {
    let tol = ctx.interface.tolerances();
    let el = slave.element;
    let centre = el.domain().centre();
    let x0 = slave.map(&centre);
    let (dir, _) = ctx.projector.direction(slave, &centre);
    let plane = AuxiliaryPlane::new(x0, dir, slave.nodes[1] - slave.nodes[0])
        .or_else(|| AuxiliaryPlane::from_normal(x0, dir))
        .ok_or_else(|| MortarError::DegenerateFace {
            face: slave.location(),
            reason: "the projection direction at its centre is zero".into(),
        })?;

    let ks = slave.node_count();
    let mut sp = [Vector2::zeros(); MAX_FACE_NODES];
    for i in 0..ks {
        sp[i] = plane.project(&slave.nodes[i]);
    }
    let spoly = Polygon::from_slice(&sp[..el.corner_count()]);
    let area_s = spoly.signed_area();
    if area_s <= 0.0 {
        return Err(MortarError::InvertedFace {
            face: slave.location(),
            reason: "its normal points against the projection direction at its centre".into(),
        });
    }
    let slave_map = PlanarMap::new(el, &sp[..ks]);
    let (s_lo, s_hi) = spoly
        .vertices
        .iter()
        .fold((sp[0], sp[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    let merge = tol.merge * spoly.diameter();
    let master_mesh = ctx.interface.master();
    let coords = master_mesh.coords();
    let mut mp = [Vector2::zeros(); MAX_FACE_NODES];
    let mut clip = Polygon::default();
    let mut tris: ArrayVec<[Vector2<f64>; 3], MAX_POLYGON_VERTICES> = ArrayVec::new();

    for &m in candidates {
        let view = master_mesh.face(m as usize);
        let mel = view.element;
        let km = view.nodes.len();
        for (p, &n) in mp.iter_mut().zip(view.nodes) {
            *p = plane.project(&coords[n as usize]);
        }
        // Quick rejection by in-plane bounding boxes before clipping.
        let corners = &mp[..mel.corner_count()];
        let (lo, hi) = corners
            .iter()
            .fold((corners[0], corners[0]), |(lo, hi), p| {
                (lo.inf(p), hi.sup(p))
            });
        if lo.x > s_hi.x + merge
            || lo.y > s_hi.y + merge
            || hi.x < s_lo.x - merge
            || hi.y < s_lo.y - merge
        {
            continue;
        }
        let mut mpoly = Polygon::from_slice(corners);
        let area_m = mpoly.signed_area();
        if area_m.abs() <= tol.clip_area * area_s {
            continue; // seen edge-on from the plane
        }
        if area_m < 0.0 {
            mpoly.reverse();
        }
        clip_convex(&mpoly, &spoly, merge, &mut clip);
        if clip.len() < 3 || clip.signed_area() <= tol.clip_area * area_s.min(area_m.abs()) {
            continue;
        }
        let deg = degree.unwrap_or_else(|| default_degree(el, mel));
        let rule = QuadratureRule::cached(ReferenceDomain::Triangle, deg)?;
        let master_map = PlanarMap::new(mel, &mp[..km]);
        tris.clear();
        clip.for_each_triangle(|t| tris.push(t));
        let mut any = false;
        for t in &tris {
            let e1 = t[1] - t[0];
            let e2 = t[2] - t[0];
            let twice_area = e1.x * e2.y - e1.y * e2.x;
            if twice_area <= 0.0 {
                continue;
            }
            any = true;
            out.cells += 1;
            for (q, w) in rule.points().iter().zip(rule.weights()) {
                let p = t[0] + e1 * q.x + e2 * q.y;
                let fail = |f: InverseMapFailure, side, tag| MortarError::ProjectionFailed {
                    face: FaceLocation {
                        side: Some(side),
                        tag,
                    },
                    point: plane.lift(&p).into(),
                    iterations: f.iterations,
                    residual: f.residual,
                };
                let xi_s = slave_map
                    .invert(&p, tol.newton, tol.newton_max_iterations)
                    .map_err(|f| fail(f, Side::Slave, slave.tag))?;
                let xi_m = master_map
                    .invert(&p, tol.newton, tol.newton_max_iterations)
                    .map_err(|f| fail(f, Side::Master, view.tag))?;
                out.points.push(PairedPoint {
                    master: m,
                    xi_slave: xi_s,
                    xi_master: xi_m,
                    weight: w * twice_area,
                });
            }
        }
        if any {
            out.pairs += 1;
            out.degrees |= 1 << deg;
        }
    }
    Ok(())
}
