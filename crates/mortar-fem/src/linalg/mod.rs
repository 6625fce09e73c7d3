//! Sparse linear algebra behind one solver interface ([`solver`]: [`SparseSolver`],
//! [`Factorization`]), with faer's sparse direct factorisations as its backend (faer's API
//! stays inside `faer_backend.rs`, METIS's inside [`nested_dissection`]) and a restarted
//! GMRES. The matrix type and its assembly from triplets are those of the coupling
//! ([`SparseMatrix`], [`Triplets`] of `mortar-core`), re-exported here.
//!
//! - [`LuFactorization`], [`CholeskyFactorization`]: factorise once, solve many times, and
//!   [`refactor`](LuFactorization::refactor) a new matrix of the same pattern reusing the
//!   symbolic analysis (Newton steps, new time step sizes).
//! - [`BorderedLu`]: the LU of a sparse matrix bordered by a few dense rows and columns,
//!   the border eliminated by its Schur complement outside the sparse factorisation.
//! - [`SubstructuredCholesky`]: the same for two domains coupled through a small separator
//!   (two tied bodies), the domains factorised in parallel.
//! - [`gmres`]: right-preconditioned restarted GMRES(m) on any [`LinearOperator`] (an
//!   assembled matrix or a matrix-free product), with any [`Preconditioner`] (the
//!   factorisations above, or [`IdentityPreconditioner`]).

mod bordered;
mod conditioning;
mod faer_backend;
mod gmres;
pub mod nested_dissection;
pub mod solver;
mod substructured;
mod system_info;

pub use bordered::BorderedLu;
pub use conditioning::{inf_norm, well_conditioned, MAX_CONDITION};
pub use faer_backend::{
    fill_reducing_ordering, solve_sparse_lu, CholeskyFactorization, FaerError, FaerSolver,
    LuFactorization, SaddlePointFactorization, NESTED_DISSECTION_MIN, PARALLEL_MIN_COLUMN,
};
pub use gmres::{
    gmres, GmresOptions, GmresReport, IdentityPreconditioner, LinearOperator, Preconditioner,
};
pub use mortar_core::linalg::{
    CompressWorkspace, PartList, RowAccumulator, SparseMatrix, Triplets,
};
pub use solver::{FactorStats, Factorization, MatrixKind, SolverError, SparseSolver};
pub use substructured::{SubstructuredCholesky, SUBSTRUCTURED_MIN};
pub use system_info::{SystemInfo, UnknownPlaces};
