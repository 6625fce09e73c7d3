//! `[solve] backend`, `linear_tolerance` and `petsc_options`: which linear solver a scene's
//! systems go to, picked and said.
//!
//! `backend = "direct"` is the sparse direct solve of `mortar-fem` (faer's Cholesky or LU,
//! by body where that pays): exact to rounding, its memory growing as the fill (about
//! `n^(4/3)` in 3D). `"petsc"` is PETSc's Krylov methods with algebraic multigrid
//! ([`PetscBackend::automatic`]: CG with GAMG for a symmetric positive definite system, the
//! rigid motions of a displacement field as GAMG's near null space; GMRES with a Schur
//! fieldsplit for a saddle point), to the relative tolerance `linear_tolerance` (default
//! [`DEFAULT_LINEAR_TOLERANCE`]), in a build with the `petsc` feature. `"auto"` (the default)
//! is the direct solve below the [`AutoSwitch`] measured for the scene's kind and dimension,
//! PETSc from there on when the build has it.

use std::sync::Arc;

use mortar::petsc::{PetscBackend, SolveReport};
use mortar_fem::linalg::{FaerSolver, SparseSolver};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};

/// `[solve] backend`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BackendChoice {
    /// The direct solve below the scene's [`AutoSwitch`], PETSc above when built with it.
    #[default]
    Auto,
    /// The sparse direct solve.
    Direct,
    /// PETSc's Krylov methods with algebraic multigrid.
    Petsc,
}

impl BackendChoice {
    /// Whether this is the default, `"auto"`.
    pub fn is_auto(&self) -> bool {
        *self == BackendChoice::Auto
    }
}

/// The unknowns from which `backend = "auto"` picks PETSc for a 3D contact scene (when the
/// build has it): on the 3D contact benchmark (`examples/bench_contact.rs`,
/// docs/performance.md) the direct solve is the quicker at 9.4e4 unknowns and PETSc's CG with
/// GAMG at 3.0e5 (about half the time, a third of the memory); the switch lies between.
pub const AUTO_PETSC_MIN: usize = 200_000;

/// The unknowns from which `backend = "auto"` picks PETSc for a 3D tied heat scene: on the 3D
/// tied heat benchmark (`examples/bench_tied_heat.rs --dim 3`) the direct solve is the quicker
/// at 1.1e4 unknowns (0.09 s against 0.41 s) and PETSc's CG with GAMG at 3.4e4 (0.69 s against
/// 0.80 s), 0.28 of the time at 2.6e5; the switch lies between.
pub const AUTO_PETSC_MIN_TIED_HEAT_3D: usize = 25_000;

/// Where `backend = "auto"` switches from the direct solve to PETSc for a kind of system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AutoSwitch {
    /// The unknowns from which PETSc is picked; `None`: the direct solve at every size.
    pub min_unknowns: Option<usize>,
    /// What the switch rests on, for the report.
    pub measured: &'static str,
}

impl AutoSwitch {
    /// The switch of a scene of `kind` (`"contact"`, `"tied_heat"`) in dimension `dim`: in 3D
    /// from [`AUTO_PETSC_MIN`] (contact) or [`AUTO_PETSC_MIN_TIED_HEAT_3D`] (tied heat)
    /// unknowns; in 2D never, the direct solve's fill growing only as `n log n` (tied heat
    /// at 1.0e6 unknowns: the direct solve in 0.5 to 0.6 of PETSc's time over two runs of
    /// `bench_tied_heat`, docs/bench_tied_heat.json; 2D contact through PETSc is not
    /// measured).
    pub fn of(kind: &str, dim: usize) -> Self {
        match (kind, dim) {
            ("pellet", _) => Self {
                min_unknowns: None,
                measured: "the pellet, whose sizes the direct solve and JFNK serve (PETSc when \
                           asked for)",
            },
            ("tied_heat", 3) => Self {
                min_unknowns: Some(AUTO_PETSC_MIN_TIED_HEAT_3D),
                measured: "3D tied heat, where PETSc's multigrid is the quicker from about 3e4",
            },
            (_, 3) => Self {
                min_unknowns: Some(AUTO_PETSC_MIN),
                measured: "3D contact, where PETSc's multigrid is the quicker and the leaner \
                           from about 2e5",
            },
            _ => Self {
                min_unknowns: None,
                measured: "2D, the quicker at every size measured (tied heat at 1e6 unknowns: \
                           about half PETSc's time)",
            },
        }
    }
}

/// The Krylov solves' relative tolerance unless `[solve] linear_tolerance` says otherwise:
/// well below the Newton tolerance of the contact scenes (1e-10 of the residual), so that
/// the Newton iteration counts stay the direct solve's.
pub const DEFAULT_LINEAR_TOLERANCE: f64 = 1e-12;

/// The linear solver a scene's systems go to, with why it was picked.
#[derive(Debug, Clone)]
pub struct PickedSolver {
    /// `"direct"` or `"petsc"`.
    pub name: &'static str,
    /// Why.
    pub why: String,
    petsc: Option<Arc<PetscBackend>>,
}

impl PickedSolver {
    /// The direct solve, for `why`.
    pub fn direct(why: impl Into<String>) -> Self {
        Self {
            name: "direct",
            why: why.into(),
            petsc: None,
        }
    }

    /// Picks the backend for `unknowns` unknowns: `choice` with the tolerance and options of
    /// the scene (`None`: the defaults), `"auto"` by `switch`.
    ///
    /// # Errors
    /// A message (for the key `solve.backend`) if PETSc is asked for in a build without it,
    /// saying how to get it; for `solve.linear_tolerance` if it is not in (0, 1).
    pub fn pick(
        choice: BackendChoice,
        linear_tolerance: Option<f64>,
        petsc_options: &str,
        unknowns: usize,
        switch: AutoSwitch,
    ) -> Result<Self, (&'static str, String)> {
        let rtol = linear_tolerance.unwrap_or(DEFAULT_LINEAR_TOLERANCE);
        if !(rtol > 0.0 && rtol < 1.0) {
            return Err(("solve.linear_tolerance", format!("{rtol} is not in (0, 1)")));
        }
        let petsc = |why: String| Self {
            name: "petsc",
            why,
            petsc: Some(Arc::new(PetscBackend::automatic(rtol, petsc_options))),
        };
        match choice {
            BackendChoice::Direct => Ok(Self::direct("asked for (backend = \"direct\")")),
            BackendChoice::Petsc if !mortar::petsc::is_built() => Err((
                "solve.backend",
                "\"petsc\": this build has no PETSc; install it (Debian: apt-get install \
                 petsc-dev libclang-dev pkg-config) and build with `--features petsc` \
                 (docs/solvers.md)"
                    .into(),
            )),
            BackendChoice::Petsc => Ok(petsc(format!(
                "asked for (backend = \"petsc\"), relative tolerance {rtol:e}"
            ))),
            BackendChoice::Auto => match switch.min_unknowns {
                None => Ok(Self::direct(format!(
                    "auto: the direct solve in {}",
                    switch.measured
                ))),
                Some(min) if unknowns < min => Ok(Self::direct(format!(
                    "auto: {unknowns} unknowns, below {min}, where the direct solve is the \
                     quicker ({})",
                    switch.measured
                ))),
                Some(_) if !mortar::petsc::is_built() => Ok(Self::direct(format!(
                    "auto: {unknowns} unknowns, PETSc's size, but this build has no PETSc \
                     (`--features petsc`)"
                ))),
                Some(min) => Ok(petsc(format!(
                    "auto: {unknowns} unknowns, at least {min} ({}); relative tolerance {rtol:e}",
                    switch.measured
                ))),
            },
        }
    }

    /// The PETSc backend, shared, when it was picked: for a solver state that keeps it.
    pub fn shared(&self) -> Option<Arc<dyn SparseSolver>> {
        self.petsc
            .as_ref()
            .map(|p| Arc::clone(p) as Arc<dyn SparseSolver>)
    }

    /// The solver to give the physics: `None` for the direct solve (the physics' own, by
    /// body where that pays), PETSc otherwise.
    pub fn solver(&self) -> Option<&dyn SparseSolver> {
        self.petsc.as_deref().map(|p| p as &dyn SparseSolver)
    }

    /// The solver, the direct one included.
    pub fn solver_or_direct(&self) -> &dyn SparseSolver {
        self.solver().unwrap_or(&FaerSolver)
    }

    /// PETSc's reports of the solves so far (none for the direct solve).
    pub fn reports(&self) -> Vec<SolveReport> {
        self.petsc.as_ref().map(|p| p.reports()).unwrap_or_default()
    }

    /// The PETSc set-ups and solves that failed so far, as their messages (a symmetric solve
    /// that the physics then retried as a general one, say).
    pub fn failures(&self) -> Vec<String> {
        self.petsc
            .as_ref()
            .map(|p| p.failures())
            .unwrap_or_default()
    }

    /// The report's `"linear_solver"` entry: the backend, why, and per PETSc solve the
    /// method, preconditioner, iterations and residual.
    pub fn json(&self) -> Value {
        let reports = self.reports();
        let iterations: Vec<usize> = reports.iter().map(|r| r.iterations).collect();
        json!({
            "backend": self.name,
            "why": self.why,
            "solves": reports.len(),
            "iterations": iterations,
            "methods": methods(&reports),
            "failed": self.failures(),
            "largest_relative_residual": reports
                .iter()
                .map(|r| r.relative_residual)
                .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r)))),
        })
    }

    /// One line for a summary: `linear solver: petsc (why): solves 12, cg+gamg, iterations 9
    /// to 14`.
    pub fn summary_line(&self) -> String {
        let reports = self.reports();
        let mut line = format!("linear solver: {} ({})", self.name, self.why);
        if let (Some(lo), Some(hi)) = (
            reports.iter().map(|r| r.iterations).min(),
            reports.iter().map(|r| r.iterations).max(),
        ) {
            line.push_str(&format!(
                ": solves {}, {}, iterations {lo} to {hi}",
                reports.len(),
                methods(&reports).join(", ")
            ));
        }
        let failed = self.failures().len();
        if failed > 0 {
            line.push_str(&format!(
                "; {failed} failed (in report.json's linear_solver.failed), retried"
            ));
        }
        line
    }
}

/// The methods that ran, `ksp+pc` as PETSc names them, each once, in order.
fn methods(reports: &[SolveReport]) -> Vec<String> {
    let set: std::collections::BTreeSet<String> = reports
        .iter()
        .map(|r| format!("{}+{}", r.ksp_type, r.pc_type))
        .collect();
    set.into_iter().collect()
}

/// The scene file `text` with its linear solver's `backend` set to `backend`: `[solver]
/// backend` for a pellet scene, `[solve] backend` for the others (`mortar run --backend`).
/// The text is parsed and written back, so that its comments are dropped.
///
/// # Errors
/// The parser's message for a text that is not TOML.
pub fn with_backend(text: &str, backend: BackendChoice) -> Result<String, String> {
    let mut doc: toml::Table = toml::from_str(text).map_err(|e| e.to_string())?;
    let section = match doc.get("kind").and_then(toml::Value::as_str) {
        Some("pellet") => "solver",
        _ => "solve",
    };
    let table = doc
        .entry(section)
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    let toml::Value::Table(table) = table else {
        return Err(format!("`{section}` is not a table"));
    };
    let name = toml::Value::try_from(backend).map_err(|e| e.to_string())?;
    table.insert("backend".into(), name);
    toml::to_string(&doc).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pick_follows_the_choice_the_size_and_the_build() {
        let contact = AutoSwitch::of("contact", 3);
        let direct =
            PickedSolver::pick(BackendChoice::Direct, None, "", 10_000_000, contact).unwrap();
        assert_eq!(direct.name, "direct");
        assert!(direct.solver().is_none());
        let small = PickedSolver::pick(BackendChoice::Auto, None, "", 1_000, contact).unwrap();
        assert_eq!(small.name, "direct");
        assert!(small.why.contains("below"), "{}", small.why);
        let large =
            PickedSolver::pick(BackendChoice::Auto, None, "", AUTO_PETSC_MIN, contact).unwrap();
        let asked = PickedSolver::pick(BackendChoice::Petsc, Some(1e-9), "", 10, contact);
        // In 2D the direct solve at any size; in 3D tied heat from its own switch.
        let flat = AutoSwitch::of("tied_heat", 2);
        let flat = PickedSolver::pick(BackendChoice::Auto, None, "", usize::MAX, flat).unwrap();
        assert_eq!(flat.name, "direct");
        assert!(flat.why.contains("2D"), "{}", flat.why);
        let heat = AutoSwitch::of("tied_heat", 3);
        let heat = PickedSolver::pick(BackendChoice::Auto, None, "", 30_000, heat).unwrap();
        if mortar::petsc::is_built() {
            assert_eq!(heat.name, "petsc");
            assert_eq!(large.name, "petsc");
            let asked = asked.unwrap();
            assert_eq!(asked.name, "petsc");
            assert!(asked.why.contains("1e-9"), "{}", asked.why);
        } else {
            assert_eq!(large.name, "direct");
            assert!(large.why.contains("no PETSc"), "{}", large.why);
            let (key, what) = asked.unwrap_err();
            assert_eq!(key, "solve.backend");
            assert!(what.contains("--features petsc"), "{what}");
        }
        let (key, _) =
            PickedSolver::pick(BackendChoice::Petsc, Some(0.0), "", 10, contact).unwrap_err();
        assert_eq!(key, "solve.linear_tolerance");
    }

    #[test]
    fn with_backend_sets_the_key_of_the_kind() {
        let contact = "kind = \"contact\"\n[solve]\nload_steps = 2\n";
        let out: toml::Table =
            toml::from_str(&with_backend(contact, BackendChoice::Petsc).unwrap()).unwrap();
        assert_eq!(out["solve"]["backend"].as_str(), Some("petsc"));
        assert_eq!(out["solve"]["load_steps"].as_integer(), Some(2));
        let pellet = "kind = \"pellet\"\n";
        let out: toml::Table =
            toml::from_str(&with_backend(pellet, BackendChoice::Direct).unwrap()).unwrap();
        assert_eq!(out["solver"]["backend"].as_str(), Some("direct"));
        assert!(with_backend("kind = \"contact\"\nsolve = 1\n", BackendChoice::Auto).is_err());
        assert!(with_backend("not toml [", BackendChoice::Auto).is_err());
    }
}
