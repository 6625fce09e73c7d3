//! Writes docs/verification.md from the verification claims (`tests/verification/claims.toml`,
//! the bounds the tests assert and the figures they guard) and the page's template
//! (`tests/verification/template.md`), reading the figures that examples wrote to JSON under
//! `docs/`. `cargo test --test verification` fails when the committed page differs from what
//! this writes, or a figure strays from its bound.
//!
//! ```text
//! cargo run --example verification_doc            # writes docs/verification.md
//! cargo run --example verification_doc -- --check # only reports the problems
//! ```

#[path = "../tests/verification/claims.rs"]
mod claims;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let problems = claims::problems();
    for p in &problems {
        eprintln!("{p}");
    }
    if std::env::args().any(|a| a == "--check") {
        return if problems.is_empty() {
            Ok(())
        } else {
            Err(format!("{} problem(s)", problems.len()).into())
        };
    }
    let page = claims::render()?;
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/verification.md");
    std::fs::write(&path, page)?;
    println!(
        "wrote {} ({} claims, {} problem(s))",
        path.display(),
        claims::claims().len(),
        problems.len()
    );
    Ok(())
}
