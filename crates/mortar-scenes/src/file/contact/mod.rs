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

mod check;
mod output;
mod solve;
mod solve_spec;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

use mortar_core::linalg::SparseMatrix;
use mortar_fem::mesh::BoundaryFace;
use mortar_physics::contact::{ContactSolution, NormalGap};
use mortar_physics::elastic::ElasticBody;
use mortar_physics::tied::Tie;
use serde::{Deserialize, Serialize};

use super::tied_heat::SideSpec;
use crate::NamedLaw;

pub(super) use output::steps_json;
pub use solve_spec::ContactSolveSpec;

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

mortar::coupling_keys! {
    /// The contact interface.
    pub struct ContactInterfaceSpec {
        /// The slave side.
        pub slave: SideSpec,
        /// The master side.
        pub master: SideSpec,
        /// The law.
        #[serde(default)]
        pub law: LawSpec,
        /// A law by name from the shipped [`LawRegistry`](mortar_physics::laws::LawRegistry) (or a
        /// program's own, through [`ContactSpec::solve_with`](crate::file::FileScene::solve_with)),
        /// with its parameters, in place of `law`: `named_law = { name = "exponential_pressure",
        /// base_pressure = 1e5, stiffness = 1e12, onset = 1e-6 }`.
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
    /// The linear solver the Newton systems went to, and why.
    pub linear_solver: crate::linear_solver::PickedSolver,
    seconds: [(&'static str, f64); 5],
    t_start: Instant,
}

impl SolvedContact {
    /// Seconds per phase so far: reading, coupling, assembly, contact solve, stresses.
    pub fn seconds(&self) -> &[(&'static str, f64)] {
        &self.seconds
    }
}
