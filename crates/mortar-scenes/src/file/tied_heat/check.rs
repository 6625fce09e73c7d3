//! The tied heat scene's check, by section: the kind and dimension, the bodies, the
//! interface, and `[solve]` (`solve_spec.rs`, beside the section's keys). Each step returns
//! the first value it refuses, so the sections are checked in the file's order.

use std::path::Path;

use super::{BodySpec, Mode, TiedHeatSpec};
use crate::file::error::Errors;
use crate::file::two_bodies::{
    body_names, check_body_name, check_kind, check_search_radius, check_side_bodies,
};
use crate::file::{FileScene, SceneError};

impl TiedHeatSpec {
    /// Checks values and cross-references: the kind, two bodies with file-safe names,
    /// positive conductivities, interface sides naming two different bodies, the solve mode's
    /// keys.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming the key.
    pub(super) fn check_keys(&self, path: &Path) -> Result<(), SceneError> {
        let errors = Errors { path };
        check_kind(&errors, &self.kind, Self::KIND)?;
        if let Some(d) = self.dimension {
            if d != 2 && d != 3 {
                return Err(errors.invalid("dimension".into(), format!("{d} is not 2 or 3")));
            }
        }
        if self.bodies.len() != 2 {
            return Err(errors.invalid(
                "bodies".into(),
                format!(
                    "a tied heat scene has exactly two bodies, found {} ({})",
                    self.bodies.len(),
                    body_names(&self.bodies)
                ),
            ));
        }
        for (name, b) in &self.bodies {
            self.check_body(&errors, name, b)?;
        }
        self.check_interface(&errors)?;
        self.solve.check(&errors)
    }

    /// `[bodies.NAME]`: a file-safe name that is not `report`, a positive finite
    /// conductivity, a non-negative finite `rho_cp` (given, for a transient solve), and
    /// finite sources, initial temperatures, temperatures and fluxes.
    fn check_body(&self, errors: &Errors, name: &str, b: &BodySpec) -> Result<(), SceneError> {
        let key = |k: &str| format!("bodies.{name}.{k}");
        check_body_name(errors, name)?;
        if name == "report" {
            return Err(errors.invalid(
                "bodies.report".into(),
                "\"report\" is reserved for report.json".into(),
            ));
        }
        if !(b.conductivity > 0.0 && b.conductivity.is_finite()) {
            return Err(errors.invalid(
                key("conductivity"),
                format!("{} is not positive and finite", b.conductivity),
            ));
        }
        if let Some(c) = b.rho_cp {
            if !(c >= 0.0 && c.is_finite()) {
                return Err(
                    errors.invalid(key("rho_cp"), format!("{c} is not non-negative and finite"))
                );
            }
        }
        for (k, v) in [("source", b.source), ("initial", b.initial)] {
            if !v.is_finite() {
                return Err(errors.invalid(key(k), format!("{v} is not finite")));
            }
        }
        for (i, d) in b.dirichlet.iter().enumerate() {
            if !d.value.is_finite() {
                return Err(errors.invalid(
                    format!("bodies.{name}.dirichlet[{i}].value"),
                    format!("{} is not finite", d.value),
                ));
            }
        }
        for (i, n) in b.neumann.iter().enumerate() {
            if !n.flux.is_finite() {
                return Err(errors.invalid(
                    format!("bodies.{name}.neumann[{i}].flux"),
                    format!("{} is not finite", n.flux),
                ));
            }
        }
        if self.solve.mode == Mode::Transient && b.rho_cp.is_none() {
            return Err(errors.invalid(
                key("rho_cp"),
                "missing: a transient solve needs the volumetric heat capacity".into(),
            ));
        }
        Ok(())
    }

    /// `[interface]`: its sides name bodies of the scene, two different ones, and its search
    /// radius is in range.
    fn check_interface(&self, errors: &Errors) -> Result<(), SceneError> {
        let sides = [&self.interface.slave, &self.interface.master];
        check_side_bodies(errors, "interface", sides, &self.bodies, "the bodies are ")?;
        check_search_radius(errors, "interface", self.interface.search_radius)?;
        if self.interface.slave.body == self.interface.master.body {
            return Err(errors.invalid(
                "interface".into(),
                format!(
                    "slave and master are both on body \"{}\"; they must be the two bodies",
                    self.interface.slave.body
                ),
            ));
        }
        Ok(())
    }
}
