//! The built-in pellet scene (docs/models.md, sections 3 and 3a): a UO2 pellet in its zircaloy
//! cladding, helium in the gap, power ramped to 20 kW/m, cladding outer surface at 580 K;
//! thermal expansion narrows the gap into contact, the pressure law and the plenum act. Solved by Newton
//! and by JFNK, which must agree; then the thermal-only scene (gap held open) against the
//! closed form.
//!
//! ```text
//! cargo run --release --example pellet [OUT_DIR [REFINEMENT]]
//! ```

use std::path::PathBuf;

use mortar_scenes::pellet::{run as run_scene, PelletScene, SolverMethod};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run(&std::env::args().skip(1).collect::<Vec<_>>())
}

/// Runs the example with the arguments `[OUT_DIR [REFINEMENT]]`.
pub fn run(args: &[String]) -> Result<(), Box<dyn std::error::Error>> {
    let out = args
        .first()
        .map(PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("mortar-pellet"));
    let refinement = match args.get(1) {
        Some(r) => r.parse()?,
        None => PelletScene::default().mesh.refinement,
    };
    let num = |v: &serde_json::Value| v.as_f64().unwrap_or(f64::NAN);
    let mut centre = Vec::new();
    for method in [SolverMethod::Newton, SolverMethod::Jfnk] {
        let mut scene = PelletScene::default();
        scene.mesh.refinement = refinement;
        scene.solver.method = method;
        let dir = out.join(format!("{method:?}").to_lowercase());
        let r = run_scene(&scene, &dir, true)?;
        let s = &r["solver"];
        println!("{method:?}: outputs in {}", dir.display());
        println!(
            "  contact engaged at {:.3} s (gap below xi); centre {:.4} K, gap {:.4} um, peak interface pressure {:.4} MPa, plenum {:.5} MPa",
            num(&r["gap_closure_time"]),
            num(&r["center_temperature"]),
            1e6 * num(&r["gap"]),
            1e-6 * num(&r["peak_interface_pressure"]),
            1e-6 * num(&r["plenum_pressure"]),
        );
        println!(
            "  {} Newton steps, {} linear iterations, {} factorisations, {:.3} s in Newton",
            s["newton_iterations"],
            s["linear_iterations"],
            s["factorizations"],
            num(&s["seconds"]["newton_total"])
        );
        centre.push(num(&r["center_temperature"]));
    }
    let diff = (centre[0] - centre[1]).abs() / centre[0];
    println!("Newton and JFNK centre temperatures differ by {diff:.1e} (relative)");
    if diff > 1e-8 {
        return Err(format!("Newton and JFNK disagree by {diff:e}").into());
    }
    // Thermal only, the gap held at its as-built width: the closed form of section 5.
    let mut scene = PelletScene::default();
    scene.mesh.refinement = refinement;
    scene.model.mechanics = false;
    let r = run_scene(&scene, &out.join("thermal"), true)?;
    println!(
        "thermal only: centre {:.3} K, closed form {:.3} K, error {:.2e} of (T_0 - T_co)",
        num(&r["center_temperature"]),
        num(&r["closed_form"]["center_temperature"]),
        num(&r["error"]["center_relative_to_span"])
    );
    Ok(())
}
