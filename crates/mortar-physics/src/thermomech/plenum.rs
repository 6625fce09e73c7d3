//! The gas pressure in the gap: given, or an ideal gas of fixed moles in the plenum and the
//! gap (its volume and temperature).

use crate::error::PhysicsError;

/// The molar gas constant `R` (J/mol/K, exact since the 2019 SI).
pub const GAS_CONSTANT: f64 = 8.314_462_618;

/// The pressure of the gas in the gap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GasPressure {
    /// A given pressure (Pa), constant in time (0: no gas).
    Fixed(f64),
    /// A plenum connected to the gap: the pressure follows the gap's volume and temperature.
    Plenum(Plenum),
}

/// A closed amount of ideal gas filling the gap and a plenum (docs/models.md, section 3a):
/// `P_o (V_plenum + V_gap) = n R T_gap`, the moles `n` fixed by the fill,
/// `P_fill (V_plenum + V_gap0) = n R T_fill`. Volumes per unit length in 2D (m^2 per metre of
/// rod, the cross-section's areas), volumes in 3D.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plenum {
    /// `V_plenum` (m^3, or m^2 per unit length in 2D).
    pub volume: f64,
    /// `n R` (J/K): the gas amount times the gas constant.
    pub gas_amount: f64,
}

impl Plenum {
    /// The plenum of volume `volume` filled at `fill_pressure` (Pa) and `fill_temperature`
    /// (K) with the gap of volume `fill_gap_volume` (the as-built gap at the fill).
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a negative or non-finite volume, pressure or
    /// temperature, a zero total volume, or a non-positive fill temperature.
    pub fn from_fill(
        volume: f64,
        fill_gap_volume: f64,
        fill_pressure: f64,
        fill_temperature: f64,
    ) -> Result<Self, PhysicsError> {
        let bad = |what: String| {
            Err(PhysicsError::InvalidInput {
                body: "plenum".into(),
                what,
            })
        };
        for (what, v) in [
            ("plenum volume", volume),
            ("gap volume at the fill", fill_gap_volume),
            ("fill pressure", fill_pressure),
        ] {
            if !(v >= 0.0 && v.is_finite()) {
                return bad(format!("{what} {v} is not non-negative and finite"));
            }
        }
        if !(fill_temperature > 0.0 && fill_temperature.is_finite()) {
            return bad(format!(
                "fill temperature {fill_temperature} K is not positive and finite"
            ));
        }
        if volume + fill_gap_volume <= 0.0 {
            return bad("the plenum and the gap have no volume".into());
        }
        Ok(Self {
            volume,
            gas_amount: fill_pressure * (volume + fill_gap_volume) / fill_temperature,
        })
    }

    /// `P_o = n R T / (V_plenum + V_gap)` (Pa).
    pub fn pressure(&self, gap_volume: f64, temperature: f64) -> f64 {
        self.gas_amount * temperature / (self.volume + gap_volume)
    }
}
