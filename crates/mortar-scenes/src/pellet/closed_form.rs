//! The closed form of docs/models.md section 3: steady radial heat flow through a pellet with
//! `k = 1 / (A + B T)`, an open gap of conductance `U(T_gas)` and a cladding of constant
//! conductivity, the cladding's outer temperature fixed.

use std::f64::consts::PI;

use mortar_physics::laws::GapConductance;

/// The steady temperatures of the closed form (K).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ClosedForm {
    /// `T_0`, the pellet centre.
    pub center_temperature: f64,
    /// `T_ps`, the pellet surface.
    pub pellet_surface_temperature: f64,
    /// `T_ci`, the cladding inner surface.
    pub cladding_inner_temperature: f64,
    /// `U` at the gas temperature `(T_ps + T_ci) / 2` (W/m^2/K).
    pub gap_conductance: f64,
}

/// The closed form for linear power `q'` (W/m), pellet radius `a`, conductivity
/// `1 / (A + B T)`, cladding radii `b < c`, conductivity `k_c`, outer temperature `T_co`,
/// and the gap law (its gas conductivity taken at the mean `(T_ps + T_ci) / 2`, as the
/// discrete law does; the resulting equation for `T_ps` is solved by fixed-point iteration):
///
/// ```text
/// T_ci = T_co + q' ln(c/b) / (2 pi k_c)
/// T_ps = T_ci + q' / (2 pi a U((T_ps + T_ci) / 2))
/// T_0  = ((A + B T_ps) exp(B q' / (4 pi)) - A) / B
/// ```
#[allow(clippy::too_many_arguments)]
pub fn closed_form(
    linear_power: f64,
    a: f64,
    (ka, kb): (f64, f64),
    b: f64,
    c: f64,
    k_c: f64,
    outer_temperature: f64,
    gap: &GapConductance,
) -> ClosedForm {
    let q = linear_power;
    let t_ci = outer_temperature + q * (c / b).ln() / (2.0 * PI * k_c);
    let mut t_ps = t_ci;
    let mut u = gap.conductance(t_ci);
    for _ in 0..200 {
        u = gap.conductance(0.5 * (t_ps + t_ci));
        let next = t_ci + q / (2.0 * PI * a * u);
        let done = (next - t_ps).abs() <= 1e-13 * next.abs();
        t_ps = next;
        if done {
            break;
        }
    }
    let t_0 = if kb > 0.0 {
        ((ka + kb * t_ps) * (kb * q / (4.0 * PI)).exp() - ka) / kb
    } else {
        t_ps + q * ka / (4.0 * PI)
    };
    ClosedForm {
        center_temperature: t_0,
        pellet_surface_temperature: t_ps,
        cladding_inner_temperature: t_ci,
        gap_conductance: u,
    }
}
