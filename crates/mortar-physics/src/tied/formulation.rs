//! How a tied system is solved: dual-condensed SPD or saddle point (`Formulation`), the
//! automatic choice between them, the treatment of Dirichlet slave nodes, and the report of
//! which was taken and why.

use std::fmt;

/// How a tied system is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Formulation {
    /// The slave unknowns are condensed out (`T_s = D^-1 (M T_m - ...)`, D diagonal): a
    /// symmetric positive definite system in the remaining unknowns, by sparse Cholesky.
    DualCondensed,
    /// The saddle-point system `[[A, B^T], [B, 0]]` in the unknowns and the multipliers, by
    /// sparse LU.
    SaddlePoint,
}

impl Formulation {
    /// `"dual-condensed SPD"` or `"saddle point"` (what factorises it:
    /// [`FormulationReport::factorisation`]).
    pub fn describe(self) -> &'static str {
        match self {
            Formulation::DualCondensed => "dual-condensed SPD",
            Formulation::SaddlePoint => "saddle point",
        }
    }
}

impl fmt::Display for Formulation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.describe())
    }
}

/// Which formulation to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum FormulationChoice {
    /// The cheaper condensed form when D is diagonal on the slave unknowns that carry a
    /// multiplier (dual multipliers on a fully covered interface), else the saddle point; the
    /// report says which and why.
    #[default]
    Auto,
    /// Always the saddle point.
    SaddlePoint,
    /// Always the condensation; an error if D is not diagonal.
    DualCondensed,
}

/// What to do with Dirichlet conditions on slave interface nodes.
///
/// A slave node's value is what the condensation computes from the master side
/// (`T_s = D^-1 M T_m`), so a Dirichlet value there conflicts with it, and in the saddle point
/// the node's multiplier row would over-constrain the master side (and make the system
/// singular when that row has no free entry). Such nodes arise wherever the interface meets a
/// Dirichlet boundary (the "crosspoints" at the ends of a straight interface).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum SlaveDirichlet {
    /// Remove the multiplier of each Dirichlet slave node and share its basis function equally
    /// among the nearest free slave nodes: those sharing a slave face with it, or, where all
    /// its faces' nodes are Dirichlet nodes (a corner of the interface), those one face
    /// further (Wohlmuth's crosspoint modification, done on the assembled rows of D and M).
    /// The modified multiplier space still reproduces constants, so the patch test still
    /// passes, and D stays diagonal on the free slave nodes, so the condensation remains
    /// available. A Dirichlet slave node with no free slave node in reach loses its multiplier
    /// without redistribution (counted in the report). Both formulations use the same
    /// modified rows, so they solve the same discrete problem.
    #[default]
    Redistribute,
    /// Refuse with [`PhysicsError::DirichletOnSlave`](crate::PhysicsError::DirichletOnSlave).
    Refuse,
}

/// Settings of a tied solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TiedOptions {
    /// Which formulation.
    pub formulation: FormulationChoice,
    /// Dirichlet conditions on slave interface nodes.
    pub slave_dirichlet: SlaveDirichlet,
    /// D counts as diagonal when every off-diagonal entry between condensed slave nodes is at
    /// most this times its row's diagonal entry.
    pub diagonal_tolerance: f64,
}

impl Default for TiedOptions {
    /// Automatic formulation, redistribution of Dirichlet slave multipliers, tolerance 1e-10.
    fn default() -> Self {
        Self {
            formulation: FormulationChoice::Auto,
            slave_dirichlet: SlaveDirichlet::Redistribute,
            diagonal_tolerance: 1e-10,
        }
    }
}

impl TiedOptions {
    /// These options with a given formulation choice.
    pub fn with_formulation(mut self, formulation: FormulationChoice) -> Self {
        self.formulation = formulation;
        self
    }
}

/// Which formulation a tied solve used, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct FormulationReport {
    /// The formulation.
    pub formulation: Formulation,
    /// Why it was chosen.
    pub reason: String,
    /// What factorises the system: sparse Cholesky (dual condensed), sparse `L D L^T` in an
    /// order that needs no pivoting (saddle point), or sparse LU with partial pivoting (a
    /// saddle point that the `L D L^T` refused).
    pub factorisation: &'static str,
    /// Unknowns of the factorised system.
    pub unknowns: usize,
    /// Stored entries of the factorised matrix.
    pub nonzeros: usize,
    /// Multipliers (constraint rows) after the treatment of Dirichlet slave nodes.
    pub multipliers: usize,
    /// Dirichlet slave nodes whose multiplier was shared among the nearest free slave nodes.
    pub redistributed: usize,
    /// Dirichlet slave nodes whose multiplier was removed without a free slave node to take it.
    pub dropped: usize,
}

impl fmt::Display for FormulationReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} ({} unknowns, {} multipliers): {}; {}",
            self.formulation, self.unknowns, self.multipliers, self.reason, self.factorisation
        )
    }
}
