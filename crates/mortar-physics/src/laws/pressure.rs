//! The exponential contact pressure `P_c = P_o exp(S_NE (xi - g)^2)`: `ExponentialPressure`
//! with a fixed gas pressure, `ExponentialContact` with the gas pressure an unknown.

use num_traits::Float;

use super::{cst, ConstraintLaw, LawError, LawPoint};

/// The regularised (exponential) gap pressure
///
/// ```text
/// P_c(g) = P_o exp(S_NE (xi - g)^2)   for g < xi,      P_c = P_o   for g >= xi,
/// ```
///
/// `P_o` the plenum gas pressure, `xi` the gap at which the surfaces start to feel each
/// other, `S_NE` the stiffness exponent (1/m^2). The law is `C(g, t) = t - P_c(g)` (`t` the
/// pressure on the slave surface, the force on a segment being its area times `P_c`).
///
/// Overflow-safe: past the maximum pressure `P_max` (reached at
/// `g* = xi - sqrt(ln(P_max / P_o) / S_NE)`) the exponential is continued by its tangent,
/// `P_c = P_max (1 + 2 S_NE (xi - g*) (g* - g))`, and the result is capped at `f64::MAX`,
/// so that `P_c` is finite, continuous and non-increasing in `g` for every finite `g`
/// (continuously differentiable up to the cap). [`pressure_checked`](Self::pressure_checked)
/// refuses a NaN gap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExponentialPressure {
    base: f64,
    stiffness: f64,
    onset: f64,
    max_pressure: f64,
}

impl ExponentialPressure {
    /// The default ratio `P_max / P_o`.
    pub const DEFAULT_MAX_RATIO: f64 = 1e6;

    /// The law with plenum pressure `P_o` (Pa), stiffness `S_NE` (1/m^2) and onset gap `xi`
    /// (m), and the maximum pressure `1e6 P_o` (see
    /// [`with_max_pressure`](Self::with_max_pressure)).
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] for a non-positive or non-finite `P_o`, a negative or
    /// non-finite `S_NE`, or a non-finite `xi`.
    pub fn try_new(base_pressure: f64, stiffness: f64, onset: f64) -> Result<Self, LawError> {
        let bad = |what: String| {
            Err(LawError::InvalidParameter {
                law: "exponential pressure",
                what,
            })
        };
        if !(base_pressure > 0.0 && base_pressure.is_finite()) {
            return bad(format!("P_o = {base_pressure} is not positive and finite"));
        }
        if !(stiffness >= 0.0 && stiffness.is_finite()) {
            return bad(format!("S_NE = {stiffness} is not non-negative and finite"));
        }
        if !onset.is_finite() {
            return bad(format!("xi = {onset} is not finite"));
        }
        Self {
            base: base_pressure,
            stiffness,
            onset,
            max_pressure: f64::INFINITY,
        }
        .with_max_pressure(base_pressure * Self::DEFAULT_MAX_RATIO)
    }

    /// The same law with maximum pressure `P_max`, past which the exponential continues
    /// linearly.
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] unless `P_o < P_max < infinity`.
    pub fn with_max_pressure(mut self, max_pressure: f64) -> Result<Self, LawError> {
        if !(max_pressure > self.base && max_pressure.is_finite()) {
            return Err(LawError::InvalidParameter {
                law: "exponential pressure",
                what: format!(
                    "P_max = {max_pressure} is not finite and above P_o = {}",
                    self.base
                ),
            });
        }
        self.max_pressure = max_pressure;
        Ok(self)
    }

    /// `P_max`.
    pub fn max_pressure(&self) -> f64 {
        self.max_pressure
    }

    /// The gap `g*` below which the law is linear (`-infinity` when `S_NE = 0`).
    pub fn linear_below(&self) -> f64 {
        self.onset - ((self.max_pressure / self.base).ln() / self.stiffness).sqrt()
    }

    /// `P_c(g)` (see the type's documentation). A NaN gap gives an unspecified value: use
    /// [`pressure_checked`](Self::pressure_checked) on untrusted input.
    pub fn pressure<S: Float>(&self, g: S) -> S {
        let xi = cst::<S>(self.onset);
        if g >= xi || self.stiffness == 0.0 {
            return cst(self.base);
        }
        let s = cst::<S>(self.stiffness);
        let e = s * (xi - g) * (xi - g);
        let e_max = (self.max_pressure / self.base).ln();
        if e <= cst(e_max) {
            cst::<S>(self.base) * e.exp()
        } else {
            let g_star = self.linear_below();
            let slope = 2.0 * self.stiffness * (self.onset - g_star);
            let p =
                cst::<S>(self.max_pressure) * (S::one() + cst::<S>(slope) * (cst::<S>(g_star) - g));
            p.min(S::max_value())
        }
    }

    /// `P_c(g)`, refusing a NaN gap.
    ///
    /// # Errors
    /// [`LawError::NanInput`] for a NaN gap.
    pub fn pressure_checked(&self, g: f64) -> Result<f64, LawError> {
        if g.is_nan() {
            Err(LawError::NanInput { argument: "gap" })
        } else {
            Ok(self.pressure(g))
        }
    }
}

impl ConstraintLaw for ExponentialPressure {
    fn residual<S: Float>(&self, p: LawPoint<S>) -> S {
        p.multiplier - self.pressure(p.gap)
    }
}

/// The exponential pressure law with the gas pressure as it goes: the multiplier is the contact
/// pressure `p_c = P_c - P_o` (Pa, in excess of the gas pressure, which acts on both surfaces
/// beside it), and `P_o` is the point's [`gas_pressure`](LawPoint::gas_pressure), an unknown
/// of a problem with a plenum:
///
/// ```text
/// C(g, p_c; P_o) = p_c - P_o (exp(S_NE (xi - g)^2) - 1)   for g < xi,    p_c  otherwise,
/// ```
///
/// overflow-safe as [`ExponentialPressure`] (the exponential continued linearly past
/// `P_max / P_o`, by default 1e6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExponentialContact {
    /// The law at `P_o = 1`: `P_c = P_o shape(g)`.
    shape: ExponentialPressure,
}

impl ExponentialContact {
    /// The law with stiffness `S_NE` (1/m^2) and onset gap `xi` (m), and the ratio
    /// `P_max / P_o` of [`ExponentialPressure::DEFAULT_MAX_RATIO`].
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] for a negative or non-finite `S_NE` or a non-finite `xi`.
    pub fn try_new(stiffness: f64, onset: f64) -> Result<Self, LawError> {
        Ok(Self {
            shape: ExponentialPressure::try_new(1.0, stiffness, onset)?,
        })
    }

    /// The same law with the ratio `P_max / P_o` (above 1, finite).
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] for a ratio not above 1 or not finite.
    pub fn with_max_ratio(mut self, ratio: f64) -> Result<Self, LawError> {
        self.shape = self.shape.with_max_pressure(ratio)?;
        Ok(self)
    }

    /// The total interface pressure `P_c(g) = P_o shape(g)` at gas pressure `P_o`.
    pub fn pressure<S: Float>(&self, g: S, gas_pressure: S) -> S {
        gas_pressure * self.shape.pressure(g)
    }

    /// The onset gap `xi` (m): the surfaces feel each other below it.
    pub fn onset(&self) -> f64 {
        self.shape.onset
    }
}

impl ConstraintLaw for ExponentialContact {
    fn residual<S: Float>(&self, p: LawPoint<S>) -> S {
        p.multiplier - p.gas_pressure * (self.shape.pressure(p.gap) - S::one())
    }
}
