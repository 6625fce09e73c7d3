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
    let f = FileGeometry::read(&dished()).unwrap();
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
    s.power.linear_power = 0.0;
    s.cladding.coolant_pressure = 0.0;
    s.cladding.outer_temperature = s.model.reference_temperature;
    s.plenum.fill_temperature = s.model.reference_temperature;
    s.plenum.fill_pressure = 4e6;
    let p = coupled_problem(&s, ContactComplementarity::try_new(1e14).unwrap()).unwrap();
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
    let stress =
        recover_stress_with_axial_strain(&body, &f.displacement(0), 0.0, &p.options().elastic)
            .unwrap();
    let largest = stress
        .cells
        .iter()
        .flat_map(|c| {
            c.iter()
                .enumerate()
                .map(|(k, v)| if k < 3 { v + gas } else { *v })
        })
        .fold(0.0f64, |a, v| a.max(v.abs()));
    eprintln!(
        "dished pellet under {gas:.4e} Pa of gas alone: largest deviation from -P I {:.2e} of P",
        largest / gas
    );
    assert!(
        largest < crate::claims::claim("pellet.file_hydrostatic").bound * gas,
        "{largest}"
    );
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

/// A mesh file is the r-z section of the thermomechanical scene: in 2D, or without
/// mechanics, it is refused by name; a missing group names the file, the group and the
/// groups the file has.
#[test]
fn a_mesh_file_is_refused_where_it_does_not_apply() {
    let mut s = file_scene(dished());
    s.model.geometry = Geometry::Plane;
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
