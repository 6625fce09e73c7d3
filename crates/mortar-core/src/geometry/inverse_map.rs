//! Inverse maps of surface elements: the reference coordinates of a point, by Newton's method
//! on the face's map projected into a plane, or on a line's map along one coordinate, with
//! the reason when it fails.

use nalgebra::{Matrix2, Vector2};

use crate::element::{ReferenceElement, MAX_FACE_NODES};

/// Why an inverse map failed: Newton did not converge, or met a singular Jacobian.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InverseMapFailure {
    /// Iterations made.
    pub iterations: usize,
    /// Norm of the last update (reference units), or infinity for a singular Jacobian.
    pub residual: f64,
}

/// Finds reference coordinates `xi` with `sum_i N_i(xi) p_i = target`, where `p_i` are the
/// element's nodes projected into a plane (2D points). This inverts the projection of a face
/// onto the auxiliary plane: for affine elements (Tri3) it takes one Newton step, for bilinear
/// quads a few.
///
/// # Errors
/// [`InverseMapFailure`] when Newton does not converge to `tol` (reference units) within
/// `max_iterations`, or the Jacobian is singular.
pub fn invert_surface_map<E: ReferenceElement + ?Sized>(
    element: &E,
    affine: bool,
    nodes: &[Vector2<f64>],
    target: &Vector2<f64>,
    tol: f64,
    max_iterations: usize,
) -> Result<Vector2<f64>, InverseMapFailure> {
    let mut xi = element.domain().centre();
    let mut last = f64::INFINITY;
    for it in 0..max_iterations.max(1) {
        let (x, j) = planar_map_and_jacobian(element, nodes, &xi);
        let r = x - target;
        let Some(inv) = j.try_inverse() else {
            return Err(InverseMapFailure {
                iterations: it,
                residual: f64::INFINITY,
            });
        };
        let dx = inv * r;
        xi -= dx;
        last = dx.norm();
        if affine || last <= tol {
            return Ok(xi);
        }
    }
    Err(InverseMapFailure {
        iterations: max_iterations,
        residual: last,
    })
}

/// The point `sum_i N_i(xi) p_i` of a face whose nodes `p_i` lie in a plane, and its 2x2
/// Jacobian with respect to `xi`.
pub(super) fn planar_map_and_jacobian<E: ReferenceElement + ?Sized>(
    element: &E,
    nodes: &[Vector2<f64>],
    xi: &Vector2<f64>,
) -> (Vector2<f64>, Matrix2<f64>) {
    let k = element.node_count();
    let mut n = [0.0; MAX_FACE_NODES];
    let mut g = [[0.0; 2]; MAX_FACE_NODES];
    element.shape_values_into(xi, &mut n[..k]);
    element.shape_gradients_into(xi, &mut g[..k]);
    let mut x = Vector2::zeros();
    let mut j = Matrix2::zeros();
    for i in 0..k {
        x += nodes[i] * n[i];
        j[(0, 0)] += nodes[i].x * g[i][0];
        j[(0, 1)] += nodes[i].x * g[i][1];
        j[(1, 0)] += nodes[i].y * g[i][0];
        j[(1, 1)] += nodes[i].y * g[i][1];
    }
    (x, j)
}

/// Finds the reference coordinate `xi` of a line element with `sum_i N_i(xi) s_i = target`,
/// where `s_i` are scalar nodal values (the nodes' coordinates along a line).
///
/// # Errors
/// [`InverseMapFailure`] when Newton does not converge or the derivative vanishes.
pub fn invert_line_map<E: ReferenceElement + ?Sized>(
    element: &E,
    affine: bool,
    values: &[f64],
    target: f64,
    tol: f64,
    max_iterations: usize,
) -> Result<f64, InverseMapFailure> {
    let k = element.node_count();
    let mut xi = Vector2::zeros();
    let mut n = [0.0; MAX_FACE_NODES];
    let mut g = [[0.0; 2]; MAX_FACE_NODES];
    let mut last = f64::INFINITY;
    for it in 0..max_iterations.max(1) {
        element.shape_values_into(&xi, &mut n[..k]);
        element.shape_gradients_into(&xi, &mut g[..k]);
        let mut r = -target;
        let mut d = 0.0;
        for i in 0..k {
            r += values[i] * n[i];
            d += values[i] * g[i][0];
        }
        if d == 0.0 || !d.is_finite() {
            return Err(InverseMapFailure {
                iterations: it,
                residual: f64::INFINITY,
            });
        }
        let dx = r / d;
        xi.x -= dx;
        last = dx.abs();
        if affine || last <= tol {
            return Ok(xi.x);
        }
    }
    Err(InverseMapFailure {
        iterations: max_iterations,
        residual: last,
    })
}
