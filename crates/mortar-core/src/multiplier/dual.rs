use nalgebra::SMatrix;

use super::{LmBasis, MultiplierSpace};
use crate::element::MAX_FACE_NODES;
use crate::error::{MortarError, Result};
use crate::geometry::ModelGeometry;
use crate::interface::FaceGeometry;
use crate::interface::WARPED_EXTRA_DEGREE;
use crate::quadrature::{Quadrature, QuadratureRule};
use crate::tolerances::Tolerances;

type Square = SMatrix<f64, MAX_FACE_NODES, MAX_FACE_NODES>;

/// Dual (biorthogonal) multipliers (Wohlmuth): `Phi_j = sum_k A_jk N_k` with
/// `A = D_e M_e^-1`, computed per slave face with the face's own Jacobian, so that
/// `int_face Phi_j N_k = delta_jk int_face N_k`. On a fully covered interface D is diagonal.
///
/// For a flat Tri3 this gives the classical `Phi_j = 3 N_j - 1`, for a straight Line2
/// `Phi_1 = 2 N_1 - N_2`; for a Quad4, `A` depends on the face's shape.
///
/// With the axisymmetric measure ([`ModelGeometry::Axisymmetric`], through
/// [`basis_for`](MultiplierSpace::basis_for)) both `D_e` and `M_e` are weighted by the radius
/// `r` (the x coordinate) of each point, as in Popp et al. for any measure: then
/// `int_face Phi_j N_k r ds = delta_jk int_face N_k r ds`, and the D of the weighted coupling
/// is diagonal. On a Line2 from `r_1` to `r_2` the coefficients depend on `r_1 / r_2`; a face
/// lying on the axis (`r = 0` throughout) has a singular weighted mass matrix and is refused.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DualMultipliers;

impl MultiplierSpace for DualMultipliers {
    fn name(&self) -> &'static str {
        "dual"
    }

    fn diagonal_d(&self) -> bool {
        true
    }

    fn basis(&self, face: &FaceGeometry, _tol: &Tolerances) -> Result<LmBasis> {
        dual_basis(face, ModelGeometry::Cartesian)
    }

    fn basis_for(
        &self,
        face: &FaceGeometry,
        _tol: &Tolerances,
        geometry: ModelGeometry,
    ) -> Result<LmBasis> {
        dual_basis(face, geometry)
    }
}

/// The dual basis on `face`, biorthogonal with respect to the measure of `geometry`.
fn dual_basis(face: &FaceGeometry, geometry: ModelGeometry) -> Result<LmBasis> {
    let el = face.element;
    let k = face.node_count();
    // N_j N_k has degree 2p; the Jacobian of a planar quad adds 1 (2 with margin); that of
    // a warped or curved face is not a polynomial (WARPED_EXTRA_DEGREE more).
    let extra = if face.is_flat() {
        0
    } else {
        WARPED_EXTRA_DEGREE
    };
    let degree = (2 * el.shape_degree() + 2 + extra).min(20);
    let rule = QuadratureRule::cached(el.domain(), degree)?;
    let mut me = Square::identity();
    for j in 0..k {
        me[(j, j)] = 0.0;
    }
    let mut de = [0.0; MAX_FACE_NODES];
    let mut n = [0.0; MAX_FACE_NODES];
    for (xi, w) in rule.points().iter().zip(rule.weights()) {
        el.shape_values_into(xi, &mut n[..k]);
        let mut wj = w * el.jacobian_det(face.node_coords(), xi);
        if geometry.is_axisymmetric() {
            // The radius; the constant 2 pi cancels in D_e M_e^-1.
            wj *= face.map(xi).x.max(0.0);
        }
        for a in 0..k {
            de[a] += wj * n[a];
            for b in 0..k {
                me[(a, b)] += wj * n[a] * n[b];
            }
        }
    }
    let fail = |reason: &str| MortarError::MultiplierSpace {
        space: "dual",
        face: face.location(),
        reason: reason.to_string(),
    };
    let chol = me
        .cholesky()
        .ok_or_else(|| fail("the local mass matrix is not positive definite"))?;
    let inv = chol.inverse();
    let mut basis = LmBasis::identity(k);
    basis.identity = false;
    for j in 0..k {
        for i in 0..k {
            basis.a[j][i] = de[j] * inv[(j, i)];
        }
    }
    if basis.a[..k]
        .iter()
        .any(|row| row[..k].iter().any(|v| !v.is_finite()))
    {
        return Err(fail("non-finite coefficients"));
    }
    Ok(basis)
}
