//! Assembly of the mortar operators D and M.
//!
//! `D[j,k] = int Phi_j N_k^s` and `M[j,l] = int Phi_j N_l^m` over the overlap of the two
//! surfaces, rows following the slave interface nodes and columns the slave (D) or master (M)
//! interface nodes, each by ascending node tag.
//!
//! Work is split into chunks of slave faces fixed by their places in space, processed in
//! parallel on a rayon pool of the requested size; every chunk writes its own triplets and
//! chunks are concatenated in order, so the sum of each entry is taken in the same order
//! whatever the thread count: D and M are bit-for-bit identical serial or parallel, and a
//! part of an interface that knows the whole ([`WholeInterface`]) computes its rows as the
//! whole does.

mod coupling;
mod key_index;
mod local;
mod master_coverage;
mod options;
mod pool;
mod straight_line;
mod warning;
mod whole;

pub use coupling::{
    assemble_coupling, assemble_coupling_reusing, Coupling, CouplingStats, PhaseSeconds,
    Recombined, ThreadSeconds, MAX_THREADS_PER_CORE,
};
pub use local::{integrate_batch_into, integrate_face_into, LocalBlocks};
pub use master_coverage::MASTER_OVERLAP_RATIO;
pub use options::CouplingOptions;
pub use warning::CouplingWarning;
pub(crate) use whole::{anchor, ChunkPlan};
pub use whole::{WholeInterface, BUCKET_FACES};
