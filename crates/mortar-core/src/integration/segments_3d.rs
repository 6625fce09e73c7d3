//! 3D segment-based integration: auxiliary plane, clipping, triangulation, quadrature.

use arrayvec::ArrayVec;
use nalgebra::Vector2;

use super::{default_degree, PairedPoint, PairedRule, SegmentContext};
use crate::element::{ReferenceDomain, MAX_FACE_NODES};
use crate::error::{MortarError, Result};
use crate::geometry::{
    clip_convex, invert_surface_map, AuxiliaryPlane, Polygon, MAX_POLYGON_VERTICES,
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
    let merge = tol.merge * spoly.diameter();
    let mut mp = [Vector2::zeros(); MAX_FACE_NODES];
    let mut clip = Polygon::default();
    let mut tris: ArrayVec<[Vector2<f64>; 3], MAX_POLYGON_VERTICES> = ArrayVec::new();

    for &m in candidates {
        let master = ctx.interface.master_face(m as usize);
        let km = master.node_count();
        for i in 0..km {
            mp[i] = plane.project(&master.nodes[i]);
        }
        let mut mpoly = Polygon::from_slice(&mp[..master.element.corner_count()]);
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
        let deg = degree.unwrap_or_else(|| default_degree(el, master.element));
        let rule = QuadratureRule::cached(ReferenceDomain::Triangle, deg)?;
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
                let xi_s = invert(slave, &sp[..ks], &p, &plane, ctx)?;
                let xi_m = invert(&master, &mp[..km], &p, &plane, ctx)?;
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

/// Reference coordinates of the face point that projects to `p` in the plane.
fn invert(
    face: &FaceGeometry,
    projected: &[Vector2<f64>],
    p: &Vector2<f64>,
    plane: &AuxiliaryPlane,
    ctx: &SegmentContext<'_>,
) -> Result<Vector2<f64>> {
    let tol = ctx.interface.tolerances();
    invert_surface_map(
        face.element,
        face.element.is_affine(),
        projected,
        p,
        tol.newton,
        tol.newton_max_iterations,
    )
    .map_err(|f| MortarError::ProjectionFailed {
        face: face.location(),
        point: plane.lift(p).into(),
        iterations: f.iterations,
        residual: f.residual,
    })
}
