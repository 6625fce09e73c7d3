//! Pointwise constraint laws between the (nodal) weighted gap `g` and the multiplier `lambda`
//! of an interface: a residual `C(g, lambda; T) = 0` written once, generically over a
//! [`num_traits::Float`] scalar, whose tangent comes by forward automatic differentiation
//! ([`Dual`] numbers): a new law needs no hand-written derivative.
//!
//! Conventions. For thermal laws `g` is the temperature jump `T_s - T_m` (K) and `lambda` the
//! heat flux leaving the slave body (W/m^2); for mechanical laws `g` is the normal gap (m,
//! positive open) and `lambda` the contact pressure (Pa, positive in compression). `T` is the
//! interface temperature (K), for laws whose coefficients depend on it (a gas conductivity).
//!
//! - [`Tying`]: `C = g` (the two sides are equal).
//! - [`GapConductance`]: `q = U (T_s - T_m)` with the Ross-Stoute or simplified conductance,
//!   written in the resistance `R = 1/U` and normalised so that both limits `U -> 0` and
//!   `U -> infinity` stay finite and well scaled.
//! - [`MechanicalGapConductance`]: the same across a gap that moves, `U = k_g(T) /
//!   (max(g_n, 0) + added) + h_contact p_contact` with the point's mechanical gap and contact
//!   pressure (the pellet in its cladding).
//! - [`ExponentialPressure`]: the regularised (exponential) contact pressure
//!   `P_c = P_o exp(S_NE (xi - g)^2)`, overflow-safe; [`ExponentialContact`], the same with
//!   `P_o` the point's gas pressure as it goes and the contact pressure `P_c - P_o` as the
//!   multiplier.
//! - [`ContactComplementarity`]: `C = lambda - max(0, lambda - c g)` (semi-smooth Newton).
//!
//! [`DynLaw`] is any law behind one type, chosen at run time; a [`LawRegistry`] makes the
//! shipped laws (and a program's own) by name from their parameters, and holds the fuel's
//! relocation models ([`RelocationModel`]: [`NoRelocation`], [`FrapconRelocation`]) by name.
//!
//! [`evaluate`] is the checked evaluation: value and partial derivatives, or a [`LawError`]
//! for NaN input or a non-finite result; [`check_tangent`] compares that tangent with finite
//! differences, for a law of one's own.
//!
//! A new law, in a few lines (the tangent comes for free):
//!
//! ```
//! use mortar_physics::laws::{evaluate, ConstraintLaw, LawPoint};
//! use num_traits::Float;
//!
//! /// A radiative gap: q = s (T_s^4 - T_m^4), with T_s, T_m = T +- g / 2.
//! struct Radiation { s: f64 }
//! impl ConstraintLaw for Radiation {
//!     fn residual<S: Float>(&self, p: LawPoint<S>) -> S {
//!         let half = S::from(0.5).unwrap();
//!         let (ts, tm) = (p.temperature + half * p.gap, p.temperature - half * p.gap);
//!         p.multiplier - S::from(self.s).unwrap() * (ts.powi(4) - tm.powi(4))
//!     }
//! }
//! let t = evaluate(&Radiation { s: 5.67e-8 }, LawPoint::new(0.0, 0.0, 600.0)).unwrap();
//! assert!((t.d_multiplier - 1.0).abs() < 1e-15);
//! assert!((t.d_gap + 5.67e-8 * 4.0 * 600f64.powi(3)).abs() < 1e-9); // -4 s T^3
//! assert!(evaluate(&Radiation { s: 1.0 }, LawPoint::new(f64::NAN, 0.0, 1.0)).is_err());
//! ```

mod check;
mod complementarity;
mod dual;
mod dynamic;
mod gap;
mod pressure;
mod relocation;

pub use check::{check_tangent, TangentCheck};
pub use complementarity::ContactComplementarity;
pub use dual::Dual;
pub use dynamic::{DynLaw, LawParameters, LawRegistry, ObjectLaw};
pub use gap::{GapConductance, GasConductivity, MechanicalGapConductance};
pub use pressure::{ExponentialContact, ExponentialPressure};
pub use relocation::{FrapconRelocation, NoRelocation, RelocationInput, RelocationModel};

/// The scalar trait of [`ConstraintLaw::residual`], re-exported so that a law of one's own
/// needs no direct dependency on `num-traits`.
pub use num_traits::Float;

/// The arguments of a law at one point (one slave node).
///
/// The first three are the law's own: its gap, its multiplier and the interface temperature.
/// The last three are what a law of a thermomechanical interface may also see of the other
/// physics at the same point (zero where no such physics runs): the mechanical normal gap and
/// contact pressure (for a thermal law whose conductance follows the gap), and the gas pressure
/// of the gap (for a mechanical law whose pressure follows the plenum). For a mechanical law
/// `normal_gap` and `contact_pressure` repeat `gap` and `multiplier`; a law reads one or the
/// other, and the solver adds the two derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawPoint<S> {
    /// The gap: the temperature jump `T_s - T_m` (thermal) or the normal gap (mechanical).
    pub gap: S,
    /// The multiplier: the heat flux leaving the slave (thermal) or the contact pressure.
    pub multiplier: S,
    /// The interface temperature (K), for temperature-dependent coefficients.
    pub temperature: S,
    /// The mechanical normal gap (m, positive open) at the point.
    pub normal_gap: S,
    /// The contact pressure (Pa, positive in compression), in excess of the gas pressure.
    pub contact_pressure: S,
    /// The pressure of the gas in the gap (Pa), the plenum pressure `P_o`.
    pub gas_pressure: S,
}

impl<S: num_traits::Zero> LawPoint<S> {
    /// The point `(gap, multiplier, temperature)`, with no mechanical gap, contact pressure or
    /// gas pressure (all zero).
    pub fn new(gap: S, multiplier: S, temperature: S) -> Self {
        Self {
            gap,
            multiplier,
            temperature,
            normal_gap: S::zero(),
            contact_pressure: S::zero(),
            gas_pressure: S::zero(),
        }
    }

    /// The same point seen by a thermomechanical interface: mechanical normal gap (m),
    /// contact pressure and gas pressure (Pa).
    pub fn with_mechanics(mut self, normal_gap: S, contact_pressure: S, gas_pressure: S) -> Self {
        self.normal_gap = normal_gap;
        self.contact_pressure = contact_pressure;
        self.gas_pressure = gas_pressure;
        self
    }
}

/// A pointwise constraint law `C(g, lambda; T) = 0`, written once over a generic float.
///
/// Implement [`residual`](ConstraintLaw::residual) only; [`evaluate`] differentiates it
/// with [`Dual`] numbers. Use `S::from(x).unwrap()` (exact for `f64` and [`Dual`]) for
/// constants, and branch on comparisons of `S` values as on `f64`.
pub trait ConstraintLaw {
    /// The residual `C` at `p`.
    fn residual<S: Float>(&self, p: LawPoint<S>) -> S;

    /// The residual in the dual numbers that [`evaluate`] uses (value and the six partial
    /// derivatives). Provided: `residual` at `Dual<6>`; only a wrapper that cannot be generic
    /// ([`DynLaw`]) overrides it.
    fn residual_dual(&self, p: LawPoint<Dual<6>>) -> Dual<6> {
        self.residual(p)
    }
}

/// A law's value and its partial derivatives at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawTangent {
    /// `C`.
    pub value: f64,
    /// `dC/dg`.
    pub d_gap: f64,
    /// `dC/dlambda`.
    pub d_multiplier: f64,
    /// `dC/dT`.
    pub d_temperature: f64,
    /// `dC/d(normal gap)`.
    pub d_normal_gap: f64,
    /// `dC/d(contact pressure)`.
    pub d_contact_pressure: f64,
    /// `dC/d(gas pressure)`.
    pub d_gas_pressure: f64,
}

/// Errors of laws.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LawError {
    /// An argument is NaN.
    #[error("constraint law evaluated with a NaN {argument}")]
    NanInput {
        /// `"gap"`, `"multiplier"`, `"temperature"`, `"normal gap"`, `"contact pressure"` or
        /// `"gas pressure"`.
        argument: &'static str,
    },
    /// The law's value or a derivative is not finite at a finite point.
    #[error("constraint law not finite at (gap {gap}, multiplier {multiplier}, temperature {temperature}): {what}")]
    NonFinite {
        /// The gap.
        gap: f64,
        /// The multiplier.
        multiplier: f64,
        /// The temperature.
        temperature: f64,
        /// Which quantity, and its value.
        what: String,
    },
    /// A parameter of a law is out of range.
    #[error("{law}: {what}")]
    InvalidParameter {
        /// The law.
        law: &'static str,
        /// What is wrong.
        what: String,
    },
}

/// The checked evaluation of a law: its value and partial derivatives at `p` (by forward
/// automatic differentiation, one pass with six directions).
///
/// # Errors
/// [`LawError::NanInput`] if an argument is NaN, [`LawError::NonFinite`] if the value or a
/// derivative is not finite.
pub fn evaluate<L: ConstraintLaw + ?Sized>(
    law: &L,
    p: LawPoint<f64>,
) -> Result<LawTangent, LawError> {
    for (argument, v) in [
        ("gap", p.gap),
        ("multiplier", p.multiplier),
        ("temperature", p.temperature),
        ("normal gap", p.normal_gap),
        ("contact pressure", p.contact_pressure),
        ("gas pressure", p.gas_pressure),
    ] {
        if v.is_nan() {
            return Err(LawError::NanInput { argument });
        }
    }
    let c = law.residual_dual(LawPoint {
        gap: Dual::<6>::variable(p.gap, 0),
        multiplier: Dual::variable(p.multiplier, 1),
        temperature: Dual::variable(p.temperature, 2),
        normal_gap: Dual::variable(p.normal_gap, 3),
        contact_pressure: Dual::variable(p.contact_pressure, 4),
        gas_pressure: Dual::variable(p.gas_pressure, 5),
    });
    let t = LawTangent {
        value: c.re,
        d_gap: c.eps[0],
        d_multiplier: c.eps[1],
        d_temperature: c.eps[2],
        d_normal_gap: c.eps[3],
        d_contact_pressure: c.eps[4],
        d_gas_pressure: c.eps[5],
    };
    for (what, v) in [
        ("value", t.value),
        ("dC/dg", t.d_gap),
        ("dC/dlambda", t.d_multiplier),
        ("dC/dT", t.d_temperature),
        ("dC/d(normal gap)", t.d_normal_gap),
        ("dC/d(contact pressure)", t.d_contact_pressure),
        ("dC/d(gas pressure)", t.d_gas_pressure),
    ] {
        if !v.is_finite() {
            return Err(LawError::NonFinite {
                gap: p.gap,
                multiplier: p.multiplier,
                temperature: p.temperature,
                what: format!("{what} = {v}"),
            });
        }
    }
    Ok(t)
}

/// `x` as the scalar `S` (exact for `f64` and [`Dual`]).
#[inline]
pub(crate) fn cst<S: Float>(x: f64) -> S {
    S::from(x).unwrap_or_else(S::nan)
}

/// Mesh tying: `C = g`, the two sides equal (`T_s = T_m`); the multiplier is free.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Tying;

impl ConstraintLaw for Tying {
    fn residual<S: Float>(&self, p: LawPoint<S>) -> S {
        p.gap
    }
}
