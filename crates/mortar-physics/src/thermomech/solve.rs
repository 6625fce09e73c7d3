//! The solves of the thermomechanical problem: Newton on the assembled Jacobian (the axial
//! unknowns as a bordered LU's border) or JFNK with the block lower-triangular preconditioner.

use std::sync::Arc;
use std::time::Instant;

use mortar_fem::linalg::{
    BorderedLu, Factorization, LuFactorization, MatrixKind, Preconditioner, SolverError,
    SparseMatrix, SparseSolver, Triplets,
};

use super::problem::{GapThermoMechanics, Offsets};
use crate::error::PhysicsError;
use crate::heat::{Linearization, StepData};
use crate::laws::ConstraintLaw;
use crate::nonlinear::{
    assembled_residual_scale, jfnk_solve, JfnkOptions, NewtonOptions, NewtonProblem, NewtonReport,
    SolverStats,
};

/// How the linearised problems of [`GapThermoMechanics`] are solved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ThermoMechSolver {
    /// Newton on the assembled exact Jacobian of the whole problem, sparse LU (symbolic
    /// analysis reused while the pattern holds), refactorised every Newton step; or, with a
    /// backend ([`ThermoMechSolverState::with_backend`]), each Jacobian handed to it as a
    /// general (nonsymmetric) matrix.
    Newton,
    /// Jacobian-free Newton-Krylov on the whole residual: GMRES on finite-difference
    /// products, right-preconditioned by the block lower-triangular preconditioner of the
    /// thermal unknowns (temperatures, fluxes) and the mechanical ones (displacements,
    /// pressures, gas pressure), each block factorised by itself from the Picard matrix,
    /// and kept across Newton steps and time steps until GMRES slows down.
    Jfnk(JfnkOptions),
}

/// Counters of the solves, accumulated over calls.
pub type ThermoMechStats = SolverStats;

/// GMRES is "slowing down" when a solve takes more than this many times the iterations of
/// the first solve after the last factorisation (and at least [`SLOWDOWN_MIN`] more): a
/// solve with a kept preconditioner is stopped there, the blocks refactorised and the solve
/// started again.
const SLOWDOWN_RATIO: usize = 2;
/// See [`SLOWDOWN_RATIO`].
const SLOWDOWN_MIN: usize = 5;

/// The solver state kept across Newton steps and time steps.
#[derive(Debug)]
pub struct ThermoMechSolverState {
    /// The method.
    pub method: ThermoMechSolver,
    lu: Option<BorderedLu>,
    /// The backend Newton's Jacobians go to, if not the bordered LU.
    backend: Option<Arc<dyn SparseSolver>>,
    /// The backend's set-up of the last Jacobian.
    backend_factors: Option<Box<dyn Factorization>>,
    block: Option<BlockPreconditioner>,
    /// GMRES iterations of the first solve after the last factorisation, and of the last.
    iterations: (usize, usize),
    /// The counters.
    pub stats: ThermoMechStats,
}

impl ThermoMechSolverState {
    /// A fresh state for `method`.
    pub fn new(method: ThermoMechSolver) -> Self {
        Self {
            method,
            lu: None,
            backend: None,
            backend_factors: None,
            block: None,
            iterations: (0, 0),
            stats: ThermoMechStats::default(),
        }
    }

    /// Newton's Jacobians solved by `backend` (a PETSc Krylov solve, say) as general
    /// matrices, in place of the bordered sparse LU; JFNK's block preconditioner keeps its own
    /// factorisations.
    pub fn with_backend(mut self, backend: Arc<dyn SparseSolver>) -> Self {
        self.backend = Some(backend);
        self
    }

    fn slowed_down(&self) -> bool {
        let (first, last) = self.iterations;
        last > SLOWDOWN_RATIO * first && last >= first + SLOWDOWN_MIN
    }
}

/// The block lower-triangular preconditioner: thermal unknowns first, then the mechanical
/// ones with the thermal correction's coupling (thermal expansion) subtracted.
#[derive(Debug)]
struct BlockPreconditioner {
    thermal: Vec<usize>,
    mechanical: Vec<usize>,
    thermal_lu: LuFactorization,
    /// The mechanical block, its last unknowns (the axial ones, dense rows and columns) as a
    /// border.
    mechanical_lu: BorderedLu,
    /// Mechanical rows, thermal columns (local numbering).
    coupling: SparseMatrix,
}

impl BlockPreconditioner {
    /// The blocks of `a`; `thermal[i]` says whether unknown `i` is thermal; the last
    /// `border` unknowns (mechanical) are the mechanical block's border.
    fn new(
        a: &SparseMatrix,
        is_thermal: &[bool],
        border: usize,
    ) -> Result<(Self, usize), SolverError> {
        let mut local = vec![0u32; is_thermal.len()];
        let (mut thermal, mut mechanical) = (Vec::new(), Vec::new());
        for (i, &t) in is_thermal.iter().enumerate() {
            if t {
                local[i] = thermal.len() as u32;
                thermal.push(i);
            } else {
                local[i] = mechanical.len() as u32;
                mechanical.push(i);
            }
        }
        let (mut tt, mut mm, mut mt) = (
            Triplets::default(),
            Triplets::default(),
            Triplets::default(),
        );
        for (row, vec) in a.outer_iterator().enumerate() {
            for (col, &v) in vec.iter() {
                match (is_thermal[row], is_thermal[col]) {
                    (true, true) => tt.push(local[row], local[col], v),
                    (false, false) => mm.push(local[row], local[col], v),
                    (false, true) => mt.push(local[row], local[col], v),
                    (true, false) => {}
                }
            }
        }
        let (nt, nm) = (thermal.len(), mechanical.len());
        let thermal_lu = LuFactorization::try_new(&tt.to_csr(nt, nt))?;
        let mechanical_lu = BorderedLu::try_new(&mm.to_csr(nm, nm), border)?;
        Ok((
            Self {
                thermal,
                mechanical,
                thermal_lu,
                mechanical_lu,
                coupling: mt.to_csr(nm, nt),
            },
            2,
        ))
    }
}

impl Preconditioner for BlockPreconditioner {
    fn apply_in_place(&self, x: &mut [f64]) -> Result<(), SolverError> {
        let mut xt: Vec<f64> = self.thermal.iter().map(|&i| x[i]).collect();
        self.thermal_lu.solve_in_place(&mut xt)?;
        let mut xm: Vec<f64> = self.mechanical.iter().map(|&i| x[i]).collect();
        for (row, vec) in self.coupling.outer_iterator().enumerate() {
            xm[row] -= vec.iter().map(|(c, v)| v * xt[c]).sum::<f64>();
        }
        self.mechanical_lu.solve_in_place(&mut xm)?;
        for (&i, v) in self.thermal.iter().zip(xt) {
            x[i] = v;
        }
        for (&i, v) in self.mechanical.iter().zip(xm) {
            x[i] = v;
        }
        Ok(())
    }
}

impl<TL: ConstraintLaw, ML: ConstraintLaw> GapThermoMechanics<TL, ML> {
    /// Solves for the state at time `t`: steady when `transient` is `None`, else one backward
    /// Euler step of size `dt` from `old` (the previous state). `x` is the initial guess and,
    /// on success, the solution.
    ///
    /// # Errors
    /// [`PhysicsError::Newton`] with the residual history when Newton fails, and the errors
    /// of the assembly, of the laws and of the linear solvers.
    pub fn solve(
        &self,
        x: &mut [f64],
        t: f64,
        transient: Option<(&[f64], f64)>,
        solver: &mut ThermoMechSolverState,
        options: &NewtonOptions,
    ) -> Result<NewtonReport, PhysicsError> {
        let data = self.heat.step_data(t, transient)?;
        let mut step = Step {
            problem: self,
            data,
            solver,
        };
        SolverStats::timed_newton(&mut step, x, options, |s| &mut s.solver.stats)
    }

    /// The residual of a steady solve at time `t` (for checks and tests).
    ///
    /// # Errors
    /// The errors of the assembly and of the laws.
    pub fn steady_residual(&self, x: &[f64], t: f64) -> Result<Vec<f64>, PhysicsError> {
        let data = self.heat.step_data(t, None)?;
        let mut r = vec![0.0; self.dimension()];
        self.evaluate(x, &data, &mut r, None)?;
        Ok(r)
    }

    /// The exact Jacobian of a steady solve at time `t` (for checks and tests).
    ///
    /// # Errors
    /// As [`steady_residual`](Self::steady_residual).
    pub fn steady_jacobian(&self, x: &[f64], t: f64) -> Result<SparseMatrix, PhysicsError> {
        let data = self.heat.step_data(t, None)?;
        let mut r = vec![0.0; self.dimension()];
        Ok(self
            .evaluate(x, &data, &mut r, Some(Linearization::Newton))?
            .expect("a matrix was asked"))
    }

    /// The number of axial unknowns (the last ones).
    fn axial_unknowns(&self) -> usize {
        self.offsets.axial.iter().flatten().count()
    }

    /// Whether each unknown is thermal (temperature, flux) rather than mechanical.
    fn thermal_unknowns(&self) -> Vec<bool> {
        let o: &Offsets = &self.offsets;
        (0..o.len).map(|i| i < o.u[0] || o.is_flux(i)).collect()
    }
}

/// One solve as a [`NewtonProblem`].
struct Step<'a, TL, ML> {
    problem: &'a GapThermoMechanics<TL, ML>,
    data: StepData,
    solver: &'a mut ThermoMechSolverState,
}

/// The matrix of `lin` at `x`, its assembly time counted.
fn matrix<TL: ConstraintLaw, ML: ConstraintLaw>(
    problem: &GapThermoMechanics<TL, ML>,
    data: &StepData,
    stats: &mut ThermoMechStats,
    x: &[f64],
    lin: Linearization,
) -> Result<SparseMatrix, PhysicsError> {
    let t0 = Instant::now();
    let mut scratch = vec![0.0; x.len()];
    let a = problem
        .evaluate(x, data, &mut scratch, Some(lin))?
        .expect("a matrix was asked");
    stats.assembly_seconds += t0.elapsed().as_secs_f64();
    Ok(a)
}

/// Factorises the blocks of the Picard matrix at `x` into `solver`.
fn refresh_blocks<TL: ConstraintLaw, ML: ConstraintLaw>(
    problem: &GapThermoMechanics<TL, ML>,
    data: &StepData,
    solver: &mut ThermoMechSolverState,
    x: &[f64],
) -> Result<(), PhysicsError> {
    let a = matrix(problem, data, &mut solver.stats, x, Linearization::Picard)?;
    let t0 = Instant::now();
    let border = problem.axial_unknowns();
    let (pc, analyses) = BlockPreconditioner::new(&a, &problem.thermal_unknowns(), border)?;
    let stats = &mut solver.stats;
    stats.symbolic_analyses += analyses;
    stats.factorizations += 1;
    stats.linear_seconds += t0.elapsed().as_secs_f64();
    solver.block = Some(pc);
    solver.iterations = (0, 0);
    Ok(())
}

impl<TL: ConstraintLaw, ML: ConstraintLaw> NewtonProblem for Step<'_, TL, ML> {
    fn residual(&self, x: &[f64], r: &mut [f64]) -> Result<(), PhysicsError> {
        self.problem.evaluate(x, &self.data, r, None).map(|_| ())
    }

    fn solve_linearized(
        &mut self,
        x: &[f64],
        r: &[f64],
        dx: &mut [f64],
        forcing: f64,
    ) -> Result<usize, PhysicsError> {
        match self.solver.method {
            ThermoMechSolver::Newton => {
                let a = matrix(
                    self.problem,
                    &self.data,
                    &mut self.solver.stats,
                    x,
                    Linearization::Newton,
                )?;
                let t0 = Instant::now();
                let solver = &mut *self.solver;
                dx.copy_from_slice(r);
                if let Some(backend) = &solver.backend {
                    let factors = solver.stats.counted(&mut solver.backend_factors, &a, || {
                        backend.factor(&a, MatrixKind::General)
                    })?;
                    factors.solve_in_place(dx)?;
                } else {
                    // The axial unknowns (last, dense rows and columns) as the border.
                    let border = self.problem.axial_unknowns();
                    let lu = solver
                        .stats
                        .factorize_bordered(&mut solver.lu, &a, border)?;
                    lu.solve_in_place(dx)?;
                }
                solver.stats.linear_seconds += t0.elapsed().as_secs_f64();
                Ok(1)
            }
            ThermoMechSolver::Jfnk(opts) => {
                let fresh = self.solver.block.is_none() || self.solver.slowed_down();
                let (problem, data) = (self.problem, &self.data);
                if fresh {
                    refresh_blocks(problem, data, self.solver, x)?;
                } else {
                    self.solver.stats.reused_preconditioners += 1;
                }
                let f = |x: &[f64], r: &mut [f64]| problem.evaluate(x, data, r, None).map(|_| ());
                let t0 = Instant::now();
                dx.fill(0.0);
                // A kept preconditioner gets the iterations of a solve that has not slowed
                // down; past them it is refactorised and the solve starts again.
                let first = self.solver.iterations.0;
                let capped = if fresh {
                    opts
                } else {
                    JfnkOptions {
                        max_iterations: (SLOWDOWN_RATIO * first)
                            .max(first + SLOWDOWN_MIN)
                            .min(opts.max_iterations),
                        ..opts
                    }
                };
                let pc = self.solver.block.as_ref().expect("built above");
                let mut out = jfnk_solve(&f, x, r, pc, dx, forcing, &capped);
                let stale = !fresh
                    && match &out {
                        Err(_) => true,
                        Ok(rep) => rep.relative_residual > forcing,
                    };
                let mut wasted = 0;
                if stale {
                    wasted = out
                        .as_ref()
                        .map_or(capped.max_iterations, |rep| rep.iterations);
                    self.solver.stats.linear_seconds += t0.elapsed().as_secs_f64();
                    let t1 = Instant::now();
                    refresh_blocks(problem, data, self.solver, x)?;
                    dx.fill(0.0);
                    let pc = self.solver.block.as_ref().expect("built above");
                    out = jfnk_solve(&f, x, r, pc, dx, forcing, &opts);
                    self.solver.stats.linear_seconds += t1.elapsed().as_secs_f64();
                } else {
                    self.solver.stats.linear_seconds += t0.elapsed().as_secs_f64();
                }
                let its = out?.iterations;
                let (first, _) = self.solver.iterations;
                self.solver.iterations = (if first == 0 { its.max(1) } else { first }, its);
                // The iterations of an abandoned solve count too.
                Ok(its + wasted)
            }
        }
    }

    /// `| |A| |x| | + |F(x) - A x|`, `A` the Picard matrix at `x`: the magnitudes of the
    /// terms before they cancel.
    fn residual_scale(&mut self, x: &[f64]) -> Result<f64, PhysicsError> {
        let mut r = vec![0.0; x.len()];
        let a = self
            .problem
            .evaluate(x, &self.data, &mut r, Some(Linearization::Picard))?
            .expect("a matrix was asked");
        Ok(assembled_residual_scale(&a, x, &r))
    }
}
