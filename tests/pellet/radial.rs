//! The independent reference of the coupled pellet: a fine
//! 1D radial model of the thermomechanical pellet in its cladding, written here from the
//! equations of docs/models.md (sections 3 and 3a) without calling the library's heat, elastic,
//! contact or law code, so that the 2D cross-section and the r-z model can be checked
//! against it (centre temperature, gap, contact pressure, plenum pressure through the
//! ramp). It reads only the thermal defaults of `PelletScene::from_toml("")` (numbers).
//!
//! # The model (axisymmetric, per unit length of rod; plane strain `eps_zz = 0`, or
//! generalized plane strain: a uniform `eps_zz` per body balancing its axial force)
//!
//! **Heat.** `rho c_p T_t = (1/r) (r k(T) T_r)_r + Q(t)` in the pellet `0 <= r <= a`
//! (`k = 1/(A + B T)`, `Q = q'(t) / (pi a^2)`, `q'(t) = q' min(t / t_ramp, 1)`), the same with
//! `k_c` and no source in the cladding `b <= r <= c`, `T(c) = T_co`, initially `T = T_co`.
//! Across the gap the heat per unit length `2 pi a q`, `q = U (T_ps - T_ci)` per unit area of
//! the pellet's (reference) surface, as docs/models.md section 3 (`T_ps = T_ci + q'/(2 pi a U)`),
//!
//! ```text
//! U = k_g(T_gap) / (max(g, 0) + 1.5 (R_f + R_c) + j) + h_contact p_contact,
//! T_gap = (T_ps + T_ci) / 2,     k_g = 2.531e-3 T^0.7146 (helium) or a constant.
//! ```
//!
//! Discretisation: vertex-centred finite volumes on uniform radial grids (pellet `0..a`,
//! cladding `b..c`), control volumes bounded by the mid-points, lumped capacity, backward
//! Euler with the source at the end of the step. Face fluxes are two-point fluxes that are
//! exact for the steady profiles: in the pellet the Kirchhoff potential
//! `phi(T) = int k dT = ln(A + B T) / B` across the face at the mid-point `r_f`,
//! `2 pi r_f (phi_i - phi_{i+1}) / h` (exact for the steady `phi = phi_s + Q (a^2 - r^2)/4`);
//! in the cladding `2 pi k_c (T_j - T_{j+1}) / ln(r_{j+1} / r_j)` (exact for `ln r`). So the
//! steady state is nodally exact on any grid and the transient is second order in `h`.
//!
//! **Mechanics** (quasi-static, small strain, plane strain). For `T(r)` given, the radial
//! displacement of each body is (Timoshenko and Goodier, *Theory of Elasticity*, 3rd ed.,
//! McGraw-Hill 1970, secs. 150-151, with `eps_zz = 0`):
//!
//! ```text
//! u(r) = beta I(r) / r + C1 r + C2 / r,   beta = alpha (1 + nu) / (1 - nu),
//! I(r) = int_{r_in}^r (T - T_ref) s ds,
//! sigma_r(r) = M1 C1 - M2 C2 / r^2 - M2 beta I(r) / r^2,
//! M1 = 2 (lambda + mu) = E / ((1 + nu)(1 - 2 nu)),  M2 = 2 mu = E / (1 + nu),
//! ```
//!
//! from equilibrium `sigma_r' + (sigma_r - sigma_theta)/r = 0` with
//! `sigma = lambda tr(eps - eps_th) + 2 mu (eps - eps_th)`. Pellet: `C2 = 0`, `sigma_r(a) = -P`,
//! so `u_p(a) = 2 (1 + nu) alpha I_p / a - P a (1 + nu)(1 - 2 nu) / E` (free expansion for
//! `P = 0`, docs/models.md section 3a). Cladding (thick-walled cylinder): `sigma_r(b) = -P`,
//! `sigma_r(c) = -p_cool` fix `C1`, `C2` (Lame's solution when `T = T_ref`).
//! `P = P_o + p_contact` is the normal pressure on both gap surfaces. The integrals of `T r` are
//! exact for the piecewise-linear interpolant of the nodal temperatures.
//!
//! **Free axial expansion** (generalized plane strain, the scene's default). With a uniform
//! `eps_zz = e` per body the same `u(r)` holds (the equilibrium does not see `e`) and
//! `sigma_r` gains `lambda e`: the plane-strain solution with the surface pressures shifted
//! by `lambda e`. Each body's `e` balances its axial force,
//! `int sigma_zz dA = 2 pi int (lambda (beta (T - T_ref) + 2 C1) + (lambda + 2 mu) e
//! - 3 K alpha (T - T_ref)) r dr`, against `-P_o pi a^2` (the plenum on the pellet's ends) and
//! `P_o pi b^2 - p_cool pi c^2` (the cladding's closed ends): linear in `e`, solved from two
//! evaluations (`pellet_axial_strain`, `cladding_axial_strain`).
//!
//! **Relocation** (FRAPCON's default model, FRAPCON-3.5 / FRAPCON-4.0: Geelhood et al.,
//! NUREG/CR-7022 Vol. 1; PNNL-19418 Vol. 1 Rev. 2). The cracked pellet's fragments move out by
//! a share `f(q', Bu)` of the cold gap `b - a`, an outward strain `eps_rl = f (b - a) / a`
//! across the axis; being uniform and free of stress, it only adds `eps_rl r` to the pellet's
//! displacement: `u_p(a) += f(q', Bu) (b - a)`, with `q'` the largest power reached (the ramp
//! never falls) and `f` written here again from the correlation (`relocation_share`).
//!
//! **Gap, contact, plenum.** `g = (b + u_c(b)) - (a + u_p(a))`. The pellet carries
//! `P = P_o + p` on its surface; the cladding `P_o + rho p`, with `rho` 1 (the pressure on
//! both surfaces) or `a / b` (the pellet's contact force spread over the cladding's surface,
//! the mortar coupling's transfer), `cladding_contact_share`. Contact laws (docs/models.md, section 3a):
//!
//! - `Exponential`: `P_c = P_o exp(S_NE (xi - g)^2)` for `g < xi`, else `P_o`; past the maximum
//!   pressure `P_max = max_pressure_ratio P_o` (reached at `g* = xi - sqrt(ln(ratio)/S_NE)`) the
//!   exponential is continued by its tangent, so it never overflows. `p_contact = P_c - P_o`.
//! - `Exact`: `g >= 0`, `p_contact >= 0`, `p_contact g = 0` (semi-smooth Newton on
//!   `p - max(0, p - c_n g)`), `P_o` acting on both surfaces beside it.
//!
//! Plenum: `n = P_fill (V_plenum + V_gap0) / (R T_fill)` with `V_gap0 = pi (b^2 - a^2)` (the
//! cold, unloaded gap at the fill), `P_o = n R T_gap / (V_plenum + V_gap)`,
//! `V_gap = pi ((b + u_c)^2 - (a + u_p)^2)`.
//!
//! **Solve.** Each step solves the whole coupled system (nodal temperatures, `g`, `P_o`,
//! `p_contact`) by Newton with the analytic Jacobian (tested against finite differences): the
//! heat block is tridiagonal (the gap flux couples the two adjacent surface nodes), the three
//! gap unknowns border it, and the bordered system is solved by its Schur complement. A step
//! that fails (no convergence in 40 iterations, or a non-finite residual) is cut in halves.
//!
//! **Closure.** The surfaces *touch* when `g <= xi` for the exponential law (where the
//! pressure starts to rise above `P_o`) and when the contact is active (`p_contact > 0` or
//! `g <= 0`) for the exact law. The closure time reported is the end of the first step at
//! which they touch, and its linear interpolation in `g` within that step.
//!
//! The verification tests are at the end of the file, each with its source.

use std::f64::consts::PI;

use mortar_scenes::pellet::{AxialModel, ContactLawName, PelletScene};
use nalgebra::{Matrix3, Vector3};

/// The molar gas constant `R` (J/mol/K, exact since the 2019 SI).
pub const GAS_CONSTANT: f64 = 8.314_462_618;

/// The complementarity constant `c_n` of the exact law, in MPa per micrometre (the unknowns'
/// scaled units): of the order of the pellet's radial stiffness
/// `E / (a (1 + nu)(1 - 2 nu))` = 94 MPa/um at the defaults. Any positive value gives the
/// same solution.
const COMPLEMENTARITY: f64 = 100.0;

/// The gas conductivity of the gap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GasConductivity {
    /// Helium: `k_g(T) = 2.531e-3 T^0.7146` W/m/K (T in K).
    Helium,
    /// A constant (W/m/K).
    Constant(f64),
}

/// The normal pressure law of the gap.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactLaw {
    /// The regularised `P_c = P_o exp(S_NE (xi - g)^2)` for `g < xi`, else `P_o`.
    Exponential,
    /// Kuhn-Tucker `g >= 0`, `p >= 0`, `p g = 0`, with `P_o` acting beside it.
    Exact,
}

/// Isotropic thermoelastic constants of one body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thermoelastic {
    /// Young's modulus `E` (Pa).
    pub young: f64,
    /// Poisson's ratio `nu`.
    pub poisson: f64,
    /// Linear expansion coefficient `alpha` (1/K).
    pub expansion: f64,
}

impl Thermoelastic {
    /// `M1 = 2 (lambda + mu) = E / ((1 + nu)(1 - 2 nu))`.
    fn m1(&self) -> f64 {
        self.young / ((1.0 + self.poisson) * (1.0 - 2.0 * self.poisson))
    }

    /// `M2 = 2 mu = E / (1 + nu)`.
    fn m2(&self) -> f64 {
        self.young / (1.0 + self.poisson)
    }

    /// `lambda = E nu / ((1 + nu)(1 - 2 nu))`.
    fn lambda(&self) -> f64 {
        self.young * self.poisson / ((1.0 + self.poisson) * (1.0 - 2.0 * self.poisson))
    }

    /// `lambda + 2 mu = M1 - lambda = E (1 - nu) / ((1 + nu)(1 - 2 nu))`.
    fn p_wave(&self) -> f64 {
        self.m1() - self.lambda()
    }

    /// `beta = alpha (1 + nu) / (1 - nu)`, the plane-strain thermal factor.
    fn beta(&self) -> f64 {
        self.expansion * (1.0 + self.poisson) / (1.0 - self.poisson)
    }
}

/// Every input of the 1D radial pellet (docs/models.md, sections 3 and 3a), SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadialPellet {
    /// Pellet radius `a` (m).
    pub pellet_radius: f64,
    /// Cladding inner radius `b` (m).
    pub cladding_inner_radius: f64,
    /// Cladding outer radius `c` (m).
    pub cladding_outer_radius: f64,
    /// Linear power `q'` at the end of the ramp (W/m).
    pub linear_power: f64,
    /// Duration of the linear ramp from 0 (s); 0 for a step.
    pub ramp_time: f64,
    /// Backward Euler step (s).
    pub time_step: f64,
    /// End of the transient (s).
    pub end_time: f64,
    /// `A` of the pellet's `k = 1 / (A + B T)` (m K/W).
    pub conductivity_a: f64,
    /// `B` of the pellet's `k = 1 / (A + B T)` (m/W).
    pub conductivity_b: f64,
    /// Cladding conductivity `k_c` (W/m/K).
    pub cladding_conductivity: f64,
    /// Pellet `rho c_p` (J/m^3/K).
    pub pellet_heat_capacity: f64,
    /// Cladding `rho c_p` (J/m^3/K).
    pub cladding_heat_capacity: f64,
    /// Cladding outer temperature `T_co`, also the initial temperature (K).
    pub outer_temperature: f64,
    /// Pellet roughness `R_f` (m).
    pub roughness_pellet: f64,
    /// Cladding roughness `R_c` (m).
    pub roughness_cladding: f64,
    /// Temperature jump distances `g_f + g_c` (m).
    pub jump_distance: f64,
    /// Gas conductivity.
    pub gas: GasConductivity,
    /// `h_contact` of `U = ... + h_contact p_contact` (W/m^2/K/Pa).
    pub contact_conductance: f64,
    /// Pellet `E`, `nu`, `alpha`.
    pub pellet_elastic: Thermoelastic,
    /// Cladding `E`, `nu`, `alpha`.
    pub cladding_elastic: Thermoelastic,
    /// Stress-free temperature `T_ref` (K).
    pub reference_temperature: f64,
    /// Coolant pressure on the cladding's outside (Pa).
    pub coolant_pressure: f64,
    /// Plenum volume per unit length of rod (m^3/m).
    pub plenum_volume: f64,
    /// Helium fill pressure (Pa).
    pub fill_pressure: f64,
    /// Fill temperature (K).
    pub fill_temperature: f64,
    /// `xi`, the gap at which the surfaces start to feel each other (m).
    pub onset_gap: f64,
    /// `S_NE`, the stiffness exponent of the exponential law (1/m^2).
    pub stiffness: f64,
    /// `P_max / P_o`, past which the exponential law continues linearly.
    pub max_pressure_ratio: f64,
    /// The pressure law.
    pub law: ContactLaw,
    /// `false`: rigid bodies (`u = 0`, the gap held at `b - a`), heat only.
    pub mechanics: bool,
    /// Free axial expansion (generalized plane strain: each body's uniform axial strain
    /// balances its axial force); `false`: plane strain.
    pub generalized: bool,
    /// The burnup (MWd/kgU) of FRAPCON's relocation model, or `None` for no relocation.
    pub relocation_burnup: Option<f64>,
    /// The share of the contact pressure `p` the cladding's inner surface carries: 1 (the
    /// default: `P_o + p` on both surfaces), or `a / b`, the pellet's contact force
    /// `2 pi a p` spread over the cladding's `2 pi b`, as the mortar coupling transfers it
    /// (both small-deformation readings; they differ by the as-built gap over the radius,
    /// 0.5 % at 20 um, 1.9 % at 80 um).
    pub cladding_contact_share: f64,
    /// Radial cells in the pellet.
    pub pellet_cells: usize,
    /// Radial cells in the cladding.
    pub cladding_cells: usize,
}

impl Default for RadialPellet {
    /// The thermal data of `PelletScene::from_toml("")` (docs/models.md, section 3), the mechanical
    /// and gap data of sections 4 and 6, and:
    ///
    /// - `S_NE = 1e12 /m^2` (the exponent is `((xi - g) / 1 um)^2`): in the closing scene the
    ///   peak interface pressure (about 220 MPa at 30 s, `P_c/P_o` about 20) is reached at
    ///   `xi - g` of 1.7 um, i.e. `g` = 3.3 um: the surfaces never interpenetrate (that would
    ///   need `P_c/P_o = e^25`), far inside the requirement of a penetration below a micrometre
    ///   (which needs only `S_NE > ln(P_c/P_o) / (xi + 1 um)^2`, about 1e11 here), while the
    ///   law's stiffness there, `2 S_NE (xi - g) P_c` (8e14 Pa/m), is within a decade of the
    ///   pellet's radial stiffness `E / (a (1 + nu)(1 - 2 nu))` (9.4e13 Pa/m), which Newton
    ///   handles without a step cut;
    /// - `xi = 5 um`, the maximum pressure `1e6 P_o` (the library's ratio);
    /// - `h_contact = 1e-4 W/m^2/K/Pa` (1 kW/m^2/K at 10 MPa): the specification gives no value;
    /// - 400 pellet and 60 cladding cells (about 10 um each).
    fn default() -> Self {
        let mut scene = PelletScene::from_toml("").expect("the default pellet scene");
        // The specification's as-built gap, 80 um (the scene's default is 20 um, so that its gap
        // closes at 20 kW/m: what this model's tests found).
        scene.cladding.inner_radius = 4.18e-3;
        Self {
            contact_conductance: 1e-4,
            ..Self::from_scene(&scene)
        }
    }
}

impl RadialPellet {
    /// The model with the data of a 2D pellet scene (radii, conductivities, capacities, outer
    /// temperature, gap roughness, jump distance and contact conductance, gas, power, ramp,
    /// time step and end, elastic constants, coolant and plenum, contact law), the exponential
    /// law's cap of the library (`1e6 P_o`) and 400 pellet and 60 cladding cells.
    pub fn from_scene(scene: &PelletScene) -> Self {
        Self {
            pellet_radius: scene.pellet.radius,
            cladding_inner_radius: scene.cladding.inner_radius,
            cladding_outer_radius: scene.cladding.outer_radius,
            linear_power: scene.power.linear_power,
            ramp_time: scene.power.ramp_time,
            time_step: scene.time.step,
            end_time: scene.time.end,
            conductivity_a: scene.pellet.conductivity_a,
            conductivity_b: scene.pellet.conductivity_b,
            cladding_conductivity: scene.cladding.conductivity,
            pellet_heat_capacity: scene.pellet.heat_capacity,
            cladding_heat_capacity: scene.cladding.heat_capacity,
            outer_temperature: scene.cladding.outer_temperature,
            roughness_pellet: scene.gap.roughness_pellet,
            roughness_cladding: scene.gap.roughness_cladding,
            jump_distance: scene.gap.jump_distance,
            gas: match scene.gap.gas_conductivity {
                Some(k) => GasConductivity::Constant(k),
                None => GasConductivity::Helium,
            },
            contact_conductance: scene.gap.contact_conductance,
            pellet_elastic: Thermoelastic {
                young: scene.pellet.youngs_modulus,
                poisson: scene.pellet.poisson_ratio,
                expansion: scene.pellet.thermal_expansion,
            },
            cladding_elastic: Thermoelastic {
                young: scene.cladding.youngs_modulus,
                poisson: scene.cladding.poisson_ratio,
                expansion: scene.cladding.thermal_expansion,
            },
            reference_temperature: scene.model.reference_temperature,
            coolant_pressure: scene.cladding.coolant_pressure,
            plenum_volume: scene.plenum.volume,
            fill_pressure: scene.plenum.fill_pressure,
            fill_temperature: scene.plenum.fill_temperature,
            onset_gap: scene.contact.onset_gap,
            stiffness: scene.contact.stiffness_exponent,
            max_pressure_ratio: 1e6,
            law: match scene.contact.law {
                ContactLawName::Exponential => ContactLaw::Exponential,
                ContactLawName::Exact => ContactLaw::Exact,
            },
            mechanics: scene.model.mechanics,
            generalized: scene.model.axial() == AxialModel::Generalized,
            cladding_contact_share: 1.0,
            relocation_burnup: match scene.model.relocation.as_str() {
                "none" => None,
                "frapcon" => Some(scene.model.burnup),
                other => panic!("the radial model has no relocation model {other:?}"),
            },
            pellet_cells: 400,
            cladding_cells: 60,
        }
    }

    /// The default data with the linear power raised to 160 kW/m (the 10 s ramp kept). With
    /// free axial expansion (the default) the 80 um gap does not close at the default
    /// 20 kW/m, nor at any power below 85.4 kW/m however slow the ramp (the steady state
    /// touches, `g = xi`, from there), and within the 10 s ramp (time step 1 s) only from
    /// 138.1 kW/m with the exponential law and 150.4 kW/m with the exact law (`g = 0`)
    /// (`smallest_power_closing_the_gap`; in plane strain 72.2, 109.8 and 120.2 kW/m);
    /// 160 kW/m closes within the ramp under both. The
    /// temperatures are then far above UO2's melting point (about 3120 K): a numerical
    /// benchmark, not a fuel rod (no relocation, swelling or melting modelled).
    pub fn closing() -> Self {
        Self {
            linear_power: 160e3,
            ..Self::default()
        }
    }

    /// `q'(t) = q' min(t / t_ramp, 1)` (W/m).
    pub fn linear_power_at(&self, t: f64) -> f64 {
        if self.ramp_time > 0.0 {
            self.linear_power * (t / self.ramp_time).clamp(0.0, 1.0)
        } else if t > 0.0 {
            self.linear_power
        } else {
            0.0
        }
    }

    /// `k(T) = 1 / (A + B T)` of the pellet.
    fn pellet_conductivity(&self, t: f64) -> f64 {
        1.0 / (self.conductivity_a + self.conductivity_b * t)
    }

    /// The Kirchhoff potential `phi(T) = int k dT = ln(A + B T) / B` (`T / A` for `B = 0`).
    fn kirchhoff(&self, t: f64) -> f64 {
        let (a, b) = (self.conductivity_a, self.conductivity_b);
        if b > 0.0 {
            (a + b * t).ln() / b
        } else {
            t / a
        }
    }

    /// `k_g(T)` and `dk_g/dT`.
    pub fn gas_conductivity(&self, t: f64) -> (f64, f64) {
        match self.gas {
            GasConductivity::Helium => {
                let t = t.max(1.0);
                let k = 2.531e-3 * t.powf(0.7146);
                (k, 0.7146 * k / t)
            }
            GasConductivity::Constant(k) => (k, 0.0),
        }
    }

    /// The fixed distance added to the open gap: `1.5 (R_f + R_c) + j` (m).
    fn added_distance(&self) -> f64 {
        1.5 * (self.roughness_pellet + self.roughness_cladding) + self.jump_distance
    }

    /// The gap conductance `U` (W/m^2/K) at gap `g` (m), contact pressure `p` (Pa) and gas
    /// temperature `T_gap` (K), with `dU/dg`, `dU/dp`, `dU/dT_gap`.
    pub fn gap_conductance(&self, g: f64, p: f64, t_gap: f64) -> [f64; 4] {
        let (kg, dkg) = self.gas_conductivity(t_gap);
        let d = g.max(0.0) + self.added_distance();
        let dd = if g > 0.0 { 1.0 } else { 0.0 };
        [
            kg / d + self.contact_conductance * p,
            -kg / (d * d) * dd,
            self.contact_conductance,
            dkg / d,
        ]
    }

    /// The exponential law's `P_c(g; P_o)` (Pa) with `dP_c/dg` and `dP_c/dP_o`.
    pub fn exponential_pressure(&self, g: f64, p_o: f64) -> [f64; 3] {
        let x = self.onset_gap - g;
        if x <= 0.0 || self.stiffness == 0.0 {
            return [p_o, 0.0, 1.0];
        }
        let s = self.stiffness;
        let e_max = self.max_pressure_ratio.ln();
        let x_max = (e_max / s).sqrt();
        if x <= x_max {
            let f = (s * x * x).exp();
            [p_o * f, -2.0 * s * x * p_o * f, f]
        } else {
            let slope = 2.0 * s * x_max;
            let f = self.max_pressure_ratio * (1.0 + slope * (x - x_max));
            [p_o * f, -p_o * self.max_pressure_ratio * slope, f]
        }
    }

    /// The moles of gas per unit length, `n = P_fill (V_plenum + V_gap0) / (R T_fill)`.
    pub fn gas_moles(&self) -> f64 {
        let (a, b) = (self.pellet_radius, self.cladding_inner_radius);
        self.fill_pressure * (self.plenum_volume + PI * (b * b - a * a))
            / (GAS_CONSTANT * self.fill_temperature)
    }

    /// The pellet's surface displacement `u_p(a)` (m) for `I_p = int_0^a (T - T_ref) r dr`
    /// (K m^2) and the pressure `P` (Pa) on its surface:
    /// `2 (1 + nu) alpha I_p / a - P a (1 + nu)(1 - 2 nu) / E`.
    pub fn pellet_surface_displacement(&self, i_p: f64, pressure: f64) -> f64 {
        let m = &self.pellet_elastic;
        let a = self.pellet_radius;
        2.0 * (1.0 + m.poisson) * m.expansion * i_p / a - pressure * a / m.m1()
    }

    /// The pellet's uniform axial strain for `I_p`, the pressure `P` on its surface and the
    /// plenum pressure `P_o` on its ends (zero in plane strain). With `eps_zz = e` the plane
    /// solution holds with `sigma_r` shifted by `lambda e` (`C1 = (-P - lambda e + M2 beta
    /// I_p / a^2) / M1`), and `sigma_zz = lambda (beta (T - T_ref) + 2 C1) + (lambda + 2 mu) e
    /// - 3 K alpha (T - T_ref)`, whose integral over the section,
    /// `-2 pi M2 beta I_p + 2 pi lambda C1 a^2 + pi a^2 (lambda + 2 mu) e`, must be
    /// `-P_o pi a^2`. Linear in `e`: solved from two evaluations.
    pub fn pellet_axial_strain(&self, i_p: f64, pressure: f64, plenum: f64) -> f64 {
        if !self.generalized {
            return 0.0;
        }
        let m = &self.pellet_elastic;
        let a = self.pellet_radius;
        let (lambda, beta) = (m.lambda(), m.beta());
        let force = |e: f64| {
            let c1 = (-pressure - lambda * e + m.m2() * beta * i_p / (a * a)) / m.m1();
            -2.0 * PI * m.m2() * beta * i_p
                + 2.0 * PI * lambda * c1 * a * a
                + PI * a * a * m.p_wave() * e
        };
        let f0 = force(0.0);
        (-plenum * PI * a * a - f0) / (force(1.0) - f0)
    }

    /// FRAPCON-3.5's relocation as a share of the cold gap at the linear power `q` (W/m) and
    /// the burnup `bu` (MWd/kgU): `0.055 + min(R, R (0.5795 + 0.2447 ln Bu))` above
    /// 0.0937 MWd/kgU (0.055 below), `R` = 0.345 up to 20 kW/m, rising by 0.005 per kW/m to
    /// 0.445 at 40 kW/m.
    pub fn relocation_share(q: f64, bu: f64) -> f64 {
        let kw = q * 1e-3;
        let r = 0.345 + 0.005 * (kw.clamp(20.0, 40.0) - 20.0);
        if bu > 0.0937 {
            0.055 + r * (0.5795 + 0.2447 * bu.ln()).min(1.0)
        } else {
            0.055
        }
    }

    /// The pellet surface's outward displacement by relocation at the linear power `q` (W/m):
    /// `f(q, Bu) (b - a)`, zero without relocation.
    pub fn relocation_displacement(&self, q: f64) -> f64 {
        self.relocation_burnup.map_or(0.0, |bu| {
            Self::relocation_share(q, bu) * (self.cladding_inner_radius - self.pellet_radius)
        })
    }

    /// The pellet's surface displacement `u_p(a)` (m) with the axial model: in plane strain
    /// [`pellet_surface_displacement`](Self::pellet_surface_displacement); in generalized
    /// plane strain the same with the pressure `P + lambda e`
    /// ([`pellet_axial_strain`](Self::pellet_axial_strain)).
    pub fn pellet_displacement(&self, i_p: f64, pressure: f64, plenum: f64) -> f64 {
        let e = self.pellet_axial_strain(i_p, pressure, plenum);
        self.pellet_surface_displacement(i_p, pressure + self.pellet_elastic.lambda() * e)
    }

    /// The cladding's uniform axial strain for the inner pressure `p_in`, the coolant's
    /// `p_out`, the plenum pressure `P_o` on its closed ends and `I_c` (zero in plane
    /// strain): `int sigma_zz dA = -2 pi M2 beta I_c + 2 pi lambda C1 (c^2 - b^2)
    /// + pi (c^2 - b^2) (lambda + 2 mu) e = P_o pi b^2 - p_out pi c^2`, `C1` of the plane
    /// solution with both pressures shifted by `lambda e`.
    pub fn cladding_axial_strain(&self, p_in: f64, p_out: f64, plenum: f64, i_c: f64) -> f64 {
        if !self.generalized {
            return 0.0;
        }
        let m = &self.cladding_elastic;
        let (b, c) = (self.cladding_inner_radius, self.cladding_outer_radius);
        let (lambda, beta) = (m.lambda(), m.beta());
        let area = PI * (c * c - b * b);
        let force = |e: f64| {
            let (pi, po) = (p_in + lambda * e, p_out + lambda * e);
            let c2 = ((pi - po) * b * b * c * c / m.m2() + beta * i_c * b * b) / (c * c - b * b);
            let c1 = (-pi + m.m2() * c2 / (b * b)) / m.m1();
            -2.0 * PI * m.m2() * beta * i_c + 2.0 * lambda * c1 * area + area * m.p_wave() * e
        };
        let f0 = force(0.0);
        (plenum * PI * b * b - p_out * PI * c * c - f0) / (force(1.0) - f0)
    }

    /// The cladding's inner displacement `u_c(b)` (m) with the axial model: the plane
    /// solution with both pressures shifted by `lambda e`
    /// ([`cladding_axial_strain`](Self::cladding_axial_strain)).
    pub fn cladding_inner_displacement(&self, p_in: f64, p_out: f64, plenum: f64, i_c: f64) -> f64 {
        let e = self.cladding_axial_strain(p_in, p_out, plenum, i_c);
        let shift = self.cladding_elastic.lambda() * e;
        self.cladding_displacement(
            self.cladding_inner_radius,
            p_in + shift,
            p_out + shift,
            0.0,
            i_c,
        )
    }

    /// The cladding's displacement `u(r)` (m) at radius `r` for inner pressure `p_in`, outer
    /// pressure `p_out` (Pa), `I(r) = int_b^r (T - T_ref) s ds` and `I_c = I(c)` (K m^2):
    /// `u = beta I(r)/r + C1 r + C2/r`, `C1`, `C2` from `sigma_r(b) = -p_in`, `sigma_r(c) = -p_out`.
    pub fn cladding_displacement(&self, r: f64, p_in: f64, p_out: f64, i_r: f64, i_c: f64) -> f64 {
        let m = &self.cladding_elastic;
        let (b, c) = (self.cladding_inner_radius, self.cladding_outer_radius);
        let (m1, m2, beta) = (m.m1(), m.m2(), m.beta());
        // sigma_r(b) = M1 C1 - M2 C2 / b^2 = -p_in,
        // sigma_r(c) = M1 C1 - M2 C2 / c^2 - M2 beta I_c / c^2 = -p_out.
        let c2 = ((p_in - p_out) * b * b * c * c / m2 + beta * i_c * b * b) / (c * c - b * b);
        let c1 = (-p_in + m2 * c2 / (b * b)) / m1;
        beta * i_r / r + c1 * r + c2 / r
    }

    /// The cladding's radial stress `sigma_r(r)` (Pa), same arguments as
    /// [`cladding_displacement`](Self::cladding_displacement).
    pub fn cladding_radial_stress(&self, r: f64, p_in: f64, p_out: f64, i_r: f64, i_c: f64) -> f64 {
        let m = &self.cladding_elastic;
        let (b, c) = (self.cladding_inner_radius, self.cladding_outer_radius);
        let (m1, m2, beta) = (m.m1(), m.m2(), m.beta());
        let c2 = ((p_in - p_out) * b * b * c * c / m2 + beta * i_c * b * b) / (c * c - b * b);
        let c1 = (-p_in + m2 * c2 / (b * b)) / m1;
        m1 * c1 - m2 * c2 / (r * r) - m2 * beta * i_r / (r * r)
    }

    /// Runs the transient from the uniform `T_co` (with its consistent mechanical state at
    /// `t = 0`) to `end_time` by steps of `time_step`.
    ///
    /// # Errors
    /// A message when a step fails even after 12 halvings.
    pub fn simulate(&self) -> Result<RadialHistory, String> {
        let grid = Grid::new(self);
        let mut state = self.initial_state(&grid)?;
        let mut rows = vec![self.row(&grid, 0.0, &state)];
        let mut cuts = 0;
        let steps = (self.end_time / self.time_step - 1e-9).ceil().max(0.0) as usize;
        let mut t = 0.0;
        for k in 1..=steps {
            let t_new = (k as f64 * self.time_step).min(self.end_time);
            state = self.advance(&grid, &state, t, t_new, 0, &mut cuts)?;
            t = t_new;
            rows.push(self.row(&grid, t, &state));
        }
        let touches = |r: &RadialRow| match self.law {
            ContactLaw::Exponential => r.gap <= self.onset_gap,
            ContactLaw::Exact => r.contact_pressure > 0.0 || r.gap <= 0.0,
        };
        let closure = rows.iter().position(touches).map(|k| {
            let step_time = rows[k].time;
            let threshold = match self.law {
                ContactLaw::Exponential => self.onset_gap,
                ContactLaw::Exact => 0.0,
            };
            let interpolated_time = if k == 0 {
                0.0
            } else {
                let (r0, r1) = (&rows[k - 1], &rows[k]);
                let s = ((r0.gap - threshold) / (r0.gap - r1.gap)).clamp(0.0, 1.0);
                r0.time + s * (r1.time - r0.time)
            };
            Closure {
                step_time,
                interpolated_time,
            }
        });
        Ok(RadialHistory {
            rows,
            closure,
            step_cuts: cuts,
            final_state: state,
        })
    }

    /// The steady state at linear power `q'` (W/m), Newton started from `guess`.
    ///
    /// # Errors
    /// A message when Newton fails.
    pub fn steady(&self, linear_power: f64, guess: &RadialState) -> Result<RadialState, String> {
        let grid = Grid::new(self);
        self.newton(&grid, guess, &guess.temperature, 0.0, linear_power)
    }

    /// The state at `t = 0`: `T = T_co` everywhere, zero power, mechanics and plenum solved.
    ///
    /// # Errors
    /// A message when Newton fails.
    pub fn initial(&self) -> Result<RadialState, String> {
        self.initial_state(&Grid::new(self))
    }

    fn initial_state(&self, grid: &Grid) -> Result<RadialState, String> {
        let t0 = self.outer_temperature;
        let guess = RadialState {
            temperature: vec![t0; grid.r.len()],
            gap: self.cladding_inner_radius - self.pellet_radius,
            plenum_pressure: self.fill_pressure * t0 / self.fill_temperature,
            contact_pressure: 0.0,
        };
        self.newton(grid, &guess, &guess.temperature, 0.0, 0.0)
    }

    /// One step from `t0` to `t1`, halved recursively on failure.
    fn advance(
        &self,
        grid: &Grid,
        state: &RadialState,
        t0: f64,
        t1: f64,
        depth: usize,
        cuts: &mut usize,
    ) -> Result<RadialState, String> {
        let q = self.linear_power_at(t1);
        match self.newton(grid, state, &state.temperature, 1.0 / (t1 - t0), q) {
            Ok(s) => Ok(s),
            Err(e) if depth >= 12 => Err(format!("step {t0}..{t1}: {e}")),
            Err(_) => {
                *cuts += 1;
                let tm = 0.5 * (t0 + t1);
                let mid = self.advance(grid, state, t0, tm, depth + 1, cuts)?;
                self.advance(grid, &mid, tm, t1, depth + 1, cuts)
            }
        }
    }

    /// Newton on the coupled system of one backward Euler step (`inv_dt = 0`: steady).
    fn newton(
        &self,
        grid: &Grid,
        guess: &RadialState,
        old: &[f64],
        inv_dt: f64,
        q: f64,
    ) -> Result<RadialState, String> {
        let mut y = Unknowns::from_state(guess);
        for _ in 0..40 {
            let sys = self.linearise(grid, &y, old, inv_dt, q, true);
            if !sys
                .residual_t
                .iter()
                .chain(sys.residual_z.iter())
                .all(|v| v.is_finite())
            {
                return Err("non-finite residual".into());
            }
            let (dt, dz) = sys.solve();
            let mut lambda = 1.0;
            let mut next = y.minus(&dt, &dz, lambda);
            // Back off an update that leaves the residual's domain (A + B T <= 0).
            for _ in 0..10 {
                let r = self.linearise(grid, &next, old, inv_dt, q, false);
                if r.residual_t
                    .iter()
                    .chain(r.residual_z.iter())
                    .all(|v| v.is_finite())
                {
                    break;
                }
                lambda *= 0.5;
                next = y.minus(&dt, &dz, lambda);
            }
            y = next;
            let step_t = dt.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let done = lambda == 1.0
                && step_t <= 1e-9
                && dz[0].abs() <= 1e-9
                && dz[1].abs() <= 1e-10 * (1.0 + y.z[1].abs())
                && dz[2].abs() <= 1e-10 * (1.0 + y.z[2].abs());
            if done {
                return Ok(y.state(self.outer_temperature));
            }
        }
        Err("Newton did not converge in 40 iterations".into())
    }

    /// The residual and (with `jacobian`) its Jacobian at `y`.
    fn linearise(
        &self,
        grid: &Grid,
        y: &Unknowns,
        old: &[f64],
        inv_dt: f64,
        q: f64,
        jacobian: bool,
    ) -> Linearised {
        let n = y.t.len();
        let np = grid.pellet_nodes - 1; // pellet surface node
        let ci = np + 1; // cladding inner node
        let t_full = |i: usize| {
            if i < n {
                y.t[i]
            } else {
                self.outer_temperature
            }
        };
        let mut res = vec![0.0; n];
        let mut lower = vec![0.0; n]; // d R_i / d T_{i-1}
        let mut diag = vec![0.0; n];
        let mut upper = vec![0.0; n]; // d R_i / d T_{i+1}
                                      // Capacity and source.
        let source = q / (PI * self.pellet_radius * self.pellet_radius);
        for i in 0..n {
            let cap = grid.capacity[i] * inv_dt;
            res[i] += cap * (y.t[i] - old[i]);
            diag[i] += cap;
            if i <= np {
                res[i] -= source * grid.area[i];
            }
        }
        // Pellet faces.
        for i in 0..np {
            let f = grid.face_factor[i];
            let flux = f * (self.kirchhoff(y.t[i]) - self.kirchhoff(y.t[i + 1]));
            let (d0, d1) = (
                f * self.pellet_conductivity(y.t[i]),
                -f * self.pellet_conductivity(y.t[i + 1]),
            );
            res[i] += flux;
            res[i + 1] -= flux;
            diag[i] += d0;
            upper[i] += d1;
            lower[i + 1] -= d0;
            diag[i + 1] -= d1;
        }
        // Cladding faces (the last one to the fixed outer node).
        for i in ci..n {
            let f = grid.face_factor[i];
            let flux = f * (y.t[i] - t_full(i + 1));
            res[i] += flux;
            diag[i] += f;
            if i + 1 < n {
                res[i + 1] -= flux;
                upper[i] -= f;
                lower[i + 1] -= f;
                diag[i + 1] += f;
            }
        }
        // The gap flux 2 pi a U (T_ps - T_ci).
        let (g, p_o, p) = (y.z[0] * 1e-6, y.z[1] * 1e6, y.z[2] * 1e6);
        let (t_ps, t_ci) = (y.t[np], y.t[ci]);
        let t_gap = 0.5 * (t_ps + t_ci);
        let [u, du_dg, du_dp, du_dt] = self.gap_conductance(g, p, t_gap);
        let w = 2.0 * PI * self.pellet_radius;
        let dtemp = t_ps - t_ci;
        let qg = w * u * dtemp;
        res[np] += qg;
        res[ci] -= qg;
        let dq_dps = w * (u + 0.5 * du_dt * dtemp);
        let dq_dci = w * (-u + 0.5 * du_dt * dtemp);
        diag[np] += dq_dps;
        upper[np] += dq_dci;
        lower[ci] -= dq_dps;
        diag[ci] -= dq_dci;
        // d(qg)/dz in the scaled units (um, MPa).
        let dq_dz = [w * dtemp * du_dg * 1e-6, 0.0, w * dtemp * du_dp * 1e6];

        // Mechanics, plenum, contact.
        let (i_p, i_c) = grid.integrals(self, t_full);
        let on = if self.mechanics { 1.0 } else { 0.0 };
        let p_int = p_o + p;
        let u_p =
            on * (self.pellet_displacement(i_p, p_int, p_o) + self.relocation_displacement(q));
        let rho = self.cladding_contact_share;
        let p_clad = p_o + rho * p;
        let u_c = on * self.cladding_inner_displacement(p_clad, self.coolant_pressure, p_o, i_c);
        // Linear coefficients: u_p = e_p I_p - f_p P - g_p P_o,
        // u_c = e_c I_c + f_c (P_o + rho p) + h_c P_o + const (P = P_o + p).
        let e_p = on * self.pellet_displacement(1.0, 0.0, 0.0);
        let f_p = -on * self.pellet_displacement(0.0, 1.0, 0.0);
        let g_p = -on * self.pellet_displacement(0.0, 0.0, 1.0);
        let b = self.cladding_inner_radius;
        let e_c = on * self.cladding_inner_displacement(0.0, 0.0, 0.0, 1.0);
        let f_c = on * self.cladding_inner_displacement(1.0, 0.0, 0.0, 0.0);
        let h_c = on * self.cladding_inner_displacement(0.0, 0.0, 1.0, 0.0);
        let (rp, rc) = (self.pellet_radius + u_p, b + u_c);
        let gap_mech = rc - rp;
        let volume = self.plenum_volume + PI * (rc * rc - rp * rp);
        let nr = self.gas_moles() * GAS_CONSTANT;
        let mut rz = [0.0; 3];
        rz[0] = y.z[0] - 1e6 * gap_mech;
        rz[1] = y.z[1] - 1e-6 * nr * t_gap / volume;
        let mut d = Matrix3::zeros();
        d[(0, 0)] = 1.0;
        // d(gap_mech)/dp = rho f_c + f_p, d(gap_mech)/dP_o = f_c + f_p + h_c + g_p (per Pa);
        // dz1, dz2 are 1e6 Pa.
        d[(0, 1)] = -1e6 * (f_c + f_p + h_c + g_p) * 1e6;
        d[(0, 2)] = -1e6 * (rho * f_c + f_p) * 1e6;
        let dv_dp = 2.0 * PI * (rc * rho * f_c + rp * f_p);
        let dv_dpo = 2.0 * PI * (rc * (f_c + h_c) + rp * (f_p + g_p));
        let dgas = 1e-6 * nr * t_gap / (volume * volume) * 1e6;
        d[(1, 1)] = 1.0 + dgas * dv_dpo;
        d[(1, 2)] = dgas * dv_dp;
        match self.law {
            ContactLaw::Exponential => {
                let [pc, dpc_dg, dpc_dpo] = self.exponential_pressure(g, p_o);
                rz[2] = y.z[2] - 1e-6 * (pc - p_o);
                d[(2, 0)] = -1e-6 * dpc_dg * 1e-6;
                d[(2, 1)] = -(dpc_dpo - 1.0);
                d[(2, 2)] = 1.0;
            }
            ContactLaw::Exact => {
                let trial = y.z[2] - COMPLEMENTARITY * y.z[0];
                if trial > 0.0 {
                    rz[2] = COMPLEMENTARITY * y.z[0];
                    d[(2, 0)] = COMPLEMENTARITY;
                } else {
                    rz[2] = y.z[2];
                    d[(2, 2)] = 1.0;
                }
            }
        }
        let mut c = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        if jacobian {
            for i in 0..n {
                let (dup, duc) = if i <= np {
                    (e_p * grid.weight[i], 0.0)
                } else {
                    (0.0, e_c * grid.weight[i])
                };
                c[0][i] = -1e6 * (duc - dup);
                let dv = 2.0 * PI * (rc * duc - rp * dup);
                let dtg = if i == np || i == ci { 0.5 } else { 0.0 };
                c[1][i] = -1e-6 * nr * (dtg / volume - t_gap * dv / (volume * volume));
            }
        }
        Linearised {
            residual_t: res,
            residual_z: Vector3::from(rz),
            lower,
            diag,
            upper,
            b_rows: (np, ci, dq_dz),
            c,
            d,
        }
    }

    /// The output row of a state.
    fn row(&self, grid: &Grid, time: f64, s: &RadialState) -> RadialRow {
        let np = grid.pellet_nodes - 1;
        let (i_p, _) = grid.integrals(self, |i| s.temperature[i]);
        let p_int = s.plenum_pressure + s.contact_pressure;
        let on = if self.mechanics { 1.0 } else { 0.0 };
        RadialRow {
            time,
            linear_power: self.linear_power_at(time),
            center_temperature: s.temperature[0],
            pellet_surface_temperature: s.temperature[np],
            cladding_inner_temperature: s.temperature[np + 1],
            gap: s.gap,
            interface_pressure: p_int,
            contact_pressure: s.contact_pressure,
            plenum_pressure: s.plenum_pressure,
            pellet_surface_displacement: on
                * (self.pellet_displacement(i_p, p_int, s.plenum_pressure)
                    + self.relocation_displacement(self.linear_power_at(time))),
        }
    }

    /// The heat per unit length leaving through `r = c` at a steady state (W/m): the flux of
    /// the last cladding face (the outer node's control volume has no source, and its
    /// temperature is fixed).
    pub fn outer_flux(&self, s: &RadialState) -> f64 {
        let grid = Grid::new(self);
        let n = grid.r.len() - 1;
        grid.face_factor[n - 1] * (s.temperature[n - 1] - s.temperature[n])
    }

    /// `int_0^a (T - T_ref) r dr` and `int_b^c (T - T_ref) r dr` of the piecewise-linear
    /// interpolant of the nodal temperatures of `s` (K m^2).
    pub fn temperature_integrals(&self, s: &RadialState) -> (f64, f64) {
        Grid::new(self).integrals(self, |i| s.temperature[i])
    }

    /// The radii of the nodes (pellet `0..=a`, then cladding `b..=c`).
    pub fn node_radii(&self) -> Vec<f64> {
        Grid::new(self).r
    }
}

/// The radial grids: pellet nodes `0..pellet_nodes`, then the cladding's, the last (`r = c`)
/// held at `T_co`.
struct Grid {
    r: Vec<f64>,
    pellet_nodes: usize,
    /// `area_i = pi (r_{i+1/2}^2 - r_{i-1/2}^2)` of each control volume.
    area: Vec<f64>,
    /// `rho c_p area_i`.
    capacity: Vec<f64>,
    /// Face `i` (between nodes `i` and `i + 1`, none between the bodies): `2 pi r_f / h`
    /// (pellet, times the Kirchhoff difference) or `2 pi k_c / ln(r_{i+1}/r_i)` (cladding).
    face_factor: Vec<f64>,
    /// `int N_i r dr` of the hat function of each node over its body.
    weight: Vec<f64>,
}

impl Grid {
    fn new(m: &RadialPellet) -> Self {
        let (a, b, c) = (
            m.pellet_radius,
            m.cladding_inner_radius,
            m.cladding_outer_radius,
        );
        let (np, nc) = (m.pellet_cells, m.cladding_cells);
        let mut r: Vec<f64> = (0..=np).map(|i| a * i as f64 / np as f64).collect();
        r.extend((0..=nc).map(|j| b + (c - b) * j as f64 / nc as f64));
        r[np] = a;
        r[np + 1 + nc] = c;
        let total = r.len();
        let mut area = vec![0.0; total];
        let mut capacity = vec![0.0; total];
        let mut face_factor = vec![0.0; total];
        let mut weight = vec![0.0; total];
        for (lo, hi, rho_c) in [
            (0, np, m.pellet_heat_capacity),
            (np + 1, total - 1, m.cladding_heat_capacity),
        ] {
            for i in lo..=hi {
                let inner = if i == lo {
                    r[i]
                } else {
                    0.5 * (r[i - 1] + r[i])
                };
                let outer = if i == hi {
                    r[i]
                } else {
                    0.5 * (r[i] + r[i + 1])
                };
                area[i] = PI * (outer * outer - inner * inner);
                capacity[i] = rho_c * area[i];
            }
            for i in lo..hi {
                let h = r[i + 1] - r[i];
                face_factor[i] = if lo == 0 {
                    2.0 * PI * 0.5 * (r[i] + r[i + 1]) / h
                } else {
                    2.0 * PI * m.cladding_conductivity / (r[i + 1] / r[i]).ln()
                };
                weight[i] += h / 6.0 * (2.0 * r[i] + r[i + 1]);
                weight[i + 1] += h / 6.0 * (r[i] + 2.0 * r[i + 1]);
            }
        }
        Self {
            r,
            pellet_nodes: np + 1,
            area,
            capacity,
            face_factor,
            weight,
        }
    }

    /// `(I_p, I_c)` for the nodal temperatures `t(i)` (every node, the outer one included).
    fn integrals(&self, m: &RadialPellet, t: impl Fn(usize) -> f64) -> (f64, f64) {
        let (mut i_p, mut i_c) = (0.0, 0.0);
        for i in 0..self.r.len() {
            let v = self.weight[i] * (t(i) - m.reference_temperature);
            if i < self.pellet_nodes {
                i_p += v;
            } else {
                i_c += v;
            }
        }
        (i_p, i_c)
    }
}

/// The unknowns of one solve: nodal temperatures (without the fixed outer node) and
/// `z = [g in um, P_o in MPa, p_contact in MPa]`.
struct Unknowns {
    t: Vec<f64>,
    z: [f64; 3],
}

impl Unknowns {
    fn from_state(s: &RadialState) -> Self {
        let n = s.temperature.len() - 1;
        Self {
            t: s.temperature[..n].to_vec(),
            z: [
                s.gap * 1e6,
                s.plenum_pressure * 1e-6,
                s.contact_pressure * 1e-6,
            ],
        }
    }

    fn minus(&self, dt: &[f64], dz: &Vector3<f64>, lambda: f64) -> Self {
        Self {
            t: self.t.iter().zip(dt).map(|(t, d)| t - lambda * d).collect(),
            z: [
                self.z[0] - lambda * dz[0],
                self.z[1] - lambda * dz[1],
                self.z[2] - lambda * dz[2],
            ],
        }
    }

    fn state(&self, outer: f64) -> RadialState {
        let mut temperature = self.t.clone();
        temperature.push(outer);
        RadialState {
            temperature,
            gap: self.z[0] * 1e-6,
            plenum_pressure: self.z[1] * 1e6,
            contact_pressure: self.z[2] * 1e6,
        }
    }
}

/// The linearised system `[A B; C D] [dT; dz] = [r_T; r_z]`, `A` tridiagonal, `B` nonzero in
/// the two surface rows only.
struct Linearised {
    residual_t: Vec<f64>,
    residual_z: Vector3<f64>,
    lower: Vec<f64>,
    diag: Vec<f64>,
    upper: Vec<f64>,
    /// `(pellet surface row, cladding inner row, d(gap flux)/dz)`: `B` is `+dq/dz` in the first
    /// row and `-dq/dz` in the second.
    b_rows: (usize, usize, [f64; 3]),
    c: [Vec<f64>; 3],
    d: Matrix3<f64>,
}

impl Linearised {
    /// Thomas' algorithm for `A x = rhs`.
    fn solve_tridiagonal(&self, rhs: &[f64]) -> Vec<f64> {
        let n = rhs.len();
        let mut c = vec![0.0; n];
        let mut x = vec![0.0; n];
        let mut beta = self.diag[0];
        x[0] = rhs[0] / beta;
        for i in 1..n {
            c[i - 1] = self.upper[i - 1] / beta;
            beta = self.diag[i] - self.lower[i] * c[i - 1];
            x[i] = (rhs[i] - self.lower[i] * x[i - 1]) / beta;
        }
        for i in (0..n - 1).rev() {
            x[i] -= c[i] * x[i + 1];
        }
        x
    }

    /// The Newton update `(dT, dz)` (to subtract) by the Schur complement on `z`.
    fn solve(&self) -> (Vec<f64>, Vector3<f64>) {
        let n = self.residual_t.len();
        let y0 = self.solve_tridiagonal(&self.residual_t);
        let (ps, ci, dq) = self.b_rows;
        let mut x = Vec::with_capacity(3);
        for k in 0..3 {
            let mut col = vec![0.0; n];
            col[ps] = dq[k];
            col[ci] = -dq[k];
            x.push(self.solve_tridiagonal(&col));
        }
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(u, v)| u * v).sum::<f64>();
        let mut s = self.d;
        let mut rhs = self.residual_z;
        for i in 0..3 {
            for k in 0..3 {
                s[(i, k)] -= dot(&self.c[i], &x[k]);
            }
            rhs[i] -= dot(&self.c[i], &y0);
        }
        let dz = s
            .lu()
            .solve(&rhs)
            .unwrap_or(Vector3::from_element(f64::NAN));
        let dt = (0..n)
            .map(|i| y0[i] - x[0][i] * dz[0] - x[1][i] * dz[1] - x[2][i] * dz[2])
            .collect();
        (dt, dz)
    }
}

/// The solution at one time: nodal temperatures (pellet `0..=a`, cladding `b..=c`, see
/// [`RadialPellet::node_radii`]), gap, plenum and contact pressures (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct RadialState {
    /// Nodal temperatures (K).
    pub temperature: Vec<f64>,
    /// `g = (b + u_c(b)) - (a + u_p(a))` (m).
    pub gap: f64,
    /// `P_o` (Pa).
    pub plenum_pressure: f64,
    /// `p_contact = P_c - P_o` (Pa).
    pub contact_pressure: f64,
}

/// One line of the history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadialRow {
    /// Time (s).
    pub time: f64,
    /// `q'(t)` (W/m).
    pub linear_power: f64,
    /// `T(0)` (K).
    pub center_temperature: f64,
    /// `T(a)` (K).
    pub pellet_surface_temperature: f64,
    /// `T(b)` (K).
    pub cladding_inner_temperature: f64,
    /// `g` (m).
    pub gap: f64,
    /// `P_c = P_o + p_contact`, the normal pressure on both surfaces (Pa).
    pub interface_pressure: f64,
    /// `p_contact` (Pa).
    pub contact_pressure: f64,
    /// `P_o` (Pa).
    pub plenum_pressure: f64,
    /// `u_p(a)` (m).
    pub pellet_surface_displacement: f64,
}

/// When the surfaces first touch (see the module's doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Closure {
    /// The end of the first step at which they touch (s).
    pub step_time: f64,
    /// The time at which `g` reaches `xi` (exponential law), linear in `g` within that step;
    /// for the exact law `g` is 0 at the step's end by construction, so this is the step's end.
    pub interpolated_time: f64,
}

/// The transient's result.
#[derive(Debug, Clone, PartialEq)]
pub struct RadialHistory {
    /// One row at `t = 0` and one per step.
    pub rows: Vec<RadialRow>,
    /// The first touch, if any.
    pub closure: Option<Closure>,
    /// How many steps were halved.
    pub step_cuts: usize,
    /// The state at the end.
    pub final_state: RadialState,
}

impl RadialHistory {
    /// Prints a few rows (every `every`-th and the last) to stderr, for the record.
    pub fn print(&self, label: &str, every: usize) {
        eprintln!(
            "{label}: closure {:?}, step cuts {}",
            self.closure, self.step_cuts
        );
        eprintln!(
            "  {:>6} {:>8} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}",
            "t s",
            "q' W/m",
            "T0 K",
            "Tps K",
            "Tci K",
            "g um",
            "Pc MPa",
            "p MPa",
            "Po MPa",
            "u_p um"
        );
        let last = self.rows.len() - 1;
        for (k, r) in self.rows.iter().enumerate() {
            if k % every.max(1) == 0 || k == last {
                eprintln!(
                    "  {:>6.2} {:>8.0} {:>9.3} {:>9.3} {:>9.3} {:>9.4} {:>9.4} {:>9.4} {:>9.4} {:>9.4}",
                    r.time,
                    r.linear_power,
                    r.center_temperature,
                    r.pellet_surface_temperature,
                    r.cladding_inner_temperature,
                    r.gap * 1e6,
                    r.interface_pressure * 1e-6,
                    r.contact_pressure * 1e-6,
                    r.plenum_pressure * 1e-6,
                    r.pellet_surface_displacement * 1e6
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Verification of the reference itself.
// ---------------------------------------------------------------------------------------------

/// The steady closed form of docs/models.md section 3 (open gap held at `b - a`), written again
/// here: `T_ci = T_co + q' ln(c/b) / (2 pi k_c)`, `T_ps = T_ci + q' / (2 pi a U(T_gap))`
/// (fixed point, `U` at the mean of the two surfaces), `T_0 = ((A + B T_ps) e^{B q'/(4 pi)} - A)/B`.
fn closed_form(m: &RadialPellet, q: f64) -> [f64; 3] {
    let (a, b, c) = (
        m.pellet_radius,
        m.cladding_inner_radius,
        m.cladding_outer_radius,
    );
    let t_ci = m.outer_temperature + q * (c / b).ln() / (2.0 * PI * m.cladding_conductivity);
    let mut t_ps = t_ci;
    for _ in 0..200 {
        let kg = 2.531e-3 * (0.5 * (t_ps + t_ci)).powf(0.7146);
        let u = kg / (b - a + 1.5 * (m.roughness_pellet + m.roughness_cladding) + m.jump_distance);
        t_ps = t_ci + q / (2.0 * PI * a * u);
    }
    let (ka, kb) = (m.conductivity_a, m.conductivity_b);
    let t_0 = ((ka + kb * t_ps) * (kb * q / (4.0 * PI)).exp() - ka) / kb;
    [t_0, t_ps, t_ci]
}

/// The steady state at `q` by continuation in the power from the state at `t = 0`.
fn steady_by_continuation(m: &RadialPellet, q: f64, steps: usize) -> RadialState {
    let mut s = m.initial().unwrap();
    for k in 1..=steps {
        s = m.steady(q * k as f64 / steps as f64, &s).unwrap();
    }
    s
}

/// The defaults are the data tables of docs/models.md, sections 3 and 3a (the thermal ones read from the
/// library's default scene, so a change there shows here).
#[test]
fn defaults_follow_physics_md() {
    let m = RadialPellet::default();
    let rel = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs();
    for (x, y) in [
        (m.pellet_radius, 4.1e-3),
        (m.cladding_inner_radius, 4.18e-3),
        (m.cladding_outer_radius, 4.75e-3),
        (m.linear_power, 20e3),
        (m.conductivity_a, 0.0375),
        (m.conductivity_b, 2.165e-4),
        (m.cladding_conductivity, 16.0),
        (m.outer_temperature, 580.0),
        (m.roughness_pellet, 2e-6),
        (m.roughness_cladding, 1e-6),
        (m.jump_distance, 10e-6),
        (m.pellet_heat_capacity, 3.3e6),
        (m.cladding_heat_capacity, 2.0e6),
        (m.pellet_elastic.young, 200e9),
        (m.cladding_elastic.poisson, 0.4),
        (m.reference_temperature, 293.0),
        (m.coolant_pressure, 15.5e6),
        (m.plenum_volume, 2e-6),
        (m.fill_pressure, 2e6),
        (m.fill_temperature, 293.0),
        (m.onset_gap, 5e-6),
    ] {
        assert!(rel(x, y), "{x} against {y}");
    }
    assert_eq!(m.gas, GasConductivity::Helium);
    assert_eq!(m.law, ContactLaw::Exponential);
    assert!(m.mechanics && m.ramp_time > 0.0 && m.time_step > 0.0);
    // The helium law: 2.531e-3 T^0.7146 and its derivative.
    let (k, dk) = m.gas_conductivity(735.0);
    assert!(rel(k, 2.531e-3 * 735f64.powf(0.7146)));
    assert!((dk - 0.7146 * k / 735.0).abs() <= 1e-12 * dk);
    let constant = RadialPellet {
        gas: GasConductivity::Constant(0.3),
        ..m
    };
    assert_eq!(constant.gas_conductivity(900.0), (0.3, 0.0));
}

/// The exponential law (docs/models.md, section 3a): `P_o` for `g >= xi`, `P_o exp(S_NE (xi - g)^2)`
/// below, continued by its tangent past `P_max = ratio P_o` (value and slope continuous there),
/// finite for any gap; its derivatives against central differences.
#[test]
fn exponential_law_is_capped_and_smooth() {
    let m = RadialPellet::default();
    let p_o = 4e6;
    assert_eq!(
        m.exponential_pressure(m.onset_gap + 1e-6, p_o),
        [p_o, 0.0, 1.0]
    );
    let g = m.onset_gap - 2e-6;
    let [p, dp, dpo] = m.exponential_pressure(g, p_o);
    assert!((p - p_o * (m.stiffness * 4e-12).exp()).abs() <= 1e-12 * p);
    assert!((dpo - p / p_o).abs() <= 1e-12 * dpo);
    let h = 1e-12;
    let fd =
        (m.exponential_pressure(g + h, p_o)[0] - m.exponential_pressure(g - h, p_o)[0]) / (2.0 * h);
    assert!((fd - dp).abs() <= 1e-6 * dp.abs(), "{fd} {dp}");
    // The cap: g* = xi - sqrt(ln(ratio) / S_NE).
    let g_star = m.onset_gap - (m.max_pressure_ratio.ln() / m.stiffness).sqrt();
    let above = m.exponential_pressure(g_star + 1e-15, p_o);
    let below = m.exponential_pressure(g_star - 1e-15, p_o);
    let p_max = m.max_pressure_ratio * p_o;
    assert!((above[0] - p_max).abs() <= 1e-8 * p_max && (below[0] - p_max).abs() <= 1e-8 * p_max);
    assert!((above[1] - below[1]).abs() <= 1e-8 * above[1].abs());
    for g in [-1e-3, -1.0, -1e6] {
        let [p, dp, _] = m.exponential_pressure(g, p_o);
        assert!(p.is_finite() && p > p_max && dp < 0.0, "g = {g}: {p}");
        assert!((p - p_max * (1.0 + (below[1] / p_max) * (g - g_star))).abs() <= 1e-9 * p);
    }
}

/// The analytic Jacobian of the coupled residual against central differences, both laws, at
/// an open and a closed state (a coarse grid; the states need not be solutions).
#[test]
fn jacobian_matches_finite_differences() {
    let (a, b) = (4.1e-3, 4.18e-3);
    for (law, share, relocation) in [
        (ContactLaw::Exponential, 1.0, None),
        (ContactLaw::Exact, 1.0, None),
        (ContactLaw::Exponential, a / b, Some(10.0)),
    ] {
        for (gap_um, p_mpa) in [(30.0, 0.0), (3.0, 20.0), (0.02, 20.0)] {
            let m = RadialPellet {
                law,
                pellet_cells: 12,
                cladding_cells: 4,
                cladding_contact_share: share,
                relocation_burnup: relocation,
                ..RadialPellet::default()
            };
            let grid = Grid::new(&m);
            let n = grid.r.len() - 1;
            let t: Vec<f64> = grid
                .r
                .iter()
                .map(|r| 580.0 + 900.0 * (1.0 - (r / m.cladding_outer_radius).powi(2)))
                .collect();
            let old: Vec<f64> = t.iter().map(|v| v - 5.0).collect();
            let y = Unknowns {
                t: t[..n].to_vec(),
                z: [gap_um, 6.0, p_mpa],
            };
            let lin = m.linearise(&grid, &y, &old, 0.5, 40e3, true);
            let all = |l: &Linearised| {
                let mut v = l.residual_t.clone();
                v.extend(l.residual_z.iter());
                v
            };
            // Column k of the Jacobian by central differences.
            for k in 0..n + 3 {
                let h = if k < n { 1e-2 } else { 1e-6 };
                let shifted = |s: f64| {
                    let mut y2 = Unknowns {
                        t: y.t.clone(),
                        z: y.z,
                    };
                    if k < n {
                        y2.t[k] += s;
                    } else {
                        y2.z[k - n] += s;
                    }
                    all(&m.linearise(&grid, &y2, &old, 0.5, 40e3, false))
                };
                let (rp, rm) = (shifted(h), shifted(-h));
                for i in 0..n + 3 {
                    let fd = (rp[i] - rm[i]) / (2.0 * h);
                    let exact = match (i < n, k < n) {
                        (true, true) => {
                            if k + 1 == i {
                                lin.lower[i]
                            } else if k == i {
                                lin.diag[i]
                            } else if k == i + 1 {
                                lin.upper[i]
                            } else {
                                0.0
                            }
                        }
                        (true, false) => {
                            let (ps, ci, dq) = lin.b_rows;
                            if i == ps {
                                dq[k - n]
                            } else if i == ci {
                                -dq[k - n]
                            } else {
                                0.0
                            }
                        }
                        (false, true) => lin.c[i - n][k],
                        (false, false) => lin.d[(i - n, k - n)],
                    };
                    // Truncation, plus the round-off of the differenced residuals.
                    let roundoff = 1e-14 * rp[i].abs().max(rm[i].abs()) / h;
                    let scale = 1e-6 * (exact.abs() + fd.abs()) + 1e-9 + roundoff;
                    assert!(
                        (fd - exact).abs() <= scale,
                        "{law:?} gap {gap_um} um: J[{i}][{k}] = {exact}, differences {fd}"
                    );
                }
            }
        }
    }
}

/// Mechanics off (rigid bodies, the gap held at `b - a`): the steady state against the closed
/// form of docs/models.md section 3, written again above, and the library's
/// `PelletScene::closed_form()` read as numbers. The finite volumes are exact for the steady
/// profiles, so the agreement is to rounding on any grid (measured 3.5e-16 against the closed
/// form written here, 1.1e-14 against the library's, whose fixed point on the gap
/// conductance stops at its own tolerance; bound 1e-12).
#[test]
fn mechanics_off_steady_state_is_the_closed_form() {
    for cells in [(400, 60), (25, 4)] {
        let m = RadialPellet {
            mechanics: false,
            pellet_cells: cells.0,
            cladding_cells: cells.1,
            ..RadialPellet::default()
        };
        let s = steady_by_continuation(&m, m.linear_power, 1);
        let np = m.pellet_cells;
        let got = [s.temperature[0], s.temperature[np], s.temperature[np + 1]];
        let want = closed_form(&m, m.linear_power);
        let mut scene = PelletScene::from_toml("").unwrap();
        scene.cladding.inner_radius = m.cladding_inner_radius;
        let lib = scene.closed_form().unwrap();
        let lib = [
            lib.center_temperature,
            lib.pellet_surface_temperature,
            lib.cladding_inner_temperature,
        ];
        let worst = (0..3)
            .map(|k| ((got[k] - want[k]) / want[k]).abs())
            .fold(0.0, f64::max);
        let worst_lib = (0..3)
            .map(|k| ((got[k] - lib[k]) / lib[k]).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "mechanics off, {cells:?} cells: (T_0, T_ps, T_ci) = {got:.6?} K, closed form {want:.6?}, relative {worst:.1e} (library's {worst_lib:.1e})"
        );
        assert!(worst < 1e-12 && worst_lib < 1e-12);
        assert!((s.gap - (m.cladding_inner_radius - m.pellet_radius)).abs() < 1e-15);
    }
}

/// The integral `int (T - T_ref) r dr` on the piecewise-linear interpolant: exact for a linear
/// `T` (round-off), second order for `T_ref + theta (1 - r^2/a^2)`, whose integral is
/// `theta a^2 / 4`.
#[test]
fn temperature_integrals_are_exact_for_linear_and_second_order_for_quadratic() {
    let theta = 700.0;
    let mut errors = Vec::new();
    for cells in [100, 200, 400] {
        let m = RadialPellet {
            pellet_cells: cells,
            cladding_cells: cells / 4,
            ..RadialPellet::default()
        };
        let (a, b, c, tr) = (
            m.pellet_radius,
            m.cladding_inner_radius,
            m.cladding_outer_radius,
            m.reference_temperature,
        );
        let state = |f: &dyn Fn(f64, bool) -> f64| RadialState {
            temperature: m
                .node_radii()
                .iter()
                .enumerate()
                .map(|(i, &r)| f(r, i <= m.pellet_cells))
                .collect(),
            gap: 0.0,
            plenum_pressure: 0.0,
            contact_pressure: 0.0,
        };
        let linear = state(&|r, pellet| tr + theta * (1.0 + r / if pellet { a } else { c }));
        let (ip, ic) = m.temperature_integrals(&linear);
        let ip_exact = theta * (a * a / 2.0 + a * a / 3.0);
        let ic_exact = theta * ((c * c - b * b) / 2.0 + (c.powi(3) - b.powi(3)) / (3.0 * c));
        assert!((ip - ip_exact).abs() <= 1e-13 * ip_exact, "{ip} {ip_exact}");
        assert!((ic - ic_exact).abs() <= 1e-13 * ic_exact, "{ic} {ic_exact}");
        let quadratic = state(&|r, _| tr + theta * (1.0 - r * r / (a * a)));
        let (iq, _) = m.temperature_integrals(&quadratic);
        errors.push(((iq - theta * a * a / 4.0) / (theta * a * a / 4.0)).abs());
    }
    eprintln!(
        "int (T - T_ref) r dr of a parabola, relative errors at 100, 200, 400 cells: {errors:?}"
    );
    for w in errors.windows(2) {
        assert!((w[0] / w[1] - 4.0).abs() < 0.1, "{errors:?}");
    }
    assert!(errors[2] < 1e-5);
}

/// Free expansion (Timoshenko and Goodier, *Theory of Elasticity*, 3rd ed., sec. 150): with
/// every pressure zero (no fill, no coolant), the model's pellet surface displacement on its
/// own temperature is, with `I = int_0^a (T - T_ref) r dr` (taken here by Simpson's rule on
/// each cell, exact for the piecewise-linear `T` times `r`):
///
/// - plane strain (`eps_zz = 0`): `u(a) = (1 + nu)(2 alpha / a) I`;
/// - generalized plane strain (uniform `eps_zz`, zero axial force): `u(a) = 2 alpha I / a`,
///   the free expansion of the mean temperature, and `eps_zz = 2 alpha I / a^2`.
///
/// Under a pressure `P` on the surface alone, the solid cylinder's uniform stress:
/// `u(a) = -P a (1 + nu)(1 - 2 nu) / E` in plane strain, `-P a (1 - nu) / E` with free ends
/// (`sigma_zz = 0`), `-P a (1 - 2 nu) / E` when the plenum pressure `P` also loads the ends
/// (hydrostatic).
#[test]
fn free_expansion_of_the_model_is_the_closed_form() {
    for generalized in [false, true] {
        let m = RadialPellet {
            fill_pressure: 0.0,
            coolant_pressure: 0.0,
            generalized,
            ..RadialPellet::default()
        };
        let h = m.simulate().unwrap();
        let last = h.rows.last().unwrap();
        assert_eq!(last.interface_pressure, 0.0);
        let r = m.node_radii();
        let t = &h.final_state.temperature;
        let f = |k: usize| (t[k] - m.reference_temperature) * r[k];
        let mut integral = 0.0;
        for k in 0..m.pellet_cells {
            let mid =
                0.5 * (t[k] + t[k + 1] - 2.0 * m.reference_temperature) * 0.5 * (r[k] + r[k + 1]);
            integral += (r[k + 1] - r[k]) / 6.0 * (f(k) + 4.0 * mid + f(k + 1));
        }
        let (e, nu, alpha) = (
            m.pellet_elastic.young,
            m.pellet_elastic.poisson,
            m.pellet_elastic.expansion,
        );
        let a = m.pellet_radius;
        let factor = if generalized { 1.0 } else { 1.0 + nu };
        let exact = factor * 2.0 * alpha / a * integral;
        let error = ((last.pellet_surface_displacement - exact) / exact).abs();
        eprintln!(
            "free expansion (generalized: {generalized}) at t = {} s: u(a) = {:.6e} m, closed form {exact:.6e} m, relative {error:.1e}",
            last.time, last.pellet_surface_displacement
        );
        assert!(error < 1e-8);
        let i_p = m.temperature_integrals(&h.final_state).0;
        let strain = m.pellet_axial_strain(i_p, 0.0, 0.0);
        let want = if generalized {
            2.0 * alpha * i_p / (a * a)
        } else {
            0.0
        };
        assert!(
            (strain - want).abs() <= 1e-12 * want.abs(),
            "{strain} {want}"
        );
        let p = 30e6;
        for (plenum, want) in [
            (
                0.0,
                if generalized {
                    -p * a * (1.0 - nu) / e
                } else {
                    -p * a * (1.0 + nu) * (1.0 - 2.0 * nu) / e
                },
            ),
            (
                p,
                if generalized {
                    -p * a * (1.0 - 2.0 * nu) / e
                } else {
                    -p * a * (1.0 + nu) * (1.0 - 2.0 * nu) / e
                },
            ),
        ] {
            let under_pressure = m.pellet_displacement(0.0, p, plenum);
            assert!(
                (under_pressure - want).abs() <= 1e-13 * want.abs(),
                "generalized {generalized}, plenum {plenum}: {under_pressure} {want}"
            );
        }
    }
}

/// The closed-end tube (Lame; Timoshenko and Goodier, ch. 4): inner pressure `p_i` (the
/// plenum's, also on the closed ends), outer `p_o`, `T = T_ref`, free axial expansion:
/// `sigma_r = A - B / r^2`, `sigma_t = A + B / r^2`, `sigma_z = A`, with
/// `A = (p_i b^2 - p_o c^2) / (c^2 - b^2)`, `B = (p_i - p_o) b^2 c^2 / (c^2 - b^2)`, so
/// `u(b) = ((1 - 2 nu) A b + (1 + nu) B / b) / E` and `eps_z = (1 - 2 nu) A / E`; a uniform
/// `Delta T` alone gives `u = alpha Delta T r`, `eps_z = alpha Delta T` and no stress.
#[test]
fn cladding_with_closed_ends_is_the_lame_tube() {
    let m = RadialPellet {
        generalized: true,
        ..RadialPellet::default()
    };
    let (b, c) = (m.cladding_inner_radius, m.cladding_outer_radius);
    let (e, nu, alpha) = (
        m.cladding_elastic.young,
        m.cladding_elastic.poisson,
        m.cladding_elastic.expansion,
    );
    let (p_i, p_o) = (7e6, 15.5e6);
    let a_ = (p_i * b * b - p_o * c * c) / (c * c - b * b);
    let b_ = (p_i - p_o) * b * b * c * c / (c * c - b * b);
    let u = m.cladding_inner_displacement(p_i, p_o, p_i, 0.0);
    let want = ((1.0 - 2.0 * nu) * a_ * b + (1.0 + nu) * b_ / b) / e;
    let strain = m.cladding_axial_strain(p_i, p_o, p_i, 0.0);
    let want_strain = (1.0 - 2.0 * nu) * a_ / e;
    eprintln!("closed-end tube: u(b) = {u:.6e} m (Lame {want:.6e}), eps_z = {strain:.6e} ({want_strain:.6e})");
    assert!((u - want).abs() <= 1e-12 * want.abs());
    assert!((strain - want_strain).abs() <= 1e-12 * want_strain.abs());
    let dt = 300.0;
    let i_c = dt * (c * c - b * b) / 2.0;
    let u = m.cladding_inner_displacement(0.0, 0.0, 0.0, i_c);
    assert!((u - alpha * dt * b).abs() <= 1e-12 * alpha * dt * b, "{u}");
    let strain = m.cladding_axial_strain(0.0, 0.0, 0.0, i_c);
    assert!(
        (strain - alpha * dt).abs() <= 1e-12 * alpha * dt,
        "{strain}"
    );
}

/// The cladding's thick-wall response (Lame; Timoshenko and Goodier, ch. 4, the thick-walled
/// cylinder under uniform pressure) in plane strain, `T = T_ref`, inner pressure `p_i`, outer
/// `p_o`:
/// `u(r) = (1 + nu)/E [ (1 - 2 nu)(p_i b^2 - p_o c^2) r / (c^2 - b^2)
///                    + (p_i - p_o) b^2 c^2 / ((c^2 - b^2) r) ]`,
/// with `sigma_r(b) = -p_i`, `sigma_r(c) = -p_o`; and a uniform `Delta T` alone gives
/// `u = (1 + nu) alpha Delta T r` and no stress.
#[test]
fn cladding_is_the_lame_thick_wall() {
    let m = RadialPellet::default();
    let (b, c) = (m.cladding_inner_radius, m.cladding_outer_radius);
    let (e, nu, alpha) = (
        m.cladding_elastic.young,
        m.cladding_elastic.poisson,
        m.cladding_elastic.expansion,
    );
    let (p_i, p_o) = (7e6, 15.5e6);
    let mut worst = 0.0f64;
    for r in [b, 0.5 * (b + c), c] {
        let lame = (1.0 + nu) / e
            * ((1.0 - 2.0 * nu) * (p_i * b * b - p_o * c * c) * r / (c * c - b * b)
                + (p_i - p_o) * b * b * c * c / ((c * c - b * b) * r));
        let u = m.cladding_displacement(r, p_i, p_o, 0.0, 0.0);
        worst = worst.max(((u - lame) / lame).abs());
    }
    let s_b = m.cladding_radial_stress(b, p_i, p_o, 0.0, 0.0);
    let s_c = m.cladding_radial_stress(c, p_i, p_o, 0.0, 0.0);
    eprintln!(
        "Lame, p_i = 7 MPa, p_o = 15.5 MPa: u(b) = {:.6e} m, worst relative error {worst:.1e}; sigma_r(b) = {s_b:.6e}, sigma_r(c) = {s_c:.6e} Pa",
        m.cladding_displacement(b, p_i, p_o, 0.0, 0.0)
    );
    assert!(worst < 1e-12);
    assert!((s_b + p_i).abs() < 1e-12 * p_o && (s_c + p_o).abs() < 1e-12 * p_o);
    let dt = 300.0;
    let i_of = |r: f64| dt * (r * r - b * b) / 2.0;
    for r in [b, 0.5 * (b + c), c] {
        let u = m.cladding_displacement(r, 0.0, 0.0, i_of(r), i_of(c));
        let want = (1.0 + nu) * alpha * dt * r;
        assert!((u - want).abs() <= 1e-12 * want, "{u} {want}");
        let s = m.cladding_radial_stress(r, 0.0, 0.0, i_of(r), i_of(c));
        assert!(s.abs() < 1e-3, "{s}");
    }
}

/// The largest difference of the centre temperature, relative, and of the gap (m) between two
/// histories over their common times.
fn history_difference(h1: &RadialHistory, h2: &RadialHistory) -> (f64, f64) {
    let (mut dt, mut dg) = (0.0f64, 0.0f64);
    for r1 in &h1.rows {
        let r2 = h2
            .rows
            .iter()
            .find(|r| (r.time - r1.time).abs() < 1e-9)
            .expect("common times");
        dt =
            dt.max(((r1.center_temperature - r2.center_temperature) / r2.center_temperature).abs());
        dg = dg.max((r1.gap - r2.gap).abs());
    }
    (dt, dg)
}

/// Mesh convergence of the transient (the default ramp to 30 s): the centre temperature
/// history on 200/30, 400/60 and 800/120 cells; the last two agree to 1e-4 and the differences
/// fall at second order.
#[test]
fn transient_converges_under_radial_refinement() {
    let run = |k: usize| {
        RadialPellet {
            pellet_cells: 200 * k,
            cladding_cells: 30 * k,
            ..RadialPellet::default()
        }
        .simulate()
        .unwrap()
    };
    let h = [run(1), run(2), run(4)];
    let (d1, g1) = history_difference(&h[0], &h[1]);
    let (d2, g2) = history_difference(&h[1], &h[2]);
    eprintln!(
        "radial refinement: centre temperature differences {d1:.2e}, {d2:.2e} (ratio {:.2}); gap {g1:.2e}, {g2:.2e} m (ratio {:.2})",
        d1 / d2,
        g1 / g2
    );
    assert!(d2 < 1e-4);
    assert!(d1 / d2 > 3.5, "{d1} {d2}");
}

/// Backward Euler is first order: halving the step halves the change of the history. Steps
/// 1/2, 1/4, 1/8 s (the default ramp to 30 s), compared at the half seconds: the ratio of the
/// successive differences is near 2 (1.83 already from 1 s).
#[test]
fn transient_is_first_order_in_time() {
    let run = |dt: f64| {
        RadialPellet {
            time_step: dt,
            ..RadialPellet::default()
        }
        .simulate()
        .unwrap()
    };
    let h = [run(0.5), run(0.25), run(0.125)];
    assert!(h.iter().all(|h| h.step_cuts == 0));
    let (d1, g1) = history_difference(&h[0], &h[1]);
    let (d2, g2) = history_difference(&h[1], &h[2]);
    let (ratio_t, ratio_g) = (d1 / d2, g1 / g2);
    eprintln!(
        "time step 1/2 -> 1/4 -> 1/8 s: centre temperature differences {d1:.3e}, {d2:.3e} (ratio {ratio_t:.3}); gap {g1:.3e}, {g2:.3e} m (ratio {ratio_g:.3})"
    );
    assert!((ratio_t - 2.0).abs() < 0.15, "{ratio_t}");
    assert!((ratio_g - 2.0).abs() < 0.15, "{ratio_g}");
}

/// The default scene (20 kW/m over 10 s, to 30 s): the gap narrows from 71.2 um
/// (at 580 K and the coolant pressure) but does not close; the closing scene (160 kW/m, same
/// ramp) closes within the ramp under both laws, the surfaces never interpenetrating under the
/// exponential law (the `S_NE` choice).
#[test]
fn default_scene_stays_open_and_the_closing_scene_closes_in_the_ramp() {
    let m = RadialPellet::default();
    let h = m.simulate().unwrap();
    h.print("default scene (20 kW/m, ramp 10 s)", 3);
    assert!(h.closure.is_none());
    let last = h.rows.last().unwrap();
    assert!(last.gap > 40e-6 && last.contact_pressure == 0.0);

    let m = RadialPellet::closing();
    let h = m.simulate().unwrap();
    h.print("closing scene (160 kW/m, ramp 10 s), exponential law", 3);
    let closure = h.closure.expect("the gap closes");
    assert!(closure.step_time <= m.ramp_time, "{closure:?}");
    let peak = h
        .rows
        .iter()
        .map(|r| r.contact_pressure)
        .fold(0.0, f64::max);
    let smallest_gap = h.rows.iter().map(|r| r.gap).fold(f64::INFINITY, f64::min);
    eprintln!(
        "closing scene: peak contact pressure {:.3} MPa, smallest gap {:.3} um, step cuts {}",
        peak * 1e-6,
        smallest_gap * 1e6,
        h.step_cuts
    );
    assert!(peak > 0.0 && smallest_gap > -1e-6);

    let exact = RadialPellet {
        law: ContactLaw::Exact,
        ..m
    }
    .simulate()
    .unwrap();
    exact.print("closing scene, exact law", 3);
    let closure_exact = exact.closure.expect("the gap closes");
    assert!(closure_exact.step_time <= m.ramp_time, "{closure_exact:?}");
    let last = exact.rows.last().unwrap();
    assert!(last.gap.abs() < 1e-12 && last.contact_pressure > 0.0);
}

/// The smallest powers that close the gap: at the steady state (any ramp slow enough) by
/// continuation and bisection, and within the default 10 s ramp (closure at a step end up to
/// `t_ramp`) by bisection on the transient, for both laws. All lie above the default 20 kW/m,
/// and the closing scene's 160 kW/m above them.
#[test]
fn smallest_power_closing_the_gap() {
    let m = RadialPellet::default();
    let touches = |g: f64| g <= m.onset_gap;
    // Steady: continuation in steps of 4 kW/m, then bisection between the last two.
    let mut s = m.initial().unwrap();
    let mut q = 0.0;
    let mut open = s.clone();
    while !touches(s.gap) {
        open = s.clone();
        q += 4e3;
        assert!(q <= 200e3, "no closure below 200 kW/m");
        s = m.steady(q, &s).unwrap();
    }
    let (mut lo, mut hi) = (q - 4e3, q);
    while hi - lo > 10.0 {
        let mid = 0.5 * (lo + hi);
        let t = m.steady(mid, &open).unwrap();
        if touches(t.gap) {
            hi = mid;
        } else {
            lo = mid;
            open = t;
        }
    }
    let steady_threshold = hi;
    let closes_in_ramp = |q: f64| {
        let h = RadialPellet {
            linear_power: q,
            end_time: m.ramp_time,
            ..m
        }
        .simulate()
        .unwrap();
        h.closure.is_some()
    };
    let (mut lo, mut hi) = (m.linear_power, RadialPellet::closing().linear_power);
    assert!(!closes_in_ramp(lo) && closes_in_ramp(hi));
    while hi - lo > 10.0 {
        let mid = 0.5 * (lo + hi);
        if closes_in_ramp(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let closes_in_ramp_exact = |q: f64| {
        let h = RadialPellet {
            linear_power: q,
            end_time: m.ramp_time,
            law: ContactLaw::Exact,
            ..m
        }
        .simulate()
        .unwrap();
        h.closure.is_some()
    };
    let (mut lo2, mut hi2) = (m.linear_power, 2.0 * RadialPellet::closing().linear_power);
    assert!(closes_in_ramp_exact(hi2));
    while hi2 - lo2 > 10.0 {
        let mid = 0.5 * (lo2 + hi2);
        if closes_in_ramp_exact(mid) {
            hi2 = mid;
        } else {
            lo2 = mid;
        }
    }
    eprintln!(
        "smallest linear power closing the gap: {:.2} kW/m at the steady state (T_0 = {:.0} K there); within the 10 s ramp {:.2} kW/m (exponential law, g <= xi), {:.2} kW/m (exact law, g = 0)",
        steady_threshold * 1e-3,
        s.temperature[0],
        hi * 1e-3,
        hi2 * 1e-3
    );
    assert!(steady_threshold > m.linear_power && hi > steady_threshold);
    assert!(hi2 > hi && RadialPellet::closing().linear_power > hi2);
}

/// Energy balance at the steady state: the linear power `q'` put in the pellet leaves through
/// `r = c` (the flux of the last cladding face), to 1e-6 relative; open (default scene) and
/// closed (closing scene, in contact).
#[test]
fn steady_state_balances_the_power() {
    for m in [RadialPellet::default(), RadialPellet::closing()] {
        let h = m.simulate().unwrap();
        let s = m.steady(m.linear_power, &h.final_state).unwrap();
        let out = m.outer_flux(&s);
        let error = ((out - m.linear_power) / m.linear_power).abs();
        eprintln!(
            "steady state at {} kW/m: T_0 = {:.3} K, g = {:.4} um, p_contact = {:.4} MPa, P_o = {:.4} MPa; flux out {out:.6} W/m, relative imbalance {error:.1e}",
            m.linear_power * 1e-3,
            s.temperature[0],
            s.gap * 1e6,
            s.contact_pressure * 1e-6,
            s.plenum_pressure * 1e-6
        );
        assert!(error < 1e-6);
    }
}
