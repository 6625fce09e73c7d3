//! Plane-strain elasticity: smoothed aggregation (GAMG) needs the rigid body modes as its
//! near null space to coarsen a vector problem well; with them it converges in fewer
//! iterations that grow less with the size than without them.

use mortar_core::linalg::solve_sparse_lu;
use mortar_petsc::{KrylovMethod, PetscSolver, Preconditioner, RigidBodyModes, SolveOptions};

use super::common::{elasticity_2d, relative_error, rhs};

/// CG+GAMG iterations on the `m x m` clamped square, with and without rigid body modes.
fn iterations(m: usize) -> (usize, usize) {
    let (a, coords) = elasticity_2d(m);
    let b = rhs(a.rows());
    let reference = (m <= 16).then(|| solve_sparse_lu(&a, &b).unwrap());
    let mut out = [0; 2];
    for (k, with_modes) in [true, false].into_iter().enumerate() {
        let mut options = SolveOptions::new(KrylovMethod::Cg, Preconditioner::Gamg);
        options.rtol = 1e-8;
        if with_modes {
            options.near_null_space = Some(RigidBodyModes {
                dim: 2,
                coordinates: coords.clone(),
            });
        }
        let solved = PetscSolver::new(options).solve(&a, &b).unwrap();
        println!("elasticity {m}x{m} ({} unknowns): {}", a.rows(), solved.report);
        if let Some(reference) = &reference {
            let err = relative_error(&solved.x, reference);
            assert!(err < 1e-5, "error {err:.2e}");
        }
        out[k] = solved.report.iterations;
    }
    (out[0], out[1])
}

#[test]
fn rigid_body_modes_help_gamg_on_elasticity() {
    let sizes = [16, 32, 64];
    let its: Vec<(usize, usize)> = sizes.iter().map(|&m| iterations(m)).collect();
    println!("CG+GAMG iterations at m = {sizes:?} (with modes, without): {its:?}");
    let (with_large, without_large) = its[2];
    assert!(with_large < without_large, "{its:?}");
    assert!(with_large as f64 <= 2.0 * its[0].0 as f64 + 2.0, "{its:?}");
}
