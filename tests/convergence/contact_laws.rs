//! Contact through a regularised law, and the refusals of the contact solver.

use mortar::physics::contact::{solve_contact, ContactOptions};
use mortar::physics::laws::{ContactComplementarity, ExponentialPressure};
use mortar::physics::PhysicsError;

use mortar::CouplingOptions;

use super::blocks::{stacked_blocks, stacked_blocks_with, Blocks, SIGMA};

fn solve<L: mortar::physics::laws::ConstraintLaw>(
    b: &Blocks,
    law: &L,
    options: &ContactOptions,
) -> Result<mortar::physics::contact::ContactSolution, PhysicsError> {
    solve_contact(
        [&b.stiffness[0], &b.stiffness[1]],
        [&b.load[0], &b.load[1]],
        [
            (&b.dirichlet[0].0, &b.dirichlet[0].1),
            (&b.dirichlet[1].0, &b.dirichlet[1].1),
        ],
        &b.gap,
        law,
        options,
    )
}

/// The exponential pressure law `P_c(g) = P_o exp(S (xi - g)^2)` through the same
/// Newton iteration as the exact law. Source of the reference (closed form): the stacked
/// blocks under a uniform pressure `sigma` carry it through the interface, so the pressure is
/// `sigma` at every slave node and the gap is the one at which the law gives it,
/// `g* = xi - sqrt(ln(sigma / P_o) / S)` (a uniform penetration).
#[test]
fn the_exponential_pressure_law_carries_the_load_at_its_closed_form_gap() {
    let (p_o, xi) = (1e5, 0.0);
    // A penetration of 1 um at 50 MPa.
    let s = (SIGMA / p_o).ln() / 1e-12;
    let law = ExponentialPressure::try_new(p_o, s, xi).unwrap();
    let g_star = xi - ((SIGMA / p_o).ln() / s).sqrt();
    for dim in [2, 3] {
        let b = stacked_blocks(dim, 0.0, SIGMA);
        let options = ContactOptions {
            load_steps: 4,
            ..ContactOptions::default()
        };
        let sol = solve(&b, &law, &options).unwrap();
        let worst_p = sol
            .pressure
            .iter()
            .map(|p| (p - SIGMA).abs() / SIGMA)
            .fold(0.0f64, f64::max);
        let worst_g = sol
            .gap
            .iter()
            .map(|g| (g - g_star).abs() / g_star.abs())
            .fold(0.0f64, f64::max);
        let steps: Vec<usize> = sol.steps.iter().map(|s| s.newton_steps).collect();
        eprintln!(
            "exponential law {dim}D: pressure error {worst_p:.1e}, gap error {worst_g:.1e} \
             (g* = {g_star:.3e} m), Newton steps per load step {steps:?}"
        );
        // Measured 1.4e-12 and 6.8e-12 (pressure), 1.4e-13 and 5.7e-13 (gap) in 2D and 3D:
        // the Newton tolerance's level, with a decade or two to spare.
        let bound = crate::claims::claim("contact.exponential").bound;
        assert!(worst_p < bound, "{dim}D: pressure off by {worst_p:e}");
        assert!(worst_g < bound, "{dim}D: gap off by {worst_g:e}");
        // From zero pressure the first load step walks up the exponential (15 steps in 2D and 3D);
        // the later ones start near the solution.
        assert!(steps.iter().all(|&n| n <= 20), "{steps:?}");
    }
}

/// A body held by nothing but contact in one direction. Lifted off the lower block and
/// pushed down, the upper block falls onto it: the first Newton system has the rigid mode
/// (without a correct digit; the solver then pulls the open gaps shut with springs for that
/// step, and says so), the semi-smooth Newton then closes the contact, and the solution is
/// that of the touching blocks (pressure `sigma`, gap zero). Pulled up, contact never holds
/// it: a typed error naming the cause, not a panic.
#[test]
fn a_body_held_only_by_contact_falls_into_it_or_is_refused() {
    let b = stacked_blocks(2, 0.01, SIGMA);
    let law = ContactComplementarity::try_new(1e12).unwrap();
    let sol = solve(&b, &law, &ContactOptions::default()).unwrap();
    let worst_p = sol
        .pressure
        .iter()
        .map(|p| (p - SIGMA).abs() / SIGMA)
        .fold(0.0f64, f64::max);
    assert!(worst_p < 1e-10, "pressure off by {worst_p:e}");
    assert!(sol.gap.iter().all(|g| g.abs() < 1e-12), "{:?}", sol.gap);
    assert!(sol.steps[0].regularised >= 1, "{:?}", sol.steps[0]);

    let b = stacked_blocks(2, 0.01, -SIGMA);
    match solve(&b, &law, &ContactOptions::default()) {
        Err(e @ PhysicsError::InvalidInput { .. }) => {
            assert!(e.to_string().contains("not held"), "{e}");
            eprintln!("pulled off: {e}");
        }
        other => panic!("expected a typed refusal, got {other:?}"),
    }
}

/// With dual multipliers (D diagonal) the pressures are condensed out of every Newton system
/// (a symmetric system of the displacements, Cholesky); with standard multipliers they stay
/// (the saddle point, LU). Both give the closed-form patch solution (pressure `sigma`), and
/// the report says which was used and why.
#[test]
fn dual_multipliers_condense_the_pressure_and_standard_ones_keep_the_saddle_point() {
    let law = ContactComplementarity::try_new(1e12).unwrap();
    for dim in [2, 3] {
        let dual = solve(
            &stacked_blocks(dim, 0.0, SIGMA),
            &law,
            &ContactOptions::default(),
        )
        .unwrap();
        assert!(
            dual.formulation
                .starts_with("pressures condensed out (D is diagonal"),
            "{}",
            dual.formulation
        );
        let standard = stacked_blocks_with(dim, 0.0, SIGMA, &CouplingOptions::default());
        let std_sol = solve(&standard, &law, &ContactOptions::default()).unwrap();
        assert!(
            std_sol.formulation.starts_with("saddle point"),
            "{}",
            std_sol.formulation
        );
        for sol in [&dual, &std_sol] {
            let worst = sol
                .pressure
                .iter()
                .map(|p| (p - SIGMA).abs() / SIGMA)
                .fold(0.0f64, f64::max);
            assert!(
                worst < 1e-10,
                "{dim}D {}: pressure off by {worst:e}",
                sol.formulation
            );
        }
    }
}
