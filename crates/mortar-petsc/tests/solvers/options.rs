//! Free-form PETSc options pass through and win over the typed ones, for one solve only; a
//! bad one is PETSc's typed error.

use mortar_petsc::{KrylovMethod, PetscError, PetscSolver, Preconditioner, SolveOptions};

use super::common::{poisson_2d, rhs};

#[test]
fn petsc_options_override_the_typed_ones_for_one_solve() {
    let a = poisson_2d(16);
    let b = rhs(a.rows());
    let mut options = SolveOptions::new(KrylovMethod::Cg, Preconditioner::Gamg);
    options.petsc_options =
        "-ksp_type gmres -ksp_gmres_restart 50 -pc_type hypre -pc_hypre_type boomeramg".into();
    let solved = PetscSolver::new(options).solve(&a, &b).unwrap();
    println!("{}", solved.report);
    assert_eq!(solved.report.ksp_type, "gmres");
    assert_eq!(solved.report.pc_type, "hypre");

    // The next solve does not see them.
    let solved = PetscSolver::new(SolveOptions::new(KrylovMethod::Cg, Preconditioner::Gamg))
        .solve(&a, &b)
        .unwrap();
    assert_eq!(
        (
            solved.report.ksp_type.as_str(),
            solved.report.pc_type.as_str()
        ),
        ("cg", "gamg")
    );
}

#[test]
fn a_petsc_tolerance_option_changes_the_iterations() {
    let a = poisson_2d(32);
    let b = rhs(a.rows());
    let run = |extra: &str| {
        let mut options = SolveOptions::new(KrylovMethod::Cg, Preconditioner::Jacobi);
        options.rtol = 1e-10;
        options.petsc_options = extra.into();
        PetscSolver::new(options)
            .solve(&a, &b)
            .unwrap()
            .report
            .iterations
    };
    let (tight, loose) = (run(""), run("-ksp_rtol 1e-3"));
    assert!(loose < tight, "{loose} vs {tight}");
}

#[test]
fn an_unknown_type_is_petscs_typed_error() {
    let a = poisson_2d(4);
    let options = SolveOptions {
        petsc_options: "-ksp_type no_such_method".into(),
        ..SolveOptions::default()
    };
    let err = PetscSolver::new(options).solve(&a, &rhs(16)).unwrap_err();
    println!("{err}");
    match &err {
        PetscError::Call {
            function, message, ..
        } => {
            assert_eq!(*function, "KSPSetFromOptions");
            assert!(message.contains("no_such_method"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}
