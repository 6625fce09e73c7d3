//! The examples a user copies from, run by the test command: each light example's
//! code is compiled into this test as a module (its own `main` unused here) and run, with a
//! small size where it takes one and its outputs in a temporary folder. Each test fails when
//! its example returns an error or panics; `extend_element`, `extend_law`, `pellet`,
//! `shrink_fit` (the mean pressure converging at the faceting's rate), `tie_two_squares` and
//! `tied_heat` (the patch test to 1e-12, the refinement rates of the element order) return one
//! when their own checks of the results fail, `write_scene_meshes` is compared here with the committed meshes, and
//! `hertz2d` and `hertz3d` (refinement studies) only have to run: the accuracy of their scenes
//! is checked in `tests/convergence`. About 6 s in all.
//!
//! Not run here, only compiled (`cargo test` builds every example): the benchmarks
//! (`bench_contact`, `bench_coupling`, `bench_pellet`, `bench_tied_heat`; their `--quick` runs
//! take 4 to 9 s each; `bench_small_calls`, about 3 s; `bench_pellet_dials`, about 3 s) and `curved_segmentation` (48 s at its
//! default, n = 4; run by `bench_coupling --tradeoff`), which print figures and check
//! nothing; what they measure is checked in `tests/` (the curved segmentation in
//! `tests/integration/second_order.rs` and `tests/convergence/curved_reference.rs`).

use std::path::PathBuf;

use clap::Parser as _;

#[allow(dead_code)]
#[path = "../examples/extend_element.rs"]
mod extend_element;
#[allow(dead_code)]
#[path = "../examples/extend_law.rs"]
mod extend_law;
#[allow(dead_code)]
#[path = "../examples/hertz2d.rs"]
mod hertz2d;
#[allow(dead_code)]
#[path = "../examples/hertz3d.rs"]
mod hertz3d;
#[allow(dead_code)]
#[path = "../examples/pellet.rs"]
mod pellet;
#[allow(dead_code)]
#[path = "../examples/shrink_fit.rs"]
mod shrink_fit;
#[allow(dead_code)]
#[path = "../examples/tie_two_squares.rs"]
mod tie_two_squares;
#[allow(dead_code)]
#[path = "../examples/tied_heat.rs"]
mod tied_heat;
#[allow(dead_code)]
#[path = "../examples/write_scene_meshes.rs"]
mod write_scene_meshes;

/// A fresh folder for one example's outputs.
fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mortar-example-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn strings(args: &[&str]) -> Vec<String> {
    args.iter().map(|s| s.to_string()).collect()
}

#[test]
fn extend_element_runs() {
    let out = out_dir("extend-element");
    extend_element::run(&out).unwrap();
    assert!(out.join("couple/D.mtx").is_file() && out.join("scene/report.json").is_file());
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn extend_law_runs() {
    let out = out_dir("extend-law");
    extend_law::run(&strings(&[out.to_str().unwrap()])).unwrap();
    assert!(out.join("report.json").is_file());
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn hertz2d_runs() {
    hertz2d::run(hertz2d::Args::parse_from(["hertz2d", "--levels", "2"])).unwrap();
}

#[test]
fn hertz3d_runs() {
    let args = hertz3d::Args::parse_from(["hertz3d", "--n", "4", "--levels", "2"]);
    hertz3d::run(args).unwrap();
}

#[test]
fn pellet_runs() {
    let out = out_dir("pellet");
    pellet::run(&strings(&[out.to_str().unwrap(), "1"])).unwrap();
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn shrink_fit_runs() {
    shrink_fit::run(&strings(&["8", "2", "3", "2"])).unwrap();
}

#[test]
fn tie_two_squares_runs() {
    tie_two_squares::run().unwrap();
}

#[test]
fn tied_heat_runs() {
    tied_heat::run(tied_heat::Args::parse_from([
        "tied_heat",
        "--dim",
        "2",
        "--quick",
    ]))
    .unwrap();
}

/// The example writes the meshes of `examples/scenes/tied_square.toml`: written again, they
/// are the committed ones byte for byte.
#[test]
fn write_scene_meshes_writes_the_committed_meshes() {
    let out = out_dir("scene-meshes");
    write_scene_meshes::run(&strings(&[out.to_str().unwrap()])).unwrap();
    let scenes = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    for name in ["tied_square_left.msh", "tied_square_right.msh"] {
        let written = std::fs::read(out.join(name)).unwrap();
        assert_eq!(written, std::fs::read(scenes.join(name)).unwrap(), "{name}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}
