//! The 5-point Poisson system: PETSc's iterative solves agree with a direct solve (faer's
//! sparse LU) to their tolerance, and with algebraic multigrid the iterations hardly grow
//! with the size, where Jacobi's double with each halving of h (CG's iterations grow as the
//! square root of the condition number, here as m).

use mortar_fem::linalg::solve_sparse_lu;
use mortar_petsc::{ConvergedReason, KrylovMethod, PetscSolver, Preconditioner, SolveOptions};

use super::common::{poisson_2d, relative_error, relative_residual, rhs};

#[test]
fn iterative_and_mumps_solves_match_a_direct_solve() {
    let a = poisson_2d(24);
    let b = rhs(a.rows());
    let reference = solve_sparse_lu(&a, &b).unwrap();
    for (method, pc) in [
        (KrylovMethod::Cg, Preconditioner::Gamg),
        (KrylovMethod::Cg, Preconditioner::BoomerAmg),
        (KrylovMethod::Cg, Preconditioner::Jacobi),
        (KrylovMethod::Gmres, Preconditioner::Gamg),
        (KrylovMethod::PreOnly, Preconditioner::Lu),
    ] {
        let mut options = SolveOptions::new(method, pc);
        options.rtol = 1e-10;
        let solved = PetscSolver::new(options).solve(&a, &b).unwrap();
        println!("poisson 24x24: {}", solved.report);
        assert!(solved.report.reason.is_converged());
        // rtol on the (preconditioned) residual times the condition number (about 300).
        let err = relative_error(&solved.x, &reference);
        assert!(err < 1e-7, "{}: error {err:.2e}", solved.report);
        assert!(relative_residual(&a, &solved.x, &b) < 1e-8);
    }
}

#[test]
fn the_report_names_what_ran() {
    let a = poisson_2d(8);
    let solved = PetscSolver::new(SolveOptions::new(
        KrylovMethod::Cg,
        Preconditioner::BoomerAmg,
    ))
    .solve(&a, &rhs(64))
    .unwrap();
    let r = &solved.report;
    assert!(r.backend.starts_with("PETSc 3."), "{}", r.backend);
    assert_eq!((r.ksp_type.as_str(), r.pc_type.as_str()), ("cg", "hypre"));
    // (PETSC_OPTIONS, if set, follows.)
    assert!(
        r.options.starts_with("-pc_hypre_type boomeramg"),
        "{}",
        r.options
    );
    assert!(r.iterations > 0 && r.residual_norm > 0.0);
    assert!(matches!(
        r.reason,
        ConvergedReason::Rtol | ConvergedReason::Atol
    ));
}

/// CG iterations at m = 32, 64, 128 (1 024 to 16 384 unknowns) with each preconditioner.
fn iterations(pc: Preconditioner) -> Vec<usize> {
    [32, 64, 128]
        .into_iter()
        .map(|m| {
            let a = poisson_2d(m);
            let mut options = SolveOptions::new(KrylovMethod::Cg, pc.clone());
            options.rtol = 1e-8;
            let solved = PetscSolver::new(options).solve(&a, &rhs(a.rows())).unwrap();
            println!("poisson {m}x{m}: {}", solved.report);
            solved.report.iterations
        })
        .collect()
}

#[test]
fn amg_iterations_grow_slowly_with_the_size() {
    let jacobi = iterations(Preconditioner::Jacobi);
    let gamg = iterations(Preconditioner::Gamg);
    let boomer = iterations(Preconditioner::BoomerAmg);
    println!(
        "CG iterations at m = 32, 64, 128: jacobi {jacobi:?}, gamg {gamg:?}, boomeramg {boomer:?}"
    );
    // Jacobi: about doubling per halving of h.
    assert!(jacobi[2] as f64 > 3.0 * jacobi[0] as f64, "{jacobi:?}");
    for its in [&gamg, &boomer] {
        // Multigrid: a 16-fold larger system in at most 1.6 times the iterations, and far
        // fewer than Jacobi's.
        assert!((its[2] as f64) <= 1.6 * its[0] as f64 + 2.0, "{its:?}");
        assert!(its[2] * 5 < jacobi[2], "{its:?} vs {jacobi:?}");
    }
}
