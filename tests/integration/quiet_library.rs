//! The library crates write nothing to standard output or standard error: what a run has to
//! say goes into its results (counts, warnings, errors), and only the command-line program
//! prints. A timing print left in `memory.rs` once wrote a line to standard error at every
//! large coupling. (Clippy's `print_stdout`, `print_stderr` and `dbg_macro` are denied in the
//! library crates too; this test holds without clippy.)

use std::path::{Path, PathBuf};

/// The `.rs` files under `dir`, recursively.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn library_crates_do_not_print() {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates");
    let mut files = Vec::new();
    for krate in std::fs::read_dir(&crates).unwrap() {
        let src = krate.unwrap().path().join("src");
        if src.is_dir() {
            sources(&src, &mut files);
        }
    }
    assert!(files.len() > 50, "found only {} sources", files.len());
    let mut prints = Vec::new();
    for file in &files {
        // Unit-test modules in their own files may report what they measured.
        if file.file_name().is_some_and(|n| n == "tests.rs") {
            continue;
        }
        let text = std::fs::read_to_string(file).unwrap();
        for (i, line) in text.lines().enumerate() {
            let code = line.trim_start();
            if code.starts_with("//") {
                continue;
            }
            let calls = ["println!(", "print!(", "dbg!("];
            if calls.iter().any(|c| code.contains(c)) {
                prints.push(format!("{}:{}: {}", file.display(), i + 1, code));
            }
        }
    }
    assert!(
        prints.is_empty(),
        "library code prints:\n{}",
        prints.join("\n")
    );
}
