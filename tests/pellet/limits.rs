//! The coupled pellet says when a run leaves its models' ranges (named warnings, status
//! "warnings") and where a failed solve was left (its step, time, Newton's reason and the
//! block of equations with the largest residual).

use mortar_scenes::pellet::limits::{LIMITS, UO2_MELTING_POINT};
use mortar_scenes::pellet::{run, AxialModel, PelletError, PelletScene};
use serde_json::Value;

fn out(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!(
        "mortar-pellet-limits-{}-{name}",
        std::process::id()
    ))
}

/// The names of a report's warnings.
fn names(rep: &Value) -> Vec<&str> {
    rep["warnings"]
        .as_array()
        .expect("a warnings array")
        .iter()
        .map(|w| w["name"].as_str().unwrap())
        .collect()
}

/// The default scene (20 kW/m, refinement 3, 30 s, free axial expansion) stays below
/// melting, inside the conductivity's range, with the cladding's von Mises stress and the
/// interface pressure below the cladding's yield; it leaves one range, which the run says: the
/// pellet's surface hoop stress passes UO2's fracture strength from about 12 kW/m (422 MPa at
/// full power: real pellets crack, this elastic one does not). In plane strain the cladding's von Mises stress, mostly the axial
/// stress of its ends held at the reference temperature, passes the yield stress too (148 MPa
/// at t = 0, at most 154 MPa, against 145 MPa). Regression: the stress the limits read must
/// hold generalized plane strain's axial strain (without it the pellet's hoop stress came out
/// compressive and the cracking went unreported).
#[test]
fn the_default_scene_names_the_ranges_it_leaves() {
    let dir = out("default");
    let rep = run(&PelletScene::default(), &dir, false).unwrap();
    assert_eq!(names(&rep), ["pellet_cracking"]);
    assert_eq!(rep["status"], "warnings");
    let mut plane = PelletScene::default();
    plane.model.axial = Some(AxialModel::PlaneStrain);
    let rep_plane = run(&plane, &dir, false).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(
        names(&rep_plane),
        ["cladding_beyond_elastic", "pellet_cracking"]
    );
    for w in rep["warnings"].as_array().unwrap() {
        let (value, bound) = (w["value"].as_f64().unwrap(), w["bound"].as_f64().unwrap());
        assert!(value > bound, "{w}");
        for key in ["what", "source", "unit", "quantity"] {
            assert!(w[key].as_str().is_some_and(|s| !s.is_empty()), "{key}: {w}");
        }
        assert!(w["when"]["first"]["time"].as_f64().is_some(), "{w}");
        assert!(w["where"]["radius"].as_f64().is_some(), "{w}");
    }
    let cracking = &rep["warnings"][0];
    assert_eq!(cracking["where"]["body"], "pellet");
    // At the pellet's surface (the hoop stress's peak), first during the ramp.
    let r = cracking["where"]["radius"].as_f64().unwrap();
    assert!((r - 4.1e-3).abs() < 1e-6, "{r}");
    let first = cracking["when"]["first"]["time"].as_f64().unwrap();
    assert!(first > 0.0 && first < 10.0, "{first}");
    // Below the melting point with a margin.
    let t0 = rep["steady"]["center_temperature"].as_f64().unwrap();
    assert!(t0 < 0.5 * UO2_MELTING_POINT, "{t0}");
}

/// In r-z a warning's radius is the node's `x` (its distance from the axis), not its
/// distance from the origin of the section. Regression: the radius was `|(x, y)|`, which
/// put the cracking of the r-z segment's pellet surface outside the pellet.
#[test]
fn an_rz_warning_gives_the_distance_from_the_axis() {
    let dir = out("rz");
    // The dished pellet: its tension peaks away from the mid-plane.
    let mut s = PelletScene::default();
    s.model.geometry = mortar_scenes::pellet::Geometry::Axisymmetric;
    s.mesh.file = Some(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/pellet_rz.msh"),
    );
    let rep = run(&s, &dir, false).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let cracking = rep["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|w| w["name"] == "pellet_cracking")
        .expect("the r-z pellet cracks as the cross-section's does");
    assert!(
        cracking["where"]["position"][1].as_f64().unwrap() > 0.0,
        "{cracking}"
    );
    let r = cracking["where"]["radius"].as_f64().unwrap();
    let x = cracking["where"]["position"][0].as_f64().unwrap();
    assert_eq!(r, x, "{cracking}");
    assert!(r <= 4.1e-3 * (1.0 + 1e-12), "{r}");
}

/// At 500 kW/m (a short run: refinement 1, one step), every range is left, fuel_melting
/// first among them, each once, with the status "warnings".
#[test]
fn a_high_power_scene_melts_the_fuel() {
    let mut s = PelletScene::default();
    s.power.linear_power = 500e3;
    s.power.ramp_time = 1.0;
    s.time.end = 1.0;
    s.time.snapshots = 1;
    s.mesh.refinement = 1;
    let dir = out("high");
    let rep = run(&s, &dir, false).unwrap();
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(report["status"], "warnings");
    assert_eq!(rep["status"], "warnings");
    let found = names(&rep);
    for limit in LIMITS {
        assert_eq!(
            found.iter().filter(|&&n| n == limit.name).count(),
            1,
            "{} in {found:?}",
            limit.name
        );
    }
    let melting = rep["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|w| w["name"] == "fuel_melting")
        .unwrap();
    assert_eq!(melting["bound"].as_f64(), Some(UO2_MELTING_POINT));
    assert!(melting["value"].as_f64().unwrap() > UO2_MELTING_POINT);
    assert_eq!(melting["where"]["body"], "pellet");
    assert!(melting["source"].as_str().unwrap().contains("Fink"));
}

/// At 1e12 W/m the first time step cannot be solved, even halved: the error names the step,
/// its time, Newton's reason and the block of equations holding the largest residual (the
/// heat balance), and report.json says the same.
#[test]
fn a_failed_solve_names_its_step_time_and_block() {
    let mut s = PelletScene::default();
    s.power.linear_power = 1e12;
    s.mesh.refinement = 1;
    let dir = out("failed");
    let e = run(&s, &dir, false).unwrap_err();
    let text = e.to_string();
    match &e {
        PelletError::SolveFailed {
            step, time, block, ..
        } => {
            assert_eq!(*step, Some(1));
            assert!((time - 0.0625).abs() < 1e-12, "{time}");
            assert_eq!(*block, Some("heat"));
        }
        other => panic!("expected a located failure, got {other}"),
    }
    for needle in [
        "time step 1 of 30",
        "t = 0.0625 s",
        "LineSearch",
        "heat equations",
    ] {
        assert!(text.contains(needle), "no {needle:?} in {text}");
    }
    let rep: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(rep["status"], "failed");
    let f = &rep["failure"];
    assert_eq!(f["step"], 1);
    assert_eq!(f["reason"], "LineSearch");
    assert_eq!(f["block"], "heat");
    let blocks = f["blocks"].as_object().unwrap();
    assert_eq!(blocks.len(), 6);
    let heat = blocks["heat"].as_f64().unwrap();
    assert!(blocks.values().all(|v| v.as_f64().unwrap() <= heat));
}
