//! Laws chosen at run time: `DynLaw`, an object-safe law with its name, and `LawRegistry`,
//! which makes the shipped and the user's laws by name from numeric parameters.

use std::collections::BTreeMap;
use std::fmt;
use std::sync::Arc;

use num_traits::Float;

use super::{
    cst, ConstraintLaw, ContactComplementarity, Dual, ExponentialContact, ExponentialPressure,
    FrapconRelocation, GapConductance, GasConductivity, LawError, LawPoint,
    MechanicalGapConductance, NoRelocation, RelocationModel, Tying,
};

/// The object-safe face of a [`ConstraintLaw`]: its residual at `f64` and in the dual numbers
/// of [`evaluate`](super::evaluate). Every `ConstraintLaw + Send + Sync` is one.
pub trait ObjectLaw: Send + Sync {
    /// The residual at `p`.
    fn residual_f64(&self, p: LawPoint<f64>) -> f64;
    /// The residual and its six partial derivatives at `p`.
    fn residual_dual6(&self, p: LawPoint<Dual<6>>) -> Dual<6>;
}

impl<L: ConstraintLaw + Send + Sync> ObjectLaw for L {
    fn residual_f64(&self, p: LawPoint<f64>) -> f64 {
        self.residual(p)
    }

    fn residual_dual6(&self, p: LawPoint<Dual<6>>) -> Dual<6> {
        self.residual(p)
    }
}

/// Any law behind one type, so that a scene or a program picks it at run time (from a
/// [`LawRegistry`], say) and the solvers, generic over [`ConstraintLaw`], take it as they take
/// a law's own type: its tangent through [`evaluate`](super::evaluate) is the wrapped law's,
/// exact. Its [`residual`](ConstraintLaw::residual) at other scalar types than `f64` and the
/// dual numbers of `evaluate` sees values only (no derivative).
///
/// ```
/// use mortar_physics::laws::{evaluate, DynLaw, ExponentialContact, LawPoint};
/// let law = DynLaw::new("exponential_contact", ExponentialContact::try_new(1e12, 5e-6).unwrap());
/// let p = LawPoint::new(4e-6, 0.0, 900.0).with_mechanics(4e-6, 0.0, 5e6);
/// let t = evaluate(&law, p).unwrap();
/// assert_eq!(law.name(), "exponential_contact");
/// assert!(t.d_gap > 0.0 && t.d_multiplier == 1.0);
/// ```
#[derive(Clone)]
pub struct DynLaw {
    name: String,
    law: Arc<dyn ObjectLaw>,
}

impl DynLaw {
    /// `law` under the name `name` (for reports).
    pub fn new(name: impl Into<String>, law: impl ConstraintLaw + Send + Sync + 'static) -> Self {
        Self {
            name: name.into(),
            law: Arc::new(law),
        }
    }

    /// The name.
    pub fn name(&self) -> &str {
        &self.name
    }
}

impl fmt::Debug for DynLaw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("DynLaw").field("name", &self.name).finish()
    }
}

impl ConstraintLaw for DynLaw {
    fn residual<S: Float>(&self, p: LawPoint<S>) -> S {
        let v = |x: S| x.to_f64().unwrap_or(f64::NAN);
        let r = self.law.residual_f64(LawPoint {
            gap: v(p.gap),
            multiplier: v(p.multiplier),
            temperature: v(p.temperature),
            normal_gap: v(p.normal_gap),
            contact_pressure: v(p.contact_pressure),
            gas_pressure: v(p.gas_pressure),
        });
        cst(r)
    }

    fn residual_dual(&self, p: LawPoint<Dual<6>>) -> Dual<6> {
        self.law.residual_dual6(p)
    }
}

/// The parameters of a law made by name: numbers by key (SI units).
pub type LawParameters = BTreeMap<String, f64>;

/// A maker of a law from its parameters.
type Maker = Arc<dyn Fn(&LawParameters) -> Result<DynLaw, LawError> + Send + Sync>;

/// Laws by name, made from their parameters: the shipped ones ([`with_shipped`](Self::with_shipped))
/// and a program's own ([`register`](Self::register)).
///
/// ```
/// use mortar_physics::laws::{evaluate, LawParameters, LawPoint, LawRegistry};
/// let registry = LawRegistry::with_shipped();
/// let params = LawParameters::from([("c".to_string(), 1e14)]);
/// let law = registry.make("contact_complementarity", &params).unwrap();
/// assert!(evaluate(&law, LawPoint::new(1e-6, 0.0, 300.0)).is_ok());
/// assert!(registry.make("no_such_law", &params).is_err());
/// ```
#[derive(Clone, Default)]
pub struct LawRegistry {
    makers: BTreeMap<String, Maker>,
    relocation: BTreeMap<String, Arc<dyn RelocationModel>>,
}

impl fmt::Debug for LawRegistry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("LawRegistry")
            .field("laws", &self.makers.keys().collect::<Vec<_>>())
            .field("relocation", &self.relocation.keys().collect::<Vec<_>>())
            .finish()
    }
}

/// `params[key]`, or an error naming the law and the key.
fn get(law: &'static str, params: &LawParameters, key: &str) -> Result<f64, LawError> {
    params
        .get(key)
        .copied()
        .ok_or_else(|| LawError::InvalidParameter {
            law,
            what: format!(
                "parameter {key:?} is missing (given: {:?})",
                params.keys().collect::<Vec<_>>()
            ),
        })
}

/// Refuses a parameter that the shipped law `law` does not take (`known`), so that a
/// misspelt one is not passed over for a default.
fn only(law: &'static str, params: &LawParameters, known: &[&str]) -> Result<(), LawError> {
    match params.keys().find(|k| !known.contains(&k.as_str())) {
        Some(k) => Err(LawError::InvalidParameter {
            law,
            what: format!("unknown parameter {k:?} (the law takes {known:?})"),
        }),
        None => Ok(()),
    }
}

/// The gas of a gap law: `gas_conductivity` (W/m/K) if given, else helium.
fn gas(params: &LawParameters) -> GasConductivity {
    params
        .get("gas_conductivity")
        .map_or(GasConductivity::HELIUM, |&k| GasConductivity::Constant(k))
}

impl LawRegistry {
    /// An empty registry.
    pub fn new() -> Self {
        Self::default()
    }

    /// The shipped laws, by name, with their parameters (SI units):
    ///
    /// - `tying`: none;
    /// - `gap_conductance`: `gap_width`, `roughness_fuel`, `roughness_cladding`,
    ///   `jump_distance`, optional `gas_conductivity` (helium otherwise);
    /// - `mechanical_gap_conductance`: `roughness_fuel`, `roughness_cladding`,
    ///   `jump_distance`, `contact_conductance`, optional `gas_conductivity`;
    /// - `exponential_pressure`: `base_pressure`, `stiffness`, `onset`;
    /// - `exponential_contact`: `stiffness`, `onset`;
    /// - `contact_complementarity`: `c`.
    ///
    /// A parameter a law does not take is refused, naming it. The relocation models:
    /// `none` ([`NoRelocation`]) and `frapcon` ([`FrapconRelocation`]).
    pub fn with_shipped() -> Self {
        let mut r = Self::new();
        r.register_relocation(NoRelocation);
        r.register_relocation(FrapconRelocation);
        r.register("tying", |p| {
            only("tying", p, &[])?;
            Ok(DynLaw::new("tying", Tying))
        });
        r.register("gap_conductance", |p| {
            let law = "gap conductance";
            only(
                law,
                p,
                &[
                    "gap_width",
                    "roughness_fuel",
                    "roughness_cladding",
                    "jump_distance",
                    "gas_conductivity",
                ],
            )?;
            Ok(DynLaw::new(
                "gap_conductance",
                GapConductance::ross_stoute(
                    get(law, p, "gap_width")?,
                    get(law, p, "roughness_fuel")?,
                    get(law, p, "roughness_cladding")?,
                    get(law, p, "jump_distance")?,
                    gas(p),
                )?,
            ))
        });
        r.register("mechanical_gap_conductance", |p| {
            let law = "mechanical gap conductance";
            only(
                law,
                p,
                &[
                    "roughness_fuel",
                    "roughness_cladding",
                    "jump_distance",
                    "contact_conductance",
                    "gas_conductivity",
                ],
            )?;
            Ok(DynLaw::new(
                "mechanical_gap_conductance",
                MechanicalGapConductance::try_new(
                    get(law, p, "roughness_fuel")?,
                    get(law, p, "roughness_cladding")?,
                    get(law, p, "jump_distance")?,
                    gas(p),
                    get(law, p, "contact_conductance")?,
                )?,
            ))
        });
        r.register("exponential_pressure", |p| {
            let law = "exponential pressure";
            only(law, p, &["base_pressure", "stiffness", "onset"])?;
            Ok(DynLaw::new(
                "exponential_pressure",
                ExponentialPressure::try_new(
                    get(law, p, "base_pressure")?,
                    get(law, p, "stiffness")?,
                    get(law, p, "onset")?,
                )?,
            ))
        });
        r.register("exponential_contact", |p| {
            let law = "exponential contact";
            only(law, p, &["stiffness", "onset"])?;
            Ok(DynLaw::new(
                "exponential_contact",
                ExponentialContact::try_new(get(law, p, "stiffness")?, get(law, p, "onset")?)?,
            ))
        });
        r.register("contact_complementarity", |p| {
            only("contact complementarity", p, &["c"])?;
            Ok(DynLaw::new(
                "contact_complementarity",
                ContactComplementarity::try_new(get("contact complementarity", p, "c")?)?,
            ))
        });
        r
    }

    /// Registers (or replaces) the law `name`, made by `make` from its parameters.
    pub fn register(
        &mut self,
        name: impl Into<String>,
        make: impl Fn(&LawParameters) -> Result<DynLaw, LawError> + Send + Sync + 'static,
    ) -> &mut Self {
        self.makers.insert(name.into(), Arc::new(make));
        self
    }

    /// Registers (or replaces) a relocation model under its [`name`](RelocationModel::name),
    /// for scene files to name (`[model] relocation` of the pellet).
    ///
    /// ```
    /// use mortar_physics::laws::{LawRegistry, RelocationInput, RelocationModel};
    /// #[derive(Debug)]
    /// struct Half;
    /// impl RelocationModel for Half {
    ///     fn name(&self) -> &str { "half" }
    ///     fn strain(&self, rod: &RelocationInput) -> f64 { 0.5 * rod.cold_gap / rod.pellet_radius }
    /// }
    /// let mut registry = LawRegistry::with_shipped();
    /// registry.register_relocation(Half);
    /// assert_eq!(registry.relocation_names(), ["frapcon", "half", "none"]);
    /// assert!(registry.relocation("half").is_ok() && registry.relocation("escore").is_err());
    /// ```
    pub fn register_relocation(&mut self, model: impl RelocationModel + 'static) -> &mut Self {
        self.relocation
            .insert(model.name().to_string(), Arc::new(model));
        self
    }

    /// The names of the relocation models, sorted.
    pub fn relocation_names(&self) -> Vec<&str> {
        self.relocation.keys().map(String::as_str).collect()
    }

    /// The relocation model `name`.
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] for an unknown name, listing the known ones.
    pub fn relocation(&self, name: &str) -> Result<Arc<dyn RelocationModel>, LawError> {
        self.relocation
            .get(name)
            .cloned()
            .ok_or_else(|| LawError::InvalidParameter {
                law: "relocation",
                what: format!(
                    "no relocation model named {name:?} (known: {:?})",
                    self.relocation_names()
                ),
            })
    }

    /// The names, sorted.
    pub fn names(&self) -> Vec<&str> {
        self.makers.keys().map(String::as_str).collect()
    }

    /// The law `name` made from `params`.
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] for an unknown name (listing the known ones), a missing
    /// parameter, a parameter a shipped law does not take, or a value the law refuses.
    pub fn make(&self, name: &str, params: &LawParameters) -> Result<DynLaw, LawError> {
        match self.makers.get(name) {
            Some(make) => make(params),
            None => Err(LawError::InvalidParameter {
                law: "registry",
                what: format!("no law named {name:?} (known: {:?})", self.names()),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::laws::evaluate;

    /// Every shipped law made by name evaluates, value and tangent, as the law itself, bit for
    /// bit, at points on both sides of its kinks.
    #[test]
    fn shipped_laws_by_name_are_the_laws_themselves() {
        let r = LawRegistry::with_shipped();
        let params = |kv: &[(&str, f64)]| -> LawParameters {
            kv.iter().map(|(k, v)| (k.to_string(), *v)).collect()
        };
        let surfaces = [
            ("roughness_fuel", 2e-6),
            ("roughness_cladding", 1e-6),
            ("jump_distance", 10e-6),
        ];
        let gap = [&surfaces[..], &[("gap_width", 20e-6)]].concat();
        let mechanical_gap = [&surfaces[..], &[("contact_conductance", 1e-4)]].concat();
        let cases: Vec<(DynLaw, Box<dyn ObjectLaw>)> = vec![
            (r.make("tying", &params(&[])).unwrap(), Box::new(Tying)),
            (
                r.make("gap_conductance", &params(&gap)).unwrap(),
                Box::new(
                    GapConductance::ross_stoute(20e-6, 2e-6, 1e-6, 10e-6, GasConductivity::HELIUM)
                        .unwrap(),
                ),
            ),
            (
                r.make("mechanical_gap_conductance", &params(&mechanical_gap))
                    .unwrap(),
                Box::new(
                    MechanicalGapConductance::try_new(
                        2e-6,
                        1e-6,
                        10e-6,
                        GasConductivity::HELIUM,
                        1e-4,
                    )
                    .unwrap(),
                ),
            ),
            (
                r.make(
                    "exponential_pressure",
                    &params(&[("base_pressure", 2e6), ("stiffness", 1e12), ("onset", 5e-6)]),
                )
                .unwrap(),
                Box::new(ExponentialPressure::try_new(2e6, 1e12, 5e-6).unwrap()),
            ),
            (
                r.make(
                    "exponential_contact",
                    &params(&[("stiffness", 1e12), ("onset", 5e-6)]),
                )
                .unwrap(),
                Box::new(ExponentialContact::try_new(1e12, 5e-6).unwrap()),
            ),
            (
                r.make("contact_complementarity", &params(&[("c", 1e14)]))
                    .unwrap(),
                Box::new(ContactComplementarity::try_new(1e14).unwrap()),
            ),
        ];
        for (made, own) in &cases {
            for g in [-1e-6, 0.0, 3e-6, 8e-6] {
                let p = LawPoint::new(g, 2e5, 900.0).with_mechanics(g, 2e6, 5e6);
                let a = evaluate(made, p).unwrap();
                let own_dual = own.residual_dual6(LawPoint {
                    gap: Dual::variable(p.gap, 0),
                    multiplier: Dual::variable(p.multiplier, 1),
                    temperature: Dual::variable(p.temperature, 2),
                    normal_gap: Dual::variable(p.normal_gap, 3),
                    contact_pressure: Dual::variable(p.contact_pressure, 4),
                    gas_pressure: Dual::variable(p.gas_pressure, 5),
                });
                assert_eq!(a.value, own_dual.re, "{}", made.name());
                assert_eq!(
                    [a.d_gap, a.d_multiplier, a.d_temperature, a.d_normal_gap],
                    [
                        own_dual.eps[0],
                        own_dual.eps[1],
                        own_dual.eps[2],
                        own_dual.eps[3]
                    ],
                    "{}",
                    made.name()
                );
                assert_eq!(made.residual(p), own.residual_f64(p));
            }
        }
        assert_eq!(r.names().len(), 6);
        let e = r
            .make("exponential_contact", &params(&[("onset", 5e-6)]))
            .unwrap_err();
        assert!(e.to_string().contains("stiffness"), "{e}");
        // A parameter the law does not take (here misspelt) is refused, naming it, rather
        // than passed over for a default.
        let e = r
            .make(
                "mechanical_gap_conductance",
                &params(&[&mechanical_gap[..], &[("gas_conductivty", 0.3)]].concat()),
            )
            .unwrap_err();
        assert!(
            e.to_string()
                .contains("unknown parameter \"gas_conductivty\""),
            "{e}"
        );
    }
}
