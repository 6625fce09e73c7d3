//! # mortar-physics
//!
//! Formulations on top of the mortar operators. For now: mesh tying, as the constraint matrix
//! `B = [D, -M]` of the saddle-point system and, with dual multipliers, the condensation
//! operator `P = D^-1 M` that eliminates the slave unknowns (`u_s = P u_m`).
//!
//! Heat conduction, gap conductance, contact and the nonlinear solvers build on these.

pub mod tying;

pub use tying::{constraint_matrix, dual_condensation, TyingError};
