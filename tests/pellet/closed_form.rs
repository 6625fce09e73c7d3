use mortar::scenes::pellet::{run, PelletScene};

fn out(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("mortar-pellet-test-{}-{name}", std::process::id()))
}

/// A steady-only scene (no transient) at refinement `r`.
fn steady(r: usize) -> PelletScene {
    let mut s = PelletScene::default();
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
        e[default - 1][0] < 0.01,
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
