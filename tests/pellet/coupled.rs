//! The thermomechanical pellet: the 2D cross-section and the r-z model against the
//! independent 1D radial model of `radial.rs`, its energy balance, its Jacobian against
//! finite differences, Newton against JFNK, and its failures.

use mortar::core::linalg::SparseMatrix;
use mortar::physics::heat::assemble_heat_matrices;
use mortar::physics::laws::{ContactComplementarity, ExponentialContact};
use mortar::physics::nonlinear::{NewtonFailureReason, NewtonOptions};
use mortar::physics::thermomech::{ThermoMechSolver, ThermoMechSolverState};
use mortar::physics::PhysicsError;
use mortar_scenes::pellet::{
    coupled_problem, run, AxialModel, ContactLawName, Geometry, PelletError, PelletScene,
    SolverMethod,
};
use serde_json::Value;

use super::radial::{RadialHistory, RadialPellet};

fn out(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!(
        "mortar-pellet-coupled-{}-{name}",
        std::process::id()
    ))
}

/// Runs `scene`, removes its outputs, returns the report.
pub(super) fn run_scene(scene: &PelletScene, name: &str) -> Value {
    let dir = out(name);
    let rep = run(scene, &dir, false).unwrap_or_else(|e| panic!("{name}: {e}"));
    // The coupling's warnings are reported (none: the pellet covers the cladding's inside).
    assert_eq!(
        rep["coupling_warnings"].as_array().map(Vec::len),
        Some(0),
        "{name}"
    );
    for file in [
        "report.json",
        "pellet.pvd",
        "interface.pvd",
        "pellet_0000.vtu",
        "interface_0000.vtu",
        "temperatures.png",
        "gap.png",
        "pressures.png",
    ] {
        assert!(dir.join(file).exists(), "{name}: no {file}");
    }
    let _ = std::fs::remove_dir_all(&dir);
    rep
}

fn series(rep: &Value, key: &str) -> Vec<f64> {
    rep["history"][key]
        .as_array()
        .unwrap_or_else(|| panic!("history.{key}"))
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

/// Two runs' histories are the same bit for bit.
fn assert_same_history(a: &Value, b: &Value) {
    for key in [
        "center_temperature",
        "gap",
        "interface_pressure",
        "plenum_pressure",
    ] {
        assert_eq!(series(a, key), series(b, key), "{key}");
    }
}

/// The default scene with a contact conductance (so that its term is exercised).
fn scene(law: ContactLawName) -> PelletScene {
    let mut s = PelletScene::default();
    s.gap.contact_conductance = 1e-4;
    s.contact.law = law;
    s
}

/// Source: the independent 1D radial model of `radial.rs` (finite volumes exact for the
/// steady profiles, Timoshenko-Goodier cylinders in plane strain or generalized plane strain,
/// the same gap, contact and plenum laws), 400 + 60 radial cells, the same time steps. The
/// 2D cross-section and the r-z model (a segment with its bottom held in z and its top free
/// and plane, or both ends held for plane strain) agree at every step of the ramp and hold
/// (0 to 30 s) on the centre temperature, the mean gap (relative to the larger of itself and
/// `xi`, 5 um: under the exact law it closes to zero), the interface pressure `P_c` and the
/// plenum pressure to 0.5%, on the contact pressure `P_c - P_o` to 0.5% of its peak, and
/// close the gap within 0.05 s of the radial model's time (inside the ramp for the default,
/// exponential, law). Measured, largest over the steps (centre, gap, P_c, P_o,
/// p_contact / peak):
///
/// | model, axial, law, refinement | centre | gap | P_c | P_o | p_contact |
/// | --- | --- | --- | --- | --- | --- |
/// | 2D, generalized, exponential, 4 | 0.04% | 0.07% | 0.07% | 0.06% | 0.18% |
/// | 2D, plane strain, exponential, 3 | 0.07% | 0.12% | 0.14% | 0.06% | 0.18% |
/// | 2D, plane strain, exact, 8 | 0.01% | 0.04% | 0.11% | 0.06% | 0.26% |
/// | r-z, generalized, exponential, 3 | 0.06% | 0.07% | 0.12% | 0.05% | 0.21% |
/// | r-z, plane strain, exact, 8 | 0.01% | 0.02% | 0.11% | 0.06% | 0.38% |
///
/// With free axial expansion the contact pressure's peak is smaller (5.2 MPa above the
/// plenum's at 20 kW/m) and its 2D error converges at second order: 0.60%, 0.18%, 0.13% of
/// the peak at refinements 3, 4, 6 (hence 4, by JFNK). The exact law's contact pressure
/// (2.4 MPa at its peak in plane strain, from an interference of about 1 um) is far more
/// sensitive to the displacement's discretisation error: in 2D 3.0% of its peak at
/// refinement 3, 0.50% at 6, hence the finer meshes (2D solved by JFNK). With free axial
/// expansion the exact law's gap does not close at 20 kW/m (no contact pressure), so the
/// exact-law cases are in plane strain.
#[test]
fn the_cross_section_and_the_rz_model_agree_with_the_radial_model() {
    use AxialModel::{Generalized, PlaneStrain};
    for (geometry, axial, law, refinement, method) in [
        (
            Geometry::Plane,
            Generalized,
            ContactLawName::Exponential,
            4,
            SolverMethod::Jfnk,
        ),
        (
            Geometry::Plane,
            PlaneStrain,
            ContactLawName::Exponential,
            3,
            SolverMethod::Newton,
        ),
        (
            Geometry::Plane,
            PlaneStrain,
            ContactLawName::Exact,
            8,
            SolverMethod::Jfnk,
        ),
        (
            Geometry::Axisymmetric,
            Generalized,
            ContactLawName::Exponential,
            3,
            SolverMethod::Newton,
        ),
        (
            Geometry::Axisymmetric,
            PlaneStrain,
            ContactLawName::Exact,
            8,
            SolverMethod::Newton,
        ),
    ] {
        let mut s = scene(law);
        s.mesh.refinement = refinement;
        s.solver.method = method;
        s.model.geometry = geometry;
        s.model.axial = Some(axial);
        let law = (geometry, axial, law);
        let (rep, radial, worst, peak) = against_radial(
            &s,
            RadialPellet::from_scene(&s),
            &format!("radial-{law:?}").replace(['(', ')', ' ', ','], ""),
        );
        assert_eq!(rep["models"]["axial"], serde_json::to_value(axial).unwrap());
        assert!(
            peak > 1e6,
            "{law:?}: the contact pressure rises ({peak} Pa)"
        );
        eprintln!(
            "{law:?}: largest relative differences to the radial model (centre, gap, P_c, P_o, \
             p_contact/peak): {worst:?}; closure {} (model) vs {:?} (radial)",
            rep["gap_closure_time"], radial.closure
        );
        for (what, w) in ["centre", "gap", "P_c", "P_o", "p_contact"]
            .iter()
            .zip(worst)
        {
            assert!(
                w < crate::claims::claim("pellet.coupled").bound,
                "{law:?}: {what} differs by {w:.2e}"
            );
        }
        let closure = rep["gap_closure_time"].as_f64().expect("the gap closes");
        let reference = radial.closure.expect("closes").interpolated_time;
        if law.2 == ContactLawName::Exponential {
            // The default scene's gap closes during the ramp (the exact law, which needs
            // g = 0 rather than g = xi, closes at 14 s, after it).
            assert!(
                closure < s.power.ramp_time,
                "closes during the ramp: {closure}"
            );
        }
        assert!(
            (closure - reference).abs() < crate::claims::claim("pellet.closure").bound + 1e-9,
            "{closure} vs {reference}"
        );
        // The steady state conserves energy: the power put in leaves through the cladding.
        let imbalance = rep["steady"]["relative_imbalance"].as_f64().unwrap();
        assert!(
            imbalance < crate::claims::claim("pellet.energy").bound,
            "{law:?}: energy imbalance {imbalance:e}"
        );
    }
}

/// Runs `s` and the radial model `model` (of its data); the largest differences at the steps, relative
/// (centre temperature, mean gap relative to the larger of itself and `xi`, interface pressure
/// `P_c`, plenum pressure `P_o`, contact pressure `P_c - P_o` relative to the larger of its
/// peak and 1 MPa), with the report, the radial history and the radial model's peak contact
/// pressure.
pub(super) fn against_radial(
    s: &PelletScene,
    model: RadialPellet,
    name: &str,
) -> (Value, RadialHistory, [f64; 5], f64) {
    let rep = run_scene(s, name);
    let radial = model.simulate().unwrap();
    let t2d = series(&rep, "time");
    assert_eq!(t2d.len(), radial.rows.len());
    let peak = radial
        .rows
        .iter()
        .map(|r| r.contact_pressure)
        .fold(0.0, f64::max);
    let mut worst = [0.0f64; 5];
    for (k, r) in radial.rows.iter().enumerate() {
        assert!((t2d[k] - r.time).abs() < 1e-12);
        let pairs = [
            (
                series(&rep, "center_temperature")[k],
                r.center_temperature,
                r.center_temperature,
            ),
            (
                series(&rep, "gap")[k],
                r.gap,
                r.gap.abs().max(s.contact.onset_gap),
            ),
            (
                series(&rep, "interface_pressure")[k],
                r.interface_pressure,
                r.interface_pressure,
            ),
            (
                series(&rep, "plenum_pressure")[k],
                r.plenum_pressure,
                r.plenum_pressure,
            ),
            (
                series(&rep, "interface_pressure")[k] - series(&rep, "plenum_pressure")[k],
                r.contact_pressure,
                peak.max(1e6),
            ),
        ];
        for (w, (a, b, scale)) in worst.iter_mut().zip(pairs) {
            *w = w.max((a - b).abs() / scale.abs());
        }
    }
    (rep, radial, worst, peak)
}

/// The largest difference between the assembled Jacobian and central finite differences of
/// the residual, over `dirs` directions, relative to the largest product.
pub(super) fn jacobian_error(
    j: &SparseMatrix,
    f: impl Fn(&[f64]) -> Vec<f64>,
    x: &[f64],
    dirs: usize,
) -> f64 {
    let n = x.len();
    let mut worst = 0.0f64;
    for d in 0..dirs {
        // A deterministic pseudo-random direction of unit entries' scale.
        let v: Vec<f64> = (0..n)
            .map(|i| ((i * 7919 + d * 104_729) % 1000) as f64 / 500.0 - 1.0)
            .collect();
        let mut jv = vec![0.0; n];
        for (r, row) in j.outer_iterator().enumerate() {
            jv[r] = row.iter().map(|(c, a)| a * v[c]).sum();
        }
        let h = 1e-6;
        let plus: Vec<f64> = x.iter().zip(&v).map(|(a, b)| a + h * b).collect();
        let minus: Vec<f64> = x.iter().zip(&v).map(|(a, b)| a - h * b).collect();
        let (fp, fm) = (f(&plus), f(&minus));
        let scale = jv.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        for i in 0..n {
            let fd = (fp[i] - fm[i]) / (2.0 * h);
            worst = worst.max((fd - jv[i]).abs() / scale);
        }
    }
    worst
}

/// The coupled Jacobian (heat with k(T), elasticity, both laws, the plenum) against central
/// finite differences of the residual at a state with the gap closing (pellet expanded by
/// 17 um of its 20 um gap, temperatures, fluxes and pressures away from zero), for both
/// contact laws. Source: the definition of the derivative.
#[test]
fn the_coupled_jacobian_matches_finite_differences() {
    let mut s = scene(ContactLawName::Exponential);
    s.mesh.refinement = 1;
    let check = |name: &str, err: f64| {
        eprintln!("{name}: Jacobian against finite differences {err:.2e}");
        assert!(
            err < crate::claims::claim("pellet.jacobian").bound,
            "{name}: {err:e}"
        );
    };
    let exp = ExponentialContact::try_new(1e12, 5e-6).unwrap();
    let exact = ContactComplementarity::try_new(1e14).unwrap();
    macro_rules! check_law {
        ($law:expr, $name:expr) => {{
            let p = coupled_problem(&s, $law).unwrap();
            let bodies = p.heat().bodies();
            let temperature = |b: usize, hot: f64| -> Vec<f64> {
                bodies[b]
                    .mesh
                    .coords()
                    .iter()
                    .map(|x| hot - 1e4 * x.norm() * (1.0 + 0.3 * x.x / x.norm().max(1e-9)))
                    .collect()
            };
            let mut x = p.state([&temperature(0, 900.0), &temperature(1, 700.0)]);
            // Unknowns: T (both), u (both, micrometres), fluxes, contact pressures (MPa), gas.
            let (n0, n1) = (bodies[0].mesh.node_count(), bodies[1].mesh.node_count());
            let coords = bodies[0].mesh.coords();
            let eps = 17.0 / 4.1e-3; // um per metre of radius
            for (i, c) in coords.iter().enumerate() {
                let o = n0 + n1 + 2 * i;
                x[o] = eps * c.x * (1.0 + 0.01 * (i % 3) as f64);
                x[o + 1] = eps * c.y;
            }
            let rows = p.normal_gap().weights.len();
            let base = n0 + n1 + 2 * (n0 + n1);
            for j in 0..rows {
                x[base + j] = 5.0 + 0.1 * j as f64;
                x[base + rows + j] = 2.0 + 0.05 * j as f64;
            }
            // The axial unknowns (last): microstrain in 2D, micrometres of the top in r-z.
            let n = x.len();
            x[n - 2] = 5000.0;
            x[n - 1] = 1500.0;
            let t = 5.0;
            let jac = p.steady_jacobian(&x, t).unwrap();
            let err = jacobian_error(&jac, |y| p.steady_residual(y, t).unwrap(), &x, 3);
            check($name, err);
        }};
    }
    // Free axial expansion: generalized plane strain in 2D, a free plane top in r-z.
    for geometry in [Geometry::Plane, Geometry::Axisymmetric] {
        s.model.geometry = geometry;
        check_law!(exp, &format!("{geometry:?}, exponential"));
        check_law!(exact, &format!("{geometry:?}, exact"));
    }
}

/// Newton on the assembled Jacobian and JFNK with the block preconditioner converge to the
/// same states (1e-8 relative on every history entry), and JFNK keeps its factorisations
/// across steps.
#[test]
fn newton_and_jfnk_agree_on_the_coupled_scene() {
    let mut s = scene(ContactLawName::Exponential);
    s.mesh.refinement = 2;
    s.time.snapshots = 1;
    s.solver.method = SolverMethod::Newton;
    let newton = run_scene(&s, "newton");
    assert_eq!(newton["method"], "newton");
    s.solver.method = SolverMethod::Jfnk;
    let jfnk = run_scene(&s, "jfnk");
    assert_eq!(jfnk["method"], "jfnk");
    // "auto" picks JFNK for the coupled scene and says so: the same run.
    s.solver.method = SolverMethod::Auto;
    let auto = run_scene(&s, "auto");
    assert_eq!(auto["method"], "jfnk");
    assert_eq!(auto["solver_choice"]["asked"], "auto");
    assert!(auto["solver_choice"]["why"]
        .as_str()
        .unwrap()
        .contains("measured"));
    assert!(auto["solver_choice"]["fallback_to_newton"].is_null());
    assert_same_history(&auto, &jfnk);
    for key in [
        "center_temperature",
        "gap",
        "interface_pressure",
        "plenum_pressure",
        "pellet_surface_displacement",
    ] {
        for (a, b) in series(&newton, key).iter().zip(series(&jfnk, key)) {
            assert!((a - b).abs() <= 1e-8 * a.abs(), "{key}: {a} vs {b}");
        }
    }
    let (sn, sj) = (&newton["solver"], &jfnk["solver"]);
    eprintln!("Newton: {sn}\nJFNK: {sj}");
    let steps = sj["newton_iterations"].as_u64().unwrap();
    assert!(
        sj["factorizations"].as_u64().unwrap() * 4 < steps,
        "kept across steps"
    );
    assert!(sj["reused_preconditioners"].as_u64().unwrap() > 0);
}

/// A Newton that cannot converge (one step allowed at a tolerance it cannot reach) fails at
/// the first solve, the initial state (no step to cut there; a time step cut MAX_STEP_CUTS
/// times is tests/pellet/limits.rs's 1e12 W/m), with its residual history, the solve named,
/// having written the report (status "failed", no valid step).
#[test]
fn a_failing_initial_solve_is_reported() {
    let mut s = scene(ContactLawName::Exponential);
    s.mesh.refinement = 1;
    s.solver.max_iterations = 1;
    s.solver.relative_tolerance = 1e-15;
    let dir = out("failing");
    let _ = std::fs::remove_dir_all(&dir);
    let e = run(&s, &dir, false).unwrap_err();
    match &e {
        PelletError::SolveFailed {
            step,
            block,
            source,
            ..
        } if matches!(**source, PhysicsError::Newton(_)) => {
            let PhysicsError::Newton(f) = source.as_ref() else {
                unreachable!()
            };
            assert_eq!(f.reason, NewtonFailureReason::MaxIterations);
            assert_eq!(f.residual_history.len(), 2);
            assert_eq!(*step, Some(0));
            assert!(block.is_some());
        }
        other => panic!("expected a Newton failure, got {other}"),
    }
    let text = std::fs::read_to_string(dir.join("report.json")).unwrap();
    let rep: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(rep["status"], "failed");
    assert!(rep["error"].as_str().unwrap().contains("Newton"));
    assert!(rep["error"]
        .as_str()
        .unwrap()
        .contains("the initial state failed at t = 0 s"));
    assert_eq!(rep["failure"]["step"], 0);
    assert_eq!(rep["valid_steps"], 0);
    assert!(rep["residual_history"]
        .as_array()
        .is_some_and(|h| !h.is_empty()));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Non-physical values are refused, naming the key.
#[test]
fn non_physical_values_are_refused() {
    for (toml, key) in [
        ("[pellet]\npoisson_ratio = 0.5", "pellet.poisson_ratio"),
        ("[cladding]\npoisson_ratio = -1.0", "cladding.poisson_ratio"),
        ("[pellet]\nyoungs_modulus = 0.0", "pellet.youngs_modulus"),
        (
            "[cladding]\nyoungs_modulus = -80e9",
            "cladding.youngs_modulus",
        ),
        (
            "[pellet]\nthermal_expansion = -1e-5",
            "pellet.thermal_expansion",
        ),
        (
            "[cladding]\ncoolant_pressure = -1.0",
            "cladding.coolant_pressure",
        ),
        (
            "[plenum]\nfill_temperature = 0.0",
            "plenum.fill_temperature",
        ),
        ("[pellet]\nradius = -4.1e-3", "pellet.radius"),
        ("[cladding]\ninner_radius = 5e-3", "radii"),
        (
            "[model]\ngeometry = \"3d\"\nmechanics = false",
            "model.geometry",
        ),
        ("[model]\nsegment_height = 0.0", "model.segment_height"),
        ("[mesh]\naxial_layers = 0", "mesh.axial_layers"),
        (
            "[model]\ngeometry = \"axisymmetric\"\nmechanics = false",
            "model.geometry",
        ),
    ] {
        match PelletScene::from_toml(toml) {
            Err(PelletError::Invalid(m)) => assert!(m.contains(key), "{toml}: {m}"),
            other => panic!("{toml}: {other:?}"),
        }
    }
}

/// The 3D segment (the cross-section swept along z through one layer of Hex8, its bottom held
/// in z and its top free, kept plane: free axial expansion) against the 2D cross-section in
/// generalized plane strain, both from the same physics code, at refinement 1, at every step.
/// Not to round-off: the 2D mortar projects along the interpolated nodal normals, the 3D one
/// onto each slave face's auxiliary plane, so D and M differ by the discretisation (O(h^2)).
/// Source: a prismatic segment with a free plane end under a z-independent load is in
/// generalized plane strain (uniform axial strain), so its solution is the 2D one.
#[test]
fn the_3d_segment_is_the_generalized_plane_strain_cross_section() {
    let mut s2 = scene(ContactLawName::Exponential);
    s2.mesh.refinement = 1;
    s2.time.snapshots = 1;
    let mut s3 = s2.clone();
    s3.model.geometry = mortar_scenes::pellet::Geometry::ThreeD;
    s3.mesh.axial_layers = 1;
    let (r2, r3) = (run_scene(&s2, "2d"), run_scene(&s3, "3d"));
    assert_eq!(r3["models"]["geometry"], "3d");
    assert_eq!(r3["models"]["axial"], "generalized");
    let strains = |r: &Value| {
        let a = &r["steady"]["axial_strain"];
        [
            a["pellet"].as_f64().unwrap(),
            a["cladding"].as_f64().unwrap(),
        ]
    };
    for (a, b) in strains(&r2).into_iter().zip(strains(&r3)) {
        eprintln!("3D against 2D: axial strain {b:.6e} vs {a:.6e}");
        assert!(
            (a - b).abs() < crate::claims::claim("pellet.segment_3d_strain").bound * a.abs(),
            "axial strain {b} vs {a}"
        );
    }
    for (key, bound) in [
        ("center_temperature", 1e-5),
        ("gap", crate::claims::claim("pellet.segment_3d").bound),
        (
            "interface_pressure",
            crate::claims::claim("pellet.segment_3d").bound,
        ),
        ("plenum_pressure", 1e-5),
        ("pellet_surface_displacement", 1e-5),
    ] {
        let worst = series(&r2, key)
            .iter()
            .zip(series(&r3, key))
            .map(|(a, b)| (a - b).abs() / a.abs())
            .fold(0.0, f64::max);
        eprintln!("3D against 2D: {key} within {worst:.2e}");
        assert!(worst < bound, "{key}: {worst:e}");
    }
    let imbalance = r3["steady"]["relative_imbalance"].as_f64().unwrap();
    assert!(imbalance < 1e-6, "3D energy imbalance {imbalance:e}");
}

/// Free expansion inside the coupled problem: the gap kept open (cladding inner radius
/// 4.5 mm) and no pressures (no coolant, no fill gas), the steady pellet surface displacement
/// of the coupled solve against the closed form evaluated on the computed temperature (the
/// area integral of its interpolant by the consistent capacity matrix): in plane strain
/// `u(a) = (1 + nu) (2 alpha / a) int_0^a (T - T_ref) r dr = (1 + nu) alpha / (pi a)
/// int_A (T - T_ref) dA`; in generalized plane strain (free ends, the default) the same
/// without the factor `1 + nu`. Second order (plane strain, measured largest errors over the
/// surface nodes 6.6e-3, 2.9e-3, 1.6e-3, 7.3e-4 at refinements 2, 3, 4, 6): within 1e-3 from
/// refinement 6. Source: Timoshenko and Goodier, *Theory of Elasticity*, sec. 150.
#[test]
fn free_expansion_inside_the_coupled_problem() {
    for axial in [AxialModel::PlaneStrain, AxialModel::Generalized] {
        let errors: Vec<f64> = [3, 6]
            .into_iter()
            .map(|r| free_expansion_error(r, axial))
            .collect();
        eprintln!(
            "free expansion in the coupled problem ({axial:?}), refinements 3 and 6: errors {errors:?}"
        );
        assert!(errors[0] / errors[1] > 3.5, "second order: {errors:?}");
        assert!(errors[1] < 1e-3, "{errors:?}");
    }
}

/// The largest relative error of the free expansion at refinement `r` (see above).
fn free_expansion_error(r: usize, axial: AxialModel) -> f64 {
    let mut s = scene(ContactLawName::Exponential);
    s.model.axial = Some(axial);
    s.cladding.inner_radius = 4.5e-3;
    s.cladding.outer_radius = 5.0e-3;
    s.cladding.coolant_pressure = 0.0;
    s.plenum.fill_pressure = 0.0;
    s.mesh.refinement = r;
    let p = coupled_problem(&s, ExponentialContact::try_new(1e12, 5e-6).unwrap()).unwrap();
    let bodies = p.heat().bodies();
    let t0: Vec<f64> = vec![s.cladding.outer_temperature; bodies[0].mesh.node_count()];
    let t1: Vec<f64> = vec![s.cladding.outer_temperature; bodies[1].mesh.node_count()];
    let mut x = p.state([&t0, &t1]);
    let mut solver = ThermoMechSolverState::new(ThermoMechSolver::Newton);
    p.solve(
        &mut x,
        s.power.ramp_time,
        None,
        &mut solver,
        &NewtonOptions::default(),
    )
    .unwrap();
    let f = p.fields(&x);
    assert_eq!(f.gas_pressure, 0.0);
    assert!(p.gaps(&x).iter().all(|&g| g > 100e-6), "the gap stays open");
    // int_A (T - T_ref) dA by the capacity matrix (rho c_p int N_i N_j).
    let pellet = &bodies[0];
    let c = assemble_heat_matrices(pellet, &Default::default())
        .unwrap()
        .capacity;
    let t_ref = s.model.reference_temperature;
    let integral: f64 = c
        .outer_iterator()
        .map(|row| {
            row.iter()
                .map(|(j, v)| v * (f.temperature[0][j] - t_ref))
                .sum::<f64>()
        })
        .sum::<f64>()
        / s.pellet.heat_capacity;
    let (a, nu, alpha) = (
        s.pellet.radius,
        s.pellet.poisson_ratio,
        s.pellet.thermal_expansion,
    );
    let factor = match axial {
        AxialModel::PlaneStrain => 1.0 + nu,
        AxialModel::Generalized => 1.0,
    };
    let exact = factor * alpha / (std::f64::consts::PI * a) * integral;
    let u = f.displacement(0);
    let coords = pellet.mesh.coords();
    let mut worst = 0.0f64;
    for &n in p.heat().tie().slave_nodes() {
        let (n, x) = (n as usize, coords[n as usize]);
        let ur = (u[2 * n] * x.x + u[2 * n + 1] * x.y) / x.norm();
        worst = worst.max((ur - exact).abs() / exact);
    }
    worst
}

/// Run-time choice of laws: the scene run with its laws made by name from
/// the registry (`DynLaw`, through `run_coupled_with`) gives the built-in run's history bit
/// for bit.
#[test]
fn laws_chosen_by_name_run_the_scene_as_the_built_in_ones() {
    use mortar::physics::laws::{LawParameters, LawRegistry};
    use mortar_scenes::pellet::run_coupled_with;
    let mut s = scene(ContactLawName::Exponential);
    s.mesh.refinement = 1;
    s.time.snapshots = 1;
    let built_in = run_scene(&s, "builtin-laws");
    let registry = LawRegistry::with_shipped();
    let params = |kv: &[(&str, f64)]| -> LawParameters {
        kv.iter().map(|(k, v)| (k.to_string(), *v)).collect()
    };
    let thermal = registry
        .make(
            "mechanical_gap_conductance",
            &params(&[
                ("roughness_fuel", s.gap.roughness_pellet),
                ("roughness_cladding", s.gap.roughness_cladding),
                ("jump_distance", s.gap.jump_distance),
                ("contact_conductance", s.gap.contact_conductance),
            ]),
        )
        .unwrap();
    let contact = registry
        .make(
            "exponential_contact",
            &params(&[
                ("stiffness", s.contact.stiffness_exponent),
                ("onset", s.contact.onset_gap),
            ]),
        )
        .unwrap();
    let dir = out("dyn-laws");
    let by_name = run_coupled_with(&s, thermal, contact, &dir, false).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_same_history(&built_in, &by_name);
}

/// Scene files naming laws: `[laws.thermal]` and `[laws.contact]` with the
/// built-in laws' names and parameters run as the built-in scene, bit for bit; an unknown
/// name is an error listing the known ones, a missing parameter one naming it; a program's
/// own law registered by name (gap conductance plus radiation) runs through the same file
/// syntax and transfers more heat (a cooler centre).
#[test]
fn scene_files_name_their_laws() {
    use mortar::physics::laws::{DynLaw, LawError, LawRegistry, MechanicalGapConductance};
    use mortar_scenes::pellet::run_with_registry;
    let base = "kind = \"pellet\"\n[mesh]\nrefinement = 1\n[time]\nsnapshots = 1\n\
                [gap]\ncontact_conductance = 1e-4\n";
    let named = format!(
        "{base}[laws.thermal]\nname = \"mechanical_gap_conductance\"\nroughness_fuel = 2e-6\n\
         roughness_cladding = 1e-6\njump_distance = 10e-6\ncontact_conductance = 1e-4\n\
         [laws.contact]\nname = \"exponential_contact\"\nstiffness = 1e12\nonset = 5e-6\n"
    );
    let built_in = run_scene(&PelletScene::from_toml(base).unwrap(), "laws-builtin");
    let by_name = run_scene(&PelletScene::from_toml(&named).unwrap(), "laws-named");
    assert_same_history(&built_in, &by_name);
    assert_eq!(by_name["models"]["contact_law"], "exponential_contact");
    assert_eq!(built_in["gap_closure_time"], by_name["gap_closure_time"]);

    let unknown = named.replace("\"exponential_contact\"", "\"hertzian\"");
    let dir = out("laws-unknown");
    match run(&PelletScene::from_toml(&unknown).unwrap(), &dir, false) {
        Err(PelletError::Law(e)) => {
            let m = e.to_string();
            assert!(
                m.contains("hertzian") && m.contains("exponential_contact"),
                "{m}"
            );
        }
        other => panic!("{other:?}"),
    }
    let missing = named.replace("onset = 5e-6\n", "");
    match run(&PelletScene::from_toml(&missing).unwrap(), &dir, false) {
        Err(PelletError::Law(e)) => assert!(e.to_string().contains("onset"), "{e}"),
        other => panic!("{other:?}"),
    }

    /// Gap conductance plus radiation across the gap, `q = U dT + s e (T_s^4 - T_m^4)`.
    struct Radiating {
        conductance: MechanicalGapConductance,
        emissivity: f64,
    }
    impl mortar::physics::laws::ConstraintLaw for Radiating {
        fn residual<S: mortar::physics::laws::Float>(
            &self,
            p: mortar::physics::laws::LawPoint<S>,
        ) -> S {
            let half = S::from(0.5).unwrap();
            let (ts, tm) = (p.temperature + half * p.gap, p.temperature - half * p.gap);
            let sigma = S::from(5.670374419e-8 * self.emissivity).unwrap();
            let r = self
                .conductance
                .resistance(p.normal_gap, p.contact_pressure, p.temperature);
            // q = dT / R + radiation, normalised as the gap conductance (R q - dT) / (R + R_ref).
            let q_rad = sigma * (ts.powi(4) - tm.powi(4));
            let r_ref = S::from(1e-4).unwrap();
            (r * (p.multiplier - q_rad) - p.gap) / (r + r_ref)
        }
    }
    let mut registry = LawRegistry::with_shipped();
    registry.register("radiating_gap", |p| {
        let get = |k: &str| {
            p.get(k).copied().ok_or(LawError::InvalidParameter {
                law: "radiating gap",
                what: format!("{k} missing"),
            })
        };
        Ok(DynLaw::new(
            "radiating_gap",
            Radiating {
                conductance: MechanicalGapConductance::try_new(
                    get("roughness_fuel")?,
                    get("roughness_cladding")?,
                    get("jump_distance")?,
                    mortar::physics::laws::GasConductivity::HELIUM,
                    get("contact_conductance")?,
                )?,
                emissivity: get("emissivity")?,
            },
        ))
    });
    let radiating = named
        .replace("\"mechanical_gap_conductance\"", "\"radiating_gap\"")
        .replace(
            "contact_conductance = 1e-4\n[laws.contact]",
            "contact_conductance = 1e-4\nemissivity = 0.8\n[laws.contact]",
        );
    let dir = out("laws-radiating");
    let rep = run_with_registry(
        &PelletScene::from_toml(&radiating).unwrap(),
        &registry,
        &dir,
        false,
    )
    .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(rep["models"]["gap_conductance"], "radiating_gap");
    let (t_rad, t_cond) = (
        rep["center_temperature"].as_f64().unwrap(),
        built_in["center_temperature"].as_f64().unwrap(),
    );
    eprintln!("centre temperature with radiation {t_rad:.3} K, without {t_cond:.3} K");
    assert!(
        t_rad < t_cond,
        "radiation carries heat: {t_rad} vs {t_cond}"
    );
}

/// Regression: a run into the folder of an earlier run left the earlier run's extra
/// snapshots (`pellet_0004.vtu` of a 4-snapshot run beside a 1-snapshot run's files, or the
/// thermal run's `pellet_steady.vtu`), which a ParaView user takes for this run's. The
/// pellet outputs this run did not write are now removed; other files stay.
#[test]
fn a_second_run_leaves_no_stale_snapshots() {
    let dir = out("stale");
    let _ = std::fs::remove_dir_all(&dir);
    let mut s = scene(ContactLawName::Exponential);
    s.mesh.refinement = 1;
    s.time.snapshots = 4;
    run(&s, &dir, false).unwrap();
    assert!(dir.join("pellet_0004.vtu").exists());
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    std::fs::write(dir.join("pellet_steady.vtu"), "an old thermal run's").unwrap();
    s.time.snapshots = 1;
    let rep = run(&s, &dir, false).unwrap();
    let vtu: Vec<&str> = rep["vtu"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(vtu, ["pellet_0000.vtu", "pellet_0001.vtu"]);
    for stale in [
        "pellet_0002.vtu",
        "pellet_0004.vtu",
        "interface_0003.vtu",
        "pellet_steady.vtu",
    ] {
        assert!(!dir.join(stale).exists(), "{stale} left behind");
    }
    assert!(dir.join("notes.txt").exists(), "a user's file is kept");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The cold state in the coupled problem (source: a body free to expand under a uniform
/// temperature change carries no stress; at `T = T_ref` without load it carries none at
/// all): no power, no fill gas, no coolant, the whole rod at the cladding's outer
/// temperature `T_ref + dT`, the gap kept open. With free axial expansion (2D generalized
/// plane strain, r-z with a free top) the steady state's stress is zero to rounding in both
/// bodies for `dT = 0` and `dT = 400 K`, and each body's axial strain is `alpha dT`; in plane
/// strain the same heating leaves `sigma_zz = -E alpha dT` in each.
#[test]
fn the_cold_state_is_stress_free_with_free_ends() {
    use mortar::physics::elastic::recover_stress_with_axial_strain;
    for (geometry, axial) in [
        (Geometry::Plane, AxialModel::Generalized),
        (Geometry::Axisymmetric, AxialModel::Generalized),
        (Geometry::Plane, AxialModel::PlaneStrain),
    ] {
        for dt in [0.0, 400.0] {
            let mut s = scene(ContactLawName::Exponential);
            s.mesh.refinement = 1;
            s.model.geometry = geometry;
            s.model.axial = Some(axial);
            s.power.linear_power = 0.0;
            s.plenum.fill_pressure = 0.0;
            s.cladding.coolant_pressure = 0.0;
            s.cladding.inner_radius = 4.5e-3;
            s.cladding.outer_radius = 5.0e-3;
            s.cladding.outer_temperature = s.model.reference_temperature + dt;
            let p = coupled_problem(&s, ExponentialContact::try_new(1e12, 5e-6).unwrap()).unwrap();
            let bodies = p.heat().bodies();
            let t = s.cladding.outer_temperature;
            let t0 = vec![t; bodies[0].mesh.node_count()];
            let t1 = vec![t; bodies[1].mesh.node_count()];
            let mut x = p.state([&t0, &t1]);
            let mut solver = ThermoMechSolverState::new(ThermoMechSolver::Newton);
            p.solve(&mut x, 0.0, None, &mut solver, &NewtonOptions::default())
                .unwrap();
            let f = p.fields(&x);
            let options = p.options().elastic;
            for b in 0..2 {
                let elastic = &p.elastic_bodies()[b];
                let m = elastic.material;
                let body = elastic
                    .clone()
                    .with_temperature(f.temperature[b].to_vec())
                    .unwrap();
                let plane_gps = geometry == Geometry::Plane && axial == AxialModel::Generalized;
                let e = if plane_gps {
                    f.axial_strain[b].unwrap()
                } else {
                    0.0
                };
                let stress =
                    recover_stress_with_axial_strain(&body, &f.displacement(b), e, &options)
                        .unwrap();
                let scale = m.youngs_modulus * m.thermal_expansion * 400.0;
                let expected_zz = match axial {
                    AxialModel::Generalized => 0.0,
                    AxialModel::PlaneStrain => -m.youngs_modulus * m.thermal_expansion * dt,
                };
                let largest = stress
                    .cells
                    .iter()
                    .flat_map(|c| {
                        c.iter()
                            .enumerate()
                            .map(|(k, v)| if k == 2 { v - expected_zz } else { *v })
                    })
                    .fold(0.0f64, |a, v| a.max(v.abs()));
                eprintln!(
                    "cold state, {geometry:?} {axial:?}, dT = {dt} K, body {b}: largest stress error {largest:.2e} Pa ({:.1e} of E alpha 400 K), axial strain {:?}",
                    largest / scale,
                    f.axial_strain[b]
                );
                assert!(
                    largest < crate::claims::claim("pellet.cold").bound * scale,
                    "{geometry:?} {axial:?} {dt} {b}: {largest}"
                );
                if axial == AxialModel::Generalized {
                    let strain = f.axial_strain[b].unwrap();
                    let want = m.thermal_expansion * dt;
                    assert!(
                        (strain - want).abs() <= 1e-11 * m.thermal_expansion * 400.0,
                        "{strain} {want}"
                    );
                }
            }
        }
    }
}
