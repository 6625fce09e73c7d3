//! Tests of the sparse solvers: LU and Cholesky factorisations (solve, refactor with the
//! symbolic analysis reused, typed errors), restarted GMRES against the direct solve, and the
//! solver interface (`SparseSolver`, `Factorization`) against the factorisations it wraps.

use mortar_fem::linalg::{
    gmres, CholeskyFactorization, GmresOptions, IdentityPreconditioner, LinearOperator,
    LuFactorization, SaddlePointFactorization, SolverError, SparseMatrix, Triplets,
};

/// The 2D five-point Laplacian on an `n x n` grid plus a convection term `c` (non-symmetric
/// for `c != 0`), scaled by `scale`.
fn convection_diffusion(n: usize, c: f64, scale: f64) -> SparseMatrix {
    let mut t = Triplets::default();
    let id = |i: usize, j: usize| (i + n * j) as u32;
    for j in 0..n {
        for i in 0..n {
            let r = id(i, j);
            t.push(r, r, 4.0 * scale);
            if i > 0 {
                t.push(r, id(i - 1, j), (-1.0 - c) * scale);
            }
            if i + 1 < n {
                t.push(r, id(i + 1, j), (-1.0 + c) * scale);
            }
            if j > 0 {
                t.push(r, id(i, j - 1), -scale);
            }
            if j + 1 < n {
                t.push(r, id(i, j + 1), -scale);
            }
        }
    }
    t.to_csr(n * n, n * n)
}

fn residual(a: &SparseMatrix, x: &[f64], b: &[f64]) -> f64 {
    let mut ax = vec![0.0; b.len()];
    a.apply(x, &mut ax);
    let r: f64 = ax.iter().zip(b).map(|(p, q)| (p - q).powi(2)).sum();
    let nb: f64 = b.iter().map(|v| v * v).sum();
    (r / nb).sqrt()
}

fn rhs(n: usize) -> Vec<f64> {
    (0..n).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect()
}

#[test]
fn lu_solves_non_symmetric_systems_and_refactors() {
    let a = convection_diffusion(12, 0.4, 1.0);
    let b = rhs(a.rows());
    let mut lu = LuFactorization::try_new(&a).unwrap();
    assert_eq!(lu.dim(), 144);
    let x = lu.solve(&b).unwrap();
    assert!(residual(&a, &x, &b) < 1e-13);
    // Same pattern, new values: the symbolic analysis is reused.
    let a2 = convection_diffusion(12, -0.7, 3.0);
    lu.refactor(&a2).unwrap();
    let x2 = lu.solve(&b).unwrap();
    assert!(residual(&a2, &x2, &b) < 1e-13);
    // CSC storage of the same matrix gives the same solution.
    let csc = a2.to_csc();
    let x3 = LuFactorization::try_new(&csc).unwrap().solve(&b).unwrap();
    for (p, q) in x2.iter().zip(&x3) {
        assert!((p - q).abs() < 1e-12);
    }
}

#[test]
fn lu_handles_a_zero_diagonal_block() {
    // [[K, B^T], [B, 0]] with K = 2 I (3x3), B = [1 1 1].
    let mut t = Triplets::default();
    for i in 0..3 {
        t.push(i, i, 2.0);
        t.push(i, 3, 1.0);
        t.push(3, i, 1.0);
    }
    let a = t.to_csr(4, 4);
    let x = LuFactorization::try_new(&a)
        .unwrap()
        .solve(&[1.0, 2.0, 3.0, 0.0])
        .unwrap();
    // x_i = (f_i - lambda) / 2 with sum x = 0: lambda = 2.
    assert!((x[3] - 2.0).abs() < 1e-14);
    assert!((x[0] + 0.5).abs() < 1e-14 && x[1].abs() < 1e-14 && (x[2] - 0.5).abs() < 1e-14);
}

#[test]
fn cholesky_solves_and_refactors_and_refuses_indefinite_matrices() {
    let a = convection_diffusion(15, 0.0, 1.0);
    let b = rhs(a.rows());
    let mut llt = CholeskyFactorization::try_new(&a).unwrap();
    let x = llt.solve(&b).unwrap();
    assert!(residual(&a, &x, &b) < 1e-13);
    let lu = LuFactorization::try_new(&a).unwrap().solve(&b).unwrap();
    for (p, q) in x.iter().zip(&lu) {
        assert!((p - q).abs() < 1e-12 * (1.0 + q.abs()));
    }
    let a2 = convection_diffusion(15, 0.0, 0.25);
    llt.refactor(&a2).unwrap();
    let x2 = llt.solve(&b).unwrap();
    for (p, q) in x2.iter().zip(&x) {
        assert!((p - 4.0 * q).abs() < 1e-11 * (1.0 + q.abs()));
    }
    let neg = convection_diffusion(15, 0.0, -1.0);
    assert!(matches!(
        llt.refactor(&neg),
        Err(SolverError::NotPositiveDefinite { .. })
    ));
    // The failed refactor kept the previous factors.
    assert_eq!(llt.solve(&b).unwrap(), x2);
    assert!(matches!(
        CholeskyFactorization::try_new(&neg),
        Err(SolverError::NotPositiveDefinite { .. })
    ));
}

/// `[[K, B^T], [B, 0]]`: `K` the Laplacian of an `n x n` grid scaled by `scale`, `B` one row
/// per constraint tying unknown `i` to unknown `n^2 - 1 - i` (`i < constraints`) and a last
/// row fixing the mean if `mean`.
fn saddle(n: usize, scale: f64, constraints: usize, mean: bool) -> (SparseMatrix, usize) {
    let k = convection_diffusion(n, 0.0, scale);
    let nk = k.rows();
    let mut t = Triplets::default();
    for (r, row) in k.outer_iterator().enumerate() {
        for (c, v) in row.iter() {
            t.push(r as u32, c as u32, *v);
        }
    }
    let mut rows = 0;
    for i in 0..constraints {
        let r = (nk + rows) as u32;
        for (c, v) in [(i, 1.0), (nk - 1 - i, -1.0)] {
            t.push(r, c as u32, v);
            t.push(c as u32, r, v);
        }
        rows += 1;
    }
    if mean {
        let r = (nk + rows) as u32;
        for c in 0..nk {
            t.push(r, c as u32, 1.0 / nk as f64);
            t.push(c as u32, r, 1.0 / nk as f64);
        }
        rows += 1;
    }
    (t.to_csr(nk + rows, nk + rows), rows)
}

#[test]
fn saddle_point_ldlt_matches_lu_refactors_and_refuses_a_zero_pivot() {
    let (a, m) = saddle(15, 1.0, 20, true);
    let b = rhs(a.rows());
    let mut ldlt = SaddlePointFactorization::try_new(&a, m).unwrap();
    assert_eq!(ldlt.dim(), a.rows());
    let x = ldlt.solve(&b).unwrap();
    assert!(residual(&a, &x, &b) < 1e-14, "{}", residual(&a, &x, &b));
    let lu = LuFactorization::try_new(&a).unwrap().solve(&b).unwrap();
    for (p, q) in x.iter().zip(&lu) {
        assert!((p - q).abs() < 1e-12 * (1.0 + q.abs()), "{p} vs {q}");
    }
    // Same pattern, new values; CSC storage alike.
    let (a2, _) = saddle(15, 1e6, 20, true);
    ldlt.refactor(&a2).unwrap();
    let x2 = ldlt.solve(&b).unwrap();
    // K at 1e6 beside constraints of 1: the residual's floor is LU's too.
    let lu2 = LuFactorization::try_new(&a2).unwrap().solve(&b).unwrap();
    let (r_ldlt, r_lu) = (residual(&a2, &x2, &b), residual(&a2, &lu2, &b));
    assert!(
        r_ldlt <= 2.0 * r_lu + 1e-14,
        "LDL^T {r_ldlt:e}, LU {r_lu:e}"
    );
    let x3 = SaddlePointFactorization::try_new(&a2.to_csc(), m)
        .unwrap()
        .solve(&b)
        .unwrap();
    for (p, q) in x2.iter().zip(&x3) {
        assert!((p - q).abs() < 1e-12 * (1.0 + q.abs()));
    }
    // [[0, 1], [1, 0]]: the primal pivot is zero; only pivoting (LU) solves it.
    let mut t = Triplets::default();
    t.push(0, 1, 1.0);
    t.push(1, 0, 1.0);
    let swap = t.to_csr(2, 2);
    assert!(matches!(
        SaddlePointFactorization::try_new(&swap, 1),
        Err(SolverError::Singular { .. })
    ));
    assert!(matches!(
        SaddlePointFactorization::try_new(&swap, 3),
        Err(SolverError::DimensionMismatch {
            expected: 2,
            found: 3,
            ..
        })
    ));
}

#[test]
fn typed_errors() {
    let a = convection_diffusion(4, 0.0, 1.0);
    let mut lu = LuFactorization::try_new(&a).unwrap();
    assert!(matches!(
        lu.solve(&[1.0; 3]),
        Err(SolverError::DimensionMismatch {
            expected: 16,
            found: 3,
            ..
        })
    ));
    // Another pattern: one more entry.
    let mut t = Triplets::default();
    for (v, (r, c)) in a.iter() {
        t.push(r as u32, c as u32, *v);
    }
    t.push(5, 0, 0.0);
    let b = t.to_csr(16, 16);
    assert!(matches!(
        lu.refactor(&b),
        Err(SolverError::PatternMismatch(_))
    ));
    // Singular matrices: structurally (an empty column) and numerically.
    let mut s = Triplets::default();
    s.push(0, 0, 1.0);
    s.push(1, 0, 1.0);
    let s = s.to_csr(2, 2);
    assert!(matches!(
        LuFactorization::try_new(&s).and_then(|f| f.solve(&[1.0, 1.0])),
        Err(SolverError::Singular { .. })
    ));
    let mut z = Triplets::default();
    z.push(0, 0, 1.0);
    z.push(0, 1, 1.0);
    z.push(1, 0, 1.0);
    z.push(1, 1, 1.0);
    let z = z.to_csr(2, 2);
    assert!(matches!(
        LuFactorization::try_new(&z).and_then(|f| f.solve(&[1.0, 2.0])),
        Err(SolverError::Singular { .. })
    ));
    let rect = Triplets::default().to_csr(2, 3);
    assert!(matches!(
        LuFactorization::try_new(&rect),
        Err(SolverError::DimensionMismatch {
            expected: 2,
            found: 3,
            ..
        })
    ));
}

#[test]
fn gmres_matches_the_direct_solve() {
    let a = convection_diffusion(20, 0.3, 1.0);
    let b = rhs(a.rows());
    let direct = LuFactorization::try_new(&a).unwrap().solve(&b).unwrap();
    let mut x = vec![0.0; b.len()];
    let opts = GmresOptions {
        restart: 25,
        max_iterations: 2000,
        relative_tolerance: 1e-11,
    };
    let report = gmres(&a, &IdentityPreconditioner, &b, &mut x, &opts).unwrap();
    assert!(report.relative_residual <= 1e-11, "{report:?}");
    assert!(report.cycles > 1, "restarts happen: {report:?}");
    for (p, q) in x.iter().zip(&direct) {
        assert!((p - q).abs() < 1e-8 * (1.0 + q.abs()), "{p} vs {q}");
    }
}

#[test]
fn gmres_with_an_exact_preconditioner_converges_in_one_iteration() {
    let a = convection_diffusion(20, 0.3, 1.0);
    let b = rhs(a.rows());
    let lu = LuFactorization::try_new(&a).unwrap();
    let mut x = vec![0.0; b.len()];
    let report = gmres(&a, &lu, &b, &mut x, &GmresOptions::default()).unwrap();
    assert_eq!(report.iterations, 1, "{report:?}");
    assert!(residual(&a, &x, &b) < 1e-12);
    // A nearby matrix's factorisation as the preconditioner (as in Newton-Krylov).
    let near = convection_diffusion(20, 0.35, 1.05);
    let pre = LuFactorization::try_new(&near).unwrap();
    let mut y = vec![0.0; b.len()];
    let r = gmres(&a, &pre, &b, &mut y, &GmresOptions::default()).unwrap();
    assert!(r.iterations < 15, "{r:?}");
    // A matrix-free operator: the same product written as a closure-backed type.
    struct Shifted<'a>(&'a SparseMatrix);
    impl LinearOperator for Shifted<'_> {
        fn dim(&self) -> usize {
            self.0.rows()
        }
        fn apply(&self, x: &[f64], y: &mut [f64]) {
            self.0.apply(x, y);
            for (yi, xi) in y.iter_mut().zip(x) {
                *yi += 0.5 * xi;
            }
        }
    }
    let mut z = vec![0.0; b.len()];
    let r = gmres(&Shifted(&a), &lu, &b, &mut z, &GmresOptions::default()).unwrap();
    assert!(r.relative_residual < 1e-10);
}

#[test]
fn gmres_reports_non_convergence_and_sizes() {
    let a = convection_diffusion(20, 0.3, 1.0);
    let b = rhs(a.rows());
    let mut x = vec![0.0; b.len()];
    let opts = GmresOptions {
        restart: 5,
        max_iterations: 10,
        relative_tolerance: 1e-12,
    };
    match gmres(&a, &IdentityPreconditioner, &b, &mut x, &opts) {
        Err(SolverError::NotConverged {
            iterations,
            residual,
            ..
        }) => {
            assert_eq!(iterations, 10);
            assert!(residual > 1e-12 && residual < 1.0);
        }
        other => panic!("{other:?}"),
    }
    let mut short = vec![0.0; 3];
    assert!(matches!(
        gmres(&a, &IdentityPreconditioner, &b, &mut short, &opts),
        Err(SolverError::DimensionMismatch { found: 3, .. })
    ));
    // A zero right-hand side gives zero at once.
    let mut w = vec![1.0; b.len()];
    let r = gmres(
        &a,
        &IdentityPreconditioner,
        &vec![0.0; b.len()],
        &mut w,
        &opts,
    )
    .unwrap();
    assert_eq!(r.iterations, 0);
    assert!(w.iter().all(|v| *v == 0.0));
}

/// The graph Laplacian of an `n x n` grid (each row sums to zero): the stiffness of a body
/// without Dirichlet condition, singular (constants).
fn neumann_laplacian(n: usize) -> SparseMatrix {
    let mut t = Triplets::default();
    let id = |i: usize, j: usize| (i + n * j) as u32;
    for j in 0..n {
        for i in 0..n {
            let mut deg = 0.0;
            for (di, dj) in [(-1i64, 0i64), (1, 0), (0, -1), (0, 1)] {
                let (a, b) = (i as i64 + di, j as i64 + dj);
                if a >= 0 && b >= 0 && (a as usize) < n && (b as usize) < n {
                    t.push(id(i, j), id(a as usize, b as usize), -1.0);
                    deg += 1.0;
                }
            }
            t.push(id(i, j), id(i, j), deg);
        }
    }
    t.to_csr(n * n, n * n)
}

/// A body held by the constraints alone: `[[K_a, 0, B_a^T], [0, K_b, B_b^T], [B_a, B_b, 0]]`
/// with `K_a` definite (the 2D Laplacian with Dirichlet sides), `K_b` singular (the graph
/// Laplacian), `B` tying the first row of nodes of `b` to the first row of `a`. With the
/// first unknown of `b` marked to go last, the `L D L^T` solves it as LU does.
#[test]
fn saddle_point_ldlt_solves_a_floating_body_with_one_unknown_last() {
    let n = 8;
    let ka = convection_diffusion(n, 0.0, 1.0);
    let kb = neumann_laplacian(n);
    let (na, nb) = (ka.rows(), kb.rows());
    let mut t = Triplets::default();
    for (r, row) in ka.outer_iterator().enumerate() {
        for (c, v) in row.iter() {
            t.push(r as u32, c as u32, *v);
        }
    }
    for (r, row) in kb.outer_iterator().enumerate() {
        for (c, v) in row.iter() {
            t.push((na + r) as u32, (na + c) as u32, *v);
        }
    }
    for i in 0..n {
        let r = (na + nb + i) as u32;
        for (c, v) in [(i, 1.0), (na + i, -1.0)] {
            t.push(r, c as u32, v);
            t.push(c as u32, r, v);
        }
    }
    let size = na + nb + n;
    let a = t.to_csr(size, size);
    let b = rhs(size);
    let mut last = vec![false; na + nb];
    last[na] = true;
    let x = SaddlePointFactorization::try_new_with_last(&a, n, &last)
        .unwrap()
        .solve(&b)
        .unwrap();
    let lu = LuFactorization::try_new(&a).unwrap().solve(&b).unwrap();
    assert!(residual(&a, &x, &b) < 1e-13, "{}", residual(&a, &x, &b));
    for (p, q) in x.iter().zip(&lu) {
        assert!((p - q).abs() < 1e-10 * (1.0 + q.abs()), "{p} vs {q}");
    }
}

/// The solver interface of the faer backend gives the very numbers of the factorisation it
/// wraps (LU for a general matrix, Cholesky for an SPD one), refactors as they do, reports
/// their size and entries, and preconditions GMRES as a boxed factorisation.
#[test]
fn the_solver_interface_solves_as_the_factorisations_it_wraps() {
    use mortar_fem::linalg::{Factorization, FaerSolver, MatrixKind, SparseSolver};
    let solver: &dyn SparseSolver = &FaerSolver;
    let general = convection_diffusion(12, 0.4, 1.0);
    let spd = convection_diffusion(12, 0.0, 1.0);
    let b = rhs(general.rows());

    let mut lu = solver.factor(&general, MatrixKind::General).unwrap();
    let direct = LuFactorization::try_new(&general)
        .unwrap()
        .solve(&b)
        .unwrap();
    assert_eq!(lu.solve(&b).unwrap(), direct);
    let stats = lu.stats();
    assert_eq!((stats.dim, stats.factor_entries), (general.rows(), None));

    let mut llt = solver
        .factor(&spd, MatrixKind::SymmetricPositiveDefinite)
        .unwrap();
    let chol = CholeskyFactorization::try_new(&spd).unwrap();
    let mut x = b.clone();
    llt.solve_in_place(&mut x).unwrap();
    assert_eq!(x, chol.solve(&b).unwrap());
    assert_eq!(llt.stats().factor_entries, Some(chol.factor_entries()));

    // Refactor with new values of the same pattern; another pattern is refused.
    let scaled = convection_diffusion(12, 0.0, 0.25);
    llt.refactor(&scaled).unwrap();
    let mut again = CholeskyFactorization::try_new(&spd).unwrap();
    again.refactor(&scaled).unwrap();
    assert_eq!(llt.solve(&b).unwrap(), again.solve(&b).unwrap());
    assert!(matches!(
        lu.refactor(&convection_diffusion(11, 0.4, 1.0)),
        Err(SolverError::PatternMismatch(_))
    ));

    // A boxed factorisation is a preconditioner: exact, GMRES converges at once.
    let mut y = vec![0.0; b.len()];
    let report = solver
        .solve_preconditioned(&general, &lu, &b, &mut y, &GmresOptions::default())
        .unwrap();
    assert!(report.iterations <= 1 && residual(&general, &y, &b) < 1e-12);
}
