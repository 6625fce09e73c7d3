//! Every bad input: a non-zero exit, one line on stderr naming the thing and where, and no
//! output (not even the output directory).

use mortar::elements::{LINE2, QUAD4, TRI3};
use mortar::generate::{line_mesh, square_quads, square_triangles, Diagonal};
use mortar::io::{msh41_bytes, Endianness, MshFormat};
use mortar::SurfaceMesh;

use crate::common::{ascii_text, gmsh_style_file, line_number, mortar, replace_line, TempDir};

/// A valid master file in `dir`.
fn master(dir: &TempDir) -> String {
    let m = square_quads(3, 0.0, true, 1000).unwrap();
    dir.file(
        "master.msh",
        msh41_bytes(&[(&m, "bottom")], MshFormat::Ascii).unwrap(),
    )
}

/// A valid slave text: 2 x 2 cells of triangles.
fn slave_text() -> String {
    ascii_text(
        &square_triangles(2, Diagonal::Main, 0.0, false, 1).unwrap(),
        "top",
    )
}

/// Runs `mortar couple` and checks the failure: exit code, one stderr line holding every
/// needle, nothing written.
fn assert_fails(dir: &TempDir, slave: &str, master: &str, needles: &[&str]) {
    assert_fails_with(dir, slave, master, &[], needles);
}

/// [`assert_fails`] with `extra` options.
fn assert_fails_with(dir: &TempDir, slave: &str, master: &str, extra: &[&str], needles: &[&str]) {
    let out = dir.join("out");
    let out_arg = out.to_string_lossy();
    let mut args = vec![
        "couple", "--slave", slave, "--master", master, "--out", &out_arg,
    ];
    args.extend_from_slice(extra);
    let run = mortar(&args);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success(), "should fail: {slave} {master}");
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
    assert!(stderr.starts_with("mortar: error: "), "{stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "{needle:?} not in: {stderr}");
    }
    assert!(!out.exists(), "the output directory was created: {stderr}");
    assert!(run.stdout.is_empty());
}

#[test]
fn missing_file_and_missing_group() {
    let dir = TempDir::new("e-missing");
    let m = master(&dir);
    let missing = dir.join("nowhere.msh").to_string_lossy().into_owned();
    assert_fails(
        &dir,
        &missing,
        &m,
        &["slave mesh", "cannot read", "nowhere.msh"],
    );
    assert_fails(
        &dir,
        &format!("{m}#nope"),
        &m,
        &[
            "no physical group named \"nope\"",
            "master.msh",
            "\"bottom\"",
        ],
    );
    assert_fails(&dir, &format!("{m}#"), &m, &["--slave", "no group name"]);
}

#[test]
fn malformed_ascii_files_name_the_line() {
    let dir = TempDir::new("e-ascii");
    let m = master(&dir);
    let text = slave_text();

    let s = dir.file("trunc.msh", &text[..text.find("$EndElements").unwrap() - 7]);
    let lines = std::fs::read_to_string(&s).unwrap().lines().count();
    assert_fails(
        &dir,
        &s,
        &m,
        &["trunc.msh", &format!("line {lines}"), "ends"],
    );

    let s = dir.file(
        "header.msh",
        text.replacen("$MeshFormat", "$MeshFormats", 1),
    );
    assert_fails(
        &dir,
        &s,
        &m,
        &["header.msh", "line 1", "not a Gmsh MSH file"],
    );

    let s = dir.file("version.msh", text.replacen("4.1 0 8", "2.2 0 8", 1));
    assert_fails(
        &dir,
        &s,
        &m,
        &["version.msh", "line 2", "version 2.2", "only 4.1"],
    );

    let bad = replace_line(&text, "0.5 0.5 0", "0.5 0,5 0");
    let s = dir.file("number.msh", &bad);
    let line = format!("line {}", line_number(&bad, "0.5 0,5 0"));
    assert_fails(
        &dir,
        &s,
        &m,
        &["number.msh", &line, "y coordinate of node 5", "\"0,5\""],
    );

    let bad = replace_line(&text, "1 1 2 5", "1 1 2 77");
    let s = dir.file("undefined.msh", &bad);
    let line = format!("line {}", line_number(&bad, "1 1 2 77"));
    assert_fails(
        &dir,
        &s,
        &m,
        &["undefined.msh", &line, "element 1", "node 77"],
    );

    let bad = replace_line(&text, "0.5 0.5 0", "0.5 nan 0");
    let s = dir.file("nan.msh", &bad);
    let line = format!("line {}", line_number(&bad, "0.5 nan 0"));
    assert_fails(&dir, &s, &m, &["nan.msh", &line, "node 5", "non-finite"]);
}

#[test]
fn malformed_binary_files_name_the_byte_offset() {
    let dir = TempDir::new("e-binary");
    let m = master(&dir);
    let mesh = square_triangles(2, Diagonal::Main, 0.0, false, 1).unwrap();
    let bytes = msh41_bytes(&[(&mesh, "top")], MshFormat::Binary(Endianness::Little)).unwrap();
    let cut = bytes.len() - 30;
    let s = dir.file("trunc.msh", &bytes[..cut]);
    assert_fails(
        &dir,
        &s,
        &m,
        &["trunc.msh", &format!("byte offset {cut}"), "ends"],
    );

    // A node coordinate made NaN, in place.
    let mut nan = bytes.clone();
    let nodes = nan.windows(7).position(|w| w == b"$Nodes\n").unwrap() + 7;
    // Header (4 size_t), block header (3 int + 1 size_t), 9 tags: then node 1's x.
    let x1 = nodes + 32 + 20 + 9 * 8;
    assert_eq!(f64::from_le_bytes(nan[x1..x1 + 8].try_into().unwrap()), 0.0);
    nan[x1..x1 + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    let s = dir.file("nan.msh", &nan);
    assert_fails(
        &dir,
        &s,
        &m,
        &[
            "nan.msh",
            &format!("byte offset {x1}"),
            "node 1 ",
            "non-finite",
        ],
    );

    let s = dir.file("endian.msh", {
        let mut b = bytes.clone();
        let at = b.windows(8).position(|w| w == b"4.1 1 8\n").unwrap() + 8;
        b[at..at + 4].copy_from_slice(&[2, 0, 0, 0]);
        b
    });
    assert_fails(&dir, &s, &m, &["endian.msh", "endianness"]);
}

#[test]
fn unsupported_selections_and_element_types() {
    let dir = TempDir::new("e-select");
    let m = master(&dir);
    let cube = dir.file("cube.msh", gmsh_style_file(true, 2));
    assert_fails(&dir, &cube, &m, &["cube.msh", "volume elements", "#GROUP"]);
    assert_fails(
        &dir,
        &format!("{cube}#vol"),
        &m,
        &["cube.msh", "\"vol\"", "dimension 3"],
    );
    let tri6 = gmsh_style_file(true, 21);
    let line = format!("line {}", line_number(&tri6, "3 1 2 3 4 5 6 7 8 1 2"));
    let s = dir.file("tri6.msh", &tri6);
    assert_fails(
        &dir,
        &format!("{s}#face"),
        &m,
        &[
            "tri6.msh",
            &line,
            "element 3",
            "type 21",
            "10-node triangle",
        ],
    );
}

/// Three triangles, or two plus one whose corners are `bad`.
fn mesh_with_face(bad: Option<[u64; 3]>, quad: Option<[u64; 4]>) -> SurfaceMesh {
    let mut mesh = SurfaceMesh::new();
    for (t, x) in [
        (1, [0.0, 0.0]),
        (2, [1.0, 0.0]),
        (3, [1.0, 1.0]),
        (4, [0.0, 1.0]),
        (5, [2.0, 0.0]),
        (6, [2.0, 1.0]),
    ] {
        mesh.add_node(t, [x[0], x[1], 0.0]).unwrap();
    }
    mesh.add_face_with_tag(11, &TRI3, &[1, 2, 3]).unwrap();
    mesh.add_face_with_tag(12, &TRI3, &[1, 3, 4]).unwrap();
    if let Some(b) = bad {
        mesh.add_face_with_tag(13, &TRI3, &b).unwrap();
    }
    if let Some(q) = quad {
        mesh.add_face_with_tag(14, &QUAD4, &q).unwrap();
    }
    mesh
}

#[test]
fn degenerate_inverted_and_non_overlapping_interfaces() {
    let dir = TempDir::new("e-geometry");
    let m = master(&dir);

    let text = ascii_text(&mesh_with_face(Some([2, 5, 5]), None), "top");
    let line = format!("line {}", line_number(&text, "13 2 5 5"));
    let s = dir.file("degenerate.msh", &text);
    assert_fails(
        &dir,
        &format!("{s}#top"),
        &m,
        &["degenerate.msh#top", &line, "face 13", "degenerate"],
    );

    // A bow-tie quadrilateral: 2, 5, 3, 6 crosses itself.
    let text = ascii_text(&mesh_with_face(None, Some([2, 5, 3, 6])), "top");
    let line = format!("line {}", line_number(&text, "14 2 5 3 6"));
    let s = dir.file("inverted.msh", &text);
    assert_fails(
        &dir,
        &s,
        &m,
        &["inverted.msh", &line, "face 14", "inverted"],
    );

    // A face oriented against its neighbours: refused when the files are trusted as given...
    let text = ascii_text(&mesh_with_face(None, Some([2, 3, 6, 5])), "top");
    let s = dir.file("flipped.msh", &text);
    assert_fails_with(
        &dir,
        &s,
        &m,
        &["--keep-orientation"],
        &[
            "flipped.msh",
            "line",
            "inverted",
            "oriented against its neighbours",
        ],
    );
    // ... and turned to agree with its neighbours (and said so) by default.
    let out = dir.join("flipped-out");
    let run = mortar(&[
        "couple",
        "--slave",
        &s,
        "--master",
        &m,
        "--out",
        &out.to_string_lossy(),
    ]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["orientation"]["slave"]["flipped"], 1, "{stdout}");
    assert_eq!(summary["orientation"]["master"]["flipped"], 0, "{stdout}");
    let area = summary["area"].as_f64().unwrap();
    assert!((area - 1.0).abs() < 1e-12, "area {area}");

    // The master moved far away.
    let mut far = square_quads(3, 0.0, true, 1000).unwrap();
    far.transform(|x| x + nalgebra::Vector3::new(5.0, 0.0, 0.0))
        .unwrap();
    let far = dir.file("far.msh", ascii_text(&far, "bottom"));
    let s = dir.file("slave.msh", slave_text());
    assert_fails(&dir, &s, &far, &["slave.msh", "far.msh", "no overlap"]);

    // Lines against faces.
    let lines = ascii_text(&mortar::generate::line_mesh(3, true, 1).unwrap(), "edge");
    let lines = dir.file("lines.msh", lines);
    assert_fails(
        &dir,
        &s,
        &lines,
        &["slave.msh", "lines.msh", "dimension mismatch"],
    );
}

#[test]
fn bad_options_and_unwritable_outputs() {
    let dir = TempDir::new("e-options");
    let m = master(&dir);
    let s = dir.file("slave.msh", slave_text());
    let run = mortar(&[
        "couple",
        "--slave",
        &s,
        "--master",
        &m,
        "--out",
        &dir.join("o").to_string_lossy(),
        "--degree",
        "0",
    ]);
    assert_eq!(run.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&run.stderr).contains("degree 0"));
    assert!(!dir.join("o").exists());

    // An absurd thread count is refused at once (it ran past 60 s starting threads), naming
    // the limit; nothing is written.
    let start = std::time::Instant::now();
    let out = dir.join("t").to_string_lossy().into_owned();
    let run = mortar(&[
        "couple",
        "--slave",
        &s,
        "--master",
        &m,
        "--out",
        &out,
        "--threads",
        "100000",
    ]);
    assert_eq!(run.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("threads 100000") && stderr.contains("per core"),
        "{stderr}"
    );
    assert!(start.elapsed().as_secs_f64() < 10.0, "refused at once");
    assert!(!dir.join("t").exists());

    // The output path is a file: nothing is written, the file is untouched.
    let blocker = dir.file("blocker", "keep");
    let run = mortar(&["couple", "--slave", &s, "--master", &m, "--out", &blocker]);
    assert_eq!(run.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("cannot write") && stderr.contains("blocker"),
        "{stderr}"
    );
    assert_eq!(std::fs::read_to_string(&blocker).unwrap(), "keep");

    // An existing output directory is left as it was when the input is bad.
    let existing = dir.join("existing");
    std::fs::create_dir(&existing).unwrap();
    let run = mortar(&[
        "couple",
        "--slave",
        &format!("{s}#nope"),
        "--master",
        &m,
        "--out",
        &existing.to_string_lossy(),
    ]);
    assert_eq!(run.status.code(), Some(1));
    assert!(existing.is_dir());
    assert_eq!(std::fs::read_dir(&existing).unwrap().count(), 0);

    // A usage error is clap's (exit code 2).
    let run = mortar(&["couple", "--slave", &s]);
    assert_eq!(run.status.code(), Some(2));
}

/// A fin (a third face on an edge) and a T junction (a third line at a node)
/// are refused, whether the surfaces are oriented by the program or kept as given, naming
/// every face involved with its line in the file.
#[test]
fn a_fin_and_a_t_junction_name_their_faces_and_lines() {
    let dir = TempDir::new("e-topology");
    let m = master(&dir);
    // The unit square's two triangles, and a fin standing on their shared diagonal.
    let mut fin = SurfaceMesh::new();
    for (t, x) in [
        (1, [0.0, 0.0, 0.0]),
        (2, [1.0, 0.0, 0.0]),
        (3, [1.0, 1.0, 0.0]),
        (4, [0.0, 1.0, 0.0]),
        (7, [0.5, 0.5, 0.5]),
    ] {
        fin.add_node(t, x).unwrap();
    }
    fin.add_face_with_tag(11, &TRI3, &[1, 2, 3]).unwrap();
    fin.add_face_with_tag(12, &TRI3, &[1, 3, 4]).unwrap();
    fin.add_face_with_tag(13, &TRI3, &[1, 3, 7]).unwrap();
    let text = ascii_text(&fin, "top");
    let lines: Vec<String> = ["11 1 2 3", "12 1 3 4", "13 1 3 7"]
        .iter()
        .map(|l| format!("line {}", line_number(&text, l)))
        .collect();
    let s = dir.file("fin.msh", &text);
    for extra in [&[][..], &["--keep-orientation"][..]] {
        assert_fails_with(
            &dir,
            &s,
            &m,
            extra,
            &[
                "fin.msh",
                "face 13",
                &lines[2],
                &format!("face 11 at {}", lines[0]),
                &format!("face 12 at {}", lines[1]),
                "shared by 3",
                "fin",
            ],
        );
    }

    // A segment in two lines and a third line up from its middle node.
    let mut t = SurfaceMesh::new();
    for (tag, x) in [
        (1, [0.0, 0.0, 0.0]),
        (2, [0.5, 0.0, 0.0]),
        (3, [1.0, 0.0, 0.0]),
        (4, [0.5, 0.5, 0.0]),
    ] {
        t.add_node(tag, x).unwrap();
    }
    t.add_face_with_tag(11, &LINE2, &[1, 2]).unwrap();
    t.add_face_with_tag(12, &LINE2, &[2, 3]).unwrap();
    t.add_face_with_tag(13, &LINE2, &[2, 4]).unwrap();
    let text = ascii_text(&t, "top");
    let lines: Vec<String> = ["11 1 2", "12 2 3", "13 2 4"]
        .iter()
        .map(|l| format!("line {}", line_number(&text, l)))
        .collect();
    let s = dir.file("t.msh", &text);
    let m = dir.file(
        "master2d.msh",
        ascii_text(&line_mesh(3, true, 1000).unwrap(), "bottom"),
    );
    for extra in [&[][..], &["--keep-orientation"][..]] {
        assert_fails_with(
            &dir,
            &s,
            &m,
            extra,
            &[
                "t.msh",
                "face 13",
                &lines[2],
                &format!("face 11 at {}", lines[0]),
                &format!("face 12 at {}", lines[1]),
                "node 2",
                "T junction",
            ],
        );
    }
}
