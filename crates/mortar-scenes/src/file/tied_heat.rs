//! `kind = "tied_heat"`: heat conduction in two bodies read from Gmsh files, tied by mortar
//! along two physical groups of their boundaries.
//!
//! Keys (all others are errors):
//!
//! - `kind = "tied_heat"`, optional `title` (a string) and `dimension` (2 or 3, checked
//!   against the meshes).
//! - `[bodies.NAME]`, exactly two (`NAME`: letters, digits, `_`, `-`; it names the VTU file):
//!   `mesh` (a Gmsh 4.1 file, relative to the scene file), `group` (the physical group of the
//!   cells), `conductivity` (k > 0), `rho_cp` (volumetric heat capacity, needed for a
//!   transient solve; default 0), `source` (W/m^3, default 0), `initial` (the initial
//!   temperature of a transient solve, default 0), `dirichlet = [{ group, value }, ...]`
//!   (prescribed temperature) and `neumann = [{ group, flux }, ...]` (entering heat flux
//!   `k dT/dn`, W/m^2) on physical groups of the body's boundary faces (lines in 2D, surfaces
//!   in 3D). Boundary faces without a condition are insulated.
//! - `[interface]`: `slave = { body, group }`, `master = { body, group }` (the slave side
//!   carries the multipliers), `multipliers = "standard" | "dual" | "linear"` (default
//!   `"dual"`; `"linear"`: on the corner nodes of second-order faces only),
//!   `integration = "segment" | "element"` (default `"segment"`), `degree` (default
//!   automatic), and for segment-based integration `curved_tolerance`, `subdivision` (curved
//!   second-order faces in 3D) and `quad_subdivision` (non-parallelogram slave quads);
//!   `search_radius` (a distance along the slave normals; default as far as the nearest
//!   master surface, within a bound relative to the interface's size) and
//!   `require_full_coverage` (default false: uncovered slave area and overlapping master
//!   faces are warnings, not errors).
//! - `[solve]` (optional): `mode = "steady" | "transient"` (default steady); `dt` and `steps`
//!   (at most [`MAX_STEPS`])
//!   for a transient solve; `formulation = "auto" | "saddle_point" | "dual_condensed"`
//!   (default auto: the dual condensation when D is diagonal).
//!
//! Outputs: `NAME.vtu` per body (nodal `temperature`, at the end of a transient solve) and
//! `report.json` (formulation and why, unknowns, seconds per phase, solver iterations).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use mortar_core::Interface;
use mortar_physics::heat::{
    HeatBody, HeatMaterial, HeatOptions, NeumannCondition, TiedHeat, TiedHeatSolution,
};
use mortar_physics::tied::{FormulationChoice, TiedOptions};
use serde::{Deserialize, Serialize};

use super::{coupling_of, face_nodes, widen_hint};
use super::{SceneError, SceneOutput, SceneSource};
use mortar::extend::Registries;

/// The most time steps a transient tied-heat scene may ask for (the pellet scene's limit too):
/// beyond it a step count is refused rather than run without end.
pub const MAX_STEPS: usize = 1_000_000;
use mortar::io::vtu::{vtu_string, VtuPiece};
use mortar::io::{parse_gmsh_volume, CouplingSettings, GmshVolume, Integration, Multipliers};

/// A tied heat scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TiedHeatSpec {
    /// `"tied_heat"`.
    pub kind: String,
    /// A title for reports.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub title: Option<String>,
    /// The expected dimension of the bodies (2 or 3), checked against the meshes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dimension: Option<u8>,
    /// The settings of the solve.
    #[serde(default)]
    pub solve: SolveSpec,
    /// The two bodies, by name.
    pub bodies: BTreeMap<String, BodySpec>,
    /// The interface.
    pub interface: InterfaceSpec,
}

/// One body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// The Gmsh 4.1 file, relative to the scene file's folder.
    pub mesh: PathBuf,
    /// The physical group of the body's cells.
    pub group: String,
    /// The conductivity k (W/m/K).
    pub conductivity: f64,
    /// The volumetric heat capacity rho c_p (J/m^3/K).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rho_cp: Option<f64>,
    /// The heat source (W/m^3).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub source: f64,
    /// The initial temperature of a transient solve.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub initial: f64,
    /// Prescribed temperatures.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub dirichlet: Vec<DirichletSpec>,
    /// Entering heat fluxes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub neumann: Vec<NeumannSpec>,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// A prescribed temperature on a physical group of boundary faces.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DirichletSpec {
    /// The physical group (in the body's mesh file).
    pub group: String,
    /// The temperature.
    pub value: f64,
}

/// An entering heat flux `k dT/dn` on a physical group of boundary faces.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NeumannSpec {
    /// The physical group (in the body's mesh file).
    pub group: String,
    /// The flux (W/m^2), positive into the body.
    pub flux: f64,
}

/// One side of the interface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SideSpec {
    /// The body's name.
    pub body: String,
    /// The physical group of the side's faces (in the body's mesh file).
    pub group: String,
}

/// The interface and its mortar coupling.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterfaceSpec {
    /// The slave side: it carries the multipliers.
    pub slave: SideSpec,
    /// The master side.
    pub master: SideSpec,
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

impl InterfaceSpec {
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

/// Steady or transient.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// The steady state.
    #[default]
    Steady,
    /// Backward Euler from the initial temperatures.
    Transient,
}

/// The formulation of the tied system.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FormulationSpec {
    /// The dual condensation when D is diagonal, else the saddle point.
    #[default]
    Auto,
    /// The saddle point (sparse LU).
    SaddlePoint,
    /// The dual condensation (sparse Cholesky); an error if D is not diagonal.
    DualCondensed,
}

/// The settings of the solve.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolveSpec {
    /// Steady or transient.
    #[serde(default)]
    pub mode: Mode,
    /// The time step of a transient solve.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dt: Option<f64>,
    /// The number of time steps of a transient solve.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<usize>,
    /// The formulation.
    #[serde(default)]
    pub formulation: FormulationSpec,
}

impl TiedHeatSpec {
    /// Parses a scene file's text; `path` names it in messages.
    ///
    /// # Errors
    /// [`SceneError::Syntax`] for bad TOML, an unknown or missing key or a wrong type (with
    /// its line); [`SceneError::Invalid`] for values out of range or inconsistent (see
    /// [`check`](Self::check)).
    pub fn parse(text: &str, path: &Path) -> Result<Self, SceneError> {
        let spec: Self = SceneError::parse(path, text)?;
        spec.check(path)?;
        Ok(spec)
    }

    /// The TOML text of the scene.
    ///
    /// # Errors
    /// [`SceneError::Other`] if a value cannot be written as TOML (a NaN, say).
    pub fn to_toml(&self) -> Result<String, SceneError> {
        toml::to_string(self).map_err(|e| SceneError::Other(format!("scene as TOML: {e}")))
    }

    /// Checks values and cross-references: the kind, two bodies with file-safe names,
    /// positive conductivities, interface sides naming two different bodies, the solve mode's
    /// keys.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming the key.
    pub fn check(&self, path: &Path) -> Result<(), SceneError> {
        let invalid = |key: &str, what: String| SceneError::Invalid {
            path: path.to_path_buf(),
            key: key.to_string(),
            what,
        };
        if self.kind != "tied_heat" {
            return Err(invalid(
                "kind",
                format!("\"{}\" is not \"tied_heat\"", self.kind),
            ));
        }
        if let Some(d) = self.dimension {
            if d != 2 && d != 3 {
                return Err(invalid("dimension", format!("{d} is not 2 or 3")));
            }
        }
        if self.bodies.len() != 2 {
            return Err(invalid(
                "bodies",
                format!(
                    "a tied heat scene has exactly two bodies, found {} ({})",
                    self.bodies.len(),
                    self.bodies.keys().cloned().collect::<Vec<_>>().join(", ")
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
            if name == "report" {
                return Err(invalid(
                    "bodies.report",
                    "\"report\" is reserved for report.json".into(),
                ));
            }
            if !(b.conductivity > 0.0 && b.conductivity.is_finite()) {
                return Err(invalid(
                    &key("conductivity"),
                    format!("{} is not positive and finite", b.conductivity),
                ));
            }
            if let Some(c) = b.rho_cp {
                if !(c >= 0.0 && c.is_finite()) {
                    return Err(invalid(
                        &key("rho_cp"),
                        format!("{c} is not non-negative and finite"),
                    ));
                }
            }
            for (k, v) in [("source", b.source), ("initial", b.initial)] {
                if !v.is_finite() {
                    return Err(invalid(&key(k), format!("{v} is not finite")));
                }
            }
            for (i, d) in b.dirichlet.iter().enumerate() {
                if !d.value.is_finite() {
                    return Err(invalid(
                        &format!("bodies.{name}.dirichlet[{i}].value"),
                        format!("{} is not finite", d.value),
                    ));
                }
            }
            for (i, n) in b.neumann.iter().enumerate() {
                if !n.flux.is_finite() {
                    return Err(invalid(
                        &format!("bodies.{name}.neumann[{i}].flux"),
                        format!("{} is not finite", n.flux),
                    ));
                }
            }
            if self.solve.mode == Mode::Transient && b.rho_cp.is_none() {
                return Err(invalid(
                    &key("rho_cp"),
                    "missing: a transient solve needs the volumetric heat capacity".into(),
                ));
            }
        }
        for (side, s) in [
            ("interface.slave", &self.interface.slave),
            ("interface.master", &self.interface.master),
        ] {
            if !self.bodies.contains_key(&s.body) {
                return Err(invalid(
                    &format!("{side}.body"),
                    format!(
                        "no body named \"{}\" (the bodies are {})",
                        s.body,
                        self.bodies.keys().cloned().collect::<Vec<_>>().join(", ")
                    ),
                ));
            }
        }
        if let Some(r) = self.interface.search_radius {
            if !(r > 0.0 && r.is_finite()) {
                return Err(invalid(
                    "interface.search_radius",
                    format!("{r} is not positive and finite"),
                ));
            }
        }
        if self.interface.slave.body == self.interface.master.body {
            return Err(invalid(
                "interface",
                format!(
                    "slave and master are both on body \"{}\"; they must be the two bodies",
                    self.interface.slave.body
                ),
            ));
        }
        match self.solve.mode {
            Mode::Steady => {
                for (k, set) in [
                    ("dt", self.solve.dt.is_some()),
                    ("steps", self.solve.steps.is_some()),
                ] {
                    if set {
                        return Err(invalid(
                            &format!("solve.{k}"),
                            "only a transient solve (mode = \"transient\") has a time step".into(),
                        ));
                    }
                }
            }
            Mode::Transient => {
                match self.solve.dt {
                    Some(dt) if dt > 0.0 && dt.is_finite() => {}
                    Some(dt) => {
                        return Err(invalid(
                            "solve.dt",
                            format!("{dt} is not positive and finite"),
                        ))
                    }
                    None => {
                        return Err(invalid(
                            "solve.dt",
                            "missing: a transient solve needs dt".into(),
                        ))
                    }
                }
                match self.solve.steps {
                    Some(s) if s > MAX_STEPS => {
                        return Err(invalid(
                            "solve.steps",
                            format!("{s} steps: at most {MAX_STEPS} (as the pellet scene)"),
                        ))
                    }
                    Some(s) if s >= 1 => {}
                    _ => {
                        return Err(invalid(
                            "solve.steps",
                            "a transient solve needs steps >= 1".into(),
                        ))
                    }
                }
            }
        }
        Ok(())
    }

    /// Reads the meshes (through `source`, paths relative to `base`, the scene file's
    /// folder), builds and solves the problem, and renders the VTU files and `report.json`.
    /// `path` names the scene file in messages and in the report.
    ///
    /// # Errors
    /// [`SceneError::Mesh`] for a missing mesh file, a missing group or a group of the wrong
    /// dimension (each naming the key, the file and the group); [`SceneError::Invalid`] for
    /// bodies of different dimensions or not of `dimension`; [`SceneError::Physics`] for a
    /// problem that cannot be built or solved (an inverted cell, an interface without
    /// overlap, a singular system).
    pub fn run(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
    ) -> Result<SceneOutput, SceneError> {
        self.solve(path, base, source)?.output()
    }

    /// Reads the meshes and solves the problem (see [`run`](Self::run)), without rendering.
    ///
    /// # Errors
    /// As [`run`](Self::run).
    pub fn solve(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
    ) -> Result<SolvedTiedHeat, SceneError> {
        self.solve_with(path, base, source, &Registries::default())
    }

    /// [`run`](Self::run) with the bodies' cells looked up in `registries.cells` (the shipped
    /// cells and a program's own; the interface faces are the surface elements of their
    /// faces).
    ///
    /// # Errors
    /// As [`run`](Self::run).
    pub fn run_with(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
        registries: &Registries,
    ) -> Result<SceneOutput, SceneError> {
        self.solve_with(path, base, source, registries)?.output()
    }

    /// [`solve`](Self::solve) with the cells of `registries` (see [`run_with`](Self::run_with)).
    ///
    /// # Errors
    /// As [`run`](Self::run).
    pub fn solve_with(
        &self,
        path: &Path,
        base: &Path,
        source: &dyn SceneSource,
        registries: &Registries,
    ) -> Result<SolvedTiedHeat, SceneError> {
        let t_start = Instant::now();
        let registry = &registries.cells;
        let mesh_error = |context: String, source| SceneError::Mesh {
            path: path.to_path_buf(),
            context,
            source: Box::new(source),
        };
        let physics = |source| SceneError::Physics {
            path: path.to_path_buf(),
            source: Box::new(source),
        };

        // Read the bodies, slave first.
        let order = [&self.interface.slave, &self.interface.master];
        let mut volumes: Vec<(String, GmshVolume)> = Vec::with_capacity(2);
        for side in order {
            let name = &side.body;
            let b = &self.bodies[name];
            let file = base.join(&b.mesh);
            let bytes = source
                .read(&file)
                .map_err(|e| mesh_error(format!("bodies.{name}.mesh"), e))?;
            let v = parse_gmsh_volume(bytes, &file, &b.group, registry)
                .map_err(|e| mesh_error(format!("bodies.{name}.group"), e))?;
            volumes.push((name.clone(), v));
        }
        let dims = [volumes[0].1.dimension, volumes[1].1.dimension];
        if dims[0] != dims[1] {
            return Err(SceneError::Invalid {
                path: path.to_path_buf(),
                key: "bodies".into(),
                what: format!(
                    "body \"{}\" ({}) is {}D but body \"{}\" ({}) is {}D",
                    volumes[0].0,
                    volumes[0].1.label(),
                    dims[0],
                    volumes[1].0,
                    volumes[1].1.label(),
                    dims[1]
                ),
            });
        }
        if let Some(d) = self.dimension {
            if d != dims[0] {
                return Err(SceneError::Invalid {
                    path: path.to_path_buf(),
                    key: "dimension".into(),
                    what: format!(
                        "the scene says {d}D, but the bodies' groups ({}, {}) are {}D",
                        volumes[0].1.label(),
                        volumes[1].1.label(),
                        dims[0]
                    ),
                });
            }
        }

        // Boundary conditions and interface sides.
        let mut bodies = Vec::with_capacity(2);
        let mut surfaces = Vec::with_capacity(2);
        for (side, (name, v)) in order.iter().zip(&volumes) {
            let b = &self.bodies[name];
            let mut body = HeatBody::new(
                name.clone(),
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
                    .map_err(|e| mesh_error(format!("bodies.{name}.dirichlet[{i}]"), e))?;
                let value = d.value;
                body = body.with_dirichlet_nodes(face_nodes(&faces), move |_, _| value);
            }
            for (i, n) in b.neumann.iter().enumerate() {
                let faces = v
                    .boundary_faces_in(&n.group)
                    .map_err(|e| mesh_error(format!("bodies.{name}.neumann[{i}]"), e))?;
                let flux = n.flux;
                body.neumann.push(NeumannCondition {
                    faces,
                    flux: Arc::new(move |_, _| flux),
                });
            }
            let which = if surfaces.is_empty() {
                "slave"
            } else {
                "master"
            };
            let surface = v
                .boundary_surface_in(&side.group)
                .map_err(|e| mesh_error(format!("interface.{which}"), e))?;
            surfaces.push(surface);
            bodies.push(body);
        }
        let t_read = t_start.elapsed().as_secs_f64();

        let (coupling, tolerances) = coupling_of(&self.interface.settings(), "interface", path)?;
        let master_surface = surfaces.pop().expect("two surfaces");
        let slave_surface = surfaces.pop().expect("two surfaces");
        let master = bodies.pop().expect("two bodies");
        let slave = bodies.pop().expect("two bodies");
        let interface = Interface::with_tolerances(slave_surface, master_surface, tolerances)
            .map_err(|e| physics(e.into()))?;
        let problem =
            TiedHeat::on_interface(slave, master, interface, &coupling, &HeatOptions::default())
                .map_err(physics)?;
        let tied = TiedOptions::default().with_formulation(match self.solve.formulation {
            FormulationSpec::Auto => FormulationChoice::Auto,
            FormulationSpec::SaddlePoint => FormulationChoice::SaddlePoint,
            FormulationSpec::DualCondensed => FormulationChoice::DualCondensed,
        });

        let (solution, steps, time) = match self.solve.mode {
            Mode::Steady => (problem.solve_steady(&tied, 0.0).map_err(physics)?, 0, 0.0),
            Mode::Transient => {
                let (dt, steps) = (self.solve.dt.unwrap_or(1.0), self.solve.steps.unwrap_or(1));
                let initial = [0, 1].map(|i| {
                    let b = &problem.bodies()[i];
                    vec![self.bodies[&b.name].initial; b.mesh.node_count()]
                });
                let mut stepper = problem
                    .backward_euler(&tied, initial, 0.0, dt)
                    .map_err(physics)?;
                let mut seconds = stepper.solution().seconds;
                let (mut loads, mut solve) = (0.0, 0.0);
                for done in 0..steps {
                    if crate::interrupt::requested() {
                        return Err(SceneError::Interrupted {
                            path: path.to_path_buf(),
                            done,
                            steps,
                        });
                    }
                    let s = stepper.step().map_err(physics)?;
                    loads += s.seconds.loads;
                    solve += s.seconds.solve;
                }
                seconds.loads = loads;
                seconds.solve = solve;
                let mut solution = stepper.solution().clone();
                solution.seconds = seconds;
                (solution, steps, stepper.time())
            }
        };

        Ok(SolvedTiedHeat {
            spec: self.clone(),
            path: path.to_path_buf(),
            labels: [volumes[0].1.label(), volumes[1].1.label()],
            files: [volumes[0].1.path.clone(), volumes[1].1.path.clone()],
            dimension: dims[0],
            coupling: coupling.describe(),
            problem,
            solution,
            steps,
            time,
            t_start,
            t_read,
        })
    }
}

/// A solved tied heat scene.
#[derive(Debug, Clone)]
pub struct SolvedTiedHeat {
    /// The scene.
    pub spec: TiedHeatSpec,
    /// The scene file.
    pub path: PathBuf,
    /// The bodies' meshes as `file#group`, slave first.
    pub labels: [String; 2],
    /// The bodies' mesh files, slave first.
    files: [PathBuf; 2],
    /// The dimension of the bodies.
    pub dimension: u8,
    coupling: String,
    /// The problem (bodies: slave first, named as in the scene).
    pub problem: TiedHeat,
    /// The solution (at the end of a transient solve).
    pub solution: TiedHeatSolution,
    /// Time steps taken (0 for a steady solve).
    pub steps: usize,
    /// The final time (0 for a steady solve).
    pub time: f64,
    t_start: Instant,
    t_read: f64,
}

impl SolvedTiedHeat {
    /// The VTU file of each body (`NAME.vtu`, nodal `temperature`), `report.json` and a
    /// readable summary.
    ///
    /// # Errors
    /// [`SceneError::Other`] if a file cannot be rendered.
    pub fn output(&self) -> Result<SceneOutput, SceneError> {
        let (problem, solution, steps, time) =
            (&self.problem, &self.solution, self.steps, self.time);
        let (t_start, t_read, dims) = (self.t_start, self.t_read, [self.dimension]);
        let path = &self.path;
        let t_out = Instant::now();
        let mut files = Vec::with_capacity(3);
        let mut body_reports = Vec::with_capacity(2);
        for (i, body) in problem.bodies().iter().enumerate() {
            let t = &solution.temperatures[i];
            let file = format!("{}.vtu", body.name);
            let vtu = vtu_string(
                Path::new(&file),
                &[VtuPiece {
                    mesh: &body.mesh,
                    point_data: vec![("temperature", t)],
                }],
            )
            .map_err(|e| SceneError::Other(e.to_string()))?;
            files.push((file.clone(), vtu.into_bytes()));
            let (lo, hi) = t
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                    (a.min(v), b.max(v))
                });
            body_reports.push(serde_json::json!({
                "name": body.name,
                "role": if i == 0 { "slave" } else { "master" },
                "mesh": self.labels[i],
                "nodes": body.mesh.node_count(),
                "cells": body.mesh.cell_count(),
                "temperature_min": lo,
                "temperature_max": hi,
                "vtu": file,
            }));
        }
        let f = &solution.formulation;
        let s = solution.seconds;
        let stats = &problem.tie().coupling().stats;
        let dofs: usize = problem.bodies().iter().map(|b| b.mesh.node_count()).sum();
        let seconds_output = t_out.elapsed().as_secs_f64();
        let warnings: Vec<String> = problem
            .tie()
            .coupling()
            .warnings
            .iter()
            .map(|w| {
                mortar::io::warning_text(
                    w,
                    &widen_hint("interface", self.spec.interface.search_radius),
                )
            })
            .collect();
        let report = serde_json::json!({
            "kind": "tied_heat",
            "scene": path.display().to_string(),
            "title": self.spec.title,
            "dimension": dims[0],
            "mode": self.spec.solve.mode,
            "steps": steps,
            "dt": self.spec.solve.dt,
            "time": time,
            "dofs": dofs,
            "formulation": {
                "name": f.formulation.describe(),
                "factorisation": f.factorisation,
                "reason": f.reason,
                "unknowns": f.unknowns,
                "nonzeros": f.nonzeros,
                "multipliers": f.multipliers,
                "redistributed": f.redistributed,
                "dropped": f.dropped,
            },
            "solver": { "kind": "sparse direct", "iterations": serde_json::Value::Null },
            "interface": {
                "slave": format!("{}#{}", self.files[0].display(), self.spec.interface.slave.group),
                "master": format!("{}#{}", self.files[1].display(), self.spec.interface.master.group),
                "multipliers": self.spec.interface.multipliers,
                "integration": self.spec.interface.integration,
                "coupling": self.coupling,
                "slave_nodes": problem.tie().slave_nodes().len(),
                "master_nodes": problem.tie().master_nodes().len(),
                "area": stats.area,
            },
            "bodies": body_reports,
            "warnings": warnings,
            "seconds": {
                "read": t_read,
                "assembly": s.assembly,
                "coupling": s.coupling,
                "loads": s.loads,
                "system": s.system,
                "factorisation": s.factorisation,
                "solve": s.solve,
                "output": seconds_output,
                "total": t_start.elapsed().as_secs_f64(),
            },
        });
        let mut json = serde_json::to_string_pretty(&report)
            .map_err(|e| SceneError::Other(format!("report.json: {e}")))?;
        json.push('\n');
        files.push(("report.json".to_string(), json.into_bytes()));

        let summary = format!(
            "tied heat, {}D, {} unknowns ({} + {} nodes){}\nformulation: {}\ntemperature: {}\nseconds: read {:.3}, assembly {:.3}, coupling {:.3}, factorisation {:.3}, solve {:.3}, total {:.3}",
            dims[0],
            dofs,
            problem.bodies()[0].mesh.node_count(),
            problem.bodies()[1].mesh.node_count(),
            if steps > 0 {
                format!(", {steps} steps to t = {time}")
            } else {
                String::new()
            },
            f,
            body_reports
                .iter()
                .map(|b| format!(
                    "{} in [{:.6}, {:.6}]",
                    b["name"].as_str().unwrap_or(""),
                    b["temperature_min"].as_f64().unwrap_or(f64::NAN),
                    b["temperature_max"].as_f64().unwrap_or(f64::NAN)
                ))
                .collect::<Vec<_>>()
                .join(", "),
            t_read,
            s.assembly,
            s.coupling,
            s.factorisation,
            s.solve,
            t_start.elapsed().as_secs_f64(),
        );
        Ok(SceneOutput {
            files,
            summary,
            warnings,
        })
    }
}
