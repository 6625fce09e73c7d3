use mortar_scenes::pellet::{run_from_toml, PelletError, PelletScene, SolverMethod};

#[test]
fn parses_the_keys_and_refuses_unknown_ones() {
    let s = PelletScene::from_toml(
        r#"
        [pellet]
        radius = 4.0e-3
        conductivity_a = 0.04
        conductivity_b = 2e-4
        [cladding]
        inner_radius = 4.1e-3
        outer_radius = 4.7e-3
        conductivity = 15.0
        outer_temperature = 600.0
        [gap]
        roughness_pellet = 1e-6
        roughness_cladding = 1e-6
        jump_distance = 5e-6
        gas_conductivity = 0.25
        [power]
        linear_power = 15e3
        ramp_time = 5.0
        [solver]
        method = "jfnk"
        [mesh]
        refinement = 1
        "#,
    )
    .unwrap();
    assert_eq!(s.solver.method, SolverMethod::Jfnk);
    assert_eq!(s.gap.gas_conductivity, Some(0.25));
    assert_eq!(s.mesh.refinement, 1);
    assert!(matches!(
        PelletScene::from_toml("[pellet]\nradios = 1.0"),
        Err(PelletError::Parse(_))
    ));
    assert!(matches!(
        PelletScene::from_toml("[solver]\nmethod = \"picard\""),
        Err(PelletError::Parse(_))
    ));
    assert!(matches!(
        PelletScene::from_toml("[cladding]\ninner_radius = 4.0e-3"),
        Err(PelletError::Invalid(_))
    ));
}

#[test]
fn run_from_toml_writes_the_report() {
    let dir = std::env::temp_dir().join(format!("mortar-pellet-test-{}-toml", std::process::id()));
    let rep = run_from_toml(
        "[model]\nmechanics = false\n[mesh]\nrefinement = 1\n[time]\nend = 2.0\nsnapshots = 2\n[gap]\ngas_conductivity = 0.3\n",
        &dir,
        false,
    )
    .unwrap();
    let text = std::fs::read_to_string(dir.join("report.json")).unwrap();
    let written: serde_json::Value = serde_json::from_str(&text).unwrap();
    // serde_json's float parsing may differ in the last digit: compare the keys closely.
    for key in ["center_temperature", "pellet_surface_temperature"] {
        let (a, b) = (written[key].as_f64().unwrap(), rep[key].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-12 * a.abs());
    }
    assert_eq!(written["vtu"], rep["vtu"]);
    for key in [
        "center_temperature",
        "pellet_surface_temperature",
        "cladding_inner_temperature",
    ] {
        let (v, cf) = (
            rep[key].as_f64().unwrap(),
            rep["closed_form"][key].as_f64().unwrap(),
        );
        assert!(
            (v - cf).abs() < 0.02 * (cf - 580.0).max(1.0),
            "{key}: {v} vs {cf}"
        );
    }
    assert!(rep["solver"]["newton_iterations"].as_u64().unwrap() > 0);
    assert!(dir.join("pellet.pvd").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Regression: a run that fails in the transient (here Newton allowed one
/// step at a tolerance it cannot reach in one) left `pellet_0000.vtu` behind. Every output
/// is now written at the end, all or none: the failed run leaves no output folder.
#[test]
fn a_failed_run_writes_nothing() {
    let mut scene = mortar_scenes::pellet::PelletScene::default();
    scene.model.mechanics = false;
    scene.solver.max_iterations = 1;
    scene.solver.relative_tolerance = 1e-15;
    let dir = std::env::temp_dir().join(format!("mortar-pellet-failed-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let err = mortar_scenes::pellet::run(&scene, &dir, false).unwrap_err();
    eprintln!("failed as asked: {err}");
    assert!(
        !dir.exists(),
        "{:?}",
        std::fs::read_dir(&dir).map(|d| d.count())
    );
}
