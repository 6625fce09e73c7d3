//! The pellet scene: the steady state against the closed form of PHYSICS.md section 5 and its
//! convergence under refinement, Newton against JFNK, the scene file.

mod pellet {
    mod closed_form;
    mod free_expansion;
    mod scene_file;
    mod solvers;
}
