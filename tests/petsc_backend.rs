//! The physics' elastic solve through PETSc (`mortar::petsc::PetscBackend`, CG with algebraic
//! multigrid) against the direct backend: a plane-strain block (64 x 32 Quad4, 4 290 free
//! unknowns) held at its bottom, pressed and sheared on its top. Source: the direct sparse
//! Cholesky solve of the same system; the Krylov solve's relative tolerance 1e-10 bounds the
//! difference by about the condition number's share of it (measured 1.4e-10, 85 CG
//! iterations with GAMG).
//! In a build without PETSc (`--features petsc` absent) the same call is a typed error that
//! says how to get it.

use mortar::generate::{rectangle_mesh, CellShape};
use mortar::petsc::{KrylovMethod, PetscBackend, Preconditioner, SolveOptions};
use mortar::physics::elastic::{
    solve_elastic_on, solve_elastic_with, ComponentSet, ElasticBody, ElasticMaterial,
    ElasticOptions,
};
use nalgebra::Vector3;

#[test]
fn an_elastic_solve_through_petsc_matches_the_direct_one() {
    let mesh = rectangle_mesh([0.0, 0.0], [2.0, 1.0], [64, 32], CellShape::Tensor, 1).unwrap();
    let body = ElasticBody::new("block", mesh, ElasticMaterial::new(200e9, 0.3))
        .with_dirichlet_where(
            |f| f.centroid.y < 1e-9,
            ComponentSet::All,
            |_| Vector3::zeros(),
        )
        .unwrap()
        .with_traction_where(
            |f| f.centroid.y > 1.0 - 1e-9,
            |x| Vector3::new(2e7 * x.x, -1e8, 0.0),
        )
        .unwrap();
    let options = ElasticOptions::default();
    let direct = solve_elastic_with(&body, &options).unwrap();
    let mut petsc = SolveOptions::new(KrylovMethod::Cg, Preconditioner::Gamg);
    petsc.rtol = 1e-10;
    let backend = PetscBackend::new(petsc);
    let solved = solve_elastic_on(&body, &options, &backend);
    if !mortar::petsc::is_built() {
        let e = solved.unwrap_err().to_string();
        assert!(e.contains("--features petsc"), "{e}");
        return;
    }
    let u = solved.unwrap();
    let norm = direct.iter().map(|v| v * v).sum::<f64>().sqrt();
    let diff = u
        .iter()
        .zip(&direct)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt()
        / norm;
    let report = &backend.reports()[0];
    println!("elastic block through PETSc: {report}; relative difference {diff:.2e}");
    assert!(report.reason.is_converged(), "{report}");
    assert_eq!(report.ksp_type, "cg");
    assert!(diff < 1e-8, "{diff:e}");
}
