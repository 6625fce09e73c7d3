//! Convergence and consistency tests of tied heat conduction (one binary, a folder of
//! modules): measured convergence rates on straight and curved non-conforming interfaces in 2D
//! and 3D, the patch test (a linear field reproduced to round-off), the two solution paths
//! (saddle point and dual condensation) agreeing, backward Euler, and deterministic parallel
//! assembly. Meshes are small so that the binary runs in seconds in the test profile.

/// The verification claims: the bounds of the figures docs/verification.md states.
#[path = "verification/claims.rs"]
mod claims;

mod convergence {
    mod axisymmetric_coupling;
    mod axisymmetric_elastic;
    mod axisymmetric_heat;
    mod axisymmetric_tied;
    mod blocks;
    mod components;
    mod contact;
    mod contact_laws;
    mod contrast;
    mod curved_reference;
    mod determinism;
    mod law_ranges;
    mod mesh_ratio;
    mod patch;
    mod paths;
    mod quad_subdivision;
    mod rates;
    mod shrink_fit;
    mod transient;
}
