//! PETSc as a backend of the finite-element code's solver interface
//! ([`mortar_fem::linalg::SparseSolver`]): "factorising" a matrix sets up PETSc's Krylov
//! method and preconditioner for it, each solve is a Krylov solve to the options' tolerance
//! (an inexact inverse, where the direct backend's is exact to rounding), and every solve's
//! report is kept for the caller to read ([`PetscBackend::reports`]).
//!
//! The preconditioner (the AMG hierarchy, say) is built when the matrix is "factorised" and
//! again when its values change ([`Factorization::refactor`]), and kept for every solve
//! between: a report says `setup_kept` for those. Matrix-free iterative solves
//! ([`SparseSolver::solve_preconditioned`]) with the caller's preconditioner run the
//! interface's default, the finite-element crate's own GMRES: PETSc sees assembled matrices
//! only.

use std::sync::{Arc, Mutex};

use mortar_core::linalg::SparseMatrix;
use mortar_fem::linalg::{
    FactorStats, Factorization, MatrixKind, SolverError, SparseSolver, SystemInfo,
};

use crate::blocks::{petsc_matrix, Blocks};
#[cfg(feature = "petsc")]
use crate::csr::csr_parts;
use crate::{
    FieldSplit, KrylovMethod, PetscError, PetscSolver, Preconditioner, RigidBodyModes,
    SolveOptions, SolveReport,
};

/// PETSc behind the solver interface, with the solve options it applies to every system
/// ([`new`](Self::new)) or with the method it picks for each ([`automatic`](Self::automatic)).
#[derive(Debug, Clone)]
pub struct PetscBackend {
    solver: PetscSolver,
    automatic: bool,
    reports: Arc<Mutex<Vec<SolveReport>>>,
    failures: Arc<Mutex<Vec<String>>>,
}

impl PetscBackend {
    /// A backend solving every system with `options`.
    pub fn new(options: SolveOptions) -> Self {
        Self {
            solver: PetscSolver::new(options),
            automatic: false,
            reports: Arc::default(),
            failures: Arc::default(),
        }
    }

    /// A backend that picks the method for each system from what it is
    /// ([`method_for`](Self::method_for)), to the relative tolerance `rtol`, with the further
    /// PETSc options `petsc_options` (which may override the pick: `-ksp_type minres`).
    pub fn automatic(rtol: f64, petsc_options: impl Into<String>) -> Self {
        let options = SolveOptions {
            rtol,
            petsc_options: petsc_options.into(),
            ..SolveOptions::default()
        };
        Self {
            automatic: true,
            ..Self::new(options)
        }
    }

    /// The options an automatic backend solves a system of `n` unknowns with: a saddle
    /// point (multipliers last, `info.multipliers_last > 0`) by GMRES with the Schur
    /// fieldsplit (GAMG on the primal block, Jacobi on PETSc's `selfp` Schur approximation);
    /// a symmetric positive definite matrix of a 3D displacement field (`info.displacements`
    /// in 3D, not axisymmetric) by CG with BoomerAMG tuned for elasticity
    /// ([`Preconditioner::BoomerAmgElasticity3d`]: fewer than half of GAMG's iterations on
    /// uniform blocks, a ninth on graded meshes); any other symmetric positive definite
    /// matrix by CG with GAMG; any other by GMRES with GAMG. A displacement field's rigid motions reach
    /// GAMG through `info` (see [`factor_system`](SparseSolver::factor_system)). The
    /// tolerance and the further options are the backend's.
    pub fn method_for(&self, kind: MatrixKind, info: &SystemInfo<'_>, n: usize) -> SolveOptions {
        let base = self.solver.options();
        let (method, preconditioner) = if info.multipliers_last > 0 && info.multipliers_last < n {
            let first = (0..n - info.multipliers_last).collect();
            (
                KrylovMethod::Gmres,
                Preconditioner::FieldSplitSchur(FieldSplit { first }),
            )
        } else if kind == MatrixKind::SymmetricPositiveDefinite {
            let elasticity_3d = info
                .displacements
                .is_some_and(|p| p.dim == 3 && !p.axisymmetric);
            let preconditioner = if elasticity_3d {
                Preconditioner::BoomerAmgElasticity3d
            } else {
                Preconditioner::Gamg
            };
            (KrylovMethod::Cg, preconditioner)
        } else {
            (KrylovMethod::Gmres, Preconditioner::Gamg)
        };
        SolveOptions {
            method,
            preconditioner,
            near_null_space: None,
            block_size: 1,
            ..base.clone()
        }
    }

    /// The reports of the solves made through this backend (and its clones), in order.
    pub fn reports(&self) -> Vec<SolveReport> {
        self.reports.lock().map(|r| r.clone()).unwrap_or_default()
    }

    /// The set-ups and solves through this backend (and its clones) that failed, in order, as
    /// their errors' messages: what a caller that retries another way (a general solve after
    /// a failed symmetric one) would otherwise leave unsaid.
    pub fn failures(&self) -> Vec<String> {
        self.failures.lock().map(|f| f.clone()).unwrap_or_default()
    }

    /// Records the failure `e` and gives it back.
    fn failed(failures: &Mutex<Vec<String>>, e: SolverError) -> SolverError {
        if let Ok(mut f) = failures.lock() {
            f.push(e.to_string());
        }
        e
    }
}

/// A system set up for PETSc's solves: its matrix (full), and PETSc's solver with the
/// preconditioner built for it.
#[derive(Debug)]
struct PetscSystem {
    /// The pattern of the matrix PETSc solves (the caller's, full, or its blocked embedding),
    /// which a refactor must keep; PETSc holds the values.
    pattern: Pattern,
    kind: MatrixKind,
    rtol: f64,
    /// Where the caller's unknowns sit in the blocked system, if embedded.
    blocks: Option<Blocks>,
    #[cfg(feature = "petsc")]
    prepared: crate::petsc::Prepared,
    reports: Arc<Mutex<Vec<SolveReport>>>,
    failures: Arc<Mutex<Vec<String>>>,
}

/// What a refactor must keep of a matrix: its size and its pattern (by a hash of the row
/// pointers and column indices), so that no copy of the matrix is kept beside PETSc's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Pattern {
    rows: usize,
    nnz: usize,
    hash: u64,
}

impl Pattern {
    fn of(a: &SparseMatrix) -> Self {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        a.indptr().raw_storage().hash(&mut h);
        a.indices().hash(&mut h);
        Self {
            rows: a.rows(),
            nnz: a.nnz(),
            hash: h.finish(),
        }
    }
}

/// A PETSc failure as the solver interface's error.
fn solver_error(e: PetscError, rtol: f64) -> SolverError {
    match e {
        PetscError::NotConverged {
            reason,
            iterations,
            residual_norm,
            ksp_type,
            pc_type,
        } => SolverError::NotConverged {
            method: format!("PETSc {ksp_type}+{pc_type} ({reason})"),
            iterations,
            residual: residual_norm,
            tolerance: rtol,
        },
        PetscError::InvalidInput(what) => SolverError::Backend(format!("PETSc: {what}")),
        e => SolverError::Backend(e.to_string()),
    }
}

impl Factorization for PetscSystem {
    fn solve_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        let n = self
            .blocks
            .as_ref()
            .map_or(self.pattern.rows, |b| b.unknowns());
        if x.len() != n {
            return Err(SolverError::DimensionMismatch {
                expected: n,
                found: x.len(),
                what: "entries of the right-hand side",
            });
        }
        #[cfg(feature = "petsc")]
        {
            let blocked = self.blocks.as_ref().map(|b| b.scatter(x));
            let rhs = blocked.as_deref().unwrap_or(x);
            let (solution, report) = crate::petsc::solve_prepared(&self.prepared, rhs)
                .map_err(|e| PetscBackend::failed(&self.failures, solver_error(e, self.rtol)))?;
            if solution.iter().any(|v| !v.is_finite()) {
                return Err(SolverError::Singular { pivot: None });
            }
            match &self.blocks {
                Some(b) => b.gather(&solution, x),
                None => x.copy_from_slice(&solution),
            }
            if let Ok(mut reports) = self.reports.lock() {
                reports.push(report);
            }
            Ok(())
        }
        #[cfg(not(feature = "petsc"))]
        {
            let _ = (&self.reports, &self.failures);
            Err(solver_error(PetscError::NotBuilt, self.rtol))
        }
    }

    fn refactor(&mut self, a: &SparseMatrix) -> Result<(), SolverError> {
        let blocks = self.blocks.as_ref().filter(|b| a.rows() == b.unknowns());
        let a = petsc_matrix(
            a,
            self.kind == MatrixKind::SymmetricPositiveDefinite,
            blocks,
        );
        let pattern = Pattern::of(&a);
        if pattern != self.pattern {
            return Err(SolverError::PatternMismatch(format!(
                "{} entries of a {} x {} matrix against {} analysed",
                pattern.nnz, pattern.rows, pattern.rows, self.pattern.nnz
            )));
        }
        #[cfg(feature = "petsc")]
        crate::petsc::update(&mut self.prepared, &csr_parts(&a))
            .map_err(|e| solver_error(e, self.rtol))?;
        Ok(())
    }

    fn stats(&self) -> FactorStats {
        FactorStats {
            dim: self
                .blocks
                .as_ref()
                .map_or(self.pattern.rows, Blocks::unknowns),
            factor_entries: None,
            method: "PETSc Krylov solve (its reports say which method)",
        }
    }
}

/// `vectors` made orthonormal by modified Gram-Schmidt (twice, for rounding), those that
/// depend on the earlier ones (a rotation of unknowns on one line, say) dropped.
fn orthonormal(vectors: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for mut v in vectors {
        let norm0 = dot(&v, &v).sqrt();
        for _ in 0..2 {
            for q in &basis {
                let c = dot(&v, q);
                v.iter_mut().zip(q).for_each(|(x, y)| *x -= c * y);
            }
        }
        let norm = dot(&v, &v).sqrt();
        if norm > 1e-10 * norm0 && norm > 0.0 {
            v.iter_mut().for_each(|x| *x /= norm);
            basis.push(v);
        }
    }
    basis
}

impl SparseSolver for PetscBackend {
    fn factor(
        &self,
        a: &SparseMatrix,
        kind: MatrixKind,
    ) -> Result<Box<dyn Factorization>, SolverError> {
        self.factor_system(a, kind, SystemInfo::default())
    }

    /// As [`factor`](SparseSolver::factor); with GAMG and no rigid body modes in the
    /// options, a displacement field's rigid motions (`info.displacements`, restricted to
    /// the system's unknowns) are the near null space.
    fn factor_system(
        &self,
        a: &SparseMatrix,
        kind: MatrixKind,
        info: SystemInfo<'_>,
    ) -> Result<Box<dyn Factorization>, SolverError> {
        let (rows, cols) = a.shape();
        if rows != cols {
            return Err(SolverError::DimensionMismatch {
                expected: rows,
                found: cols,
                what: "columns of a square matrix",
            });
        }
        let picked;
        let options = if self.automatic {
            picked = self.method_for(kind, &info, rows);
            &picked
        } else {
            self.solver.options()
        };
        if !crate::is_built() {
            let e = solver_error(PetscError::NotBuilt, options.rtol);
            return Err(Self::failed(&self.failures, e));
        }
        let upper = kind == MatrixKind::SymmetricPositiveDefinite;
        // GAMG or BoomerAMG for elasticity on a displacement field: the system in whole node
        // blocks, the nodes' rigid body modes as GAMG's near null space (else the rigid
        // motions as explicit vectors). BoomerAMG reads the block size as its number of
        // functions and coarsens each component by itself: without the blocks CG took 89
        // iterations instead of 32 on the 3D contact blocks at 1e6 unknowns.
        let by_nodes = matches!(
            options.preconditioner,
            Preconditioner::Gamg | Preconditioner::BoomerAmgElasticity3d
        ) && options.near_null_space.is_none();
        let places = info
            .displacements
            .filter(|p| by_nodes && p.points.len() == rows && p.components.len() == rows);
        let blocks = places.as_ref().and_then(Blocks::of);
        let blocked_options;
        let (a, options) = match &blocks {
            Some(b) => {
                blocked_options = SolveOptions {
                    near_null_space: Some(RigidBodyModes {
                        dim: b.dim,
                        coordinates: b.coordinates.clone(),
                    }),
                    ..options.clone()
                };
                (petsc_matrix(a, upper, Some(b)), &blocked_options)
            }
            None => (petsc_matrix(a, upper, None), options),
        };
        crate::check_input(&a, &vec![0.0; a.rows()], options)
            .map_err(|e| solver_error(e, options.rtol))?;
        let modes = match (&blocks, places) {
            (None, Some(p)) => orthonormal(p.rigid_body_modes()),
            _ => Vec::new(),
        };
        let pattern = Pattern::of(&a);
        #[cfg(feature = "petsc")]
        let prepared = crate::petsc::prepare(a, options, modes)
            .map_err(|e| Self::failed(&self.failures, solver_error(e, options.rtol)))?;
        #[cfg(not(feature = "petsc"))]
        let _ = (modes, a);
        Ok(Box::new(PetscSystem {
            pattern,
            kind,
            rtol: options.rtol,
            blocks,
            #[cfg(feature = "petsc")]
            prepared,
            reports: Arc::clone(&self.reports),
            failures: Arc::clone(&self.failures),
        }))
    }
}
