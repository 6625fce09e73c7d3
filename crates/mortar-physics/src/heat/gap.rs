//! Two bodies exchanging heat across an interface through a pointwise [`ConstraintLaw`]
//! (gap conductance, tying), with `k(T)` conduction, steady or backward Euler, solved by
//! Newton on the assembled Jacobian or by Jacobian-free Newton-Krylov.

use std::time::Instant;

use mortar_core::mesh::SurfaceMesh;
use mortar_core::{assemble_coupling, CouplingOptions, Interface, Tolerances};
use mortar_fem::linalg::{LuFactorization, SparseMatrix, Triplets};

use super::assembly::{assemble_heat_load, assemble_heat_matrices, HeatOptions};
use super::body::HeatBody;
use super::nonlinear::{assemble_conduction, Conductivity, Linearization};
use crate::error::PhysicsError;
use crate::laws::{evaluate, ConstraintLaw, LawPoint};
use crate::nonlinear::{
    assembled_residual_scale, jfnk_solve, JfnkOptions, NewtonOptions, NewtonProblem, NewtonReport,
    SolverStats,
};
use crate::tied::Tie;

/// How the linearised problems of [`GapHeat`] are solved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GapSolver {
    /// Newton on the assembled exact Jacobian, sparse LU (symbolic analysis reused).
    Newton,
    /// Jacobian-free Newton-Krylov: GMRES on finite-difference Jacobian-vector products,
    /// right-preconditioned by the sparse LU of the Picard matrix (frozen conductivities,
    /// law tangent without its temperature derivative), refactorised once per Newton step
    /// with the symbolic analysis reused.
    Jfnk(JfnkOptions),
}

/// Counters of the linear algebra of [`GapHeat`] solves, accumulated over calls.
pub type GapSolverStats = SolverStats;

/// The solver state kept across Newton steps and time steps (the LU with its symbolic
/// analysis, and the counters).
#[derive(Debug, Clone)]
pub struct GapSolverState {
    /// The method.
    pub method: GapSolver,
    lu: Option<LuFactorization>,
    /// The counters.
    pub stats: GapSolverStats,
}

impl GapSolverState {
    /// A fresh state for `method`.
    pub fn new(method: GapSolver) -> Self {
        Self {
            method,
            lu: None,
            stats: GapSolverStats::default(),
        }
    }
}

/// Heat conduction with `k(T)` in two bodies (slave, master) exchanging heat across an
/// interface through a pointwise [`ConstraintLaw`] (e.g. a
/// [`GapConductance`](crate::laws::GapConductance) across an open gap).
///
/// Unknowns: the slave body's nodal temperatures, the master body's, then one multiplier
/// per slave interface node (a row of D), the heat flux leaving the slave. Residual:
///
/// ```text
/// slave:   f_int(T_s) + C_s (T_s - T_s_old)/dt - F_s + D^T lambda
/// master:  f_int(T_m) + C_m (T_m - T_m_old)/dt - F_m - M^T lambda
/// law j:   d_j C(g_j, lambda_j; Tbar_j),   d_j = sum_k D_jk,
///          g_j = (D T_s - M T_m)_j / d_j,  Tbar_j = (D T_s + M T_m)_j / (2 d_j)
/// ```
///
/// (the capacity terms dropped in a steady solve), Dirichlet rows replaced by `T - g`. With
/// dual multipliers (D diagonal) `g_j` and `Tbar_j` are the jump and mean of the slave
/// node's temperature and the projected master temperature. The interface may be open: the
/// coupling projects across the gap (give the search distance in `tolerances`).
#[derive(Debug, Clone)]
pub struct GapHeat<L> {
    bodies: [HeatBody; 2],
    conductivity: [Conductivity; 2],
    law: L,
    tie: Tie,
    capacity: [SparseMatrix; 2],
    options: HeatOptions,
    dirichlet: [Vec<u32>; 2],
    is_dirichlet: Vec<bool>,
    weight: Vec<f64>,
    scale: f64,
}

/// The data of one solve: time, step and previous state.
#[derive(Debug, Clone)]
pub(crate) struct StepData {
    /// External loads (plus capacity times old temperatures over dt) per body.
    load: [Vec<f64>; 2],
    /// Dirichlet values per body, in the order of `dirichlet`.
    values: [Vec<f64>; 2],
    inv_dt: f64,
    /// The time the solve reaches (s).
    pub(crate) time: f64,
}

impl<L: ConstraintLaw> GapHeat<L> {
    /// Builds the problem: capacities, the coupling of `slave_surface` and `master_surface`
    /// (whose node tags are the bodies' node tags) with the given tolerances (for an open gap,
    /// a `search_distance` above the gap width), and the law.
    ///
    /// The coupling and the assembly must use the same geometry
    /// ([`CouplingOptions::geometry`], [`HeatOptions::geometry`]): with both axisymmetric the
    /// law's terms `d_j C(...)` take the revolved areas `d_j = sum_k D_jk` of the r-z coupling,
    /// and the problem is the r-z one (heat flows in W, fluxes in W/m^2).
    ///
    /// # Errors
    /// [`PhysicsError::Mortar`] for a bad interface, [`PhysicsError::InvalidInput`] for a
    /// conductivity law out of range, a slave interface node without coupling, or a coupling
    /// geometry other than the heat options', and the errors of the assembly.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        slave: (HeatBody, Conductivity),
        master: (HeatBody, Conductivity),
        slave_surface: SurfaceMesh,
        master_surface: SurfaceMesh,
        coupling: &CouplingOptions,
        tolerances: Tolerances,
        law: L,
        options: &HeatOptions,
    ) -> Result<Self, PhysicsError> {
        crate::field::cells::check_same_geometry(coupling.geometry, options.geometry)?;
        let (slave, ks) = slave;
        let (master, km) = master;
        ks.check(&slave.name)?;
        km.check(&master.name)?;
        let capacity = [
            assemble_heat_matrices(&slave, options)?.capacity,
            assemble_heat_matrices(&master, options)?.capacity,
        ];
        let interface = Interface::with_tolerances(slave_surface, master_surface, tolerances)?;
        let c = assemble_coupling(&interface, coupling)?;
        let tie = Tie::from_coupling(&slave.mesh, &master.mesh, interface, c)?;
        let weight: Vec<f64> = tie
            .coupling()
            .d
            .outer_iterator()
            .map(|row| row.iter().map(|(_, v)| v).sum())
            .collect();
        if let Some(j) = weight.iter().position(|&w| !(w > 0.0 && w.is_finite())) {
            return Err(PhysicsError::InvalidInput {
                body: slave.name.clone(),
                what: format!(
                    "slave interface node {} has no coupling (row sum of D {}): the master \
                     surface does not cover it, or it carries no multiplier (linear \
                     multipliers on second-order faces; gap heat needs a flux at every slave \
                     node: use dual or standard multipliers)",
                    tie.coupling().slave_nodes[j],
                    weight[j]
                ),
            });
        }
        let dirichlet = [slave.dirichlet_nodes().0, master.dirichlet_nodes().0];
        let n0 = slave.mesh.node_count();
        let mut is_dirichlet = vec![false; n0 + master.mesh.node_count()];
        for &i in &dirichlet[0] {
            is_dirichlet[i as usize] = true;
        }
        for &i in &dirichlet[1] {
            is_dirichlet[n0 + i as usize] = true;
        }
        Ok(Self {
            bodies: [slave, master],
            conductivity: [ks, km],
            law,
            tie,
            capacity,
            options: *options,
            dirichlet,
            is_dirichlet,
            weight,
            scale: 1.0,
        })
    }

    /// Scales the multiplier unknowns: the state holds `mu = lambda / scale`. With `scale`
    /// of the order of the interface's heat transfer coefficient (W/m^2/K), `mu` is a
    /// temperature like the other unknowns, which the finite differences of JFNK and the
    /// norms of Newton's convergence test want. The default is 1.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] unless `scale` is positive and finite.
    pub fn with_multiplier_scale(mut self, scale: f64) -> Result<Self, PhysicsError> {
        if !(scale > 0.0 && scale.is_finite()) {
            return Err(PhysicsError::InvalidInput {
                body: "options".into(),
                what: format!("multiplier scale {scale} is not positive and finite"),
            });
        }
        self.scale = scale;
        Ok(self)
    }

    /// The interface heat fluxes `lambda` (W/m^2, leaving the slave) of a state, one per
    /// slave interface node (row of D).
    pub fn fluxes(&self, x: &[f64]) -> Vec<f64> {
        self.split(x)[2].iter().map(|m| m * self.scale).collect()
    }

    /// The bodies.
    pub fn bodies(&self) -> &[HeatBody; 2] {
        &self.bodies
    }

    /// The interface and its coupling.
    pub fn tie(&self) -> &Tie {
        &self.tie
    }

    /// The law.
    pub fn law(&self) -> &L {
        &self.law
    }

    /// The number of unknowns.
    pub fn dimension(&self) -> usize {
        self.offsets()[2] + self.weight.len()
    }

    fn offsets(&self) -> [usize; 3] {
        let n0 = self.bodies[0].mesh.node_count();
        [0, n0, n0 + self.bodies[1].mesh.node_count()]
    }

    /// The state vector of the temperatures `[slave, master]` (by mesh node index), with zero
    /// multipliers.
    pub fn state(&self, temperatures: [&[f64]; 2]) -> Vec<f64> {
        let mut x = Vec::with_capacity(self.dimension());
        x.extend_from_slice(temperatures[0]);
        x.extend_from_slice(temperatures[1]);
        x.resize(self.dimension(), 0.0);
        x
    }

    /// The slave temperatures, master temperatures and scaled multipliers `mu` of a state
    /// vector (see [`with_multiplier_scale`](Self::with_multiplier_scale)).
    pub fn split<'a>(&self, x: &'a [f64]) -> [&'a [f64]; 3] {
        let o = self.offsets();
        [&x[..o[1]], &x[o[1]..o[2]], &x[o[2]..]]
    }

    /// For each slave interface node (row of D), the slave temperature `(D T_s)_j / d_j` and
    /// the projected master temperature `(M T_m)_j / d_j` of a state.
    pub fn interface_temperatures(&self, x: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let [ts, tm, _] = self.split(x);
        let c = self.tie.coupling();
        let sn = self.tie.slave_nodes();
        let mn = self.tie.master_nodes();
        let mut a = Vec::with_capacity(self.weight.len());
        let mut b = Vec::with_capacity(self.weight.len());
        for (j, (drow, mrow)) in c.d.outer_iterator().zip(c.m.outer_iterator()).enumerate() {
            let gs: f64 = drow.iter().map(|(k, v)| v * ts[sn[k] as usize]).sum();
            let gm: f64 = mrow.iter().map(|(l, v)| v * tm[mn[l] as usize]).sum();
            a.push(gs / self.weight[j]);
            b.push(gm / self.weight[j]);
        }
        (a, b)
    }

    /// Loads and Dirichlet values at time `t`; `old` and `dt` for a backward Euler step
    /// (`None`: steady).
    pub(crate) fn step_data(
        &self,
        t: f64,
        transient: Option<(&[f64], f64)>,
    ) -> Result<StepData, PhysicsError> {
        let mut load = [
            assemble_heat_load(&self.bodies[0], t, &self.options)?,
            assemble_heat_load(&self.bodies[1], t, &self.options)?,
        ];
        let mut inv_dt = 0.0;
        if let Some((old, dt)) = transient {
            if !(dt > 0.0 && dt.is_finite()) {
                return Err(PhysicsError::InvalidInput {
                    body: "options".into(),
                    what: format!("time step {dt} is not positive and finite"),
                });
            }
            inv_dt = 1.0 / dt;
            let o = self.offsets();
            for b in 0..2 {
                let old_b = &old[o[b]..o[b + 1]];
                for (r, row) in self.capacity[b].outer_iterator().enumerate() {
                    load[b][r] += row.iter().map(|(k, v)| v * old_b[k]).sum::<f64>() * inv_dt;
                }
            }
        }
        let values = [0, 1].map(|b| {
            let (nodes, conds) = self.bodies[b].dirichlet_nodes();
            self.bodies[b].dirichlet_values(&nodes, &conds, t)
        });
        Ok(StepData {
            load,
            values,
            inv_dt,
            time: t,
        })
    }

    /// The residual, and the matrix of `lin` if asked.
    fn evaluate(
        &self,
        x: &[f64],
        data: &StepData,
        r: &mut [f64],
        lin: Option<Linearization>,
    ) -> Result<Option<SparseMatrix>, PhysicsError> {
        let o = self.offsets();
        let n = self.dimension();
        if x.len() != n || r.len() != n {
            return Err(PhysicsError::WrongLength {
                what: "state vector".into(),
                expected: n,
                got: x.len().min(r.len()),
            });
        }
        let mut trip = Triplets::default();
        self.body_terms(x, data, r, lin, &mut trip)?;
        // Interface.
        let c = self.tie.coupling();
        let sn = self.tie.slave_nodes();
        let mn = self.tie.master_nodes();
        let (ts, tm) = (&x[o[0]..o[1]], &x[o[1]..o[2]]);
        for (j, (drow, mrow)) in c.d.outer_iterator().zip(c.m.outer_iterator()).enumerate() {
            let lj = self.scale * x[o[2] + j];
            let w = self.weight[j];
            let gs: f64 = drow.iter().map(|(k, v)| v * ts[sn[k] as usize]).sum();
            let gm: f64 = mrow.iter().map(|(l, v)| v * tm[mn[l] as usize]).sum();
            let tan = evaluate(
                &self.law,
                LawPoint::new((gs - gm) / w, lj, 0.5 * (gs + gm) / w),
            )?;
            let row = o[2] + j;
            r[row] = w * tan.value;
            for (k, v) in drow.iter() {
                let gi = o[0] + sn[k] as usize;
                r[gi] += v * lj;
            }
            for (l, v) in mrow.iter() {
                let gi = o[1] + mn[l] as usize;
                r[gi] -= v * lj;
            }
            if lin.is_some() {
                let dt = if lin == Some(Linearization::Newton) {
                    0.5 * tan.d_temperature
                } else {
                    0.0
                };
                for (k, v) in drow.iter() {
                    let gi = o[0] + sn[k] as usize;
                    trip.push(row as u32, gi as u32, (tan.d_gap + dt) * v);
                    if !self.is_dirichlet[gi] {
                        trip.push(gi as u32, row as u32, v * self.scale);
                    }
                }
                for (l, v) in mrow.iter() {
                    let gi = o[1] + mn[l] as usize;
                    trip.push(row as u32, gi as u32, (-tan.d_gap + dt) * v);
                    if !self.is_dirichlet[gi] {
                        trip.push(gi as u32, row as u32, -v * self.scale);
                    }
                }
                trip.push(row as u32, row as u32, w * tan.d_multiplier * self.scale);
            }
        }
        self.dirichlet_terms(x, data, r, lin, &mut trip);
        Ok(lin.map(|_| trip.to_csr(n, n)))
    }

    /// The bodies' terms of the residual (conduction, capacity, loads) into the rows of the
    /// temperatures, `x` and `r` starting with the temperatures `[slave, master]` (longer
    /// vectors allowed), and the matrix entries of `lin` (Dirichlet rows left out) into `trip`.
    pub(crate) fn body_terms(
        &self,
        x: &[f64],
        data: &StepData,
        r: &mut [f64],
        lin: Option<Linearization>,
        trip: &mut Triplets,
    ) -> Result<(), PhysicsError> {
        let o = self.offsets();
        for b in 0..2 {
            let tb = &x[o[b]..o[b + 1]];
            let (f, k) = assemble_conduction(
                &self.bodies[b],
                &self.conductivity[b],
                tb,
                &self.options,
                lin,
            )?;
            let rb = &mut r[o[b]..o[b + 1]];
            for (i, row) in self.capacity[b].outer_iterator().enumerate() {
                let ct: f64 = row.iter().map(|(c, v)| v * tb[c]).sum();
                rb[i] = f[i] + ct * data.inv_dt - data.load[b][i];
            }
            if let Some(k) = k {
                for ((i, krow), crow) in k
                    .outer_iterator()
                    .enumerate()
                    .zip(self.capacity[b].outer_iterator())
                {
                    let gi = o[b] + i;
                    if self.is_dirichlet[gi] {
                        continue;
                    }
                    for (c, v) in krow.iter() {
                        trip.push(gi as u32, (o[b] + c) as u32, *v);
                    }
                    for (c, v) in crow.iter() {
                        trip.push(gi as u32, (o[b] + c) as u32, v * data.inv_dt);
                    }
                }
            }
        }
        Ok(())
    }

    /// The Dirichlet rows `T - g` (as [`body_terms`](Self::body_terms)).
    pub(crate) fn dirichlet_terms(
        &self,
        x: &[f64],
        data: &StepData,
        r: &mut [f64],
        lin: Option<Linearization>,
        trip: &mut Triplets,
    ) {
        let o = self.offsets();
        for b in 0..2 {
            for (&node, &g) in self.dirichlet[b].iter().zip(&data.values[b]) {
                let gi = o[b] + node as usize;
                r[gi] = x[gi] - g;
                if lin.is_some() {
                    trip.push(gi as u32, gi as u32, 1.0);
                }
            }
        }
    }

    /// Whether temperature unknown `i` (of `[slave, master]`) is prescribed.
    pub(crate) fn is_dirichlet(&self, i: usize) -> bool {
        self.is_dirichlet[i]
    }

    /// `w_j`, the row sums of D (the slave nodes' shares of the interface).
    pub(crate) fn weights(&self) -> &[f64] {
        &self.weight
    }

    /// The residual `F(x)` of a steady solve at time `t` (for checks and tests).
    ///
    /// # Errors
    /// The errors of the assembly and of the law.
    pub fn steady_residual(&self, x: &[f64], t: f64) -> Result<Vec<f64>, PhysicsError> {
        let data = self.step_data(t, None)?;
        let mut r = vec![0.0; self.dimension()];
        self.evaluate(x, &data, &mut r, None)?;
        Ok(r)
    }

    /// Solves for the state at time `t`: steady when `dt` is `None`, else one backward Euler
    /// step of size `dt` from `old`. `x` is the initial guess and, on success, the solution.
    ///
    /// # Errors
    /// [`PhysicsError::Newton`] with the residual history when Newton fails, and the errors of
    /// the assembly, of the law and of the linear solvers.
    pub fn solve(
        &self,
        x: &mut [f64],
        t: f64,
        transient: Option<(&[f64], f64)>,
        solver: &mut GapSolverState,
        options: &NewtonOptions,
    ) -> Result<NewtonReport, PhysicsError> {
        let data = self.step_data(t, transient)?;
        let mut step = Step {
            problem: self,
            data,
            solver,
        };
        SolverStats::timed_newton(&mut step, x, options, |s| &mut s.solver.stats)
    }
}

/// One solve as a [`NewtonProblem`].
struct Step<'a, L> {
    problem: &'a GapHeat<L>,
    data: StepData,
    solver: &'a mut GapSolverState,
}

impl<L: ConstraintLaw> NewtonProblem for Step<'_, L> {
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
        let lin = match self.solver.method {
            GapSolver::Newton => Linearization::Newton,
            GapSolver::Jfnk(_) => Linearization::Picard,
        };
        let t0 = Instant::now();
        let mut scratch = vec![0.0; x.len()];
        let a = self
            .problem
            .evaluate(x, &self.data, &mut scratch, Some(lin))?
            .expect("a matrix was asked");
        let t1 = Instant::now();
        let stats = &mut self.solver.stats;
        stats.assembly_seconds += (t1 - t0).as_secs_f64();
        let lu = stats.factorize(&mut self.solver.lu, &a)?;
        let its = match self.solver.method {
            GapSolver::Newton => {
                dx.copy_from_slice(r);
                lu.solve_in_place(dx)?;
                1
            }
            GapSolver::Jfnk(opts) => {
                let problem = self.problem;
                let data = &self.data;
                let f = |x: &[f64], r: &mut [f64]| problem.evaluate(x, data, r, None).map(|_| ());
                jfnk_solve(&f, x, r, lu, dx, forcing, &opts)?.iterations
            }
        };
        stats.linear_seconds += t1.elapsed().as_secs_f64();
        Ok(its)
    }

    /// `| |A| |x| | + |F(x) - A x|`, `A` the Picard matrix at `x` (conduction, capacity, the
    /// law's rows) and `F(x) - A x` the loads: the magnitudes of the terms before they cancel.
    fn residual_scale(&mut self, x: &[f64]) -> Result<f64, PhysicsError> {
        let mut r = vec![0.0; x.len()];
        let a = self
            .problem
            .evaluate(x, &self.data, &mut r, Some(Linearization::Picard))?
            .expect("a matrix was asked");
        Ok(assembled_residual_scale(&a, x, &r))
    }
}
