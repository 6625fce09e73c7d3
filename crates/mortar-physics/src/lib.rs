//! # mortar-physics
//!
//! Formulations on top of the mortar operators.
//!
//! - [`tying`]: the constraint matrix `B = [D, -M]` of the saddle-point system and, with dual
//!   multipliers, the condensation operator `P = D^-1 M` (`u_s = P u_m`).
//! - [`tied`]: two bodies tied by mortar, the tied linear system, solved as a saddle point
//!   (sparse LU) or condensed to a symmetric positive definite system (sparse Cholesky) when D
//!   is diagonal, with the choice reported.
//! - [`field`]: what scalar and vector fields share: the numbering of unknowns
//!   (`node * components + component`) and the components a condition applies to.
//! - [`heat`]: steady and transient (backward Euler) heat conduction on 2D and 3D volume
//!   meshes (stiffness, capacity, loads; deterministic parallel assembly), error norms
//!   against exact solutions, and the tied heat problem of two bodies; `k(T)` conduction and
//!   two bodies exchanging heat through a constraint law ([`heat::GapHeat`]).
//! - [`contact`]: frictionless normal contact of two bodies on the mortar weighted gap, any
//!   [`laws::ConstraintLaw`] (the exact complementarity by semi-smooth Newton, or a
//!   regularised pressure law), in load steps.
//! - [`elastic`]: small-strain linear elasticity (2D plane strain, 3D), thermal strain, stresses.
//! - [`laws`]: pointwise constraint laws `C(g, lambda; T)` written once over a generic float,
//!   tangents by automatic differentiation: tying, gap conductance, exponential pressure,
//!   contact complementarity.
//! - [`nonlinear`]: one Newton loop (line search, Eisenstat-Walker forcing) over a problem
//!   that solves its own linearisation: assembled Newton or Jacobian-free Newton-Krylov.
//!
//! Sign conventions: the tying constraint is `D T_s - M T_m = 0`; the multiplier is the heat
//! flux leaving the slave body (`lambda = -k dT/dn_s`, `n_s` the slave's outward normal);
//! Neumann data is the heat flux entering a body (`q = k dT/dn`, W/m^2).
//!
//! ```text
//! use mortar_physics::heat::{HeatBody, HeatMaterial, TiedHeat};
//! let slave = HeatBody::new("right", right_mesh, HeatMaterial::new(1.0, 1.0))
//!     .with_source(|x, _t| q(x))
//!     .with_dirichlet_where(|f| on_outer_boundary(f), |x, _t| exact(x))?;
//! let problem = TiedHeat::new(slave, master, slave_faces, master_faces,
//!     &CouplingOptions::default().dual(), &Default::default())?;
//! let solution = problem.solve_steady(&TiedOptions::default(), 0.0)?;
//! println!("{}", solution.formulation); // dual-condensed SPD (...): D is diagonal ...; sparse Cholesky
//! ```

// What a run has to say goes into its results; only the command-line program prints.
#![cfg_attr(
    not(test),
    deny(clippy::print_stdout, clippy::print_stderr, clippy::dbg_macro)
)]

pub mod contact;
pub mod elastic;
pub mod error;
pub mod field;
pub mod heat;
pub mod laws;
mod linear_solve;
pub mod nonlinear;
pub mod thermomech;
pub mod tied;
pub mod tying;

pub use error::PhysicsError;
pub use linear_solve::LinearSolve;

/// The backend of the physics' solves through the solver interface of `mortar-fem` (direct
/// factorisations of a general or a symmetric positive definite matrix, preconditioned GMRES).
pub(crate) static SOLVER: &dyn mortar_fem::linalg::SparseSolver = &mortar_fem::linalg::FaerSolver;
pub use tying::{constraint_matrix, dual_condensation, TyingError};
