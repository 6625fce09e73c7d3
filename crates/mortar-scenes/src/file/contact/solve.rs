//! Solving a contact scene, as named steps: the bodies read (their meshes, materials and
//! conditions), the tie of their contact surfaces, the assembly, the check that contact and
//! the Dirichlet conditions hold every rigid motion, the load steps under the law, and the
//! stresses.

use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use mortar::io::GmshVolume;
use mortar_core::linalg::SparseMatrix;
use mortar_core::{CouplingOptions, SurfaceMesh};
use mortar_fem::mesh::BoundaryFace;
use mortar_physics::contact::{
    automatic_complementarity, rigid_motions, solve_contact_on, ContactOptions, ContactSolution,
    HeldMotions, NormalGap, RigidMotion,
};
use mortar_physics::elastic::{
    assemble_elastic_load, assemble_elastic_stiffness, recover_stress, ComponentSet, ElasticBody,
    ElasticMaterial, ElasticOptions, TractionCondition,
};
use mortar_physics::laws::{ContactComplementarity, ExponentialPressure, LawRegistry};
use mortar_physics::tied::Tie;
use mortar_physics::{LinearSolve, PhysicsError};
use nalgebra::Vector3;

use super::{Component, ComponentValue, ContactSpec, DisplacementSpec, LawSpec, SolvedContact};
use crate::file::error::Errors;
use crate::file::solve_keys::LinearSolverKeys;
use crate::file::two_bodies::{interface_of, mesh_sides};
use crate::file::{face_nodes, FileScene, ReadScene, SceneError};

impl FileScene for ContactSpec {
    const KIND: &'static str = "contact";

    type Solved = SolvedContact;

    fn check(&self, path: &Path) -> Result<(), SceneError> {
        self.check_keys(path)
    }

    fn sides(&self) -> [(&str, &Path, &str); 2] {
        let sides = [&self.contact.slave, &self.contact.master];
        mesh_sides(sides, &self.bodies, |b| (&b.mesh, &b.group))
    }

    /// Solves the bodies' meshes (see the [module](super)), with a `named_law` made by
    /// `read.registries.laws` (the shipped ones and a program's own).
    ///
    /// # Errors
    /// [`SceneError::Invalid`] for a component or traction that does not fit the dimension
    /// and for a load step whose Newton iteration fails (naming it), [`SceneError::Invalid`]
    /// (key `contact.named_law`) for a law the registry does not know or whose parameters it
    /// refuses, [`SceneError::Physics`] otherwise.
    fn solve_read(&self, read: ReadScene<'_>) -> Result<SolvedContact, SceneError> {
        let ReadScene {
            path,
            volumes,
            registries,
            started: t_start,
        } = read;
        let errors = Errors { path };
        let dim = volumes[0].1.dimension as usize;
        let ReadBodies {
            bodies,
            mut surfaces,
            labels,
        } = self.read_bodies(&errors, &volumes, dim)?;
        let t_read = t_start.elapsed().as_secs_f64();

        let t = Instant::now();
        let (master_surface, _) = surfaces.pop().expect("two surfaces");
        let (slave_surface, slave_faces) = surfaces.pop().expect("two surfaces");
        let (coupling, tie, gap) =
            self.tie_of(&errors, &bodies, [slave_surface, master_surface], dim)?;
        let t_coupling = t.elapsed().as_secs_f64();

        let t = Instant::now();
        let options = ElasticOptions::default();
        let (stiffness, load, dirichlet) = assemble(&errors, &bodies, &options)?;
        let t_assembly = t.elapsed().as_secs_f64();
        let held = held_motions(&errors, &bodies, &dirichlet, &gap)?;
        let linear_solver = self
            .solve
            .linear_solver(stiffness[0].rows() + stiffness[1].rows(), dim)
            .map_err(|(key, what)| errors.invalid(key.into(), what))?;

        let t = Instant::now();
        let system = ContactSystem {
            stiffness: &stiffness,
            load: &load,
            dirichlet: &dirichlet,
            gap: &gap,
            linear: linear_solver
                .solver()
                .map(|s| LinearSolve::on(s, [bodies[0].mesh.coords(), bodies[1].mesh.coords()]))
                .unwrap_or_default(),
        };
        let (solution, law_description, complementarity) =
            self.solve_law(&errors, &system, &tie, dim, &registries.laws)?;
        let names = [bodies[0].name.as_str(), bodies[1].name.as_str()];
        let solution =
            solution.map_err(|(step, e)| self.solve_error(&errors, step, e, names, &held))?;
        let t_solve = t.elapsed().as_secs_f64();

        let t = Instant::now();
        let stress = |b: usize| {
            recover_stress(&bodies[b], &solution.displacements[b], &options)
                .map_err(|e| errors.physics(e))
        };
        let stresses = [stress(0)?, stress(1)?];
        let t_stress = t.elapsed().as_secs_f64();

        Ok(SolvedContact {
            spec: self.clone(),
            path: path.to_path_buf(),
            labels: [labels[0].clone(), labels[1].clone()],
            dimension: dim,
            coupling: coupling.describe(),
            law: law_description,
            bodies: bodies
                .try_into()
                .map_err(|_| SceneError::Other("two bodies".into()))?,
            tie,
            slave_faces,
            solution,
            stresses: stresses.map(|s| (s.nodal, s.von_mises)),
            stiffness,
            load,
            dirichlet,
            gap,
            complementarity,
            linear_solver,
            seconds: [
                ("read", t_read),
                ("coupling", t_coupling),
                ("assembly", t_assembly),
                ("contact_solve", t_solve),
                ("stress", t_stress),
            ],
            t_start,
        })
    }
}

impl ContactSpec {
    /// The bodies of the meshes `volumes` (slave first, `dim` components): each elastic body
    /// with its conditions ([`elastic_body`](Self::elastic_body)), then its contact surface
    /// and faces, and its mesh's label.
    fn read_bodies(
        &self,
        errors: &Errors,
        volumes: &[(String, GmshVolume)],
        dim: usize,
    ) -> Result<ReadBodies, SceneError> {
        let order = [&self.contact.slave, &self.contact.master];
        let mut bodies = Vec::with_capacity(2);
        let mut surfaces = Vec::with_capacity(2);
        let mut labels = Vec::with_capacity(2);
        for (which, (side, (name, v))) in ["slave", "master"]
            .into_iter()
            .zip(order.iter().zip(volumes))
        {
            bodies.push(self.elastic_body(errors, name, v, dim)?);
            let surface = v
                .boundary_surface_in(&side.group)
                .map_err(|e| errors.mesh(format!("contact.{which}"), e))?;
            let faces = v
                .boundary_faces_in(&side.group)
                .map_err(|e| errors.mesh(format!("contact.{which}"), e))?;
            surfaces.push((surface, faces));
            labels.push(v.label());
        }
        Ok(ReadBodies {
            bodies,
            surfaces,
            labels,
        })
    }

    /// The tie of the contact surfaces `[slave, master]` of `bodies` (their mortar coupling
    /// under `[contact]`'s settings) and its weighted normal gap (`dim` components).
    fn tie_of(
        &self,
        errors: &Errors,
        bodies: &[ElasticBody],
        [slave, master]: [SurfaceMesh; 2],
        dim: usize,
    ) -> Result<(CouplingOptions, Tie, NormalGap), SceneError> {
        let (coupling, interface) =
            interface_of(errors, &self.contact.settings(), "contact", slave, master)?;
        let tie = Tie::on_interface(&bodies[0].mesh, &bodies[1].mesh, interface, &coupling)
            .map_err(|e| errors.physics(e))?;
        let gap = NormalGap::new(
            &tie,
            dim,
            bodies[0].mesh.node_count(),
            bodies[1].mesh.node_count(),
        )
        .map_err(|e| errors.physics(e))?;
        Ok((coupling, tie, gap))
    }

    /// The error of load steps that failed: a Newton failure names its load step (under the
    /// key `solve.load_steps`); another failure names the bodies as the scene does
    /// ([`name_bodies`]).
    fn solve_error(
        &self,
        errors: &Errors,
        step: Option<usize>,
        e: PhysicsError,
        names: [&str; 2],
        held: &[HeldMotions; 2],
    ) -> SceneError {
        match (step, e) {
            (Some(k), e) => errors.invalid(
                "solve.load_steps".into(),
                format!(
                    "load step {k} of {}: Newton's method did not converge: {e}",
                    self.solve.load_steps
                ),
            ),
            (None, e) => errors.physics(name_bodies(e, names, held)),
        }
    }
    /// Body `name` of the mesh `v` (`dim` components): its material, its displacement
    /// conditions and its tractions.
    fn elastic_body(
        &self,
        errors: &Errors,
        name: &str,
        v: &GmshVolume,
        dim: usize,
    ) -> Result<ElasticBody, SceneError> {
        let b = &self.bodies[name];
        let mut body = ElasticBody::new(
            name.to_string(),
            v.mesh.clone(),
            ElasticMaterial::new(b.youngs_modulus, b.poisson_ratio),
        );
        for (i, d) in b.dirichlet.iter().enumerate() {
            let key = format!("bodies.{name}.dirichlet[{i}]");
            let faces = v
                .boundary_faces_in(&d.group)
                .map_err(|e| errors.mesh(key.clone(), e))?;
            let (components, value) = dirichlet_value(errors, d, dim, &key)?;
            body = body.with_dirichlet_nodes(face_nodes(&faces), components, move |_| value);
        }
        for (i, t) in b.traction.iter().enumerate() {
            let key = format!("bodies.{name}.traction[{i}]");
            let faces = v
                .boundary_faces_in(&t.group)
                .map_err(|e| errors.mesh(key.clone(), e))?;
            if t.value.len() != dim {
                return Err(errors.invalid(
                    format!("{key}.value"),
                    format!("{} values for a {dim}D body", t.value.len()),
                ));
            }
            let mut tv = Vector3::zeros();
            tv.as_mut_slice()[..dim].copy_from_slice(&t.value);
            body.tractions.push(TractionCondition {
                faces,
                traction: Arc::new(move |_| tv),
            });
        }
        Ok(body)
    }

    /// The contact law of `[contact]` (by name, exact or exponential), its description and
    /// (exact) its complementarity parameter, and the load steps solved under it.
    fn solve_law(
        &self,
        errors: &Errors,
        system: &ContactSystem,
        tie: &Tie,
        dim: usize,
        laws: &LawRegistry,
    ) -> Result<(StepsResult, String, Option<f64>), SceneError> {
        let options = self.solve.options();
        let c = &self.contact;
        if let Some(named) = &c.named_law {
            let law = named
                .make(laws)
                .map_err(|e| errors.invalid("contact.named_law".into(), e.to_string()))?;
            let description = format!("{} (by name) {:?}", named.name, named.parameters);
            return Ok((system.solve(&law, &options), description, None));
        }
        Ok(match c.law {
            LawSpec::Exact => {
                let cc = automatic_complementarity(&system.stiffness[0], tie, system.gap, dim);
                let law = ContactComplementarity::try_new(cc)
                    .map_err(|e| errors.invalid("contact.law".into(), e.to_string()))?;
                (
                    system.solve(&law, &options),
                    format!("exact complementarity, c = {cc:e} Pa/m (automatic)"),
                    Some(cc),
                )
            }
            LawSpec::Exponential => {
                let (po, s, xi) = (
                    c.base_pressure.unwrap_or(0.0),
                    c.stiffness.unwrap_or(0.0),
                    c.onset.unwrap_or(0.0),
                );
                let law = ExponentialPressure::try_new(po, s, xi)
                    .map_err(|e| errors.invalid("contact.law".into(), e.to_string()))?;
                (
                    system.solve(&law, &options),
                    format!(
                        "exponential pressure, P_o = {po:e} Pa, S = {s:e} 1/m^2, xi = {xi:e} m"
                    ),
                    None,
                )
            }
        })
    }
}

/// The two bodies as read, slave first: the elastic bodies with their conditions, their
/// contact surfaces with the faces those are made of, and their meshes as `file#group`.
struct ReadBodies {
    bodies: Vec<ElasticBody>,
    surfaces: Vec<(SurfaceMesh, Vec<BoundaryFace>)>,
    labels: Vec<String>,
}

/// Per body (slave first): the stiffness matrix, the load vector, and the Dirichlet
/// unknowns with their values.
fn assemble(
    errors: &Errors,
    bodies: &[ElasticBody],
    options: &ElasticOptions,
) -> Result<Assembled, SceneError> {
    let stiffness = [
        assemble_elastic_stiffness(&bodies[0], options).map_err(|e| errors.physics(e))?,
        assemble_elastic_stiffness(&bodies[1], options).map_err(|e| errors.physics(e))?,
    ];
    let load = [
        assemble_elastic_load(&bodies[0], options).map_err(|e| errors.physics(e))?,
        assemble_elastic_load(&bodies[1], options).map_err(|e| errors.physics(e))?,
    ];
    let dirichlet = [bodies[0].dirichlet_dofs(), bodies[1].dirichlet_dofs()];
    Ok((stiffness, load, dirichlet))
}

/// Which rigid motions of each body its Dirichlet conditions and the contact hold: a motion
/// held by neither leaves the problem singular, an error naming the body and the motion
/// before any solve.
fn held_motions(
    errors: &Errors,
    bodies: &[ElasticBody],
    dirichlet: &[Dofs; 2],
    gap: &NormalGap,
) -> Result<[HeldMotions; 2], SceneError> {
    let held = rigid_motions(
        [bodies[0].mesh.coords(), bodies[1].mesh.coords()],
        [&dirichlet[0].0, &dirichlet[1].0],
        gap,
    );
    for (body, h) in bodies.iter().zip(&held) {
        if !h.free.is_empty() {
            return Err(errors.physics(PhysicsError::NotHeld {
                body: body.name.clone(),
                motions: describe_motions(&h.free),
            }));
        }
    }
    Ok(held)
}

/// The components and value of a displacement condition `d` (`key` in messages) of a body of
/// `dim` components.
fn dirichlet_value(
    errors: &Errors,
    d: &DisplacementSpec,
    dim: usize,
    key: &str,
) -> Result<(ComponentSet, Vector3<f64>), SceneError> {
    Ok(match (d.component, &d.value) {
        (Component::Z, _) if dim == 2 => {
            return Err(errors.invalid(
                format!("{key}.component"),
                "z in a 2D body (plane strain has x and y)".into(),
            ))
        }
        (Component::All, ComponentValue::Array(a)) => {
            if a.len() != dim {
                return Err(errors.invalid(
                    format!("{key}.value"),
                    format!("{} values for a {dim}D body", a.len()),
                ));
            }
            let mut v = Vector3::zeros();
            v.as_mut_slice()[..dim].copy_from_slice(a);
            (ComponentSet::All, v)
        }
        (Component::All, ComponentValue::Number(x)) => {
            (ComponentSet::All, Vector3::new(*x, *x, *x))
        }
        (c, ComponentValue::Number(x)) => {
            let k = match c {
                Component::X => 0,
                Component::Y => 1,
                _ => 2,
            };
            let mut v = Vector3::zeros();
            v[k] = *x;
            (ComponentSet::One(k), v)
        }
        (_, ComponentValue::Array(_)) => {
            return Err(errors.invalid(
                format!("{key}.value"),
                "an array is for component = \"all\"".into(),
            ))
        }
    })
}

type Dofs = (Vec<u32>, Vec<f64>);

/// Per body (slave first): the stiffness matrix, the load vector, the Dirichlet unknowns
/// with their values.
type Assembled = ([SparseMatrix; 2], [Vec<f64>; 2], [Dofs; 2]);

/// The load steps' solution, or the step (if one) and the error where they failed.
type StepsResult = Result<ContactSolution, (Option<usize>, PhysicsError)>;

/// The assembled contact problem of the two bodies, before its law: stiffnesses, loads,
/// prescribed displacements and the normal gap.
struct ContactSystem<'a> {
    stiffness: &'a [mortar_core::linalg::SparseMatrix; 2],
    load: &'a [Vec<f64>; 2],
    dirichlet: &'a [Dofs; 2],
    gap: &'a NormalGap,
    /// Where the Newton systems go.
    linear: LinearSolve<'a>,
}

impl ContactSystem<'_> {
    /// The load steps under `law` ([`solve_steps`]).
    fn solve<L: mortar_physics::laws::ConstraintLaw>(
        &self,
        law: &L,
        options: &ContactOptions,
    ) -> StepsResult {
        solve_steps(
            self.stiffness,
            self.load,
            self.dirichlet,
            self.gap,
            law,
            options,
            self.linear,
        )
    }
}

/// Motions described and joined by `" and "`.
fn describe_motions(motions: &[RigidMotion]) -> String {
    motions
        .iter()
        .map(RigidMotion::describe)
        .collect::<Vec<_>>()
        .join(" and ")
}

/// The solver's error with the bodies named as the scene names them: `"slave"` and
/// `"master"` become the bodies' names; an error of the contact as a whole (a body held in
/// some direction by contact alone, which has not closed or has let go) names the bodies whose
/// Dirichlet conditions leave such a motion free, and the motion.
fn name_bodies(e: PhysicsError, names: [&str; 2], held: &[HeldMotions; 2]) -> PhysicsError {
    match e {
        PhysicsError::InvalidInput { body, what } => {
            let body = match body.as_str() {
                "slave" => names[0].to_string(),
                "master" => names[1].to_string(),
                "contact" => {
                    let resting: Vec<String> = names
                        .iter()
                        .zip(held)
                        .filter(|(_, h)| !h.by_contact_only.is_empty())
                        .map(|(name, h)| {
                            format!(
                                "{name} (its {} held by contact alone)",
                                describe_motions(&h.by_contact_only)
                            )
                        })
                        .collect();
                    if resting.is_empty() {
                        body
                    } else {
                        resting.join(", ")
                    }
                }
                _ => body,
            };
            PhysicsError::InvalidInput { body, what }
        }
        e => e,
    }
}

/// [`solve_contact`]; on a Newton failure, the failing load step (found by re-solving the
/// first `k` steps, the loads scaled by `k / n`, which repeats the same increments).
fn solve_steps<L: mortar_physics::laws::ConstraintLaw>(
    stiffness: &[mortar_core::linalg::SparseMatrix; 2],
    load: &[Vec<f64>; 2],
    dirichlet: &[Dofs; 2],
    gap: &NormalGap,
    law: &L,
    options: &ContactOptions,
    linear: LinearSolve<'_>,
) -> StepsResult {
    let run = |scale: f64, steps: usize| {
        let l = [0, 1].map(|b| load[b].iter().map(|x| x * scale).collect::<Vec<_>>());
        let d = [0, 1].map(|b| dirichlet[b].1.iter().map(|x| x * scale).collect::<Vec<_>>());
        solve_contact_on(
            [&stiffness[0], &stiffness[1]],
            [&l[0], &l[1]],
            [(&dirichlet[0].0, &d[0]), (&dirichlet[1].0, &d[1])],
            gap,
            law,
            &ContactOptions {
                load_steps: steps,
                ..*options
            },
            linear,
        )
    };
    match run(1.0, options.load_steps) {
        Ok(s) => Ok(s),
        Err(e @ PhysicsError::Newton(_)) => {
            let n = options.load_steps;
            for k in 1..n {
                if let Err(PhysicsError::Newton(_)) = run(k as f64 / n as f64, k) {
                    return Err((Some(k), e));
                }
            }
            Err((Some(n), e))
        }
        Err(e) => Err((None, e)),
    }
}
