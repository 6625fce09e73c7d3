//! PETSc's linear solvers for the toolkit's sparse matrices: Krylov methods (CG, GMRES,
//! MINRES) with algebraic multigrid (PETSc's GAMG, hypre's BoomerAMG), a MUMPS LU, Jacobi,
//! or a Schur-complement fieldsplit for saddle points.
//!
//! The system's PETSc (3.18 or later, real double-precision scalars, MPI-built: Debian's
//! `petsc-dev`) is linked with the `petsc` feature; without it this crate builds with no C
//! dependency and [`PetscSolver::solve`] answers [`PetscError::NotBuilt`], so that a caller
//! can name the backend in every build and fail with a reason in those without it.
//!
//! PETSc starts at the first solve of the process (MPI with it, on one process, unless the
//! program started MPI itself) and stays up; [`finalize`] stops it for good. Solves from
//! several threads run one at a time. Each solve's options (the typed ones, then the
//! `PETSC_OPTIONS` environment variable, then the free-form [`SolveOptions::petsc_options`],
//! a later one overriding an earlier one) are PETSc's options database for that solve only.
//!
//! ```no_run
//! use mortar_core::linalg::SparseMatrix;
//! use mortar_petsc::{KrylovMethod, PetscSolver, Preconditioner, SolveOptions};
//!
//! // 2x2 SPD system.
//! let a = SparseMatrix::new((2, 2), vec![0, 2, 4], vec![0, 1, 0, 1], vec![4.0, 1.0, 1.0, 3.0]);
//! let mut options = SolveOptions::new(KrylovMethod::Cg, Preconditioner::Jacobi);
//! options.rtol = 1e-10;
//! options.petsc_options = "-ksp_norm_type unpreconditioned".into();
//! let solved = PetscSolver::new(options).solve(&a, &[1.0, 2.0])?;
//! println!("{}", solved.report); // PETSc 3.18.5 cg+jacobi: 2 iterations, ...
//! # Ok::<(), mortar_petsc::PetscError>(())
//! ```

mod backend;
mod blocks;
mod csr;
mod error;
mod options;
#[cfg(feature = "petsc")]
mod petsc;
mod report;

pub use backend::PetscBackend;
pub use error::PetscError;
pub use options::{
    accepted_residual, FieldSplit, KrylovMethod, Preconditioner, RigidBodyModes, SolveOptions,
    BOOMERAMG_ELASTICITY_3D,
};
pub use report::{ConvergedReason, SolveReport};

use mortar_core::linalg::SparseMatrix;

/// A solution and what PETSc did to find it.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The solution.
    pub x: Vec<f64>,
    /// What ran and how it went.
    pub report: SolveReport,
}

/// A linear solver of PETSc's, configured by [`SolveOptions`].
#[derive(Clone, Debug, PartialEq)]
pub struct PetscSolver {
    options: SolveOptions,
}

impl PetscSolver {
    /// A solver with these options.
    pub fn new(options: SolveOptions) -> Self {
        Self { options }
    }

    /// The solver's options.
    pub fn options(&self) -> &SolveOptions {
        &self.options
    }

    /// Solves `a x = b` from `x = 0`.
    ///
    /// # Errors
    /// [`PetscError::NotBuilt`] without the `petsc` feature; [`PetscError::InvalidInput`] if
    /// `a` is not square, `b` or the near null space's coordinates do not match it, or the
    /// field split is not a proper subset of the unknowns; [`PetscError::NotConverged`] with
    /// PETSc's reason and the iterations if the solver stopped short of the tolerance
    /// (an indefinite matrix under CG, a singular one under LU, too few iterations);
    /// [`PetscError::Call`] if a PETSc function failed; [`PetscError::Initialize`] or
    /// [`PetscError::Finalized`] if PETSc cannot run in this process.
    pub fn solve(&self, a: &SparseMatrix, b: &[f64]) -> Result<Solution, PetscError> {
        check_input(a, b, &self.options)?;
        let parts = csr::csr_parts(a);
        #[cfg(feature = "petsc")]
        {
            let (x, report) = petsc::solve(&parts, b, &self.options)?;
            Ok(Solution { x, report })
        }
        #[cfg(not(feature = "petsc"))]
        {
            let _ = parts;
            Err(PetscError::NotBuilt)
        }
    }
}

/// Whether this build has the PETSc backend (the `petsc` feature).
pub fn is_built() -> bool {
    cfg!(feature = "petsc")
}

/// Starts PETSc now (it starts at the first solve otherwise) and returns its version
/// (`PETSc 3.18.5`).
///
/// # Errors
/// [`PetscError::NotBuilt`] without the `petsc` feature; [`PetscError::Initialize`] if
/// PETSc or MPI cannot start; [`PetscError::Finalized`] after [`finalize`].
pub fn start() -> Result<String, PetscError> {
    #[cfg(feature = "petsc")]
    {
        petsc::ensure_started()
    }
    #[cfg(not(feature = "petsc"))]
    {
        Err(PetscError::NotBuilt)
    }
}

/// Finalises PETSc (and MPI, if PETSc's start began it) for the rest of the process: call it
/// at the end of a program that wants PETSc's exit-time output (`-log_view`) or runs under
/// `mpiexec`; later solves answer [`PetscError::Finalized`]. Nothing happens if PETSc never
/// started or is finalised already, or in a build without the `petsc` feature.
///
/// # Errors
/// [`PetscError::Call`] if PETSc's or MPI's finalisation fails.
pub fn finalize() -> Result<(), PetscError> {
    #[cfg(feature = "petsc")]
    {
        petsc::finalize()
    }
    #[cfg(not(feature = "petsc"))]
    {
        Ok(())
    }
}

/// The checks PETSc would make later and less clearly: square `a`, `b` of its size, near
/// null space and field split consistent with it.
fn check_input(a: &SparseMatrix, b: &[f64], options: &SolveOptions) -> Result<(), PetscError> {
    let (nrows, ncols) = a.shape();
    let invalid = |m: String| Err(PetscError::InvalidInput(m));
    if nrows != ncols {
        return invalid(format!("the matrix is {nrows} x {ncols}, not square"));
    }
    if b.len() != nrows {
        return invalid(format!(
            "the right-hand side has {} entries for {nrows} unknowns",
            b.len()
        ));
    }
    let bs = options.effective_block_size();
    if nrows % bs != 0 {
        return invalid(format!("{nrows} unknowns are not blocks of {bs}"));
    }
    if let Some(modes) = &options.near_null_space {
        if !(modes.dim == 2 || modes.dim == 3) {
            return invalid(format!("rigid body modes in {} dimensions", modes.dim));
        }
        if modes.coordinates.len() != nrows {
            return invalid(format!(
                "{} coordinates ({} per node) for {nrows} unknowns ({} per node)",
                modes.coordinates.len(),
                modes.dim,
                modes.dim
            ));
        }
    }
    if let Preconditioner::FieldSplitSchur(split) = &options.preconditioner {
        let ascending = split.first.windows(2).all(|w| w[0] < w[1]);
        let in_range = split.first.last().is_none_or(|&i| i < nrows);
        if !ascending || !in_range || split.first.is_empty() || split.first.len() >= nrows {
            return invalid(format!(
                "the first field must be some, not all, of the {nrows} unknowns, ascending"
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn identity(n: usize) -> SparseMatrix {
        SparseMatrix::new((n, n), (0..=n).collect(), (0..n).collect(), vec![1.0; n])
    }

    #[test]
    fn inconsistent_input_is_a_typed_error() {
        let solver = PetscSolver::new(SolveOptions::default());
        let err = solver.solve(&identity(3), &[1.0, 2.0]).unwrap_err();
        assert!(matches!(err, PetscError::InvalidInput(_)), "{err}");

        let options = SolveOptions {
            near_null_space: Some(RigidBodyModes {
                dim: 2,
                coordinates: vec![0.0; 4],
            }),
            ..SolveOptions::default()
        };
        let err = PetscSolver::new(options).solve(&identity(3), &[0.0; 3]);
        assert!(matches!(err, Err(PetscError::InvalidInput(_))));

        let split = Preconditioner::FieldSplitSchur(FieldSplit {
            first: vec![0, 1, 2],
        });
        let err = PetscSolver::new(SolveOptions::new(KrylovMethod::Gmres, split))
            .solve(&identity(3), &[0.0; 3]);
        assert!(matches!(err, Err(PetscError::InvalidInput(_))));
    }

    #[cfg(not(feature = "petsc"))]
    #[test]
    fn without_the_feature_a_solve_says_so() {
        let err = PetscSolver::new(SolveOptions::default())
            .solve(&identity(2), &[1.0, 1.0])
            .unwrap_err();
        assert!(matches!(err, PetscError::NotBuilt));
        assert!(err.to_string().contains("--features petsc"));
        assert!(!is_built());
        assert!(finalize().is_ok());
    }

    #[test]
    fn a_csc_matrix_reaches_the_backend_as_csr() {
        let a = SparseMatrix::new_csc((2, 2), vec![0, 1, 3], vec![0, 0, 1], vec![1.0, 2.0, 3.0]);
        let parts = csr::csr_parts(&a);
        assert_eq!(&*parts.indptr, &[0, 2, 3]);
        assert_eq!(&*parts.indices, &[0, 1, 1]);
        assert_eq!(&*parts.data, &[1.0, 2.0, 3.0]);
    }
}
