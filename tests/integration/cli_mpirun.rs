//! `mpirun -n 3 mortar couple`: the same D.mtx and M.mtx as one process (to round-off), and
//! a summary with every rank's counts; in a build without MPI, the error that says how to get
//! one.

use std::process::Command;

use mortar::generate::{square_quads, square_triangles, Diagonal};
use mortar::io::{write_msh41_ascii, write_msh41_binary, Endianness};

use crate::common::{mortar, read_mtx, TempDir};

/// Two non-matching Gmsh surfaces in `dir`: (slave argument, master argument).
fn two_surfaces(dir: &TempDir) -> (String, String) {
    let slave = square_triangles(12, Diagonal::Main, 0.0, false, 1).unwrap();
    let master = square_quads(17, 0.0, true, 1000).unwrap();
    let (s, m) = (dir.join("slave.msh"), dir.join("master.msh"));
    write_msh41_ascii(&slave, &s, "top").unwrap();
    write_msh41_binary(&master, &m, "bottom", Endianness::Little).unwrap();
    (
        format!("{}#top", s.display()),
        m.to_string_lossy().into_owned(),
    )
}

#[test]
fn couple_on_three_ranks_writes_the_one_process_operators() {
    let dir = TempDir::new("cli_mpirun");
    let (s, m) = two_surfaces(&dir);
    let one = dir.join("one");
    let one_s = one.to_string_lossy().into_owned();
    let run = mortar(&["couple", "--slave", &s, "--master", &m, "--out", &one_s]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );

    let three = dir.join("three");
    let three_s = three.to_string_lossy().into_owned();
    let args = ["couple", "--slave", &s, "--master", &m, "--out", &three_s];
    if !mortar_mpi::BUILT_WITH_MPI {
        // `mpirun`'s variable without MPI linked: the error names the feature to build with.
        let run = Command::new(env!("CARGO_BIN_EXE_mortar"))
            .args(args)
            .env("OMPI_COMM_WORLD_SIZE", "3")
            .output()
            .expect("run the mortar binary");
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success());
        assert!(stderr.contains("built without MPI"), "{stderr}");
        assert!(stderr.contains("mortar-mpi/mpi"), "{stderr}");
        return;
    }
    let run = Command::new("mpirun")
        .args(["--oversubscribe", "-n", "3", env!("CARGO_BIN_EXE_mortar")])
        .args(args)
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .output()
        .expect("mpirun (Open MPI: apt-get install openmpi-bin libopenmpi-dev)");
    assert!(
        run.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&run.stdout),
        String::from_utf8_lossy(&run.stderr)
    );
    for name in ["D.mtx", "M.mtx"] {
        let (a, b) = (read_mtx(&one.join(name)), read_mtx(&three.join(name)));
        assert_eq!((a.len(), a[0].len()), (b.len(), b[0].len()), "{name}");
        let scale = a.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
        for (r, (ra, rb)) in a.iter().zip(&b).enumerate() {
            for (c, (x, y)) in ra.iter().zip(rb).enumerate() {
                assert!(
                    (x - y).abs() <= 1e-12 * scale,
                    "{name}[{r},{c}]: {x} and {y}"
                );
                assert_eq!(*x == 0.0, *y == 0.0, "{name}[{r},{c}]: pattern");
            }
        }
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(three.join("summary.json")).unwrap())
            .unwrap();
    let one_summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(one.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["ranks"], 3);
    assert_eq!(summary["slave_nodes"], one_summary["slave_nodes"]);
    assert_eq!(summary["master_nodes"], one_summary["master_nodes"]);
    let per_rank = summary["per_rank"].as_array().unwrap();
    assert_eq!(per_rank.len(), 3);
    let faces: u64 = per_rank
        .iter()
        .map(|r| r["slave_faces"].as_u64().unwrap())
        .sum();
    assert_eq!(faces, 288);
    assert!(!three.join("gap.mtx").exists());
}
