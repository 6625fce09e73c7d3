//! `mortar run` with `kind = "contact"`: two stacked elastic blocks read from Gmsh files
//! (non-matching meshes), pressed by `sigma` on the top, carry it through the interface as a
//! uniform contact pressure `sigma` (the patch test); the outputs; the refusals.

use std::path::Path;

use mortar::core::mesh::{BoundaryFace, VolumeMesh};
use mortar::generate::{rectangle_mesh, CellShape};
use mortar::io::{msh41_volume_bytes, MshFormat};
use mortar_scenes::file::contact::ContactSpec;
use mortar_scenes::file::{FileScene, FileSystem};
use serde_json::Value;

use crate::common::{mortar, TempDir};

const SIGMA: f64 = 50e6;

/// A body's Gmsh file with face groups `NAME_bottom`, `NAME_top`, `NAME_left`, `NAME_rest`.
fn body_file(mesh: &VolumeMesh, name: &str, y0: f64, y1: f64) -> Vec<u8> {
    let faces = mesh.boundary_faces().unwrap();
    let near = |a: f64, b: f64| (a - b).abs() < 1e-9;
    let pick = |p: &dyn Fn(&BoundaryFace) -> bool| -> Vec<BoundaryFace> {
        faces.iter().filter(|f| p(f)).cloned().collect()
    };
    let bottom = pick(&|f| near(f.centroid.y, y0));
    let top = pick(&|f| near(f.centroid.y, y1));
    let left = pick(&|f| near(f.centroid.x, 0.0));
    let rest =
        pick(&|f| !near(f.centroid.y, y0) && !near(f.centroid.y, y1) && !near(f.centroid.x, 0.0));
    msh41_volume_bytes(
        (mesh, name),
        &[
            (&bottom, &format!("{name}_bottom")),
            (&top, &format!("{name}_top")),
            (&left, &format!("{name}_left")),
            (&rest, &format!("{name}_rest")),
        ],
        MshFormat::Ascii,
    )
    .unwrap()
}

const SCENE: &str = r#"kind = "contact"
title = "stacked blocks"

[bodies.upper]
mesh = "upper.msh"
group = "upper"
youngs_modulus = 210e9
poisson_ratio = 0.3
dirichlet = [{ group = "upper_left", component = "x", value = 0.0 }]
traction = [{ group = "upper_top", value = [0.0, -50e6] }]

[bodies.lower]
mesh = "lower.msh"
group = "lower"
youngs_modulus = 210e9
poisson_ratio = 0.3
dirichlet = [
    { group = "lower_bottom", component = "y", value = 0.0 },
    { group = "lower_left", component = "x", value = 0.0 },
]

[contact]
slave = { body = "upper", group = "upper_bottom" }
master = { body = "lower", group = "lower_top" }
law = "exact"
multipliers = "dual"
integration = "segment"

[solve]
load_steps = 1
"#;

/// Writes the meshes and the scene into `dir`; returns the scene file.
fn setup(dir: &TempDir) -> String {
    let lower = rectangle_mesh([0.0, 0.0], [1.0, 1.0], [4, 4], CellShape::Tensor, 1).unwrap();
    let upper = rectangle_mesh([0.0, 1.0], [1.0, 2.0], [5, 5], CellShape::Simplex, 1000).unwrap();
    dir.file("lower.msh", body_file(&lower, "lower", 0.0, 1.0));
    dir.file("upper.msh", body_file(&upper, "upper", 1.0, 2.0));
    dir.file("scene.toml", SCENE)
}

/// The named `DataArray`'s values in a VTU text.
fn array(vtu: &str, name: &str) -> Vec<f64> {
    let head = format!("Name=\"{name}\"");
    let rest = vtu
        .split(&head)
        .nth(1)
        .unwrap_or_else(|| panic!("{name} in VTU"));
    let body = rest.split_once('>').unwrap().1;
    body.split("</DataArray>")
        .next()
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect()
}

#[test]
fn stacked_blocks_carry_the_uniform_pressure() {
    let dir = TempDir::new("contact-scene");
    let scene = setup(&dir);
    for (multipliers, formulation) in [("dual", "pressures condensed"), ("standard", "saddle")] {
        let text = SCENE.replace("\"dual\"", &format!("\"{multipliers}\""));
        let path = Path::new(&scene);
        let spec = ContactSpec::parse(&text, path).unwrap();
        let solved = spec
            .solve(path, path.parent().unwrap(), &FileSystem)
            .unwrap();
        let worst = solved
            .solution
            .pressure
            .iter()
            .map(|p| (p - SIGMA).abs() / SIGMA)
            .fold(0.0f64, f64::max);
        assert!(worst < 1e-8, "{multipliers}: pressure off by {worst:e}");
        assert!(
            solved.solution.formulation.starts_with(formulation),
            "{}",
            solved.solution.formulation
        );
        // The force: sigma times the width (per unit thickness).
        assert!((solved.solution.force - SIGMA).abs() < 1e-8 * SIGMA);
    }

    let out = dir.join("out");
    let o = mortar(&["run", &scene, "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let upper = std::fs::read_to_string(out.join("upper.vtu")).unwrap();
    let lower = std::fs::read_to_string(out.join("lower.vtu")).unwrap();
    for vtu in [&upper, &lower] {
        assert!(vtu.contains("Name=\"displacement\" NumberOfComponents=\"3\""));
        for name in ["stress_xx", "stress_yy", "stress_xy", "von_mises"] {
            assert!(vtu.contains(&format!("Name=\"{name}\"")), "{name}");
        }
        // The uniaxial stress: sigma_yy = -sigma everywhere.
        let syy = array(vtu, "stress_yy");
        let worst = syy
            .iter()
            .map(|s| (s + SIGMA).abs() / SIGMA)
            .fold(0.0f64, f64::max);
        assert!(worst < 1e-6, "sigma_yy off by {worst:e}");
        let u = array(vtu, "displacement");
        assert_eq!(u.len() % 3, 0);
        assert!(u.chunks(3).all(|c| c[2] == 0.0), "2D: u_z = 0");
    }
    let interface = std::fs::read_to_string(out.join("interface.vtu")).unwrap();
    let p = array(&interface, "contact_pressure");
    assert_eq!(p.len(), 6, "6 slave interface nodes");
    assert!(p.iter().all(|p| (p - SIGMA).abs() < 1e-6 * SIGMA), "{p:?}");
    let gap = array(&interface, "gap");
    assert!(gap.iter().all(|g| g.abs() < 1e-12), "{gap:?}");
    let types = array(&interface, "types");
    assert_eq!(types, vec![3.0; 5], "5 VTK_LINE cells");

    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["kind"], "contact");
    assert_eq!(report["dimension"], 2);
    // Fully covered: the warnings are reported, and there are none.
    assert_eq!(report["warnings"].as_array().map(Vec::len), Some(0));
    assert!(report["formulation"]
        .as_str()
        .unwrap()
        .starts_with("pressures condensed out"));
    let step = &report["load_steps"][0];
    assert!(step["newton_steps"].as_u64().unwrap() >= 1);
    assert!(step["settled_at"].is_number() || step["settled_at"].is_null());
    assert!(!step["residuals"].as_array().unwrap().is_empty());
    assert_eq!(step["active"], 6);
    let f = report["contact_force"].as_f64().unwrap();
    assert!((f - SIGMA).abs() < 1e-8 * SIGMA, "{f}");
    for k in [
        "read",
        "coupling",
        "assembly",
        "contact_solve",
        "stress",
        "total",
    ] {
        assert!(report["seconds"][k].as_f64().unwrap() >= 0.0, "{k}");
    }
}

/// Runs the scene text `text` from `dir`; asserts failure, each needle in stderr, and
/// nothing written.
fn assert_fails(dir: &TempDir, name: &str, text: &str, needles: &[&str]) {
    let scene = dir.file(name, text);
    let out = dir.join(&format!("out-{name}"));
    let o = mortar(&["run", &scene, "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{name}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{name}: one line: {stderr}");
    for n in needles {
        assert!(stderr.contains(n), "{name}: {n:?} not in {stderr}");
    }
    assert!(!out.exists(), "{name}: nothing written");
}

#[test]
fn bad_contact_scenes_are_refused_naming_the_key() {
    let dir = TempDir::new("contact-scene-err");
    setup(&dir);
    let once = |old: &str, new: &str| SCENE.replacen(old, new, 1);
    assert_fails(
        &dir,
        "e.toml",
        &once("youngs_modulus = 210e9", "youngs_modulus = 0.0"),
        &["bodies.upper.youngs_modulus", "not positive"],
    );
    assert_fails(
        &dir,
        "nu.toml",
        &once("poisson_ratio = 0.3", "poisson_ratio = 0.5"),
        &["bodies.upper.poisson_ratio", "(-1, 0.5)"],
    );
    assert_fails(
        &dir,
        "group.toml",
        &once("group = \"upper_top\"", "group = \"roof\""),
        &["bodies.upper.traction[0]", "roof"],
    );
    assert_fails(
        &dir,
        "cells.toml",
        &once("group = \"lower\"", "group = \"floor\""),
        &["bodies.lower.group", "floor"],
    );
    assert_fails(
        &dir,
        "contact_group.toml",
        &once("group = \"lower_top\"", "group = \"lid\""),
        &["contact.master", "lid"],
    );
    assert_fails(
        &dir,
        "file.toml",
        &once("mesh = \"lower.msh\"", "mesh = \"nowhere.msh\""),
        &["bodies.lower.mesh", "nowhere.msh"],
    );
    assert_fails(
        &dir,
        "z.toml",
        &once("component = \"x\"", "component = \"z\""),
        &["bodies.upper.dirichlet[0].component", "2D"],
    );
    let bad = once("law = \"exact\"", "law = \"exact\"\nfriction = 0.3");
    let line = 1 + bad.lines().position(|l| l.starts_with("friction")).unwrap();
    assert_fails(
        &dir,
        "key.toml",
        &bad,
        &["unknown field `friction`", &format!("line {line}")],
    );
    assert_fails(
        &dir,
        "newton.toml",
        &once("load_steps = 1", "load_steps = 2\nmax_newton_steps = 3").replace(
            "law = \"exact\"",
            "law = \"exponential\"\nbase_pressure = 1e5\nstiffness = 6.2146e12\nonset = 0.0",
        ),
        &["load step 1 of 2", "Newton"],
    );
}

#[test]
fn builtin_hertz2d_matches_the_closed_form() {
    let dir = TempDir::new("contact-hertz");
    let out = dir.join("out");
    let o = mortar(&[
        "--json",
        "run",
        "--scene",
        "hertz2d",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: Value = serde_json::from_slice(&o.stdout).unwrap();
    for k in ["R", "E_star", "d"] {
        assert!(report["inputs"][k].as_f64().unwrap() > 0.0, "{k}");
    }
    assert!(report["P"].as_f64().unwrap() > 0.0);
    let (a, a_exact) = (
        report["computed"]["a"].as_f64().unwrap(),
        report["closed_form"]["a"].as_f64().unwrap(),
    );
    // The bracket of the last node in contact and the first open one holds the closed form's
    // half-width; the zero of p^2 extrapolated through the last two nodes in contact (exact
    // for the elliptical profile) is within 2 % of it, the bracket's midpoint within a cell.
    let bracket: Vec<f64> = report["computed"]["a_bracket"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(
        bracket[0] <= a_exact && a_exact <= bracket[1],
        "{bracket:?} {a_exact}"
    );
    let a2 = report["computed"]["a_squared"].as_f64().unwrap();
    assert!(
        (a2 - a_exact).abs() < 0.02 * a_exact,
        "a^2 fit {a2}, closed form {a_exact}"
    );
    assert!(
        (a - a_exact).abs() <= bracket[1] - bracket[0],
        "a = {a}, {a_exact}"
    );
    let (p0, p0_exact) = (
        report["computed"]["p0"].as_f64().unwrap(),
        report["closed_form"]["p0"].as_f64().unwrap(),
    );
    assert!(
        (p0 - p0_exact).abs() < 0.02 * p0_exact,
        "p0 = {p0}, {p0_exact}"
    );
    assert!(out.join("report.json").is_file());
}

/// The built-in contact scenes write what a user opens and copies (as `docs/scenes.md` says):
/// a VTU per body, `interface.vtu`, the scene file and its meshes. The scene file written
/// runs to the same interface pressures (to 1e-12 of the peak), and the closed-form figures
/// of the built-in (solved from those files) are those of the scene's in-memory run (the
/// library's `HertzScene::run` and `ShrinkFitScene::run`) to 1e-9: one scene, two ways in.
#[test]
fn builtin_contact_scenes_write_their_results_and_their_scene_file() {
    use mortar_scenes::file::HERTZ_ARC_CELLS;
    use mortar_scenes::hertz::HertzScene;
    use mortar_scenes::shrink_fit::ShrinkFitScene;
    let dir = TempDir::new("contact-builtin-files");
    for (name, bodies) in [
        ("hertz2d", ["cylinder", "block"]),
        ("shrink_fit", ["disc", "ring"]),
    ] {
        let out = dir.join(name);
        let o = mortar(&[
            "--json",
            "run",
            "--scene",
            name,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let report: Value = serde_json::from_slice(&o.stdout).unwrap();
        for body in bodies {
            for file in [format!("{body}.vtu"), format!("{body}.msh")] {
                assert!(out.join(&file).is_file(), "{name}: {file}");
            }
        }
        assert!(out.join("interface.vtu").is_file(), "{name}");
        assert_eq!(report["scene"]["kind"], "contact", "{name}");

        // The scene file written runs, to the same pressures.
        let again = dir.join(&format!("{name}-again"));
        let scene = out.join("scene.toml");
        let o = mortar(&[
            "run",
            scene.to_str().unwrap(),
            "--out",
            again.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let read = |d: &Path| {
            array(
                &std::fs::read_to_string(d.join("interface.vtu")).unwrap(),
                "contact_pressure",
            )
        };
        let (p, q) = (read(&out), read(&again));
        let peak = p.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        assert!(peak > 0.0 && p.len() == q.len(), "{name}");
        let worst = p
            .iter()
            .zip(&q)
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        assert!(
            worst <= crate::claims::claim("scenes.pressure").bound * peak,
            "{name}: pressures differ by {worst:e}"
        );

        // The built-in's figures are the in-memory run's.
        let (computed, in_memory) = match name {
            "hertz2d" => {
                let run = HertzScene::new(HERTZ_ARC_CELLS).run().unwrap();
                (report["computed"]["p0"].as_f64().unwrap(), run.peak)
            }
            _ => {
                let run = ShrinkFitScene::new(32, 32).run().unwrap();
                (report["computed"]["p_mean"].as_f64().unwrap(), run.mean)
            }
        };
        assert!(
            (computed - in_memory).abs()
                <= crate::claims::claim("scenes.closed_form").bound * in_memory,
            "{name}: {computed} from the scene file, {in_memory} in memory"
        );
    }
}

/// The built-in 3D Hertz scene (a sphere octant on a block, the default mesh of
/// `mortar_scenes::hertz::sphere`): report.json carries the inputs, and the closed form of
/// Johnson (1985, sec. 4.2) at the imposed approach `d` (`a = sqrt(R d)`,
/// `p0 = 2 E* a / (pi R)`) and at the computed load `P` beside the computed values: the peak
/// pressure within 3 % of both, the contact radius within one element of both, at most 10
/// Newton steps.
#[test]
fn builtin_hertz3d_matches_the_closed_form() {
    let dir = TempDir::new("contact-hertz3d");
    let out = dir.join("out");
    let o = mortar(&[
        "--json",
        "run",
        "--scene",
        "hertz3d",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(report["dimension"].as_u64(), Some(3));
    for k in ["R", "E_star", "d"] {
        assert!(report["inputs"][k].as_f64().unwrap() > 0.0, "{k}");
    }
    let (r, e, d) = (
        report["inputs"]["R"].as_f64().unwrap(),
        report["inputs"]["E_star"].as_f64().unwrap(),
        report["inputs"]["d"].as_f64().unwrap(),
    );
    let at_d = &report["closed_form"]["at_d"];
    let a_d = at_d["a"].as_f64().unwrap();
    assert!((a_d - (r * d).sqrt()).abs() < 1e-12 * a_d);
    let p0_d = at_d["p0"].as_f64().unwrap();
    assert!((p0_d - 2.0 * e * a_d / (std::f64::consts::PI * r)).abs() < 1e-9 * p0_d);
    let p = report["P"].as_f64().unwrap();
    assert!(p > 0.0);
    let a_p = report["closed_form"]["at_P"]["a"].as_f64().unwrap();
    assert!((a_p - (3.0 * p * r / (4.0 * e)).cbrt()).abs() < 1e-12 * a_p);
    let p0 = report["computed"]["p0"].as_f64().unwrap();
    let a = report["computed"]["a"].as_f64().unwrap();
    for closed in ["at_d", "at_P"] {
        let c = &report["closed_form"][closed];
        let (a_c, p0_c) = (c["a"].as_f64().unwrap(), c["p0"].as_f64().unwrap());
        assert!(
            (p0 - p0_c).abs() < 0.03 * p0_c,
            "{closed}: p0 = {p0}, {p0_c}"
        );
        let element = report["element_at_a"][closed].as_f64().unwrap();
        assert!(
            (a - a_c).abs() <= element,
            "{closed}: a = {a}, {a_c}, element {element}"
        );
    }
    for step in report["load_steps"].as_array().unwrap() {
        assert!(step["newton_steps"].as_u64().unwrap() <= 10, "{step}");
    }
    assert!(out.join("report.json").is_file());
}

/// Regression: the coupling's warnings reached neither the terminal nor (for scene files)
/// report.json. The built-in shrink fit (disc as slave) leaves two end faces covered in part
/// (the ring's end projects short of the disc's across the interference): the warning is
/// printed as `mortar: warning: ...` and kept in report.json.
#[test]
fn scene_warnings_are_printed_and_reported() {
    let dir = TempDir::new("contact-warnings");
    let out = dir.join("out");
    let o = mortar(&[
        "run",
        "--scene",
        "shrink_fit",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("mortar: warning: uncovered slave area"),
        "{stderr}"
    );
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let warnings = report["warnings"].as_array().unwrap();
    assert!(
        warnings
            .iter()
            .any(|w| w.as_str().unwrap().starts_with("uncovered slave area")),
        "{warnings:?}"
    );
}

/// Scene files name their contact law: `named_law = { name = ... }` with a
/// law of the registry runs as the built-in `law` key does (exact contact: the uniform
/// pressure to 1e-8); an unknown name is refused naming the key and the known laws; `law` and
/// `named_law` together are refused.
#[test]
fn contact_scenes_name_their_law() {
    let dir = TempDir::new("contact-named");
    let scene = setup(&dir);
    let path = Path::new(&scene);
    let named = SCENE.replace(
        "law = \"exact\"",
        "named_law = { name = \"contact_complementarity\", c = 1e12 }",
    );
    assert_ne!(named, SCENE);
    let spec = ContactSpec::parse(&named, path).unwrap();
    let solved = spec
        .solve(path, path.parent().unwrap(), &FileSystem)
        .unwrap();
    let worst = solved
        .solution
        .pressure
        .iter()
        .map(|p| (p - SIGMA).abs() / SIGMA)
        .fold(0.0f64, f64::max);
    assert!(worst < 1e-8, "pressure off by {worst:e}");
    assert_fails(
        &dir,
        "unknown_law.toml",
        &named.replace("contact_complementarity", "coulomb"),
        &["contact.named_law", "coulomb", "exponential_contact"],
    );
    assert_fails(
        &dir,
        "both_laws.toml",
        &named.replace("named_law =", "law = \"exponential\"\nnamed_law ="),
        &["contact.named_law", "not both"],
    );
}

/// The stacked blocks of [`setup`] with the upper block moved up by `gap` and pressed down by
/// a prescribed displacement `-(gap + squeeze)` of its top (held in x on its left side); the
/// lower block held in y at its bottom and in x on its left side. Writes the meshes into
/// `dir` and returns the scene text, whose `[contact]` table ends the file.
fn gap_scene(dir: &TempDir, gap: f64, squeeze: f64) -> String {
    let lower = rectangle_mesh([0.0, 0.0], [1.0, 1.0], [4, 4], CellShape::Tensor, 1).unwrap();
    let (y0, y1) = (1.0 + gap, 2.0 + gap);
    let upper = rectangle_mesh([0.0, y0], [1.0, y1], [5, 5], CellShape::Simplex, 1000).unwrap();
    dir.file("lower.msh", body_file(&lower, "lower", 0.0, 1.0));
    dir.file("upper.msh", body_file(&upper, "upper", y0, y1));
    format!(
        r#"kind = "contact"

[bodies.upper]
mesh = "upper.msh"
group = "upper"
youngs_modulus = 210e9
poisson_ratio = 0.3
dirichlet = [
    {{ group = "upper_left", component = "x", value = 0.0 }},
    {{ group = "upper_top", component = "y", value = {} }},
]

[bodies.lower]
mesh = "lower.msh"
group = "lower"
youngs_modulus = 210e9
poisson_ratio = 0.3
dirichlet = [
    {{ group = "lower_bottom", component = "y", value = 0.0 }},
    {{ group = "lower_left", component = "x", value = 0.0 }},
]

[contact]
slave = {{ body = "upper", group = "upper_bottom" }}
master = {{ body = "lower", group = "lower_top" }}
"#,
        -(gap + squeeze)
    )
}

/// Regression: `[contact] search_radius` was checked and then never applied (the interface
/// was built with the default search). Two blocks 0.5 apart (slave faces of 0.2, the
/// interface 1 wide): without the key the search does not reach across and the scene is
/// refused for want of overlap; with `search_radius = 0.6` the gap is coupled and closed by
/// the prescribed squeeze `delta`, and the pressure is the closed form of two equal blocks in
/// series under uniaxial plane strain, `sigma = E delta / (2 (1 - nu^2))`, at every node.
#[test]
fn contact_search_radius_reaches_across_an_open_gap() {
    let dir = TempDir::new("contact-search-radius");
    let (gap, squeeze) = (0.5, 1e-3);
    let text = gap_scene(&dir, gap, squeeze);
    assert!(text.contains("value = -0.501"), "{text}");
    assert_fails(&dir, "no_radius.toml", &text, &["no overlap"]);
    let with_radius = format!("{text}search_radius = 0.6\n");
    let scene = dir.file("radius.toml", &with_radius);
    let path = Path::new(&scene);
    let spec = ContactSpec::parse(&with_radius, path).unwrap();
    let solved = spec
        .solve(path, path.parent().unwrap(), &FileSystem)
        .unwrap();
    let (e, nu) = (210e9, 0.3);
    let sigma = e * squeeze / (2.0 * (1.0 - nu * nu));
    let worst = solved
        .solution
        .pressure
        .iter()
        .map(|p| (p - sigma).abs() / sigma)
        .fold(0.0f64, f64::max);
    assert_eq!(solved.solution.pressure.len(), 6);
    assert!(worst < 1e-8, "pressure off by {worst:e}");
    assert!(solved.tie.coupling().warnings.is_empty());
}

/// Regression: a body held in one direction only was solved with exit 0 and an arbitrary
/// rigid shift in the other. The upper block of [`gap_scene`] (touching, `gap = 0`) without
/// its x condition is free to slide along x: neither a prescribed displacement nor the contact
/// normal (y) holds that, and the scene is refused naming the body by its scene name and the
/// motion; nothing is written. Held in x again, it runs.
#[test]
fn a_body_free_to_slide_is_refused_naming_it_and_the_motion() {
    let dir = TempDir::new("contact-not-held");
    let text = gap_scene(&dir, 0.0, 1e-3);
    let free = text.replace(
        "    { group = \"upper_left\", component = \"x\", value = 0.0 },\n",
        "",
    );
    assert_ne!(free, text);
    assert_fails(
        &dir,
        "free_x.toml",
        &free,
        &[
            "body \"upper\" is not held against rigid motion",
            "translation along x",
        ],
    );
    let scene = dir.file("held.toml", &text);
    let o = mortar(&["run", &scene, "--out", dir.join("out").to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// A body held in a direction by contact alone that is pulled away from the contact: the
/// error names the body by its scene name and the motion only contact held (the upper block
/// of the stacked blocks, held in x on its left side, pulled up by a traction on its top).
#[test]
fn a_body_pulled_off_the_contact_is_named() {
    let dir = TempDir::new("contact-pulled-off");
    setup(&dir);
    let pulled = SCENE.replace("value = [0.0, -50e6]", "value = [0.0, 50e6]");
    assert_ne!(pulled, SCENE);
    assert_fails(
        &dir,
        "pulled.toml",
        &pulled,
        &["upper (its translation along y held by contact alone)"],
    );
}

/// A contact scene of two bodies of `file` (tests/meshes, made by Gmsh with
/// `Mesh.ElementOrder = 2`): `slave` pressed onto `master` by a prescribed displacement `push`
/// of its outer face `slave_end`, the master's outer face `master_end` held.
fn second_order_scene(
    file: &str,
    [slave, master]: [&str; 2],
    [slave_end, master_end]: [&str; 2],
    [slave_face, master_face]: [&str; 2],
    push: &str,
) -> String {
    let mesh = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/meshes")
        .join(file);
    let mesh = mesh.display();
    format!(
        r#"kind = "contact"
[bodies.{slave}]
mesh = "{mesh}"
group = "{slave}"
youngs_modulus = 1e9
poisson_ratio = 0.3
dirichlet = [{{ group = "{slave_end}", component = "all", value = {push} }}]
[bodies.{master}]
mesh = "{mesh}"
group = "{master}"
youngs_modulus = 1e9
poisson_ratio = 0.3
dirichlet = [{{ group = "{master_end}", component = "all", value = 0.0 }}]
[contact]
slave = {{ body = "{slave}", group = "{slave_face}" }}
master = {{ body = "{master}", group = "{master_face}" }}
"#
    )
}

/// Second-order contact writes its results: the interface (the slave surface) of Quad9,
/// Quad8, Tri6 and Line3 faces was refused ("surface cell 0 has 9 nodes", everything lost) or
/// written as VTK triangles (a Line3, typed by its node count). Each face is now written with
/// VTK's quadratic type (VTK file format documentation, cell types: 21 quadratic edge, 22
/// quadratic triangle, 23 quadratic quad, 28 biquadratic quad) and the bodies with theirs
/// (22, 23, 24 quadratic tetra, 25 quadratic hexahedron, 29 triquadratic hexahedron), each
/// connectivity the cell's node count long.
#[test]
fn second_order_contact_writes_quadratic_vtk_cells() {
    let dir = TempDir::new("contact-second-order");
    let cases = [
        (
            "so_3d_hex27.msh",
            ["top", "bottom"],
            ["top_z1", "bottom_z0"],
            ["top_bottom", "bottom_top"],
            "[0.0, 0.0, -0.001]",
            (28, 9),
            [(29, 27), (24, 10)],
        ),
        (
            "so_3d_hex20.msh",
            ["bottom", "top"],
            ["bottom_z0", "top_z1"],
            ["bottom_top", "top_bottom"],
            "[0.0, 0.0, 0.001]",
            (23, 8),
            [(25, 20), (24, 10)],
        ),
        (
            "so_3d_hex20.msh",
            ["top", "bottom"],
            ["top_z1", "bottom_z0"],
            ["top_bottom", "bottom_top"],
            "[0.0, 0.0, -0.001]",
            (22, 6),
            [(24, 10), (25, 20)],
        ),
        (
            "so_2d_quad8.msh",
            ["right", "left"],
            ["right_x1", "left_x0"],
            ["right_x0", "left_x1"],
            "[-0.001, 0.0]",
            (21, 3),
            [(23, 8), (22, 6)],
        ),
    ];
    for (k, (file, bodies, ends, faces, push, interface, volumes)) in cases.into_iter().enumerate()
    {
        let scene = dir.file(
            &format!("scene{k}.toml"),
            second_order_scene(file, bodies, ends, faces, push),
        );
        let out = dir.join(&format!("out{k}"));
        let o = mortar(&["run", &scene, "--out", out.to_str().unwrap()]);
        assert!(
            o.status.success(),
            "{file}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let check = |name: &str, (vtk, nodes): (u8, usize)| {
            let vtu = std::fs::read_to_string(out.join(name)).unwrap();
            let types = array(&vtu, "types");
            assert!(
                !types.is_empty() && types.iter().all(|&t| t == f64::from(vtk)),
                "{file} {name}: {types:?}"
            );
            let offsets = array(&vtu, "offsets");
            assert_eq!(
                offsets.last().copied(),
                Some((nodes * types.len()) as f64),
                "{file} {name}"
            );
        };
        check("interface.vtu", interface);
        check(&format!("{}.vtu", bodies[0]), volumes[0]);
        check(&format!("{}.vtu", bodies[1]), volumes[1]);
        let interface = std::fs::read_to_string(out.join("interface.vtu")).unwrap();
        let p = array(&interface, "contact_pressure");
        assert!(p.iter().any(|&p| p > 0.0), "{file}: in contact");
    }
}

/// A 2D mesh written clockwise (its surface's normal along -z, every cell's nodes running
/// clockwise) was read, then refused at assembly as "cell 31 is inverted or degenerate",
/// naming one cell as if the others were fine. The reader now says that the whole mesh is
/// clockwise, naming the file and group, and the scene names the body; one clockwise cell
/// among counter-clockwise ones is still the assembly's inverted cell.
#[test]
fn a_clockwise_2d_mesh_is_named_as_such() {
    let dir = TempDir::new("contact-clockwise");
    setup(&dir);
    let mut lower = rectangle_mesh([0.0, 0.0], [1.0, 1.0], [4, 4], CellShape::Tensor, 1).unwrap();
    // Mirrored in y and moved back onto [0, 1]^2: every cell clockwise.
    lower
        .transform(|x| nalgebra::Vector3::new(x.x, 1.0 - x.y, 0.0))
        .unwrap();
    let bytes = body_file(&lower, "lower", 0.0, 1.0);
    let path = Path::new("lower.msh");
    let registry = mortar::elements::volume::VolumeRegistry::default();
    let err = mortar::io::parse_gmsh_volume(bytes.clone(), path, "lower", &registry).unwrap_err();
    let text = err.to_string();
    assert!(
        matches!(err, mortar::io::IoError::ClockwiseMesh { cells: 16, .. }),
        "{text}"
    );
    assert!(
        text.contains("whole 2D mesh is clockwise") && text.contains("\"lower\""),
        "{text}"
    );
    dir.file("lower.msh", bytes);
    assert_fails(
        &dir,
        "clockwise.toml",
        SCENE,
        &[
            "bodies.lower.group",
            "whole 2D mesh is clockwise",
            "all 16 cells",
        ],
    );
}

/// The shipped example contact scene (`examples/scenes/contact_blocks.toml`, Gmsh-made meshes
/// of `make_contact_blocks.py`) runs from the command line and passes the contact patch test
/// it describes: the 50 MPa on the upper block's top crosses the non-matching interface as a
/// uniform contact pressure of 50 MPa.
#[test]
fn example_contact_scene_runs() {
    let dir = TempDir::new("contact-example");
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/contact_blocks.toml"
    );
    let out = dir.join("out");
    let o = mortar(&["run", scene, "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let interface = std::fs::read_to_string(out.join("interface.vtu")).unwrap();
    let p = array(&interface, "contact_pressure");
    assert!(!p.is_empty());
    assert!(p.iter().all(|p| (p - SIGMA).abs() < 1e-6 * SIGMA), "{p:?}");
    for f in ["upper.vtu", "lower.vtu", "report.json"] {
        assert!(out.join(f).is_file(), "{f}");
    }
}

/// `mortar run --backend` puts the scene's systems where it says, for a built-in scene (its
/// scene file written out with the choice) and a scene file alike, and the same result comes
/// out: the built-in `hertz2d` through PETSc gives the direct run's half-width and peak; in a
/// build without PETSc the choice is refused naming the key and how to get PETSc.
#[test]
fn run_backend_overrides_the_scenes_solve_backend() {
    let dir = TempDir::new("run-backend");
    let run = |args: &[&str], out: &str| {
        let out = dir.join(out);
        let mut all = vec!["--json", "run"];
        all.extend_from_slice(args);
        all.extend_from_slice(&["--out", out.to_str().unwrap()]);
        (mortar(&all), out)
    };
    let (direct, _) = run(&["--scene", "hertz2d", "--backend", "direct"], "direct");
    assert!(
        direct.status.success(),
        "{}",
        String::from_utf8_lossy(&direct.stderr)
    );
    let direct: Value = serde_json::from_slice(&direct.stdout).unwrap();
    assert_eq!(direct["scene"]["linear_solver"]["backend"], "direct");
    assert!(direct["scene"]["linear_solver"]["why"]
        .as_str()
        .unwrap()
        .contains("asked for"));
    let (petsc, out) = run(&["--scene", "hertz2d", "--backend", "petsc"], "petsc");
    if !mortar::petsc::is_built() {
        let e = String::from_utf8_lossy(&petsc.stderr);
        assert!(
            !petsc.status.success() && e.contains("solve.backend"),
            "{e}"
        );
        assert!(e.contains("--features petsc"), "{e}");
        return;
    }
    assert!(
        petsc.status.success(),
        "{}",
        String::from_utf8_lossy(&petsc.stderr)
    );
    let petsc: Value = serde_json::from_slice(&petsc.stdout).unwrap();
    assert_eq!(petsc["scene"]["linear_solver"]["backend"], "petsc");
    for key in ["a", "p0"] {
        let (p, d) = (
            petsc["computed"][key].as_f64().unwrap(),
            direct["computed"][key].as_f64().unwrap(),
        );
        assert!((p - d).abs() <= 1e-8 * d.abs(), "{key}: {p} against {d}");
    }
    let written = std::fs::read_to_string(out.join("scene.toml")).unwrap();
    assert!(written.contains("backend = \"petsc\""), "{written}");
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/contact_blocks.toml");
    let (o, _) = run(&[file.to_str().unwrap(), "--backend", "petsc"], "file");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(report["linear_solver"]["backend"], "petsc");
}
