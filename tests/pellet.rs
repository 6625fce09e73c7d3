//! The pellet scene: the steady state against the closed form of docs/models.md section 3 and its
//! convergence under refinement, Newton against JFNK, the scene file, and the independent 1D
//! radial reference of the coupled thermomechanical pellet, and the limits of its models.

/// The verification claims: the bounds of the figures docs/verification.md states.
#[path = "verification/claims.rs"]
mod claims;

mod pellet {
    mod closed_form;
    mod coupled;
    mod file_mesh;
    mod free_expansion;
    mod limits;
    mod radial;
    mod relocation;
    mod scene_file;
    mod solvers;
}
