//! Property tests of the mortar operators D and M on covered, non-matching interfaces drawn
//! by the strategies of `mortar::testing` (one binary, a folder of modules).
//!
//! Each `proptest!` block runs 16 to 64 cases, so that the whole binary stays within a few
//! seconds in the test profile. Failing cases are recorded in `*.proptest-regressions` files
//! next to the module sources; commit them.

/// The verification claims: the bounds of the figures docs/verification.md states.
#[path = "verification/claims.rs"]
mod claims;

mod properties {
    pub mod common;

    mod closed_form;
    mod conservation;
    mod curved;
    mod dual;
    mod element_based;
    mod errors;
    mod extremes;
    mod facing;
    mod fused_lines;
    mod gather;
    mod invariance;
    mod patch;
    mod reuse;
    mod rounding;
    mod search;
    mod straight_lines;
    mod strategies;
    mod threads;
    mod user_plug_ins;
}
