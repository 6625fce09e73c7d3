//! The verification page against its data: docs/verification.md is what
//! `tests/verification/claims.toml` and `tests/verification/template.md` generate, every
//! figure it states lies within its test's bound (and within 100 times of it, or the page
//! states the bound), and every test named there exists and reads its bound from the data.
//! After changing the data or the template: `cargo run --example verification_doc`. The
//! performance page is checked the same way against its template and the benchmarks' JSON
//! files (`cargo run --example performance_doc`).

mod verification {
    pub mod claims;
}

use verification::claims::{
    claim, claims, format_values, problems, render, render_performance, select,
};

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

/// Fails, naming the first line that differs, when the committed `docs/{page}` is not
/// `generated`; `command` writes it.
fn assert_committed(page: &str, generated: &str, command: &str) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("docs")
        .join(page);
    let committed = std::fs::read_to_string(&path).unwrap();
    if committed != generated {
        let line = committed
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(committed.lines().count().min(generated.lines().count()));
        panic!(
            "docs/{page} differs from the generated page from line {}:\n  committed: {:?}\n  \
             generated: {:?}\nrun `{command}`",
            line + 1,
            committed.lines().nth(line),
            generated.lines().nth(line)
        );
    }
}

#[test]
fn the_committed_page_is_the_generated_one() {
    let page = render().unwrap_or_else(|e| panic!("rendering the verification page: {e}"));
    assert_committed(
        "verification.md",
        &page,
        "cargo run --release --example verification_doc",
    );
}

/// docs/performance.md is what `tests/verification/performance_template.md` and the
/// benchmarks' JSON files under `docs/` generate.
#[test]
fn the_committed_performance_page_is_the_generated_one() {
    let page =
        render_performance().unwrap_or_else(|e| panic!("rendering the performance page: {e}"));
    assert_committed(
        "performance.md",
        &page,
        "cargo run --release --example performance_doc",
    );
}

/// The JSON placeholders' selectors, reducers, scales and styles, on a small array of records
/// like a benchmark's.
#[test]
fn json_placeholders_select_reduce_and_format() {
    let runs = serde_json::json!([
        {"case": "a", "n": 10, "threads": 1, "s": 0.25, "ok": true, "deep": {"x": 1500.0}},
        {"case": "a", "n": 10, "threads": 2, "s": 0.125, "ok": true, "deep": {"x": 2.0}},
        {"case": "b", "n": 20, "threads": "default", "s": 4.0, "ok": false, "deep": {"x": 3.0}},
    ]);
    let show = |pointer: &str, format: &str| {
        let values: Vec<_> = select(&runs, pointer)?.into_iter().cloned().collect();
        format_values(&values, format).map(|(text, _)| text)
    };
    let ok = |pointer: &str, format: &str| show(pointer, format).unwrap();
    assert_eq!(ok("/1/s", ".3"), "0.125");
    assert_eq!(ok("/[case=a,threads=1]/s", "e1"), "2.5e-1");
    assert_eq!(ok("/[n>=10,n<=10,threads!=2]/deep/x", ","), "1,500");
    assert_eq!(ok("/[case=b]/threads", "text"), "default");
    assert_eq!(ok("/[]/s", "max *1e3 ,"), "4,000");
    assert_eq!(ok("/[case=a]/s", "min .3"), "0.125");
    assert_eq!(ok("/[ok=true]", "count .0"), "2");
    assert_eq!(ok("/[deep/x>=2,deep/x<=3]", "count .0"), "2");
    assert_eq!(ok("/[threads=1]/s", "/4 .4"), "0.0625");
    assert_eq!(ok("/0/s", ">=0.25"), "met");
    assert_eq!(ok("/0/s", "<=0.2"), "not met");
    // Several values without a reducer, none to reduce, and a style that is not one.
    assert!(show("/[case=a]/s", ".3").unwrap_err().contains("2 values"));
    assert!(show("/[case=c]/s", "max .3")
        .unwrap_err()
        .contains("keeps no element"));
    assert!(show("/[case=c]/s", ".3").unwrap_err().contains("0 values"));
    assert!(show("/0/s", "%3").is_err());
    assert!(show("/0/missing", ".3").is_err());
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
