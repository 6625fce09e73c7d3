//! Heat across a gap: the gas conductivity `k_g(T)` (`GasConductivity`), the Ross-Stoute gap
//! conductance at a fixed width (`GapConductance`) and at the mechanical gap with contact
//! conductance (`MechanicalGapConductance`), in resistance form.

use num_traits::Float;

use super::{cst, ConstraintLaw, LawError, LawPoint};

/// The conductivity `k_g(T)` (W/m/K) of the gas in a gap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GasConductivity {
    /// A constant.
    Constant(f64),
    /// `k_g = coefficient * T^exponent` (T in K).
    PowerLaw {
        /// The coefficient.
        coefficient: f64,
        /// The exponent.
        exponent: f64,
    },
}

impl GasConductivity {
    /// Helium: `k_g(T) = 2.531e-3 T^0.7146` W/m/K (docs/models.md, section 3).
    pub const HELIUM: Self = Self::PowerLaw {
        coefficient: 2.531e-3,
        exponent: 0.7146,
    };

    /// Temperatures below this (K) are taken as it by the power law, so that the law stays
    /// finite (and positive) whatever the iterate.
    pub const MIN_TEMPERATURE: f64 = 1.0;

    /// `k_g(T)`.
    pub fn at<S: Float>(&self, t: S) -> S {
        match *self {
            Self::Constant(k) => cst(k),
            Self::PowerLaw {
                coefficient,
                exponent,
            } => {
                let t = t.max(cst(Self::MIN_TEMPERATURE));
                cst::<S>(coefficient) * t.powf(cst(exponent))
            }
        }
    }

    fn check(&self) -> Result<(), LawError> {
        let ok = |v: f64| v > 0.0 && v.is_finite();
        let fine = match *self {
            Self::Constant(k) => ok(k),
            Self::PowerLaw {
                coefficient,
                exponent,
            } => ok(coefficient) && exponent.is_finite(),
        };
        if fine {
            Ok(())
        } else {
            Err(LawError::InvalidParameter {
                law: "gap conductance",
                what: format!("gas conductivity {self:?} is not positive and finite"),
            })
        }
    }
}

/// Heat transfer across an open gap, `q = U (T_s - T_m)`, with the Ross-Stoute conductance
///
/// ```text
/// U = k_g(T) / (d_g + 1.5 (R_f + R_c) + g_f + g_c)        (simplified: U = k_g / d_g)
/// ```
///
/// written in the resistance `R = 1/U` (never dividing by `U`) and normalised by a reference
/// resistance `R_ref`:
///
/// ```text
/// C(g, q; T) = (R(T) q - g) / (R(T) + R_ref)          (W/m^2)
/// ```
///
/// with `g = T_s - T_m` and `q` the flux leaving the slave. `C = 0` is `q = U g` for every
/// `R_ref > 0`; the normalisation keeps both limits finite and well scaled: as `R -> 0`
/// (`U -> infinity`) `C -> -g / R_ref`, tying; as `R -> infinity` (`U -> 0`) `C -> q`, no
/// flux. `R_ref` only scales the residual rows; pick it near the expected `R` (the default,
/// 1e-4 m^2 K/W, is a typical gap conductance of 1e4 W/m^2/K).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GapConductance {
    /// The open gap width `d_g` (m).
    pub gap_width: f64,
    /// The added distance `1.5 (R_f + R_c) + g_f + g_c` (m): roughness and jump distances.
    pub added_distance: f64,
    /// The gas conductivity.
    pub gas: GasConductivity,
    /// The reference resistance `R_ref` (m^2 K/W) of the normalisation.
    pub reference_resistance: f64,
}

impl GapConductance {
    /// The default reference resistance (m^2 K/W).
    pub const DEFAULT_REFERENCE_RESISTANCE: f64 = 1e-4;

    /// The Ross-Stoute law: gap `d_g`, roughnesses `R_f` (fuel, slave) and `R_c` (cladding),
    /// temperature jump distances `g_f + g_c`, all in metres.
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] for a negative or non-finite distance, a total distance
    /// of zero, or a non-positive gas conductivity.
    pub fn ross_stoute(
        gap_width: f64,
        roughness_fuel: f64,
        roughness_cladding: f64,
        jump_distance: f64,
        gas: GasConductivity,
    ) -> Result<Self, LawError> {
        for (what, v) in [
            ("gap width", gap_width),
            ("fuel roughness", roughness_fuel),
            ("cladding roughness", roughness_cladding),
            ("jump distance", jump_distance),
        ] {
            if !(v >= 0.0 && v.is_finite()) {
                return Err(LawError::InvalidParameter {
                    law: "gap conductance",
                    what: format!("{what} {v} is not non-negative and finite"),
                });
            }
        }
        let law = Self {
            gap_width,
            added_distance: 1.5 * (roughness_fuel + roughness_cladding) + jump_distance,
            gas,
            reference_resistance: Self::DEFAULT_REFERENCE_RESISTANCE,
        };
        law.check()?;
        Ok(law)
    }

    /// The simplified law `U = k_g / d_g`.
    ///
    /// # Errors
    /// As [`ross_stoute`](Self::ross_stoute).
    pub fn simplified(gap_width: f64, gas: GasConductivity) -> Result<Self, LawError> {
        Self::ross_stoute(gap_width, 0.0, 0.0, 0.0, gas)
    }

    /// The same law with another reference resistance.
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] unless `r_ref` is positive and finite.
    pub fn with_reference_resistance(mut self, r_ref: f64) -> Result<Self, LawError> {
        self.reference_resistance = r_ref;
        self.check()?;
        Ok(self)
    }

    fn check(&self) -> Result<(), LawError> {
        self.gas.check()?;
        let d = self.gap_width + self.added_distance;
        if !(d > 0.0 && d.is_finite()) {
            return Err(LawError::InvalidParameter {
                law: "gap conductance",
                what: format!("total distance d_g + added = {d} is not positive and finite"),
            });
        }
        let r = self.reference_resistance;
        if !(r > 0.0 && r.is_finite()) {
            return Err(LawError::InvalidParameter {
                law: "gap conductance",
                what: format!("reference resistance {r} is not positive and finite"),
            });
        }
        Ok(())
    }

    /// The resistance `R(T) = (d_g + added) / k_g(T)` (m^2 K/W).
    pub fn resistance<S: Float>(&self, temperature: S) -> S {
        cst::<S>(self.gap_width + self.added_distance) / self.gas.at(temperature)
    }

    /// The conductance `U(T) = 1 / R(T)` (W/m^2/K), for reports.
    pub fn conductance(&self, temperature: f64) -> f64 {
        1.0 / self.resistance(temperature)
    }
}

impl ConstraintLaw for GapConductance {
    fn residual<S: Float>(&self, p: LawPoint<S>) -> S {
        let r = self.resistance(p.temperature);
        (r * p.multiplier - p.gap) / (r + cst(self.reference_resistance))
    }
}

/// Heat transfer across a gap that moves: the Ross-Stoute conductance on the point's current
/// mechanical gap `g_n` ([`LawPoint::normal_gap`]) plus a contact term that grows with the
/// contact pressure `p_c` ([`LawPoint::contact_pressure`]) once the surfaces touch
/// (docs/models.md, section 3a):
///
/// ```text
/// U = k_g(T) / (max(g_n, 0) + 1.5 (R_f + R_c) + g_f + g_c) + h_contact max(p_c, 0)
/// ```
///
/// written, as [`GapConductance`], in the resistance `R = 1/U` and normalised by `R_ref`:
/// `C(g, q; T, g_n, p_c) = (R q - g) / (R + R_ref)`, with `g = T_s - T_m` and `q` the flux
/// leaving the slave. `R = d / (k_g + h_contact max(p_c, 0) d)`, `d` the total distance,
/// never divides by zero (`d > 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MechanicalGapConductance {
    /// The added distance `1.5 (R_f + R_c) + g_f + g_c` (m), positive.
    pub added_distance: f64,
    /// The gas conductivity.
    pub gas: GasConductivity,
    /// `h_contact` (W/m^2/K/Pa): the conductance gained per pascal of contact pressure.
    pub contact_conductance: f64,
    /// The reference resistance `R_ref` (m^2 K/W) of the normalisation.
    pub reference_resistance: f64,
}

impl MechanicalGapConductance {
    /// The law with roughnesses `R_f` (fuel, slave) and `R_c` (cladding), jump distances
    /// `g_f + g_c` (m), the gas, and `h_contact` (W/m^2/K/Pa; 0 for none), with the default
    /// reference resistance ([`GapConductance::DEFAULT_REFERENCE_RESISTANCE`]).
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] for a negative or non-finite distance or `h_contact`,
    /// an added distance of zero (the conductance of a closed gap would be infinite), or a
    /// non-positive gas conductivity.
    pub fn try_new(
        roughness_fuel: f64,
        roughness_cladding: f64,
        jump_distance: f64,
        gas: GasConductivity,
        contact_conductance: f64,
    ) -> Result<Self, LawError> {
        let bad = |what: String| {
            Err(LawError::InvalidParameter {
                law: "gap conductance",
                what,
            })
        };
        for (what, v) in [
            ("fuel roughness", roughness_fuel),
            ("cladding roughness", roughness_cladding),
            ("jump distance", jump_distance),
            ("contact conductance", contact_conductance),
        ] {
            if !(v >= 0.0 && v.is_finite()) {
                return bad(format!("{what} {v} is not non-negative and finite"));
            }
        }
        let added_distance = 1.5 * (roughness_fuel + roughness_cladding) + jump_distance;
        if added_distance <= 0.0 {
            return bad(
                "roughness and jump distances are all zero: a closed gap would conduct infinitely"
                    .into(),
            );
        }
        gas.check()?;
        Ok(Self {
            added_distance,
            gas,
            contact_conductance,
            reference_resistance: GapConductance::DEFAULT_REFERENCE_RESISTANCE,
        })
    }

    /// The resistance `R = 1/U` (m^2 K/W) at gap `g_n` (m), contact pressure `p_c` (Pa) and
    /// temperature `T` (K).
    pub fn resistance<S: Float>(&self, normal_gap: S, contact_pressure: S, temperature: S) -> S {
        let d = normal_gap.max(S::zero()) + cst(self.added_distance);
        let h = cst::<S>(self.contact_conductance) * contact_pressure.max(S::zero());
        d / (self.gas.at(temperature) + h * d)
    }

    /// The conductance `U = 1/R` (W/m^2/K), for reports.
    pub fn conductance(&self, normal_gap: f64, contact_pressure: f64, temperature: f64) -> f64 {
        1.0 / self.resistance(normal_gap, contact_pressure, temperature)
    }
}

impl ConstraintLaw for MechanicalGapConductance {
    fn residual<S: Float>(&self, p: LawPoint<S>) -> S {
        let r = self.resistance(p.normal_gap, p.contact_pressure, p.temperature);
        (r * p.multiplier - p.gap) / (r + cst(self.reference_resistance))
    }
}
