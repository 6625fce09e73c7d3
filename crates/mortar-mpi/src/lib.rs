//! The mortar coupling over MPI ranks. Each rank holds a part of the slave and master
//! surfaces (any distribution: the caller's own partition, as a finite-element code would
//! pass it); [`couple_distributed`] finds the faces each rank needs from the others (the
//! ranks' boxes exchanged, faces sent where they reach), couples each rank's slave faces with
//! the core's [`assemble_coupling`](mortar_core::assemble_coupling) and returns the rows of D
//! and M of the slave nodes the rank owns, in the global numbering (node tags); [`gather`]
//! puts them together on one rank.
//!
//! MPI is the system's (Open MPI from Debian's `libopenmpi-dev`), through rsmpi, with the
//! `mpi` feature (`Mpi`, `MpiExchange`, which exist only in that build); without it the
//! crate builds with no C dependency and offers the one-rank [`SelfExchange`], so that a
//! caller writes one code path for both builds. Everything here is written on the
//! [`Exchange`] trait. What is checked and measured: `docs/distributed.md`.
//!
//! ```
//! use mortar_core::mesh::SurfaceMesh;
//! use mortar_elements::LINE2;
//! use mortar_mpi::{couple_distributed, gather, DistributedOptions, SelfExchange};
//!
//! // Two non-matching lines on one rank.
//! let line = |n: usize, first: u64, flip: bool| -> mortar_core::Result<SurfaceMesh> {
//!     let mut mesh = SurfaceMesh::new();
//!     for i in 0..=n {
//!         mesh.add_node(first + i as u64, [i as f64 / n as f64, 0.0, 0.0])?;
//!     }
//!     for i in 0..n as u64 {
//!         let (a, b) = (first + i, first + i + 1);
//!         mesh.add_face(&LINE2, &if flip { [b, a] } else { [a, b] })?;
//!     }
//!     Ok(mesh)
//! };
//! let (slave, master) = (line(4, 1, false)?, line(7, 100, true)?);
//! let rows = couple_distributed(&SelfExchange, &slave, &master, &DistributedOptions::default())?;
//! assert_eq!(rows.rows, vec![1, 2, 3, 4, 5]);
//! let all = gather(&SelfExchange, &rows, 0)?.expect("rank 0 is the root");
//! assert_eq!(all.m.shape(), (5, 8));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod couple;
mod error;
mod exchange;
mod model;
#[cfg(feature = "mpi")]
mod mpi;
mod rows;
mod wire;
mod world;

pub use couple::{couple_distributed, DistributedOptions};
pub use error::{DistributedError, Result};
pub use exchange::{agree, Exchange, SelfExchange};
pub use model::{modelled_counts, ModelledRank};
#[cfg(feature = "mpi")]
pub use mpi::{Mpi, MpiExchange};
pub use rows::{gather, GatheredCoupling, RankCounts, RankRows, RankSeconds, TaggedRows};
pub use world::{launched_ranks, World, BUILT_WITH_MPI};
