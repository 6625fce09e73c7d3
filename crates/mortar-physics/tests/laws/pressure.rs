//! Properties of the exponential contact pressure law: finite and monotone over any finite
//! gap, linear past the maximum pressure, NaN and bad parameters refused.

use mortar_physics::laws::{evaluate, ExponentialPressure, LawError, LawPoint};
use proptest::prelude::*;

fn law() -> ExponentialPressure {
    // 2 MPa plenum, contact felt from 10 um, steep.
    ExponentialPressure::try_new(2e6, 1e12, 1e-5).unwrap()
}

fn any_finite() -> impl Strategy<Value = f64> {
    prop_oneof![
        -1e-4..1e-4f64,
        -1e300..1e300f64,
        prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO,
        Just(f64::MAX),
        Just(-f64::MAX),
    ]
}

proptest! {
    #[test]
    fn finite_and_monotone_for_every_finite_gap(a in any_finite(), b in any_finite()) {
        let law = law();
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        let (p_lo, p_hi) = (law.pressure_checked(lo).unwrap(), law.pressure_checked(hi).unwrap());
        prop_assert!(p_lo.is_finite() && p_hi.is_finite());
        prop_assert!(p_lo >= p_hi, "P({lo}) = {p_lo} < P({hi}) = {p_hi}");
        prop_assert!(p_hi >= 2e6);
        let t = evaluate(&law, LawPoint::new(lo, 0.0, 0.0)).unwrap();
        prop_assert!(t.d_gap >= 0.0); // C = t - P(g), P non-increasing
    }
}

#[test]
fn continues_linearly_past_the_maximum_pressure() {
    let law = law();
    let gs = law.linear_below();
    let p = |g: f64| law.pressure(g);
    // Continuous at the switch, linear beyond it.
    assert!((p(gs) - law.max_pressure()).abs() <= 1e-9 * law.max_pressure());
    let (a, b, c) = (p(gs - 1e-6), p(gs - 2e-6), p(gs - 3e-6));
    assert!(((b - a) - (c - b)).abs() <= 1e-6 * (b - a));
    // The slope matches the exponential's at the switch.
    let h = 1e-12;
    let left = (p(gs - h) - p(gs - 2.0 * h)) / h;
    let right = (p(gs + 2.0 * h) - p(gs + h)) / h;
    assert!(
        (left - right).abs() <= 1e-3 * left.abs(),
        "{left} vs {right}"
    );
    assert_eq!(p(-f64::MAX), f64::MAX);
    assert_eq!(p(1.0), 2e6);
}

#[test]
fn refuses_nan_and_bad_parameters() {
    assert!(matches!(
        law().pressure_checked(f64::NAN),
        Err(LawError::NanInput { argument: "gap" })
    ));
    assert!(ExponentialPressure::try_new(0.0, 1.0, 0.0).is_err());
    assert!(ExponentialPressure::try_new(1.0, -1.0, 0.0).is_err());
    assert!(law().with_max_pressure(1.0).is_err());
}
