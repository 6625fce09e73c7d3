//! Inputs PETSc cannot solve come back as typed errors naming PETSc's reason and the
//! iterations, never as a panic or an abort.

use mortar_core::linalg::SparseMatrix;
use mortar_petsc::{
    ConvergedReason, KrylovMethod, PetscError, PetscSolver, Preconditioner, SolveOptions,
};

use super::common::{poisson_2d, rhs, tied_poisson};

#[test]
fn cg_on_an_indefinite_saddle_point_is_a_typed_error() {
    let (a, _) = tied_poisson(8);
    let err = PetscSolver::new(SolveOptions::new(KrylovMethod::Cg, Preconditioner::Jacobi))
        .solve(&a, &rhs(a.rows()))
        .unwrap_err();
    println!("{err}");
    // Jacobi meets the zero diagonal of the multiplier block (PETSc's Jacobi then uses 1),
    // and CG meets negative curvature.
    assert!(
        matches!(err, PetscError::NotConverged { reason, .. } if !reason.is_converged()),
        "{err:?}"
    );
}

#[test]
fn lu_of_a_singular_matrix_is_a_typed_error() {
    // The pure Neumann Laplacian of a path: rows sum to zero, constants in its kernel.
    let n: usize = 6;
    let mut indptr = vec![0];
    let (mut indices, mut data) = (Vec::new(), Vec::new());
    for i in 0..n {
        let lo = i.saturating_sub(1);
        let hi = (i + 1).min(n - 1);
        for j in lo..=hi {
            indices.push(j);
            data.push(if i == j { (hi - lo) as f64 } else { -1.0 });
        }
        indptr.push(indices.len());
    }
    let a = SparseMatrix::new((n, n), indptr, indices, data);
    let err = PetscSolver::new(SolveOptions::new(KrylovMethod::PreOnly, Preconditioner::Lu))
        .solve(&a, &rhs(n))
        .unwrap_err();
    println!("{err}");
    assert!(
        matches!(
            err,
            PetscError::Inaccurate { .. }
                | PetscError::NotConverged {
                    reason: ConvergedReason::DivergedPreconditionerFailed,
                    ..
                }
                | PetscError::Call { .. }
        ),
        "{err:?}"
    );
}

#[test]
fn too_few_iterations_is_a_typed_error_with_the_count() {
    let a = poisson_2d(32);
    let mut options = SolveOptions::new(KrylovMethod::Cg, Preconditioner::Jacobi);
    options.max_it = 5;
    let err = PetscSolver::new(options)
        .solve(&a, &rhs(a.rows()))
        .unwrap_err();
    println!("{err}");
    match err {
        PetscError::NotConverged {
            reason, iterations, ..
        } => {
            assert_eq!(reason, ConvergedReason::DivergedIterations);
            assert_eq!(iterations, 5);
        }
        other => panic!("{other:?}"),
    }
}

/// A preconditioner with a near-zero pivot weights the preconditioned residual, which PETSc's
/// test measures, by its inverse: left-preconditioned GMRES with Jacobi on `diag(1e-20, K)`
/// (`K` a 2D Poisson matrix) removes the first component in one step, the preconditioned
/// residual falls by about 1e-20 and PETSc reports convergence while the true residual of the
/// Poisson part is untouched. The solve is refused, not returned.
#[test]
fn a_converged_preconditioned_residual_with_a_large_true_one_is_refused() {
    let k = poisson_2d(8);
    let n = k.rows() + 1;
    let mut indptr = vec![0, 1];
    let (mut indices, mut data) = (vec![0], vec![1e-20]);
    for row in k.outer_iterator() {
        for (j, v) in row.iter() {
            indices.push(j + 1);
            data.push(*v);
        }
        indptr.push(indices.len());
    }
    let a = SparseMatrix::new((n, n), indptr, indices, data);
    let mut options = SolveOptions::new(KrylovMethod::Gmres, Preconditioner::Jacobi);
    options.rtol = 1e-12;
    let err = PetscSolver::new(options).solve(&a, &rhs(n)).unwrap_err();
    println!("{err}");
    match err {
        PetscError::Inaccurate {
            relative_residual,
            tolerance,
            ..
        } => {
            assert_eq!(tolerance, mortar_petsc::accepted_residual(1e-12));
            assert!(relative_residual > 1e-3, "{relative_residual}");
        }
        other => panic!("{other:?}"),
    }
}
