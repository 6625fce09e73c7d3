//! The `mortar` program end to end: Gmsh files in, D.mtx, M.mtx and summary.json out.

use mortar::elements::ElementRegistry;
use mortar::generate::{line_mesh, square_quads, square_triangles, Diagonal};
use mortar::io::{
    read_surface, write_msh41, write_msh41_ascii, write_msh41_binary, Endianness, MshFormat,
};
use mortar::{assemble_coupling, CouplingOptions, Interface};

use crate::common::{mortar, offset_tags, read_mtx, row_sums, TempDir};

fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn tags(value: &serde_json::Value) -> Vec<u64> {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_u64().unwrap())
        .collect()
}

/// Runs `mortar couple` and checks what every tied unit interface satisfies: the files parse,
/// their sizes match the node lists of the summary, D 1 = M 1 (constants are tied), the sum of
/// D and the summary's area are 1, and no temporary file is left.
fn couple_and_check(
    out: &std::path::Path,
    extra: &[&str],
) -> (Vec<Vec<f64>>, Vec<Vec<f64>>, serde_json::Value) {
    let out_s = out.to_string_lossy().into_owned();
    let mut args = vec!["couple", "--out", &out_s];
    args.extend_from_slice(extra);
    let run = mortar(&args);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "mortar {args:?} failed: {stderr}");
    let d = read_mtx(&out.join("D.mtx"));
    let m = read_mtx(&out.join("M.mtx"));
    let summary = json(&out.join("summary.json"));
    let slave = tags(&summary["slave_nodes"]);
    let master = tags(&summary["master_nodes"]);
    assert!(
        slave.windows(2).all(|w| w[0] < w[1]),
        "slave nodes ascending"
    );
    assert!(
        master.windows(2).all(|w| w[0] < w[1]),
        "master nodes ascending"
    );
    assert_eq!((d.len(), d[0].len()), (slave.len(), slave.len()));
    assert_eq!((m.len(), m[0].len()), (slave.len(), master.len()));
    for (j, (a, b)) in row_sums(&d).iter().zip(row_sums(&m)).enumerate() {
        assert!(
            (a - b).abs() < 1e-12,
            "row {j} (slave node {}): D 1 = {a}, M 1 = {b}",
            slave[j]
        );
    }
    let total: f64 = row_sums(&d).iter().sum();
    assert!((total - 1.0).abs() < 1e-12, "sum of D = {total}");
    let area = summary["area"].as_f64().unwrap();
    assert!((area - 1.0).abs() < 1e-12, "summary area = {area}");
    for key in [
        "pairs",
        "segments",
        "candidates",
        "threads",
        "slave_faces",
        "master_faces",
    ] {
        assert!(summary[key].as_u64().unwrap() > 0, "{key}");
    }
    assert!(summary["seconds"].as_f64().unwrap() >= 0.0);
    let phases = &summary["seconds_by_phase"];
    for key in ["tree", "faces", "assembly", "total"] {
        assert!(phases[key].as_f64().is_some(), "seconds_by_phase.{key}");
    }
    assert!(phases["thread_seconds"]["search"].as_f64().is_some());
    let mut names: Vec<String> = std::fs::read_dir(out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let mut expected = vec!["D.mtx", "M.mtx", "gap.mtx", "normals.mtx", "summary.json"];
    if summary["slave_basis"] == "recombined" {
        assert_eq!(summary["recombination"], "T.mtx");
        expected.insert(2, "T.mtx");
    } else {
        assert_eq!(summary["slave_basis"], "nodal");
        assert!(summary["recombination"].is_null());
    }
    assert_eq!(names, expected, "only the outputs, no temporaries");
    (d, m, summary)
}

/// `mortar couple --lm dual` on Tri6 and Quad8 slave faces writes D in the recombined basis
/// of Popp, Gee and Wall (2012), `D~ = D T^T`, and `T.mtx` beside it: D diagonal as written
/// (the nodal D had 0.2 of the diagonal off it on the rows of edge nodes), and the slave
/// values `u_s = T^T D~^-1 M u_m` of the fields x and y at the master nodes are those at the
/// slave nodes (the flat interface z = 0.5: both sides interpolate them exactly). On Line3
/// faces (not recombined) the summary says `nodal`, and a `T.mtx` of an earlier run into the
/// same folder is removed.
#[test]
fn couples_second_order_faces_with_dual_multipliers_in_the_recombined_basis() {
    let dir = TempDir::new("clidualso");
    let meshes = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/meshes");
    let file = meshes.join("so_3d_hex20.msh");
    let registry = ElementRegistry::new();
    let out = dir.join("out");
    for (slave, master, kind) in [
        ("top_bottom", "bottom_top", "Tri6"),
        ("bottom_top", "top_bottom", "Quad8"),
    ] {
        let s = format!("{}#{slave}", file.display());
        let m = format!("{}#{master}", file.display());
        let (d, m_rows, summary) =
            couple_and_check(&out, &["--slave", &s, "--master", &m, "--lm", "dual"]);
        assert_eq!(summary["slave_basis"], "recombined", "{kind}");
        assert_eq!(summary["d_off_diagonal"], 0, "{kind}");
        let t = read_mtx(&out.join("T.mtx"));
        let n = d.len();
        for (j, row) in d.iter().enumerate() {
            for (k, v) in row.iter().enumerate() {
                assert!((j == k) == (*v != 0.0), "{kind}: D[{j}][{k}] = {v}");
            }
        }
        let position = |group: &str, key: &str| {
            let mesh = read_surface(&file, Some(group), &registry).unwrap();
            assert!(mesh.face(0).element.name() == kind || group == master);
            tags(&summary[key])
                .iter()
                .map(|t| mesh.coords()[mesh.node_index(*t).unwrap() as usize])
                .collect::<Vec<_>>()
        };
        let (xs, xm) = (
            position(slave, "slave_nodes"),
            position(master, "master_nodes"),
        );
        for c in 0..2 {
            let scaled: Vec<f64> = (0..n)
                .map(|j| {
                    m_rows[j]
                        .iter()
                        .zip(&xm)
                        .map(|(v, x)| v * x[c])
                        .sum::<f64>()
                        / d[j][j]
                })
                .collect();
            for (k, x) in xs.iter().enumerate() {
                let u: f64 = (0..n).map(|j| t[j][k] * scaled[j]).sum();
                assert!(
                    (u - x[c]).abs() < 1e-12,
                    "{kind}: node {k}: {u} against {}",
                    x[c]
                );
            }
        }
    }
    // Line3 faces into the same folder: nodal, and the T.mtx above removed.
    let file = meshes.join("so_2d_quad8.msh");
    let s = format!("{}#right_x0", file.display());
    let m = format!("{}#left_x1", file.display());
    let (_, _, summary) = couple_and_check(&out, &["--slave", &s, "--master", &m, "--lm", "dual"]);
    assert_eq!(summary["slave_basis"], "nodal");
    assert!(!out.join("T.mtx").exists());
}

#[test]
fn couples_a_3d_interface_from_an_ascii_group_and_a_binary_file() {
    let dir = TempDir::new("cli3d");
    let slave = square_triangles(4, Diagonal::Main, 0.0, false, 1).unwrap();
    let master = square_quads(5, 0.0, true, 1000).unwrap();
    let s = dir.join("slave.msh");
    let m = dir.join("master.msh");
    write_msh41_ascii(&slave, &s, "top").unwrap();
    write_msh41_binary(&master, &m, "bottom", Endianness::Big).unwrap();
    let out = dir.join("out/nested");
    let slave_arg = format!("{}#top", s.display());
    let master_arg = m.to_string_lossy().into_owned();
    let (d, m_mat, summary) =
        couple_and_check(&out, &["--slave", &slave_arg, "--master", &master_arg]);
    assert_eq!(summary["dimension"], 3);
    // The vocabulary's defaults, as scene files and Python take them.
    assert_eq!(summary["multipliers"], "dual");
    assert_eq!(summary["integration"], "segment");
    assert_eq!(summary["slave_faces"], 32);
    assert_eq!(summary["master_faces"], 25);
    assert_eq!(
        tags(&summary["slave_nodes"]),
        (1..=25).collect::<Vec<u64>>()
    );
    assert_eq!(
        tags(&summary["master_nodes"]),
        (1000..1036).collect::<Vec<u64>>()
    );

    // The files hold exactly what the library computes: values survive the text format.
    let registry = ElementRegistry::new();
    let interface = Interface::new(
        read_surface(&s, Some("top"), &registry).unwrap(),
        read_surface(&m, None, &registry).unwrap(),
    )
    .unwrap();
    let coupling = assemble_coupling(&interface, &CouplingOptions::default().dual()).unwrap();
    for (v, (r, c)) in coupling.d.iter() {
        assert_eq!(v.to_bits(), d[r][c].to_bits(), "D[{r},{c}]");
    }
    for (v, (r, c)) in coupling.m.iter() {
        assert_eq!(v.to_bits(), m_mat[r][c].to_bits(), "M[{r},{c}]");
    }
}

#[test]
fn couples_a_2d_interface_of_lines_with_dual_multipliers() {
    let dir = TempDir::new("cli2d");
    let s = dir.join("slave.msh");
    let m = dir.join("master.msh");
    write_msh41_binary(
        &line_mesh(6, false, 1).unwrap(),
        &s,
        "bottom",
        Endianness::Little,
    )
    .unwrap();
    write_msh41_ascii(&line_mesh(7, true, 100).unwrap(), &m, "top").unwrap();
    let out = dir.join("out");
    let (s, m) = (
        s.to_string_lossy().into_owned(),
        m.to_string_lossy().into_owned(),
    );
    let (d, _, summary) = couple_and_check(&out, &["--slave", &s, "--master", &m, "--lm", "dual"]);
    assert_eq!(summary["dimension"], 2);
    assert_eq!(summary["multipliers"], "dual");
    assert_eq!(tags(&summary["slave_nodes"]), (1..=7).collect::<Vec<u64>>());
    assert_eq!(
        tags(&summary["master_nodes"]),
        (100..=107).collect::<Vec<u64>>()
    );
    // Dual multipliers: D is diagonal.
    for (r, row) in d.iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            assert!(r == c || v.abs() < 1e-14, "D[{r},{c}] = {v}");
        }
    }
    // A straight interface: the sorted merge took every face, and the summary says so.
    assert_eq!(summary["straight_line_faces"], 6);
    let out2 = dir.join("out2").to_string_lossy().into_owned();
    let args = [
        "couple", "--slave", &s, "--master", &m, "--lm", "dual", "--out", &out2,
    ];
    let run = mortar(&args);
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(
        text.contains("path     the sorted merge of a straight line for 6 of 6 slave faces"),
        "{text}"
    );
}

#[test]
fn couples_two_groups_of_one_file_with_element_based_integration() {
    let dir = TempDir::new("cligroups");
    let slave = square_triangles(3, Diagonal::Anti, 0.0, false, 1).unwrap();
    let master = offset_tags(&square_quads(4, 0.0, true, 1).unwrap(), 500, 500);
    let file = dir.join("both.msh");
    write_msh41(
        &[(&slave, "slave"), (&master, "master")],
        &file,
        MshFormat::Ascii,
    )
    .unwrap();
    let out = dir.join("out");
    let s = format!("{}#slave", file.display());
    let m = format!("{}#master", file.display());
    let run = mortar(&[
        "couple",
        "--slave",
        &s,
        "--master",
        &m,
        "--out",
        &out.to_string_lossy(),
        "--integration",
        "element",
        "--degree",
        "6",
        "--threads",
        "1",
        "--json",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    // --json prints the summary, the same as the file.
    let printed: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(printed, json(&out.join("summary.json")));
    assert_eq!(printed["slave_faces"], 18);
    assert_eq!(printed["master_faces"], 16);
    assert_eq!(printed["integration"], "element");
    assert_eq!(printed["degree"], 6);
    assert_eq!(printed["threads"], 1);
    assert_eq!(
        tags(&printed["master_nodes"]),
        (501..=525).collect::<Vec<u64>>()
    );
    // Element-based integration is inexact across master edges, but D 1 = M 1 still holds
    // row by row up to quadrature error, and the slave area is exact.
    let d = read_mtx(&out.join("D.mtx"));
    let total: f64 = row_sums(&d).iter().sum();
    assert!((total - 1.0).abs() < 1e-10, "{total}");
}

#[test]
fn no_arguments_runs_the_pellet_scene_into_out_pellet() {
    let dir = TempDir::new("default-job");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_mortar"))
        .current_dir(dir.join(""))
        .output()
        .expect("run the mortar binary");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = String::from_utf8_lossy(&run.stdout);
    // It says what it modelled and why, and the results.
    for needle in [
        "pellet",
        "thermoelasticity",
        "exponential contact law",
        "contact engaged at t = ",
        "gap below the onset of the pressure law",
        "warning pellet_cracking",
        "centre temperature",
        "peak contact pressure",
        "plenum pressure",
        "out/pellet",
    ] {
        assert!(text.contains(needle), "no {needle:?} in\n{text}");
    }
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out/pellet/report.json")).unwrap())
            .unwrap();
    // The default scene leaves the ranges of pellet cracking and cladding yield
    // (tests/pellet/limits.rs), and says so.
    assert_eq!(report["status"], "warnings");
    assert_eq!(report["models"]["mechanics"], true);
    let closure = report["gap_closure_time"].as_f64().expect("the gap closes");
    assert!(
        closure > 0.0 && closure < 10.0,
        "closes in the ramp: {closure}"
    );
    let imbalance = report["steady"]["relative_imbalance"].as_f64().unwrap();
    assert!(imbalance < 1e-6, "energy imbalance {imbalance:e}");
    assert!(dir.join("out/pellet/pellet_0000.vtu").exists());
}

/// The shipped dished-pellet scene runs from another folder: its `[mesh] file` is found
/// beside the scene file, and the report gives what was taken from the file.
#[test]
fn runs_the_dished_pellet_scene_from_its_gmsh_file() {
    let dir = TempDir::new("pellet-rz");
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/pellet_rz.toml"
    );
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_mortar"))
        .current_dir(dir.join(""))
        .args(["run", scene, "--out", "out"])
        .output()
        .expect("run the mortar binary");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out/report.json")).unwrap()).unwrap();
    let file = &report["mesh"]["file"];
    assert_eq!(file["pellet_radius"].as_f64(), Some(4.1e-3), "{file}");
    assert!(file["end_voids"].as_f64().unwrap() > 4.8e-9, "{file}");
    assert_eq!(report["models"]["mechanics"], true);
    assert!(dir.join("out/pellet_0000.vtu").exists());
}

#[test]
fn demo_couples_the_built_in_pair() {
    let run = mortar(&["demo"]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = String::from_utf8_lossy(&run.stdout);
    for needle in [
        "default scene",
        "slave",
        "master",
        "pairs",
        "segments",
        "area",
        "time",
        "dual multipliers",
        // Tri3 against flat Quad4: the closed form (the clip polygons' moments).
        "path     the closed form for 1152 of 1152 slave faces",
    ] {
        assert!(text.contains(needle), "no {needle:?} in\n{text}");
    }
    // The area, the sum of D: the unit square to rounding.
    let area: f64 = text
        .lines()
        .find_map(|l| l.strip_prefix("area"))
        .and_then(|l| l.split_whitespace().next())
        .and_then(|v| v.parse().ok())
        .expect("an area line");
    assert!((area - 1.0).abs() < 1e-12, "area {area}");
    let run = mortar(&["--json", "demo"]);
    assert!(run.status.success());
    let summary: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert!((summary["area"].as_f64().unwrap() - 1.0).abs() < 1e-12);
    assert_eq!(summary["slave_faces"], 2 * 24 * 24);
    assert_eq!(summary["master_faces"], 35 * 35);
}

#[test]
fn help_is_printed() {
    let run = mortar(&["--help"]);
    assert!(run.status.success());
    assert!(String::from_utf8_lossy(&run.stdout).contains("couple"));
    let run = mortar(&["couple", "--help"]);
    assert!(run.status.success());
    let text = String::from_utf8_lossy(&run.stdout);
    for flag in [
        "--slave",
        "--master",
        "--out",
        "--lm",
        "--integration",
        "--degree",
        "--curved-tolerance",
        "--subdivision",
        "--quad-subdivision",
        "--threads",
    ] {
        assert!(text.contains(flag), "{flag}");
    }
}

/// `mortar run --help` says what the command does: it listed the kinds tied_heat and pellet
/// only, said every VTU carries temperature and that built-in scenes write their scene file
/// and meshes (the contact built-ins wrote report.json only). It now names the contact kind,
/// its outputs and what each built-in writes (all four their scene file and meshes), and
/// couple's help names gap.mtx and normals.mtx.
#[test]
fn run_help_says_what_is_written() {
    let run = mortar(&["run", "--help"]);
    assert!(run.status.success());
    let text = String::from_utf8_lossy(&run.stdout).replace('\n', " ");
    let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
    for needle in [
        "kind = \"tied_heat\", \"contact\" or \"pellet\"",
        "DIR/interface.vtu",
        "displacement, stresses",
        "The built-in tied_heat, hertz2d, hertz3d and shrink_fit also write their scene file \
         (scene.toml) and meshes",
    ] {
        assert!(text.contains(needle), "{needle:?} not in: {text}");
    }
    assert!(
        !text.contains("BODY.vtu (temperature) per body and"),
        "{text}"
    );
    let run = mortar(&["couple", "--help"]);
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(
        text.contains("gap.mtx") && text.contains("normals.mtx"),
        "{text}"
    );
}

/// Regression: `mortar ... | head` panicked ("failed printing to stdout: Broken pipe") when
/// the reader had gone before the summary was printed. It now ends quietly with status 141
/// (128 + SIGPIPE, as Unix tools do), no panic message.
#[test]
fn a_closed_standard_output_ends_quietly() {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_mortar"))
        .arg("demo")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run the mortar binary");
    // The reader goes before anything is written.
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("wait for mortar");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(141), "{stderr}");
}

/// A long transient stops cleanly on Ctrl-C. A pellet scene of 10^5 steps
/// (the r-z model, about half a millisecond a step) gets SIGINT after a second: the process
/// ends with status 130 (128 + SIGINT), says it was interrupted, and leaves report.json with
/// `"status": "interrupted"`, the steps that are valid and their history.
#[test]
fn ctrl_c_stops_a_long_run_cleanly() {
    let dir = TempDir::new("ctrl-c");
    let scene = dir.file(
        "long.toml",
        "kind = \"pellet\"\n[model]\ngeometry = \"axisymmetric\"\n[mesh]\nrefinement = 1\n\
         [time]\nstep = 1.0\nend = 1e5\nsnapshots = 0\n",
    );
    let out = dir.join("out");
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_mortar"))
        .args(["run", &scene, "--out", out.to_str().unwrap()])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run the mortar binary");
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let kill = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("run kill");
    assert!(kill.success());
    let done = child.wait_with_output().expect("wait for mortar");
    let stderr = String::from_utf8_lossy(&done.stderr);
    assert_eq!(done.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("interrupted"), "{stderr}");
    let report = json(&out.join("report.json"));
    assert_eq!(report["status"], "interrupted");
    let valid = report["valid_steps"].as_u64().unwrap();
    assert!(valid > 1 && valid < 100_001, "{valid} steps");
    let times = report["history"]["time"].as_array().unwrap();
    assert_eq!(times.len() as u64, valid);
}

/// `mortar couple --lm linear` on a Gmsh-made second-order interface (Tri6 slave against
/// Quad8 master, `tests/meshes/so_3d_hex20.msh`, the unit square `z = 0.5`): the summary
/// names the space, D 1 = M 1 and sum(D) = 1 (checked by `couple_and_check`), and only the
/// corner nodes of the slave faces have rows (closed form: linear multipliers live on the
/// corners).
#[test]
fn couples_second_order_faces_with_linear_multipliers() {
    let dir = TempDir::new("clilinear");
    let file =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/meshes/so_3d_hex20.msh");
    let s = format!("{}#top_bottom", file.display());
    let m = format!("{}#bottom_top", file.display());
    let out = dir.join("out");
    let (d, m_rows, summary) =
        couple_and_check(&out, &["--slave", &s, "--master", &m, "--lm", "linear"]);
    assert_eq!(summary["multipliers"], "linear");
    let registry = ElementRegistry::new();
    let slave = read_surface(&file, Some("top_bottom"), &registry).unwrap();
    let mut corner = std::collections::BTreeSet::new();
    for f in 0..slave.face_count() {
        let face = slave.face(f);
        assert_eq!(face.element.name(), "Tri6");
        for &n in &face.nodes[..3] {
            corner.insert(slave.node_tags()[n as usize]);
        }
    }
    let rows = tags(&summary["slave_nodes"]);
    assert!(corner.len() < rows.len());
    for (j, tag) in rows.iter().enumerate() {
        let has = d[j].iter().any(|v| *v != 0.0);
        assert_eq!(has, corner.contains(tag), "row {j} (node {tag})");
        assert_eq!(m_rows[j].iter().any(|v| *v != 0.0), has, "M row {j}");
    }
}

/// `mortar couple --quad-subdivision 2` reaches the integration: on a slave quad that is not
/// a parallelogram the summary's formulation names the cut, D 1 = M 1 and sum(D) = the
/// quad's area (checked by `couple_and_check` against 1: the quad (0,0), (1,0), (1,1.2),
/// (0,0.8) has area 1), and M differs from the uncut one (closed form of the dial: only the
/// distribution of M changes).
#[test]
fn couples_with_the_quad_subdivision_dial() {
    let dir = TempDir::new("cliquadcut");
    let mut slave = mortar::SurfaceMesh::new();
    for (i, p) in [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.2, 0.0],
        [0.0, 0.8, 0.0],
    ]
    .iter()
    .enumerate()
    {
        slave.add_node(i as u64 + 1, *p).unwrap();
    }
    slave
        .add_face(&mortar::elements::QUAD4, &[1, 2, 3, 4])
        .unwrap();
    // Tri3 covering [-0.1, 1.3]^2, facing the slave.
    let mut master = square_triangles(5, Diagonal::Main, 0.0, true, 101).unwrap();
    master
        .transform(|x| nalgebra::Vector3::new(1.4 * x.x - 0.1, 1.4 * x.y - 0.1, 0.0))
        .unwrap();
    let (s, m) = (dir.join("slave.msh"), dir.join("master.msh"));
    write_msh41_ascii(&slave, &s, "slave").unwrap();
    write_msh41_ascii(&master, &m, "master").unwrap();
    let (s, m) = (
        s.to_string_lossy().into_owned(),
        m.to_string_lossy().into_owned(),
    );
    let (_, m_plain, _) = couple_and_check(&dir.join("plain"), &["--slave", &s, "--master", &m]);
    let (_, m_cut, summary) = couple_and_check(
        &dir.join("cut"),
        &["--slave", &s, "--master", &m, "--quad-subdivision", "2"],
    );
    let formulation = summary["formulation"].as_str().unwrap();
    assert!(formulation.contains("cut 2x2"), "{formulation}");
    let changed = m_plain
        .iter()
        .flatten()
        .zip(m_cut.iter().flatten())
        .fold(0.0f64, |w, (a, b)| w.max((a - b).abs()));
    assert!(changed > 1e-9, "M unchanged: {changed:e}");
}

/// A dense Matrix Market array (`array real general`): its rows.
fn read_dense_mtx(path: &std::path::Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("%%MatrixMarket matrix array real general")
    );
    let mut lines = lines.filter(|l| !l.starts_with('%'));
    let size: Vec<usize> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    let values: Vec<f64> = lines.map(|l| l.trim().parse().unwrap()).collect();
    assert_eq!(values.len(), size[0] * size[1]);
    (0..size[0])
        .map(|r| (0..size[1]).map(|c| values[c * size[0] + r]).collect())
        .collect()
}

/// `couple` writes the weighted gap and the slave's nodal normals (they were computed and
/// dropped). Closed form: two parallel flat unit squares a distance `g` apart (slave at
/// `z = 0` facing `+z`, master at `z = g`), fully covered, so that `M 1 = D 1 = w` (the slave
/// nodal areas) and linear fields are tied: `G_j = D x_s - M x_m = (0, 0, -g w_j)`, the
/// normal `n_j = (0, 0, 1)` and the normal gap `-n_j . G_j = g w_j`. In 2D likewise with two
/// parallel lines, two columns.
/// Couples the surfaces of `slave` and `master` into `out`; returns the rows of gap.mtx, of
/// normals.mtx and the slave nodal areas (the row sums of D), one per slave node.
fn gap_and_normals(
    out: &std::path::Path,
    slave: &std::path::Path,
    master: &std::path::Path,
) -> (Vec<Vec<f64>>, Vec<Vec<f64>>, Vec<f64>) {
    let args = [
        "--slave",
        slave.to_str().unwrap(),
        "--master",
        master.to_str().unwrap(),
    ];
    let (d, _, _) = couple_and_check(out, &args);
    let w = row_sums(&d);
    let gap = read_dense_mtx(&out.join("gap.mtx"));
    let normals = read_dense_mtx(&out.join("normals.mtx"));
    assert_eq!((gap.len(), normals.len()), (w.len(), w.len()));
    (gap, normals, w)
}

#[test]
fn couple_writes_the_weighted_gap_and_the_normals() {
    let dir = TempDir::new("cli-gap");
    let g = 0.05;
    let slave = square_triangles(4, Diagonal::Main, 0.0, false, 1).unwrap();
    let master = square_quads(5, g, true, 1000).unwrap();
    let (s, m) = (dir.join("slave.msh"), dir.join("master.msh"));
    write_msh41_ascii(&slave, &s, "top").unwrap();
    write_msh41_ascii(&master, &m, "bottom").unwrap();
    let (gap, normals, w) = gap_and_normals(&dir.join("out3d"), &s, &m);
    assert_eq!((gap[0].len(), normals[0].len()), (3, 3));
    for (j, ((gj, nj), wj)) in gap.iter().zip(&normals).zip(&w).enumerate() {
        assert!(
            gj[0].abs() < 1e-14 && gj[1].abs() < 1e-14,
            "row {j}: {gj:?}"
        );
        assert!((gj[2] + g * wj).abs() < 1e-14, "row {j}: {gj:?}, w {wj}");
        assert_eq!(nj, &vec![0.0, 0.0, 1.0], "row {j}");
    }

    // 2D: the line y = 0 (slave, oriented by the program to face the master: normal -y)
    // above the line y = -g.
    let slave = line_mesh(6, false, 1).unwrap();
    let mut master = line_mesh(7, false, 100).unwrap();
    master
        .transform(|x| x - nalgebra::Vector3::new(0.0, g, 0.0))
        .unwrap();
    let (s, m) = (dir.join("s2.msh"), dir.join("m2.msh"));
    write_msh41_ascii(&slave, &s, "a").unwrap();
    write_msh41_ascii(&master, &m, "b").unwrap();
    let (gap, normals, w) = gap_and_normals(&dir.join("out2d"), &s, &m);
    assert_eq!(
        (gap[0].len(), normals[0].len()),
        (2, 2),
        "two columns in 2D"
    );
    for (j, ((gj, nj), wj)) in gap.iter().zip(&normals).zip(&w).enumerate() {
        assert!(gj[0].abs() < 1e-14, "row {j}: {gj:?}");
        assert!((gj[1] - g * wj).abs() < 1e-14, "row {j}: {gj:?}, w {wj}");
        assert!(
            (nj[0]).abs() < 1e-15 && (nj[1] + 1.0).abs() < 1e-15,
            "row {j}: {nj:?}"
        );
    }
}
