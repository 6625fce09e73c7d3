//! Unit tests of the built-in elements: shape functions (partition of unity, Kronecker delta,
//! gradients, completeness, degree, conformity), geometric maps (interpolation, measure,
//! normals, inverse maps) and the registry (one binary, a folder of modules).
//!
//! Every check is a generic function called once per element type, listed by hand.

mod unit {
    mod geometry;
    #[cfg(feature = "volume")]
    mod lagrange;
    mod registry;
    mod shape;

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
