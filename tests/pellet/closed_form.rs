use mortar_scenes::pellet::{run, PelletScene};

fn out(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("mortar-pellet-test-{}-{name}", std::process::id()))
}

/// A steady-only thermal scene (no transient, the gap held open) at refinement `r`.
fn steady(r: usize) -> PelletScene {
    let mut s = PelletScene::default();
    s.model.mechanics = false;
    s.time.end = 0.0;
    s.time.snapshots = 0;
    s.mesh.refinement = r;
    s
}

/// The error of the centre temperature relative to `T_0 - T_co`, and of the two surfaces.
fn errors(r: usize) -> [f64; 3] {
    let dir = out(&format!("cf{r}"));
    let rep = run(&steady(r), &dir, false).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let e = &rep["error"];
    let span = e["span"].as_f64().unwrap();
    [
        e["center_relative_to_span"].as_f64().unwrap(),
        e["pellet_surface_temperature"].as_f64().unwrap().abs() / span,
        e["cladding_inner_temperature"].as_f64().unwrap().abs() / span,
    ]
}

#[test]
fn default_mesh_within_one_percent_and_converging() {
    let default = PelletScene::default().mesh.refinement;
    let e: Vec<[f64; 3]> = (1..=3).map(errors).collect();
    eprintln!(
        "relative errors (centre, pellet surface, cladding inner) by refinement 1..=3: {e:?}"
    );
    assert!(
        e[default - 1][0] < crate::claims::claim("pellet.thermal_default").bound,
        "default mesh: {:?}",
        e[default - 1]
    );
    for k in 0..3 {
        // Each measure falls with refinement, the centre at about second order in h.
        assert!(
            e[1][k] < e[0][k] && e[2][k] < e[1][k],
            "quantity {k}: {e:?}"
        );
    }
    let rate = (e[0][0] / e[2][0]).ln() / 3f64.ln();
    assert!(rate > 1.5, "centre error rate {rate}: {e:?}");
}

/// Regression: at zero or tiny power the residual starts at round-off
/// (1e-11 W/m against conduction terms of 1e4), Newton's relative criterion asked for
/// round-off of round-off and the line search failed. Source of the reference (closed form):
/// at zero power the temperature is the outer one everywhere; at low power the steady closed
/// form of docs/models.md section 3 (the mesh error scales with the power).
#[test]
fn zero_and_low_power_give_the_outer_temperature_and_the_closed_form() {
    for power in [0.0, 1e-6, 1.0] {
        let mut s = steady(2);
        s.power.linear_power = power;
        let dir = out(&format!("low{power}"));
        let rep = run(&s, &dir, false).unwrap_or_else(|e| panic!("power {power}: {e}"));
        let _ = std::fs::remove_dir_all(&dir);
        let t0 = rep["center_temperature"].as_f64().unwrap();
        let cf = rep["closed_form"]["center_temperature"].as_f64().unwrap();
        let t_co = s.cladding.outer_temperature;
        eprintln!("power {power} W/m: centre {t0} K, closed form {cf} K");
        if power == 0.0 {
            assert!((t0 - t_co).abs() <= 1e-12 * t_co, "{t0}");
        } else {
            // The rise above T_co within the default mesh's 1 % (as at full power).
            assert!(
                (t0 - cf).abs() <= 0.01 * (cf - t_co),
                "power {power}: centre {t0} against {cf}"
            );
        }
    }
}
