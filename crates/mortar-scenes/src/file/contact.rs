//! `kind = "contact"`: frictionless small-deformation contact of two elastic bodies (plane
//! strain in 2D) read from Gmsh files, across a mortar interface between two physical groups
//! of their boundaries.
//!
//! Keys (all others are errors):
//!
//! - `kind = "contact"`, optional `title`.
//! - `[bodies.NAME]`, exactly two: `mesh`, `group` (the cells), `youngs_modulus` (E > 0),
//!   `poisson_ratio` (-1 < nu < 0.5), `dirichlet = [{ group, component, value }, ...]`
//!   (`component` `"x" | "y" | "z" | "all"`; `value` a number, or for `"all"` an array of one
//!   value per component) and `traction = [{ group, value = [tx, ty(, tz)] }, ...]` (Pa).
//! - `[contact]`: `slave = { body, group }`, `master = { body, group }`, `law = "exact" |
//!   "exponential"` (the latter with `base_pressure`, `stiffness`, `onset`), `multipliers`
//!   (default `"dual"`; or `"standard"`, or `"linear"`: on the corners of second-order faces
//!   only), `integration` (default `"segment"`), `degree` (default automatic),
//!   `curved_tolerance`, `subdivision`, `quad_subdivision` (segment-based integration of
//!   curved and of non-parallelogram faces, as `mortar couple`'s options), `search_radius`
//!   (a distance along the slave normals; default as far as the nearest master surface,
//!   within a bound relative to the interface's size), `require_full_coverage` (default
//!   false).
//! - `[solve]` (optional): `load_steps` (default 1), `max_newton_steps` (default 30),
//!   `tolerance` (default 1e-10).
//!
//! Outputs: `NAME.vtu` per body (point data `displacement` (3 components), `stress_xx`,
//! `stress_yy`, `stress_zz`, `stress_yz`, `stress_xz`, `stress_xy`, `von_mises`),
//! `interface.vtu` (the slave surface, point data `gap` and `contact_pressure`) and
//! `report.json`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use mortar_core::element::ElementRef;
use mortar_core::linalg::SparseMatrix;
use mortar_core::Interface;
use mortar_fem::mesh::BoundaryFace;
use mortar_physics::contact::{
    automatic_complementarity, rigid_motions, solve_contact, ContactOptions, ContactSolution,
    HeldMotions, NormalGap, RigidMotion,
};
use mortar_physics::elastic::{
    assemble_elastic_load, assemble_elastic_stiffness, recover_stress, ComponentSet, ElasticBody,
    ElasticMaterial, ElasticOptions, TractionCondition,
};
use mortar_physics::laws::{ContactComplementarity, ExponentialPressure};

use crate::NamedLaw;
use mortar_physics::tied::Tie;
use mortar_physics::PhysicsError;
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::tied_heat::SideSpec;
use super::{coupling_of, face_nodes, widen_hint};
use super::{SceneError, SceneOutput, SceneSource};
use mortar::extend::Registries;
use mortar::extend::VolumeRegistry;
use mortar::io::vtu::{surface_vtu_string, vtu_string_with_vectors, VtuPiece};
use mortar::io::{
    parse_gmsh_volume, CouplingSettings, GmshVolume, Integration, IoError, Multipliers,
};
use mortar_physics::laws::LawRegistry;

/// A contact scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// `"contact"`.
    pub kind: String,
    /// A title for reports.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub title: Option<String>,
    /// The settings of the solve.
    #[serde(default)]
    pub solve: ContactSolveSpec,
    /// The two bodies, by name.
    pub bodies: BTreeMap<String, ElasticBodySpec>,
    /// The contact interface.
    pub contact: ContactInterfaceSpec,
}

/// One elastic body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ElasticBodySpec {
    /// The Gmsh 4.1 file, relative to the scene file's folder.
    pub mesh: PathBuf,
    /// The physical group of the body's cells.
    pub group: String,
    /// E (Pa).
    pub youngs_modulus: f64,
    /// nu.
    pub poisson_ratio: f64,
    /// Prescribed displacements.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub dirichlet: Vec<DisplacementSpec>,
    /// Tractions.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub traction: Vec<TractionSpec>,
}

/// A displacement component.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Component {
    /// x.
    X,
    /// y.
    Y,
    /// z (3D only).
    Z,
    /// Every component.
    All,
}

/// A number, or one number per component.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ComponentValue {
    /// The same value for each component.
    Number(f64),
    /// One value per component.
    Array(Vec<f64>),
}

/// A prescribed displacement on a physical group of boundary faces.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DisplacementSpec {
    /// The physical group.
    pub group: String,
    /// The component(s).
    pub component: Component,
    /// The value (m).
    pub value: ComponentValue,
}

/// A traction (Pa) on a physical group of boundary faces.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TractionSpec {
    /// The physical group.
    pub group: String,
    /// The traction vector, one value per component.
    pub value: Vec<f64>,
}

/// The contact law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LawSpec {
    /// Exact complementarity (semi-smooth Newton), automatic `c`.
    #[default]
    Exact,
    /// `P_o exp(S (xi - g)^2)`.
    Exponential,
}

/// The contact interface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactInterfaceSpec {
    /// The slave side.
    pub slave: SideSpec,
    /// The master side.
    pub master: SideSpec,
    /// The law.
    #[serde(default)]
    pub law: LawSpec,
    /// A law by name from the shipped [`LawRegistry`](mortar_physics::laws::LawRegistry) (or a program's own, through
    /// [`ContactSpec::solve_with`]), with its parameters, in place of `law`:
    /// `named_law = { name = "exponential_pressure", base_pressure = 1e5, stiffness = 1e12,
    /// onset = 1e-6 }`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub named_law: Option<NamedLaw>,
    /// `P_o` of the exponential law.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base_pressure: Option<f64>,
    /// `S` of the exponential law.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// `xi` of the exponential law.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub onset: Option<f64>,
    /// The multiplier space (default dual, the vocabulary's: [`Multipliers::default`]).
    #[serde(default)]
    pub multipliers: Multipliers,
    /// The integration strategy.
    #[serde(default)]
    pub integration: Integration,
    /// The quadrature degree (default automatic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub degree: Option<u32>,
    /// Segment-based: the curved-face subdivision tolerance (see
    /// [`CouplingSettings::curved_tolerance`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curved_tolerance: Option<f64>,
    /// Segment-based: a fixed curved-face subdivision level.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub subdivision: Option<u32>,
    /// Segment-based: the cut of non-parallelogram slave quads (see
    /// [`CouplingSettings::quad_subdivision`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quad_subdivision: Option<u32>,
    /// How far along the slave normals the search looks for master faces, a distance (see
    /// [`CouplingSettings::search_radius`]; default: as far as the nearest master surface,
    /// within a bound relative to the interface's size).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub search_radius: Option<f64>,
    /// Make uncovered slave area, overlapping master faces and skipped pairs errors instead
    /// of warnings.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub require_full_coverage: bool,
}

impl ContactInterfaceSpec {
    /// The coupling settings of these keys.
    pub fn settings(&self) -> CouplingSettings {
        CouplingSettings {
            multipliers: self.multipliers,
            integration: self.integration,
            degree: self.degree,
            curved_tolerance: self.curved_tolerance,
            subdivision: self.subdivision,
            quad_subdivision: self.quad_subdivision,
            search_radius: self.search_radius,
            require_full_coverage: self.require_full_coverage,
            threads: None,
        }
    }
}

/// The settings of the solve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSolveSpec {
    /// Load increments.
    #[serde(default = "one")]
    pub load_steps: usize,
    /// Newton steps allowed per load step.
    #[serde(default = "thirty")]
    pub max_newton_steps: usize,
    /// The relative tolerance.
    #[serde(default = "tol")]
    pub tolerance: f64,
}

fn one() -> usize {
    1
}
fn thirty() -> usize {
    30
}
fn tol() -> f64 {
    1e-10
}

impl Default for ContactSolveSpec {
    fn default() -> Self {
        Self {
            load_steps: 1,
            max_newton_steps: 30,
            tolerance: 1e-10,
        }
    }
}

/// The Voigt names of the stress components.
pub const STRESS_NAMES: [&str; 6] = [
    "stress_xx",
    "stress_yy",
    "stress_zz",
    "stress_yz",
    "stress_xz",
    "stress_xy",
];

impl ContactSpec {
    /// Parses a scene file's text; `path` names it in messages.
    ///
    /// # Errors
    /// [`SceneError::Syntax`] for bad TOML or an unknown key; [`SceneError::Invalid`] naming
    /// the key for values out of range (see [`check`](Self::check)).
    pub fn parse(text: &str, path: &Path) -> Result<Self, SceneError> {
        let spec: Self = SceneError::parse(path, text)?;
        spec.check(path)?;
        Ok(spec)
    }

    /// The TOML text of the scene.
    ///
    /// # Errors
    /// [`SceneError::Other`] if a value cannot be written as TOML.
    pub fn to_toml(&self) -> Result<String, SceneError> {
        toml::to_string(self).map_err(|e| SceneError::Other(format!("scene as TOML: {e}")))
    }

    /// Checks values and cross-references that do not need the meshes.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming the key.
    pub fn check(&self, path: &Path) -> Result<(), SceneError> {
        let invalid = |key: &str, what: String| SceneError::Invalid {
            path: path.to_path_buf(),
            key: key.to_string(),
            what,
        };
        if self.kind != "contact" {
            return Err(invalid(
                "kind",
                format!("\"{}\" is not \"contact\"", self.kind),
            ));
        }
        if self.bodies.len() != 2 {
            return Err(invalid(
                "bodies",
                format!(
                    "a contact scene has exactly two bodies, found {}",
                    self.bodies.len()
                ),
            ));
        }
        for (name, b) in &self.bodies {
            let key = |k: &str| format!("bodies.{name}.{k}");
            if name.is_empty()
                || !name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
            {
                return Err(invalid(
                    &format!("bodies.{name}"),
                    "a body name is made of letters, digits, '_' and '-' (it names the VTU file)"
                        .into(),
                ));
            }
            if name == "report" || name == "interface" {
                return Err(invalid(
                    &format!("bodies.{name}"),
                    format!("\"{name}\" is reserved for {name}.json / {name}.vtu"),
                ));
            }
            let e = b.youngs_modulus;
            if !(e > 0.0 && e.is_finite()) {
                return Err(invalid(
                    &key("youngs_modulus"),
                    format!("{e} is not positive and finite"),
                ));
            }
            let nu = b.poisson_ratio;
            if !(nu > -1.0 && nu < 0.5) {
                return Err(invalid(
                    &key("poisson_ratio"),
                    format!("{nu} is not in (-1, 0.5)"),
                ));
            }
            for (i, d) in b.dirichlet.iter().enumerate() {
                let k = format!("bodies.{name}.dirichlet[{i}].value");
                match (&d.value, d.component) {
                    (ComponentValue::Array(_), c) if c != Component::All => {
                        return Err(invalid(
                            &k,
                            "an array is for component = \"all\"; give a number".into(),
                        ))
                    }
                    (ComponentValue::Array(v), _) if v.iter().any(|x| !x.is_finite()) => {
                        return Err(invalid(&k, format!("{v:?} is not finite")))
                    }
                    (ComponentValue::Number(x), _) if !x.is_finite() => {
                        return Err(invalid(&k, format!("{x} is not finite")))
                    }
                    _ => {}
                }
            }
            for (i, t) in b.traction.iter().enumerate() {
                if !(t.value.len() == 2 || t.value.len() == 3)
                    || t.value.iter().any(|x| !x.is_finite())
                {
                    return Err(invalid(
                        &format!("bodies.{name}.traction[{i}].value"),
                        format!("{:?} is not 2 or 3 finite numbers", t.value),
                    ));
                }
            }
        }
        for (which, side) in [
            ("slave", &self.contact.slave),
            ("master", &self.contact.master),
        ] {
            if !self.bodies.contains_key(&side.body) {
                return Err(invalid(
                    &format!("contact.{which}.body"),
                    format!(
                        "no body named \"{}\" (bodies: {})",
                        side.body,
                        self.bodies.keys().cloned().collect::<Vec<_>>().join(", ")
                    ),
                ));
            }
        }
        if self.contact.slave.body == self.contact.master.body {
            return Err(invalid(
                "contact.master.body",
                "the slave and master sides are on two different bodies".into(),
            ));
        }
        let c = &self.contact;
        if let Some(named) = &c.named_law {
            if c.law != LawSpec::default() {
                return Err(invalid(
                    "contact.named_law",
                    "give either law or named_law, not both".into(),
                ));
            }
            // Unknown names and parameters are checked against the shipped laws when the
            // scene runs with them (a program's registry may know more).
            if named.name.is_empty() {
                return Err(invalid("contact.named_law", "the name is empty".into()));
            }
        }
        match c.law {
            // Exact contact, or a law by name: the exponential law's keys are refused rather
            // than passed over.
            _ if c.named_law.is_some() || c.law == LawSpec::Exact => {
                let by_name = if c.named_law.is_some() {
                    "; a law by name takes its parameters in named_law"
                } else {
                    ""
                };
                for (k, v) in [
                    ("base_pressure", c.base_pressure),
                    ("stiffness", c.stiffness),
                    ("onset", c.onset),
                ] {
                    if v.is_some() {
                        return Err(invalid(
                            &format!("contact.{k}"),
                            format!(
                                "only the exponential law (law = \"exponential\") has it{by_name}"
                            ),
                        ));
                    }
                }
            }
            // The built-in exponential law.
            _ => {
                for (k, v) in [
                    ("base_pressure", c.base_pressure),
                    ("stiffness", c.stiffness),
                    ("onset", c.onset),
                ] {
                    if v.is_none() {
                        return Err(invalid(
                            &format!("contact.{k}"),
                            "missing: the exponential law needs base_pressure, stiffness and onset"
                                .into(),
                        ));
                    }
                }
                if let Err(e) = ExponentialPressure::try_new(
                    c.base_pressure.unwrap_or(0.0),
                    c.stiffness.unwrap_or(0.0),
                    c.onset.unwrap_or(0.0),
                ) {
                    return Err(invalid("contact.law", e.to_string()));
                }
            }
        }
        if let Some(r) = c.search_radius {
            if !(r > 0.0 && r.is_finite()) {
                return Err(invalid(
                    "contact.search_radius",
                    format!("{r} is not positive and finite"),
                ));
            }
        }
        if self.solve.load_steps == 0 {
            return Err(invalid("solve.load_steps", "must be at least 1".into()));
        }
        if self.solve.max_newton_steps == 0 {
            return Err(invalid(
                "solve.max_newton_steps",
                "must be at least 1".into(),
            ));
        }
        if !(self.solve.tolerance > 0.0 && self.solve.tolerance.is_finite()) {
            return Err(invalid(
                "solve.tolerance",
                format!("{} is not positive and finite", self.solve.tolerance),
            ));
        }
        Ok(())
    }

    /// Reads the meshes, solves and renders the outputs (see the [module](self)).
    ///
    /// # Errors
    /// [`SceneError::Mesh`] for a missing file or group, [`SceneError::Invalid`] for a
    /// component or traction that does not fit the dimension and for a load step whose
    /// Newton iteration fails (naming it), [`SceneError::Physics`] otherwise.
    pub fn run(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
    ) -> Result<SceneOutput, SceneError> {
        self.solve(path, base, source)?.output()
    }

    /// Reads the meshes and solves, without rendering.
    ///
    /// # Errors
    /// As [`run`](Self::run).
    pub fn solve(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
    ) -> Result<SolvedContact, SceneError> {
        self.solve_with(path, base, source, &Registries::default())
    }

    /// [`run`](Self::run) with the cells and laws of `registries` (the shipped ones and a
    /// program's own).
    ///
    /// # Errors
    /// As [`solve_with`](Self::solve_with).
    pub fn run_with(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
        registries: &Registries,
    ) -> Result<SceneOutput, SceneError> {
        self.solve_with(path, base, source, registries)?.output()
    }

    /// [`solve`](Self::solve), with the bodies' cells looked up in `registries.cells` and a
    /// `named_law` made by `registries.laws` (the shipped ones and a program's own).
    ///
    /// # Errors
    /// As [`run`](Self::run); [`SceneError::Invalid`] (key `contact.named_law`) for a law the
    /// registry does not know or whose parameters it refuses.
    pub fn solve_with(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
        registries: &Registries,
    ) -> Result<SolvedContact, SceneError> {
        let t_start = Instant::now();
        let errors = Errors { path };
        let volumes = self.read_volumes(&errors, base, source, &registries.cells)?;
        let dim = volumes[0].1.dimension as usize;
        let order = [&self.contact.slave, &self.contact.master];
        let mut bodies = Vec::with_capacity(2);
        let mut surfaces = Vec::with_capacity(2);
        let mut labels = Vec::with_capacity(2);
        for (which, (side, (name, v))) in ["slave", "master"]
            .into_iter()
            .zip(order.iter().zip(&volumes))
        {
            bodies.push(self.elastic_body(&errors, name, v, dim)?);
            let surface = v
                .boundary_surface_in(&side.group)
                .map_err(|e| errors.mesh(format!("contact.{which}"), e))?;
            let faces = v
                .boundary_faces_in(&side.group)
                .map_err(|e| errors.mesh(format!("contact.{which}"), e))?;
            surfaces.push((surface, faces));
            labels.push(v.label());
        }
        let t_read = t_start.elapsed().as_secs_f64();

        let t = Instant::now();
        let (coupling, tolerances) = coupling_of(&self.contact.settings(), "contact", path)?;
        let (master_surface, _) = surfaces.pop().expect("two surfaces");
        let (slave_surface, slave_faces) = surfaces.pop().expect("two surfaces");
        let interface = Interface::with_tolerances(slave_surface, master_surface, tolerances)
            .map_err(|e| errors.physics(e.into()))?;
        let tie = Tie::on_interface(&bodies[0].mesh, &bodies[1].mesh, interface, &coupling)
            .map_err(|e| errors.physics(e))?;
        let gap = NormalGap::new(
            &tie,
            dim,
            bodies[0].mesh.node_count(),
            bodies[1].mesh.node_count(),
        )
        .map_err(|e| errors.physics(e))?;
        let t_coupling = t.elapsed().as_secs_f64();

        let t = Instant::now();
        let options = ElasticOptions::default();
        let stiffness = [
            assemble_elastic_stiffness(&bodies[0], &options).map_err(|e| errors.physics(e))?,
            assemble_elastic_stiffness(&bodies[1], &options).map_err(|e| errors.physics(e))?,
        ];
        let load = [
            assemble_elastic_load(&bodies[0], &options).map_err(|e| errors.physics(e))?,
            assemble_elastic_load(&bodies[1], &options).map_err(|e| errors.physics(e))?,
        ];
        let dirichlet = [bodies[0].dirichlet_dofs(), bodies[1].dirichlet_dofs()];
        let t_assembly = t.elapsed().as_secs_f64();
        let held = rigid_motions(
            [bodies[0].mesh.coords(), bodies[1].mesh.coords()],
            [&dirichlet[0].0, &dirichlet[1].0],
            &gap,
        );
        let names = [bodies[0].name.as_str(), bodies[1].name.as_str()];
        for (name, h) in names.iter().zip(&held) {
            if !h.free.is_empty() {
                return Err(errors.physics(PhysicsError::NotHeld {
                    body: name.to_string(),
                    motions: describe_motions(&h.free),
                }));
            }
        }

        let t = Instant::now();
        let system = ContactSystem {
            stiffness: &stiffness,
            load: &load,
            dirichlet: &dirichlet,
            gap: &gap,
        };
        let (solution, law_description, complementarity) =
            self.solve_law(&errors, &system, &tie, dim, &registries.laws)?;
        let solution = solution.map_err(|(step, e)| match (step, e) {
            (Some(k), e) => errors.invalid(
                "solve.load_steps".into(),
                format!(
                    "load step {k} of {}: Newton's method did not converge: {e}",
                    self.solve.load_steps
                ),
            ),
            (None, e) => errors.physics(name_bodies(e, names, &held)),
        })?;
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

    /// The bodies' meshes, slave first (through `source`, paths relative to `base`), of one
    /// dimension.
    fn read_volumes(
        &self,
        errors: &Errors,
        base: &Path,
        source: &dyn SceneSource,
        registry: &VolumeRegistry,
    ) -> Result<Vec<(String, GmshVolume)>, SceneError> {
        let mut volumes = Vec::with_capacity(2);
        for side in [&self.contact.slave, &self.contact.master] {
            let name = &side.body;
            let b = &self.bodies[name];
            let file = base.join(&b.mesh);
            let bytes = source
                .read(&file)
                .map_err(|e| errors.mesh(format!("bodies.{name}.mesh"), e))?;
            let v = parse_gmsh_volume(bytes, &file, &b.group, registry)
                .map_err(|e| errors.mesh(format!("bodies.{name}.group"), e))?;
            volumes.push((name.clone(), v));
        }
        let dim = volumes[0].1.dimension;
        if volumes[1].1.dimension != dim {
            return Err(errors.invalid(
                "bodies".into(),
                format!(
                    "body \"{}\" is {}D but body \"{}\" is {}D",
                    volumes[0].0, dim, volumes[1].0, volumes[1].1.dimension
                ),
            ));
        }
        Ok(volumes)
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
        let options = ContactOptions {
            load_steps: self.solve.load_steps,
            max_newton_steps: self.solve.max_newton_steps,
            tolerance: self.solve.tolerance,
        };
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

/// The errors of one scene file, each naming it.
struct Errors<'a> {
    path: &'a Path,
}

impl Errors<'_> {
    fn mesh(&self, context: String, source: IoError) -> SceneError {
        SceneError::Mesh {
            path: self.path.to_path_buf(),
            context,
            source: Box::new(source),
        }
    }

    fn physics(&self, source: PhysicsError) -> SceneError {
        SceneError::Physics {
            path: self.path.to_path_buf(),
            source: Box::new(source),
        }
    }

    fn invalid(&self, key: String, what: String) -> SceneError {
        SceneError::Invalid {
            path: self.path.to_path_buf(),
            key,
            what,
        }
    }
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

/// The load steps' solution, or the step (if one) and the error where they failed.
type StepsResult = Result<ContactSolution, (Option<usize>, PhysicsError)>;

/// The assembled contact problem of the two bodies, before its law: stiffnesses, loads,
/// prescribed displacements and the normal gap.
struct ContactSystem<'a> {
    stiffness: &'a [mortar_core::linalg::SparseMatrix; 2],
    load: &'a [Vec<f64>; 2],
    dirichlet: &'a [Dofs; 2],
    gap: &'a NormalGap,
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
) -> StepsResult {
    let run = |scale: f64, steps: usize| {
        let l = [0, 1].map(|b| load[b].iter().map(|x| x * scale).collect::<Vec<_>>());
        let d = [0, 1].map(|b| dirichlet[b].1.iter().map(|x| x * scale).collect::<Vec<_>>());
        solve_contact(
            [&stiffness[0], &stiffness[1]],
            [&l[0], &l[1]],
            [(&dirichlet[0].0, &d[0]), (&dirichlet[1].0, &d[1])],
            gap,
            law,
            &ContactOptions {
                load_steps: steps,
                ..*options
            },
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

/// A solved contact scene.
#[derive(Debug)]
pub struct SolvedContact {
    /// The scene.
    pub spec: ContactSpec,
    /// The scene file.
    pub path: PathBuf,
    /// The bodies' meshes as `file#group`, slave first.
    pub labels: [String; 2],
    /// 2 or 3.
    pub dimension: usize,
    coupling: String,
    law: String,
    /// The bodies, slave first.
    pub bodies: [ElasticBody; 2],
    /// The tie of the contact surfaces.
    pub tie: Tie,
    slave_faces: Vec<BoundaryFace>,
    /// The contact solution.
    pub solution: ContactSolution,
    /// Per body (slave first): nodal stresses (Voigt) and von Mises stresses.
    pub stresses: [(Vec<[f64; 6]>, Vec<f64>); 2],
    /// Per body: the stiffness matrix (reactions are `K u - f` on the Dirichlet rows).
    pub stiffness: [SparseMatrix; 2],
    /// Per body: the load vector.
    pub load: [Vec<f64>; 2],
    /// Per body: the Dirichlet unknowns and their values.
    pub dirichlet: [(Vec<u32>, Vec<f64>); 2],
    /// The weighted normal gap of the tie.
    pub gap: NormalGap,
    /// The exact law's parameter `c` (Pa/m), automatic; `None` for another law.
    pub complementarity: Option<f64>,
    seconds: [(&'static str, f64); 5],
    t_start: Instant,
}

impl SolvedContact {
    /// Seconds per phase so far: reading, coupling, assembly, contact solve, stresses.
    pub fn seconds(&self) -> &[(&'static str, f64)] {
        &self.seconds
    }

    /// `NAME.vtu` per body, `interface.vtu`, `report.json` and a summary.
    ///
    /// # Errors
    /// [`SceneError::Other`] if a file cannot be rendered.
    pub fn output(&self) -> Result<SceneOutput, SceneError> {
        let t_out = Instant::now();
        let other = |e: &dyn std::fmt::Display| SceneError::Other(e.to_string());
        let dim = self.dimension;
        let sol = &self.solution;
        let mut files = Vec::with_capacity(4);
        let mut body_reports = Vec::with_capacity(2);
        for (i, body) in self.bodies.iter().enumerate() {
            let n = body.mesh.node_count();
            let u = &sol.displacements[i];
            let mut u3 = vec![0.0; 3 * n];
            for node in 0..n {
                u3[3 * node..3 * node + dim].copy_from_slice(&u[dim * node..dim * node + dim]);
            }
            let (stress, vm) = &self.stresses[i];
            let comps: Vec<Vec<f64>> = (0..6)
                .map(|k| stress.iter().map(|s| s[k]).collect())
                .collect();
            let mut point_data: Vec<(&str, &[f64])> = STRESS_NAMES
                .iter()
                .zip(&comps)
                .map(|(name, c)| (*name, c.as_slice()))
                .collect();
            point_data.push(("von_mises", vm));
            let file = format!("{}.vtu", body.name);
            let vtu = vtu_string_with_vectors(
                Path::new(&file),
                &[VtuPiece {
                    mesh: &body.mesh,
                    point_data,
                }],
                &[("displacement", vec![&u3])],
            )
            .map_err(|e| other(&e))?;
            files.push((file.clone(), vtu.into_bytes()));
            let umax = u.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            let vmax = vm.iter().fold(0.0f64, |a, x| a.max(*x));
            body_reports.push(serde_json::json!({
                "name": body.name,
                "role": if i == 0 { "slave" } else { "master" },
                "mesh": self.labels[i],
                "nodes": n,
                "cells": body.mesh.cell_count(),
                "displacement_max": umax,
                "von_mises_max": vmax,
                "vtu": file,
            }));
        }

        // The interface: the slave surface, its nodes in coupling row order.
        let slave = &self.bodies[0];
        let rows = &self.tie.slave_nodes();
        let mut row_of = std::collections::HashMap::with_capacity(rows.len());
        for (j, &node) in rows.iter().enumerate() {
            row_of.insert(node, j as u32);
        }
        let points: Vec<Vector3<f64>> = rows
            .iter()
            .map(|&n| slave.mesh.coords()[n as usize])
            .collect();
        // Every node of a slave face has a row (the interface is made of these faces): a
        // face without is refused, not left out of the file.
        let cells = self
            .slave_faces
            .iter()
            .map(|f| {
                let nodes: Option<Vec<u32>> =
                    f.nodes.iter().map(|n| row_of.get(n).copied()).collect();
                nodes.map(|nodes| (f.element, nodes)).ok_or_else(|| {
                    SceneError::Other(format!(
                        "interface.vtu: a node of slave face {} (of cell {}) has no row of the \
                         coupling",
                        f.local_face, f.cell
                    ))
                })
            })
            .collect::<Result<Vec<(ElementRef, Vec<u32>)>, SceneError>>()?;
        let vtu = surface_vtu_string(
            Path::new("interface.vtu"),
            &points,
            &cells,
            &[("gap", &sol.gap), ("contact_pressure", &sol.pressure)],
        )
        .map_err(|e| other(&e))?;
        files.push(("interface.vtu".to_string(), vtu.into_bytes()));

        let steps = steps_json(&sol.steps);
        let pmax = sol.pressure.iter().fold(0.0f64, |a, x| a.max(*x));
        let mut seconds: serde_json::Map<String, serde_json::Value> = self
            .seconds
            .iter()
            .map(|(k, v)| (k.to_string(), serde_json::json!(v)))
            .collect();
        seconds.insert(
            "output".into(),
            serde_json::json!(t_out.elapsed().as_secs_f64()),
        );
        seconds.insert(
            "total".into(),
            serde_json::json!(self.t_start.elapsed().as_secs_f64()),
        );
        let c = &self.spec.contact;
        let warnings: Vec<String> = self
            .tie
            .coupling()
            .warnings
            .iter()
            .map(|w| {
                mortar::io::warning_text(w, &widen_hint("contact", self.spec.contact.search_radius))
            })
            .collect();
        let report = serde_json::json!({
            "kind": "contact",
            "scene": self.path.display().to_string(),
            "title": self.spec.title,
            "dimension": dim,
            "formulation": sol.formulation,
            "law": self.law,
            "interface": {
                "slave": format!("{}#{}", c.slave.body, c.slave.group),
                "master": format!("{}#{}", c.master.body, c.master.group),
                "multipliers": c.multipliers,
                "integration": c.integration,
                "coupling": self.coupling,
                "slave_nodes": rows.len(),
                "vtu": "interface.vtu",
            },
            "load_steps": steps,
            "active": sol.steps.last().map_or(0, |s| s.active),
            "contact_force": sol.force,
            "pressure_max": pmax,
            "bodies": body_reports,
            "warnings": warnings,
            "seconds": seconds,
        });
        let mut json = serde_json::to_string_pretty(&report).map_err(|e| other(&e))?;
        json.push('\n');
        files.push(("report.json".to_string(), json.into_bytes()));
        let summary = format!(
            "contact, {dim}D, {} + {} nodes, {} slave interface nodes\nformulation: {}\nload steps: {} (Newton steps {:?}), active nodes {}, contact force {:.6e}, peak pressure {:.6e} Pa",
            self.bodies[0].mesh.node_count(),
            self.bodies[1].mesh.node_count(),
            rows.len(),
            sol.formulation,
            sol.steps.len(),
            sol.steps.iter().map(|s| s.newton_steps).collect::<Vec<_>>(),
            sol.steps.last().map_or(0, |s| s.active),
            sol.force,
            pmax,
        );
        Ok(SceneOutput {
            files,
            summary,
            warnings,
        })
    }
}

/// The load steps of a contact solution as the reports write them.
pub(super) fn steps_json(steps: &[mortar_physics::contact::ContactStep]) -> Vec<serde_json::Value> {
    steps
        .iter()
        .enumerate()
        .map(|(k, s)| {
            serde_json::json!({
                "step": k + 1,
                "load_factor": s.load_factor,
                "newton_steps": s.newton_steps,
                "settled_at": s.settled_at,
                "residuals": s.residuals,
                "active": s.active,
            })
        })
        .collect()
}
