//! Unit tests of the element-free kernels of `mortar-core`: quadrature exactness, polygon
//! operations, convex clipping and the auxiliary plane (one binary, a folder of modules).

mod unit {
    mod clipping;
    mod plane;
    mod polygon;
    mod quadrature;
    pub mod strategies;

    /// The proptest configuration of a block: `cases` cases, or as many as the environment
    /// variable `PROPTEST_CASES` says (to run the tests harder: `PROPTEST_CASES=1000 cargo test`).
    pub fn config(cases: u32) -> proptest::test_runner::Config {
        let cases = std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(cases);
        proptest::test_runner::Config {
            cases,
            ..Default::default()
        }
    }
}
