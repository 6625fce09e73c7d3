//! proptest strategies for property-based patch tests (feature `proptest-support`).
//!
//! The strategies draw the inputs on which mortar operators have known exact answers, so that
//! a user's own element, multiplier space or integration strategy can be checked the way this
//! crate's own property tests check the built-in ones:
//!
//! - [`perturbed_square`]: structured Tri3 / Quad4 / mixed meshes of the unit square with
//!   jittered nodes; boundary nodes stay on the boundary, so two such meshes *cover* the same
//!   square (every slave point has a master point and vice versa);
//! - [`perturbed_line`]: Line2 meshes of `[0, 1]` with jittered interior nodes;
//! - [`covered_pair_3d`], [`covered_pair_2d`], [`covered_pair`]: a slave and a master mesh of
//!   different resolution or cell kind covering the same square (or segment), facing each
//!   other;
//! - [`rigid_motion_3d`], [`rigid_motion_2d`], [`scale_factor`]: rigid motions (uniformly random
//!   rotations, translations up to `1e6`) and uniform scale factors, log-uniform in
//!   `[1e-6, 1e6]`, for invariance tests;
//! - [`relabelled`]: a copy of a mesh with new node tags, nodes and faces stored in another
//!   order and each face's corner list rotated, with the map from old to new tags;
//!   [`shuffled`]: a copy with nodes and faces in a seeded random order (the benchmark's
//!   worst-case file order);
//! - [`patch_test`]: the checks, with their exact answers: constants and linear fields
//!   reproduced (`D 1 = M 1`, `D x_s = M x_m`), row sums of D against the slave nodal areas
//!   computed independently ([`nodal_areas`]), biorthogonality of a dual D.
//!
//! ```
//! use mortar::testing::{covered_pair_3d, rigid_motion_3d};
//! use mortar::{assemble_coupling, CouplingOptions};
//! use proptest::prelude::*;
//! use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
//!
//! let config = Config { cases: 8, ..Config::default() };
//! let rng = TestRng::deterministic_rng(RngAlgorithm::ChaCha);
//! let mut runner = TestRunner::new_with_rng(config, rng);
//! runner
//!     .run(&(covered_pair_3d(), rigid_motion_3d()), |(pair, motion)| {
//!         let moved = pair.transformed(|x| motion.apply(x)).unwrap();
//!         let interface = moved.interface().unwrap();
//!         let coupling = assemble_coupling(&interface, &CouplingOptions::default()).unwrap();
//!         // Constants are reproduced on a covered interface: D 1 = M 1, row by row.
//!         let d = coupling.d.outer_iterator().map(|row| row.data().iter().sum::<f64>());
//!         let m = coupling.m.outer_iterator().map(|row| row.data().iter().sum::<f64>());
//!         for (a, b) in d.zip(m) {
//!             prop_assert!((a - b).abs() <= 1e-12 * coupling.stats.area);
//!         }
//!         Ok(())
//!     })
//!     .unwrap();
//! ```

mod checks;
mod mesh;
mod motion;
mod pair;
mod relabel;

pub use checks::{nodal_areas, patch_test, PatchReport};
pub use mesh::{
    cell_kind, perturbed_line, perturbed_square, polyline, CellKind, MAX_LINE_JITTER,
    MAX_SQUARE_JITTER,
};
pub use motion::{
    log_uniform, rigid_motion_2d, rigid_motion_3d, rotation_2d, scale_factor, translation,
    unit_quaternion, RigidMotion,
};
pub use pair::{
    covered_pair, covered_pair_2d, covered_pair_3d, covered_pair_3d_with, MeshPair, PairConfig,
};
pub use relabel::{relabelled, relabelling, shuffled, shuffled_faces, Relabelled, Relabelling};
