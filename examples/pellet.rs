//! The built-in pellet scene (PHYSICS.md sections 4 and 5): a UO2 pellet in its zircaloy
//! cladding, helium in the open gap, power ramped to 20 kW/m, cladding outer surface at
//! 580 K; steady temperatures compared with the closed form, for Newton and JFNK.
//!
//! ```text
//! cargo run --release --example pellet [OUT_DIR [REFINEMENT]]
//! ```

use std::path::PathBuf;

use mortar::scenes::pellet::{run, PelletScene, SolverMethod};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("mortar-pellet"));
    let refinement = match std::env::args().nth(2) {
        Some(r) => r.parse()?,
        None => PelletScene::default().mesh.refinement,
    };
    for method in [SolverMethod::Newton, SolverMethod::Jfnk] {
        let mut scene = PelletScene::default();
        scene.mesh.refinement = refinement;
        scene.solver.method = method;
        let dir = out.join(format!("{method:?}").to_lowercase());
        let r = run(&scene, &dir, true)?;
        let cf = &r["closed_form"];
        println!("{method:?}: outputs in {}", dir.display());
        println!(
            "  {:<28} {:>10} {:>12} {:>8}",
            "", "computed", "closed form", "diff"
        );
        for key in [
            "center_temperature",
            "pellet_surface_temperature",
            "cladding_inner_temperature",
        ] {
            let (a, b) = (
                r[key].as_f64().unwrap_or(f64::NAN),
                cf[key].as_f64().unwrap_or(f64::NAN),
            );
            println!("  {key:<28} {a:>10.3} {b:>12.3} {:>8.3}", a - b);
        }
        let s = &r["solver"];
        println!(
            "  centre error / (T_0 - T_co) = {:.3e}; Newton iterations {}, linear iterations {}, {:.3} s in Newton",
            r["error"]["center_relative_to_span"].as_f64().unwrap_or(f64::NAN),
            s["newton_iterations"],
            s["linear_iterations"],
            s["seconds"]["newton_total"].as_f64().unwrap_or(f64::NAN)
        );
    }
    Ok(())
}
