//! Solving a tied heat scene, as named steps: the bodies' meshes read and checked to be of
//! one dimension, each body with its material and conditions, the tied problem on the mortar
//! interface of their sides, and the steady or transient solve of `[solve]`.

use std::path::Path;
use std::sync::Arc;

use mortar::io::GmshVolume;
use mortar_core::{CouplingOptions, SurfaceMesh};
use mortar_physics::heat::{
    HeatBody, HeatMaterial, HeatOptions, NeumannCondition, TiedHeat, TiedHeatSolution,
};
use mortar_physics::tied::TiedOptions;
use mortar_physics::LinearSolve;

use super::{Mode, SolvedTiedHeat, TiedHeatSpec};
use crate::file::error::Errors;
use crate::file::solve_keys::LinearSolverKeys;
use crate::file::two_bodies::{interface_of, mesh_sides};
use crate::file::{face_nodes, FileScene, ReadScene, SceneError};

impl FileScene for TiedHeatSpec {
    const KIND: &'static str = "tied_heat";

    type Solved = SolvedTiedHeat;

    fn check(&self, path: &Path) -> Result<(), SceneError> {
        self.check_keys(path)
    }

    fn sides(&self) -> [(&str, &Path, &str); 2] {
        let sides = [&self.interface.slave, &self.interface.master];
        mesh_sides(sides, &self.bodies, |b| (&b.mesh, &b.group))
    }

    /// Builds and solves the problem from the bodies' meshes (the interface faces are the
    /// surface elements of their cells' faces).
    ///
    /// # Errors
    /// [`SceneError::Mesh`] for an interface group of the wrong dimension;
    /// [`SceneError::Invalid`] for bodies not of `dimension`; [`SceneError::Physics`] for a
    /// problem that cannot be built or solved (an inverted cell, an interface without
    /// overlap, a singular system).
    fn solve_read(&self, read: ReadScene<'_>) -> Result<SolvedTiedHeat, SceneError> {
        let ReadScene {
            path,
            volumes,
            started: t_start,
            ..
        } = read;
        let errors = Errors { path };
        let dimension = self.dimension_of(&errors, &volumes)?;

        // Boundary conditions and interface sides.
        let order = [&self.interface.slave, &self.interface.master];
        let mut bodies = Vec::with_capacity(2);
        let mut surfaces = Vec::with_capacity(2);
        for (side, (name, v)) in order.iter().zip(&volumes) {
            let body = self.heat_body(&errors, name, v)?;
            let which = if surfaces.is_empty() {
                "slave"
            } else {
                "master"
            };
            let surface = v
                .boundary_surface_in(&side.group)
                .map_err(|e| errors.mesh(format!("interface.{which}"), e))?;
            surfaces.push(surface);
            bodies.push(body);
        }
        let t_read = t_start.elapsed().as_secs_f64();

        let master_surface = surfaces.pop().expect("two surfaces");
        let slave_surface = surfaces.pop().expect("two surfaces");
        let master = bodies.pop().expect("two bodies");
        let slave = bodies.pop().expect("two bodies");
        let (coupling, problem) =
            self.problem_of(&errors, [slave, master], [slave_surface, master_surface])?;
        let unknowns = problem.bodies().iter().map(|b| b.mesh.node_count()).sum();
        let linear_solver = self
            .solve
            .linear_solver(unknowns, usize::from(dimension))
            .map_err(|(key, what)| errors.invalid(key.into(), what))?;
        let linear = LinearSolve {
            backend: linear_solver.solver(),
            ..LinearSolve::default()
        };
        let (solution, steps, time) = self.solve_problem(&errors, &problem, &linear)?;

        Ok(SolvedTiedHeat {
            spec: self.clone(),
            path: path.to_path_buf(),
            labels: [volumes[0].1.label(), volumes[1].1.label()],
            files: [volumes[0].1.path.clone(), volumes[1].1.path.clone()],
            dimension,
            coupling: coupling.describe(),
            problem,
            solution,
            steps,
            time,
            linear_solver,
            t_start,
            t_read,
        })
    }
}

impl TiedHeatSpec {
    /// The dimension of the meshes `volumes`: one for both, and the scene's `dimension` when
    /// it gives one.
    fn dimension_of(
        &self,
        errors: &Errors,
        volumes: &[(String, GmshVolume)],
    ) -> Result<u8, SceneError> {
        let dims = [volumes[0].1.dimension, volumes[1].1.dimension];
        if let Some(d) = self.dimension {
            if d != dims[0] {
                return Err(errors.invalid(
                    "dimension".into(),
                    format!(
                        "the scene says {d}D, but the bodies' groups ({}, {}) are {}D",
                        volumes[0].1.label(),
                        volumes[1].1.label(),
                        dims[0]
                    ),
                ));
            }
        }
        Ok(dims[0])
    }

    /// Body `name` of the mesh `v`: its material, its heat source, its prescribed
    /// temperatures and its entering fluxes.
    fn heat_body(
        &self,
        errors: &Errors,
        name: &str,
        v: &GmshVolume,
    ) -> Result<HeatBody, SceneError> {
        let b = &self.bodies[name];
        let mut body = HeatBody::new(
            name.to_string(),
            v.mesh.clone(),
            HeatMaterial::new(b.conductivity, b.rho_cp.unwrap_or(0.0)),
        );
        if b.source != 0.0 {
            let q = b.source;
            body = body.with_source(move |_, _| q);
        }
        for (i, d) in b.dirichlet.iter().enumerate() {
            let faces = v
                .boundary_faces_in(&d.group)
                .map_err(|e| errors.mesh(format!("bodies.{name}.dirichlet[{i}]"), e))?;
            let value = d.value;
            body = body.with_dirichlet_nodes(face_nodes(&faces), move |_, _| value);
        }
        for (i, n) in b.neumann.iter().enumerate() {
            let faces = v
                .boundary_faces_in(&n.group)
                .map_err(|e| errors.mesh(format!("bodies.{name}.neumann[{i}]"), e))?;
            let flux = n.flux;
            body.neumann.push(NeumannCondition {
                faces,
                flux: Arc::new(move |_, _| flux),
            });
        }
        Ok(body)
    }

    /// The tied heat problem of the bodies `[slave, master]` on the mortar interface of
    /// their sides' surfaces, coupled under `[interface]`'s settings, and those options.
    fn problem_of(
        &self,
        errors: &Errors,
        [slave, master]: [HeatBody; 2],
        [slave_surface, master_surface]: [SurfaceMesh; 2],
    ) -> Result<(CouplingOptions, TiedHeat), SceneError> {
        let (coupling, interface) = interface_of(
            errors,
            &self.interface.settings(),
            "interface",
            slave_surface,
            master_surface,
        )?;
        let problem =
            TiedHeat::on_interface(slave, master, interface, &coupling, &HeatOptions::default())
                .map_err(|e| errors.physics(e))?;
        Ok((coupling, problem))
    }

    /// The solve `[solve]` asks for: the steady state, or the transient solve
    /// ([`march`](Self::march)); with the time steps taken and the final time (0 and 0 for
    /// the steady state).
    fn solve_problem(
        &self,
        errors: &Errors,
        problem: &TiedHeat,
        linear: &LinearSolve<'_>,
    ) -> Result<(TiedHeatSolution, usize, f64), SceneError> {
        let tied = self.solve.tied_options();
        Ok(match self.solve.mode {
            Mode::Steady => (
                problem
                    .solve_steady_on(&tied, 0.0, linear)
                    .map_err(|e| errors.physics(e))?,
                0,
                0.0,
            ),
            Mode::Transient => self.march(errors, problem, &tied, linear)?,
        })
    }

    /// The transient solve: backward Euler from the bodies' initial temperatures, `[solve]`'s
    /// steps of `dt`, stopping between steps when an interrupt is asked for. The solution's
    /// seconds add up the steps' loads and solves.
    fn march(
        &self,
        errors: &Errors,
        problem: &TiedHeat,
        tied: &TiedOptions,
        linear: &LinearSolve<'_>,
    ) -> Result<(TiedHeatSolution, usize, f64), SceneError> {
        let (dt, steps) = self.solve.time_steps();
        let initial = [0, 1].map(|i| {
            let b = &problem.bodies()[i];
            vec![self.bodies[&b.name].initial; b.mesh.node_count()]
        });
        let mut stepper = problem
            .backward_euler_on(tied, initial, 0.0, dt, linear)
            .map_err(|e| errors.physics(e))?;
        let mut seconds = stepper.solution().seconds;
        let (mut loads, mut solve) = (0.0, 0.0);
        for done in 0..steps {
            if crate::interrupt::requested() {
                return Err(SceneError::Interrupted {
                    path: errors.path.to_path_buf(),
                    done,
                    steps,
                });
            }
            let s = stepper.step().map_err(|e| errors.physics(e))?;
            loads += s.seconds.loads;
            solve += s.seconds.solve;
        }
        seconds.loads = loads;
        seconds.solve = solve;
        let mut solution = stepper.solution().clone();
        solution.seconds = seconds;
        Ok((solution, steps, stepper.time()))
    }
}
