use mortar::physics::nonlinear::NewtonFailureReason;
use mortar::physics::PhysicsError;
use mortar::scenes::pellet::{run, PelletError, PelletScene, SolverMethod};

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
        assert!((x - y).abs() <= 1e-8 * x.abs(), "{x} vs {y}");
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
