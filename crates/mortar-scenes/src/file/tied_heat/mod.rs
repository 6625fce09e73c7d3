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
//!   (default auto: the dual condensation when D is diagonal); `backend = "auto" | "direct" |
//!   "petsc"`, `linear_tolerance` and `petsc_options` (where the system goes: see
//!   [`crate::linear_solver`]).
//!
//! Outputs: `NAME.vtu` per body (nodal `temperature`, at the end of a transient solve) and
//! `report.json` (formulation and why, unknowns, seconds per phase, solver iterations).

mod check;
mod output;
mod solve;
mod solve_spec;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

use mortar_physics::heat::{TiedHeat, TiedHeatSolution};
use serde::{Deserialize, Serialize};

pub use solve_spec::{FormulationSpec, Mode, SolveSpec};

/// The most time steps a transient tied-heat scene may ask for (the pellet scene's limit too):
/// beyond it a step count is refused rather than run without end.
pub const MAX_STEPS: usize = 1_000_000;

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

mortar::coupling_keys! {
    /// The interface and its mortar coupling.
    pub struct InterfaceSpec {
        /// The slave side: it carries the multipliers.
        pub slave: SideSpec,
        /// The master side.
        pub master: SideSpec,
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
    /// The linear solver the system went to, and why.
    pub linear_solver: crate::linear_solver::PickedSolver,
    t_start: Instant,
    t_read: f64,
}
