//! `mortar run` refuses bad scenes with a message naming the key, file and group, a non-zero
//! exit code, and no output written.

use mortar::io::MshFormat;
use mortar_scenes::file::tied_block;

use crate::common::{mortar, TempDir};

/// Writes the 2D scene (and the 3D meshes as `left3.msh`, `right3.msh`) into `dir`; returns
/// the scene file's text.
fn setup(dir: &TempDir) -> String {
    let scene = tied_block(2, 4, MshFormat::Ascii).unwrap();
    for (name, bytes) in &scene.meshes {
        dir.file(name, bytes);
    }
    let scene3 = tied_block(3, 4, MshFormat::Ascii).unwrap();
    for (name, bytes) in &scene3.meshes {
        dir.file(&name.replace(".msh", "3.msh"), bytes);
    }
    scene.toml
}

/// Runs the scene text `text`; asserts failure with exit code 1, each needle in stderr, and
/// nothing written.
fn assert_fails(dir: &TempDir, name: &str, text: &str, needles: &[&str]) {
    let scene = dir.file(name, text);
    let out = dir.join(&format!("out-{name}"));
    let o = mortar(&["run", &scene, "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{name}: {stderr}");
    assert!(stderr.starts_with("mortar: error: "), "{name}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{name}: one line: {stderr}");
    for n in needles {
        assert!(stderr.contains(n), "{name}: {n:?} not in {stderr}");
    }
    assert!(!out.exists(), "{name}: nothing written");
}

#[test]
fn unknown_keys_are_named_with_their_line() {
    let dir = TempDir::new("scene-err-key");
    let text = setup(&dir);
    let bad = text.replace("conductivity = 2.0", "conductivity = 2.0\ncolour = \"red\"");
    let line = 1 + bad.lines().position(|l| l.starts_with("colour")).unwrap();
    assert_fails(
        &dir,
        "key.toml",
        &bad,
        &[
            "key.toml",
            &format!("line {line}"),
            "unknown field `colour`",
        ],
    );
    let bad = text.replace("[interface]", "[interface]\nmultiplier = \"dual\"");
    assert_fails(&dir, "key2.toml", &bad, &["unknown field `multiplier`"]);
    // A value of the wrong type is named by its key as well as its line.
    let bad = text.replace("conductivity = 2.0", "conductivity = \"2.0\"");
    let line = 1 + bad.lines().position(|l| l.contains("\"2.0\"")).unwrap();
    let body = bad
        .lines()
        .take(line)
        .filter(|l| l.starts_with("[bodies."))
        .last()
        .unwrap();
    let key = format!("{}.conductivity", &body[1..body.len() - 1]);
    assert_fails(
        &dir,
        "type.toml",
        &bad,
        &[&format!("line {line}"), &key, "invalid type"],
    );
    let bad = format!("{text}\n[output]\nformat = \"vtk\"\n");
    assert_fails(&dir, "key3.toml", &bad, &["unknown field `output`"]);
    let bad = text.replace("multipliers = \"dual\"", "multipliers = \"mortar\"");
    assert_fails(&dir, "value.toml", &bad, &["mortar", "standard", "dual"]);
    assert_fails(
        &dir,
        "missing_kind.toml",
        &text.replace("kind = \"tied_heat\"", ""),
        &["kind", "missing"],
    );
}

#[test]
fn missing_groups_and_files_are_named() {
    let dir = TempDir::new("scene-err-group");
    let text = setup(&dir);
    assert_fails(
        &dir,
        "group.toml",
        &text.replace("group = \"right_cut\"", "group = \"right_gap\""),
        &[
            "interface.slave",
            "right.msh",
            "no physical group named \"right_gap\"",
            "\"right_cut\"",
        ],
    );
    assert_fails(
        &dir,
        "dirichlet.toml",
        &text.replace("group = \"left_end\"", "group = \"left_edge\""),
        &["bodies.left.dirichlet[0]", "left.msh", "\"left_edge\""],
    );
    assert_fails(
        &dir,
        "body.toml",
        &text.replace("group = \"left\"", "group = \"lft\""),
        &["bodies.left.group", "left.msh", "\"lft\""],
    );
    // A face group of the other body's file is not on this body's boundary.
    assert_fails(
        &dir,
        "other.toml",
        &text
            .replace("mesh = \"left.msh\"", "mesh = \"right.msh\"")
            .replace("group = \"left\"", "group = \"right\""),
        &["left_end"],
    );
    assert_fails(
        &dir,
        "file.toml",
        &text.replace("mesh = \"right.msh\"", "mesh = \"nowhere/right.msh\""),
        &["bodies.right.mesh", "cannot read", "nowhere/right.msh"],
    );
    assert_fails(
        &dir,
        "body_name.toml",
        &text.replace("body = \"left\"", "body = \"lefty\""),
        &["interface.master.body", "\"lefty\""],
    );
    // The scene file itself.
    let out = dir.join("out-none");
    let o = mortar(&[
        "run",
        dir.join("none.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("cannot read scene file"));
    assert!(!out.exists());
}

#[test]
fn mismatched_dimensions_are_named() {
    let dir = TempDir::new("scene-err-dim");
    let text = setup(&dir);
    // A 2D body tied to a 3D body.
    assert_fails(
        &dir,
        "mixed.toml",
        &text
            .replace("mesh = \"right.msh\"", "mesh = \"right3.msh\"")
            .replace("dimension = 2\n", ""),
        &[
            "bodies",
            "\"left\"",
            "2D",
            "\"right\"",
            "3D",
            "right3.msh#right",
        ],
    );
    // The scene says 3D, the meshes are 2D.
    assert_fails(
        &dir,
        "declared.toml",
        &text.replace("dimension = 2", "dimension = 3"),
        &["dimension", "says 3D", "2D"],
    );
    // A body named by a group of lines.
    assert_fails(
        &dir,
        "lines_body.toml",
        &text.replace("group = \"left\"", "group = \"left_end\""),
        &[
            "\"left_end\" has dimension 1",
            "a body needs a group of dimension 2",
        ],
    );
    // A boundary condition on a group of faces (dimension 2) of a 2D body.
    assert_fails(
        &dir,
        "faces_bc.toml",
        &text.replace("group = \"left_end\"", "group = \"left\""),
        &[
            "bodies.left.dirichlet[0]",
            "\"left\" has dimension 2",
            "2D body \"left\" is made of lines",
        ],
    );
    // A 3D scene whose interface names a group of cells.
    let text3 = text
        .replace("left.msh", "left3.msh")
        .replace("right.msh", "right3.msh")
        .replace("dimension = 2", "dimension = 3")
        .replace("group = \"right_cut\"", "group = \"right\"");
    assert_fails(
        &dir,
        "cells_interface.toml",
        &text3,
        &[
            "interface.slave",
            "\"right\" has dimension 3",
            "made of surfaces",
        ],
    );
}

#[test]
fn scene_kinds() {
    let dir = TempDir::new("scene-err-kind");
    let text = setup(&dir);
    assert_fails(
        &dir,
        "pellet.toml",
        &text.replace("kind = \"tied_heat\"", "kind = \"pellet\""),
        // A tied-heat file relabelled as a pellet scene: the pellet reader refuses its keys.
        &["pellet.toml", "pellet scene file", "unknown field `bodies`"],
    );
    assert_fails(
        &dir,
        "kind.toml",
        &text.replace("kind = \"tied_heat\"", "kind = \"friction\""),
        &[
            "unknown scene kind \"friction\"",
            "tied_heat",
            "contact",
            "pellet",
        ],
    );
    assert_fails(
        &dir,
        "contact.toml",
        &text.replace("kind = \"tied_heat\"", "kind = \"contact\""),
        // A tied-heat file relabelled as a contact scene: the contact reader refuses its keys.
        &["contact.toml", "unknown field `conductivity`"],
    );
    assert_fails(
        &dir,
        "steady_dt.toml",
        &text.replace("mode = \"steady\"", "mode = \"steady\"\ndt = 0.1"),
        &["solve.dt", "transient"],
    );
    assert_fails(
        &dir,
        "transient_rho.toml",
        &text.replace(
            "mode = \"steady\"",
            "mode = \"transient\"\ndt = 0.1\nsteps = 2",
        ),
        &["rho_cp", "transient"],
    );
    // A step count too large to ever finish is refused at once, naming the key and the
    // limit.
    for steps in ["1000000000000", "9223372036854775807"] {
        assert_fails(
            &dir,
            &format!("steps_{}.toml", steps.len()),
            &text
                .replace(
                    "mode = \"steady\"",
                    &format!("mode = \"transient\"\ndt = 0.1\nsteps = {steps}"),
                )
                .replace("conductivity = ", "rho_cp = 1.0\nconductivity = "),
            &["solve.steps", "at most 1000000"],
        );
    }
    let out = dir.join("out-builtin");
    let o = mortar(&["run", "--scene", "nope", "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no built-in scene named \"nope\""));
    assert!(!out.exists());
}

/// The dials of segment-based integration in a scene file: out of range or given with
/// element-based integration, refused naming their key; in range, the scene runs.
#[test]
fn integration_dials_are_checked_and_named() {
    let dir = TempDir::new("scene-err-dials");
    let text = setup(&dir);
    for (name, line, key) in [
        (
            "quad.toml",
            "quad_subdivision = 0",
            "interface.quad_subdivision",
        ),
        ("level.toml", "subdivision = 17", "interface.subdivision"),
        (
            "tol.toml",
            "curved_tolerance = 2.0",
            "interface.curved_tolerance",
        ),
    ] {
        let bad = text.replace("[interface]", &format!("[interface]\n{line}"));
        assert_fails(&dir, name, &bad, &[key, "out of range"]);
    }
    let bad = text.replace(
        "integration = \"segment\"",
        "integration = \"element\"\nquad_subdivision = 2",
    );
    assert_fails(
        &dir,
        "element.toml",
        &bad,
        &["interface.quad_subdivision", "not element-based"],
    );
    let good = text.replace("[interface]", "[interface]\nquad_subdivision = 2");
    let scene = dir.file("good.toml", &good);
    let out = dir.join("out-good");
    let o = mortar(&["run", &scene, "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
