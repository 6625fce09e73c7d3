//! # mortar-scenes
//!
//! Ready-made problems of the mortar toolkit, built in code or read from scene files: meshes,
//! data and solver settings in one place, for the examples, the tests, the `mortar` command
//! and Python. A run shows its progress and stops on request through [`progress`] and
//! [`interrupt`], which the command line fills (a bar, Ctrl-C) and a library leaves quiet; the
//! PNG plots are the feature `plots` (on by default).
//!
//! - [`pellet`]: the fuel pellet in its cladding, thermomechanical (2D, r-z or 3D: expansion,
//!   gap closure, gap conductance on the mechanical gap, contact, plenum pressure; Newton or
//!   JFNK, checked against an independent radial model), or thermal only against the closed
//!   form.
//! - [`tied_heat`]: heat conduction in two bodies tied by mortar across a straight or curved
//!   non-conforming interface, with a manufactured solution.
//! - [`hertz`]: the Hertz contact of a cylinder (2D, plane strain) or a sphere (3D) pressed
//!   onto a block (frictionless mortar contact), checked against the closed forms.
//! - [`shrink_fit`]: a disc pressed into a ring (plane strain, frictionless mortar contact on
//!   non-matching faceted circles), checked against Lamé's closed form.
//! - [`file`](mod@file): scene files (TOML) naming Gmsh meshes, groups, materials, boundary conditions
//!   and the interface, as run by `mortar run SCENE.toml --out DIR`.

pub mod file;
pub mod hertz;
pub mod interrupt;
pub mod linear_solver;
mod named_law;
mod parse;
pub mod pellet;
#[cfg(feature = "plots")]
pub mod plot;
pub mod progress;
mod scene;
pub mod shrink_fit;
pub mod tied_heat;

pub use named_law::NamedLaw;
pub use scene::{run_scene, write_scene_output, Scene, SceneContext, SceneRun};
