//! Dual (biorthogonal) multipliers: per slave face `A = D_e M_e^-1`, so that D is diagonal on a
//! covered interface, with the recombination of the shape functions that second-order faces
//! need first.

use nalgebra::SMatrix;

use super::{LmBasis, MultiplierFastPaths, MultiplierSpace};
use crate::element::{ElementRef, SurfaceElement, MAX_FACE_NODES};
use crate::error::{MortarError, Result};
use crate::geometry::ModelGeometry;
use crate::interface::WARPED_EXTRA_DEGREE;
use crate::interface::{FaceGeometry, Interface};
use crate::linalg::SparseMatrix;
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
/// **Second-order faces.** Where a corner's shape function integrates to zero or less over
/// the reference element (Tri6: 0; Quad8: -1/3 of 4), `D_e` would have a zero or negative
/// entry and the basis would be singular or ill-posed. There the shape functions are first
/// recombined (Popp, Gee and Wall, "Dual quadratic mortar finite element methods for 3D
/// finite deformation contact", SIAM J. Sci. Comput. 34, 2012): with `alpha =`
/// [`RECOMBINATION_ALPHA`], `N~_c = N_c + alpha sum_(m on an edge of c) N_m` for each corner
/// `c` and `N~_m = (1 - 2 alpha) N_m` for each edge node `m` (a centre node stays), so that
/// each `N~` integrates to a positive share of the face (Tri6 corners 1/15 of the face, edge
/// nodes 1/5; Quad8 corners 1/20, edge nodes 1/5), and the basis is built biorthogonal to the
/// `N~`: `int Phi_j N~_k = delta_jk int N~_k`. The `Phi_j` are returned in terms of the
/// face's own `N` (`a = A T` for `N~ = T N`), so D, M and everything built on them keep the
/// nodal unknowns; D is then `D~ T^-T` with `D~` diagonal (positive on a covered face), not
/// diagonal itself. The coupling gives `D~ = D T^T` and `T` too
/// ([`Coupling::recombined`](crate::Coupling::recombined)): the constraint in the slave
/// unknowns `u~ = T^-T u` of the recombined basis, `D~ u~_s = M u_m`, condenses. Line3 and
/// Quad9 faces (all integrals positive) and linear faces are not recombined.
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

    fn fast_paths(&self) -> Option<&dyn MultiplierFastPaths> {
        Some(self)
    }
}

impl MultiplierFastPaths for DualMultipliers {
    /// Biorthogonal, for either measure.
    fn diagonal_d(&self) -> bool {
        true
    }

    /// Tri6 and Quad8 faces are recombined (see [`DualMultipliers`]).
    fn recombines(&self) -> bool {
        true
    }

    /// On an affine face in the Cartesian measure: the face's constant Jacobian cancels from
    /// the coefficients (the axisymmetric measure weights them by the face's radii).
    fn basis_is_uniform(&self, element: ElementRef, geometry: ModelGeometry) -> bool {
        element.is_affine() && !geometry.is_axisymmetric()
    }
}

/// The weight `alpha` of the recombination of second-order shape functions (see
/// [`DualMultipliers`]): 1/5, as Popp, Gee and Wall (2012) take for Tri6 and Quad8.
pub const RECOMBINATION_ALPHA: f64 = 0.2;

/// The recombination `N~ = T N` of an element's shape functions when one of its corner
/// functions integrates to zero or less over the reference element (see [`DualMultipliers`]),
/// with the edge node of each pair of neighbouring corners found from the reference
/// coordinates; `None` when every corner function integrates to a positive value.
pub fn recombination(
    element: &dyn SurfaceElement,
) -> Option<SMatrix<f64, MAX_FACE_NODES, MAX_FACE_NODES>> {
    let (k, c) = (element.node_count(), element.corner_count());
    let rule = QuadratureRule::cached(element.domain(), element.shape_degree()).ok()?;
    let mut integral = [0.0; MAX_FACE_NODES];
    let mut n = [0.0; MAX_FACE_NODES];
    for (xi, w) in rule.points().iter().zip(rule.weights()) {
        element.shape_values_into(xi, &mut n[..k]);
        for i in 0..k {
            integral[i] += w * n[i];
        }
    }
    let scale = element.domain().measure();
    if integral[..c].iter().all(|&v| v > 1e-12 * scale) {
        return None;
    }
    let r = element.node_reference_coords();
    let mut t = Square::identity();
    for m in c..k {
        // The neighbouring corners (consecutive, cyclically) whose middle node m is.
        let edge = (0..c)
            .map(|a| (a, (a + 1) % c))
            .find(|&(a, b)| (0..2).all(|d| (0.5 * (r[a][d] + r[b][d]) - r[m][d]).abs() < 1e-12));
        if let Some((a, b)) = edge {
            t[(a, m)] += RECOMBINATION_ALPHA;
            t[(b, m)] += RECOMBINATION_ALPHA;
            t[(m, m)] = 1.0 - 2.0 * RECOMBINATION_ALPHA;
        }
    }
    Some(t)
}

/// The dual basis on `face`, biorthogonal with respect to the measure of `geometry`.
fn dual_basis(face: &FaceGeometry, geometry: ModelGeometry) -> Result<LmBasis> {
    let el = face.element;
    let k = face.node_count();
    let t = recombination(el);
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
        if let Some(t) = &t {
            // N~ = T N.
            let plain = n;
            for i in 0..k {
                n[i] = (0..k).map(|j| t[(i, j)] * plain[j]).sum();
            }
        }
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
    // A shape function integrating to zero or less would make its dual function vanish or
    // flip sign: the basis is not a basis of the multipliers then.
    let total: f64 = de[..k].iter().sum();
    if let Some(j) = (0..k).find(|&j| de[j] <= 1e-12 * total.abs()) {
        return Err(fail(&format!(
            "the shape function of its node {} integrates to {:.3e} of the face's measure \
             (not positive), so its dual function is not defined",
            j + 1,
            de[j] / total
        )));
    }
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
    if let Some(t) = &t {
        // Phi = A N~ = (A T) N.
        let a = basis.a;
        for j in 0..k {
            for i in 0..k {
                basis.a[j][i] = (0..k).map(|l| a[j][l] * t[(l, i)]).sum();
            }
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

/// The recombination of the slave side of `interface` as one matrix `T` over the coupling's
/// slave rows (`N~ = T N` node by node; see [`DualMultipliers`]), or `None` when no slave face
/// is recombined. With it, the dual coupling's D is `D~ T^-T` with `D~ = D T^T` diagonal on a
/// covered interface: the form in which the slave unknowns `u~ = T^-T u` condense out.
///
/// # Errors
/// [`MortarError::MultiplierSpace`] when an edge node is shared by a recombined face and one
/// that is not (a Tri6 beside a Quad9): then no one `T` serves both, and the dual D is still
/// right but its diagonal form `D T^T` does not exist.
pub fn slave_recombination(interface: &Interface) -> Result<Option<SparseMatrix>> {
    let slave = interface.slave();
    let rows = interface.slave_nodes().len();
    // Per slave row: the entries of its row of T (corner rows) and its diagonal.
    let mut diagonal = vec![1.0; rows];
    let mut recombined = vec![None::<bool>; rows];
    let mut off: Vec<(u32, u32)> = Vec::new();
    let mut any = false;
    // One recombination per element type (a quadrature of its shape functions each).
    let mut known: Vec<(ElementRef, Option<Square>)> = Vec::new();
    for f in 0..slave.face_count() {
        let face = slave.face(f);
        let t = match known
            .iter()
            .find(|(el, _)| std::ptr::addr_eq(*el, face.element))
        {
            Some((_, t)) => *t,
            None => {
                let t = recombination(face.element);
                known.push((face.element, t));
                t
            }
        };
        any |= t.is_some();
        let row = |i: usize| interface.slave_row(face.nodes[i]).map(|r| r as usize);
        let (k, c) = (face.element.node_count(), face.element.corner_count());
        for i in c..k {
            let Some(r) = row(i) else { continue };
            if recombined[r].is_some_and(|was| was != t.is_some()) {
                return Err(MortarError::MultiplierSpace {
                    space: "dual",
                    face: interface.slave_face(f).location(),
                    reason: format!(
                        "its node {} is an edge node of faces recombined and not recombined \
                         (second-order elements of different kinds side by side): no one \
                         recombination of the slave side",
                        i + 1
                    ),
                });
            }
            recombined[r] = Some(t.is_some());
        }
        let Some(t) = t else { continue };
        for m in c..k {
            let Some(rm) = row(m) else { continue };
            diagonal[rm] = t[(m, m)];
            for a in 0..c {
                if t[(a, m)] != 0.0 {
                    if let Some(ra) = row(a) {
                        off.push((ra as u32, rm as u32));
                    }
                }
            }
        }
    }
    if !any {
        return Ok(None);
    }
    off.sort_unstable();
    off.dedup();
    let mut tri = sprs::TriMat::new((rows, rows));
    for (r, d) in diagonal.iter().enumerate() {
        tri.add_triplet(r, r, *d);
    }
    for (a, m) in off {
        tri.add_triplet(a as usize, m as usize, RECOMBINATION_ALPHA);
    }
    Ok(Some(tri.to_csr()))
}
