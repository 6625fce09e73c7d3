//! Heat conduction: `rho c_p T_t - div(k grad T) = Q` on 2D (Tri3, Quad4 in the plane
//! `z = 0`) and 3D (Tet4, Hex8) volume meshes; a 2D mesh is a slice of unit thickness, or
//! with [`HeatOptions::geometry`] axisymmetric the r-z section of a body of revolution (`x = r`,
//! `y = z`, every integral weighted by `2 pi r`).
//!
//! - [`HeatBody`]: mesh, [`HeatMaterial`], source, Dirichlet and Neumann data (fields of
//!   space and time).
//! - [`assemble_heat_matrices`] (stiffness K, capacity C; [`assemble_heat_stiffness`] K alone,
//!   for a steady problem) and [`assemble_heat_load`] (F):
//!   sparse, in parallel over fixed chunks of cells merged in order, so the result is the
//!   same bit for bit whatever the thread count.
//! - [`TiedHeat`]: two bodies tied along a non-conforming interface, steady
//!   ([`TiedHeat::solve_steady`]) or transient by backward Euler ([`BackwardEuler`]); the tied
//!   system is a saddle point (LU) or, with dual multipliers on a fully covered interface,
//!   condensed to an SPD system (Cholesky), as the [`FormulationReport`](crate::tied::FormulationReport)
//!   of the solution says.
//! - [`assemble_conduction`]: the heat flow of a temperature-dependent [`Conductivity`]
//!   `k(T)` and its Newton or Picard linearisation; [`GapHeat`]: two bodies exchanging heat
//!   through a pointwise [`ConstraintLaw`](crate::laws::ConstraintLaw) (gap conductance
//!   across an open gap), steady or backward Euler, solved by Newton or JFNK ([`GapSolver`]).
//! - [`error_norms`]: L2 and H1-seminorm errors against an exact solution, by quadrature.
//!
//! Weak form per body: `(rho c_p T_t, v) + (k grad T, grad v) + <lambda, v>_Gamma =
//! (Q, v) + <q, v>_Gamma_N` on the slave body (`- <lambda, v>` on the master body), where
//! `lambda` is the heat flux leaving the slave body and `q = k dT/dn` the heat flux entering
//! through the Neumann boundary.

mod assembly;
mod body;
mod gap;
mod nonlinear;
mod norms;
mod tied;

pub use assembly::{
    assemble_heat_load, assemble_heat_matrices, assemble_heat_stiffness, HeatMatrices, HeatOptions,
};
pub use body::{DirichletCondition, Field, HeatBody, HeatMaterial, NeumannCondition};
pub(crate) use gap::StepData;
pub use gap::{GapHeat, GapSolver, GapSolverState, GapSolverStats};
pub use nonlinear::{assemble_conduction, Conductivity, Linearization};
pub use norms::{error_norms, ErrorNorms};
pub use tied::{
    BackwardEuler, HeatSeconds, TiedHeat, TiedHeatSolution, LEVEL_SHIFT_CONTRAST,
    MAX_CONDUCTIVITY_CONTRAST, MAX_LEVEL_PASSES, MAX_STIFFER_SLAVE_CONTRAST,
};
