//! The two solution paths, the automatic choice and its report, and the typed errors.

use mortar::physics::tied::{Formulation, FormulationChoice, SlaveDirichlet, TiedOptions};
use mortar::physics::{PhysicsError, TyingError};
use mortar::CouplingOptions;
use mortar_scenes::tied_heat::{Geometry, TiedHeatScene};

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .filter(|(x, _)| x.is_finite())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn condensed_and_saddle_point_solutions_agree() {
    for (dim, geometry, n) in [
        (2, Geometry::Straight, 16),
        (3, Geometry::Straight, 8),
        (2, Geometry::Curved, 16),
        // Warped quads on the sphere: their dual D is diagonal to round-off since the
        // integrals over warped faces take their non-polynomial Jacobian to 1e-10 (at a flat
        // face's degree D would be 6e-8 off diagonal and `Auto` would keep the saddle point).
        (3, Geometry::Curved, 8),
    ] {
        let problem = TiedHeatScene::new(dim, geometry, n).build().unwrap();
        let auto = problem.solve_steady(&TiedOptions::default(), 0.0).unwrap();
        let saddle = problem
            .solve_steady(
                &TiedOptions::default().with_formulation(FormulationChoice::SaddlePoint),
                0.0,
            )
            .unwrap();
        let name = format!("{dim}D {geometry:?}");
        assert_eq!(
            auto.formulation.formulation,
            Formulation::DualCondensed,
            "{name}"
        );
        assert!(auto.formulation.reason.contains("diagonal"), "{name}");
        assert_eq!(saddle.formulation.formulation, Formulation::SaddlePoint);
        assert!(auto.formulation.unknowns < saddle.formulation.unknowns);
        for b in 0..2 {
            let d = max_abs_diff(&auto.temperatures[b], &saddle.temperatures[b]);
            assert!(
                d < crate::claims::claim("tied.paths").bound,
                "{name}: temperatures differ by {d:e}"
            );
        }
        let d = max_abs_diff(&auto.flux, &saddle.flux);
        assert!(d < 1e-9, "{name}: fluxes differ by {d:e}");
        // The same rows carry a multiplier in both.
        for (a, s) in auto.flux.iter().zip(&saddle.flux) {
            assert_eq!(a.is_nan(), s.is_nan());
        }
        let expected_redistributed = geometry == Geometry::Straight;
        assert_eq!(
            auto.formulation.redistributed > 0,
            expected_redistributed,
            "{name}"
        );
        assert_eq!(auto.formulation.dropped, 0, "{name}");
    }
}

#[test]
fn standard_multipliers_fall_back_to_the_saddle_point_and_say_why() {
    let mut s = TiedHeatScene::new(2, Geometry::Straight, 8);
    s.coupling = CouplingOptions::default();
    let problem = s.build().unwrap();
    let sol = problem.solve_steady(&TiedOptions::default(), 0.0).unwrap();
    assert_eq!(sol.formulation.formulation, Formulation::SaddlePoint);
    assert!(
        sol.formulation.reason.contains("not diagonal"),
        "{}",
        sol.formulation.reason
    );
    assert!(sol.formulation.to_string().starts_with("saddle point"));
    // Standard multipliers on a body with Dirichlet sides: no pivoting needed.
    assert!(
        sol.formulation.factorisation.starts_with("sparse LDL^T"),
        "{}",
        sol.formulation
    );
    let forced = problem.solve_steady(
        &TiedOptions::default().with_formulation(FormulationChoice::DualCondensed),
        0.0,
    );
    assert!(
        matches!(
            forced,
            Err(PhysicsError::Tying(TyingError::NotDiagonal { .. }))
        ),
        "{forced:?}"
    );
}

#[test]
fn dirichlet_slave_nodes_can_be_refused() {
    let refuse = TiedOptions {
        slave_dirichlet: SlaveDirichlet::Refuse,
        ..TiedOptions::default()
    };
    let problem = TiedHeatScene::new(2, Geometry::Straight, 8)
        .build()
        .unwrap();
    match problem.solve_steady(&refuse, 0.0) {
        Err(PhysicsError::DirichletOnSlave { count, tag }) => {
            // The two ends of the interface line.
            assert_eq!(count, 2);
            assert!(tag > 1_000_000, "a slave body node: {tag}");
        }
        other => panic!("{other:?}"),
    }
    // The curved interface has no Dirichlet node: nothing to refuse.
    let curved = TiedHeatScene::new(2, Geometry::Curved, 8).build().unwrap();
    let sol = curved.solve_steady(&refuse, 0.0).unwrap();
    assert!(sol.flux.iter().all(|l| l.is_finite()));
}

#[test]
fn tied_system_input_errors() {
    use mortar::physics::tied::TiedSystem;
    let problem = TiedHeatScene::new(2, Geometry::Straight, 8)
        .build()
        .unwrap();
    let m = problem.matrices();
    let k = [&m[0].stiffness, &m[1].stiffness];
    let opts = TiedOptions::default();
    assert!(matches!(
        TiedSystem::new(k, problem.tie(), [&[0, 0], &[]], &opts),
        Err(PhysicsError::InvalidInput { .. })
    ));
    assert!(matches!(
        TiedSystem::new(k, problem.tie(), [&[], &[u32::MAX]], &opts),
        Err(PhysicsError::InvalidInput { .. })
    ));
    // The master body alone, with its Dirichlet nodes: the slave body floats on its own
    // but the interface holds it.
    let (nodes, _) = problem.bodies()[1].dirichlet_nodes();
    let mut sys = TiedSystem::new(k, problem.tie(), [&[], &nodes], &opts).unwrap();
    let b0 = vec![0.0; m[0].stiffness.rows()];
    let b1 = vec![0.0; m[1].stiffness.rows()];
    let g = vec![1.0; nodes.len()];
    assert!(matches!(
        sys.solve([&b0, &b1[1..]], [&[], &g]),
        Err(PhysicsError::WrongLength { .. })
    ));
    assert!(matches!(
        sys.solve([&b0, &b1], [&[], &g[1..]]),
        Err(PhysicsError::WrongLength { .. })
    ));
    // Constant Dirichlet data without source: the constant everywhere.
    let t = sys.solve([&b0, &b1], [&[], &g]).unwrap();
    for f in &t.fields {
        assert!(f.iter().all(|v| (v - 1.0).abs() < 1e-12));
    }
    assert!(t.multipliers.iter().all(|l| l.abs() < 1e-10));
    // Refactor with matrices of another size is refused, and the old factors stay.
    let small = mortar::core::linalg::SparseMatrix::eye(3);
    assert!(matches!(
        sys.refactor([&small, &small]),
        Err(PhysicsError::Solver(_))
    ));
    assert!(sys.solve([&b0, &b1], [&[], &g]).is_ok());
}

/// From `SUBSTRUCTURED_MIN` unknowns a 2D condensed system is factorised by body (the two
/// bodies in parallel, the interface last); it gives the saddle point's solution, also with a
/// slave body that has no Dirichlet condition of its own (held only through the interface).
#[test]
fn condensed_by_body_agrees_with_the_saddle_point() {
    use mortar::physics::tied::{TiedSystem, SUBSTRUCTURED_MIN};
    for geometry in [Geometry::Straight, Geometry::Curved] {
        let problem = TiedHeatScene::new(2, geometry, 64).build().unwrap();
        let auto = problem.solve_steady(&TiedOptions::default(), 0.0).unwrap();
        let saddle = problem
            .solve_steady(
                &TiedOptions::default().with_formulation(FormulationChoice::SaddlePoint),
                0.0,
            )
            .unwrap();
        let name = format!("{geometry:?}");
        assert!(auto.formulation.unknowns >= SUBSTRUCTURED_MIN, "{name}");
        assert!(
            auto.formulation.factorisation.contains("by body"),
            "{name}: {}",
            auto.formulation.factorisation
        );
        for b in 0..2 {
            let d = max_abs_diff(&auto.temperatures[b], &saddle.temperatures[b]);
            assert!(d < 1e-10, "{name}: temperatures differ by {d:e}");
        }
        let d = max_abs_diff(&auto.flux, &saddle.flux);
        assert!(d < 1e-9, "{name}: fluxes differ by {d:e}");
    }
    // A floating slave body: only the master's Dirichlet nodes.
    let problem = TiedHeatScene::new(2, Geometry::Straight, 64)
        .build()
        .unwrap();
    let m = problem.matrices();
    let k = [&m[0].stiffness, &m[1].stiffness];
    let (nodes, _) = problem.bodies()[1].dirichlet_nodes();
    let values: Vec<f64> = (0..nodes.len()).map(|i| (i as f64 * 0.1).sin()).collect();
    let rhs: Vec<Vec<f64>> = (0..2).map(|b| vec![1.0; k[b].rows()]).collect();
    let mut fields = Vec::new();
    for choice in [FormulationChoice::Auto, FormulationChoice::SaddlePoint] {
        let opts = TiedOptions::default().with_formulation(choice);
        let sys = TiedSystem::new(k, problem.tie(), [&[], &nodes], &opts).unwrap();
        let by_body = sys.report().factorisation.contains("by body");
        assert_eq!(by_body, choice == FormulationChoice::Auto);
        fields.push(sys.solve([&rhs[0], &rhs[1]], [&[], &values]).unwrap());
    }
    for b in 0..2 {
        let d = max_abs_diff(&fields[0].fields[b], &fields[1].fields[b]);
        let scale = fields[1].fields[b]
            .iter()
            .fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(
            d < 1e-10 * scale,
            "floating slave body {b}: differ by {d:e} of {scale:e}"
        );
    }
    // Refactored by body with twice the matrices: twice the right-hand side gives the same
    // fields.
    let opts = TiedOptions::default();
    let mut sys = TiedSystem::new(k, problem.tie(), [&[], &nodes], &opts).unwrap();
    let doubled: Vec<_> = k.iter().map(|m| m.map(|v| 2.0 * v)).collect();
    sys.refactor([&doubled[0], &doubled[1]]).unwrap();
    assert!(sys.report().factorisation.contains("by body"));
    let rhs2: Vec<Vec<f64>> = rhs
        .iter()
        .map(|r| r.iter().map(|v| 2.0 * v).collect())
        .collect();
    let again = sys.solve([&rhs2[0], &rhs2[1]], [&[], &values]).unwrap();
    for b in 0..2 {
        let d = max_abs_diff(&again.fields[b], &fields[0].fields[b]);
        let scale = fields[0].fields[b]
            .iter()
            .fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(d < 1e-10 * scale, "refactored, body {b}: differ by {d:e}");
    }
}
