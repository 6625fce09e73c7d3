//! A law of one's own in the pellet scene: heat across the gap by gas conduction
//! and radiation, `q = U (T_s - T_m) + sigma eps (T_s^4 - T_m^4)`, written once over a generic
//! float (the tangent comes by dual numbers), checked against finite differences by the
//! library's `check_tangent`, then run in the built-in thermomechanical scene as it is, with
//! its VTU, plots and report.
//!
//! ```sh
//! cargo run --release --example extend_law [OUT_DIR]
//! ```

use mortar::physics::laws::{
    check_tangent, ConstraintLaw, Float, LawPoint, MechanicalGapConductance,
};
use mortar_scenes::pellet::{exponential_contact_law, run_coupled_with, thermal_law, PelletScene};

// ---- the user's code: the law (19 lines as rustfmt lays them out, comments and blank lines not counted) ----
/// Ross-Stoute on the mechanical gap plus grey-body radiation of emissivity `eps`.
#[derive(Clone)]
struct RadiatingGap {
    gas: MechanicalGapConductance,
    emissivity: f64,
}

impl ConstraintLaw for RadiatingGap {
    fn residual<S: Float>(&self, p: LawPoint<S>) -> S {
        let c = |x: f64| S::from(x).unwrap();
        // The two surface temperatures from the mean and the jump.
        let (ts, tm) = (
            p.temperature + c(0.5) * p.gap,
            p.temperature - c(0.5) * p.gap,
        );
        let radiation = c(5.670374419e-8 * self.emissivity) * (ts.powi(4) - tm.powi(4));
        // q - radiation = dT / R, written as the library's gap laws: (R (q - rad) - dT) / (R + R_ref).
        let r = self
            .gas
            .resistance(p.normal_gap, p.contact_pressure, p.temperature);
        (r * (p.multiplier - radiation) - p.gap) / (r + c(1e-4))
    }
}
// ---- end of the user's code ----

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run(&std::env::args().skip(1).collect::<Vec<_>>())
}

/// Runs the example with the arguments `[OUT_DIR]`.
pub fn run(args: &[String]) -> Result<(), Box<dyn std::error::Error>> {
    let out: std::path::PathBuf = args.first().map_or_else(
        || std::env::temp_dir().join("mortar-extend-law"),
        Into::into,
    );
    // ---- the user's code: checking and running the law (21 lines) ----
    let scene = PelletScene::default();
    let law = RadiatingGap {
        gas: thermal_law(&scene)?,
        emissivity: 0.8,
    };
    // The tangent by dual numbers against central differences, at an open and a closed gap.
    for gap in [8e-6, 3e-6] {
        let point = LawPoint::new(80.0, 1e6, 900.0).with_mechanics(gap, 1e7, 5e6);
        let check = check_tangent(&law, point)?;
        println!(
            "tangent at a {gap:.0e} m gap: off by {:.1e}",
            check.max_relative_error
        );
        assert!(check.max_relative_error < 1e-6, "tangent off: {check:?}");
    }
    let contact = exponential_contact_law(&scene)?;
    let report = run_coupled_with(&scene, law, contact, &out, true)?;
    let t0 = report["center_temperature"].as_f64().unwrap_or(f64::NAN);
    println!(
        "with radiation: centre {t0:.3} K, outputs in {}",
        out.display()
    );
    // ---- end of the user's code ----
    Ok(())
}
