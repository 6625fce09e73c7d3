//! Two bodies exchanging heat through the gap law: body 1 (conductance `k1` to a wall at
//! temperature 1), body 2 (conductance `k2` to a wall at 0); unknowns `(T1, T2, q)` with
//! `k1 (T1 - 1) + q = 0`, `k2 T2 - q = 0`, `C(T1 - T2, q) = 0`, solved by Newton with the
//! law's automatic tangent.

use mortar_physics::laws::{evaluate, GapConductance, GasConductivity, LawPoint};
use nalgebra::{Matrix3, Vector3};
use proptest::prelude::*;

fn solve(law: &GapConductance, k1: f64, k2: f64) -> [f64; 3] {
    let mut x = Vector3::new(0.5, 0.5, 0.0);
    for _ in 0..5 {
        let t = evaluate(law, LawPoint::new(x[0] - x[1], x[2], 600.0)).unwrap();
        let r = Vector3::new(k1 * (x[0] - 1.0) + x[2], k2 * x[1] - x[2], t.value);
        let j = Matrix3::new(
            k1,
            0.0,
            1.0, //
            0.0,
            k2,
            -1.0, //
            t.d_gap,
            -t.d_gap,
            t.d_multiplier,
        );
        let dx = j.lu().solve(&r).expect("non-singular");
        x -= dx;
    }
    [x[0], x[1], x[2]]
}

proptest! {
    #[test]
    fn tends_to_tying_and_to_insulation_without_nan(k1 in 0.1..10.0f64, k2 in 0.1..10.0f64) {
        let tied_t = k1 / (k1 + k2);
        let tied_q = k1 * k2 / (k1 + k2);
        let mut last_jump = f64::INFINITY;
        let mut last_flux = 0.0;
        for e in -12..=12 {
            let u = 10f64.powi(e);
            // Simplified law with k_g = 1: U = 1 / d_g.
            let law = GapConductance::simplified(1.0 / u, GasConductivity::Constant(1.0)).unwrap();
            let [t1, t2, q] = solve(&law, k1, k2);
            prop_assert!(t1.is_finite() && t2.is_finite() && q.is_finite(), "U = {u}");
            // The exact solution of the pair: q = U (T1 - T2).
            let exact_q = 1.0 / (1.0 / k1 + 1.0 / k2 + 1.0 / u);
            prop_assert!((q - exact_q).abs() <= 1e-9 * exact_q.max(1e-300) + 1e-14, "U = {u}: q {q} vs {exact_q}");
            let jump = (t1 - t2).abs();
            prop_assert!(jump <= last_jump * (1.0 + 1e-9) + 1e-15, "the jump grows with U at {u}");
            prop_assert!(q >= last_flux * (1.0 - 1e-9), "the flux falls with U at {u}");
            last_jump = jump;
            last_flux = q;
            if e == 12 {
                prop_assert!((t1 - tied_t).abs() < 1e-9 && (t2 - tied_t).abs() < 1e-9);
                prop_assert!((q - tied_q).abs() < 1e-9);
            }
            if e == -12 {
                prop_assert!(q.abs() < 1e-11);
                prop_assert!((t1 - 1.0).abs() < 1e-10 && t2.abs() < 1e-10);
            }
        }
    }
}
