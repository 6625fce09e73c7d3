//! The contact scene's check, by section: the kind and the bodies, the interface's sides,
//! its law and search, and `[solve]` (`solve_spec.rs`, beside the section's keys). Each step returns the first value it refuses, so the
//! sections are checked in the file's order.

use std::path::Path;

use mortar_physics::laws::ExponentialPressure;

use super::{
    Component, ComponentValue, ContactInterfaceSpec, ContactSpec, ElasticBodySpec, LawSpec,
};
use crate::file::error::Errors;
use crate::file::two_bodies::{
    check_body_name, check_kind, check_search_radius, check_side_bodies,
};
use crate::file::{FileScene, SceneError};

impl ContactSpec {
    /// Checks values and cross-references that do not need the meshes.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming the key.
    pub(super) fn check_keys(&self, path: &Path) -> Result<(), SceneError> {
        let errors = Errors { path };
        check_kind(&errors, &self.kind, Self::KIND)?;
        if self.bodies.len() != 2 {
            return Err(errors.invalid(
                "bodies".into(),
                format!(
                    "a contact scene has exactly two bodies, found {}",
                    self.bodies.len()
                ),
            ));
        }
        for (name, b) in &self.bodies {
            check_body(&errors, name, b)?;
        }
        self.check_sides(&errors)?;
        self.contact.check_law(&errors)?;
        check_search_radius(&errors, "contact", self.contact.search_radius)?;
        self.solve.check(&errors)
    }

    /// `[contact]`'s slave and master name two different bodies of the scene.
    fn check_sides(&self, errors: &Errors) -> Result<(), SceneError> {
        let sides = [&self.contact.slave, &self.contact.master];
        check_side_bodies(errors, "contact", sides, &self.bodies, "bodies: ")?;
        if self.contact.slave.body == self.contact.master.body {
            return Err(errors.invalid(
                "contact.master.body".into(),
                "the slave and master sides are on two different bodies".into(),
            ));
        }
        Ok(())
    }
}

/// `[bodies.NAME]`: a file-safe name that is not an output's, an elastic material in range,
/// finite displacements given as a number or (for every component) an array, and tractions
/// of 2 or 3 finite components. Whether the components fit the mesh's dimension is checked
/// when the mesh is read.
fn check_body(errors: &Errors, name: &str, b: &ElasticBodySpec) -> Result<(), SceneError> {
    let key = |k: &str| format!("bodies.{name}.{k}");
    check_body_name(errors, name)?;
    if name == "report" || name == "interface" {
        return Err(errors.invalid(
            format!("bodies.{name}"),
            format!("\"{name}\" is reserved for {name}.json / {name}.vtu"),
        ));
    }
    let e = b.youngs_modulus;
    if !(e > 0.0 && e.is_finite()) {
        return Err(errors.invalid(
            key("youngs_modulus"),
            format!("{e} is not positive and finite"),
        ));
    }
    let nu = b.poisson_ratio;
    if !(nu > -1.0 && nu < 0.5) {
        return Err(errors.invalid(key("poisson_ratio"), format!("{nu} is not in (-1, 0.5)")));
    }
    for (i, d) in b.dirichlet.iter().enumerate() {
        let k = format!("bodies.{name}.dirichlet[{i}].value");
        match (&d.value, d.component) {
            (ComponentValue::Array(_), c) if c != Component::All => {
                return Err(errors.invalid(
                    k,
                    "an array is for component = \"all\"; give a number".into(),
                ))
            }
            (ComponentValue::Array(v), _) if v.iter().any(|x| !x.is_finite()) => {
                return Err(errors.invalid(k, format!("{v:?} is not finite")))
            }
            (ComponentValue::Number(x), _) if !x.is_finite() => {
                return Err(errors.invalid(k, format!("{x} is not finite")))
            }
            _ => {}
        }
    }
    for (i, t) in b.traction.iter().enumerate() {
        if !(t.value.len() == 2 || t.value.len() == 3) || t.value.iter().any(|x| !x.is_finite()) {
            return Err(errors.invalid(
                format!("bodies.{name}.traction[{i}].value"),
                format!("{:?} is not 2 or 3 finite numbers", t.value),
            ));
        }
    }
    Ok(())
}

impl ContactInterfaceSpec {
    /// The law's keys: `law` or `named_law` (not both; a name not empty), and the exponential
    /// law's three parameters given, in range, for it and for it alone. A law by name's own
    /// parameters are checked by the registry that makes it, when the scene runs.
    fn check_law(&self, errors: &Errors) -> Result<(), SceneError> {
        if let Some(named) = &self.named_law {
            if self.law != LawSpec::default() {
                return Err(errors.invalid(
                    "contact.named_law".into(),
                    "give either law or named_law, not both".into(),
                ));
            }
            // Unknown names and parameters are checked against the shipped laws when the
            // scene runs with them (a program's registry may know more).
            if named.name.is_empty() {
                return Err(errors.invalid("contact.named_law".into(), "the name is empty".into()));
            }
        }
        let parameters = [
            ("base_pressure", self.base_pressure),
            ("stiffness", self.stiffness),
            ("onset", self.onset),
        ];
        match self.law {
            // Exact contact, or a law by name: the exponential law's keys are refused rather
            // than passed over.
            _ if self.named_law.is_some() || self.law == LawSpec::Exact => {
                let by_name = if self.named_law.is_some() {
                    "; a law by name takes its parameters in named_law"
                } else {
                    ""
                };
                for (k, v) in parameters {
                    if v.is_some() {
                        return Err(errors.invalid(
                            format!("contact.{k}"),
                            format!(
                                "only the exponential law (law = \"exponential\") has it{by_name}"
                            ),
                        ));
                    }
                }
            }
            // The built-in exponential law.
            _ => {
                for (k, v) in parameters {
                    if v.is_none() {
                        return Err(errors.invalid(
                            format!("contact.{k}"),
                            "missing: the exponential law needs base_pressure, stiffness and onset"
                                .into(),
                        ));
                    }
                }
                if let Err(e) = ExponentialPressure::try_new(
                    self.base_pressure.unwrap_or(0.0),
                    self.stiffness.unwrap_or(0.0),
                    self.onset.unwrap_or(0.0),
                ) {
                    return Err(errors.invalid("contact.law".into(), e.to_string()));
                }
            }
        }
        Ok(())
    }
}
