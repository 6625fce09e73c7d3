//! What `[solve]` says: its keys with their defaults, checked, and the contact solver's
//! options they make. A key of the section is added here, beside its check and its use.

use mortar_physics::contact::ContactOptions;
use serde::{Deserialize, Serialize};

use crate::linear_solver::{BackendChoice, LinearSolverKeys};

use crate::file::error::Errors;
use crate::file::SceneError;

/// The settings of the solve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSolveSpec {
    /// Load increments.
    #[serde(default = "one")]
    pub load_steps: usize,
    /// Newton steps allowed per load step.
    #[serde(default = "thirty")]
    pub max_newton_steps: usize,
    /// The relative tolerance of Newton's iteration.
    #[serde(default = "tol")]
    pub tolerance: f64,
    /// Where the Newton systems go ([`crate::linear_solver`]).
    #[serde(default, skip_serializing_if = "BackendChoice::is_auto")]
    pub backend: BackendChoice,
    /// The Krylov solves' relative tolerance (PETSc).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub linear_tolerance: Option<f64>,
    /// Further PETSc options (`-ksp_monitor ...`).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub petsc_options: String,
}

fn one() -> usize {
    1
}
fn thirty() -> usize {
    30
}
fn tol() -> f64 {
    1e-10
}

impl Default for ContactSolveSpec {
    fn default() -> Self {
        Self {
            load_steps: 1,
            max_newton_steps: 30,
            tolerance: 1e-10,
            backend: BackendChoice::Auto,
            linear_tolerance: None,
            petsc_options: String::new(),
        }
    }
}

impl ContactSolveSpec {
    /// `[solve]`: at least one load step and one Newton step, a positive finite tolerance.
    pub(super) fn check(&self, errors: &Errors) -> Result<(), SceneError> {
        if self.load_steps == 0 {
            return Err(errors.invalid("solve.load_steps".into(), "must be at least 1".into()));
        }
        if self.max_newton_steps == 0 {
            return Err(
                errors.invalid("solve.max_newton_steps".into(), "must be at least 1".into())
            );
        }
        if !(self.tolerance > 0.0 && self.tolerance.is_finite()) {
            return Err(errors.invalid(
                "solve.tolerance".into(),
                format!("{} is not positive and finite", self.tolerance),
            ));
        }
        self.check_linear_keys(errors)
    }

    /// The contact solver's options of these keys.
    pub(super) fn options(&self) -> ContactOptions {
        ContactOptions {
            load_steps: self.load_steps,
            max_newton_steps: self.max_newton_steps,
            tolerance: self.tolerance,
        }
    }
}

impl LinearSolverKeys for ContactSolveSpec {
    const KIND: &'static str = "contact";

    fn linear_keys(&self) -> (BackendChoice, Option<f64>, &str) {
        (self.backend, self.linear_tolerance, &self.petsc_options)
    }
}
