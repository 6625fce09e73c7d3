//! The pellet scene: a fuel pellet (disc, `k = 1 / (A + B T)`) inside its
//! cladding (annulus, constant `k`), helium in the gap between them, a power ramp, the
//! cladding's outer temperature fixed (docs/models.md, sections 3 and 3a). By default it is
//! thermomechanical ([`run_coupled`]): both bodies expand (thermoelasticity, free to expand
//! axially: generalized plane strain), the gap narrows until contact engages (below the onset
//! gap `xi` of the pressure law), the gap conductance follows the mechanical gap and the
//! contact pressure,
//! the interface pressure follows the exponential pressure law (or exact contact), the plenum
//! pressure follows the gap's volume and temperature (ideal gas), the coolant presses on the
//! cladding. With `[model] mechanics = false` it is thermal only, the gap held at its
//! as-built width ([`run_thermal`], checked against the closed form [`closed_form`]).
//!
//! The 2D cross-section is meshed by the toolkit: an O-grid disc for the pellet and a polar
//! annulus for the cladding, at different resolutions, so that the interface does not match;
//! dual mortar coupling projected across the gap, the pellet's surface the slave side. Each
//! backward Euler step (and the final steady state) is one Newton solve of the whole problem,
//! on the assembled Jacobian or Jacobian-free (JFNK), as `[solver] method` says; a step that
//! fails is halved up to [`MAX_STEP_CUTS`] times.
//!
//! The scene file (TOML; every key optional, defaults from docs/models.md, sections 3 and 3a,
//! except the cladding's inner radius, see [`CladdingData`]):
//!
//! ```toml
//! kind = "pellet"
//! [pellet]
//! radius = 4.1e-3            # m
//! conductivity_a = 0.0375    # k = 1 / (a + b T): m K / W
//! conductivity_b = 2.165e-4  # m / W
//! heat_capacity = 3.3e6      # rho c_p, J/m^3/K
//! youngs_modulus = 200e9     # Pa
//! poisson_ratio = 0.3
//! thermal_expansion = 1.0e-5 # 1/K
//! [cladding]
//! inner_radius = 4.12e-3     # a 20 um gap (at 4.18 mm contact never engages at 20 kW/m)
//! outer_radius = 4.75e-3
//! conductivity = 16.0
//! outer_temperature = 580.0  # K, also the initial temperature everywhere
//! heat_capacity = 2.0e6
//! youngs_modulus = 80e9
//! poisson_ratio = 0.4
//! thermal_expansion = 6.0e-6
//! coolant_pressure = 15.5e6  # Pa, on the outer surface
//! [gap]
//! roughness_pellet = 2e-6
//! roughness_cladding = 1e-6
//! jump_distance = 10e-6      # g_f + g_c
//! # gas_conductivity = 0.3   # W/m/K; when absent, helium: 2.531e-3 T^0.7146
//! contact_conductance = 0.0  # h_contact, W/m^2/K per Pa of contact pressure
//! [contact]
//! law = "exponential"        # P_c = P_o exp(S_NE (xi - g)^2) below xi; or "exact"
//! stiffness_exponent = 1e12  # S_NE, 1/m^2
//! onset_gap = 5e-6           # xi, m
//! [plenum]
//! fill_pressure = 2e6        # Pa, helium at the fill
//! fill_temperature = 293.0   # K
//! volume = 2e-6              # m^3 per metre of rod
//! [model]
//! mechanics = true           # false: heat only, the gap held open
//! geometry = "plane"         # or "axisymmetric" (r-z) or "3d": a segment, its bottom held in z
//! axial = "generalized"      # free axial expansion; or "plane_strain" (no axial strain)
//! reference_temperature = 293.0
//! segment_height = 1e-3      # m, the r-z and 3D segment (its plenum share: volume x height)
//! relocation = "none"        # or "frapcon": the cracked pellet's outward relocation (FRAPCON's model)
//! burnup = 0.0               # MWd/kgU, held: what the relocation model sees
//! [power]
//! linear_power = 20e3        # W/m
//! ramp_time = 10.0           # s, from zero
//! [time]
//! step = 1.0                 # s, backward Euler
//! end = 30.0                 # s; then a steady solve at full power
//! snapshots = 4              # VTU files over the transient
//! [solver]
//! method = "auto"            # or "newton", "jfnk"; auto picks and says which and why
//! relative_tolerance = 1e-10
//! [mesh]
//! refinement = 3
//! axial_layers = 2           # cells along z of the r-z (pellet; cladding one more) and 3D models
//! ```
//!
//! Outputs: `report.json` (what was modelled, the warnings of the model
//! ranges it left (see [`limits`]), the time contact engages, the histories, the steady
//! state and its energy balance, the solver's counts), `pellet_NNNN.vtu` (temperature,
//! displacement, von Mises stress) and `interface_NNNN.vtu` (gap, heat flux, pressures) with
//! their `.pvd` collections, and `temperatures.png`, `gap.png`, `pressures.png`.
//!
//! ```no_run
//! let report = mortar_scenes::pellet::run_builtin(std::path::Path::new("out"), false)?;
//! println!("{} {}", report["center_temperature"], report["gap_closure_time"]);
//! # Ok::<(), mortar_scenes::pellet::PelletError>(())
//! ```

mod check;
mod closed_form;
mod coupled;
pub mod file_mesh;
pub mod limits;
mod march;
mod mesh;
mod outputs;
mod problem;
mod run;
mod stress;
mod thermal;

pub use closed_form::{closed_form, ClosedForm};
pub use coupled::{run_coupled, run_coupled_in, run_coupled_with, run_with_registry};
pub use march::MAX_STEP_CUTS;
pub use mesh::{annulus_mesh, pellet_mesh};
pub use outputs::is_output;
pub use problem::{coupled_problem, coupled_problem_with, exponential_contact_law, thermal_law};
pub use run::{run, run_builtin, run_from_toml, run_from_toml_with, run_with_laws};
pub use thermal::run_thermal;

use mortar_fem::mesh::VolumeMeshError;
use mortar_physics::laws::{GapConductance, GasConductivity, LawError};
use mortar_physics::PhysicsError;
use serde::{Deserialize, Serialize};

use crate::linear_solver::{AutoSwitch, BackendChoice, PickedSolver};

/// Errors of the pellet scene.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PelletError {
    /// The scene file is not valid TOML or has unknown keys or wrong types.
    #[error("pellet scene file: {0}")]
    Parse(String),
    /// A value is out of range.
    #[error("pellet scene: {0}")]
    Invalid(String),
    /// A mesh could not be built.
    #[error(transparent)]
    Mesh(#[from] VolumeMeshError),
    /// The gap law refused its parameters.
    #[error(transparent)]
    Law(#[from] LawError),
    /// The physics failed (a Newton solve that did not converge, say).
    #[error(transparent)]
    Physics(#[from] PhysicsError),
    /// A solve of the coupled scene failed: which one and when, why (`source`, Newton's
    /// reason and residual history for a Newton failure), and the block of equations holding
    /// the largest residual at its last iterate.
    #[error("{solve} failed at t = {time} s: {source}; {}", residual_text(.block, .blocks))]
    SolveFailed {
        /// The solve: `"the initial state"`, `"time step K of N ..."` or `"the steady state"`.
        solve: String,
        /// The time step (0 for the initial state, `None` for the steady state).
        step: Option<usize>,
        /// The time the solve was to reach (s).
        time: f64,
        /// The block of equations (`"heat"`, `"mechanics"`, `"flux"`, `"contact"`,
        /// `"plenum"`) with the largest residual norm at the last iterate; `None` when the
        /// residual could not be evaluated there.
        block: Option<&'static str>,
        /// Each block's residual norm at the last iterate, in Newton's units.
        blocks: Vec<(&'static str, f64)>,
        /// Why the solve failed.
        #[source]
        source: Box<PhysicsError>,
    },
    /// The coupling could not be built.
    #[error(transparent)]
    Mortar(#[from] mortar_core::MortarError),
    /// An output could not be written.
    #[error(transparent)]
    Io(#[from] mortar::io::IoError),
    /// The run was interrupted (Ctrl-C, [`crate::interrupt`]) before the step at `time`; the
    /// coupled scene has written what it had, with `"status": "interrupted"`.
    #[error("interrupted at t = {time} s after {steps} time steps")]
    Interrupted {
        /// The time reached (s).
        time: f64,
        /// The steps completed.
        steps: usize,
    },
    /// An output file or directory could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The path.
        path: std::path::PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// Where a failed solve's residual was left, for [`PelletError::SolveFailed`].
fn residual_text(block: &Option<&'static str>, blocks: &[(&'static str, f64)]) -> String {
    let total = blocks.iter().map(|b| b.1 * b.1).sum::<f64>().sqrt();
    match block {
        Some(name) => {
            let largest = blocks
                .iter()
                .find(|b| b.0 == *name)
                .map_or(f64::NAN, |b| b.1);
            let others: Vec<String> = blocks
                .iter()
                .filter(|b| b.0 != *name)
                .map(|(n, v)| format!("{n} {v:.3e}"))
                .collect();
            format!(
                "at the last iterate the largest residual is in the {name} equations \
                 (norm {largest:.3e} of {total:.3e}; {})",
                others.join(", ")
            )
        }
        None => "the residual could not be evaluated at the last iterate".to_string(),
    }
}

/// The pellet: `[pellet]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct PelletData {
    /// Radius `a` (m).
    pub radius: f64,
    /// `A` of `k = 1 / (A + B T)` (m K/W).
    pub conductivity_a: f64,
    /// `B` of `k = 1 / (A + B T)` (m/W).
    pub conductivity_b: f64,
    /// `rho c_p` (J/m^3/K).
    pub heat_capacity: f64,
    /// Young's modulus `E` (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio `nu`, in (-1, 0.5).
    pub poisson_ratio: f64,
    /// The linear thermal expansion coefficient `alpha` (1/K).
    pub thermal_expansion: f64,
}

impl Default for PelletData {
    fn default() -> Self {
        Self {
            radius: 4.1e-3,
            conductivity_a: 0.0375,
            conductivity_b: 2.165e-4,
            heat_capacity: 3.3e6,
            youngs_modulus: 200e9,
            poisson_ratio: 0.3,
            thermal_expansion: 1.0e-5,
        }
    }
}

/// The cladding: `[cladding]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct CladdingData {
    /// Inner radius `b` (m).
    pub inner_radius: f64,
    /// Outer radius `c` (m).
    pub outer_radius: f64,
    /// Conductivity (W/m/K).
    pub conductivity: f64,
    /// The fixed outer temperature `T_co` (K), also the initial temperature everywhere.
    pub outer_temperature: f64,
    /// `rho c_p` (J/m^3/K).
    pub heat_capacity: f64,
    /// Young's modulus `E` (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio `nu`, in (-1, 0.5).
    pub poisson_ratio: f64,
    /// The linear thermal expansion coefficient `alpha` (1/K).
    pub thermal_expansion: f64,
    /// The coolant pressure on the outer surface (Pa).
    pub coolant_pressure: f64,
}

impl Default for CladdingData {
    /// docs/models.md, section 3a, but the inner radius: 4.12 mm (a 20 um as-built
    /// gap, 40 um diametral) rather than 4.18 mm, so that contact engages during the ramp
    /// at 20 kW/m (with 4.18 mm it does not below about 72 kW/m, the independent radial model
    /// of tests/pellet/radial.rs finds).
    fn default() -> Self {
        Self {
            inner_radius: 4.12e-3,
            outer_radius: 4.75e-3,
            conductivity: 16.0,
            outer_temperature: 580.0,
            heat_capacity: 2.0e6,
            youngs_modulus: 80e9,
            poisson_ratio: 0.4,
            thermal_expansion: 6.0e-6,
            coolant_pressure: 15.5e6,
        }
    }
}

/// The gap: `[gap]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct GapData {
    /// Pellet (fuel) surface roughness `R_f` (m).
    pub roughness_pellet: f64,
    /// Cladding surface roughness `R_c` (m).
    pub roughness_cladding: f64,
    /// Temperature jump distances `g_f + g_c` (m).
    pub jump_distance: f64,
    /// A constant gas conductivity (W/m/K); `None`: helium, `2.531e-3 T^0.7146`.
    pub gas_conductivity: Option<f64>,
    /// `h_contact` (W/m^2/K/Pa): the conductance gained per pascal of contact pressure once
    /// contact engages (a positive contact pressure).
    pub contact_conductance: f64,
}

impl Default for GapData {
    fn default() -> Self {
        Self {
            roughness_pellet: 2e-6,
            roughness_cladding: 1e-6,
            jump_distance: 10e-6,
            gas_conductivity: None,
            contact_conductance: 0.0,
        }
    }
}

/// The power history: `[power]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct PowerData {
    /// The linear power `q'` (W/m) reached at the end of the ramp.
    pub linear_power: f64,
    /// The duration of the linear ramp from zero (s); 0 for a step.
    pub ramp_time: f64,
}

impl PowerData {
    /// `q'(t) = q' min(t / ramp_time, 1)` (W/m; `q'` from the start for no ramp).
    pub fn at(&self, t: f64) -> f64 {
        if self.ramp_time > 0.0 {
            self.linear_power * (t / self.ramp_time).clamp(0.0, 1.0)
        } else {
            self.linear_power
        }
    }
}

impl Default for PowerData {
    fn default() -> Self {
        Self {
            linear_power: 20e3,
            ramp_time: 10.0,
        }
    }
}

/// Time stepping: `[time]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct TimeData {
    /// The backward Euler step (s).
    pub step: f64,
    /// The end of the transient (s); a steady solve at full power follows.
    pub end: f64,
    /// How many VTU snapshots of the transient to write (the steady state is always written).
    pub snapshots: usize,
}

impl TimeData {
    /// The number of backward Euler steps, `ceil(end / step)` (0 for `end = 0`).
    pub fn steps(&self) -> usize {
        if self.end > 0.0 {
            (self.end / self.step).ceil() as usize
        } else {
            0
        }
    }

    /// A snapshot every this many steps (`usize::MAX` for none; the last step always has one).
    pub fn snapshot_every(&self) -> usize {
        if self.snapshots == 0 {
            usize::MAX
        } else {
            self.steps().div_ceil(self.snapshots).max(1)
        }
    }
}

impl Default for TimeData {
    fn default() -> Self {
        Self {
            step: 1.0,
            end: 30.0,
            snapshots: 4,
        }
    }
}

/// The normal pressure law of the gap: `[contact] law`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum ContactLawName {
    /// The exponential pressure law `P_c = P_o exp(S_NE (xi - g)^2)` for `g < xi`, else `P_o`.
    #[default]
    Exponential,
    /// Kuhn-Tucker contact (`g >= 0`, `p >= 0`, `p g = 0`), the plenum pressure beside it.
    Exact,
}

/// The contact: `[contact]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct ContactData {
    /// The law.
    pub law: ContactLawName,
    /// `S_NE` (1/m^2) of the exponential law.
    pub stiffness_exponent: f64,
    /// `xi` (m) of the exponential law: the gap below which the pressure rises.
    pub onset_gap: f64,
}

impl Default for ContactData {
    /// `S_NE = 1e12 /m^2`, `xi = 5 um`: at the default scene's peak pressure (about 20 MPa,
    /// `P_c / P_o` about 4) the gap is still 3.8 um, far from interpenetration, and the law's
    /// stiffness is within a decade of the pellet's radial stiffness (tests/pellet/radial.rs).
    fn default() -> Self {
        Self {
            law: ContactLawName::Exponential,
            stiffness_exponent: 1e12,
            onset_gap: 5e-6,
        }
    }
}

/// The plenum: `[plenum]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct PlenumData {
    /// The helium fill pressure (Pa).
    pub fill_pressure: f64,
    /// The fill temperature (K).
    pub fill_temperature: f64,
    /// The plenum's volume (m^3 per metre of rod in 2D).
    pub volume: f64,
}

impl Default for PlenumData {
    fn default() -> Self {
        Self {
            fill_pressure: 2e6,
            fill_temperature: 293.0,
            volume: 2e-6,
        }
    }
}

/// The model's geometry: `[model] geometry`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Geometry {
    /// The 2D cross-section of a long rod; its axial direction as `[model] axial` says
    /// (generalized plane strain by default).
    #[default]
    Plane,
    /// The 2D cross-section in plane strain: `geometry = "plane"` with
    /// `axial = "plane_strain"`.
    PlaneStrain,
    /// An axisymmetric r-z model of a pellet segment: its bottom held in z (a plane of
    /// symmetry), its top as `[model] axial` says (free and kept plane by default).
    Axisymmetric,
    /// A 3D pellet segment, the cross-section swept along z: bottom and top as for
    /// [`Axisymmetric`](Self::Axisymmetric).
    #[serde(rename = "3d")]
    ThreeD,
}

impl Geometry {
    /// Whether this is the 2D cross-section ([`Plane`](Self::Plane) or
    /// [`PlaneStrain`](Self::PlaneStrain)).
    pub fn is_plane(self) -> bool {
        matches!(self, Self::Plane | Self::PlaneStrain)
    }
}

/// The axial direction of the rod: `[model] axial`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum AxialModel {
    /// Free axial expansion, as fuel-performance codes model a pellet stack: each body's
    /// axial strain is one unknown (generalized plane strain in 2D; in r-z and 3D the top
    /// end free and kept plane), balanced by its axial force: the plenum pressure on the
    /// pellet's ends (`int sigma_zz dA = -P_o A_pellet`) and on the cladding's closed ends
    /// with the coolant outside (`P_o A_inner - P_coolant A_outer`). Pellet and cladding are
    /// independent axially (no axial friction).
    #[default]
    Generalized,
    /// Plane strain: no axial strain in either body (the r-z and 3D segments held in z at
    /// both ends).
    PlaneStrain,
}

/// What is modelled: `[model]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct ModelData {
    /// Thermal expansion, contact and plenum pressure; `false`: heat only, the
    /// gap held at its as-built width.
    pub mechanics: bool,
    /// The geometry.
    pub geometry: Geometry,
    /// The axial direction; `None`: generalized, but plane strain for
    /// `geometry = "plane_strain"` ([`ModelData::axial`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub axial: Option<AxialModel>,
    /// The temperature of zero thermal strain (K).
    pub reference_temperature: f64,
    /// The height of the pellet segment of the r-z and 3D models (m).
    pub segment_height: f64,
    /// The pellet's relocation model, by name: `"none"` (the default), `"frapcon"`
    /// (FRAPCON's default model, [`FrapconRelocation`](mortar_physics::laws::FrapconRelocation))
    /// or one a program registered
    /// ([`LawRegistry::register_relocation`](mortar_physics::laws::LawRegistry::register_relocation)).
    /// Applied as an outward strain of the pellet across its axis at the largest linear
    /// power reached so far, the burnup below and the cold gap `b - a`.
    pub relocation: String,
    /// The rod's burnup (MWd/kgU), held over the run: what the relocation model sees (given
    /// with `relocation = "none"`, it is refused: it would change nothing).
    pub burnup: f64,
}

impl ModelData {
    /// The axial model in effect: the one given, else plane strain for
    /// `geometry = "plane_strain"` and generalized otherwise.
    pub fn axial(&self) -> AxialModel {
        match (self.axial, self.geometry) {
            (Some(a), _) => a,
            (None, Geometry::PlaneStrain) => AxialModel::PlaneStrain,
            (None, _) => AxialModel::Generalized,
        }
    }
}

impl Default for ModelData {
    fn default() -> Self {
        Self {
            mechanics: true,
            geometry: Geometry::Plane,
            axial: None,
            reference_temperature: 293.0,
            segment_height: 1e-3,
            relocation: "none".to_string(),
            burnup: 0.0,
        }
    }
}

/// The nonlinear solver: `"auto"` (the default: picked from measurements, see
/// [`SolverData::choose`]), `"newton"` (assembled Jacobian, sparse LU) or `"jfnk"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum SolverMethod {
    /// Picked by the scene ([`SolverData::choose`]), which says which and why.
    #[default]
    Auto,
    /// Newton on the assembled Jacobian.
    Newton,
    /// Jacobian-free Newton-Krylov, preconditioned by the assembled Picard matrix.
    Jfnk,
}

impl SolverMethod {
    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Newton => "newton",
            Self::Jfnk => "jfnk",
        }
    }
}

/// The PETSc options of the pellet's Newton Jacobians: GMRES (the backend's pick for a general
/// matrix) restarted every 100 iterations, with ILU(0). GAMG, the backend's default, stalls on
/// the coupled thermomechanical Jacobian with its dense axial rows (the built-in scene's first
/// solve: relative residual 8e-7 after 10,000 iterations) and hypre's BoomerAMG breaks down;
/// ILU(0) converges on the built-in scene (median 238 iterations a solve at 2,730 unknowns;
/// restarted every 30, the default, 1,072), but not on every pellet: a Jacobian with a
/// structurally zero diagonal (the r-z and stacked example scenes) stops its set-up, and the
/// off-centre 2D example's stalls near 3e-8. A preconditioner split by physics is what those
/// and larger pellets need.
pub const PELLET_PETSC_OPTIONS: &str = "-pc_type ilu -ksp_gmres_restart 100";

/// The size of a 2D cross-section (unknowns) above which `[solver] method = "auto"` takes
/// Newton rather than JFNK ([`SolverData::choose`]).
pub const AUTO_NEWTON_ABOVE_2D: usize = 8_000;

/// The method a run uses, and why ([`SolverData::choose`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SolverChoice {
    /// The method (Newton or JFNK).
    pub method: SolverMethod,
    /// Whether it was picked (`method = "auto"`) rather than given.
    pub picked: bool,
    /// Why.
    pub reason: String,
}

/// The solver: `[solver]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverData {
    /// The method.
    pub method: SolverMethod,
    /// Newton's relative residual tolerance (per solve).
    pub relative_tolerance: f64,
    /// The most Newton steps per solve.
    pub max_iterations: usize,
    /// GMRES restart length (JFNK).
    pub gmres_restart: usize,
    /// Where Newton's Jacobians go ([`crate::linear_solver`]): `"auto"` (the direct solve,
    /// the bordered sparse LU), `"direct"` or `"petsc"` (GMRES with
    /// [`PELLET_PETSC_OPTIONS`] on the whole Jacobian; Newton then, JFNK's block
    /// preconditioner being factorised directly).
    #[serde(skip_serializing_if = "BackendChoice::is_auto")]
    pub backend: BackendChoice,
    /// The Krylov solves' relative tolerance (PETSc).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub linear_tolerance: Option<f64>,
}

impl SolverData {
    /// The method of a run: the one given, or for `"auto"` the cheapest measured for the
    /// scene, from the benchmark of every geometry (`examples/bench_pellet.rs`,
    /// `docs/bench_pellet.json`; JFNK time over Newton's for the same states: 2D 0.68, 0.62,
    /// 1.07 at 386, 2,730 and 10,206 unknowns; r-z 0.29 to 0.39 at 126 to 798; 3D 0.20 and 0.16
    /// at 1,503 and 5,103). The thermomechanical scene (`thermomechanical`) takes JFNK, but
    /// Newton for a 2D cross-section above [`AUTO_NEWTON_ABOVE_2D`] unknowns, where the
    /// measured 2D ratio crosses 1 (interpolated in the logarithm of the size between 2,730
    /// and 10,206 unknowns). A picked JFNK whose solve fails hands it to Newton.
    /// The heat-only scene takes Newton (not part of the benchmark).
    pub fn choose(&self, thermomechanical: bool, plane: bool, unknowns: usize) -> SolverChoice {
        match self.method {
            SolverMethod::Auto if thermomechanical && plane && unknowns > AUTO_NEWTON_ABOVE_2D => {
                SolverChoice {
                    method: SolverMethod::Newton,
                    picked: true,
                    reason: format!(
                        "auto: Newton for a 2D cross-section of {unknowns} unknowns (above \
                         {AUTO_NEWTON_ABOVE_2D}, where JFNK was measured no faster: docs/pellet.md)"
                    ),
                }
            }
            SolverMethod::Auto if thermomechanical => SolverChoice {
                method: SolverMethod::Jfnk,
                picked: true,
                reason: format!(
                    "auto: JFNK for {unknowns} unknowns, measured faster than Newton at this \
                     geometry and size (docs/pellet.md); a failed JFNK solve is retried by Newton"
                ),
            },
            SolverMethod::Auto => SolverChoice {
                method: SolverMethod::Newton,
                picked: true,
                reason: "auto: Newton for the heat-only scene (one field; JFNK not measured \
                         faster there)"
                    .into(),
            },
            m => SolverChoice {
                method: m,
                picked: false,
                reason: format!("[solver] method = \"{}\"", m.name()),
            },
        }
    }

    /// The linear solver of Newton's Jacobians for `unknowns` unknowns
    /// ([`PickedSolver::pick`], `"auto"` the direct solve).
    ///
    /// # Errors
    /// [`PelletError::Invalid`] naming the key for PETSc asked for in a build without it or a
    /// tolerance out of range.
    pub fn linear_solver(&self, unknowns: usize) -> Result<PickedSolver, PelletError> {
        PickedSolver::pick(
            self.backend,
            self.linear_tolerance,
            PELLET_PETSC_OPTIONS,
            unknowns,
            AutoSwitch::of("pellet", 2),
        )
        .map_err(|(key, what)| {
            PelletError::Invalid(format!("{}: {what}", key.replacen("solve.", "solver.", 1)))
        })
    }

    /// The method of [`choose`](Self::choose) with the linear solver `linear`: PETSc runs
    /// Newton's Jacobians, so that a picked JFNK becomes Newton (saying why).
    pub fn choose_with(&self, choice: SolverChoice, linear: &PickedSolver) -> SolverChoice {
        if linear.name == "petsc" && choice.method == SolverMethod::Jfnk && choice.picked {
            return SolverChoice {
                method: SolverMethod::Newton,
                picked: true,
                reason: "backend = \"petsc\": Newton, its Jacobians solved by PETSc (JFNK's \
                         block preconditioner is factorised directly)"
                    .into(),
            };
        }
        choice
    }

    /// The GMRES settings of JFNK.
    pub fn jfnk_options(&self) -> mortar_physics::nonlinear::JfnkOptions {
        mortar_physics::nonlinear::JfnkOptions {
            restart: self.gmres_restart,
            ..Default::default()
        }
    }

    /// Newton's settings, with an absolute floor of `1e-12 q'` (the residual rows are heat
    /// flows in W/m, and forces scaled to them: far below any physical one, so that a step
    /// near the steady state does not chase round-off).
    pub fn newton_options(&self, linear_power: f64) -> mortar_physics::nonlinear::NewtonOptions {
        mortar_physics::nonlinear::NewtonOptions {
            relative_tolerance: self.relative_tolerance,
            absolute_tolerance: 1e-12 * linear_power.max(1.0),
            max_iterations: self.max_iterations,
            ..Default::default()
        }
    }
}

impl Default for SolverData {
    fn default() -> Self {
        Self {
            method: SolverMethod::Auto,
            relative_tolerance: 1e-10,
            max_iterations: 30,
            gmres_restart: 30,
            backend: BackendChoice::Auto,
            linear_tolerance: None,
        }
    }
}

/// The mesh: `[mesh]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct MeshData {
    /// A Gmsh 4.1 file of the 2D cross-section or of the r-z section (`geometry =
    /// "axisymmetric"`) in place of the generated one, its parts named by physical groups
    /// ([`file_mesh`]); relative paths are resolved against the scene file's folder. The
    /// radii and the segment's height are then the file's (the `[pellet]` and `[cladding]`
    /// radii and `[model] segment_height` are replaced by them, and the report gives them).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<std::path::PathBuf>,
    /// The refinement level `r >= 1`: the pellet O-grid has `4 r` core cells per side and
    /// `2 r` radial layers (`16 r` edges on its circle); the cladding `21 r + 1` cells around
    /// and `2 r` radially.
    pub refinement: usize,
    /// Hex8 layers along z of the 3D model.
    pub axial_layers: usize,
}

impl Default for MeshData {
    fn default() -> Self {
        Self {
            file: None,
            refinement: 3,
            axial_layers: 2,
        }
    }
}

/// The pellet scene (the TOML file's tables). Every field has the default of docs/models.md (section 3).
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct PelletScene {
    /// `kind = "pellet"` (or `scene = "pellet"`), optional: what `mortar run` dispatches on.
    #[serde(alias = "kind")]
    pub scene: Option<String>,
    /// `[pellet]`.
    pub pellet: PelletData,
    /// `[cladding]`.
    pub cladding: CladdingData,
    /// `[gap]`.
    pub gap: GapData,
    /// `[power]`.
    pub power: PowerData,
    /// `[time]`.
    pub time: TimeData,
    /// `[solver]`.
    pub solver: SolverData,
    /// `[mesh]`.
    pub mesh: MeshData,
    /// `[contact]`.
    pub contact: ContactData,
    /// `[plenum]`.
    pub plenum: PlenumData,
    /// `[model]`.
    pub model: ModelData,
    /// `[laws]`: interface laws by name, in place of the `[gap]` and `[contact]` ones.
    pub laws: LawsData,
}

/// A law named in a scene file (see [`NamedLaw`](crate::NamedLaw)).
pub type LawSpec = crate::NamedLaw;

/// `[laws]`: the coupled scene's interface laws by name (each optional; both built-in when
/// absent; refused with `[model] mechanics = false`). `[laws.thermal]` replaces the gap
/// conductance of `[gap]`, `[laws.contact]` the pressure law of `[contact]`:
///
/// ```toml
/// [laws.thermal]
/// name = "mechanical_gap_conductance"
/// roughness_fuel = 2e-6
/// roughness_cladding = 1e-6
/// jump_distance = 10e-6
/// contact_conductance = 1e-4
/// [laws.contact]
/// name = "exponential_contact"
/// stiffness = 1e12
/// onset = 5e-6
/// ```
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct LawsData {
    /// The thermal law (heat flux against temperature jump).
    pub thermal: Option<LawSpec>,
    /// The contact law (contact pressure against gap).
    pub contact: Option<LawSpec>,
}

impl PelletScene {
    /// Parses a scene file.
    ///
    /// # Errors
    /// [`PelletError::Parse`] for invalid TOML, an unknown key or a wrong type;
    /// [`PelletError::Invalid`] for values out of range (see [`check`](Self::check)).
    pub fn from_toml(text: &str) -> Result<Self, PelletError> {
        let scene: Self = crate::parse::parse_toml(text)
            .map_err(|f| PelletError::Parse(format!("line {}: {}", f.line, f.keyed_message())))?;
        scene.check()?;
        Ok(scene)
    }

    /// Parses a scene file whose relative `[mesh] file` is in the folder `base` (the scene
    /// file's).
    ///
    /// # Errors
    /// As [`from_toml`](Self::from_toml).
    pub fn from_toml_in(text: &str, base: &std::path::Path) -> Result<Self, PelletError> {
        let mut scene = Self::from_toml(text)?;
        if let Some(file) = &mut scene.mesh.file {
            if file.is_relative() {
                *file = base.join(&*file);
            }
        }
        Ok(scene)
    }

    /// The scene checked, with the radii and segment height of its mesh file when it has
    /// one (and the file's meshes).
    ///
    /// # Errors
    /// [`PelletError::Invalid`] for values out of range; the errors of
    /// [`FileGeometry::read`](file_mesh::FileGeometry::read).
    pub(crate) fn resolved(&self) -> Result<(Self, Option<file_mesh::FileGeometry>), PelletError> {
        self.check()?;
        let Some(path) = &self.mesh.file else {
            return Ok((self.clone(), None));
        };
        let file =
            file_mesh::FileGeometry::read(path, self.model.geometry == Geometry::Axisymmetric)?;
        let mut scene = self.clone();
        scene.pellet.radius = file.pellet_radius;
        scene.cladding.inner_radius = file.inner_radius;
        scene.cladding.outer_radius = file.outer_radius;
        if file.axisymmetric {
            scene.model.segment_height = file.height;
        }
        scene.check()?;
        // A stack's pellets are held axially by their lands' contact only: under the exact
        // law an open land carries nothing, and the pellets above it would slide freely.
        let exact = self
            .laws
            .contact
            .as_ref()
            .map_or(self.contact.law == ContactLawName::Exact, |l| {
                l.name == "contact_complementarity"
            });
        if file.lands.is_some() && exact {
            return Err(PelletError::Invalid(format!(
                "{}: a stack of pellets (groups \"{}\" and \"{}\") under the exact contact \
                 law: its pellets are held axially only where their lands touch, and as built \
                 they do not; use the exponential law ([contact] law = \"exponential\"), whose \
                 pressure acts below its onset gap",
                path.display(),
                file_mesh::PELLET_LANDS_LOWER,
                file_mesh::PELLET_LANDS_UPPER
            )));
        }
        Ok((scene, Some(file)))
    }

    /// The Ross-Stoute gap law of this scene (gap `d_g = b - a`).
    ///
    /// # Errors
    /// [`PelletError::Law`] for parameters out of range.
    pub fn gap_law(&self) -> Result<GapConductance, PelletError> {
        let gas = match self.gap.gas_conductivity {
            Some(k) => GasConductivity::Constant(k),
            None => GasConductivity::HELIUM,
        };
        Ok(GapConductance::ross_stoute(
            self.cladding.inner_radius - self.pellet.radius,
            self.gap.roughness_pellet,
            self.gap.roughness_cladding,
            self.gap.jump_distance,
            gas,
        )?)
    }

    /// The closed-form steady temperatures of this scene (docs/models.md, section 3).
    ///
    /// # Errors
    /// [`PelletError::Law`] for gap parameters out of range.
    pub fn closed_form(&self) -> Result<ClosedForm, PelletError> {
        let (p, c) = (&self.pellet, &self.cladding);
        Ok(closed_form(
            self.power.linear_power,
            p.radius,
            (p.conductivity_a, p.conductivity_b),
            c.inner_radius,
            c.outer_radius,
            c.conductivity,
            c.outer_temperature,
            &self.gap_law()?,
        ))
    }
}
