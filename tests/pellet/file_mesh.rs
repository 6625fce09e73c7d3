//! The pellet scene from a user's Gmsh file (`[mesh] file`): an r-z section whose parts are
//! named by physical groups (the files are made by `examples/scenes/make_pellet_rz.py`).

use std::path::PathBuf;

use mortar::physics::elastic::recover_stress_with_axial_strain;
use mortar::physics::laws::ContactComplementarity;
use mortar::physics::nonlinear::NewtonOptions;
use mortar::physics::thermomech::{ThermoMechSolver, ThermoMechSolverState};
use mortar::scenes::pellet::file_mesh::FileGeometry;
use mortar::scenes::pellet::{coupled_problem, run, Geometry, PelletError, PelletScene};
use serde_json::Value;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The off-centre pellet of `examples/scenes/pellet_2d.msh`.
fn eccentric() -> PathBuf {
    root().join("examples/scenes/pellet_2d.msh")
}

/// The dished and chamfered pellet of `examples/scenes/pellet_rz.msh`.
fn dished() -> PathBuf {
    root().join("examples/scenes/pellet_rz.msh")
}

fn file_scene(path: PathBuf) -> PelletScene {
    let mut s = PelletScene::default();
    s.model.geometry = Geometry::Axisymmetric;
    s.mesh.file = Some(path);
    s
}

fn series(rep: &Value, key: &str) -> Vec<f64> {
    rep["history"][key]
        .as_array()
        .unwrap_or_else(|| panic!("history.{key}"))
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

fn out(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("mortar-pellet-file-{}-{name}", std::process::id()))
}

/// What the scene takes from the file, against the dimensions the script gives Gmsh (source:
/// closed forms): radii 4.1, 4.12 and 4.75 mm and height 4.9 mm exactly (nodes of the
/// geometry); the revolved volume of the dish (a spherical cap, `pi h (3 R^2 + h^2) / 6`)
/// and of the chamfer (a triangle at the centroid radius `a - w / 3`, Pappus), 4.904e-9 m^3,
/// to the mesh's chords of the dish's arc (measured 0.05 %); the land `pi (3.6^2 - 2.9^2)
/// mm^2` exactly.
#[test]
fn the_file_gives_the_radii_volumes_and_land() {
    let f = FileGeometry::read(&dished(), true).unwrap();
    assert_eq!(
        [f.pellet_radius, f.inner_radius, f.outer_radius, f.height],
        [4.1e-3, 4.12e-3, 4.75e-3, 4.9e-3]
    );
    let pi = std::f64::consts::PI;
    let (rd, h) = (2.9e-3, 0.3e-3);
    let (a, w, hc) = (4.1e-3, 0.5e-3, 0.15e-3);
    let voids = pi * h * (3.0 * rd * rd + h * h) / 6.0 + 2.0 * pi * (a - w / 3.0) * 0.5 * w * hc;
    let err = (f.end_voids() - voids).abs() / voids;
    eprintln!(
        "end voids {:.6e} m^3 against {voids:.6e}: {err:.2e}",
        f.end_voids()
    );
    assert!(err < 2e-3, "{err}");
    let land = pi * (3.6e-3f64.powi(2) - 2.9e-3f64.powi(2));
    assert!(
        (f.land_area - land).abs() < 1e-12 * land,
        "{} {land}",
        f.land_area
    );
}

/// Gas pressure alone (no power, the whole rod at the reference temperature, no coolant
/// pressure, the gap open under the exact contact law) leaves the dished pellet in uniform
/// hydrostatic compression `sigma = -P_o I` (source: a body under a uniform pressure over
/// its whole surface; linear elements hold the uniform strain exactly): the gas presses on
/// the lateral surface, the dish and the chamfer, the next pellet bears on the land with
/// `-P_o A_land`, so the end's balance holds only if the land's area and the wetted surfaces
/// are taken right. Measured: 3.6e-14 of P_o (taking the whole end, `pi a^2`, for the land
/// instead: 3.5 P_o, a stress concentration at the land).
#[test]
fn gas_pressure_alone_leaves_the_dished_pellet_hydrostatic() {
    let mut s = file_scene(dished());
    gas_alone(&mut s);
    let largest = hydrostatic_deviation(&s);
    eprintln!("dished pellet under gas alone: largest deviation from -P I {largest:.2e} of P");
    assert!(
        largest < crate::claims::claim("pellet.file_hydrostatic").bound,
        "{largest}"
    );
}

/// As [`gas_pressure_alone_leaves_the_dished_pellet_hydrostatic`], the off-centre pellet of
/// the 2D cross-section in generalized plane strain: `sigma_zz = -P_o` too, from the axial
/// force `-P_o A_pellet` over the file's pellet area. Measured: 3.6e-14 of P_o.
#[test]
fn gas_pressure_alone_leaves_the_off_centre_pellet_hydrostatic() {
    let mut s = file_scene(eccentric());
    s.model.geometry = Geometry::Plane;
    gas_alone(&mut s);
    let largest = hydrostatic_deviation(&s);
    eprintln!("off-centre pellet under gas alone: largest deviation from -P I {largest:.2e} of P");
    assert!(
        largest < crate::claims::claim("pellet.file_hydrostatic").bound,
        "{largest}"
    );
}

/// No power, the whole rod at the reference temperature, no coolant pressure, 4 MPa of gas.
fn gas_alone(s: &mut PelletScene) {
    s.power.linear_power = 0.0;
    s.cladding.coolant_pressure = 0.0;
    s.cladding.outer_temperature = s.model.reference_temperature;
    s.plenum.fill_temperature = s.model.reference_temperature;
    s.plenum.fill_pressure = 4e6;
}

/// The largest deviation of the pellet's stress from `-P_o I` over `P_o` at the steady
/// state of `s` (the exact contact law: the gap stays open).
fn hydrostatic_deviation(s: &PelletScene) -> f64 {
    let p = coupled_problem(s, ContactComplementarity::try_new(1e14).unwrap()).unwrap();
    let bodies = p.heat().bodies();
    let t = s.cladding.outer_temperature;
    let t0 = vec![t; bodies[0].mesh.node_count()];
    let t1 = vec![t; bodies[1].mesh.node_count()];
    let mut x = p.state([&t0, &t1]);
    let mut solver = ThermoMechSolverState::new(ThermoMechSolver::Newton);
    p.solve(&mut x, 0.0, None, &mut solver, &NewtonOptions::default())
        .unwrap();
    let f = p.fields(&x);
    let gas = f.gas_pressure;
    assert!((gas - 4e6).abs() < 0.05 * 4e6, "{gas}");
    let elastic = &p.elastic_bodies()[0];
    let body = elastic
        .clone()
        .with_temperature(f.temperature[0].to_vec())
        .unwrap();
    // In 2D the axial strain of generalized plane strain; in r-z the top's displacement is
    // in the field already.
    let axial = if s.model.geometry == Geometry::Axisymmetric {
        0.0
    } else {
        f.axial_strain[0].expect("generalized plane strain")
    };
    let stress =
        recover_stress_with_axial_strain(&body, &f.displacement(0), axial, &p.options().elastic)
            .unwrap();
    stress
        .cells
        .iter()
        .flat_map(|c| {
            c.iter()
                .enumerate()
                .map(|(k, v)| if k < 3 { v + gas } else { *v })
        })
        .fold(0.0f64, |a, v| a.max(v.abs()))
        / gas
}

/// The 2D cross-section read from a file of the centred pellet (`make_pellet_2d.py
/// --centred`) against the generated cross-section, every step (source: both discretise the
/// same problem). The file's gap is its meshes' (a chord of 0.1 mm lies 0.3 um inside the
/// 4.1 mm circle), the generated section's the design gap; the difference is the chords':
/// measured, largest over the steps, centre 7.6e-4, gap 3.3e-2 (0.14 um of the final 4.2),
/// P_c 7.2e-2 (the exponential law's pressure follows the gap steeply), P_o 1.8e-3. The
/// bounds are regression guards 1.5x above them.
#[test]
fn a_file_of_the_centred_cross_section_runs_as_the_generated_one() {
    let mut file = file_scene(root().join("tests/meshes/pellet_2d_centred.msh"));
    file.model.geometry = Geometry::Plane;
    let generated = PelletScene::default();
    let dir = out("centred");
    let a = run(&file, &dir, false).unwrap();
    let b = run(&generated, &dir, false).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    for (key, floor, bound) in [
        ("center_temperature", 0.0, 1.2e-3),
        ("gap", 5e-6, 5e-2),
        ("interface_pressure", 0.0, 0.11),
        ("plenum_pressure", 0.0, 2.8e-3),
    ] {
        let (x, y) = (series(&a, key), series(&b, key));
        let worst = x
            .iter()
            .zip(&y)
            .map(|(u, v)| (u - v).abs() / v.abs().max(floor))
            .fold(0.0f64, f64::max);
        eprintln!("centred 2D file against the generated cross-section, {key}: {worst:.2e}");
        assert!(worst < bound, "{key}: {worst}");
    }
}

/// The scene read from a file of the plain segment (no dish, no chamfer:
/// `make_pellet_rz.py --plain`) and the generated r-z section of the same height agree at
/// every step (source: both discretise the same problem, which the generated section solves
/// to 0.06-0.21 % of the independent radial model: `coupled.rs`). The meshes differ (0.2 mm
/// quadrangles from Gmsh against the generated 24 x 2 and 6 x 3 cells), so the bound is
/// the discretisation's: measured, largest over the steps, centre 9.2e-5, gap 6.1e-6, P_c
/// 1.8e-5, P_o 8.2e-7 (of each value; the gap relative to the larger of itself and 5 um).
#[test]
fn a_file_of_the_plain_segment_runs_as_the_generated_section() {
    let plain = root().join("tests/meshes/pellet_rz_plain.msh");
    let file = file_scene(plain);
    let mut generated = PelletScene::default();
    generated.model.geometry = Geometry::Axisymmetric;
    generated.model.segment_height = 4.9e-3;
    let dir = out("plain");
    let a = run(&file, &dir, false).unwrap();
    let b = run(&generated, &dir, false).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(a["mesh"]["file"]["height"].as_f64(), Some(4.9e-3));
    let bound = crate::claims::claim("pellet.file_plain").bound;
    for (key, floor) in [
        ("center_temperature", 0.0),
        ("gap", 5e-6),
        ("interface_pressure", 0.0),
        ("plenum_pressure", 0.0),
    ] {
        let (x, y) = (series(&a, key), series(&b, key));
        assert_eq!(x.len(), y.len(), "{key}");
        let worst = x
            .iter()
            .zip(&y)
            .map(|(u, v)| (u - v).abs() / v.abs().max(floor))
            .fold(0.0f64, f64::max);
        eprintln!("plain file against the generated r-z section, {key}: {worst:.2e}");
        assert!(worst < bound, "{key}: {worst}");
    }
}

/// The off-centre pellet (`examples/scenes/pellet_2d.toml`) engages contact on its near side
/// first: the time reported is when the smallest gap reaches the pressure law's onset, between
/// the two steps that bracket it, well before the mean gap does. Regression: the time was the
/// mean gap's (9.58 s, as centred), and a pellet touching from the initial state got a
/// negative time from the interpolation.
#[test]
fn an_off_centre_pellet_engages_contact_on_its_near_side_first() {
    let mut s = file_scene(eccentric());
    s.model.geometry = Geometry::Plane;
    s.time.end = 6.0;
    let dir = out("eccentric");
    let rep = run(&s, &dir, false).unwrap();
    // With the coolant at 900 K the pellet outgrows the cladding by 10 um before any power:
    // the near side touches from the initial state.
    let mut touching = s.clone();
    touching.cladding.outer_temperature = 900.0;
    touching.time.end = 1.0;
    let rep_touching = run(&touching, &dir, false).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let xi = 5e-6;
    let (time, min_gap, gap) = (
        series(&rep, "time"),
        series(&rep, "min_gap"),
        series(&rep, "gap"),
    );
    let closure = rep["gap_closure_time"].as_f64().unwrap();
    let first = min_gap.iter().position(|&g| g <= xi).unwrap();
    assert!(
        first > 0 && time[first - 1] <= closure && closure <= time[first],
        "{closure}"
    );
    // The mean gap is still well above the onset then (it reaches it after 9 s).
    assert!(gap[first] > xi + 1e-6, "{}", gap[first]);
    let t0 = rep_touching["gap_closure_time"].as_f64().unwrap();
    assert!(
        series(&rep_touching, "min_gap")[0] <= xi && t0 == 0.0,
        "{t0}"
    );
}

/// A mesh file is the 2D or r-z section of the thermomechanical scene: in 3D, or without
/// mechanics, it is refused by name; a missing group names the file.
#[test]
fn a_mesh_file_is_refused_where_it_does_not_apply() {
    let mut s = file_scene(dished());
    s.model.geometry = Geometry::ThreeD;
    let e = s.check().unwrap_err();
    assert!(
        matches!(e, PelletError::Invalid(_)) && e.to_string().contains("mesh.file"),
        "{e}"
    );
    let s = file_scene(root().join("tests/meshes/pellet_gap_2d.msh"));
    let dir = out("missing");
    let e = run(&s, &dir, false).unwrap_err();
    let _ = std::fs::remove_dir_all(&dir);
    let text = e.to_string();
    assert!(text.contains("pellet_gap_2d.msh"), "{text}");
}

/// The scene file's relative mesh path is the scene file's folder's.
#[test]
fn a_scene_file_reads_its_mesh_beside_it() {
    let text = std::fs::read_to_string(root().join("examples/scenes/pellet_rz.toml")).unwrap();
    let s = PelletScene::from_toml_in(&text, &root().join("examples/scenes")).unwrap();
    assert_eq!(s.mesh.file.as_deref(), Some(dished().as_path()));
}
