//! The distributed coupling under `mpirun` on 1 to 4 ranks (the system's Open MPI, ranks
//! oversubscribed on a small machine): the gathered D and M against the one-process coupling
//! of the same interface (`examples/distributed_check.rs`, which states the comparison), the
//! partition model's counts against the ranks', and a failure on one rank stopping every rank
//! with an error naming it.

use std::path::PathBuf;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The example built beside this test.
fn check_program() -> PathBuf {
    let exe = std::env::current_exe().expect("the test's path");
    let dir = exe
        .parent()
        .and_then(|deps| deps.parent())
        .expect("target/<profile>/deps");
    dir.join("examples").join("distributed_check")
}

/// `mpirun -n ranks distributed_check args`, killed after `limit`.
fn mpirun(ranks: usize, args: &[&str], limit: Duration) -> Output {
    let mut child = Command::new("mpirun")
        .args(["--oversubscribe", "-n", &ranks.to_string()])
        .arg(check_program())
        .args(args)
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("mpirun (Open MPI: apt-get install openmpi-bin libopenmpi-dev)");
    let start = Instant::now();
    while child.try_wait().expect("waiting for mpirun").is_none() {
        if start.elapsed() > limit {
            child.kill().ok();
            let out = child.wait_with_output().expect("mpirun's output");
            panic!(
                "mpirun -n {ranks} {args:?} still running after {limit:?} (a hang):\n{}\n{}",
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("mpirun's output")
}

/// Runs a case on `ranks` ranks and checks it matched the one-process coupling; returns the
/// JSON line.
fn matches_one_process(ranks: usize, case: &str, split: &str, n: usize) -> serde_json::Value {
    let n = n.to_string();
    let out = mpirun(
        ranks,
        &["--case", case, "--split", split, "--n", &n],
        Duration::from_secs(120),
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{case} {split} on {ranks} ranks:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let line = stdout
        .lines()
        .find(|l| l.starts_with('{'))
        .expect("the JSON line");
    let json: serde_json::Value = serde_json::from_str(line).expect("JSON");
    assert_eq!(json["ranks"], ranks);
    assert_eq!(json["nodes_match"], true, "{json}");
    // `modelled_counts` of the same parts gives every rank's counts of the run.
    assert_eq!(json["model_matches"], true, "{json}");
    for key in ["d_max_rel_diff", "m_max_rel_diff"] {
        let diff = json[key].as_f64().expect("patterns equal");
        assert!(
            diff <= 1e-12,
            "{case} {split} on {ranks} ranks: {key} {diff}"
        );
    }
    // The ranks order, chunk and choose as the whole interface does: the same bits, but on a
    // straight 2D line, which one process couples by the sorted merge and the ranks' parts
    // by the fused kernel (the same integrals, to round-off), and where one rank holds every
    // master face received from another ("apart": M differs in the last bit in places, not
    // yet explained; docs/distributed.md).
    if case != "line2d" && split != "apart" {
        for key in ["d_bit_identical", "m_bit_identical"] {
            assert_eq!(json[key], true, "{case} {split} on {ranks} ranks: {json}");
        }
    }
    json
}

#[test]
fn plane3d_in_strips_on_one_to_four_ranks_matches_one_process() {
    for ranks in 1..=4 {
        let json = matches_one_process(ranks, "plane3d", "strips", 12);
        let per_rank = json["per_rank"].as_array().expect("per rank");
        assert_eq!(per_rank.len(), ranks);
        if ranks > 1 {
            // Strips share their boundaries: every rank receives master faces and, but for
            // the ends, ghost slave faces.
            assert!(per_rank
                .iter()
                .all(|r| r["ghost_master_faces"].as_u64() > Some(0)));
        }
    }
}

#[test]
fn arc2d_round_robin_on_one_to_four_ranks_matches_one_process() {
    for ranks in 1..=4 {
        matches_one_process(ranks, "arc2d", "round-robin", 40);
    }
}

#[test]
fn other_cases_and_splits_on_three_ranks_match_one_process() {
    for (case, split, n) in [
        ("cylinder", "random", 16),
        ("line2d", "strips", 50),
        ("plane3d-dual", "random", 10),
        ("plane3d", "round-robin", 8),
        ("arc2d", "apart", 30),
        ("plane3d", "apart", 8),
        ("arc2d-gap", "strips", 40),
        ("cylinder", "strips-together", 16),
    ] {
        let json = matches_one_process(3, case, split, n);
        if case == "arc2d-gap" {
            // The widened search of the open gap took a second exchange of master faces.
            let per_rank = json["per_rank"].as_array().expect("per rank");
            assert!(per_rank.iter().all(|r| r["passes"] == 2), "{json}");
        }
    }
}

#[test]
fn a_rank_that_couples_nothing_names_its_faces_and_widens_the_search() {
    let json = matches_one_process(3, "plane3d-far", "strips", 12);
    let per_rank = json["per_rank"].as_array().expect("per rank");
    // The last strip (x above 2/3) is beyond the master (x below 0.4): nothing coupled there,
    // counted, and the uncovered area asks every rank for the second exchange.
    assert_eq!(per_rank[2]["pairs"], 0, "{json}");
    assert!(per_rank[2]["uncoupled_faces"].as_u64() > Some(0), "{json}");
    assert_eq!(per_rank[0]["uncoupled_faces"], 0, "{json}");
    assert!(per_rank.iter().all(|r| r["passes"] == 2), "{json}");
}

#[test]
fn a_failure_on_one_rank_stops_every_rank_with_its_name() {
    let out = mpirun(
        3,
        &["--case", "plane3d", "--n", "6", "--fail-rank", "1"],
        Duration::from_secs(60),
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    for rank in 0..3 {
        let line = stderr
            .lines()
            .find(|l| l.starts_with(&format!("rank {rank}: error:")))
            .unwrap_or_else(|| panic!("rank {rank} reported no error:\n{stderr}"));
        assert!(line.contains("rank 1"), "{line}");
        assert!(line.contains("degenerate"), "{line}");
    }
}
