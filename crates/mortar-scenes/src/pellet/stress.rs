//! The stress of a body of the coupled pellet in a state: with its temperature and, in 2D
//! generalized plane strain, its axial strain (read by the snapshots and the limits).

use mortar_physics::elastic::{recover_stress_with_axial_strain, StressField};
use mortar_physics::laws::ConstraintLaw;
use mortar_physics::thermomech::{GapThermoMechanics, StateView};

use super::PelletError;

/// The stress of body `b` (0 pellet, 1 cladding) in the state `f` at time `time` (s), with
/// its temperature, its eigenstrain at that time (the pellet's relocation) and, in 2D
/// generalized plane strain, its axial strain (which the 2D displacement does not hold; a
/// free end's, in r-z and 3D, it does).
///
/// # Errors
/// [`PelletError::Physics`] if the stresses cannot be recovered.
pub(super) fn stress_field<TL: ConstraintLaw, ML: ConstraintLaw>(
    problem: &GapThermoMechanics<TL, ML>,
    f: &StateView,
    b: usize,
    time: f64,
) -> Result<StressField, PelletError> {
    let mut body = problem.elastic_bodies()[b]
        .clone()
        .with_temperature(f.temperature[b].to_vec())?;
    body.eigenstrain = problem.eigenstrain_at(b, time)?;
    let options = &problem.options().elastic;
    let axial_strain = if body.components() == 2 && !options.geometry.is_axisymmetric() {
        f.axial_strain[b].unwrap_or(0.0)
    } else {
        0.0
    };
    let u = f.displacement(b);
    Ok(recover_stress_with_axial_strain(
        &body,
        &u,
        axial_strain,
        options,
    )?)
}
