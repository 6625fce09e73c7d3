//! The pellet scene from a user's Gmsh file (`[mesh] file`): an r-z section whose parts are
//! named by physical groups (the files are made by `examples/scenes/make_pellet_rz.py`).

use std::path::PathBuf;

use mortar::physics::elastic::recover_stress_with_axial_strain;
use mortar::physics::laws::{
    ConstraintLaw, ContactComplementarity, ExponentialContact, MechanicalGapConductance,
};
use mortar::physics::nonlinear::NewtonOptions;
use mortar::physics::thermomech::{GapThermoMechanics, ThermoMechSolver, ThermoMechSolverState};
use mortar_scenes::pellet::file_mesh::FileGeometry;
use mortar_scenes::pellet::{coupled_problem, run, Geometry, PelletError, PelletScene};
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
    hydrostatic_state(s, ContactComplementarity::try_new(1e14).unwrap()).0
}

/// [`hydrostatic_deviation`] under the contact law `law`, with the problem and the state.
fn hydrostatic_state<ML: ConstraintLaw + Clone>(
    s: &PelletScene,
    law: ML,
) -> (
    f64,
    GapThermoMechanics<MechanicalGapConductance, ML>,
    Vec<f64>,
) {
    let p = coupled_problem(s, law).unwrap();
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
    let largest = stress
        .cells
        .iter()
        .flat_map(|c| {
            c.iter()
                .enumerate()
                .map(|(k, v)| if k < 3 { v + gas } else { *v })
        })
        .fold(0.0f64, |a, v| a.max(v.abs()))
        / gas;
    (largest, p, x)
}

/// The stack of three dished pellets of `examples/scenes/pellet_stack.msh`.
fn stack() -> PathBuf {
    root().join("examples/scenes/pellet_stack.msh")
}

/// Gas pressure alone (as [`gas_pressure_alone_leaves_the_dished_pellet_hydrostatic`]) on
/// the stack of three pellets whose lands bear on each other through mortar contact under
/// the exponential law: every pellet is in uniform compression `sigma = -P_o I` (source: a
/// body under a uniform pressure over its whole surface), which holds only if the lands
/// carry exactly `P_o`, so the law's gap there is `xi - sqrt(ln 2 / S_NE)` (`P_o (e^{S (xi -
/// g)^2} - 1) = P_o`) at every land node. Measured: stress 4.7e-12 of P_o, land pressure
/// 8.9e-12 of P_o, land gap 9.0e-12 of it: the law's stiffness at the lands, 1.4e13 Pa/m
/// (`2 S_NE (xi - g) 2 P_o`), turns the displacement's last digits at Newton's tolerance into
/// the pressure's, hence a bound above the single pellet's (whose open gap has no such law).
#[test]
fn gas_pressure_alone_leaves_the_stack_hydrostatic() {
    let mut s = file_scene(stack());
    gas_alone(&mut s);
    let law = ExponentialContact::try_new(1e12, 5e-6).unwrap();
    let (largest, p, x) = hydrostatic_state(&s, law);
    let gas = p.fields(&x).gas_pressure;
    assert_eq!(p.contact_pairs(), 1);
    let want = 5e-6 - (2f64.ln() / 1e12).sqrt();
    let gap = p
        .pair_gaps(0, &x)
        .iter()
        .fold(0.0f64, |m, g| m.max((g - want).abs() / want));
    let pressure = p
        .pair_contact_pressures(0, &x)
        .iter()
        .fold(0.0f64, |m, q| m.max((q - gas).abs() / gas));
    eprintln!(
        "stack under gas alone: stress {largest:.2e}, land pressure {pressure:.2e} of P_o, land \
         gap {gap:.2e} of {want:e} m ({} land nodes)",
        p.pair_gaps(0, &x).len()
    );
    let bound = crate::claims::claim("pellet.stack_hydrostatic").bound;
    assert!(
        largest < bound && pressure < bound && gap < bound,
        "{largest} {pressure} {gap}"
    );
}

/// The stack of three pellets (`pellet_stack.toml`) against the one dished pellet of the
/// same geometry whose land is kept plane (`pellet_rz.toml`), every step: both stand for a
/// long stack of identical pellets (source: the same problem, the neighbour bearing on the
/// land through mortar contact in one, as a plane end in the other). Measured, largest over
/// the steps: centre 2.6e-4, mean gap 4.9e-3 (4.171 against 4.154 um at 30 s), plenum
/// 8.9e-4; the bounds are regression guards 1.5x above them. The contact engages at 7.90 s
/// against 8.10 s (the stack's lands deform, and its ends flare out more).
#[test]
fn the_stack_runs_as_one_pellet_of_a_long_stack() {
    let text = |f: &str| std::fs::read_to_string(root().join("examples/scenes").join(f)).unwrap();
    let scene =
        |f: &str| PelletScene::from_toml_in(&text(f), &root().join("examples/scenes")).unwrap();
    let dir = out("stack");
    let a = run(&scene("pellet_stack.toml"), &dir, false).unwrap();
    let b = run(&scene("pellet_rz.toml"), &dir, false).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(a["status"], b["status"]);
    assert!(series(&a, "land_min_gap")
        .iter()
        .all(|&g| g > 0.0 && g < 5e-6));
    for (key, floor, bound) in [
        ("center_temperature", 0.0, 4e-4),
        ("gap", 5e-6, 7.5e-3),
        ("plenum_pressure", 0.0, 1.5e-3),
    ] {
        let (x, y) = (series(&a, key), series(&b, key));
        let worst = x
            .iter()
            .zip(&y)
            .map(|(u, v)| (u - v).abs() / v.abs().max(floor))
            .fold(0.0f64, f64::max);
        eprintln!("stack against one pellet of a long stack, {key}: {worst:.2e}");
        assert!(worst < bound, "{key}: {worst}");
    }
}

/// The stack's Jacobian, its lands' contact pair included, against central finite
/// differences of the residual (source: the definition of the derivative), at a state with
/// a temperature field, the pellets stretched across and along the axis, the lands inside the
/// exponential law's range and every flux and pressure non-zero; within the coupled
/// Jacobian's bound (measured 3.8e-8).
#[test]
fn the_stack_jacobian_matches_finite_differences() {
    let s = file_scene(stack());
    let p = coupled_problem(&s, ExponentialContact::try_new(1e12, 5e-6).unwrap()).unwrap();
    let bodies = p.heat().bodies();
    let temperature = |b: usize, hot: f64| -> Vec<f64> {
        let x = bodies[b].mesh.coords();
        x.iter().map(|x| hot - 5e4 * x.x - 2e3 * x.y).collect()
    };
    let mut x = p.state([&temperature(0, 900.0), &temperature(1, 700.0)]);
    let (n0, n1) = (bodies[0].mesh.node_count(), bodies[1].mesh.node_count());
    for (i, c) in bodies[0].mesh.coords().iter().enumerate() {
        let o = n0 + n1 + 2 * i;
        x[o] = 2e3 * c.x * (1.0 + 0.01 * (i % 3) as f64);
        x[o + 1] = 1e2 * c.y;
    }
    // The fluxes and pressures of the gap and of the lands, then the gas and axial unknowns.
    let first = n0 + n1 + 2 * (n0 + n1);
    let n = x.len();
    for (k, v) in x[first..n - 3].iter_mut().enumerate() {
        *v = 1.0 + 0.01 * (k % 7) as f64;
    }
    x[n - 2] = 3.0;
    x[n - 1] = 1.0;
    assert!(p.pair_gaps(0, &x).iter().all(|&g| g > 0.0 && g < 5e-6));
    let t = 5.0;
    let jac = p.steady_jacobian(&x, t).unwrap();
    let err = super::coupled::jacobian_error(&jac, |y| p.steady_residual(y, t).unwrap(), &x, 3);
    eprintln!("stack: Jacobian against finite differences {err:.2e}");
    assert!(
        err < crate::claims::claim("pellet.jacobian").bound,
        "{err:e}"
    );
}

/// A stack's land groups come in pairs and in r-z only: a file with one of them, or a 2D
/// cross-section with both, is refused naming the groups; a stack under the exact contact
/// law is refused before anything is written (its open lands would hold nothing).
#[test]
fn a_stack_file_is_checked() {
    let text = std::fs::read_to_string(stack()).unwrap();
    let dir = out("stack-groups");
    std::fs::create_dir_all(&dir).unwrap();
    let one = dir.join("one_land_group.msh");
    std::fs::write(&one, text.replace("\"pellet_lands_upper\"", "\"other\"")).unwrap();
    let err = FileGeometry::read(&one, true).unwrap_err().to_string();
    assert!(
        err.contains("pellet_lands_lower") && err.contains("pairs"),
        "{err}"
    );
    let err = FileGeometry::read(&stack(), false).unwrap_err().to_string();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(err.contains("r-z"), "{err}");
    // Under the exact law the as-built open lands would leave the upper pellets free.
    let mut s = file_scene(stack());
    s.contact.law = mortar_scenes::pellet::ContactLawName::Exact;
    let err = run(&s, &out("stack-exact"), false).unwrap_err();
    assert!(
        matches!(err, PelletError::Invalid(_)) && err.to_string().contains("exponential"),
        "{err}"
    );
    assert!(
        !out("stack-exact").exists(),
        "a refused scene writes nothing"
    );
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
