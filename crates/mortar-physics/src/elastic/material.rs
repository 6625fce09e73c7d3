//! The isotropic linear elastic material with thermal expansion, its Lame constants and
//! stress, and the von Mises equivalent stress.

use crate::error::PhysicsError;

/// An isotropic linear elastic material (constant over a body), with an optional isotropic
/// thermal expansion: the thermal strain is `alpha (T - T_ref) I`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticMaterial {
    /// Young's modulus E (Pa), positive and finite.
    pub youngs_modulus: f64,
    /// Poisson's ratio nu, in the open interval (-1, 0.5).
    pub poisson_ratio: f64,
    /// The linear thermal expansion coefficient alpha (1/K); zero by default.
    pub thermal_expansion: f64,
    /// The temperature T_ref (K) at which the thermal strain is zero.
    pub reference_temperature: f64,
}

impl ElasticMaterial {
    /// A material of Young's modulus `youngs_modulus` and Poisson's ratio `poisson_ratio`,
    /// without thermal expansion.
    pub fn new(youngs_modulus: f64, poisson_ratio: f64) -> Self {
        Self {
            youngs_modulus,
            poisson_ratio,
            thermal_expansion: 0.0,
            reference_temperature: 0.0,
        }
    }

    /// Sets the thermal expansion coefficient `alpha` (1/K) and the stress-free temperature
    /// `reference_temperature` (K).
    pub fn with_expansion(mut self, alpha: f64, reference_temperature: f64) -> Self {
        self.thermal_expansion = alpha;
        self.reference_temperature = reference_temperature;
        self
    }

    /// The Lame parameters `(lambda, mu)`: `lambda = E nu / ((1 + nu) (1 - 2 nu))`,
    /// `mu = E / (2 (1 + nu))` (the shear modulus).
    pub fn lame(&self) -> (f64, f64) {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        (
            e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            e / (2.0 * (1.0 + nu)),
        )
    }

    /// The bulk modulus `K = E / (3 (1 - 2 nu))`.
    pub fn bulk_modulus(&self) -> f64 {
        self.youngs_modulus / (3.0 * (1.0 - 2.0 * self.poisson_ratio))
    }

    /// The thermal stress per kelvin, `3 K alpha = E alpha / (1 - 2 nu)`: the mean stress
    /// `-3 K alpha (T - T_ref)` of a fully constrained body.
    pub fn thermal_stress_coefficient(&self) -> f64 {
        3.0 * self.bulk_modulus() * self.thermal_expansion
    }

    /// The Cauchy stress `C : (eps - alpha dT I)` for the small strain `strain` in Voigt
    /// order `[xx, yy, zz, yz, xz, xy]` with engineering shear strains (`gamma_yz = 2 eps_yz`),
    /// at the temperature change `dt = T - T_ref`; the stress in the same order (tensor
    /// components).
    pub fn stress(&self, strain: &[f64; 6], dt: f64) -> [f64; 6] {
        let (lambda, mu) = self.lame();
        let p =
            lambda * (strain[0] + strain[1] + strain[2]) - self.thermal_stress_coefficient() * dt;
        [
            p + 2.0 * mu * strain[0],
            p + 2.0 * mu * strain[1],
            p + 2.0 * mu * strain[2],
            mu * strain[3],
            mu * strain[4],
            mu * strain[5],
        ]
    }

    /// Checks the data, naming `body` in the error.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a Young's modulus that is not positive and finite,
    /// a Poisson's ratio outside the open interval (-1, 0.5) (at 0.5 the material is
    /// incompressible, which this displacement formulation cannot represent), or a
    /// non-finite expansion coefficient or reference temperature.
    pub fn check(&self, body: &str) -> Result<(), PhysicsError> {
        let invalid = |what: String| PhysicsError::InvalidInput {
            body: body.to_string(),
            what,
        };
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        if !(e > 0.0 && e.is_finite()) {
            return Err(invalid(format!(
                "Young's modulus {e} is not positive and finite (allowed: 0 < E < infinity)"
            )));
        }
        if !(nu > -1.0 && nu < 0.5) {
            return Err(invalid(format!(
                "Poisson's ratio {nu} is outside the allowed open interval (-1, 0.5) \
                 (0.5, incompressible, needs a mixed formulation)"
            )));
        }
        if !self.thermal_expansion.is_finite() {
            return Err(invalid(format!(
                "thermal expansion coefficient {} is not finite",
                self.thermal_expansion
            )));
        }
        if !self.reference_temperature.is_finite() {
            return Err(invalid(format!(
                "reference temperature {} is not finite",
                self.reference_temperature
            )));
        }
        Ok(())
    }
}

/// The von Mises equivalent stress of a stress in Voigt order `[xx, yy, zz, yz, xz, xy]`:
/// `sqrt(((s_xx - s_yy)^2 + (s_yy - s_zz)^2 + (s_zz - s_xx)^2) / 2 + 3 (s_yz^2 + s_xz^2 + s_xy^2))`.
pub fn von_mises(s: &[f64; 6]) -> f64 {
    let d = (s[0] - s[1]).powi(2) + (s[1] - s[2]).powi(2) + (s[2] - s[0]).powi(2);
    (0.5 * d + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])).sqrt()
}
