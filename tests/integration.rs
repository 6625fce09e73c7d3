//! Integration tests of the facade: Gmsh input and output, Matrix Market output, and the
//! `mortar` command-line program (run as a process).

#[path = "integration/common.rs"]
mod common;

/// The verification claims: the bounds of the figures docs/verification.md states.
#[path = "verification/claims.rs"]
mod claims;

#[path = "integration/gmsh_read.rs"]
mod gmsh_read;

#[path = "integration/gmsh_errors.rs"]
mod gmsh_errors;

#[path = "integration/cli.rs"]
mod cli;

#[path = "integration/cli_errors.rs"]
mod cli_errors;

#[path = "integration/cli_mpirun.rs"]
mod cli_mpirun;

#[path = "integration/scene.rs"]
mod scene;

#[path = "integration/scene_errors.rs"]
mod scene_errors;

#[path = "integration/gmsh_meshes.rs"]
mod gmsh_meshes;

#[path = "integration/orient.rs"]
mod orient;

#[path = "integration/contact_scene.rs"]
mod contact_scene;

#[path = "integration/affine_faces.rs"]
mod affine_faces;

#[path = "integration/second_order.rs"]
mod second_order;

#[path = "integration/quiet_library.rs"]
mod quiet_library;

#[path = "integration/overlap.rs"]
mod overlap;

#[path = "integration/small_overlaps.rs"]
mod small_overlaps;

#[path = "integration/open_gap.rs"]
mod open_gap;

#[path = "integration/scene_keys.rs"]
mod scene_keys;
