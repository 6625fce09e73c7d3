//! The tangents of the shipped laws by dual numbers against central finite differences.

use mortar_physics::laws::{
    evaluate, ConstraintLaw, ContactComplementarity, ExponentialPressure, GapConductance,
    GasConductivity, LawPoint, Tying,
};
use proptest::prelude::*;

/// Central differences of `law` at `p` in each argument, with steps relative to the
/// argument (and to `gap_scale` for the gap).
fn check_fd<L: ConstraintLaw>(law: &L, p: LawPoint<f64>, gap_scale: f64) {
    let t = evaluate(law, p).unwrap();
    let f = |p: LawPoint<f64>| law.residual(p);
    let h = |v: f64| 1e-6 * (1.0 + v.abs());
    let (hg, hl, ht) = (
        1e-6 * (gap_scale + p.gap.abs()),
        h(p.multiplier),
        h(p.temperature),
    );
    let dg = (f(LawPoint {
        gap: p.gap + hg,
        ..p
    }) - f(LawPoint {
        gap: p.gap - hg,
        ..p
    })) / (2.0 * hg);
    let dl = (f(LawPoint {
        multiplier: p.multiplier + hl,
        ..p
    }) - f(LawPoint {
        multiplier: p.multiplier - hl,
        ..p
    })) / (2.0 * hl);
    let dt = (f(LawPoint {
        temperature: p.temperature + ht,
        ..p
    }) - f(LawPoint {
        temperature: p.temperature - ht,
        ..p
    })) / (2.0 * ht);
    let scale = t
        .d_gap
        .abs()
        .max(t.d_multiplier.abs())
        .max(t.d_temperature.abs())
        .max(1e-300);
    for (ad, fd, what) in [
        (t.d_gap, dg, "dC/dg"),
        (t.d_multiplier, dl, "dC/dlambda"),
        (t.d_temperature, dt, "dC/dT"),
    ] {
        assert!(
            (ad - fd).abs() <= 1e-5 * scale + 1e-7 * ad.abs(),
            "{what}: automatic {ad} vs finite difference {fd} at {p:?}"
        );
    }
}

proptest! {
    #[test]
    fn gap_conductance_tangent(g in -500.0..500.0f64, q in -1e7..1e7f64, t in 300.0..2500.0f64,
                               d in 1e-6..1e-3f64, helium in any::<bool>()) {
        let gas = if helium { GasConductivity::HELIUM } else { GasConductivity::Constant(0.3) };
        let law = GapConductance::ross_stoute(d, 2e-6, 1e-6, 1e-5, gas).unwrap();
        check_fd(&law, LawPoint::new(g, q, t), 1.0);
        check_fd(&GapConductance::simplified(d, gas).unwrap(), LawPoint::new(g, q, t), 1.0);
    }

    #[test]
    fn exponential_pressure_tangent(g in -2e-5..2e-5f64, t in -1e8..1e8f64) {
        let law = ExponentialPressure::try_new(2e6, 1e10, 1e-5).unwrap();
        // Away from the kinks at xi and at the start of the linear branch.
        prop_assume!((g - 1e-5).abs() > 1e-9 && (g - law.linear_below()).abs() > 1e-9);
        check_fd(&law, LawPoint::new(g, t, 600.0), 1e-9);
    }

    #[test]
    fn complementarity_and_tying_tangents(g in -1.0..1.0f64, t in -1.0..1.0f64) {
        let law = ContactComplementarity::try_new(3.0).unwrap();
        prop_assume!((t - 3.0 * g).abs() > 1e-4);
        check_fd(&law, LawPoint::new(g, t, 0.0), 1.0);
        check_fd(&Tying, LawPoint::new(g, t, 0.0), 1.0);
    }

    #[test]
    fn nan_input_is_an_error(which in 0usize..3, g in -1.0..1.0f64) {
        let mut p = LawPoint::new(g, 0.5, 700.0);
        match which { 0 => p.gap = f64::NAN, 1 => p.multiplier = f64::NAN, _ => p.temperature = f64::NAN }
        let gap = GapConductance::simplified(1e-4, GasConductivity::HELIUM).unwrap();
        let pressure = ExponentialPressure::try_new(1.0, 1.0, 0.0).unwrap();
        prop_assert!(evaluate(&gap, p).is_err());
        prop_assert!(evaluate(&pressure, p).is_err());
        prop_assert!(evaluate(&Tying, p).is_err());
        prop_assert!(evaluate(&ContactComplementarity::try_new(1.0).unwrap(), p).is_err());
    }
}

#[test]
fn complementarity_solves_the_kuhn_tucker_conditions() {
    let law = ContactComplementarity::try_new(10.0).unwrap();
    // Open, no pressure; closed, pressure: both zero residual.
    assert_eq!(law.residual(LawPoint::new(0.3, 0.0, 0.0)), 0.0);
    assert_eq!(law.residual(LawPoint::new(0.0, 2.0, 0.0)), 0.0);
    // Penetration, or a pull on an open gap: non-zero.
    assert!(law.residual(LawPoint::new(-0.1, 2.0, 0.0)) != 0.0);
    assert!(law.residual(LawPoint::new(0.3, -1.0, 0.0)) != 0.0);
}
