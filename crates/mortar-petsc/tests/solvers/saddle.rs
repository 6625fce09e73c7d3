//! A tied saddle point `[A B^T; B 0]` (Poisson tied across a column of nodes): GMRES with
//! the Schur-complement fieldsplit (full factorisation), and MINRES with its symmetric
//! positive definite diagonal form, match a direct solve; MUMPS's LU solves it in one step.

use mortar_fem::linalg::solve_sparse_lu;
use mortar_petsc::{FieldSplit, KrylovMethod, PetscSolver, Preconditioner, SolveOptions};

use super::common::{relative_error, rhs, tied_poisson};

#[test]
fn schur_fieldsplit_solves_a_tied_saddle_point() {
    let (a, n) = tied_poisson(16);
    let b = rhs(a.rows());
    let reference = solve_sparse_lu(&a, &b).unwrap();
    let split = Preconditioner::FieldSplitSchur(FieldSplit {
        first: (0..n).collect(),
    });
    for (method, pc) in [
        (KrylovMethod::Gmres, split.clone()),
        (KrylovMethod::Minres, split),
        (KrylovMethod::PreOnly, Preconditioner::Lu),
    ] {
        let mut options = SolveOptions::new(method, pc);
        options.rtol = 1e-10;
        let solved = PetscSolver::new(options).solve(&a, &b).unwrap();
        println!("tied poisson 16x16 + 16: {}", solved.report);
        let err = relative_error(&solved.x, &reference);
        assert!(err < 1e-6, "{}: error {err:.2e}", solved.report);
    }
}
