//! Frictionless normal contact of two bodies across a mortar interface, small deformation.
//!
//! The weighted normal gap of slave interface node `j` is
//! `g~_j = -n_j . (D x_s - M x_m)_j` with `x = X + u` and `n_j` the averaged unit normal of
//! the slave (positive open), linear in the displacements: `g~ = g~_0 - N u`. Its nodal value
//! `g_j = g~_j / w_j` (`w_j` the row sum of D, the node's share of the slave area) is the
//! gap (m) a [`ConstraintLaw`](crate::laws::ConstraintLaw) sees, with the contact pressure
//! `p_j` (Pa, positive in compression) as its multiplier:
//!
//! ```text
//! K u - f + N^T p = 0          (equilibrium: -p n on the slave, +p n on the master)
//! C(g_j(u), p_j) = 0           (the law at every slave node)
//! ```
//!
//! solved by one Newton iteration for every law ([`solve_contact`]): with the exact law,
//! [`ContactComplementarity`](crate::laws::ContactComplementarity) `C = p - max(0, p - c g)`,
//! the generalised derivative makes it the semi-smooth Newton of the primal-dual active set
//! method (active: `g = 0`; inactive: `p = 0`), which, the problem being linear otherwise,
//! ends when the active set stops changing; with a regularised law such as the exponential
//! [`ExponentialPressure`](crate::laws::ExponentialPressure) it is Newton's method on the
//! pressure law, its tangent from the law's dual numbers. `c` is chosen from the stiffness
//! and the nodal areas when not given ([`automatic_complementarity`]).
//!
//! Small deformation: D, M and the normals are those of the reference configuration, so the
//! surfaces may not slide far (a fraction of an element) for the gap to stay exact.
//!
//! With dual multipliers (D diagonal) the pressures are condensed out of every Newton system:
//! an inactive node's pressure follows from its law, an active node's normal displacement
//! from its gap (solved for its free component most along the normal), and the rest is a
//! symmetric system of the displacements less one unknown per node in contact (sparse
//! Cholesky); the active pressures are recovered from the equilibrium rows. Otherwise
//! (standard multipliers) the displacements and pressures are solved together (sparse LU).
//! [`ContactSolution::formulation`] says which.

mod curvature;
mod held;
mod normal;
mod solver;

pub use curvature::{slave_surface_measures, SlaveSurfaceMeasures};
pub use held::{rigid_motions, HeldMotions, RigidMotion, FREE_MOTION_TOLERANCE};
pub use normal::NormalGap;
pub use solver::{
    automatic_complementarity, solve_contact, solve_contact_on, ContactOptions, ContactSolution,
    ContactStep,
};
