//! `check_tangent`: a law's tangent by dual numbers against central finite differences of its
//! residual, argument by argument.

use super::{evaluate, ConstraintLaw, LawError, LawPoint};

/// The tangent of a law at a point against central finite differences of its residual, one
/// line per argument ([`check_tangent`]).
#[derive(Debug, Clone, PartialEq)]
pub struct TangentCheck {
    /// Per argument, in the order `gap`, `multiplier`, `temperature`, `normal_gap`,
    /// `contact_pressure`, `gas_pressure`: its name, the derivative by dual numbers, the
    /// central difference, and the step used.
    pub rows: Vec<(&'static str, f64, f64, f64)>,
    /// The largest relative difference `|ad - fd| / max(|ad|, |fd|)` over the arguments
    /// (arguments whose two derivatives are both zero count 0).
    pub max_relative_error: f64,
}

/// Checks the tangent that [`evaluate`] gives a law at `p` against central finite differences
/// of its residual, argument by argument, with the step `1e-6 |x|` (`1e-9` for an argument
/// at zero). A law's own derivative is exact; a difference above about 1e-6 means the
/// residual is not differentiable there (a kink such as `max(g, 0)` at `g = 0`) or is written
/// with a branch that the dual numbers do not follow (a comparison on a value derived through
/// a non-`Float` route).
///
/// ```
/// use mortar_physics::laws::{check_tangent, ExponentialContact, LawPoint};
/// let law = ExponentialContact::try_new(1e12, 5e-6).unwrap();
/// let at = LawPoint::new(3e-6, 1e7, 900.0).with_mechanics(3e-6, 1e7, 5e6);
/// let check = check_tangent(&law, at).unwrap();
/// assert!(check.max_relative_error < 1e-6, "{check:?}");
/// ```
///
/// # Errors
/// The errors of [`evaluate`] at `p` and at the shifted points.
pub fn check_tangent<L: ConstraintLaw + ?Sized>(
    law: &L,
    p: LawPoint<f64>,
) -> Result<TangentCheck, LawError> {
    let t = evaluate(law, p)?;
    let exact = [
        t.d_gap,
        t.d_multiplier,
        t.d_temperature,
        t.d_normal_gap,
        t.d_contact_pressure,
        t.d_gas_pressure,
    ];
    let names = [
        "gap",
        "multiplier",
        "temperature",
        "normal_gap",
        "contact_pressure",
        "gas_pressure",
    ];
    let get = |q: &LawPoint<f64>, i: usize| match i {
        0 => q.gap,
        1 => q.multiplier,
        2 => q.temperature,
        3 => q.normal_gap,
        4 => q.contact_pressure,
        _ => q.gas_pressure,
    };
    let set = |q: &mut LawPoint<f64>, i: usize, v: f64| match i {
        0 => q.gap = v,
        1 => q.multiplier = v,
        2 => q.temperature = v,
        3 => q.normal_gap = v,
        4 => q.contact_pressure = v,
        _ => q.gas_pressure = v,
    };
    let mut rows = Vec::with_capacity(6);
    let mut worst = 0.0f64;
    for i in 0..6 {
        let x = get(&p, i);
        let h = if x == 0.0 { 1e-9 } else { 1e-6 * x.abs() };
        let (mut plus, mut minus) = (p, p);
        set(&mut plus, i, x + h);
        set(&mut minus, i, x - h);
        let fd = (evaluate(law, plus)?.value - evaluate(law, minus)?.value) / (2.0 * h);
        let scale = exact[i].abs().max(fd.abs());
        if scale > 0.0 {
            worst = worst.max((exact[i] - fd).abs() / scale);
        }
        rows.push((names[i], exact[i], fd, h));
    }
    Ok(TangentCheck {
        rows,
        max_relative_error: worst,
    })
}
