//! What a solve asks of PETSc: the Krylov method, the preconditioner, the tolerances, the near
//! null space for algebraic multigrid, and free-form PETSc options, rendered into one options
//! string that PETSc reads (the free-form options last, so they win).

use std::fmt::Write;

/// The Krylov method (PETSc's `KSPType`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum KrylovMethod {
    /// Conjugate gradients (`cg`): symmetric positive definite matrix and preconditioner.
    Cg,
    /// Restarted GMRES (`gmres`, restart 30 unless `-ksp_gmres_restart` says otherwise): any
    /// nonsingular matrix.
    Gmres,
    /// MINRES (`minres`): symmetric, possibly indefinite matrix (saddle points) with a
    /// symmetric positive definite preconditioner.
    Minres,
    /// The preconditioner applied once (`preonly`): a direct solve when the preconditioner
    /// is [`Preconditioner::Lu`].
    PreOnly,
}

impl KrylovMethod {
    /// PETSc's name of the method.
    pub fn petsc_name(self) -> &'static str {
        match self {
            Self::Cg => "cg",
            Self::Gmres => "gmres",
            Self::Minres => "minres",
            Self::PreOnly => "preonly",
        }
    }
}

/// The preconditioner (PETSc's `PCType` and the options that complete it).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Preconditioner {
    /// PETSc's smoothed-aggregation algebraic multigrid (`gamg`); give elasticity its rigid
    /// body modes ([`SolveOptions::near_null_space`]).
    Gamg,
    /// hypre's BoomerAMG (`hypre`, `-pc_hypre_type boomeramg`).
    BoomerAmg,
    /// hypre's BoomerAMG tuned for 3D elasticity ([`BOOMERAMG_ELASTICITY_3D`]): HMIS
    /// coarsening with one level of aggressive coarsening, extended+i interpolation of at
    /// most 4 entries a row, strong threshold 0.6.
    BoomerAmgElasticity3d,
    /// The diagonal (`jacobi`).
    Jacobi,
    /// A sparse LU factorisation by MUMPS (`lu`, `-pc_factor_mat_solver_type mumps`).
    Lu,
    /// A two-field block preconditioner by the Schur complement (`fieldsplit`, Schur type):
    /// for saddle points `[A B^T; B 0]`.
    FieldSplitSchur(FieldSplit),
}

impl Preconditioner {
    /// PETSc's name of the preconditioner.
    pub fn petsc_name(&self) -> &'static str {
        match self {
            Self::Gamg => "gamg",
            Self::BoomerAmg | Self::BoomerAmgElasticity3d => "hypre",
            Self::Jacobi => "jacobi",
            Self::Lu => "lu",
            Self::FieldSplitSchur(_) => "fieldsplit",
        }
    }
}

/// The two fields of a saddle-point system: the unknowns of the first (the primal block
/// `A`), all the others forming the second (the multipliers, whose block is the Schur
/// complement `S = -B A^-1 B^T`).
///
/// Each block's solver is PETSc's `fieldsplit_0_` and `fieldsplit_1_` options; by default
/// the first is one V-cycle of GAMG, the second Jacobi on PETSc's `selfp` approximation of
/// `S` (`B diag(A)^-1 B^T`), and the factorisation is `full` (`diag` under MINRES, which
/// needs a symmetric positive definite preconditioner).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FieldSplit {
    /// The unknowns of the first field, ascending.
    pub first: Vec<usize>,
}

/// The rigid body modes of an elastic body from its nodes' coordinates, the near null space
/// that smoothed aggregation needs to coarsen elasticity well (3 modes in 2D: two
/// translations and a rotation; 6 in 3D).
///
/// The unknowns must be numbered node by node, components interleaved: unknown
/// `node * dim + c` is component `c` of node `node`.
#[derive(Clone, Debug, PartialEq)]
pub struct RigidBodyModes {
    /// The space dimension, 2 or 3: the number of unknowns per node.
    pub dim: usize,
    /// The nodes' coordinates, `dim` per node, node by node.
    pub coordinates: Vec<f64>,
}

/// The largest true relative residual `|b - A x| / |b|` a converged Krylov solve to the
/// relative tolerance `rtol` may leave, above which its solution is refused: PETSc's test
/// measures the preconditioned residual for CG and left-preconditioned GMRES, which differs
/// from the true one by the preconditioner's conditioning, so the bound is `1000 rtol`, at
/// most `sqrt(rtol)` and at least `rtol`.
///
/// ```
/// use mortar_petsc::accepted_residual;
/// assert_eq!(accepted_residual(1e-12), 1e-9);
/// assert!((accepted_residual(1e-2) - 0.1).abs() < 1e-15);
/// ```
pub fn accepted_residual(rtol: f64) -> f64 {
    (1e3 * rtol).min(rtol.sqrt()).max(rtol)
}

/// BoomerAMG's settings for 3D elasticity ([`Preconditioner::BoomerAmgElasticity3d`]): on
/// the 3D contact blocks they keep CG at 29 to 32 iterations from 3e5 to 1e6 unknowns, where
/// smoothed aggregation (GAMG with the rigid body modes) takes 66 to 79, and at 32 to 36 on
/// the graded meshes of the 3D Hertz scene, where GAMG takes 277 to 331 (docs/solvers.md).
/// Options given by the caller or `PETSC_OPTIONS` come after them and override them.
pub const BOOMERAMG_ELASTICITY_3D: &str = "-pc_hypre_boomeramg_coarsen_type HMIS \
     -pc_hypre_boomeramg_agg_nl 1 -pc_hypre_boomeramg_interp_type ext+i \
     -pc_hypre_boomeramg_P_max 4 -pc_hypre_boomeramg_strong_threshold 0.6";

/// A solve's settings.
///
/// PETSc reads them as its options (see [`SolveOptions::options_string`]); `petsc_options`
/// come last and override anything the typed fields set, so that every PETSc option passes
/// through. The report says what actually ran.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveOptions {
    /// The Krylov method.
    pub method: KrylovMethod,
    /// The preconditioner.
    pub preconditioner: Preconditioner,
    /// The relative tolerance on the residual norm (PETSc's `rtol`, which measures the
    /// preconditioned norm for CG and left-preconditioned GMRES, the unpreconditioned norm
    /// for MINRES).
    pub rtol: f64,
    /// The absolute tolerance on the residual norm.
    pub atol: f64,
    /// The most iterations.
    pub max_it: usize,
    /// Unknowns per node, interleaved (1 for a scalar field, 2 or 3 for displacements):
    /// the matrix's block size, which GAMG aggregates by. `near_null_space` sets it to its
    /// `dim`.
    pub block_size: usize,
    /// Rigid body modes for GAMG (and the matrix's block size, `dim`).
    pub near_null_space: Option<RigidBodyModes>,
    /// Further PETSc options, as on PETSc's command line (`-ksp_monitor -pc_gamg_threshold
    /// 0.02`), read after the typed ones.
    pub petsc_options: String,
}

impl Default for SolveOptions {
    /// CG with GAMG, relative tolerance 1e-8, absolute 1e-50 (PETSc's), at most 10 000
    /// iterations.
    fn default() -> Self {
        Self {
            method: KrylovMethod::Cg,
            preconditioner: Preconditioner::Gamg,
            rtol: 1e-8,
            atol: 1e-50,
            max_it: 10_000,
            block_size: 1,
            near_null_space: None,
            petsc_options: String::new(),
        }
    }
}

impl SolveOptions {
    /// The default settings with this method and preconditioner.
    pub fn new(method: KrylovMethod, preconditioner: Preconditioner) -> Self {
        Self {
            method,
            preconditioner,
            ..Self::default()
        }
    }

    /// The matrix's block size: `near_null_space`'s `dim` if given, `block_size` otherwise.
    pub fn effective_block_size(&self) -> usize {
        self.near_null_space
            .as_ref()
            .map_or(self.block_size.max(1), |modes| modes.dim)
    }

    /// The options that complete the preconditioner's choice, then `petsc_options`. The
    /// method, the preconditioner's type and the tolerances are set through PETSc's
    /// functions before it reads these.
    pub fn options_string(&self) -> String {
        self.options_string_with_environment(None)
    }

    /// What PETSc's options database holds during a solve: the options that complete the
    /// preconditioner's choice, then `environment` (the `PETSC_OPTIONS` variable, read at
    /// each solve), then `petsc_options`; a later option overrides an earlier one.
    pub fn options_string_with_environment(&self, environment: Option<&str>) -> String {
        let mut s = String::new();
        match &self.preconditioner {
            Preconditioner::BoomerAmg => s.push_str("-pc_hypre_type boomeramg"),
            Preconditioner::BoomerAmgElasticity3d => {
                let _ = write!(s, "-pc_hypre_type boomeramg {BOOMERAMG_ELASTICITY_3D}");
            }
            Preconditioner::Lu => s.push_str("-pc_factor_mat_solver_type mumps"),
            Preconditioner::FieldSplitSchur(_) => {
                let fact = if self.method == KrylovMethod::Minres {
                    "diag"
                } else {
                    "full"
                };
                let _ = write!(
                    s,
                    "-pc_fieldsplit_type schur -pc_fieldsplit_schur_fact_type {fact} \
                     -pc_fieldsplit_schur_precondition selfp \
                     -fieldsplit_0_ksp_type preonly -fieldsplit_0_pc_type gamg \
                     -fieldsplit_1_ksp_type preonly -fieldsplit_1_pc_type jacobi"
                );
            }
            Preconditioner::Gamg | Preconditioner::Jacobi => {}
        }
        for extra in [environment.unwrap_or(""), &self.petsc_options] {
            let extra = extra.trim();
            if !extra.is_empty() {
                if !s.is_empty() {
                    s.push(' ');
                }
                s.push_str(extra);
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_form_options_come_after_the_typed_ones() {
        let mut o = SolveOptions::new(KrylovMethod::Gmres, Preconditioner::Lu);
        o.petsc_options = "  -pc_factor_mat_solver_type superlu ".into();
        assert_eq!(
            o.options_string(),
            "-pc_factor_mat_solver_type mumps -pc_factor_mat_solver_type superlu"
        );
        assert_eq!(SolveOptions::default().options_string(), "");
        assert_eq!(
            o.options_string_with_environment(Some("-ksp_monitor")),
            "-pc_factor_mat_solver_type mumps -ksp_monitor -pc_factor_mat_solver_type superlu"
        );
    }

    #[test]
    fn minres_gets_a_symmetric_schur_preconditioner() {
        let split = Preconditioner::FieldSplitSchur(FieldSplit { first: vec![0, 1] });
        let minres = SolveOptions::new(KrylovMethod::Minres, split.clone()).options_string();
        let gmres = SolveOptions::new(KrylovMethod::Gmres, split).options_string();
        assert!(minres.contains("schur_fact_type diag"));
        assert!(gmres.contains("schur_fact_type full"));
    }
}
