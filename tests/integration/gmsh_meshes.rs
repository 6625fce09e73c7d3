//! `mortar couple` on meshes made by Gmsh 4.15 itself (`tests/meshes/make_meshes.py`:
//! OpenCASCADE geometry, Frontal-Delaunay triangles, Gmsh's own node order and orientation):
//! the pellet and its cladding across an 80 um open gap, in 2D and 3D.
//!
//! Reference values are closed forms of the meshes themselves: the slave length (area) is the
//! sum of its segment lengths (triangle areas), read from the same file.

use std::path::{Path, PathBuf};

use mortar::elements::ElementRegistry;
use mortar::io::read_gmsh_surface;

use crate::common::{mortar, read_mtx, row_sums, TempDir};

fn mesh(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/meshes")
        .join(name)
}

fn group(name: &str, group: &str) -> String {
    format!("{}#{group}", mesh(name).display())
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The measure of a slave group: the sum of its faces' lengths (2D) or areas (3D).
fn measure(name: &str, group: &str) -> f64 {
    let s = read_gmsh_surface(mesh(name), Some(group), &ElementRegistry::new()).unwrap();
    let m = &s.mesh;
    (0..m.face_count())
        .map(|f| {
            let x: Vec<_> = m
                .face(f)
                .nodes
                .iter()
                .map(|&i| m.coords()[i as usize])
                .collect();
            match x.len() {
                2 => (x[1] - x[0]).norm(),
                3 => 0.5 * (x[1] - x[0]).cross(&(x[2] - x[0])).norm(),
                k => panic!("unexpected face of {k} nodes"),
            }
        })
        .sum()
}

fn couple(dir: &TempDir, out: &str, file: &str, extra: &[&str]) -> std::process::Output {
    let (s, m) = (group(file, "pellet_surface"), group(file, "cladding_inner"));
    let out = dir.join(out);
    let out = out.to_string_lossy();
    let mut args = vec!["couple", "--slave", &s, "--master", &m, "-o", &out];
    args.extend_from_slice(extra);
    mortar(&args)
}

/// Gmsh's cladding curves run the same way as the pellet's (as given, the master "looks the
/// same way"): `couple` turns the master outward from the cells of its file and couples the
/// pair as `run` does, every row of D is covered across the open gap (no zero rows near 0,
/// 90, 180, 270 degrees), and sum(D) is the slave's length.
#[test]
fn couples_the_2d_pellet_and_cladding_across_the_open_gap() {
    let dir = TempDir::new("g-2d");
    let run = couple(&dir, "out", "pellet_gap_2d.msh", &[]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(!stderr.contains("warning"), "{stderr}");
    let out = dir.join("out");
    let summary = json(&out.join("summary.json"));
    let o = &summary["orientation"];
    assert_eq!(o["slave"]["method"], "cells", "{o}");
    assert_eq!(o["slave"]["flipped"], 0, "{o}");
    assert_eq!(
        o["master"]["flipped"], summary["master_faces"],
        "every cladding line reversed: {o}"
    );
    let length = measure("pellet_gap_2d.msh", "pellet_surface");
    let d = read_mtx(&out.join("D.mtx"));
    let sums = row_sums(&d);
    assert!(sums.iter().all(|&s| s > 0.0), "a zero row of D: {sums:?}");
    let total: f64 = sums.iter().sum();
    assert!(
        (total - length).abs() < 1e-12 * length,
        "{total} vs {length}"
    );
    assert_eq!(summary["uncovered_area"], 0.0);
    // The summary's area is the sum of D as written (to the rounding of the summation order).
    let area = summary["area"].as_f64().unwrap();
    assert!((area - total).abs() < 1e-14 * total, "{area} vs {total}");

    // Trusting the files as given keeps the old refusal, with the reason.
    let run = couple(&dir, "kept", "pellet_gap_2d.msh", &["--keep-orientation"]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("looks the same way"), "{stderr}");
    assert!(!dir.join("kept").exists());
}

/// The same in 3D: the cylinder pair couples across the open gap; the slave area the master does not
/// cover (slivers at the two ends, where the tilted facets of the pellet project past the
/// cladding's end across the gap) is reported as a named warning and in the summary, and
/// `--require-full-coverage` turns it into an error that writes nothing.
#[test]
fn couples_the_3d_pellet_and_cladding_and_names_the_uncovered_area() {
    let dir = TempDir::new("g-3d");
    let run = couple(&dir, "out", "pellet_gap_3d.msh", &[]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(
        stderr.contains("mortar: warning: uncovered slave area"),
        "{stderr}"
    );
    let summary = json(&dir.join("out").join("summary.json"));
    let area = measure("pellet_gap_3d.msh", "pellet_surface");
    let uncovered = summary["uncovered_area"].as_f64().unwrap();
    let sum_d = summary["area"].as_f64().unwrap();
    assert!(
        uncovered > 0.0 && uncovered < 1e-3 * area,
        "uncovered {uncovered} of {area}"
    );
    // What D misses is what was reported uncovered.
    assert!(
        (sum_d + uncovered - area).abs() < 1e-9 * area,
        "sum(D) {sum_d} + uncovered {uncovered} vs area {area}"
    );
    assert_eq!(summary["faces_without_partner"], 0);
    assert!(summary["faces_partly_covered"].as_u64().unwrap() > 0);
    let warnings = summary["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert_eq!(warnings[0]["name"], "uncovered slave area");

    let run = couple(
        &dir,
        "strict",
        "pellet_gap_3d.msh",
        &["--require-full-coverage"],
    );
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(stderr.starts_with("mortar: error: "), "{stderr}");
    assert!(stderr.contains("uncovered slave area"), "{stderr}");
    assert!(stderr.contains("full coverage was required"), "{stderr}");
    assert!(!dir.join("strict").exists(), "output written on error");
}

/// A 2D file named without its group is ambiguous (the disc and annulus, or
/// their boundary lines): the error names the groups the file has.
#[test]
fn a_2d_file_without_a_group_lists_its_groups() {
    let dir = TempDir::new("g-nogroup");
    let whole = mesh("pellet_gap_2d.msh").display().to_string();
    let master = group("pellet_gap_2d.msh", "cladding_inner");
    let out = dir.join("out");
    let run = mortar(&[
        "couple",
        "--slave",
        &whole,
        "--master",
        &master,
        "-o",
        &out.to_string_lossy(),
    ]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    for g in [
        "pellet_surface",
        "cladding_inner",
        "cladding_outer",
        "#GROUP",
    ] {
        assert!(stderr.contains(g), "{g} not in {stderr}");
    }
    assert!(!out.exists());
}
