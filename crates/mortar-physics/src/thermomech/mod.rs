//! Thermomechanical contact of two bodies across a gap (the fuel pellet in its cladding,
//! docs/models.md, section 3a): transient heat conduction with `k(T)` and small-strain
//! thermoelasticity in both bodies, coupled across a mortar interface by two pointwise
//! [`ConstraintLaw`](crate::laws::ConstraintLaw)s that see each other's quantities:
//!
//! - the thermal law, heat flux against temperature jump, sees the current mechanical gap and
//!   contact pressure ([`MechanicalGapConductance`](crate::laws::MechanicalGapConductance):
//!   Ross-Stoute on the gap plus a contact conductance);
//! - the mechanical law, contact pressure against normal gap, sees the gas pressure
//!   ([`ExponentialContact`](crate::laws::ExponentialContact), the exponential pressure law, or
//!   [`ContactComplementarity`](crate::laws::ContactComplementarity), Kuhn-Tucker);
//! - the gas pressure is given or follows a [`Plenum`] (ideal gas, fixed moles, the gap's
//!   volume and temperature).
//! - a pellet's relocation is a [`RelocationModel`](crate::laws::RelocationModel)
//!   ([`FrapconRelocation`](crate::laws::FrapconRelocation), FRAPCON's default), applied as an eigenstrain that follows time
//!   ([`GapThermoMechanics::with_eigenstrain`]).
//!
//! The whole residual (temperatures, displacements, fluxes, contact pressures, gas pressure)
//! is one [`NewtonProblem`](crate::nonlinear::NewtonProblem), solved by Newton on the
//! assembled Jacobian or by Jacobian-free Newton-Krylov with a block preconditioner
//! ([`ThermoMechSolver`]); any pair of laws goes through the same solver.

mod blocks;
mod interface;
mod pair;
mod plenum;
mod problem;
mod residual;
mod solve;

pub use plenum::{GasPressure, Plenum, GAS_CONSTANT};
pub use problem::{GapThermoMechanics, StateView, ThermoElasticBody, ThermoMechOptions};
pub use solve::{ThermoMechSolver, ThermoMechSolverState, ThermoMechStats};
