//! Linear multipliers on second-order faces: one multiplier per corner node, carrying the
//! first-order shape function of that corner; edge and centre nodes get none.

use arrayvec::ArrayVec;
use nalgebra::{DMatrix, Vector2};

use super::{LmBasis, MultiplierSpace};
use crate::element::{ReferenceDomain, SurfaceElement, MAX_FACE_NODES};
use crate::error::{MortarError, Result};
use crate::interface::FaceGeometry;
use crate::tolerances::Tolerances;

/// Linear multipliers on second-order faces: one multiplier per corner node, `Phi_c` the
/// first-order shape function of corner `c` (the Line2, Tri3 or Quad4 function of the same
/// corners), and none on the edge and centre nodes: their rows of D and M stay empty. On a
/// first-order face they are the standard multipliers.
///
/// The cheap, robust choice that several contact codes default to on quadratic meshes (4C's
/// `LM_QUAD = lin`, Puso and Laursen's "linear multipliers on quadratic faces"): the
/// multiplier space is the first-order one on the corner nodes, which is inf-sup stable
/// against the quadratic displacement or temperature traces and still reproduces linear
/// fluxes, so the tied field keeps the quadratic elements' rates (L2 3, H1 2; measured in
/// `examples/tied_heat.rs`), with a third to a half as many constraint rows (Tri6: corners
/// are about a quarter of a surface mesh's nodes, Quad8 a third, Quad9 a quarter).
///
/// In terms of the face's own shape functions, `Phi_c = sum_k L_c(xi_k) N_k` with `xi_k`
/// the reference coordinates of node `k`: exact wherever the face's shape functions contain
/// the first-order ones (Line3, Tri6, Quad8, Quad9, and the Lagrange elements of higher
/// degree); a face whose functions do not (checked at the centre and one point off it) is
/// refused with [`MortarError::MultiplierSpace`].
///
/// Consumers of the coupling see the same layout as with the other spaces (a row per slave
/// node), with the rows of the nodes that carry no multiplier empty; the tied systems of
/// `mortar-physics` keep only the rows that carry one.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LinearMultipliers;

impl MultiplierSpace for LinearMultipliers {
    fn name(&self) -> &'static str {
        "linear"
    }

    fn basis(&self, face: &FaceGeometry, _tol: &Tolerances) -> Result<LmBasis> {
        let el = face.element;
        let (k, c) = (el.node_count(), el.corner_count());
        if c >= k {
            return Ok(LmBasis::identity(k));
        }
        let fail = |reason: &str| MortarError::MultiplierSpace {
            space: "linear",
            face: face.location(),
            reason: format!("{} face: {reason}", el.name()),
        };
        let coefficients = corner_functions(el).ok_or_else(|| {
            fail("its corners do not span the first-order functions of its reference domain")
        })?;
        let linear = |corner: usize, xi: &Vector2<f64>| -> f64 {
            monomials(el.domain(), xi)
                .iter()
                .zip(coefficients.column(corner).iter())
                .map(|(m, a)| m * a)
                .sum()
        };
        let mut a = [[0.0; MAX_FACE_NODES]; MAX_FACE_NODES];
        let xi_nodes = el.node_reference_coords();
        for (corner, row) in a.iter_mut().enumerate().take(c) {
            for (node, v) in row.iter_mut().enumerate().take(k) {
                let x = Vector2::new(xi_nodes[node][0], xi_nodes[node][1]);
                *v = linear(corner, &x);
            }
        }
        // The face's functions must contain the corner functions.
        let centre = el.domain().centre();
        let off = centre + Vector2::new(0.137, if el.domain().dim() == 2 { 0.071 } else { 0.0 });
        let mut n = [0.0; MAX_FACE_NODES];
        for xi in [centre, off] {
            el.shape_values_into(&xi, &mut n[..k]);
            for (corner, row) in a.iter().enumerate().take(c) {
                let phi: f64 = row[..k].iter().zip(&n[..k]).map(|(a, n)| a * n).sum();
                if (phi - linear(corner, &xi)).abs() > 1e-10 {
                    return Err(fail(&format!(
                        "its shape functions do not reproduce the first-order function of \
                         corner {corner} (off by {:.1e} at xi = ({}, {}))",
                        (phi - linear(corner, &xi)).abs(),
                        xi.x,
                        xi.y
                    )));
                }
            }
        }
        Ok(LmBasis {
            nodes: k,
            identity: false,
            a,
        })
    }
}

/// The first-order polynomials of a reference domain: `1, xi` (line), `1, xi, eta`
/// (triangle), `1, xi, eta, xi eta` (quadrilateral).
fn monomials(domain: ReferenceDomain, xi: &Vector2<f64>) -> ArrayVec<f64, 4> {
    let all = [1.0, xi.x, xi.y, xi.x * xi.y];
    let count = match domain {
        ReferenceDomain::Line => 2,
        ReferenceDomain::Triangle => 3,
        ReferenceDomain::Quadrilateral => 4,
    };
    all[..count].iter().copied().collect()
}

/// The coefficients of the corner functions in [`monomials`] (column `c` for corner `c`):
/// the inverse of the corners' Vandermonde matrix; `None` when the corner count is not the
/// monomial count or the corners do not determine them.
fn corner_functions(el: &dyn SurfaceElement) -> Option<DMatrix<f64>> {
    let c = el.corner_count();
    let xi = el.node_reference_coords();
    let rows: Vec<ArrayVec<f64, 4>> = (0..c)
        .map(|d| monomials(el.domain(), &Vector2::new(xi[d][0], xi[d][1])))
        .collect();
    if rows.first().map(ArrayVec::len) != Some(c) {
        return None;
    }
    DMatrix::from_fn(c, c, |d, p| rows[d][p]).try_inverse()
}
