//! Ready-made problems of the seed, built in code: meshes, data and solver settings in one
//! place, for the examples, the tests and the command line.
//!
//! - [`tied_heat`]: heat conduction in two bodies tied by mortar across a straight or curved
//!   non-conforming interface, with a manufactured solution.
//! - [`file`]: scene files (TOML) naming Gmsh meshes, groups, materials, boundary conditions
//!   and the interface, as run by `mortar run SCENE.toml --out DIR`.

pub mod file;
pub mod tied_heat;
