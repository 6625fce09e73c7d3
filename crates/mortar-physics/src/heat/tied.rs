//! `TiedHeat`: linear heat conduction in two bodies tied by mortar across a non-conforming
//! interface, steady or by backward Euler, with its solution, timings and the limits on the
//! conductivity contrast it accepts.

use std::time::Instant;

use mortar_core::mesh::SurfaceMesh;
use mortar_core::{CouplingOptions, Interface};

use super::assembly::{assemble_heat_load, assemble_heat_matrices, HeatMatrices, HeatOptions};
use super::body::HeatBody;
use crate::error::PhysicsError;
use crate::linear_solve::LinearSolve;
use crate::tied::{FormulationReport, Tie, TiedOptions, TiedSystem};

/// Wall-clock seconds of the phases of a tied heat solve.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct HeatSeconds {
    /// Assembly of the body matrices (once per problem).
    pub assembly: f64,
    /// The mortar coupling D, M (once per problem).
    pub coupling: f64,
    /// Assembly of the loads and Dirichlet values (per solve or step).
    pub loads: f64,
    /// Building the tied system matrix.
    pub system: f64,
    /// The sparse factorisation.
    pub factorisation: f64,
    /// The triangular solves and the recovery of the slave values and multipliers.
    pub solve: f64,
}

impl HeatSeconds {
    /// The time of the linear algebra alone: system, factorisation and solve.
    pub fn linear_algebra(&self) -> f64 {
        self.system + self.factorisation + self.solve
    }
}

/// The temperatures of the two bodies and the interface heat flux.
#[derive(Debug, Clone, PartialEq)]
pub struct TiedHeatSolution {
    /// Nodal temperatures of the slave body and the master body (by mesh node index).
    pub temperatures: [Vec<f64>; 2],
    /// The heat flux leaving the slave body at each slave interface node (rows of D: ascending
    /// node tag), the multiplier `lambda`; `NaN` at Dirichlet slave nodes; at a node without
    /// multiplier (linear multipliers on second-order faces) the first-order interpolation of
    /// its face's corners' fluxes (where that fails, a corner without multiplier too or a
    /// face the linear basis cannot be built on, every such node keeps `NaN`).
    pub flux: Vec<f64>,
    /// Which formulation was solved, and why.
    pub formulation: FormulationReport,
    /// Timings.
    pub seconds: HeatSeconds,
}

/// Heat conduction in two bodies tied along a non-conforming interface by mortar:
/// `rho c_p T_t - div(k grad T) = Q` in each body, `T_s = T_m` weakly on the interface (the
/// multiplier is the heat flux leaving the slave body), Dirichlet and Neumann data on the
/// outer boundaries.
///
/// The body matrices and the coupling are built once by [`new`](TiedHeat::new);
/// [`solve_steady`](TiedHeat::solve_steady) and [`backward_euler`](TiedHeat::backward_euler)
/// build and factorise the tied system of their formulation (see [`TiedSystem`]).
#[derive(Debug, Clone)]
pub struct TiedHeat {
    bodies: [HeatBody; 2],
    tie: Tie,
    matrices: [HeatMatrices; 2],
    options: HeatOptions,
    dirichlet: [(Vec<u32>, Vec<usize>); 2],
    seconds: HeatSeconds,
    /// The rows without multiplier and how their flux follows from their face's corners.
    without_multiplier: Vec<crate::tied::Interpolated>,
}

/// The conductivity contrast from which [`TiedHeat`]'s solves carry every temperature relative
/// to the stiffer body's level (see `TiedHeat::solve_levelled`): below it the spurious flux
/// of a stiff body's offset, `eps contrast` of the span, is below 1e-13.
pub const LEVEL_SHIFT_CONTRAST: f64 = 1e3;

/// The most solves [`TiedHeat`] repeats to settle the stiffer body's level: each gains a
/// factor of about `eps contrast` (1e-3 at a contrast of 1e12).
pub const MAX_LEVEL_PASSES: usize = 8;

/// The largest conductivity contrast `max(k) / min(k)` of the two bodies that [`TiedHeat::new`]
/// accepts: about `1 / eps` (eps = 2.2e-16, double precision). Beyond it the stiffer body's
/// temperature drop is below one unit in the last place of the temperature span, so its
/// gradient and its heat flux are not carried by its nodal temperatures.
///
/// Measured on two bodies tied along a non-matching interface (tests/convergence/contrast.rs:
/// 2D with and without Dirichlet slave crosspoints, 3D, a body held by the tie alone; both
/// formulations): the nodal temperatures stay within 6e-15 of the span of the exact
/// piecewise-linear field at every contrast up to 1e12 (the stiffer body's level carried
/// apart, see [`LEVEL_SHIFT_CONTRAST`]), and the interface flux within 1e-14 when the slave
/// body is the softer one. When the slave body is the stiffer one, its multipliers come from
/// its own stiff rows, and their error grows with the contrast (5.8e-12 at 1e7, 8.0e-7 at
/// 1e8 for the saddle point), hence the lower limit [`MAX_STIFFER_SLAVE_CONTRAST`].
pub const MAX_CONDUCTIVITY_CONTRAST: f64 = 1e15;

/// The largest ratio `k_slave / k_master` that [`TiedHeat::new`] accepts when the slave body
/// is the stiffer one: the interface flux (the slave's multipliers) is then within 1e-8 of
/// the exact one (measured 5.5e-12 at this limit, 8.0e-7 at 1e8 with the saddle point, see
/// [`MAX_CONDUCTIVITY_CONTRAST`]). With the softer body as the slave side the flux is exact
/// to round-off up to [`MAX_CONDUCTIVITY_CONTRAST`]: a refused scene is solved exactly with
/// the sides exchanged.
pub const MAX_STIFFER_SLAVE_CONTRAST: f64 = 1e7;

/// Refuses conductivity contrasts beyond [`MAX_CONDUCTIVITY_CONTRAST`], and a slave body
/// stiffer than its master beyond [`MAX_STIFFER_SLAVE_CONTRAST`], naming both bodies.
fn check_contrast(slave: &HeatBody, master: &HeatBody) -> Result<(), PhysicsError> {
    let (ks, km) = (slave.material.conductivity, master.material.conductivity);
    let contrast = ks.max(km) / ks.min(km);
    let names = format!(
        "the conductivities {ks:e} (slave body {:?}) and {km:e} (master body {:?}) are \
         {contrast:.1e} apart",
        slave.name, master.name
    );
    let what = if contrast > MAX_CONDUCTIVITY_CONTRAST {
        format!(
            "{names}, beyond the contrast of {MAX_CONDUCTIVITY_CONTRAST:.0e} that double \
             precision carries (the stiffer body's temperature drop would be below one unit \
             in the last place of the temperature span); treat the stiffer body as \
             isothermal instead"
        )
    } else if ks / km > MAX_STIFFER_SLAVE_CONTRAST {
        format!(
            "{names}, and the slave body is the stiffer one: beyond a contrast of \
             {MAX_STIFFER_SLAVE_CONTRAST:.0e} its multipliers (the interface heat flux, from \
             its own stiff rows) would lose more than 1e-8 to round-off; make {:?} the slave \
             side and {:?} the master side (exact to round-off)",
            master.name, slave.name
        )
    } else {
        return Ok(());
    };
    Err(PhysicsError::InvalidInput {
        body: format!("{} and {}", slave.name, master.name),
        what,
    })
}

impl TiedHeat {
    /// Assembles both bodies and couples them along `slave_surface` (faces of the slave
    /// body's boundary) and `master_surface` (of the master body's), whose node tags are the
    /// bodies' node tags (as [`boundary_surface`](mortar_fem::VolumeMesh::boundary_surface)
    /// gives them).
    ///
    /// The coupling and the assembly must use the same geometry
    /// ([`CouplingOptions::geometry`], [`HeatOptions::geometry`]): with both axisymmetric the
    /// problem is the r-z one, heat flows in W over the full revolution.
    ///
    /// # Errors
    /// The errors of the assembly ([`PhysicsError::InvalidInput`],
    /// [`PhysicsError::InvertedCell`]) and of [`Tie::new`]; [`PhysicsError::InvalidInput`]
    /// if the coupling's geometry is not the heat options', if the conductivities are more
    /// than [`MAX_CONDUCTIVITY_CONTRAST`] apart, or if the slave body's is more than
    /// [`MAX_STIFFER_SLAVE_CONTRAST`] times the master body's.
    pub fn new(
        slave: HeatBody,
        master: HeatBody,
        slave_surface: SurfaceMesh,
        master_surface: SurfaceMesh,
        coupling: &CouplingOptions,
        options: &HeatOptions,
    ) -> Result<Self, PhysicsError> {
        let interface = Interface::new(slave_surface, master_surface)?;
        Self::on_interface(slave, master, interface, coupling, options)
    }

    /// [`new`](Self::new) on an interface the caller built from the two bodies' surfaces
    /// (with its own [`Tolerances`](mortar_core::Tolerances), such as a search radius,
    /// through [`Interface::with_tolerances`]).
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn on_interface(
        slave: HeatBody,
        master: HeatBody,
        interface: Interface,
        coupling: &CouplingOptions,
        options: &HeatOptions,
    ) -> Result<Self, PhysicsError> {
        crate::field::cells::check_same_geometry(coupling.geometry, options.geometry)?;
        let t0 = Instant::now();
        let matrices = [
            assemble_heat_matrices(&slave, options)?,
            assemble_heat_matrices(&master, options)?,
        ];
        check_contrast(&slave, &master)?;
        let t1 = Instant::now();
        let tie = Tie::on_interface(&slave.mesh, &master.mesh, interface, coupling)?;
        let seconds = HeatSeconds {
            assembly: (t1 - t0).as_secs_f64(),
            coupling: t1.elapsed().as_secs_f64(),
            ..Default::default()
        };
        let dirichlet = [slave.dirichlet_nodes(), master.dirichlet_nodes()];
        // If the interpolation cannot be built (see TiedHeatSolution::flux), the rows without
        // multiplier keep NaN fluxes, the value of "no multiplier here".
        let without_multiplier = tie.rows_without_multiplier().unwrap_or_default();
        Ok(Self {
            bodies: [slave, master],
            tie,
            matrices,
            options: *options,
            dirichlet,
            seconds,
            without_multiplier,
        })
    }

    /// The slave and master bodies.
    pub fn bodies(&self) -> &[HeatBody; 2] {
        &self.bodies
    }

    /// The interface and its coupling.
    pub fn tie(&self) -> &Tie {
        &self.tie
    }

    /// The bodies' stiffness and capacity matrices.
    pub fn matrices(&self) -> &[HeatMatrices; 2] {
        &self.matrices
    }

    /// The tied system of the matrices `[A_slave, A_master]`, with this problem's Dirichlet
    /// nodes.
    ///
    /// # Errors
    /// See [`TiedSystem::new`].
    pub fn system(
        &self,
        matrices: [&mortar_core::linalg::SparseMatrix; 2],
        tied: &TiedOptions,
    ) -> Result<TiedSystem, PhysicsError> {
        self.system_on(matrices, tied, &LinearSolve::default())
    }

    /// [`system`](Self::system), solved by `linear`'s backend when it names one (see
    /// [`TiedSystem::new_on`]).
    ///
    /// # Errors
    /// See [`TiedSystem::new_on`].
    pub fn system_on(
        &self,
        matrices: [&mortar_core::linalg::SparseMatrix; 2],
        tied: &TiedOptions,
        linear: &LinearSolve<'_>,
    ) -> Result<TiedSystem, PhysicsError> {
        TiedSystem::new_on(
            matrices,
            &self.tie,
            [&self.dirichlet[0].0, &self.dirichlet[1].0],
            tied,
            linear,
        )
    }

    /// The steady solution with sources and boundary data taken at time `t`.
    ///
    /// # Errors
    /// The errors of [`TiedSystem::new`] and [`TiedSystem::solve`].
    pub fn solve_steady(
        &self,
        tied: &TiedOptions,
        t: f64,
    ) -> Result<TiedHeatSolution, PhysicsError> {
        self.solve_steady_on(tied, t, &LinearSolve::default())
    }

    /// [`solve_steady`](Self::solve_steady), the system solved by `linear`'s backend when it
    /// names one.
    ///
    /// # Errors
    /// The errors of [`TiedSystem::new_on`] and [`TiedSystem::solve`].
    pub fn solve_steady_on(
        &self,
        tied: &TiedOptions,
        t: f64,
        linear: &LinearSolve<'_>,
    ) -> Result<TiedHeatSolution, PhysicsError> {
        let system = self.system_on(
            [&self.matrices[0].stiffness, &self.matrices[1].stiffness],
            tied,
            linear,
        )?;
        let (loads, g, seconds_loads) = self.loads(t)?;
        let fields = self.solve_levelled(&system, &loads, None, &g)?;
        Ok(self.solution(&system, fields, seconds_loads))
    }

    /// The body whose conductivity is at least [`LEVEL_SHIFT_CONTRAST`] times the other's.
    fn stiffer_body(&self) -> Option<usize> {
        let k = [0, 1].map(|b| self.bodies[b].material.conductivity);
        let stiffer = usize::from(k[1] > k[0]);
        (k[stiffer] >= LEVEL_SHIFT_CONTRAST * k[1 - stiffer]).then_some(stiffer)
    }

    /// `system`'s solution for the loads `loads` and Dirichlet values `g`, every temperature
    /// carried relative to the stiffer body's level where the conductivities are
    /// [`LEVEL_SHIFT_CONTRAST`] or more apart.
    ///
    /// A stiff body (conductivity `k`) whose level is set through the tie alone (held by no
    /// Dirichlet condition of its own) turns the rounding of its stiffness times its
    /// temperature, `eps k |T|`, into a spurious heat flux: its level then drifts by about
    /// `eps contrast` of the span (1.7e-3 at a contrast of 1e12). Solving for `T' = T - c`,
    /// with `c` the stiffer body's mean temperature, removes `|T|` from that product (`K 1 =
    /// 0`: a uniform temperature carries no flux, and `D 1 = M 1`: the tie holds a common
    /// level), so the spurious flux scales with the body's own temperature drop instead.
    /// `c` is taken from the previous solve and the solve repeated (with the factorisation
    /// kept: one more back substitution each) until it settles, at most
    /// [`MAX_LEVEL_PASSES`] times. `level_load` is the load a uniform temperature of 1
    /// adds (the capacity's row sums over the time step, for a backward Euler step; none for
    /// a steady solve).
    fn solve_levelled(
        &self,
        system: &TiedSystem,
        loads: &[Vec<f64>; 2],
        level_load: Option<&[Vec<f64>; 2]>,
        g: &[Vec<f64>; 2],
    ) -> Result<crate::tied::TiedFields, PhysicsError> {
        let mut fields = system.solve([&loads[0], &loads[1]], [&g[0], &g[1]])?;
        let Some(stiff) = self.stiffer_body() else {
            return Ok(fields);
        };
        let mean = |t: &[f64]| t.iter().sum::<f64>() / t.len().max(1) as f64;
        let mut level = 0.0;
        for _ in 0..MAX_LEVEL_PASSES {
            let next = mean(&fields.fields[stiff]);
            let span = fields
                .fields
                .iter()
                .flatten()
                .fold(0.0f64, |a, t| a.max(t.abs()));
            if (next - level).abs() <= 8.0 * f64::EPSILON * span {
                break;
            }
            level = next;
            let shifted_loads = [0, 1].map(|b| match level_load {
                Some(l) => loads[b]
                    .iter()
                    .zip(&l[b])
                    .map(|(f, u)| f - level * u)
                    .collect(),
                None => loads[b].clone(),
            });
            let shifted_g = [0, 1].map(|b| g[b].iter().map(|v| v - level).collect::<Vec<_>>());
            let seconds = fields.seconds;
            fields = system.solve(
                [&shifted_loads[0], &shifted_loads[1]],
                [&shifted_g[0], &shifted_g[1]],
            )?;
            for t in fields.fields.iter_mut().flatten() {
                *t += level;
            }
            fields.seconds += seconds;
        }
        Ok(fields)
    }

    /// A backward Euler integrator from the temperatures `initial = [slave, master]` (by mesh
    /// node index) at time `t0`, with time step `dt`.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a non-positive time step,
    /// [`PhysicsError::WrongLength`] for initial fields of the wrong size, and the errors of
    /// [`TiedSystem::new`].
    pub fn backward_euler(
        &self,
        tied: &TiedOptions,
        initial: [Vec<f64>; 2],
        t0: f64,
        dt: f64,
    ) -> Result<BackwardEuler<'_>, PhysicsError> {
        self.backward_euler_on(tied, initial, t0, dt, &LinearSolve::default())
    }

    /// [`backward_euler`](Self::backward_euler), each step's system solved by `linear`'s
    /// backend when it names one.
    ///
    /// # Errors
    /// As [`backward_euler`](Self::backward_euler), with those of [`TiedSystem::new_on`].
    pub fn backward_euler_on(
        &self,
        tied: &TiedOptions,
        initial: [Vec<f64>; 2],
        t0: f64,
        dt: f64,
        linear: &LinearSolve<'_>,
    ) -> Result<BackwardEuler<'_>, PhysicsError> {
        check_dt(dt)?;
        for (b, field) in initial.iter().enumerate() {
            if field.len() != self.bodies[b].mesh.node_count() {
                return Err(PhysicsError::WrongLength {
                    what: format!("initial temperatures of body {:?}", self.bodies[b].name),
                    expected: self.bodies[b].mesh.node_count(),
                    got: field.len(),
                });
            }
        }
        let a = [
            self.matrices[0].backward_euler(dt),
            self.matrices[1].backward_euler(dt),
        ];
        let system = self.system_on([&a[0], &a[1]], tied, linear)?;
        let solution = TiedHeatSolution {
            temperatures: initial,
            flux: vec![f64::NAN; self.tie.slave_nodes().len()],
            formulation: system.report().clone(),
            seconds: HeatSeconds {
                system: system.seconds().build,
                factorisation: system.seconds().factorisation,
                ..self.seconds
            },
        };
        Ok(BackwardEuler {
            problem: self,
            system,
            dt,
            time: t0,
            solution,
        })
    }

    /// Loads and Dirichlet values at time `t`, and the seconds they took.
    #[allow(clippy::type_complexity)]
    fn loads(&self, t: f64) -> Result<([Vec<f64>; 2], [Vec<f64>; 2], f64), PhysicsError> {
        let t0 = Instant::now();
        let loads = [
            assemble_heat_load(&self.bodies[0], t, &self.options)?,
            assemble_heat_load(&self.bodies[1], t, &self.options)?,
        ];
        let g = [0, 1].map(|b| {
            let (nodes, conds) = &self.dirichlet[b];
            self.bodies[b].dirichlet_values(nodes, conds, t)
        });
        Ok((loads, g, t0.elapsed().as_secs_f64()))
    }

    fn solution(
        &self,
        system: &TiedSystem,
        fields: crate::tied::TiedFields,
        loads: f64,
    ) -> TiedHeatSolution {
        let [slave, master] = fields.fields;
        let mut flux = fields.multipliers;
        for (row, from) in &self.without_multiplier {
            flux[*row as usize] = from.iter().map(|&(r, w)| w * flux[r as usize]).sum();
        }
        TiedHeatSolution {
            temperatures: [slave, master],
            flux,
            formulation: system.report().clone(),
            seconds: HeatSeconds {
                loads,
                system: system.seconds().build,
                factorisation: system.seconds().factorisation,
                solve: fields.seconds,
                ..self.seconds
            },
        }
    }
}

fn check_dt(dt: f64) -> Result<(), PhysicsError> {
    if dt > 0.0 && dt.is_finite() {
        Ok(())
    } else {
        Err(PhysicsError::InvalidInput {
            body: "options".into(),
            what: format!("time step {dt} is not positive and finite"),
        })
    }
}

/// Backward Euler time stepping of a [`TiedHeat`] problem:
/// `(K + C / dt) T^{n+1} = F(t^{n+1}) + (C / dt) T^n`, tied by mortar, with Dirichlet data at
/// `t^{n+1}`. The system is factorised once per time step size;
/// [`set_time_step`](BackwardEuler::set_time_step) refactorises with the symbolic analysis
/// reused.
#[derive(Debug)]
pub struct BackwardEuler<'a> {
    problem: &'a TiedHeat,
    system: TiedSystem,
    dt: f64,
    time: f64,
    solution: TiedHeatSolution,
}

impl BackwardEuler<'_> {
    /// Advances one step.
    ///
    /// # Errors
    /// The errors of the load assembly and of [`TiedSystem::solve`].
    pub fn step(&mut self) -> Result<&TiedHeatSolution, PhysicsError> {
        let t = self.time + self.dt;
        let (mut loads, g, seconds_loads) = self.problem.loads(t)?;
        // The capacity's load of the previous step, and of a uniform temperature of 1.
        let mut level_load = [Vec::new(), Vec::new()];
        for (b, load) in loads.iter_mut().enumerate() {
            let c = &self.problem.matrices[b].capacity;
            let old = &self.solution.temperatures[b];
            level_load[b] = c
                .outer_iterator()
                .map(|row| row.iter().map(|(_, v)| v).sum::<f64>() / self.dt)
                .collect();
            for (r, row) in c.outer_iterator().enumerate() {
                load[r] += row.iter().map(|(k, v)| v * old[k]).sum::<f64>() / self.dt;
            }
        }
        let fields = self
            .problem
            .solve_levelled(&self.system, &loads, Some(&level_load), &g)?;
        self.solution = self.problem.solution(&self.system, fields, seconds_loads);
        self.time = t;
        Ok(&self.solution)
    }

    /// Changes the time step, refactorising `K + C / dt` (symbolic analysis reused).
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a non-positive step, and the errors of
    /// [`TiedSystem::refactor`].
    pub fn set_time_step(&mut self, dt: f64) -> Result<(), PhysicsError> {
        check_dt(dt)?;
        let m = &self.problem.matrices;
        let a = [m[0].backward_euler(dt), m[1].backward_euler(dt)];
        self.system.refactor([&a[0], &a[1]])?;
        self.dt = dt;
        Ok(())
    }

    /// The current time.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The time step.
    pub fn time_step(&self) -> f64 {
        self.dt
    }

    /// The current temperatures and interface flux (the initial temperatures and `NaN` fluxes
    /// before the first step).
    pub fn solution(&self) -> &TiedHeatSolution {
        &self.solution
    }
}
