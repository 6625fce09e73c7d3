//! What `[solve]` says: its keys with their defaults, checked, and the tied system's options
//! they make. A key of the section is added here, beside its check and its use.

use mortar_physics::tied::{FormulationChoice, TiedOptions};
use serde::{Deserialize, Serialize};

use super::MAX_STEPS;
use crate::file::error::Errors;
use crate::file::solve_keys::{solve_table, LinearSolverKeys};
use crate::file::SceneError;

/// Steady or transient.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// The steady state.
    #[default]
    Steady,
    /// Backward Euler from the initial temperatures.
    Transient,
}

/// The formulation of the tied system.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FormulationSpec {
    /// The dual condensation when D is diagonal, else the saddle point.
    #[default]
    Auto,
    /// The saddle point (sparse LU).
    SaddlePoint,
    /// The dual condensation (sparse Cholesky); an error if D is not diagonal.
    DualCondensed,
}

solve_table! {
    /// The settings of the solve.
    #[derive(Default)]
    pub struct SolveSpec of "tied_heat" {
        /// Steady or transient.
        #[serde(default)]
        pub mode: Mode,
        /// The time step of a transient solve.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub dt: Option<f64>,
        /// The number of time steps of a transient solve.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub steps: Option<usize>,
        /// The formulation.
        #[serde(default)]
        pub formulation: FormulationSpec,
    }
}

impl SolveSpec {
    /// `[solve]`: a steady solve has no time step; a transient one has a positive finite
    /// `dt` and from 1 to [`MAX_STEPS`] steps; the linear solver's keys as
    /// picked for a system of PETSc's size (PETSc asked for in a build without it, or a
    /// tolerance out of range, fails before the meshes are read).
    pub(super) fn check(&self, errors: &Errors) -> Result<(), SceneError> {
        match self.mode {
            Mode::Steady => {
                for (k, set) in [("dt", self.dt.is_some()), ("steps", self.steps.is_some())] {
                    if set {
                        return Err(errors.invalid(
                            format!("solve.{k}"),
                            "only a transient solve (mode = \"transient\") has a time step".into(),
                        ));
                    }
                }
            }
            Mode::Transient => {
                match self.dt {
                    Some(dt) if dt > 0.0 && dt.is_finite() => {}
                    Some(dt) => {
                        return Err(errors.invalid(
                            "solve.dt".into(),
                            format!("{dt} is not positive and finite"),
                        ))
                    }
                    None => {
                        return Err(errors.invalid(
                            "solve.dt".into(),
                            "missing: a transient solve needs dt".into(),
                        ))
                    }
                }
                match self.steps {
                    Some(s) if s > MAX_STEPS => {
                        return Err(errors.invalid(
                            "solve.steps".into(),
                            format!("{s} steps: at most {MAX_STEPS} (as the pellet scene)"),
                        ))
                    }
                    Some(s) if s >= 1 => {}
                    _ => {
                        return Err(errors.invalid(
                            "solve.steps".into(),
                            "a transient solve needs steps >= 1".into(),
                        ))
                    }
                }
            }
        }
        self.check_linear_keys(errors)
    }

    /// The tied system's options of these keys: the formulation.
    pub(super) fn tied_options(&self) -> TiedOptions {
        TiedOptions::default().with_formulation(match self.formulation {
            FormulationSpec::Auto => FormulationChoice::Auto,
            FormulationSpec::SaddlePoint => FormulationChoice::SaddlePoint,
            FormulationSpec::DualCondensed => FormulationChoice::DualCondensed,
        })
    }

    /// A transient solve's time step and step count (checked to be given: 1 and 1 stand in
    /// otherwise).
    pub(super) fn time_steps(&self) -> (f64, usize) {
        (self.dt.unwrap_or(1.0), self.steps.unwrap_or(1))
    }
}
