//! The ranges of the interface laws' parameters over which each formulation is tested: the
//! gap conductance through the mortar heat problem [`GapHeat`] and the exponential contact
//! penalty `P_c = P_o exp(S_NE (xi - g)^2)` through the mortar contact solver, each against a
//! closed form, across many decades of the parameter. `docs/verification.md` states the
//! ranges (beside the conductivity contrast).

use mortar::core::mesh::BoundaryFace;
use mortar::core::SearchRadius;
use mortar::generate::{rectangle_mesh, CellShape};
use mortar::physics::contact::{solve_contact, ContactOptions};
use mortar::physics::heat::{
    Conductivity, GapHeat, GapSolver, GapSolverState, HeatBody, HeatMaterial, HeatOptions,
};
use mortar::physics::laws::{
    ContactComplementarity, ExponentialPressure, GapConductance, GasConductivity,
};
use mortar::physics::nonlinear::NewtonOptions;
use mortar::{CouplingOptions, Tolerances};

use super::blocks::{stacked_blocks, E, SIGMA};

/// The open gap between the two slabs (m).
const GAP: f64 = 1e-3;

fn on_x(x: f64) -> impl Fn(&BoundaryFace) -> bool + Copy {
    move |f| (f.centroid.x - x).abs() < 1e-9
}

/// Two slabs `[0, 1] x [0, 1]` (Quad4, 4 x 5) and `[1 + GAP, 2 + GAP] x [0, 1]` (Tri3, 3 x 7,
/// non-matching) of conductivity 1, held at 1 and 0 on their outer sides, exchanging heat
/// across the open gap through a gap conductance `U`; `dual` picks the multipliers. Returns
/// the largest nodal temperature error (the span is 1) and the largest relative error of the
/// interface flux. Source of the reference (closed form, series resistances): the flux is
/// `q = 1 / (1 + 1/U + 1)` and the temperatures are linear in `x` in each slab,
/// `T = 1 - q x` and `T = q (2 + GAP - x)`, which linear elements and a mortar coupling
/// that reproduces linear fields reproduce to round-off.
fn slabs_through_gap_conductance(u: f64, dual: bool) -> (f64, f64) {
    let left = rectangle_mesh([0.0, 0.0], [1.0, 1.0], [4, 5], CellShape::Tensor, 1).unwrap();
    let right = rectangle_mesh(
        [1.0 + GAP, 0.0],
        [2.0 + GAP, 1.0],
        [3, 7],
        CellShape::Simplex,
        1000,
    )
    .unwrap();
    let ss = left.boundary_surface(on_x(1.0)).unwrap();
    let ms = right.boundary_surface(on_x(1.0 + GAP)).unwrap();
    let left = HeatBody::new("left", left, HeatMaterial::new(1.0, 1.0))
        .with_dirichlet_where(on_x(0.0), |_, _| 1.0)
        .unwrap();
    let right = HeatBody::new("right", right, HeatMaterial::new(1.0, 1.0))
        .with_dirichlet_where(on_x(2.0 + GAP), |_, _| 0.0)
        .unwrap();
    // The simplified law U = k_g / d_g with a constant gas conductivity.
    let law = GapConductance::simplified(GAP, GasConductivity::Constant(u * GAP)).unwrap();
    let coupling = if dual {
        CouplingOptions::default().dual()
    } else {
        CouplingOptions::default()
    };
    let tolerances = Tolerances {
        search_radius: SearchRadius::Distance(2.0 * GAP),
        ..Tolerances::default()
    };
    let problem = GapHeat::new(
        (left, Conductivity::Constant(1.0)),
        (right, Conductivity::Constant(1.0)),
        ss,
        ms,
        &coupling,
        tolerances,
        law,
        &HeatOptions::default(),
    )
    .unwrap();
    let t0 = problem
        .bodies()
        .clone()
        .map(|b| vec![0.5; b.mesh.node_count()]);
    let mut x = problem.state([&t0[0], &t0[1]]);
    let mut solver = GapSolverState::new(GapSolver::Newton);
    problem
        .solve(&mut x, 0.0, None, &mut solver, &NewtonOptions::default())
        .unwrap_or_else(|e| panic!("U = {u:e}, dual {dual}: {e}"));
    let q = 1.0 / (2.0 + 1.0 / u);
    let [ts, tm, _] = problem.split(&x);
    let [b0, b1] = problem.bodies();
    let nodal = |t: &[f64], body: &HeatBody, exact: &dyn Fn(f64) -> f64| {
        t.iter()
            .zip(body.mesh.coords())
            .map(|(t, p)| (t - exact(p.x)).abs())
            .fold(0.0f64, f64::max)
    };
    let e_t = nodal(ts, b0, &|x| 1.0 - q * x).max(nodal(tm, b1, &|x| q * (2.0 + GAP - x)));
    let e_q = problem
        .fluxes(&x)
        .iter()
        .map(|f| (f - q).abs() / q)
        .fold(0.0f64, f64::max);
    (e_t, e_q)
}

/// The gap conductance through [`GapHeat`] from `U = 1e-12` (an insulating gap, twelve
/// decades below the slabs' own conductance) to `U = 1e12` (twelve above: the gap all but
/// tied), standard and dual multipliers: nodal temperatures and the interface flux to 1e-13
/// relative at every decade (rounding level: measured at most 2.0e-15 and 3.2e-15), with the
/// Newton defaults and no multiplier scale given.
#[test]
fn gap_conductance_is_exact_from_1e_minus_12_to_1e12() {
    let mut worst = (0.0f64, 0.0f64);
    for e in -12..=12 {
        let u = 10f64.powi(e);
        for dual in [false, true] {
            let (e_t, e_q) = slabs_through_gap_conductance(u, dual);
            assert!(
                e_t < crate::claims::claim("law.gap_conductance").bound
                    && e_q < crate::claims::claim("law.gap_conductance").bound,
                "U = {u:e}, dual {dual}: temperature error {e_t:e}, flux error {e_q:e}"
            );
            worst = (worst.0.max(e_t), worst.1.max(e_q));
        }
    }
    eprintln!(
        "gap conductance 1e-12..1e12: worst temperature error {:.1e}, flux {:.1e}",
        worst.0, worst.1
    );
}

/// The exponential pressure law `P_c(g) = P_o exp(S (xi - g)^2)` as a contact penalty,
/// its stiffness `S` over 22 decades: the penetration it allows at the load, `delta =
/// sqrt(ln(sigma / P_o) / S)`, from 1e-2 m (soft: 40 times the blocks' elastic compression)
/// down to 1e-13 m. Source of the reference (closed form): the stacked blocks under a uniform
/// pressure `sigma` carry it through the interface, so the pressure is `sigma` at every slave
/// node and the gap is `-delta`. In 2D and 3D, the pressure to 1e-10 relative at every
/// stiffness, and the gap to 1e-8 of `delta` or to 16 ulps of the blocks' compression
/// `2 sigma / E` (the rounding of the displacements the gap is computed from), whichever is
/// larger: the gap is exact to 1e-8 down to `delta` = 1e-9 m, and below that to its rounding.
/// Before the contact solver counted a law residual within the rounding of its gap as zero,
/// `delta` = 1e-9 m failed to converge (the residual stalled at 1e-9 of the pressure).
#[test]
fn the_exponential_contact_penalty_is_exact_over_22_decades_of_stiffness() {
    let p_o = 1e5;
    for dim in [2, 3] {
        let b = stacked_blocks(dim, 0.0, SIGMA);
        for e in [-2, -3, -5, -7, -9, -11, -13] {
            let delta = 10f64.powi(e);
            let s = (SIGMA / p_o).ln() / (delta * delta);
            let law = ExponentialPressure::try_new(p_o, s, 0.0).unwrap();
            let options = ContactOptions {
                load_steps: 4,
                ..ContactOptions::default()
            };
            let sol = solve_contact(
                [&b.stiffness[0], &b.stiffness[1]],
                [&b.load[0], &b.load[1]],
                [
                    (&b.dirichlet[0].0, &b.dirichlet[0].1),
                    (&b.dirichlet[1].0, &b.dirichlet[1].1),
                ],
                &b.gap,
                &law,
                &options,
            )
            .unwrap_or_else(|e| panic!("{dim}D, delta {delta:e}: {e}"));
            let worst_p = sol
                .pressure
                .iter()
                .map(|p| (p - SIGMA).abs() / SIGMA)
                .fold(0.0f64, f64::max);
            let gap_tolerance = (crate::claims::claim("law.penalty_gap").bound * delta)
                .max(16.0 * f64::EPSILON * 2.0 * SIGMA / E);
            let worst_g = sol
                .gap
                .iter()
                .map(|g| (g + delta).abs() / delta)
                .fold(0.0f64, f64::max);
            let steps: usize = sol.steps.iter().map(|s| s.newton_steps).sum();
            eprintln!(
                "{dim}D penalty S = {s:.1e} (delta {delta:.0e} m): pressure {worst_p:.1e}, \
                 gap {worst_g:.1e}, {steps} Newton steps"
            );
            // Measured at most 1.4e-12 (2D) and 6.9e-12 (3D) over the stiffnesses.
            assert!(
                worst_p < crate::claims::claim("law.penalty_pressure").bound,
                "{dim}D, delta {delta:e}: pressure {worst_p:e}"
            );
            assert!(
                worst_g * delta <= gap_tolerance,
                "{dim}D, delta {delta:e}: gap {worst_g:e} relative"
            );
        }
    }
}

/// The exact contact law (the complementarity function `C = t - max(0, t - c g)`, semi-smooth
/// Newton) with its parameter `c` from 1e3 to 1e21 Pa/m, nine decades either side of the
/// blocks' stiffness over their size (`E / h` = 2.1e11): any positive `c` has the same
/// solution, and each gives it. The upper block starts 1 cm above the lower one and is held by
/// nothing but the contact, so the active set must be found. Source of the reference (closed
/// form): as above, the pressure is `sigma` at every slave node and the gap zero. Pressure to
/// 1e-10 relative, gap to 16 ulps of the blocks' compression, in 2D and 3D.
#[test]
fn the_exact_contact_law_is_exact_for_its_parameter_over_18_decades() {
    for dim in [2, 3] {
        let b = stacked_blocks(dim, 0.01, SIGMA);
        for e in (3..=21).step_by(3) {
            let c = 10f64.powi(e);
            let law = ContactComplementarity::try_new(c).unwrap();
            let sol = solve_contact(
                [&b.stiffness[0], &b.stiffness[1]],
                [&b.load[0], &b.load[1]],
                [
                    (&b.dirichlet[0].0, &b.dirichlet[0].1),
                    (&b.dirichlet[1].0, &b.dirichlet[1].1),
                ],
                &b.gap,
                &law,
                &ContactOptions::default(),
            )
            .unwrap_or_else(|err| panic!("{dim}D, c = {c:e}: {err}"));
            let worst_p = sol
                .pressure
                .iter()
                .map(|p| (p - SIGMA).abs() / SIGMA)
                .fold(0.0f64, f64::max);
            let worst_g = sol.gap.iter().fold(0.0f64, |a, g| a.max(g.abs()));
            let steps: usize = sol.steps.iter().map(|s| s.newton_steps).sum();
            eprintln!(
                "{dim}D exact law c = {c:.0e}: pressure {worst_p:.1e}, gap {worst_g:.1e} m, \
                 {steps} Newton steps"
            );
            // Measured 1.2e-12 (2D) and 6.5e-12 (3D) for every c.
            assert!(
                worst_p < crate::claims::claim("law.exact_pressure").bound,
                "{dim}D, c = {c:e}: pressure {worst_p:e}"
            );
            assert!(
                worst_g <= 16.0 * f64::EPSILON * 2.0 * SIGMA / E,
                "{dim}D, c = {c:e}: gap {worst_g:e} m"
            );
        }
    }
}
