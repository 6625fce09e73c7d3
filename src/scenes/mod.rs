//! Ready-made problems, built in code: meshes, data and solver settings in one
//! place, for the examples, the tests and the command line.
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
mod named_law;
pub mod pellet;
pub mod shrink_fit;
pub mod tied_heat;

pub use named_law::NamedLaw;
