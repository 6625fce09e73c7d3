//! Plane-strain elasticity: smoothed aggregation (GAMG) needs the rigid body modes as its
//! near null space to coarsen a vector problem well; with them it converges in fewer
//! iterations, which hardly grow with the size, than with the two translations its block
//! size alone gives it, or with a scalar problem's constant.

use mortar_fem::linalg::solve_sparse_lu;
use mortar_petsc::{KrylovMethod, PetscSolver, Preconditioner, RigidBodyModes, SolveOptions};

use super::common::{elasticity_2d, relative_error, rhs, vector_laplacian_3d};

/// How GAMG sees the unknowns.
#[derive(Clone, Copy, Debug)]
enum Hint {
    /// Rigid body modes from the coordinates (block size 2).
    RigidBodyModes,
    /// Block size 2: GAMG's default near null space, the two translations.
    BlockSize,
    /// Nothing: a scalar problem's constant vector.
    Nothing,
}

/// CG+GAMG iterations on the `m x m` clamped square with each hint.
fn iterations(m: usize) -> [usize; 3] {
    let (a, coords) = elasticity_2d(m);
    let b = rhs(a.rows());
    let reference = (m <= 16).then(|| solve_sparse_lu(&a, &b).unwrap());
    [Hint::RigidBodyModes, Hint::BlockSize, Hint::Nothing].map(|hint| {
        let mut options = SolveOptions::new(KrylovMethod::Cg, Preconditioner::Gamg);
        options.rtol = 1e-8;
        match hint {
            Hint::RigidBodyModes => {
                options.near_null_space = Some(RigidBodyModes {
                    dim: 2,
                    coordinates: coords.clone(),
                })
            }
            Hint::BlockSize => options.block_size = 2,
            Hint::Nothing => {}
        }
        let solved = PetscSolver::new(options).solve(&a, &b).unwrap();
        println!(
            "elasticity {m}x{m} ({} unknowns), {hint:?}: {}",
            a.rows(),
            solved.report
        );
        if let Some(reference) = &reference {
            let err = relative_error(&solved.x, reference);
            assert!(err < 1e-5, "error {err:.2e}");
        }
        solved.report.iterations
    })
}

#[test]
fn rigid_body_modes_help_gamg_on_elasticity() {
    let sizes = [16, 32, 64];
    let its: Vec<[usize; 3]> = sizes.iter().map(|&m| iterations(m)).collect();
    println!(
        "CG+GAMG iterations at m = {sizes:?} (rigid body modes, block size 2, nothing): {its:?}"
    );
    let [modes, block, nothing] = its[2];
    assert!(modes < block && modes < nothing, "{its:?}");
    assert!(modes as f64 <= 1.5 * its[0][0] as f64 + 2.0, "{its:?}");
}

#[test]
fn three_dimensional_rigid_body_modes_reach_gamg() {
    let (a, coords) = vector_laplacian_3d(10);
    let b = rhs(a.rows());
    let reference = solve_sparse_lu(&a, &b).unwrap();
    let mut options = SolveOptions::new(KrylovMethod::Cg, Preconditioner::Gamg);
    options.rtol = 1e-10;
    options.near_null_space = Some(RigidBodyModes {
        dim: 3,
        coordinates: coords,
    });
    let solved = PetscSolver::new(options).solve(&a, &b).unwrap();
    println!("vector laplacian 10^3 x 3: {}", solved.report);
    assert!(solved.report.near_null_space);
    assert!(relative_error(&solved.x, &reference) < 1e-7);
}
