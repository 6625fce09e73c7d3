//! Two bodies of revolution coupled by mortar in the r-z plane: the heat problems
//! ([`TiedHeat`], [`GapHeat`]) with the axisymmetric geometry given to both the coupling
//! ([`CouplingOptions::geometry`]) and the bodies ([`HeatOptions::geometry`]).
//!
//! Source of the reference (closed form of steady radial conduction, e.g. Incropera and
//! DeWitt, *Fundamentals of Heat and Mass Transfer*, sections 3.3.2 and 3.5.2; docs/models.md,
//! section 3): a solid cylinder (pellet) `0 <= r <= a` with the uniform source `Q` in a tube
//! `a <= r <= c` (or `b <= r <= c` across a gap), insulated ends, `T(c) = T_c`. The heat
//! flux leaving the pellet is `q = Q a / 2` (W/m^2; `q' = Q pi a^2` per unit length);
//! `T(r) = T_c + (Q a^2 / (2 k_c)) ln(c / r)` in the tube,
//! `T(r) = T(a) + Q (a^2 - r^2) / (4 k_p)` in the pellet. Across a gap of conductance `U`
//! (per unit area of the pellet's surface): `T(a) = T(b) + q / U`, `b` the tube's inner
//! radius (`T_ps = T_ci + q' / (2 pi a U)`).

use mortar::core::mesh::BoundaryFace;
use mortar::core::{ModelGeometry, SearchRadius};
use mortar::generate::{rectangle_mesh, CellShape};
use mortar::physics::heat::{
    error_norms, Conductivity, GapHeat, GapSolver, GapSolverState, HeatBody, HeatMaterial,
    HeatOptions, TiedHeat,
};
use mortar::physics::laws::{GapConductance, GasConductivity, Tying};
use mortar::physics::nonlinear::NewtonOptions;
use mortar::physics::tied::{Formulation, FormulationChoice, TiedOptions};
use mortar::physics::PhysicsError;
use mortar::{CouplingOptions, Tolerances, VolumeMesh};
use nalgebra::Vector3;

use super::axisymmetric_heat::{rates, sci};

const A: f64 = 0.5;
const C: f64 = 0.8;
const H: f64 = 0.3;
const KP: f64 = 3.0;
const KC: f64 = 16.0;
const Q: f64 = 2.0e4;
const TC: f64 = 580.0;

fn on_r(r: f64) -> impl Fn(&BoundaryFace) -> bool + Copy {
    move |f| (f.centroid.x - r).abs() < 1e-9 && f.nodes.len() == 2
}

/// The closed form: pellet `0 <= r <= a`, tube `b <= r <= c`, gap resistance `1 / U`.
fn exact(r: f64, b: f64, resistance: f64) -> f64 {
    let q = Q * A / 2.0;
    let t_b = TC + Q * A * A / (2.0 * KC) * (C / b).ln();
    if r >= b - 1e-12 {
        TC + Q * A * A / (2.0 * KC) * (C / r).ln()
    } else {
        t_b + q * resistance + Q * (A * A - r * r) / (4.0 * KP)
    }
}

/// The pellet (`n` radial cells, Quad4) and the tube from `b` (`n` radial cells, Tri3), each
/// with its own axial subdivision: the interface meshes do not match.
fn bodies(n: usize, b: f64) -> (HeatBody, HeatBody) {
    let pellet_mesh =
        rectangle_mesh([0.0, 0.0], [A, H], [n, n / 2 + 1], CellShape::Tensor, 1).unwrap();
    let tube_mesh: VolumeMesh =
        rectangle_mesh([b, 0.0], [C, H], [n, n], CellShape::Simplex, 1).unwrap();
    let pellet =
        HeatBody::new("pellet", pellet_mesh, HeatMaterial::new(KP, 1.0)).with_source(|_, _| Q);
    let tube = HeatBody::new("tube", tube_mesh, HeatMaterial::new(KC, 1.0))
        .with_dirichlet_where(on_r(C), |_, _| TC)
        .unwrap();
    (pellet, tube)
}

fn axisymmetric() -> (CouplingOptions, HeatOptions) {
    (
        CouplingOptions::default().axisymmetric(),
        HeatOptions::default().with_geometry(ModelGeometry::Axisymmetric),
    )
}

/// The L2 error (both bodies) and the largest nodal error of the temperatures.
fn errors(pellet: &HeatBody, tube: &HeatBody, t: [&[f64]; 2], b: f64, res: f64) -> (f64, f64) {
    let f = move |x: &Vector3<f64>| exact(x.x, b, res);
    let g = move |x: &Vector3<f64>| {
        let dr = if x.x >= b - 1e-12 {
            -Q * A * A / (2.0 * KC * x.x)
        } else {
            -Q * x.x / (2.0 * KP)
        };
        Vector3::new(dr, 0.0, 0.0)
    };
    let e0 = error_norms(&pellet.mesh, t[0], &f, &g, None).unwrap();
    let e1 = error_norms(&tube.mesh, t[1], &f, &g, None).unwrap();
    (e0.l2.hypot(e1.l2), e0.max_nodal.max(e1.max_nodal))
}

/// The pellet tied to its tube across r = a with non-matching meshes (Quad4 against Tri3,
/// different axial subdivisions), r-z coupling and r-z bodies, dual (condensed SPD) and
/// standard (saddle point) multipliers: the temperatures match the closed form at the second
/// order in L2, the centre temperature to 1e-3 of the rise, and the interface flux (the
/// multiplier) is `Q a / 2` to 1e-3 (at 32 radial cells). Mixing an r-z coupling with
/// Cartesian bodies is refused.
#[test]
fn pellet_tied_to_its_tube_in_r_z() {
    let (coupling, heat) = axisymmetric();
    let rise = exact(0.0, A, 0.0) - TC;
    for dual in [true, false] {
        let coupling = if dual {
            coupling.clone().dual()
        } else {
            coupling.clone()
        };
        let (mut l2, mut centre, mut flux) = (Vec::new(), Vec::new(), Vec::new());
        for n in [4, 8, 16, 32] {
            let (pellet, tube) = bodies(n, A);
            let ss = pellet.mesh.boundary_surface(on_r(A)).unwrap();
            let ms = tube.mesh.boundary_surface(on_r(A)).unwrap();
            let problem = TiedHeat::new(pellet, tube, ss, ms, &coupling, &heat).unwrap();
            let tied = TiedOptions::default().with_formulation(if dual {
                FormulationChoice::Auto
            } else {
                FormulationChoice::SaddlePoint
            });
            let sol = problem.solve_steady(&tied, 0.0).unwrap();
            let want = if dual {
                Formulation::DualCondensed
            } else {
                Formulation::SaddlePoint
            };
            assert_eq!(sol.formulation.formulation, want);
            let [pellet, tube] = problem.bodies();
            let t = [&sol.temperatures[0][..], &sol.temperatures[1][..]];
            l2.push(errors(pellet, tube, t, A, 0.0).0);
            let t0 = pellet
                .mesh
                .coords()
                .iter()
                .zip(t[0])
                .filter(|(x, _)| x.x == 0.0)
                .map(|(_, t)| (t - TC - rise).abs() / rise)
                .fold(0.0, f64::max);
            centre.push(t0);
            let q = Q * A / 2.0;
            let worst = sol
                .flux
                .iter()
                .filter(|f| f.is_finite())
                .map(|f| (f - q).abs() / q)
                .fold(0.0, f64::max);
            flux.push(worst);
        }
        println!(
            "pellet tied in r-z (dual {dual}): L2 {} rates {:.3?}; centre rise {} rates {:.3?}; flux vs Q a/2 {}",
            sci(&l2),
            rates(&l2),
            sci(&centre),
            rates(&centre),
            sci(&flux)
        );
        for r in rates(&l2) {
            assert!(r > 1.85, "dual {dual}: L2 rates {:?}", rates(&l2));
        }
        assert!(centre[3] < 1e-3, "dual {dual}: {centre:?}");
        assert!(flux[3] < 1e-3, "dual {dual}: {flux:?}");
        assert!(flux[3] < flux[1], "dual {dual}: {flux:?}");
    }
    // An r-z coupling of Cartesian bodies (or the reverse) mixes W with W/m: refused.
    let (pellet, tube) = bodies(4, A);
    let ss = pellet.mesh.boundary_surface(on_r(A)).unwrap();
    let ms = tube.mesh.boundary_surface(on_r(A)).unwrap();
    match TiedHeat::new(pellet, tube, ss, ms, &coupling, &HeatOptions::default()) {
        Err(PhysicsError::InvalidInput { body, what }) => {
            assert_eq!(body, "options");
            assert!(
                what.contains("axisymmetric") && what.contains("cartesian"),
                "{what}"
            );
        }
        other => panic!("expected InvalidInput, got {other:?}"),
    }
}

/// The same pellet and tube through [`GapHeat`]: with the [`Tying`] law it gives the tied
/// solution (to 1e-9 K); with a constant gap conductance `U` across an open gap
/// (`b = a + 50 um`, the coupling projecting across it) the pellet surface lies `q / U` above
/// the tube's inner surface (to 1e-3 of `q / U` at every slave node), and the whole profile
/// matches the closed form at the second order.
#[test]
fn pellet_in_its_tube_through_gap_heat_in_r_z() {
    let (coupling, heat) = axisymmetric();
    let coupling = coupling.dual();
    let newton = NewtonOptions::default();
    // Tying.
    let n = 8;
    let (pellet, tube) = bodies(n, A);
    let ss = pellet.mesh.boundary_surface(on_r(A)).unwrap();
    let ms = tube.mesh.boundary_surface(on_r(A)).unwrap();
    let tied = TiedHeat::new(
        pellet.clone(),
        tube.clone(),
        ss.clone(),
        ms.clone(),
        &coupling,
        &heat,
    )
    .unwrap()
    .solve_steady(&TiedOptions::default(), 0.0)
    .unwrap();
    let problem = GapHeat::new(
        (pellet, Conductivity::Constant(KP)),
        (tube, Conductivity::Constant(KC)),
        ss,
        ms,
        &coupling,
        Tolerances::default(),
        Tying,
        &heat,
    )
    .unwrap();
    let t0 = problem
        .bodies()
        .clone()
        .map(|b| vec![TC; b.mesh.node_count()]);
    let mut x = problem.state([&t0[0], &t0[1]]);
    let mut solver = GapSolverState::new(GapSolver::Newton);
    problem
        .solve(&mut x, 0.0, None, &mut solver, &newton)
        .unwrap();
    let [ts, tm, _] = problem.split(&x);
    let diff = ts
        .iter()
        .zip(&tied.temperatures[0])
        .chain(tm.iter().zip(&tied.temperatures[1]))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(diff < 1e-9, "GapHeat with Tying vs TiedHeat: {diff:e} K");
    // An open gap of constant conductance.
    let gap = 50e-6;
    let b = A + gap;
    let k_gas = 0.3;
    let law = GapConductance::simplified(gap, GasConductivity::Constant(k_gas)).unwrap();
    let resistance = gap / k_gas;
    let tolerances = Tolerances {
        search_radius: SearchRadius::Distance(2.0 * gap),
        ..Tolerances::default()
    };
    let mut l2 = Vec::new();
    let mut jump = Vec::new();
    for n in [4, 8, 16, 32] {
        let (pellet, tube) = bodies(n, b);
        let ss = pellet.mesh.boundary_surface(on_r(A)).unwrap();
        let ms = tube.mesh.boundary_surface(on_r(b)).unwrap();
        let problem = GapHeat::new(
            (pellet, Conductivity::Constant(KP)),
            (tube, Conductivity::Constant(KC)),
            ss,
            ms,
            &coupling,
            tolerances,
            law,
            &heat,
        )
        .unwrap()
        .with_multiplier_scale(1.0 / resistance)
        .unwrap();
        let t0 = problem
            .bodies()
            .clone()
            .map(|b| vec![TC; b.mesh.node_count()]);
        let mut x = problem.state([&t0[0], &t0[1]]);
        let mut solver = GapSolverState::new(GapSolver::Newton);
        problem
            .solve(&mut x, 0.0, None, &mut solver, &newton)
            .unwrap();
        let [ts, tm, _] = problem.split(&x);
        let [pellet, tube] = problem.bodies();
        l2.push(errors(pellet, tube, [ts, tm], b, resistance).0);
        let (s, m) = problem.interface_temperatures(&x);
        let q = Q * A / 2.0;
        let worst = s
            .iter()
            .zip(&m)
            .map(|(s, m)| ((s - m) - q * resistance).abs() / (q * resistance))
            .fold(0.0, f64::max);
        jump.push(worst);
    }
    println!(
        "pellet across a gap in r-z: L2 {} rates {:.3?}; gap jump vs q/U {}",
        sci(&l2),
        rates(&l2),
        sci(&jump)
    );
    for r in rates(&l2) {
        assert!(r > 1.85, "L2 rates {:?}", rates(&l2));
    }
    assert!(jump[3] < 1e-3, "{jump:?}");
}
