//! The linear solver's keys of the scene files' `[solve]` tables (`backend`,
//! `linear_tolerance`, `petsc_options`): declared once for every kind that has them
//! (`solve_table!`), with their pick and their check ([`LinearSolverKeys`]).

use crate::file::error::Errors;
use crate::file::SceneError;
use crate::linear_solver::{AutoSwitch, BackendChoice, PickedSolver};

/// Declares a scene's `[solve]` table `$name` of the scene kind `$kind` (serde, unknown keys
/// refused) with the fields given and then the linear solver's keys `backend`,
/// `linear_tolerance` and `petsc_options`, and its [`LinearSolverKeys`]. A macro for the
/// reason of `mortar::coupling_keys!`: a flattened struct would lose the line of a bad value
/// and the list of the accepted keys in the scene files' messages.
macro_rules! solve_table {
    (
        $(#[$meta:meta])*
        pub struct $name:ident of $kind:literal {
            $( $(#[$field_meta:meta])* pub $field:ident : $ty:ty, )*
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct $name {
            $( $(#[$field_meta])* pub $field: $ty, )*
            /// Where the systems go ([`crate::linear_solver`]).
            #[serde(default, skip_serializing_if = "crate::linear_solver::BackendChoice::is_auto")]
            pub backend: $crate::linear_solver::BackendChoice,
            /// The Krylov solves' relative tolerance (PETSc).
            #[serde(default, skip_serializing_if = "Option::is_none")]
            pub linear_tolerance: Option<f64>,
            /// Further PETSc options (`-ksp_monitor ...`).
            #[serde(default, skip_serializing_if = "String::is_empty")]
            pub petsc_options: String,
        }

        impl $crate::file::solve_keys::LinearSolverKeys for $name {
            const KIND: &'static str = $kind;

            fn linear_keys(&self) -> ($crate::linear_solver::BackendChoice, Option<f64>, &str) {
                (self.backend, self.linear_tolerance, &self.petsc_options)
            }
        }
    };
}

pub(crate) use solve_table;

/// A scene's `[solve]` with the keys `backend`, `linear_tolerance` and `petsc_options`: their
/// pick and their check, written once for every scene kind that has them.
pub(crate) trait LinearSolverKeys {
    /// The scene kind, for its [`AutoSwitch`].
    const KIND: &'static str;

    /// `backend`, `linear_tolerance` and `petsc_options`.
    fn linear_keys(&self) -> (BackendChoice, Option<f64>, &str);

    /// The linear solver of these keys for a system of `unknowns` unknowns in dimension `dim`
    /// (`"auto"` by [`AutoSwitch::of`]).
    ///
    /// # Errors
    /// The key and what is wrong (see [`PickedSolver::pick`]).
    fn linear_solver(
        &self,
        unknowns: usize,
        dim: usize,
    ) -> Result<PickedSolver, (&'static str, String)> {
        let (backend, tolerance, options) = self.linear_keys();
        let switch = AutoSwitch::of(Self::KIND, dim);
        PickedSolver::pick(backend, tolerance, options, unknowns, switch)
    }

    /// The keys as they would be picked for a system of PETSc's size: PETSc asked for in a
    /// build without it, or a tolerance out of range, fails before the meshes are read.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming the key.
    fn check_linear_keys(&self, errors: &Errors) -> Result<(), SceneError> {
        self.linear_solver(usize::MAX, 3)
            .map(|_| ())
            .map_err(|(key, what)| errors.invalid(key.into(), what))
    }
}
