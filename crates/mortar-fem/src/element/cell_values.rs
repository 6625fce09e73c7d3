//! `CellValues`: shape values, physical gradients, points and `J x w` of one volume cell at the
//! points of a quadrature rule, recomputed in place for each cell.

use nalgebra::Vector3;

use super::{jacobian_from_gradients, VolumeElementRef};
use crate::quadrature::VolumeQuadratureRule;

/// A cell whose Jacobian determinant is not positive at a quadrature point: the cell is
/// inverted (nodes in the wrong order), degenerate, or folded.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("Jacobian determinant {det:e} at quadrature point {point} is not positive")]
pub struct NonPositiveJacobian {
    /// The quadrature point.
    pub point: usize,
    /// The determinant there.
    pub det: f64,
}

/// Shape values, physical gradients, weights and points of one cell at the points of a
/// quadrature rule (deal.II's `FEValues`). Reused from cell to cell: after the first cell of
/// an element type, [`reinit`](CellValues::reinit) allocates nothing.
///
/// ```text
/// let mut cv = CellValues::default();
/// cv.reinit(element, rule, &nodes)?;
/// for q in 0..cv.len() {
///     for (a, ga) in cv.gradients(q).iter().enumerate() { /* k ga . gb cv.jxw(q) */ }
/// }
/// ```
#[derive(Debug, Clone, Default)]
pub struct CellValues {
    nodes: usize,
    element: Option<&'static str>,
    rule_points: Vec<Vector3<f64>>,
    ref_shape: Vec<f64>,
    ref_grads: Vec<[f64; 3]>,
    /// Whether the reference gradients are the same (bit for bit) at every point of the rule
    /// (an affine element): the Jacobian and the physical gradients are then computed once
    /// per cell, with the same bits as at each point.
    constant_gradients: bool,
    gradients: Vec<Vector3<f64>>,
    jxw: Vec<f64>,
    points: Vec<Vector3<f64>>,
}

impl CellValues {
    /// Empty values; call [`reinit`](CellValues::reinit).
    pub fn new() -> Self {
        Self::default()
    }

    /// Evaluates `element` with node coordinates `nodes` (at least `node_count` of them) at the
    /// points of `rule`.
    ///
    /// # Errors
    /// [`NonPositiveJacobian`] if the Jacobian determinant is not positive at a point.
    ///
    /// # Panics
    /// If `nodes` is shorter than the element's node count, or the rule is on another domain.
    pub fn reinit(
        &mut self,
        element: VolumeElementRef,
        rule: &VolumeQuadratureRule,
        nodes: &[Vector3<f64>],
    ) -> Result<(), NonPositiveJacobian> {
        assert_eq!(
            rule.domain(),
            element.domain(),
            "quadrature rule and element domains differ"
        );
        let k = element.node_count();
        let nq = rule.len();
        // Reference values are recomputed only when the element type or the rule changes.
        if self.element != Some(element.name()) || self.rule_points[..] != rule.points()[..] {
            self.nodes = k;
            self.ref_shape.resize(nq * k, 0.0);
            self.ref_grads.resize(nq * k, [0.0; 3]);
            for (q, xi) in rule.points().iter().enumerate() {
                element.shape_values_into(xi, &mut self.ref_shape[q * k..(q + 1) * k]);
                element.shape_gradients_into(xi, &mut self.ref_grads[q * k..(q + 1) * k]);
            }
            self.constant_gradients =
                (1..nq).all(|q| self.ref_grads[q * k..(q + 1) * k] == self.ref_grads[..k]);
            self.gradients.resize(nq * k, Vector3::zeros());
            self.jxw.resize(nq, 0.0);
            self.points.resize(nq, Vector3::zeros());
            self.element = Some(element.name());
            self.rule_points.clear();
            self.rule_points.extend_from_slice(rule.points());
        }
        let dim = element.dim();
        let nodes = &nodes[..k];
        let mut first_det = 0.0;
        for (q, w) in rule.weights().iter().enumerate() {
            if q > 0 && self.constant_gradients {
                // The same Jacobian and gradients as at point 0 (same inputs, same bits).
                self.gradients.copy_within(..k, q * k);
                self.jxw[q] = w * first_det;
                let n = &self.ref_shape[q * k..(q + 1) * k];
                self.points[q] = nodes
                    .iter()
                    .zip(n)
                    .fold(Vector3::zeros(), |x, (xa, na)| x + xa * *na);
                continue;
            }
            let g = &self.ref_grads[q * k..(q + 1) * k];
            let j = jacobian_from_gradients(dim, nodes, g);
            let det = j.determinant();
            if det.is_nan() || det <= 0.0 || det.is_infinite() {
                return Err(NonPositiveJacobian { point: q, det });
            }
            let jinv_t = j
                .try_inverse()
                .ok_or(NonPositiveJacobian { point: q, det })?
                .transpose();
            for (a, ga) in g.iter().enumerate() {
                let mut p = jinv_t * Vector3::from(*ga);
                if dim == 2 {
                    p.z = 0.0;
                }
                self.gradients[q * k + a] = p;
            }
            self.jxw[q] = w * det;
            first_det = det;
            let n = &self.ref_shape[q * k..(q + 1) * k];
            self.points[q] = nodes
                .iter()
                .zip(n)
                .fold(Vector3::zeros(), |x, (xa, na)| x + xa * *na);
        }
        Ok(())
    }

    /// Number of quadrature points.
    pub fn len(&self) -> usize {
        self.jxw.len()
    }

    /// Whether there is no point (before the first `reinit`).
    pub fn is_empty(&self) -> bool {
        self.jxw.is_empty()
    }

    /// Number of nodes of the current element.
    pub fn node_count(&self) -> usize {
        self.nodes
    }

    /// Shape function values at point `q`.
    pub fn shape(&self, q: usize) -> &[f64] {
        &self.ref_shape[q * self.nodes..(q + 1) * self.nodes]
    }

    /// Physical shape function gradients at point `q` (third component zero in 2D).
    pub fn gradients(&self, q: usize) -> &[Vector3<f64>] {
        &self.gradients[q * self.nodes..(q + 1) * self.nodes]
    }

    /// Quadrature weight times Jacobian determinant at point `q`.
    pub fn jxw(&self, q: usize) -> f64 {
        self.jxw[q]
    }

    /// The physical point `q`.
    pub fn point(&self, q: usize) -> Vector3<f64> {
        self.points[q]
    }

    /// The interpolated value `sum_a N_a(x_q) u_a` at point `q` for nodal values `u` of the
    /// cell (in element node order).
    pub fn value(&self, q: usize, u: &[f64]) -> f64 {
        self.shape(q).iter().zip(u).map(|(n, v)| n * v).sum()
    }

    /// The interpolated gradient `sum_a grad N_a(x_q) u_a` at point `q`.
    pub fn gradient(&self, q: usize, u: &[f64]) -> Vector3<f64> {
        self.gradients(q)
            .iter()
            .zip(u)
            .fold(Vector3::zeros(), |g, (ga, v)| g + ga * *v)
    }
}
