//! The sparse result of the coupling: the matrix type of D and M (sprs CSR) and its
//! deterministic assembly from triplets. (The solvers are in `mortar-fem`.)

pub(crate) mod csr;
mod triplets;

pub(crate) use triplets::sort_short_by_key;
pub use triplets::{CompressWorkspace, PartList, RowAccumulator, Triplets};

/// The sparse matrix type of D and M: compressed rows, `f64` values, `usize` indices.
pub type SparseMatrix = sprs::CsMat<f64>;
