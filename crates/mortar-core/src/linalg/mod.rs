//! Sparse linear algebra: the matrix type of D and M (sprs CSR), deterministic triplet
//! assembly, and the bridge to faer's sparse solvers. faer's API stays inside `faer_backend.rs`.

mod faer_backend;
mod triplets;

pub use faer_backend::{solve_sparse_lu, FaerError};
pub use triplets::{CompressWorkspace, PartList, Triplets};

/// The sparse matrix type of D and M: compressed rows, `f64` values, `usize` indices.
pub type SparseMatrix = sprs::CsMat<f64>;
