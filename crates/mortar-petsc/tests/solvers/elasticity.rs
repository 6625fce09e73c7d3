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

/// CG+GAMG through the solver interface on a system with `keep` of the clamped square's
/// unknowns, told where they sit (`SystemInfo`) or not; its iterations and report.
fn interface_iterations(m: usize, keep: impl Fn(usize) -> bool, told: bool) -> usize {
    use mortar_core::linalg::Triplets;
    use mortar_fem::linalg::{MatrixKind, SparseSolver, SystemInfo, UnknownPlaces};
    use mortar_petsc::PetscBackend;

    let (full, coords) = elasticity_2d(m);
    let kept: Vec<usize> = (0..full.rows()).filter(|&i| keep(i)).collect();
    let mut index = vec![usize::MAX; full.rows()];
    for (k, &i) in kept.iter().enumerate() {
        index[i] = k;
    }
    let mut t = Triplets::default();
    for (&v, (i, j)) in full.iter() {
        if index[i] != usize::MAX && index[j] != usize::MAX {
            t.push(index[i] as u32, index[j] as u32, v);
        }
    }
    let a = t.to_csr(kept.len(), kept.len());
    let points: Vec<[f64; 3]> = kept
        .iter()
        .map(|&i| [coords[2 * (i / 2)], coords[2 * (i / 2) + 1], 0.0])
        .collect();
    let components: Vec<u8> = kept.iter().map(|&i| (i % 2) as u8).collect();
    let info = SystemInfo {
        displacements: told.then_some(UnknownPlaces {
            dim: 2,
            axisymmetric: false,
            points: &points,
            components: &components,
        }),
        ..SystemInfo::default()
    };
    let mut options = SolveOptions::new(KrylovMethod::Cg, Preconditioner::Gamg);
    options.rtol = 1e-8;
    let backend = PetscBackend::new(options);
    let b = rhs(a.rows());
    let x = backend
        .factor_system(&a, MatrixKind::General, info)
        .unwrap()
        .solve(&b)
        .unwrap();
    let reference = solve_sparse_lu(&a, &b).unwrap();
    assert!(relative_error(&x, &reference) < 1e-5);
    let report = &backend.reports()[0];
    println!("{m}x{m}, {} unknowns, told {told}: {report}", a.rows());
    assert_eq!(report.near_null_space, told);
    report.iterations
}

/// A displacement system's unknowns told to the backend through the solver interface
/// (`SystemInfo::displacements`) give GAMG the rigid motions as its near null space, also
/// where eliminated unknowns leave no block structure (every tenth y unknown held, a
/// roller): as few iterations as the coordinates' rigid body modes give the full system,
/// and fewer than without.
#[test]
fn the_solver_interface_gives_gamg_the_rigid_motions() {
    let m = 32;
    let full_modes = iterations(m)[0];
    let all = |_: usize| true;
    let rollers = |i: usize| i.is_multiple_of(2) || (i / 2) % 10 != 3;
    let told_all = interface_iterations(m, all, true);
    let told_rollers = interface_iterations(m, rollers, true);
    let untold_rollers = interface_iterations(m, rollers, false);
    println!(
        "CG+GAMG iterations at m = {m}: rigid body modes {full_modes}, told through the \
         interface {told_all}, with rollers {told_rollers} (untold {untold_rollers})"
    );
    assert!(
        told_all <= full_modes + 2,
        "{told_all} against {full_modes}"
    );
    assert!(told_rollers as f64 <= 1.5 * full_modes as f64 + 2.0);
    assert!(
        2 * told_rollers < untold_rollers,
        "{told_rollers} against {untold_rollers}"
    );
}
