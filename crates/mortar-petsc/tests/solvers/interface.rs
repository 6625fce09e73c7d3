//! PETSc behind the finite-element code's solver interface (`PetscBackend` as a
//! `SparseSolver`): the same calls as the direct backend (`FaerSolver`) give the same
//! solutions to the Krylov tolerance; a symmetric positive definite matrix given by its upper
//! triangle alone (all the interface promises to read) is solved as the full one; a new matrix
//! of the same pattern refactors; another pattern, or a solve that cannot converge, is a typed
//! error; each solve's report is kept.

use mortar_core::linalg::{SparseMatrix, Triplets};
use mortar_fem::linalg::{FaerSolver, MatrixKind, SolverError, SparseSolver};
use mortar_petsc::{KrylovMethod, PetscBackend, Preconditioner, SolveOptions};

use super::common::{poisson_2d, relative_error, rhs};

/// The upper triangle of `a`.
fn upper(a: &SparseMatrix) -> SparseMatrix {
    let mut t = Triplets::default();
    for (&v, (i, j)) in a.iter() {
        if i <= j {
            t.push(i as u32, j as u32, v);
        }
    }
    t.to_csr(a.rows(), a.cols())
}

fn backend(method: KrylovMethod, pc: Preconditioner) -> PetscBackend {
    let mut options = SolveOptions::new(method, pc);
    options.rtol = 1e-11;
    PetscBackend::new(options)
}

#[test]
fn petsc_answers_the_solver_interface_as_the_direct_backend_does() {
    let a = poisson_2d(32);
    let b = rhs(a.rows());
    let direct: &dyn SparseSolver = &FaerSolver;
    let reference = direct
        .factor(&a, MatrixKind::General)
        .unwrap()
        .solve(&b)
        .unwrap();
    let petsc = backend(KrylovMethod::Cg, Preconditioner::Gamg);
    let solver: &dyn SparseSolver = &petsc;
    // The full matrix as a general one, and its upper triangle as an SPD one.
    for (matrix, kind) in [
        (a.clone(), MatrixKind::General),
        (upper(&a), MatrixKind::SymmetricPositiveDefinite),
    ] {
        let x = solver.factor(&matrix, kind).unwrap().solve(&b).unwrap();
        let err = relative_error(&x, &reference);
        println!("{kind:?}: error against the direct solve {err:.2e}");
        assert!(err < 1e-10, "{kind:?}: {err:e}");
    }
    let reports = petsc.reports();
    assert_eq!(reports.len(), 2);
    assert!(reports
        .iter()
        .all(|r| r.reason.is_converged() && r.ksp_type == "cg"));

    // A new matrix of the same pattern (twice the old one): half the solution.
    let mut f = solver.factor(&a, MatrixKind::General).unwrap();
    f.refactor(&a.map(|v| 2.0 * v)).unwrap();
    let x = f.solve(&b).unwrap();
    let half: Vec<f64> = reference.iter().map(|v| 0.5 * v).collect();
    assert!(relative_error(&x, &half) < 1e-10);
    assert_eq!(f.stats().dim, a.rows());
    // Another pattern.
    let err = f.refactor(&poisson_2d(8)).unwrap_err();
    assert!(matches!(err, SolverError::PatternMismatch(_)), "{err}");
}

#[test]
fn a_solve_that_cannot_converge_is_the_interfaces_error() {
    let a = poisson_2d(16);
    let mut options = SolveOptions::new(KrylovMethod::Cg, Preconditioner::Jacobi);
    options.max_it = 3;
    let petsc = PetscBackend::new(options);
    let f = petsc.factor(&a, MatrixKind::General).unwrap();
    let err = f.solve(&rhs(a.rows())).unwrap_err();
    match &err {
        SolverError::NotConverged {
            iterations, method, ..
        } => {
            assert_eq!(*iterations, 3, "{err}");
            assert!(method.contains("cg+jacobi"), "{err}");
        }
        e => panic!("{e}"),
    }
    // The failure is kept by the backend, for a caller that retries another way; the
    // successful solves' reports stay empty.
    let failures = petsc.failures();
    assert_eq!(failures.len(), 1, "{failures:?}");
    assert!(failures[0].contains("DIVERGED_ITS"), "{failures:?}");
    assert!(petsc.reports().is_empty());
    let mut x = vec![0.0; 3];
    assert!(matches!(
        f.solve_in_place(&mut x),
        Err(SolverError::DimensionMismatch { .. })
    ));
}

/// The preconditioner is built once per matrix: the first solve of a "factorised" system
/// reports its set-up, the next solves of the same matrix keep it (`setup_kept`, no set-up
/// seconds) and give the same solutions as a fresh set-up would; new values
/// (`refactor`) build it again, once.
#[test]
fn the_preconditioner_is_set_up_once_per_matrix() {
    let a = poisson_2d(32);
    let b = rhs(a.rows());
    let b2: Vec<f64> = b.iter().enumerate().map(|(i, v)| v + i as f64).collect();
    let petsc = backend(KrylovMethod::Cg, Preconditioner::Gamg);
    let mut f = petsc.factor(&a, MatrixKind::General).unwrap();
    let x1 = f.solve(&b).unwrap();
    let x1_again = f.solve(&b).unwrap();
    let x2 = f.solve(&b2).unwrap();
    let fresh = petsc
        .factor(&a, MatrixKind::General)
        .unwrap()
        .solve(&b2)
        .unwrap();
    assert_eq!(
        x1, x1_again,
        "the kept set-up solves the same system the same way"
    );
    assert!(relative_error(&x2, &fresh) < 1e-12);
    f.refactor(&a.map(|v| 2.0 * v)).unwrap();
    let x_half = f.solve(&b).unwrap();
    let x_half_again = f.solve(&b).unwrap();
    let half: Vec<f64> = x1.iter().map(|v| 0.5 * v).collect();
    assert!(relative_error(&x_half, &half) < 1e-10);
    assert_eq!(x_half, x_half_again);
    let kept: Vec<bool> = petsc.reports().iter().map(|r| r.setup_kept).collect();
    assert_eq!(kept, [false, true, true, false, false, true]);
    for r in petsc.reports() {
        println!("{r}");
        assert!(r.setup_kept == (r.setup_seconds == 0.0), "{r}");
    }
}

/// An automatic backend picks the method by the system: CG with GAMG for the SPD Poisson
/// matrix, GMRES with the Schur fieldsplit for the tied Poisson saddle point (told its
/// multipliers are last); both match the direct solve to the tolerance, and the reports
/// say what ran.
#[test]
fn an_automatic_backend_picks_the_method_by_the_system() {
    use mortar_fem::linalg::SystemInfo;

    use super::common::tied_poisson;

    let petsc = PetscBackend::automatic(1e-10, "");
    let a = poisson_2d(32);
    let b = rhs(a.rows());
    let x = petsc
        .factor_system(
            &a,
            MatrixKind::SymmetricPositiveDefinite,
            SystemInfo::default(),
        )
        .unwrap()
        .solve(&b)
        .unwrap();
    let reference = FaerSolver
        .factor(&a, MatrixKind::General)
        .unwrap()
        .solve(&b)
        .unwrap();
    assert!(relative_error(&x, &reference) < 1e-8);

    let (k, primal) = tied_poisson(16);
    let b = rhs(k.rows());
    let info = SystemInfo {
        multipliers_last: k.rows() - primal,
        ..SystemInfo::default()
    };
    let x = petsc
        .factor_system(&k, MatrixKind::General, info)
        .unwrap()
        .solve(&b)
        .unwrap();
    let reference = FaerSolver
        .factor(&k, MatrixKind::General)
        .unwrap()
        .solve(&b)
        .unwrap();
    let err = relative_error(&x, &reference);
    let reports = petsc.reports();
    for r in &reports {
        println!("{r}");
    }
    assert!(err < 1e-6, "saddle point: {err:e}");
    let ran: Vec<(&str, &str)> = reports
        .iter()
        .map(|r| (r.ksp_type.as_str(), r.pc_type.as_str()))
        .collect();
    assert_eq!(ran, [("cg", "gamg"), ("gmres", "fieldsplit")]);
}

/// The method an automatic backend picks for a displacement field's SPD system: BoomerAMG
/// tuned for elasticity in 3D (the measured choice, docs/solvers.md), GAMG in 2D and for an
/// axisymmetric field; its options complete the pick and the caller's come after them.
#[test]
fn a_3d_displacement_field_gets_boomeramg_for_elasticity() {
    use mortar_fem::linalg::{SystemInfo, UnknownPlaces};
    use mortar_petsc::BOOMERAMG_ELASTICITY_3D;

    let petsc = PetscBackend::automatic(1e-10, "-pc_hypre_boomeramg_strong_threshold 0.5");
    let points = [[0.0, 0.0, 0.0]; 3];
    let pick = |dim: usize, axisymmetric: bool| {
        let info = SystemInfo {
            displacements: Some(UnknownPlaces {
                dim,
                axisymmetric,
                points: &points,
                components: &[0, 1, 2],
            }),
            ..SystemInfo::default()
        };
        petsc.method_for(MatrixKind::SymmetricPositiveDefinite, &info, 3)
    };
    let three = pick(3, false);
    assert_eq!(three.method, KrylovMethod::Cg);
    assert_eq!(three.preconditioner, Preconditioner::BoomerAmgElasticity3d);
    let text = three.options_string();
    assert!(
        text.starts_with("-pc_hypre_type boomeramg")
            && text.contains(BOOMERAMG_ELASTICITY_3D)
            && text.ends_with("-pc_hypre_boomeramg_strong_threshold 0.5"),
        "{text}"
    );
    assert_eq!(pick(2, false).preconditioner, Preconditioner::Gamg);
    assert_eq!(pick(3, true).preconditioner, Preconditioner::Gamg);
    let general = petsc.method_for(MatrixKind::General, &SystemInfo::default(), 3);
    assert_eq!(general.preconditioner, Preconditioner::Gamg);
}
