//! The linear algebra of one contact Newton step: the system it solves, the saddle point by
//! sparse LU, and the symmetric solve of the condensed system.

use mortar_fem::linalg::{
    CholeskyFactorization, MatrixKind, SolverError, SparseMatrix, SparseSolver,
    SubstructuredCholesky, SystemInfo, Triplets,
};

use crate::linear_solve::Places;
use crate::SOLVER;

/// A backend of the solver interface for the Newton systems, instead of the direct solves,
/// and where the free displacements sit (if told).
#[derive(Clone, Copy)]
pub(super) struct Backend<'a> {
    pub solver: &'a dyn SparseSolver,
    pub free_places: Option<&'a Places>,
}

/// A Newton step: the displacement and pressure increments, and whether its system had to be
/// regularised (see [`condensed_step`](super::condensed::condensed_step)).
pub(super) type Step = (Vec<f64>, Vec<f64>, bool);

/// The Newton system of one step, on the free displacements and the slave-node pressures:
/// `[[K_ff, N_f^T], [A N_f, diag(C_p)]] [du; dp] = [-R_u; -C]`, `A = diag(-C_g / w)`.
pub(super) struct Linearised<'a> {
    pub nfree: usize,
    /// Free displacements of the slave body (the first `slave_free` of them).
    pub slave_free: usize,
    /// The weighted gaps `w_j g_j`.
    pub weighted_gap: &'a [f64],
    pub r_u: &'a [f64],
    pub n_free: &'a [Vec<(u32, f64)>],
    pub a: &'a [f64],
    pub c: &'a [f64],
    pub c_p: &'a [f64],
}

/// Factorises the general (unsymmetric or indefinite) Newton matrix `a` and solves
/// `a x = b` in place: the one step of the contact iteration that goes through the
/// backend's general factorisation, so that the backend is named here only.
pub(super) fn solve_general(a: &SparseMatrix, b: &mut [f64]) -> Result<(), SolverError> {
    solve_by(SOLVER, a, MatrixKind::General, SystemInfo::default(), b)
}

/// Solves `a x = b` in place by `backend`: `kind` and `info` as the backend is told them.
fn solve_by(
    backend: &dyn SparseSolver,
    a: &SparseMatrix,
    kind: MatrixKind,
    info: SystemInfo<'_>,
    b: &mut [f64],
) -> Result<(), SolverError> {
    backend.factor_system(a, kind, info)?.solve_in_place(b)
}

/// The step by sparse LU of the whole system (any D).
///
/// With a `backend`, the system goes to it as a saddle point with the pressures last.
pub(super) fn saddle_step(
    lin: &Linearised<'_>,
    kff: &SparseMatrix,
    backend: Option<Backend<'_>>,
) -> Result<Step, SolverError> {
    let (nfree, rows) = (lin.nfree, lin.c.len());
    let mut t = Triplets::default();
    for (v, (i, k)) in kff.iter() {
        t.push(i as u32, k as u32, *v);
    }
    let size = nfree + rows;
    let mut rhs = vec![0.0; size];
    for (i, r) in lin.r_u.iter().enumerate() {
        rhs[i] = -r;
    }
    for (j, row) in lin.n_free.iter().enumerate() {
        let pj = (nfree + j) as u32;
        for &(cf, v) in row {
            t.push(cf, pj, v);
            if lin.a[j] != 0.0 {
                t.push(pj, cf, lin.a[j] * v);
            }
        }
        // Keep the diagonal in the pattern (zero on active rows).
        t.push(pj, pj, lin.c_p[j]);
        rhs[nfree + j] = -lin.c[j];
    }
    let jac = t.to_csr(size, size);
    match backend {
        Some(backend) => {
            let info = SystemInfo {
                multipliers_last: rows,
                ..SystemInfo::default()
            };
            solve_by(backend.solver, &jac, MatrixKind::General, info, &mut rhs)?;
        }
        None => solve_general(&jac, &mut rhs)?,
    }
    let dp = rhs.split_off(nfree);
    Ok((rhs, dp, false))
}

/// Solves the symmetric `a x = b` in place: by body where that pays
/// ([`SubstructuredCholesky::try_new_if_worthwhile`], `master` saying which unknowns are the
/// master body's: the two bodies factorised side by side, the unknowns between them last),
/// else Cholesky in the elimination order that `perm` makes for `a` (asked for only then), or
/// LU if `a` is not positive definite. Whether it was solved by body.
///
/// With a `backend` (and where `a`'s unknowns sit, if told), `a` goes to it as symmetric
/// positive definite, or as a general matrix if that solve fails.
pub(super) fn solve_symmetric(
    a: &SparseMatrix,
    perm: &mut dyn FnMut(&SparseMatrix) -> Result<Vec<usize>, SolverError>,
    master: &[bool],
    b: &mut [f64],
    backend: Option<(&dyn SparseSolver, Option<&Places>)>,
) -> Result<bool, SolverError> {
    if let Some((solver, places)) = backend {
        let info = places.map(Places::info).unwrap_or_default();
        let rhs = b.to_vec();
        return match solve_by(solver, a, MatrixKind::SymmetricPositiveDefinite, info, b) {
            Ok(()) => Ok(false),
            Err(_) => {
                b.copy_from_slice(&rhs);
                solve_by(solver, a, MatrixKind::General, info, b).map(|()| false)
            }
        };
    }
    if let Ok(Some(f)) = SubstructuredCholesky::try_new_if_worthwhile(a, master) {
        return f.solve_in_place(b).map(|()| true);
    }
    match CholeskyFactorization::try_new_ordered(a, &perm(a)?) {
        Ok(f) => f.solve_in_place(b),
        Err(_) => solve_general(a, b),
    }
    .map(|()| false)
}
