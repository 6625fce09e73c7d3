//! The verification page against its data: docs/verification.md is what
//! `tests/verification/claims.toml` and `tests/verification/template.md` generate, every
//! figure it states lies within its test's bound (and within 100 times of it, or the page
//! states the bound), and every test named there exists and reads its bound from the data.
//! After changing the data or the template: `cargo run --example verification_doc`.

mod verification {
    pub mod claims;
}

use verification::claims::{claim, claims, problems, render};

#[test]
fn every_claim_is_within_its_bound_and_names_its_test() {
    let problems = problems();
    assert!(
        problems.is_empty(),
        "{} problem(s) in tests/verification/claims.toml:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn the_committed_page_is_the_generated_one() {
    let page = render().unwrap_or_else(|e| panic!("rendering the verification page: {e}"));
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/verification.md");
    let committed = std::fs::read_to_string(&path).unwrap();
    if committed != page {
        let line = committed
            .lines()
            .zip(page.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(committed.lines().count().min(page.lines().count()));
        panic!(
            "docs/verification.md differs from the generated page from line {}:\n  committed: \
             {:?}\n  generated: {:?}\nrun `cargo run --example verification_doc`",
            line + 1,
            committed.lines().nth(line),
            page.lines().nth(line)
        );
    }
}

/// The checks catch what they are for: a figure above its bound, and a bound more than 100
/// times its figure that the page does not state.
#[test]
fn the_checks_catch_a_stray_bound() {
    assert!(!claims().is_empty());
    let dual = claim("coupling.dual");
    assert!(dual.figure_value(0).unwrap() <= dual.bound);
    let mut tighter = dual.clone();
    tighter.bound = dual.figure_value(0).unwrap() / 2.0;
    assert!(verification::claims::problems_of(&tighter, true)
        .iter()
        .any(|p| p.contains("above its bound")));
    let mut looser = claim("contact.patch_p2").clone();
    looser.bound *= 1e3;
    assert!(verification::claims::problems_of(&looser, false)
        .iter()
        .any(|p| p.contains("100 times")));
}
