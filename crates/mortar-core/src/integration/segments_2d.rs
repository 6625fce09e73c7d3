//! 2D segment-based integration on line interfaces.

use nalgebra::{Vector2, Vector3};

use super::{default_degree, PairedPoint, PairedRule, SegmentContext};
use crate::element::{ReferenceDomain, MAX_FACE_NODES};
use crate::error::{MortarError, Result};
use crate::geometry::invert_line_map;
use crate::interface::FaceGeometry;
use crate::quadrature::{Quadrature, QuadratureRule};

/// z-component of the cross product of two vectors of the xy-plane.
#[inline]
fn cross2(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

pub(super) fn segments_into(
    ctx: &SegmentContext<'_>,
    slave: &FaceGeometry,
    candidates: &[u32],
    degree: Option<u32>,
    out: &mut PairedRule,
) -> Result<()> {
    let tol = ctx.interface.tolerances();
    let centre = Vector2::zeros();
    let (n_s, _) = ctx.projector.direction(slave, &centre);
    for &m in candidates {
        let master = ctx.interface.master_face(m as usize);
        let n_m = master.element.unit_normal(master.node_coords(), &centre);
        if n_m.dot(&n_s) >= 0.0 {
            // The master line does not face the slave (far side of a thin body, or oriented
            // the wrong way round).
            out.back_facing += 1;
            continue;
        }
        // The master's end nodes, projected onto the slave line along the direction field.
        let Some(a) = project_onto_slave(ctx, slave, &master.nodes[0]) else {
            continue;
        };
        let Some(b) = project_onto_slave(ctx, slave, &master.nodes[1]) else {
            continue;
        };
        let lo = a.min(b).max(-1.0);
        let hi = a.max(b).min(1.0);
        if hi - lo <= tol.clip_area * 2.0 {
            continue;
        }
        let deg = degree.unwrap_or_else(|| default_degree(slave.element, master.element));
        let rule = QuadratureRule::cached(ReferenceDomain::Line, deg)?;
        out.pairs += 1;
        out.cells += 1;
        out.degrees |= 1 << deg;
        let half = 0.5 * (hi - lo);
        let mut values = [0.0; MAX_FACE_NODES];
        let km = master.node_count();
        for (g, w) in rule.points().iter().zip(rule.weights()) {
            let xi = Vector2::new(lo + half * (g.x + 1.0), 0.0);
            let x = slave.map(&xi);
            let (d, _) = ctx.projector.direction(slave, &xi);
            for i in 0..km {
                values[i] = cross2(&(master.nodes[i] - x), &d);
            }
            let eta = invert_line_map(
                master.element,
                master.element.is_affine(),
                &values[..km],
                0.0,
                tol.newton,
                tol.newton_max_iterations,
            )
            .map_err(|f| MortarError::ProjectionFailed {
                face: master.location(),
                point: x.into(),
                iterations: f.iterations,
                residual: f.residual,
            })?;
            let weight = w * half * slave.element.jacobian_det(slave.node_coords(), &xi);
            out.points.push(PairedPoint {
                master: m,
                xi_slave: xi,
                xi_master: Vector2::new(eta.clamp(-1.0, 1.0), 0.0),
                weight,
            });
        }
    }
    Ok(())
}

/// The slave coordinate `xi` with `y - x(xi)` parallel to the direction `d(xi)`: Newton on
/// `F(xi) = (y - x(xi)) x d(xi)`. Falls back to the (linear) projection along the direction at
/// the face centre if Newton fails; `None` if that is singular too (the line is parallel).
fn project_onto_slave(
    ctx: &SegmentContext<'_>,
    slave: &FaceGeometry,
    y: &Vector3<f64>,
) -> Option<f64> {
    let tol = ctx.interface.tolerances();
    let el = slave.element;
    let mut xi = Vector2::zeros();
    for _ in 0..tol.newton_max_iterations {
        let x = slave.map(&xi);
        let [t, _] = el.tangents(slave.node_coords(), &xi);
        let (d, dd) = ctx.projector.direction(slave, &xi);
        let r = y - x;
        let f = cross2(&r, &d);
        let df = -cross2(&t, &d) + cross2(&r, &dd[0]);
        if df == 0.0 || !df.is_finite() {
            break;
        }
        let step = f / df;
        xi.x -= step;
        if step.abs() <= tol.newton {
            return Some(xi.x);
        }
        if xi.x.abs() > 1e3 {
            break;
        }
    }
    // Fallback: project along the constant direction at the centre.
    let c = Vector2::zeros();
    let (d, _) = ctx.projector.direction(slave, &c);
    let mut values = [0.0; MAX_FACE_NODES];
    let k = slave.node_count();
    for i in 0..k {
        values[i] = cross2(&(slave.nodes[i] - y), &d);
    }
    invert_line_map(
        el,
        el.is_affine(),
        &values[..k],
        0.0,
        tol.newton,
        tol.newton_max_iterations,
    )
    .ok()
}
