use mortar::physics::nonlinear::NewtonFailureReason;
use mortar::physics::PhysicsError;
use mortar_scenes::pellet::{run, PelletError, PelletScene, SolverMethod};

fn out(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("mortar-pellet-test-{}-{name}", std::process::id()))
}

fn scene(method: SolverMethod) -> PelletScene {
    let mut s = PelletScene::default();
    s.model.mechanics = false;
    s.mesh.refinement = 1;
    s.time.step = 2.0;
    s.time.end = 6.0;
    s.time.snapshots = 1;
    s.solver.method = method;
    s
}

#[test]
fn newton_and_jfnk_agree() {
    let (a, b) = (out("newton"), out("jfnk"));
    let n = run(&scene(SolverMethod::Newton), &a, false).unwrap();
    let j = run(&scene(SolverMethod::Jfnk), &b, false).unwrap();
    assert!(a.join("report.json").exists() && a.join("pellet_steady.vtu").exists());
    let _ = (std::fs::remove_dir_all(&a), std::fs::remove_dir_all(&b));
    let close = |x: &serde_json::Value, y: &serde_json::Value| {
        let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
        assert!(
            (x - y).abs() <= crate::claims::claim("pellet.solvers").bound * x.abs(),
            "{x} vs {y}"
        );
    };
    for key in [
        "center_temperature",
        "pellet_surface_temperature",
        "cladding_inner_temperature",
    ] {
        close(&n[key], &j[key]);
    }
    let (hn, hj) = (
        n["transient"].as_array().unwrap(),
        j["transient"].as_array().unwrap(),
    );
    assert_eq!(hn.len(), 3);
    for (x, y) in hn.iter().zip(hj) {
        close(&x["center_temperature"], &y["center_temperature"]);
    }
    // JFNK iterates in GMRES; Newton does one direct solve per step.
    let s = &j["solver"];
    assert!(s["linear_iterations"].as_u64() > s["newton_iterations"].as_u64());
    assert_eq!(n["solver"]["symbolic_analyses"].as_u64(), Some(1));
}

#[test]
fn a_failing_newton_reports_its_history() {
    let mut s = scene(SolverMethod::Newton);
    s.solver.max_iterations = 1;
    s.solver.relative_tolerance = 1e-14;
    let dir = out("fail");
    let e = run(&s, &dir, false).unwrap_err();
    let _ = std::fs::remove_dir_all(&dir);
    match e {
        PelletError::Physics(PhysicsError::Newton(f)) => {
            assert_eq!(f.reason, NewtonFailureReason::MaxIterations);
            assert_eq!(f.residual_history.len(), 2);
        }
        other => panic!("expected a Newton failure, got {other}"),
    }
}

/// `[solver] method = "auto"` (the default) picks by the benchmark's rule and says why: JFNK
/// for the coupled scene (faster in every geometry and size measured), Newton for a 2D
/// cross-section above the size where the 2D trend crosses over and for the heat-only scene;
/// a method given is kept.
#[test]
fn auto_picks_by_the_measured_rule() {
    use mortar_scenes::pellet::{SolverData, AUTO_NEWTON_ABOVE_2D};
    let auto = SolverData::default();
    assert_eq!(auto.method, SolverMethod::Auto);
    let pick = |thermomech, plane, n| auto.choose(thermomech, plane, n);
    assert_eq!(pick(true, true, 2730).method, SolverMethod::Jfnk);
    assert_eq!(pick(true, false, 100_000).method, SolverMethod::Jfnk);
    let big = pick(true, true, AUTO_NEWTON_ABOVE_2D + 1);
    assert_eq!(big.method, SolverMethod::Newton);
    assert!(big.picked && big.reason.contains("2D"), "{big:?}");
    assert_eq!(pick(false, true, 0).method, SolverMethod::Newton);
    let given = SolverData {
        method: SolverMethod::Newton,
        ..SolverData::default()
    };
    let kept = given.choose(true, false, 5000);
    assert_eq!(kept.method, SolverMethod::Newton);
    assert!(!kept.picked);
}

/// A JFNK solve that fails under `"auto"` (GMRES restarted after every iteration cannot reach
/// its tolerance at the steady state) is handed to Newton: the run finishes, says so
/// (`solver_choice.fallback_to_newton`, with the time and the cause) and gives Newton's
/// answer; with JFNK asked for, the same failure is an error.
#[test]
fn a_failed_jfnk_solve_under_auto_falls_back_to_newton() {
    let mut s = PelletScene::default();
    s.mesh.refinement = 1;
    s.time.end = 2.0;
    s.time.snapshots = 1;
    s.solver.gmres_restart = 1;
    let dir = out("fallback");
    let rep = run(&s, &dir, false).unwrap();
    assert_eq!(rep["solver_choice"]["picked"], "jfnk");
    assert_eq!(rep["method"], "newton");
    let fallback = &rep["solver_choice"]["fallback_to_newton"];
    assert!(fallback["time"].as_f64().is_some(), "{fallback}");
    assert!(
        fallback["cause"].as_str().unwrap().contains("Newton"),
        "{fallback}"
    );
    s.solver.method = SolverMethod::Newton;
    let newton = run(&s, &dir, false).unwrap();
    let key = |r: &serde_json::Value| r["steady"]["center_temperature"].as_f64().unwrap();
    assert!((key(&rep) - key(&newton)).abs() <= 1e-9 * key(&newton));
    s.solver.method = SolverMethod::Jfnk;
    assert!(run(&s, &dir, false).is_err());
    let _ = std::fs::remove_dir_all(&dir);
}
