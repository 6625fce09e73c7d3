//! Pellet relocation (`[model] relocation = "frapcon"`): the cold relocated pellet against
//! its closed form, the coupled scene against the independent radial model with relocation at
//! every step, a program's own relocation model by name, and the keys' refusals.

use mortar::physics::elastic::recover_stress_with_axial_strain;
use mortar::physics::laws::{
    ExponentialContact, FrapconRelocation, LawRegistry, RelocationInput, RelocationModel,
};
use mortar::physics::nonlinear::NewtonOptions;
use mortar::physics::thermomech::{ThermoMechSolver, ThermoMechSolverState};
use mortar_scenes::pellet::{
    coupled_problem, run_with_registry, AxialModel, ContactLawName, Geometry, PelletError,
    PelletScene, SolverMethod,
};

use super::coupled::{against_radial, run_scene};
use super::radial::RadialPellet;

/// The specification's as-built gap (80 um) with FRAPCON's relocation at 10 MWd/kgU.
fn relocated(linear_power: f64) -> PelletScene {
    let mut s = PelletScene::default();
    s.cladding.inner_radius = 4.18e-3;
    s.model.relocation = "frapcon".into();
    s.model.burnup = 10.0;
    s.power.linear_power = linear_power;
    s.gap.contact_conductance = 1e-4;
    s
}

/// Source: a uniform eigenstrain that is compatible (here `eps_rr = eps_tt = e`, `eps_zz = 0`,
/// the displacement `u = e r` across the axis) stresses no free body (Timoshenko and Goodier,
/// *Theory of Elasticity*, sec. 150, with the thermal strain replaced by it). The cold rod at
/// `T = T_ref`, no power, no gas, no coolant, the gap wide open, with FRAPCON's relocation at
/// 10 MWd/kgU: at zero power its share of the cold gap is `0.055 + 0.345 = 0.4`, so
/// `e = 0.4 (b - a) / a`. In 2D (generalized plane strain), r-z and 3D (free tops) the steady
/// state's stress is zero to rounding in both bodies (largest 2.6e-13 of `E e`; bound: the
/// cold state's claim), the pellet's surface nodes move out by `e r` (to 1e-12 of it) and the
/// axial strains stay zero.
#[test]
fn the_relocated_cold_pellet_moves_by_its_strain_without_stress() {
    for geometry in [Geometry::Plane, Geometry::Axisymmetric, Geometry::ThreeD] {
        let mut s = relocated(0.0);
        s.mesh.refinement = 1;
        s.mesh.axial_layers = 1;
        s.model.geometry = geometry;
        s.model.axial = Some(AxialModel::Generalized);
        s.plenum.fill_pressure = 0.0;
        s.cladding.coolant_pressure = 0.0;
        s.cladding.outer_temperature = s.model.reference_temperature;
        let p = coupled_problem(&s, ExponentialContact::try_new(1e12, 5e-6).unwrap()).unwrap();
        let bodies = p.heat().bodies();
        let t = s.cladding.outer_temperature;
        let t0 = vec![t; bodies[0].mesh.node_count()];
        let t1 = vec![t; bodies[1].mesh.node_count()];
        let mut x = p.state([&t0, &t1]);
        let mut solver = ThermoMechSolverState::new(ThermoMechSolver::Newton);
        p.solve(&mut x, 0.0, None, &mut solver, &NewtonOptions::default())
            .unwrap();
        let (a, b) = (s.pellet.radius, s.cladding.inner_radius);
        let strain = RadialPellet::relocation_share(0.0, 10.0) * (b - a) / a;
        assert!((RadialPellet::relocation_share(0.0, 10.0) - 0.4).abs() < 1e-15);
        let f = p.fields(&x);
        let options = p.options().elastic;
        let rz = geometry == Geometry::Axisymmetric;
        for body in 0..2 {
            let elastic = &p.elastic_bodies()[body];
            let mut recovered = elastic
                .clone()
                .with_temperature(f.temperature[body].to_vec())
                .unwrap();
            recovered.eigenstrain = p.eigenstrain_at(body, 0.0).unwrap();
            assert_eq!(recovered.eigenstrain.is_some(), body == 0);
            let e = match (geometry, f.axial_strain[body]) {
                (Geometry::Plane, Some(e)) => e,
                _ => 0.0,
            };
            let u = f.displacement(body);
            let stress = recover_stress_with_axial_strain(&recovered, &u, e, &options).unwrap();
            let scale = elastic.material.youngs_modulus * strain;
            let largest = stress
                .cells
                .iter()
                .flatten()
                .fold(0.0f64, |m, v| m.max(v.abs()));
            eprintln!(
                "relocated cold state, {geometry:?}, body {body}: largest stress {:.2e} of E e, \
                 axial strain {:?}",
                largest / scale,
                f.axial_strain[body]
            );
            assert!(
                largest < crate::claims::claim("pellet.cold").bound * scale,
                "{geometry:?} body {body}: stress {largest} Pa"
            );
            if let Some(e) = f.axial_strain[body] {
                assert!(
                    e.abs() < 1e-12 * strain,
                    "{geometry:?} {body}: axial strain {e}"
                );
            }
            if body == 0 {
                // Every node moves out by e r across the axis.
                let dim = elastic.components();
                let mut worst = 0.0f64;
                for (n, x) in elastic.mesh.coords().iter().enumerate() {
                    let (want, got) = if rz {
                        (strain * x.x, u[dim * n])
                    } else {
                        let r = x.xy().norm();
                        let ur = if r > 0.0 {
                            (u[dim * n] * x.x + u[dim * n + 1] * x.y) / r
                        } else {
                            u[dim * n].hypot(u[dim * n + 1])
                        };
                        (strain * r, ur)
                    };
                    worst = worst.max((got - want).abs());
                }
                assert!(
                    worst < 1e-12 * strain * a,
                    "{geometry:?}: displacement off e r by {worst} m"
                );
            }
        }
    }
}

/// Source: the independent 1D radial model of `radial.rs` with FRAPCON's relocation written
/// again from the correlation (`RadialPellet::relocation_share`), at every step of the 30 s
/// run, against the 2D cross-section (generalized plane strain, refinement 6, JFNK), within
/// 0.5 % (the coupled pellet's bound). The specification's 80 um gap at 10 MWd/kgU:
///
/// - at 20 kW/m relocation takes 32 um of it and the gap stays open (27.3 um at 30 s, where
///   without relocation it is 59 um); measured (centre, gap, P_c, P_o): 0.021 %, 0.015 %,
///   0.007 %, 0.007 %;
/// - at 60 kW/m contact engages at 11.43 s (the radial model's time within the closure
///   bound), the peak interface pressure 18.5 MPa; measured (centre, gap, P_c, P_o,
///   p_contact / peak): 0.048 %, 0.030 %, 0.15 %, 0.010 %, 0.23 %.
///
/// The radial model's cladding carries the pellet's contact force spread over its own surface
/// (`cladding_contact_share = a / b`), as the mortar coupling transfers it (the slave's force
/// `p 2 pi a` onto the master). With the pressure on both surfaces instead (share 1, the
/// default cases' reading) the two small-deformation models differ by the as-built gap over
/// the radius at this gap: P_c 0.90 % and p_contact 1.38 % at refinement 6, 0.97 % and 1.48 %
/// at 8, not falling with refinement; a finite-deformation contact (both surfaces where they
/// moved to) would carry the full pressure on both.
#[test]
fn with_relocation_the_cross_section_agrees_with_the_radial_model() {
    for (power, closes) in [(20e3, false), (60e3, true)] {
        let mut s = relocated(power);
        s.mesh.refinement = 6;
        s.solver.method = SolverMethod::Jfnk;
        // The cladding carries the pellet's contact force spread over its surface, as the
        // mortar coupling transfers it (`a / b` of the pressure: 1.9 % less at this gap).
        let model = RadialPellet {
            cladding_contact_share: s.pellet.radius / s.cladding.inner_radius,
            ..RadialPellet::from_scene(&s)
        };
        let (rep, radial, worst, peak) = against_radial(&s, model, &format!("relocation-{power}"));
        assert_eq!(rep["models"]["relocation"], "frapcon");
        eprintln!(
            "relocation at {power} W/m: largest relative differences to the radial model \
             (centre, gap, P_c, P_o, p_contact/peak): {worst:?}; peak contact pressure {peak:e} \
             Pa; closure {} (model) vs {:?} (radial); final gap {} m",
            rep["gap_closure_time"], radial.closure, rep["gap"]
        );
        for (what, w) in ["centre", "gap", "P_c", "P_o", "p_contact"]
            .iter()
            .zip(worst)
        {
            assert!(
                w < crate::claims::claim("pellet.relocation").bound,
                "{power} W/m: {what} differs by {w:.2e}"
            );
        }
        let gap = rep["gap"].as_f64().unwrap();
        if closes {
            assert!(peak > 1e6, "the contact pressure rises ({peak} Pa)");
            let closure = rep["gap_closure_time"].as_f64().expect("contact engages");
            let reference = radial.closure.expect("engages").interpolated_time;
            assert!(
                (closure - reference).abs() < crate::claims::claim("pellet.closure").bound + 1e-9,
                "{closure} vs {reference}"
            );
        } else {
            assert!(rep["gap_closure_time"].is_null() && radial.closure.is_none());
            // Without relocation the gap would be 59 um: the model moved it.
            assert!(gap > 20e-6 && gap < 35e-6, "final gap {gap}");
        }
    }
}

/// A program's own relocation model reaches the scene file by name through the registry: one
/// that delegates to FRAPCON's under another name runs the scene bit for bit as `"frapcon"`
/// does; an unregistered name is refused, naming the known ones.
#[test]
fn a_relocation_model_of_ones_own_is_named_by_the_scene() {
    #[derive(Debug)]
    struct Mine;
    impl RelocationModel for Mine {
        fn name(&self) -> &str {
            "mine"
        }
        fn strain(&self, rod: &RelocationInput) -> f64 {
            FrapconRelocation.strain(rod)
        }
    }
    let mut s = relocated(20e3);
    s.mesh.refinement = 1;
    s.time.end = 4.0;
    let shipped = run_scene(&s, "relocation-shipped");
    let mut registry = LawRegistry::with_shipped();
    registry.register_relocation(Mine);
    s.model.relocation = "mine".into();
    let dir = std::env::temp_dir().join(format!("mortar-relocation-mine-{}", std::process::id()));
    let mine = run_with_registry(&s, &registry, &dir, false).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(mine["models"]["relocation"], "mine");
    for key in ["center_temperature", "gap", "plenum_pressure"] {
        assert_eq!(shipped["history"][key], mine["history"][key], "{key}");
    }
    s.model.relocation = "escore".into();
    let err = run_with_registry(&s, &registry, &dir, false).unwrap_err();
    let text = err.to_string();
    assert!(
        matches!(err, PelletError::Law(_)) && text.contains("escore") && text.contains("frapcon"),
        "{text}"
    );
    assert!(!dir.exists(), "a refused scene writes nothing");
}

/// The relocation keys are checked: a burnup that is negative or not finite, a burnup
/// without a relocation model (it would change nothing), relocation in the heat-only scene,
/// each refused naming the key.
#[test]
fn relocation_keys_are_checked() {
    let base = "kind = \"pellet\"\n[model]\n";
    for (body, key) in [
        ("relocation = \"frapcon\"\nburnup = -1.0", "model.burnup"),
        ("relocation = \"frapcon\"\nburnup = nan", "model.burnup"),
        ("burnup = 5.0", "model.burnup"),
        (
            "relocation = \"frapcon\"\nmechanics = false",
            "model.relocation",
        ),
    ] {
        let err = PelletScene::from_toml(&format!("{base}{body}")).unwrap_err();
        assert!(
            matches!(err, PelletError::Invalid(_)) && err.to_string().contains(key),
            "{body}: {err}"
        );
    }
    let s =
        PelletScene::from_toml(&format!("{base}relocation = \"frapcon\"\nburnup = 30.0")).unwrap();
    assert_eq!(
        (s.model.relocation.as_str(), s.model.burnup),
        ("frapcon", 30.0)
    );
    // The exact law is accepted with relocation too.
    let mut s = relocated(20e3);
    s.contact.law = ContactLawName::Exact;
    assert!(s.check().is_ok());
}
