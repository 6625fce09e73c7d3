//! Runs the Python package's tests (pytest) from `cargo test`, so that the README's one test
//! command covers them.
//!
//! Steps, each reusing what the previous run left:
//! 1. a virtual environment `python-venv/` in the cargo target folder, made with
//!    `python3 -m venv` (`$PYTHON` names another interpreter), with the pinned test
//!    requirements of `tests/requirements.txt` installed from the package registry; it is
//!    remade when that file changes;
//! 2. the package built and installed into it by `maturin develop --release --features
//!    workspace-test`, in the same cargo target folder: with the features the workspace's
//!    build gave the library, so that only PyO3 and the extension are compiled again;
//! 3. `python -m pytest tests` in this folder.
//!
//! A missing `python3`, `venv` or `pip`, a failed install or build, or a failed Python test
//! fails this test with the output of the step.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Instant;

/// The cargo target folder this test binary was built into (`<target>/<profile>/deps/`).
fn target_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    exe.ancestors()
        .nth(3)
        .expect("the test binary lies in <target>/<profile>/deps")
        .to_path_buf()
}

/// Runs `cmd`, failing the test with its output if it cannot start or fails.
fn run(what: &str, cmd: &mut Command) -> Output {
    let start = Instant::now();
    let out = cmd.output().unwrap_or_else(|e| {
        panic!("{what}: cannot run {cmd:?}: {e}\n(the Python tests need python3 with venv and pip)")
    });
    eprintln!("{what}: {:.1} s", start.elapsed().as_secs_f64());
    if !out.status.success() {
        panic!(
            "{what} failed ({}): {cmd:?}\n--- stdout ---\n{}\n--- stderr ---\n{}",
            out.status,
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
    }
    out
}

/// The venv's `bin` folder (`Scripts` on Windows).
fn bin(venv: &Path) -> PathBuf {
    if cfg!(windows) {
        venv.join("Scripts")
    } else {
        venv.join("bin")
    }
}

/// Makes (or reuses) the venv with the pinned requirements.
fn venv(target: &Path, requirements: &Path) -> PathBuf {
    let venv = target.join("python-venv");
    let stamp = venv.join("mortar-requirements.txt");
    let wanted = std::fs::read_to_string(requirements).expect("tests/requirements.txt");
    if std::fs::read_to_string(&stamp).ok().as_deref() == Some(wanted.as_str()) {
        return venv;
    }
    let python = std::env::var("PYTHON").unwrap_or_else(|_| "python3".to_string());
    run(
        "making the venv",
        Command::new(&python)
            .args(["-m", "venv", "--clear"])
            .arg(&venv),
    );
    let pip = bin(&venv).join("python");
    run(
        "installing the test requirements",
        Command::new(&pip)
            .args([
                "-m",
                "pip",
                "install",
                "--disable-pip-version-check",
                "-q",
                "-r",
            ])
            .arg(requirements),
    );
    std::fs::write(&stamp, wanted).expect("writing the venv's stamp");
    venv
}

#[test]
fn pytest() {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let target = target_dir();
    let venv = venv(&target, &here.join("tests/requirements.txt"));
    let bin = bin(&venv);
    let path = std::env::join_paths(std::iter::once(bin.clone()).chain(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    )))
    .expect("PATH");
    run(
        "building and installing the package (maturin develop --release)",
        Command::new(bin.join("maturin"))
            .args(["develop", "--release", "--features", "workspace-test"])
            .arg("--manifest-path")
            .arg(here.join("Cargo.toml"))
            .env("VIRTUAL_ENV", &venv)
            .env("PATH", &path)
            .env("CARGO_TARGET_DIR", &target)
            .current_dir(here),
    );
    let out = run(
        "pytest",
        Command::new(bin.join("python"))
            .args(["-m", "pytest", "tests", "-q", "-p", "no:cacheprovider"])
            .env("PATH", &path)
            .current_dir(here),
    );
    // The summary line ("N passed in S s"), so that cargo's output shows what ran.
    let stdout = String::from_utf8_lossy(&out.stdout);
    let summary = stdout.lines().last().unwrap_or_default();
    eprintln!("pytest: {summary}");
    assert!(
        summary.contains("passed") && !summary.contains("failed") && !summary.contains("skipped"),
        "pytest ran no test, or skipped some:\n{stdout}"
    );
}
