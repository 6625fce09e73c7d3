//! PETSc's life in a process: it starts at the first use, serves solves from several
//! threads one at a time, and once finalised answers a typed error instead of starting
//! again. Its own test binary (its own process), since finalising ends PETSc for the rest
//! of the process. Needs the `petsc` feature.

use mortar_core::linalg::SparseMatrix;
use mortar_petsc::{KrylovMethod, PetscError, PetscSolver, Preconditioner, SolveOptions};

/// The 1D Laplacian (2, -1) of `n` unknowns.
fn laplacian_1d(n: usize) -> SparseMatrix {
    let mut t = sprs::TriMat::new((n, n));
    for i in 0..n {
        t.add_triplet(i, i, 2.0);
        if i + 1 < n {
            t.add_triplet(i, i + 1, -1.0);
            t.add_triplet(i + 1, i, -1.0);
        }
    }
    t.to_csr()
}

#[test]
fn petsc_starts_once_serves_threads_and_finalizes_for_good() {
    let version = mortar_petsc::start().unwrap();
    assert!(version.starts_with("PETSc 3."), "{version}");
    assert_eq!(mortar_petsc::start().unwrap(), version);

    let a = laplacian_1d(200);
    let b = vec![1.0; 200];
    let solver = PetscSolver::new(SolveOptions::new(KrylovMethod::Cg, Preconditioner::Gamg));
    let iterations: Vec<usize> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..4)
            .map(|_| s.spawn(|| solver.solve(&a, &b).unwrap().report.iterations))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert!(
        iterations.windows(2).all(|w| w[0] == w[1]),
        "{iterations:?}"
    );

    mortar_petsc::finalize().unwrap();
    mortar_petsc::finalize().unwrap();
    assert!(matches!(solver.solve(&a, &b), Err(PetscError::Finalized)));
    assert!(matches!(mortar_petsc::start(), Err(PetscError::Finalized)));
}
