//! `TiedSystem`: the linear system of two bodies tied by mortar, built and factorised in the
//! chosen formulation (condensed Cholesky, substructured Cholesky or saddle point), and its
//! solve into both fields and the multipliers.

use std::time::Instant;

use rayon::prelude::*;

use mortar_fem::linalg::{
    CholeskyFactorization, Factorization, LuFactorization, MatrixKind, SaddlePointFactorization,
    SolverError, SparseMatrix, SparseSolver, SubstructuredCholesky, SystemInfo, Triplets,
};

use super::crosspoint::shares;
use super::formulation::{
    Formulation, FormulationChoice, FormulationReport, SlaveDirichlet, TiedOptions,
};
use super::tie::Tie;
use crate::error::PhysicsError;
use crate::linear_solve::{LinearSolve, Places};
use crate::tying::TyingError;

/// Marks "none" in index maps.
const NONE: u32 = u32::MAX;

/// The two bodies' fields and the interface multipliers of a tied solve.
#[derive(Debug, Clone, PartialEq)]
pub struct TiedFields {
    /// The slave body's and the master body's nodal values (by mesh node index).
    pub fields: [Vec<f64>; 2],
    /// The multiplier of each row of the tie's D (slave interface node and component, in
    /// coupling row order): for heat conduction the heat flux leaving the slave body, for
    /// elasticity the traction on it. `NaN` for a Dirichlet slave unknown, whose multiplier
    /// was removed, and for a node without multiplier (its row of D empty: the edge nodes of
    /// linear multipliers on second-order faces).
    pub multipliers: Vec<f64>,
    /// Seconds spent in this solve (right-hand side, triangular solves, recovery).
    pub seconds: f64,
}

/// Seconds spent building and factorising a [`TiedSystem`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SystemSeconds {
    /// Building the constraint rows and the system matrix.
    pub build: f64,
    /// The sparse factorisation (symbolic and numeric, or numeric only after a refactor).
    pub factorisation: f64,
}

/// The factorisation of the chosen formulation.
#[derive(Debug)]
enum Factor {
    Lu(Box<LuFactorization>),
    Ldlt(Box<SaddlePointFactorization>),
    Cholesky(CholeskyFactorization),
    Substructured(Box<SubstructuredCholesky>),
    /// A backend's solve of the system (PETSc's Krylov methods, say).
    Backend(Box<dyn Factorization>),
}

impl Factor {
    /// The saddle point: `L D L^T` in an order that needs no pivoting (`last`: the unknowns
    /// that pin a body without Dirichlet condition, after the multipliers), or, where that
    /// is refused (a pivot at zero, a failed check), LU with partial pivoting.
    fn saddle_point(
        matrix: &SparseMatrix,
        constraints: usize,
        last: &[bool],
    ) -> Result<Self, SolverError> {
        match SaddlePointFactorization::try_new_with_last(matrix, constraints, last) {
            Ok(f) => Ok(Factor::Ldlt(Box::new(f))),
            Err(SolverError::Singular { .. }) => {
                Ok(Factor::Lu(Box::new(LuFactorization::try_new(matrix)?)))
            }
            Err(e) => Err(e),
        }
    }

    /// The factorisation, through the solver interface.
    fn factorization(&self) -> &dyn Factorization {
        match self {
            Factor::Lu(f) => &**f,
            Factor::Ldlt(f) => &**f,
            Factor::Cholesky(f) => f,
            Factor::Substructured(f) => &**f,
            Factor::Backend(f) => &**f,
        }
    }

    /// What factorises the system, for the report.
    fn name(&self) -> &'static str {
        match self {
            Factor::Lu(_) => "sparse LU (partial pivoting)",
            Factor::Ldlt(_) => "sparse LDL^T (fill-reducing order, multipliers after their rows)",
            Factor::Cholesky(_) => "sparse Cholesky",
            Factor::Substructured(_) => {
                "sparse Cholesky by body (the bodies factorised in parallel, the interface last)"
            }
            Factor::Backend(f) => f.stats().method,
        }
    }
}

/// The linear system of two bodies tied by mortar: per-body matrices `A_1`, `A_2`
/// (symmetric positive semi-definite each, e.g. heat conduction stiffness, plus capacity over
/// the time step), the tying constraint `D T_s - M T_m = 0`, and Dirichlet conditions,
/// factorised once and solved for any right-hand side and Dirichlet values.
///
/// Unknowns are numbered per body (the slave body's, then the master body's), as the tie
/// numbers them: one per node for a scalar field, `node * c + k` for a field of `c`
/// components (see [`Tie::with_components`]). Rows of the constraint are the rows of the
/// tie's `D (x) I_c` (a slave interface node and a component), after the treatment of
/// Dirichlet slave unknowns of [`SlaveDirichlet`].
///
/// - [`Formulation::SaddlePoint`]: `[[A_ff, B_f^T], [B_f, 0]] [T_f; lambda] =
///   [b_f - A_fd g; -B_d g]` (f free, d Dirichlet), by sparse `L D L^T` in an order that
///   needs no pivoting ([`SaddlePointFactorization`]), or sparse LU where that is refused;
///   [`FormulationReport::factorisation`] says which.
/// - [`Formulation::DualCondensed`]: with D diagonal on the slave nodes that carry a row, each
///   such node's value is an affine combination of the others,
///   `T_s = D_ss^-1 (M T_m - D_sd g)`, i.e. `T = Q T_r`; the system `Q^T A Q` in the remaining
///   free unknowns is symmetric positive definite and solved by sparse Cholesky: by body
///   ([`SubstructuredCholesky`]: each body with the interface's unknowns factorised
///   on its own thread, the interface's dense Schur complement last) from
///   [`SUBSTRUCTURED_MIN`](mortar_fem::linalg::SUBSTRUCTURED_MIN) unknowns when the
///   interface has at most `2 sqrt(n)` of them, as one matrix otherwise. The multipliers
///   follow from the slave rows:
///   `lambda_j = (b - A T)_j / D_jj`.
///
/// Both give the same solution up to round-off. [`new_on`](Self::new_on) hands the system of
/// either formulation to a backend of the solver interface instead (PETSc's Krylov methods
/// with algebraic multigrid, say): the condensed one as symmetric positive definite, the
/// saddle point with its multipliers last.
#[derive(Debug)]
pub struct TiedSystem {
    layout: Layout,
    /// Row `j`: the row of the block-diagonal matrix at constraint row `j`'s own slave
    /// unknown (`row_own[j]`), what the condensed solve's multipliers need of it (the whole
    /// matrix is not kept: a copy of the bodies' matrices beside the system's).
    own_rows: SparseMatrix,
    /// The system's coupling to the Dirichlet values (system rows x Dirichlet unknowns).
    a_fd: SparseMatrix,
    /// The symmetric scaling `S` of the factorised matrix (`S K S`), by system unknown: powers
    /// of two (see [`Layout::scaling`]).
    scale: Vec<f64>,
    factor: Factor,
    report: FormulationReport,
    seconds: SystemSeconds,
}

/// How the global unknowns map to the factorised system.
#[derive(Debug, Clone)]
struct Layout {
    formulation: Formulation,
    n: [usize; 2],
    /// Field components per node.
    comps: usize,
    /// Dirichlet unknowns per body.
    nd: [usize; 2],
    /// Dirichlet unknowns (global index), slave body's list then master body's.
    dirichlet: Vec<u32>,
    /// Global unknown -> position in `dirichlet`, or NONE.
    dirichlet_pos: Vec<u32>,
    /// Constraint rows over the global unknowns (after the Dirichlet slave treatment).
    rows: SparseMatrix,
    /// For each constraint row, its coupling row and its own slave unknown.
    row_origin: Vec<u32>,
    row_own: Vec<u32>,
    coupling_rows: usize,
    /// Global unknown -> index among the system's unknowns, or NONE.
    free: Vec<u32>,
    nfree: usize,
    /// Expansion `T_g = sum w T_r` of every global unknown (identity for the retained ones).
    exp_ptr: Vec<usize>,
    exp_dof: Vec<u32>,
    exp_w: Vec<f64>,
}

impl TiedSystem {
    /// Builds and factorises the tied system of `matrices = [A_slave, A_master]` (each square,
    /// of its body's unknown count), with Dirichlet conditions on the unknowns
    /// `dirichlet = [slave list, master list]` (each without repeats).
    ///
    /// # Errors
    /// [`PhysicsError::WrongLength`] for mismatched sizes, [`PhysicsError::InvalidInput`] for a
    /// repeated or out-of-range Dirichlet node, [`PhysicsError::DirichletOnSlave`] (with
    /// [`SlaveDirichlet::Refuse`]), [`PhysicsError::Tying`] when the condensation is forced
    /// and D is not diagonal, [`PhysicsError::Solver`] when the factorisation fails (a body
    /// without Dirichlet condition that the interface does not hold, say).
    pub fn new(
        matrices: [&SparseMatrix; 2],
        tie: &Tie,
        dirichlet: [&[u32]; 2],
        options: &TiedOptions,
    ) -> Result<Self, PhysicsError> {
        Self::new_on(matrices, tie, dirichlet, options, &LinearSolve::default())
    }

    /// [`new`](Self::new), the system solved by `linear.backend` when it names one (told, for
    /// a field of several components, where each unknown sits: `linear.nodes`, each body's
    /// node coordinates), by the direct factorisations otherwise.
    ///
    /// # Errors
    /// As [`new`](Self::new); [`PhysicsError::LinearSolve`] naming the system when the
    /// backend fails to set it up.
    pub fn new_on(
        matrices: [&SparseMatrix; 2],
        tie: &Tie,
        dirichlet: [&[u32]; 2],
        options: &TiedOptions,
        linear: &LinearSolve<'_>,
    ) -> Result<Self, PhysicsError> {
        let t0 = Instant::now();
        let n = check_columns(matrices)?;
        let ndof = n[0] + n[1];
        let (dirichlet_pos, dlist) = dirichlet_positions(dirichlet, n)?;
        check_tie_sizes(tie, n)?;

        let crossing = modified_rows(tie, n[0], &dirichlet_pos, options.slave_dirichlet)?;
        let a = block_diagonal(matrices[0], matrices[1]);

        // Condensable: positive own entries, and no entry (beyond the tolerance) on another
        // row's own unknown.
        let nrows = crossing.rows.rows();
        let mut own_row = vec![NONE; ndof];
        for (j, &s) in crossing.own.iter().enumerate() {
            own_row[s as usize] = j as u32;
        }
        let check = check_diagonal(&crossing, &own_row, options.diagonal_tolerance, tie);
        let (formulation, reason) = choose_formulation(options, check, nrows)?;

        // Unknowns of the factorised system, and the expansions of all.
        let condense = formulation == Formulation::DualCondensed;
        let (free, nfree) = system_unknowns(&dirichlet_pos, &own_row, condense);
        let (exp_ptr, exp_dof, exp_w) = expansions(&crossing.rows, &own_row, condense);

        let layout = Layout {
            formulation,
            n,
            comps: tie.components(),
            nd: [dirichlet[0].len(), dirichlet[1].len()],
            dirichlet: dlist,
            dirichlet_pos,
            rows: crossing.rows,
            row_origin: crossing.origin,
            row_own: crossing.own,
            coupling_rows: tie.slave_dofs().len(),
            free,
            nfree,
            exp_ptr,
            exp_dof,
            exp_w,
        };
        let (mut matrix, a_fd) = layout.system_matrix(&a);
        let own_rows = rows_of(&a, &layout.row_own);
        drop(a);
        let scale = layout.scaling(&matrix);
        scale_symmetric(&mut matrix, &scale);
        let t1 = Instant::now();
        let factor = match (linear.backend, formulation) {
            (Some(backend), _) => layout.backend_factor(&matrix, backend, linear)?,
            (None, Formulation::SaddlePoint) => {
                Factor::saddle_point(&matrix, nrows, &layout.eliminated_last())?
            }
            (None, Formulation::DualCondensed) => layout.condensed_factor(&matrix)?,
        };
        let factorisation = factor.name();
        Ok(Self {
            layout,
            own_rows,
            a_fd,
            scale,
            factor,
            report: FormulationReport {
                formulation,
                factorisation,
                reason,
                unknowns: matrix.rows(),
                nonzeros: matrix.nnz(),
                multipliers: nrows,
                redistributed: crossing.redistributed,
                dropped: crossing.dropped,
            },
            seconds: SystemSeconds {
                build: (t1 - t0).as_secs_f64(),
                factorisation: t1.elapsed().as_secs_f64(),
            },
        })
    }

    /// Factorises new body matrices with the same sparsity patterns as before (a new time
    /// step size, a Newton step), reusing the symbolic analysis and the constraint.
    ///
    /// # Errors
    /// [`PhysicsError::Solver`] if a pattern differs or the factorisation fails (the previous
    /// factors are then kept); [`PhysicsError::LinearSolve`] naming the system when a
    /// backend's set-up fails.
    pub fn refactor(&mut self, matrices: [&SparseMatrix; 2]) -> Result<(), PhysicsError> {
        let t0 = Instant::now();
        let n = self.layout.n;
        if (0..2).any(|b| matrices[b].shape() != (n[b], n[b])) {
            return Err(SolverError::PatternMismatch(format!(
                "body matrices of {}x{} and {}x{} for a tied system of {} and {} nodes",
                matrices[0].rows(),
                matrices[0].cols(),
                matrices[1].rows(),
                matrices[1].cols(),
                self.layout.n[0],
                self.layout.n[1]
            ))
            .into());
        }
        let a = block_diagonal(matrices[0], matrices[1]);
        let (mut matrix, a_fd) = self.layout.system_matrix(&a);
        let own_rows = rows_of(&a, &self.layout.row_own);
        drop(a);
        let scale = self.layout.scaling(&matrix);
        scale_symmetric(&mut matrix, &scale);
        let t1 = Instant::now();
        let done = match &mut self.factor {
            Factor::Lu(f) => f.refactor(&matrix),
            Factor::Ldlt(f) => match f.refactor(&matrix) {
                // The new matrix needs pivoting: LU from here on.
                Err(SolverError::Singular { .. }) => LuFactorization::try_new(&matrix).map(|lu| {
                    self.factor = Factor::Lu(Box::new(lu));
                }),
                other => other,
            },
            Factor::Cholesky(f) => f.refactor(&matrix),
            Factor::Substructured(f) => f.refactor(&matrix),
            Factor::Backend(f) => f.refactor(&matrix),
        };
        self.report.factorisation = self.factor.name();
        done.map_err(|e| self.error_of(e))?;
        self.own_rows = own_rows;
        self.a_fd = a_fd;
        self.scale = scale;
        self.seconds = SystemSeconds {
            build: (t1 - t0).as_secs_f64(),
            factorisation: t1.elapsed().as_secs_f64(),
        };
        Ok(())
    }

    /// A failure of the factorisation's refactor or solve: a backend's named with the system
    /// and what to change ([`Layout::backend_error`]), the direct solves' as it is.
    fn error_of(&self, e: SolverError) -> PhysicsError {
        match self.factor {
            Factor::Backend(_) => self.layout.backend_error(e),
            _ => e.into(),
        }
    }

    /// Which formulation is used, and why.
    pub fn report(&self) -> &FormulationReport {
        &self.report
    }

    /// Seconds of the last build and factorisation.
    pub fn seconds(&self) -> SystemSeconds {
        self.seconds
    }

    /// Solves for right-hand sides `rhs = [b_slave, b_master]` (per body node) and Dirichlet
    /// values `dirichlet = [slave values, master values]`, in the order of the node lists given
    /// to [`new`](Self::new).
    ///
    /// # Errors
    /// [`PhysicsError::WrongLength`], [`PhysicsError::Solver`].
    pub fn solve(
        &self,
        rhs: [&[f64]; 2],
        dirichlet: [&[f64]; 2],
    ) -> Result<TiedFields, PhysicsError> {
        let t0 = Instant::now();
        let l = &self.layout;
        for b in 0..2 {
            if rhs[b].len() != l.n[b] {
                return Err(PhysicsError::WrongLength {
                    what: format!("right-hand side of body {b}"),
                    expected: l.n[b],
                    got: rhs[b].len(),
                });
            }
        }
        for b in 0..2 {
            if dirichlet[b].len() != l.nd[b] {
                return Err(PhysicsError::WrongLength {
                    what: format!("Dirichlet values of body {b}"),
                    expected: l.nd[b],
                    got: dirichlet[b].len(),
                });
            }
        }
        let g: Vec<f64> = dirichlet[0].iter().chain(dirichlet[1]).copied().collect();
        let b: Vec<f64> = rhs[0].iter().chain(rhs[1]).copied().collect();
        let ndof = b.len();
        let nrows = l.rows.rows();
        let saddle = l.formulation == Formulation::SaddlePoint;
        let size = l.nfree + if saddle { nrows } else { 0 };

        // Right-hand side: Q^T b on the free unknowns (saddle: Q = I), then - A_fd g, and for
        // the saddle point the constraint rows' -B_d g (inside A_fd).
        let mut x = vec![0.0; size];
        for (a, ba) in b.iter().enumerate() {
            for e in l.exp_ptr[a]..l.exp_ptr[a + 1] {
                let r = l.free[l.exp_dof[e] as usize];
                if r != NONE {
                    x[r as usize] += l.exp_w[e] * ba;
                }
            }
        }
        for (r, row) in self.a_fd.outer_iterator().enumerate() {
            x[r] -= row.iter().map(|(d, v)| v * g[d]).sum::<f64>();
        }
        // (S K S) y = S f, x = S y.
        for (xi, si) in x.iter_mut().zip(&self.scale) {
            *xi *= si;
        }
        self.factor
            .factorization()
            .solve_in_place(&mut x)
            .map_err(|e| self.error_of(e))?;
        for (xi, si) in x.iter_mut().zip(&self.scale) {
            *xi *= si;
        }

        // Recover every unknown: retained ones from x or g, condensed ones by expansion.
        let retained = |r: usize| -> f64 {
            match (l.free[r], l.dirichlet_pos[r]) {
                (f, _) if f != NONE => x[f as usize],
                (_, d) if d != NONE => g[d as usize],
                _ => unreachable!("a retained unknown is free or Dirichlet"),
            }
        };
        let mut t = vec![0.0; ndof];
        for (gi, ti) in t.iter_mut().enumerate() {
            *ti = (l.exp_ptr[gi]..l.exp_ptr[gi + 1])
                .map(|e| l.exp_w[e] * retained(l.exp_dof[e] as usize))
                .sum();
        }
        let mut multipliers = vec![f64::NAN; l.coupling_rows];
        for j in 0..nrows {
            let lambda = if saddle {
                x[l.nfree + j]
            } else {
                let s = l.row_own[j] as usize;
                let row = self.own_rows.outer_view(j).expect("row in range");
                let r = b[s] - row.iter().map(|(k, v)| v * t[k]).sum::<f64>();
                let d = l
                    .rows
                    .outer_view(j)
                    .and_then(|rv| rv.get(s).copied())
                    .unwrap_or(f64::NAN);
                r / d
            };
            multipliers[l.row_origin[j] as usize] = lambda;
        }
        let master = t.split_off(l.n[0]);
        Ok(TiedFields {
            fields: [t, master],
            multipliers,
            seconds: t0.elapsed().as_secs_f64(),
        })
    }
}

impl Layout {
    /// Per free unknown, whether it is factorised after the multipliers: for a body without
    /// Dirichlet condition (only the tie holds it; its stiffness alone is singular in a
    /// steady problem), the unknowns of one node per component (`min(c, 3)` nodes: its first,
    /// middle and last), enough to pin its constant or rigid modes, so that every other
    /// pivot of the `L D L^T` is that of a definite block.
    fn eliminated_last(&self) -> Vec<bool> {
        let mut out = vec![false; self.nfree];
        let c = self.comps.max(1);
        for b in 0..2 {
            if self.nd[b] != 0 || self.n[b] < c {
                continue;
            }
            let offset = if b == 0 { 0 } else { self.n[0] };
            let nodes = self.n[b] / c;
            let picked: &[usize] = match c.min(3) {
                1 => &[0],
                2 => &[0, nodes - 1],
                _ => &[0, nodes / 2, nodes - 1],
            };
            for &node in picked {
                for k in 0..c {
                    let f = self.free[offset + node * c + k];
                    if f != NONE {
                        out[f as usize] = true;
                    }
                }
            }
        }
        out
    }

    /// The symmetric scaling `S` of the system matrix `K` (factorised as `S K S`), by system
    /// unknown; every factor a power of two, so that the scaling itself is exact.
    ///
    /// - Dual condensed: Jacobi, `S_ii = 2^-round(log2(K_ii) / 2)`. Cholesky commutes with a
    ///   power-of-two diagonal scaling, so this changes no digit of the solution; it keeps the
    ///   pivots away from underflow and overflow when the conductivities are extreme.
    /// - Saddle point: one factor per body, `2^-round(log2(d_b) / 2)` with `d_b` the body's
    ///   largest diagonal entry, and one for the multipliers that brings the largest entry of
    ///   the scaled constraint rows to about 1. Partial pivoting compares entries of a column
    ///   across rows, so an unscaled stiff body (conductivity 1e12, or 1e300) next to a soft
    ///   one or next to constraint rows of order h chooses pivots by magnitude rather than by
    ///   structure. A body's factor is 1 when its largest diagonal entry lies within `2^+-17`
    ///   (about 8e-6 to 1.3e5), the multipliers' when the largest constraint entry lies within
    ///   `2^+-16`, so that ordinary problems are solved bit for bit as without scaling.
    fn scaling(&self, k: &SparseMatrix) -> Vec<f64> {
        let pow2 = |e: i32| 2f64.powi(e);
        let half_log2 = |d: f64| -> i32 {
            if d > 0.0 && d.is_finite() {
                (d.log2() / 2.0).round() as i32
            } else {
                0
            }
        };
        let diag = |r: usize| -> f64 {
            k.outer_view(r)
                .and_then(|row| row.get(r).copied())
                .unwrap_or(0.0)
                .abs()
        };
        if self.formulation == Formulation::DualCondensed {
            return (0..k.rows()).map(|r| pow2(-half_log2(diag(r)))).collect();
        }
        let threshold = |e: i32, limit: i32| if e.abs() <= limit { 0 } else { e };
        let mut largest = [0.0f64; 2];
        let mut body_of = vec![0usize; self.nfree];
        for (g, &f) in self.free.iter().enumerate() {
            if f != NONE {
                let b = usize::from(g >= self.n[0]);
                body_of[f as usize] = b;
                largest[b] = largest[b].max(diag(f as usize));
            }
        }
        let body = largest.map(|d| pow2(-threshold(half_log2(d), 8)));
        let mut scale: Vec<f64> = body_of.iter().map(|&b| body[b]).collect();
        // The multipliers: the largest entry of the scaled constraint rows to about 1.
        let mut b_max = 0.0f64;
        for row in self.rows.outer_iterator() {
            for (a, v) in row.iter() {
                let f = self.free[a];
                if f != NONE {
                    b_max = b_max.max(v.abs() * scale[f as usize]);
                }
            }
        }
        let e = if b_max > 0.0 && b_max.is_finite() {
            b_max.log2().round() as i32
        } else {
            0
        };
        let t = pow2(-threshold(e, 16));
        scale.resize(self.nfree + self.rows.rows(), t);
        scale
    }

    /// The factorisation of the condensed system `matrix`: by body where
    /// [`SubstructuredCholesky::try_new_if_worthwhile`] finds it pays (the two bodies side by
    /// side, balanced, the unknowns between them last: a 2D interface),
    /// else one sparse Cholesky.
    fn condensed_factor(&self, matrix: &SparseMatrix) -> Result<Factor, SolverError> {
        let mut master = vec![false; matrix.rows()];
        for (g, &f) in self.free.iter().enumerate() {
            if f != NONE {
                master[f as usize] = g >= self.n[0];
            }
        }
        Ok(
            match SubstructuredCholesky::try_new_if_worthwhile(matrix, &master)? {
                Some(f) => Factor::Substructured(Box::new(f)),
                None => Factor::Cholesky(CholeskyFactorization::try_new(matrix)?),
            },
        )
    }

    /// The system `matrix` set up by `linear`'s backend: the condensed one as symmetric
    /// positive definite (told where its unknowns sit, for a field of several components
    /// whose nodes `linear` gives), the saddle point as a general matrix with its
    /// multipliers last; refused for the saddle point of a body without Dirichlet condition,
    /// whose primal block is singular.
    fn backend_factor(
        &self,
        matrix: &SparseMatrix,
        backend: &dyn SparseSolver,
        linear: &LinearSolve<'_>,
    ) -> Result<Factor, PhysicsError> {
        let condensed = self.formulation == Formulation::DualCondensed;
        if let Some(b) = (0..2).find(|&b| !condensed && self.nd[b] == 0) {
            return Err(PhysicsError::InvalidInput {
                body: "options".into(),
                what: format!(
                    "the saddle point of a tie whose {} body has no Dirichlet condition (the \
                     tie alone holds it) has a singular primal block, which the backend's \
                     block preconditioner cannot invert: use dual multipliers (the condensed \
                     system) or the direct solve",
                    ["slave", "master"][b]
                ),
            });
        }
        let places = (condensed && self.comps > 1)
            .then(|| {
                let mut dofs = vec![(0, 0); self.nfree];
                for (g, &f) in self.free.iter().enumerate() {
                    if f != NONE {
                        let body = usize::from(g >= self.n[0]);
                        dofs[f as usize] = (body, g - body * self.n[0]);
                    }
                }
                Places::of(linear, self.comps, dofs.into_iter())
            })
            .flatten();
        let (kind, info) = match (&places, condensed) {
            (Some(p), _) => (MatrixKind::SymmetricPositiveDefinite, p.info()),
            (None, true) => (MatrixKind::SymmetricPositiveDefinite, SystemInfo::default()),
            (None, false) => (
                MatrixKind::General,
                SystemInfo {
                    multipliers_last: self.rows.rows(),
                    ..SystemInfo::default()
                },
            ),
        };
        backend
            .factor_system(matrix, kind, info)
            .map(Factor::Backend)
            .map_err(|e| self.backend_error(e))
    }

    /// A backend's failure to set up or solve the system, naming the system and what to
    /// change.
    fn backend_error(&self, e: SolverError) -> PhysicsError {
        PhysicsError::LinearSolve {
            system: format!(
                "the tied system ({:?}, {} unknowns, {} multipliers) through its backend: \
                 loosen [solve] linear_tolerance, allow more iterations (petsc_options \
                 \"-ksp_max_it N\"), or solve it directly (backend = \"direct\")",
                self.formulation,
                self.nfree,
                self.rows.rows()
            ),
            source: e,
        }
    }

    /// For each global unknown, the `(condensed unknown, expansion entry)` pairs of the
    /// condensed unknowns whose expansion names it, condensed unknowns ascending, compressed
    /// by unknown: the pointers and the pairs.
    fn expanding_onto(&self) -> (Vec<usize>, Vec<(u32, usize)>) {
        let ndof = self.free.len();
        let condensed = |g: usize| {
            let (lo, hi) = (self.exp_ptr[g], self.exp_ptr[g + 1]);
            !(hi == lo + 1 && self.exp_dof[lo] as usize == g)
        };
        let mut onto_ptr = vec![0usize; ndof + 1];
        for g in (0..ndof).filter(|&g| condensed(g)) {
            for e in self.exp_ptr[g]..self.exp_ptr[g + 1] {
                onto_ptr[self.exp_dof[e] as usize + 1] += 1;
            }
        }
        for g in 0..ndof {
            onto_ptr[g + 1] += onto_ptr[g];
        }
        let mut onto = vec![(0u32, 0usize); onto_ptr[ndof]];
        let mut next = onto_ptr.clone();
        for g in (0..ndof).filter(|&g| condensed(g)) {
            for e in self.exp_ptr[g]..self.exp_ptr[g + 1] {
                let k = self.exp_dof[e] as usize;
                onto[next[k]] = (g as u32, e);
                next[k] += 1;
            }
        }
        (onto_ptr, onto)
    }

    /// The system matrix `Q^T A Q` on the free unknowns (with the constraint rows and columns
    /// for the saddle point) and the columns of the Dirichlet unknowns, `A_fd`. Rows are built
    /// independently, in parallel: row `r` gathers the rows of `A` that expand onto its
    /// unknown (its own and those of the condensed unknowns whose expansion names it), in
    /// ascending order, and sums each column's terms in that order (the order of a triplet
    /// assembly of the same products, so the same bits).
    fn system_matrix(&self, a: &SparseMatrix) -> (SparseMatrix, SparseMatrix) {
        let saddle = self.formulation == Formulation::SaddlePoint;
        let nrows = self.rows.rows();
        let size = self.nfree + if saddle { nrows } else { 0 };
        // The global unknown of each free row.
        let mut unknown_of = vec![0u32; self.nfree];
        for (g, &f) in self.free.iter().enumerate() {
            if f != NONE {
                unknown_of[f as usize] = g as u32;
            }
        }
        // For each retained unknown, the (row, expansion entry) pairs of the condensed
        // unknowns that expand onto it, rows ascending.
        let (onto_ptr, onto) = self.expanding_onto();
        // The saddle point's columns in the free rows: the constraint rows transposed.
        let constraint_t = if saddle {
            Some(self.rows.transpose_view().to_csr())
        } else {
            None
        };
        let build_rows = |rows: std::ops::Range<usize>| {
            let mut out = RowChunk::default();
            let mut ent: Vec<(u32, f64)> = Vec::new();
            let mut dir: Vec<(u32, f64)> = Vec::new();
            for r in rows {
                let g = unknown_of[r] as usize;
                ent.clear();
                dir.clear();
                // The contributing rows: g's own, merged by row index with the condensed ones.
                let own = (g as u32, self.exp_ptr[g]);
                let list = &onto[onto_ptr[g]..onto_ptr[g + 1]];
                let at = list.partition_point(|&(a, _)| a < own.0);
                let contributing = list[..at]
                    .iter()
                    .chain(std::iter::once(&own))
                    .chain(&list[at..]);
                for &(ra, ea) in contributing {
                    let row = a.outer_view(ra as usize).expect("row in range");
                    for (b, v) in row.iter() {
                        let wa = self.exp_w[ea] * v;
                        for eb in self.exp_ptr[b]..self.exp_ptr[b + 1] {
                            let db = self.exp_dof[eb] as usize;
                            let w = wa * self.exp_w[eb];
                            match (self.free[db], self.dirichlet_pos[db]) {
                                (rb, _) if rb != NONE => ent.push((rb, w)),
                                (_, d) => dir.push((d, w)),
                            }
                        }
                    }
                }
                if let Some(ct) = &constraint_t {
                    if let Some(col) = ct.outer_view(g) {
                        ent.extend(col.iter().map(|(j, &v)| ((self.nfree + j) as u32, v)));
                    }
                }
                out.push_row(&mut ent, &mut dir);
            }
            out
        };
        const ROWS_PER_CHUNK: usize = 8192;
        let chunks: Vec<RowChunk> = (0..self.nfree.div_ceil(ROWS_PER_CHUNK))
            .into_par_iter()
            .map(|c| build_rows(c * ROWS_PER_CHUNK..((c + 1) * ROWS_PER_CHUNK).min(self.nfree)))
            .collect();
        let mut all = RowChunk::default();
        for c in chunks {
            all.append(c);
        }
        if saddle {
            let (mut ent, mut dir) = (Vec::new(), Vec::new());
            for j in 0..nrows {
                ent.clear();
                dir.clear();
                for (a, &v) in self.rows.outer_view(j).expect("row in range").iter() {
                    match (self.free[a], self.dirichlet_pos[a]) {
                        (f, _) if f != NONE => ent.push((f, v)),
                        (_, d) => dir.push((d, v)),
                    }
                }
                all.push_row(&mut ent, &mut dir);
            }
        }
        all.into_matrices(size, self.dirichlet.len())
    }

    /// The triplet assembly the row-wise [`system_matrix`](Self::system_matrix) must equal.
    #[cfg(test)]
    fn system_matrix_by_triplets(&self, a: &SparseMatrix) -> (SparseMatrix, SparseMatrix) {
        let saddle = self.formulation == Formulation::SaddlePoint;
        let nrows = self.rows.rows();
        let size = self.nfree + if saddle { nrows } else { 0 };
        let mut m = Triplets::default();
        let mut fd = Triplets::default();
        for (a, row) in a.outer_iterator().enumerate() {
            for (b, v) in row.iter() {
                for ea in self.exp_ptr[a]..self.exp_ptr[a + 1] {
                    let ra = self.free[self.exp_dof[ea] as usize];
                    if ra == NONE {
                        continue;
                    }
                    let wa = self.exp_w[ea] * v;
                    for eb in self.exp_ptr[b]..self.exp_ptr[b + 1] {
                        let db = self.exp_dof[eb] as usize;
                        let w = wa * self.exp_w[eb];
                        match (self.free[db], self.dirichlet_pos[db]) {
                            (rb, _) if rb != NONE => m.push(ra, rb, w),
                            (_, d) => fd.push(ra, d, w),
                        }
                    }
                }
            }
        }
        if saddle {
            for (j, row) in self.rows.outer_iterator().enumerate() {
                let rj = (self.nfree + j) as u32;
                for (a, v) in row.iter() {
                    match (self.free[a], self.dirichlet_pos[a]) {
                        (f, _) if f != NONE => {
                            m.push(rj, f, *v);
                            m.push(f, rj, *v);
                        }
                        (_, d) => fd.push(rj, d, *v),
                    }
                }
            }
        }
        (m.to_csr(size, size), fd.to_csr(size, self.dirichlet.len()))
    }
}

/// Rows of the system matrix and of `A_fd`, built row by row.
#[derive(Default)]
struct RowChunk {
    m: (Vec<usize>, Vec<usize>, Vec<f64>),
    fd: (Vec<usize>, Vec<usize>, Vec<f64>),
}

impl RowChunk {
    /// Appends one row of each matrix from its `(column, value)` terms: sorted by column
    /// (stable), equal columns summed in the terms' order.
    fn push_row(&mut self, ent: &mut [(u32, f64)], dir: &mut [(u32, f64)]) {
        for (terms, (len, idx, val)) in [(ent, &mut self.m), (dir, &mut self.fd)] {
            terms.sort_by_key(|t| t.0);
            let start = idx.len();
            for &(c, v) in terms.iter() {
                if idx.len() > start && *idx.last().expect("an entry") == c as usize {
                    *val.last_mut().expect("an entry") += v;
                } else {
                    idx.push(c as usize);
                    val.push(v);
                }
            }
            len.push(idx.len() - start);
        }
    }

    fn append(&mut self, other: RowChunk) {
        for (a, b) in [(&mut self.m, other.m), (&mut self.fd, other.fd)] {
            a.0.extend(b.0);
            a.1.extend(b.1);
            a.2.extend(b.2);
        }
    }

    /// The `size x size` system matrix and the `size x ndir` matrix `A_fd`.
    fn into_matrices(self, size: usize, ndir: usize) -> (SparseMatrix, SparseMatrix) {
        let csr = |(len, idx, val): (Vec<usize>, Vec<usize>, Vec<f64>), cols: usize| {
            let mut ptr = Vec::with_capacity(len.len() + 1);
            ptr.push(0);
            for l in len {
                ptr.push(ptr.last().expect("a start") + l);
            }
            SparseMatrix::new((size, cols), ptr, idx, val)
        };
        (csr(self.m, size), csr(self.fd, ndir))
    }
}

/// `K <- S K S` for the diagonal `S = diag(scale)`.
fn scale_symmetric(k: &mut SparseMatrix, scale: &[f64]) {
    if scale.iter().all(|&s| s == 1.0) {
        return;
    }
    for (r, mut row) in k.outer_iterator_mut().enumerate() {
        for (c, v) in row.iter_mut() {
            *v *= scale[r] * scale[c];
        }
    }
}

/// The constraint rows after the treatment of Dirichlet slave nodes.
struct Crossing {
    rows: SparseMatrix,
    origin: Vec<u32>,
    own: Vec<u32>,
    redistributed: usize,
    dropped: usize,
}

/// The rows `D T_s - M T_m` over the global unknowns (slave body first), with the rows of
/// Dirichlet slave nodes shared equally among the free slave nodes of their faces (see
/// [`SlaveDirichlet::Redistribute`]).
fn modified_rows(
    tie: &Tie,
    n_slave: usize,
    dirichlet_pos: &[u32],
    policy: SlaveDirichlet,
) -> Result<Crossing, PhysicsError> {
    let ns = tie.slave_dofs().len();
    let comps = tie.components();
    // Rows that carry a multiplier: all but the empty ones of nodes without (linear
    // multipliers on second-order faces), which constrain nothing.
    let carries = tie.rows_with_multiplier();
    let fixed: Vec<bool> = tie
        .slave_dofs()
        .iter()
        .zip(&carries)
        .map(|(&s, &c)| c && dirichlet_pos[s as usize] != NONE)
        .collect();
    let count = fixed.iter().filter(|f| **f).count();
    if count > 0 && policy == SlaveDirichlet::Refuse {
        let first = fixed.iter().position(|f| *f).expect("count > 0");
        return Err(PhysicsError::DirichletOnSlave {
            tag: tie.row_tag(first),
            count,
        });
    }
    let mut new_of = vec![NONE; ns];
    let (mut origin, mut own) = (Vec::new(), Vec::new());
    for r in 0..ns {
        if carries[r] && !fixed[r] {
            new_of[r] = origin.len() as u32;
            origin.push(r as u32);
            own.push(tie.slave_dofs()[r]);
        }
    }
    let interface = tie.interface();
    let shares = shares(
        interface.slave(),
        interface.slave_nodes(),
        |n| interface.slave_row(n),
        comps,
        &carries,
        &fixed,
    );
    let (mut redistributed, mut dropped) = (0usize, 0usize);
    let mut t = Triplets::default();
    for r in (0..ns).filter(|&r| carries[r]) {
        let targets: Vec<(u32, f64)> = if fixed[r] {
            if shares[r].is_empty() {
                dropped += 1;
            } else {
                redistributed += 1;
            }
            shares[r]
                .iter()
                .map(|&(k, w)| (new_of[k as usize], w))
                .collect()
        } else {
            vec![(new_of[r], 1.0)]
        };
        for (row, w) in targets {
            if let Some(d) = tie.d().outer_view(r) {
                for (k, v) in d.iter() {
                    t.push(row, tie.slave_dofs()[k], w * v);
                }
            }
            if let Some(m) = tie.m().outer_view(r) {
                for (l, v) in m.iter() {
                    t.push(
                        row,
                        (n_slave + tie.master_dofs()[l] as usize) as u32,
                        -w * v,
                    );
                }
            }
        }
    }
    let ndof = dirichlet_pos.len();
    Ok(Crossing {
        rows: t.to_csr(origin.len(), ndof),
        origin,
        own,
        redistributed,
        dropped,
    })
}

/// The unknown counts of the body matrices `[slave, master]`, refused when one is not
/// square.
fn check_columns(matrices: [&SparseMatrix; 2]) -> Result<[usize; 2], PhysicsError> {
    let n = [matrices[0].rows(), matrices[1].rows()];
    for (b, m) in matrices.iter().enumerate() {
        if m.cols() != n[b] {
            return Err(PhysicsError::WrongLength {
                what: format!("columns of body {b}'s matrix"),
                expected: n[b],
                got: m.cols(),
            });
        }
    }
    Ok(n)
}

/// Per global unknown (slave body first, bodies of `n` unknowns), its position in the list
/// of Dirichlet unknowns or NONE, and that list (global indices): `dirichlet` refused where
/// an unknown is out of range or listed twice.
fn dirichlet_positions(
    dirichlet: [&[u32]; 2],
    n: [usize; 2],
) -> Result<(Vec<u32>, Vec<u32>), PhysicsError> {
    let mut dirichlet_pos = vec![NONE; n[0] + n[1]];
    let mut dlist = Vec::with_capacity(dirichlet[0].len() + dirichlet[1].len());
    for (b, list) in dirichlet.iter().enumerate() {
        let offset = if b == 0 { 0 } else { n[0] };
        for &node in *list {
            if node as usize >= n[b] {
                return Err(PhysicsError::InvalidInput {
                    body: format!("body {b}"),
                    what: format!("Dirichlet node index {node} out of range ({})", n[b]),
                });
            }
            let g = offset + node as usize;
            if dirichlet_pos[g] != NONE {
                return Err(PhysicsError::InvalidInput {
                    body: format!("body {b}"),
                    what: format!("Dirichlet node index {node} listed twice"),
                });
            }
            dirichlet_pos[g] = dlist.len() as u32;
            dlist.push(g as u32);
        }
    }
    Ok((dirichlet_pos, dlist))
}

/// Refuses a tie whose slave or master unknowns lie beyond the bodies' `n` unknowns.
fn check_tie_sizes(tie: &Tie, n: [usize; 2]) -> Result<(), PhysicsError> {
    for (r, &s) in tie.slave_dofs().iter().enumerate() {
        if s as usize >= n[0] {
            return Err(PhysicsError::WrongLength {
                what: format!("slave body matrix (interface row {r} is node {s})"),
                expected: s as usize + 1,
                got: n[0],
            });
        }
    }
    if let Some(&m) = tie.master_dofs().iter().max() {
        if m as usize >= n[1] {
            return Err(PhysicsError::WrongLength {
                what: "master body matrix".into(),
                expected: m as usize + 1,
                got: n[1],
            });
        }
    }
    Ok(())
}

/// The formulation of the options' choice given whether the `nrows` rows can be condensed
/// (`check`), and why.
///
/// # Errors
/// The reason the rows cannot be condensed when the condensation is forced.
fn choose_formulation(
    options: &TiedOptions,
    check: Result<(), TyingError>,
    nrows: usize,
) -> Result<(Formulation, String), PhysicsError> {
    Ok(match (options.formulation, check) {
        (FormulationChoice::SaddlePoint, _) => (
            Formulation::SaddlePoint,
            "the saddle point was requested".to_string(),
        ),
        (FormulationChoice::DualCondensed, Err(e)) => return Err(e.into()),
        (_, Ok(())) if nrows == 0 => (
            Formulation::DualCondensed,
            "no multiplier is left (every slave interface node is a Dirichlet node)".to_string(),
        ),
        (FormulationChoice::DualCondensed, Ok(())) => (
            Formulation::DualCondensed,
            "the condensation was requested, and D is diagonal".to_string(),
        ),
        (FormulationChoice::Auto, Ok(())) => (
            Formulation::DualCondensed,
            "D is diagonal on the unknowns that carry the rows (dual multipliers on a fully \
             covered interface, or linear multipliers on straight Line3 faces), so the \
             slave unknowns condense out (T_s = D^-1 M T_m) into a symmetric positive \
             definite system"
                .to_string(),
        ),
        (FormulationChoice::Auto, Err(e)) => (
            Formulation::SaddlePoint,
            why_not_diagonal(&e, options.diagonal_tolerance),
        ),
    })
}

/// Per global unknown its index among the factorised system's unknowns (NONE for the
/// Dirichlet ones and, when `condense`, the rows' own unknowns), and their count.
fn system_unknowns(dirichlet_pos: &[u32], own_row: &[u32], condense: bool) -> (Vec<u32>, usize) {
    let mut free = vec![NONE; dirichlet_pos.len()];
    let mut nfree = 0usize;
    for g in 0..dirichlet_pos.len() {
        if dirichlet_pos[g] == NONE && !(condense && own_row[g] != NONE) {
            free[g] = nfree as u32;
            nfree += 1;
        }
    }
    (free, nfree)
}

/// The expansions `T_g = sum w T_r` of every global unknown, compressed by unknown
/// (`ptr`, unknowns, weights): a row's own unknown, when `condense`, from the rest of its
/// row `rows` (`own_row`: per unknown the row it is own to, or NONE); every other one
/// itself.
fn expansions(
    rows: &SparseMatrix,
    own_row: &[u32],
    condense: bool,
) -> (Vec<usize>, Vec<u32>, Vec<f64>) {
    let (mut exp_ptr, mut exp_dof, mut exp_w) = (vec![0usize], Vec::new(), Vec::new());
    for g in 0..own_row.len() {
        if condense && own_row[g] != NONE {
            let j = own_row[g] as usize;
            let row = rows.outer_view(j).expect("row in range");
            let d = row.get(g).copied().unwrap_or(0.0);
            for (k, v) in row.iter() {
                if k != g && own_row[k] == NONE {
                    exp_dof.push(k as u32);
                    exp_w.push(-v / d);
                }
            }
        } else {
            exp_dof.push(g as u32);
            exp_w.push(1.0);
        }
        exp_ptr.push(exp_dof.len());
    }
    (exp_ptr, exp_dof, exp_w)
}

/// Whether the rows can be condensed: each row's own entry positive, and its entries on other
/// rows' own unknowns at most `tol` times it.
fn check_diagonal(
    crossing: &Crossing,
    own_row: &[u32],
    tol: f64,
    tie: &Tie,
) -> Result<(), TyingError> {
    for (j, row) in crossing.rows.outer_iterator().enumerate() {
        let s = crossing.own[j] as usize;
        let d = row.get(s).copied().unwrap_or(0.0);
        let origin = crossing.origin[j] as usize;
        if d.is_nan() || d <= 0.0 {
            return Err(TyingError::Uncovered {
                row: origin,
                tag: tie.row_tag(origin),
                value: d,
            });
        }
        for (k, v) in row.iter() {
            if k != s && own_row[k] != NONE && v.abs() > tol * d {
                let col = crossing.origin[own_row[k] as usize] as usize;
                return Err(TyingError::NotDiagonal {
                    row: origin,
                    col,
                    value: *v,
                    diagonal: d,
                });
            }
        }
    }
    Ok(())
}

/// Why the condensation is not available, for the report.
fn why_not_diagonal(e: &TyingError, tol: f64) -> String {
    match e {
        TyingError::NotDiagonal {
            row,
            col,
            value,
            diagonal,
        } => format!(
            "D is not diagonal: D[{row},{col}] = {value:.3e} against D[{row},{row}] = \
             {diagonal:.3e} (relative {:.1e}, tolerance {tol:.0e}): standard multipliers, linear \
             multipliers on second-order faces, a partly covered interface, or dual \
             multipliers on warped or recombined faces; the condensation needs a diagonal D",
            (value / diagonal).abs()
        ),
        TyingError::Uncovered { tag, value, .. } => format!(
            "slave node {tag} is not covered by the master surface (D_jj = {value:.3e}); the \
             condensation needs every slave node covered"
        ),
    }
}

/// `[[a, 0], [0, b]]` in CSR, by concatenating the arrays.
/// `m` in CSR storage: borrowed if it is, copied if not.
fn row_major(m: &SparseMatrix) -> std::borrow::Cow<'_, SparseMatrix> {
    if m.is_csr() {
        std::borrow::Cow::Borrowed(m)
    } else {
        std::borrow::Cow::Owned(m.to_csr())
    }
}

/// The rows `rows` of `a`, in that order, as a matrix of `rows.len()` rows (each row's
/// entries in `a`'s order).
fn rows_of(a: &SparseMatrix, rows: &[u32]) -> SparseMatrix {
    let mut indptr = Vec::with_capacity(rows.len() + 1);
    indptr.push(0);
    let (mut indices, mut data) = (Vec::new(), Vec::new());
    for &r in rows {
        if let Some(row) = a.outer_view(r as usize) {
            for (k, v) in row.iter() {
                indices.push(k);
                data.push(*v);
            }
        }
        indptr.push(indices.len());
    }
    SparseMatrix::new((rows.len(), a.cols()), indptr, indices, data)
}

fn block_diagonal(a: &SparseMatrix, b: &SparseMatrix) -> SparseMatrix {
    let (a, b) = (row_major(a), row_major(b));
    let (na, nb) = (a.rows(), b.rows());
    let (ca, cb) = (a.cols(), b.cols());
    let mut indptr: Vec<usize> = a.proper_indptr().into_owned();
    let base = a.nnz();
    indptr.extend(b.proper_indptr().iter().skip(1).map(|p| p + base));
    let mut indices: Vec<usize> = a.indices().to_vec();
    indices.extend(b.indices().iter().map(|c| c + ca));
    let mut data: Vec<f64> = a.data().to_vec();
    data.extend_from_slice(b.data());
    SparseMatrix::new((na + nb, ca + cb), indptr, indices, data)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Eight unknowns (five of the slave body, three of the master), two Dirichlet ones (0,
    /// 6), and two slave unknowns (3, 4) tied to the master's three (a Dirichlet one among
    /// them): condensed, or kept with two constraint rows (saddle point).
    fn layout(formulation: Formulation) -> Layout {
        let ndof = 8;
        let dirichlet = vec![0u32, 6];
        let mut dirichlet_pos = vec![NONE; ndof];
        dirichlet_pos[0] = 0;
        dirichlet_pos[6] = 1;
        let ties: [(usize, &[(u32, f64)]); 2] = [
            (3, &[(5, 0.4), (6, 0.1), (7, 0.5)]),
            (4, &[(6, 0.3), (5, 0.2), (7, 0.5)]),
        ];
        let mut rows = Triplets::default();
        for (j, (s, exp)) in ties.iter().enumerate() {
            rows.push(j as u32, *s as u32, 1.0);
            for &(m, w) in exp.iter() {
                rows.push(j as u32, m, -w);
            }
        }
        let condensed = |g: usize| formulation == Formulation::DualCondensed && (g == 3 || g == 4);
        let mut free = vec![NONE; ndof];
        let mut nfree = 0;
        for g in 0..ndof {
            if dirichlet_pos[g] == NONE && !condensed(g) {
                free[g] = nfree;
                nfree += 1;
            }
        }
        let (mut exp_ptr, mut exp_dof, mut exp_w) = (vec![0], Vec::new(), Vec::new());
        for g in 0..ndof {
            match ties.iter().find(|t| t.0 == g) {
                Some((_, exp)) if condensed(g) => {
                    for &(m, w) in exp.iter() {
                        exp_dof.push(m);
                        exp_w.push(w);
                    }
                }
                _ => {
                    exp_dof.push(g as u32);
                    exp_w.push(1.0);
                }
            }
            exp_ptr.push(exp_dof.len());
        }
        Layout {
            formulation,
            n: [5, 3],
            comps: 1,
            nd: [1, 1],
            dirichlet,
            dirichlet_pos,
            rows: rows.to_csr(2, ndof),
            row_origin: vec![0, 1],
            row_own: vec![3, 4],
            coupling_rows: 2,
            free,
            nfree: nfree as usize,
            exp_ptr,
            exp_dof,
            exp_w,
        }
    }

    /// The row-wise build gives the triplet assembly's matrices bit for bit, for both
    /// formulations, on a matrix whose sums round differently in another order.
    #[test]
    fn row_wise_system_matrix_is_the_triplet_one() {
        let mut t = Triplets::default();
        for i in 0..8u32 {
            for j in 0..8u32 {
                if (i * 3 + j * 5) % 7 != 0 {
                    let v =
                        0.1 * f64::from(i + 1) + 1e-3 / f64::from(j + 1) + 1e-7 * f64::from(i * j);
                    t.push(i, j, v);
                    t.push(j, i, v);
                }
            }
        }
        let a = t.to_csr(8, 8);
        for formulation in [Formulation::DualCondensed, Formulation::SaddlePoint] {
            let l = layout(formulation);
            let (m, fd) = l.system_matrix(&a);
            let (m0, fd0) = l.system_matrix_by_triplets(&a);
            for (new, old) in [(&m, &m0), (&fd, &fd0)] {
                assert_eq!(new.shape(), old.shape(), "{formulation:?}");
                assert_eq!(new.indptr().raw_storage(), old.indptr().raw_storage());
                assert_eq!(new.indices(), old.indices(), "{formulation:?}");
                let bits =
                    |m: &SparseMatrix| m.data().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(new), bits(old), "{formulation:?}");
            }
            assert!(m.nnz() > 10 && fd.nnz() > 2);
        }
    }
}
