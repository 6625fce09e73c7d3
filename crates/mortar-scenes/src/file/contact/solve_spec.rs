//! What `[solve]` says: its keys with their defaults, checked, and the contact solver's
//! options they make. A key of the section is added here, beside its check and its use.

use mortar_physics::contact::ContactOptions;

use crate::file::solve_keys::{solve_table, LinearSolverKeys};
use crate::linear_solver::BackendChoice;

use crate::file::error::Errors;
use crate::file::SceneError;

solve_table! {
    /// The settings of the solve.
    pub struct ContactSolveSpec of "contact" {
        /// Load increments.
        #[serde(default = "one")]
        pub load_steps: usize,
        /// Newton steps allowed per load step.
        #[serde(default = "thirty")]
        pub max_newton_steps: usize,
        /// The relative tolerance of Newton's iteration.
        #[serde(default = "tol")]
        pub tolerance: f64,
    }
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
