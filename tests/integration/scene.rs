//! `mortar run`: scene files naming Gmsh bodies and groups, solved exactly on a patch test
//! (piecewise linear temperature), in 2D and 3D, from ASCII and binary files.

use std::path::Path;

use mortar::io::{Endianness, MshFormat};
use mortar_scenes::file::tied_heat::TiedHeatSpec;
use mortar_scenes::file::{tied_block, tied_block_exact, FileScene, FileSystem};
use serde_json::Value;

use crate::common::{mortar, TempDir};

/// Writes the scene of `tied_block(dim, n, format)` into `dir`; returns the scene file.
fn write_scene(dir: &TempDir, dim: usize, n: usize, format: MshFormat) -> String {
    let scene = tied_block(dim, n, format).unwrap();
    for (name, bytes) in &scene.meshes {
        dir.file(name, bytes);
    }
    dir.file("scene.toml", &scene.toml)
}

/// Solves the scene file through the library; returns the nodal temperatures per body.
fn solve(path: &str) -> [Vec<f64>; 2] {
    let path = Path::new(path);
    let text = std::fs::read_to_string(path).unwrap();
    let spec = TiedHeatSpec::parse(&text, path).unwrap();
    let solved = spec
        .solve(path, path.parent().unwrap(), &FileSystem)
        .unwrap();
    for (b, body) in solved.problem.bodies().iter().enumerate() {
        let err = body
            .mesh
            .coords()
            .iter()
            .zip(&solved.solution.temperatures[b])
            .map(|(x, t)| (t - tied_block_exact(x.x)).abs())
            .fold(0.0, f64::max);
        assert!(
            err < crate::claims::claim("tied.scene").bound,
            "{path:?}: body {}: error {err:e}",
            body.name
        );
    }
    solved.solution.temperatures.clone()
}

#[test]
fn patch_test_2d_and_3d_ascii_equals_binary() {
    for (dim, n) in [(2, 8), (3, 4)] {
        let ascii = TempDir::new(&format!("scene-ascii-{dim}"));
        let binary = TempDir::new(&format!("scene-binary-{dim}"));
        let a = solve(&write_scene(&ascii, dim, n, MshFormat::Ascii));
        let b = solve(&write_scene(
            &binary,
            dim,
            n,
            MshFormat::Binary(Endianness::Little),
        ));
        assert_eq!(
            a, b,
            "{dim}D: ASCII and binary files give the same temperatures"
        );
    }
}

#[test]
fn cli_writes_vtu_and_report() {
    let dir = TempDir::new("scene-cli");
    let scene = write_scene(&dir, 2, 8, MshFormat::Binary(Endianness::Big));
    let out = dir.join("out");
    let o = mortar(&["run", &scene, "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in ["left.vtu", "right.vtu", "report.json"] {
        assert!(out.join(f).is_file(), "{f} written");
    }
    let vtu = std::fs::read_to_string(out.join("right.vtu")).unwrap();
    assert!(vtu.contains("Name=\"temperature\""));
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["kind"], "tied_heat");
    assert_eq!(report["dimension"], 2);
    assert_eq!(report["formulation"]["name"], "dual-condensed SPD");
    assert_eq!(report["formulation"]["factorisation"], "sparse Cholesky");
    assert!(report["formulation"]["reason"]
        .as_str()
        .unwrap()
        .contains("D is diagonal"));
    assert_eq!(report["dofs"], 136);
    assert!(report["seconds"]["factorisation"].as_f64().unwrap() >= 0.0);
    let hi = report["bodies"][0]["temperature_max"].as_f64().unwrap();
    assert!((hi - 1.0).abs() < 1e-10, "right end at T = 1: {hi}");

    // Standard multipliers: the saddle point, said so, same temperatures.
    let text = std::fs::read_to_string(&scene)
        .unwrap()
        .replace("multipliers = \"dual\"", "multipliers = \"standard\"");
    let standard = dir.file("standard.toml", text);
    solve(&standard);
    let out2 = dir.join("out2");
    let o = mortar(&["--json", "run", &standard, "--out", out2.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(report["formulation"]["name"], "saddle point");
    assert!(report["formulation"]["factorisation"]
        .as_str()
        .unwrap()
        .starts_with("sparse LDL^T"));
}

#[test]
fn transient_scene_steps() {
    let dir = TempDir::new("scene-transient");
    let scene = write_scene(&dir, 2, 4, MshFormat::Ascii);
    let text = std::fs::read_to_string(&scene).unwrap().replace(
        "mode = \"steady\"",
        "mode = \"transient\"\ndt = 0.5\nsteps = 4",
    );
    let text = text.replace("conductivity = 1.0", "conductivity = 1.0\nrho_cp = 1.0");
    let text = text.replace("conductivity = 2.0", "conductivity = 2.0\nrho_cp = 1.0");
    let scene = dir.file("transient.toml", text);
    let out = dir.join("out");
    let o = mortar(&["--json", "run", &scene, "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(report["steps"], 4);
    assert_eq!(report["time"], 2.0);
    let hi = report["bodies"][0]["temperature_max"].as_f64().unwrap();
    assert!(
        hi > 0.0 && hi < 1.0,
        "heating up towards the steady state: {hi}"
    );
}

#[test]
fn builtin_scene_writes_its_scene_file() {
    let dir = TempDir::new("scene-builtin");
    let out = dir.join("out");
    let o = mortar(&[
        "run",
        "--scene",
        "tied_heat",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in [
        "scene.toml",
        "left.msh",
        "right.msh",
        "left.vtu",
        "right.vtu",
        "report.json",
    ] {
        assert!(out.join(f).is_file(), "{f} written");
    }
    // The written scene file runs as is, with the same result.
    solve(out.join("scene.toml").to_str().unwrap());
}

/// The built-in pellet is a scene file too: `mortar run --scene pellet` writes it beside its
/// results (`scene.toml`, every key at its default), and that file runs to the same bits
/// (every VTU file and the report's history).
#[test]
fn the_builtin_pellet_writes_its_scene_file() {
    let dir = TempDir::new("scene-builtin-pellet");
    let (a, b) = (dir.join("a"), dir.join("b"));
    let o = mortar(&["run", "--scene", "pellet", "--out", a.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let scene = a.join("scene.toml");
    assert!(scene.is_file(), "scene.toml written");
    let o = mortar(&["run", scene.to_str().unwrap(), "--out", b.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in ["pellet_0004.vtu", "interface_0004.vtu", "pellet.pvd"] {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(x == y, "{f} differs");
    }
    let history = |d: &std::path::Path| {
        let r: Value =
            serde_json::from_slice(&std::fs::read(d.join("report.json")).unwrap()).unwrap();
        r["history"].clone()
    };
    assert_eq!(history(&a), history(&b));
}

/// One dispatch over the kinds: a scene file of no known kind is refused naming the kinds,
/// by the command line and by the library's `run_scene` alike.
#[test]
fn an_unknown_kind_is_refused_naming_the_kinds() {
    let dir = TempDir::new("scene-unknown-kind");
    let scene = dir.file("x.toml", "kind = \"friction\"\n");
    let out = dir.join("out");
    let o = mortar(&["run", &scene, "--out", out.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("known kinds: tied_heat, contact, pellet"),
        "{err}"
    );
    assert!(!out.exists(), "nothing written");
    let registries = mortar::extend::Registries::default();
    let ctx = mortar_scenes::SceneContext {
        path: std::path::Path::new(&scene),
        base: &dir.join(""),
        source: &mortar_scenes::file::FileSystem,
        registries: &registries,
        out: &out,
        progress: false,
    };
    let e = mortar_scenes::run_scene("kind = \"friction\"\n", &ctx).unwrap_err();
    assert!(
        e.to_string()
            .contains("kind: unknown scene kind \"friction\""),
        "{e}"
    );
}

#[test]
fn example_scene_runs() {
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/tied_square.toml"
    );
    solve(scene);
}

/// Regression: the tied block with the right body (slave, loaded by the flux 4/3 at x = 1,
/// held by the tie alone) made `c` times more conductive than the left one (k = 1): at
/// `c = 1e12` its temperature was 1.7e-3 of the span off the exact piecewise-linear field
/// (4.6e-9 at 1e6), the rounding of its stiffness times its level acting as a spurious flux.
/// Solved relative to the stiffer body's level, every contrast is exact to 1e-13 of the span
/// with the softer body as the slave (the sides exchanged); with the stiffer body as the
/// slave up to `MAX_STIFFER_SLAVE_CONTRAST` (1e7), beyond which the scene is refused naming
/// the exchange that solves it exactly. Closed form: `T = 4x/3` on the left, `2/3 + 4(x -
/// 1/2)/(3c)` on the right.
#[test]
fn a_stiff_body_held_by_the_tie_alone_is_exact_or_refused() {
    let dir = TempDir::new("scene-contrast");
    let scene = write_scene(&dir, 2, 8, MshFormat::Ascii);
    let text = std::fs::read_to_string(&scene).unwrap();
    let (slave, master) = (
        "[interface.slave]\nbody = \"right\"\ngroup = \"right_cut\"",
        "[interface.master]\nbody = \"left\"\ngroup = \"left_cut\"",
    );
    assert!(text.contains(slave) && text.contains(master), "{text}");
    let exchanged = |t: &str| {
        t.replace(slave, "SLAVE")
            .replace(master, "MASTER")
            .replace(
                "SLAVE",
                "[interface.slave]\nbody = \"left\"\ngroup = \"left_cut\"",
            )
            .replace(
                "MASTER",
                "[interface.master]\nbody = \"right\"\ngroup = \"right_cut\"",
            )
    };
    for c in [1e6, 1e9, 1e12] {
        let stiff = text.replacen("conductivity = 2.0", &format!("conductivity = {c:e}"), 1);
        assert_ne!(stiff, text);
        for (t, slave_is_stiff) in [(stiff.clone(), true), (exchanged(&stiff), false)] {
            let path = dir.file(&format!("c{c:e}-{slave_is_stiff}.toml"), &t);
            let spec = TiedHeatSpec::parse(&t, Path::new(&path)).unwrap();
            let solved = spec.solve(Path::new(&path), dir.join("").as_path(), &FileSystem);
            if slave_is_stiff && c > 1e7 {
                let e = solved.unwrap_err().to_string();
                assert!(e.contains("make \"left\" the slave side"), "{e}");
                continue;
            }
            let solved = solved.unwrap();
            let exact = |x: f64| {
                if x <= 0.5 {
                    4.0 * x / 3.0
                } else {
                    2.0 / 3.0 + 4.0 * (x - 0.5) / (3.0 * c)
                }
            };
            let err = solved
                .problem
                .bodies()
                .iter()
                .zip(&solved.solution.temperatures)
                .flat_map(|(b, t)| {
                    b.mesh
                        .coords()
                        .iter()
                        .zip(t)
                        .map(|(x, t)| (t - exact(x.x)).abs())
                })
                .fold(0.0f64, f64::max);
            assert!(
                err < 1e-13 * (2.0 / 3.0),
                "c = {c:e}, stiff slave {slave_is_stiff}: {err:e}"
            );
        }
    }
}
