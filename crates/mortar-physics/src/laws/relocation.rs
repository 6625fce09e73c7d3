//! Pellet relocation: the cracked fragments of a fuel pellet moving outward at power, which
//! closes most of a light-water rod's as-fabricated gap early in life. Fuel-performance codes
//! model it as an empirical outward strain of the pellet, a function of the linear power and
//! the burnup; [`RelocationModel`] is that function, [`FrapconRelocation`] the one FRAPCON
//! uses by default (docs/models.md, section 3a). The thermomechanical problem applies it as
//! an eigenstrain that follows time
//! ([`GapThermoMechanics::with_eigenstrain`](crate::thermomech::GapThermoMechanics::with_eigenstrain)).

use std::fmt;

/// What a relocation model sees: the rod's local state and its as-fabricated geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelocationInput {
    /// The linear power (W/m), the largest reached so far: relocation does not go back when
    /// the power falls.
    pub linear_power: f64,
    /// The burnup (MWd/kgU, i.e. GWd/tU).
    pub burnup: f64,
    /// The as-fabricated (cold) radial gap between pellet and cladding (m).
    pub cold_gap: f64,
    /// The as-fabricated pellet radius (m).
    pub pellet_radius: f64,
}

/// A relocation model: the outward radial strain of the pellet that relocation adds, the
/// radial displacement of its surface over its radius. The problem applies it as a uniform
/// eigenstrain in the plane across the pellet's axis (`eps_rr = eps_tt = strain`,
/// `eps_zz = 0`), which displaces a free pellet's surface by `strain a` and stresses nothing.
///
/// ```
/// use mortar_physics::laws::{RelocationInput, RelocationModel};
///
/// /// A fixed share of the cold gap, as FRAPCON's user-given relocation.
/// #[derive(Debug)]
/// struct Share(f64);
/// impl RelocationModel for Share {
///     fn name(&self) -> &str {
///         "share"
///     }
///     fn strain(&self, rod: &RelocationInput) -> f64 {
///         self.0 * rod.cold_gap / rod.pellet_radius
///     }
/// }
/// let rod = RelocationInput { linear_power: 20e3, burnup: 10.0, cold_gap: 80e-6, pellet_radius: 4.1e-3 };
/// assert!((Share(0.5).strain(&rod) * 4.1e-3 - 40e-6).abs() < 1e-18);
/// ```
pub trait RelocationModel: fmt::Debug + Send + Sync {
    /// The model's name, as a scene file gives it.
    fn name(&self) -> &str;

    /// The relocation strain at `rod` (dimensionless, non-negative and finite for inputs in
    /// the model's range).
    fn strain(&self, rod: &RelocationInput) -> f64;
}

/// No relocation: an uncracked pellet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct NoRelocation;

impl RelocationModel for NoRelocation {
    fn name(&self) -> &str {
        "none"
    }

    fn strain(&self, _: &RelocationInput) -> f64 {
        0.0
    }
}

/// FRAPCON's default relocation model (`RelocModel = 'FRAPCON-3.5'`, also FRAPCON-4.0's
/// default; Geelhood et al., FRAPCON-3.5, NUREG/CR-7022 Vol. 1, and FRAPCON-4.0,
/// PNNL-19418 Vol. 1 Rev. 2, 2015, read from the published FRAPCON-4.0 source,
/// `UO2gtrloc`). The relocation's radial displacement is a share `f` of the cold radial gap
/// `g_0`, `strain = f g_0 / a`, with `P` the linear power in kW/m and `Bu` the burnup in
/// MWd/kgU:
///
/// ```text
/// R(P) = 0.345                        P <= 20
///        0.345 + (P - 20) / 200       20 < P <= 40
///        0.445                        P > 40
/// f    = 0.055                                               Bu <= 0.0937
///        0.055 + min(R, R (0.5795 + 0.2447 ln Bu))            Bu > 0.0937
/// ```
///
/// So a fresh pellet relocates by 5.5 % of its gap, and from about 5.6 MWd/kgU by 40 % (at
/// 20 kW/m and below) to 50 % (at 40 kW/m and above). FRAPCON's mechanical model then counts
/// only `1 - gaprecov` (0.5 by default) of it in the pellet's radius; this toolkit applies
/// the whole strain to its one gap, thermal and mechanical alike.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FrapconRelocation;

impl FrapconRelocation {
    /// The share `f` of the cold gap at the linear power `linear_power` (W/m) and the burnup
    /// `burnup` (MWd/kgU).
    pub fn gap_share(linear_power: f64, burnup: f64) -> f64 {
        let p = linear_power / 1e3;
        let r = if p <= 20.0 {
            0.345
        } else if p <= 40.0 {
            0.345 + (p - 20.0) / 200.0
        } else {
            0.445
        };
        if burnup > 0.0937 {
            0.055 + r.min(r * (0.5795 + 0.2447 * burnup.ln()))
        } else {
            0.055
        }
    }
}

impl RelocationModel for FrapconRelocation {
    fn name(&self) -> &str {
        "frapcon"
    }

    fn strain(&self, rod: &RelocationInput) -> f64 {
        Self::gap_share(rod.linear_power, rod.burnup) * rod.cold_gap / rod.pellet_radius
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The FRAPCON-3.5 model's values at its corners (NUREG/CR-7022 Vol. 1; the FRAPCON-4.0
    /// source): 5.5 % of the gap up to 0.0937 MWd/kgU, nearly continuous there (the log term
    /// nearly vanishes: `0.5795 + 0.2447 ln 0.0937 = 1.3e-4`, a step of 4.6e-5), saturated from
    /// `exp((1 - 0.5795) / 0.2447) = 5.57` MWd/kgU at `0.055 + R`, `R` 0.345 to 0.445
    /// linear between 20 and 40 kW/m, and non-decreasing in both arguments.
    #[test]
    fn frapcon_share_at_its_corners() {
        let f = FrapconRelocation::gap_share;
        assert_eq!(f(20e3, 0.0), 0.055);
        assert_eq!(f(60e3, 0.09), 0.055);
        let jump = f(20e3, 0.093_700_001) - 0.055;
        assert!(jump > 0.0 && jump < 5e-5, "{jump}");
        assert!((f(10e3, 10.0) - 0.400).abs() < 1e-15);
        assert!((f(30e3, 10.0) - 0.450).abs() < 1e-15);
        assert!((f(80e3, 60.0) - 0.500).abs() < 1e-15);
        let saturation = ((1.0 - 0.5795) / 0.2447f64).exp();
        assert!((saturation - 5.57).abs() < 0.01);
        assert!(f(20e3, 0.99 * saturation) < 0.4 && (f(20e3, saturation) - 0.4).abs() < 1e-12);
        let mut last = 0.0;
        for k in 0..200 {
            let v = f(20e3 + 200.0 * k as f64, 0.05 * k as f64);
            assert!(v >= last, "not monotone at step {k}");
            last = v;
        }
        let rod = RelocationInput {
            linear_power: 20e3,
            burnup: 10.0,
            cold_gap: 80e-6,
            pellet_radius: 4.1e-3,
        };
        assert!((FrapconRelocation.strain(&rod) * 4.1e-3 - 32e-6).abs() < 1e-18);
        assert_eq!(NoRelocation.strain(&rod), 0.0);
    }
}
