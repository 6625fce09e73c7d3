//! The residual of a [`GapThermoMechanics`] split by blocks of equations, to say where a
//! solve that did not converge was left unbalanced.

use super::problem::GapThermoMechanics;
use crate::error::PhysicsError;
use crate::laws::ConstraintLaw;

/// The names of the blocks of equations, in the order of the unknowns: the heat balance of
/// both bodies (temperatures), their mechanical equilibrium (displacements), the thermal law
/// of each slave interface node (fluxes), its contact law (pressures), the plenum's gas
/// law and the bodies' axial balances (free axial expansion; empty without).
const RESIDUAL_BLOCKS: [&str; 6] = ["heat", "mechanics", "flux", "contact", "plenum", "axial"];

impl<TL: ConstraintLaw, ML: ConstraintLaw> GapThermoMechanics<TL, ML> {
    /// The Euclidean norm of the residual's rows in each block of equations, in this order:
    /// `heat` (the bodies' heat balance), `mechanics` (their equilibrium), `flux` (the thermal
    /// law of each slave interface node), `contact` (its pressure law), `plenum` (the gas
    /// law) and `axial` (the axial force balances of free axial expansion), at the state `x` of a solve at time `t` (steady when `transient` is `None`, else
    /// a backward Euler step of size `dt` from `old`, as [`solve`](Self::solve)). The rows are
    /// those Newton measures, in its units (heat flows, the other rows scaled to them), so
    /// the block norms add in squares to Newton's residual norm.
    ///
    /// # Errors
    /// The errors of the assembly and of the laws at `x`.
    pub fn residual_blocks(
        &self,
        x: &[f64],
        t: f64,
        transient: Option<(&[f64], f64)>,
    ) -> Result<[(&'static str, f64); 6], PhysicsError> {
        let data = self.heat.step_data(t, transient)?;
        let mut r = vec![0.0; self.dimension()];
        self.evaluate(x, &data, &mut r, None)?;
        let o = &self.offsets;
        // Each row's block: the fluxes and pressures of the gap and of the contact pairs
        // together.
        let block = |i: usize| {
            if i < o.u[0] {
                0
            } else if i < o.flux {
                1
            } else if o.is_flux(i) {
                2
            } else if o.is_pressure(i) {
                3
            } else if i == o.gas {
                4
            } else {
                5
            }
        };
        let mut squares = [0.0; 6];
        for (i, v) in r.iter().enumerate() {
            squares[block(i)] += v * v;
        }
        let mut out = [("", 0.0); 6];
        for ((slot, name), sq) in out.iter_mut().zip(RESIDUAL_BLOCKS).zip(squares) {
            *slot = (name, sq.sqrt());
        }
        Ok(out)
    }
}
