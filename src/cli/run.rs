//! `mortar run`: a scene file (or a built-in scene) in, VTU files and `report.json` out.
//!
//! The scene file's `kind` picks the problem ([`run_scene`] of the scenes).

use std::path::Path;

use mortar::io::write_outputs;
use mortar_scenes::file::{
    builtin_scene, run_builtin_contact, FileSystem, InMemory, BUILTIN_CONTACT_SCENES,
};
use mortar_scenes::pellet::PelletScene;
use mortar_scenes::{run_scene, SceneContext};

use mortar::extend::Registries;
use mortar_scenes::pellet;
use serde_json::Value;

use super::RunArgs;

/// Runs the built-in pellet scene into `out` with a progress bar (the default job).
pub(super) fn default_job(out: &Path, json: bool) -> Result<(), String> {
    if !json {
        say!(
            "mortar: default scene, a fuel pellet in its cladding: heat, thermal expansion, \
             contact across the gap, plenum pressure (2D, free axial expansion)"
        );
        say!("(your own scenes: `mortar run SCENE.toml --out DIR`; see `mortar --help`)\n");
    }
    let report = pellet::run_builtin(out, !json).map_err(|e| e.to_string())?;
    print_pellet(&report, out, json);
    Ok(())
}

/// Prints the pellet's report: JSON, or the steady temperatures against the closed form.
fn print_pellet(report: &Value, out: &Path, json: bool) {
    if json {
        say!("{report}");
        return;
    }
    if report["models"]["mechanics"].as_bool() == Some(true) {
        print_coupled(report, out);
        return;
    }
    let num = |v: &Value| v.as_f64().map_or("n/a".to_string(), |x| format!("{x:.3}"));
    for key in [
        "center_temperature",
        "pellet_surface_temperature",
        "cladding_inner_temperature",
    ] {
        let closed = report
            .get("closed_form")
            .and_then(|c| c.get(key))
            .unwrap_or(&Value::Null);
        say!(
            "{key:<28} {} K   (closed form {} K)",
            num(&report[key]),
            num(closed)
        );
    }
    let rel = &report["error"]["center_relative_to_span"];
    if let Some(rel) = rel.as_f64() {
        say!("{:<28} {:.2e} of (T_0 - T_co)", "centre error", rel);
    }
    let solver = &report["solver"];
    say!(
        "{:<28} {} Newton steps, {} linear iterations, {} factorisations",
        format!("solver ({})", report["method"].as_str().unwrap_or("?")),
        solver["newton_iterations"],
        solver["linear_iterations"],
        solver["factorizations"]
    );
    if let Some(t) = report["seconds"]["total"].as_f64() {
        say!("{:<28} {t:.3} s", "time");
    }
    say!("output: {} (report.json, VTU over time)", out.display());
}

/// Prints the thermomechanical pellet's report: what was modelled and why, and the results.
fn print_coupled(report: &Value, out: &Path) {
    let f = |v: &Value| v.as_f64().unwrap_or(f64::NAN);
    let m = &report["models"];
    let law = m["contact_law"].as_str().unwrap_or("?");
    let free = m["axial"].as_str() == Some("generalized");
    let elasticity = match (m["geometry"].as_str(), free) {
        (Some("3d"), true) => "3D thermoelasticity (a segment, its top free axially)",
        (Some("3d"), false) => "3D thermoelasticity (a segment, ends held in z)",
        (Some("axisymmetric"), true) => "r-z thermoelasticity (a segment, its top free axially)",
        (Some("axisymmetric"), false) => "r-z thermoelasticity (a segment, ends held in z)",
        (_, true) => "generalized plane strain thermoelasticity (free axial expansion)",
        (_, false) => "plane-strain thermoelasticity",
    };
    say!(
        "{:<28} heat with k(T), {elasticity}, gap conductance on the",
        "modelled"
    );
    say!(
        "{:<28} mechanical gap, {law} contact law, plenum pressure (ideal gas)",
        ""
    );
    if let Some(model) = m["relocation"].as_str().filter(|&r| r != "none") {
        say!(
            "{:<28} {model} relocation at {} MWd/kgU: strain {:.3e} at full power",
            "",
            f(&m["burnup"]),
            f(&report["steady"]["relocation_strain"])
        );
    }
    // The exponential law engages below its onset gap xi, with the gap still open; the
    // exact law engages at a closed gap.
    let onset = m["contact_onset_gap"].as_f64();
    match (report["gap_closure_time"].as_f64(), onset) {
        (Some(t), Some(xi)) => say!(
            "{:<28} contact engaged at t = {t:.2} s (smallest gap below the onset of the pressure law, \
             xi = {:.2} um)",
            "gap",
            1e6 * xi
        ),
        (Some(t), None) => say!(
            "{:<28} contact engaged at t = {t:.2} s (gap closed, contact pressure positive)",
            "gap"
        ),
        (None, _) => say!(
            "{:<28} contact never engaged (the pressure stays at the gas pressure)",
            "gap"
        ),
    }
    let h = &report["history"];
    let last = |k: &str| h[k].as_array().and_then(|a| a.last()).map_or(f64::NAN, f);
    say!(
        "{:<28} {:.3} K",
        "centre temperature",
        f(&report["center_temperature"])
    );
    say!(
        "{:<28} {:.3} um (mean; min {:.3} um)",
        "final gap",
        1e6 * f(&report["gap"]),
        1e6 * last("min_gap")
    );
    say!(
        "{:<28} {:.3} MPa (interface, incl. gas)",
        "peak contact pressure",
        1e-6 * f(&report["peak_interface_pressure"])
    );
    // A stack's lands: the pellets bearing on each other.
    if let (Some(gap), Some(p)) = (
        h["land_min_gap"].as_array(),
        h["land_peak_contact_pressure"].as_array(),
    ) {
        let smallest = gap.iter().map(f).fold(f64::INFINITY, f64::min);
        let peak = p.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
        say!(
            "{:<28} smallest gap {:.3} um, peak contact pressure {:.3} MPa",
            "pellet lands",
            1e6 * smallest,
            1e-6 * peak
        );
    }
    say!(
        "{:<28} {:.4} MPa",
        "plenum pressure",
        1e-6 * f(&report["plenum_pressure"])
    );
    let st = &report["steady"];
    say!(
        "{:<28} T0 {:.3} K, energy imbalance {:.1e}",
        "steady state (full power)",
        f(&st["center_temperature"]),
        f(&st["relative_imbalance"])
    );
    for w in report["coupling_warnings"].as_array().into_iter().flatten() {
        eprintln!("mortar: warning: {}", w.as_str().unwrap_or_default());
    }
    // The model ranges the run left (docs/models.md, section 3b), one line each.
    let limits = pellet::limits::summary_lines(&report["warnings"]);
    if limits.is_empty() {
        say!("{:<28} ok: every state within the models' ranges", "status");
    } else {
        say!(
            "{:<28} warnings: {} model range(s) left, the results there are not physical",
            "status",
            limits.len()
        );
        for line in limits {
            say!("  warning {line}");
        }
    }
    let solver = &report["solver"];
    say!(
        "{:<28} {} Newton steps, {} linear iterations, {} factorisations, {} step cuts",
        format!("solver ({})", report["method"].as_str().unwrap_or("?")),
        solver["newton_iterations"],
        solver["linear_iterations"],
        solver["factorizations"],
        solver["step_cuts"]
    );
    let choice = &report["solver_choice"];
    if let Some(why) = choice["why"].as_str() {
        say!("{:<28} {why}", "");
    }
    if let Some(t) = choice["fallback_to_newton"]["time"].as_f64() {
        say!("{:<28} JFNK failed at t = {t} s: Newton took over", "");
    }
    say!("{:<28} {:.3} s", "time", f(&report["seconds"]["total"]));
    say!("output: {} (report.json, VTU over time)", out.display());
}

/// `mortar run`: a scene file of any kind, or a built-in scene (written out beside its
/// results as `scene.toml` and its meshes, for the user to copy), through the one
/// [`run_scene`] of the scenes.
pub(super) fn run(args: &RunArgs, json: bool, registries: &Registries) -> Result<(), String> {
    // A scene named `path`, its meshes under `base` from `source`, written into DIR.
    let ctx = |path, base, source| SceneContext {
        path,
        base,
        source,
        registries,
        out: &args.out,
        progress: !json,
    };
    let (run, extra) = match (&args.scene_file, &args.scene) {
        (Some(path), None) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| format!("cannot read scene file {}: {e}", path.display()))?;
            let base = path.parent().unwrap_or(Path::new(""));
            let ctx = ctx(path, base, &FileSystem);
            (
                run_scene(&text, &ctx).map_err(|e| e.to_string())?,
                Vec::new(),
            )
        }
        (None, Some(name)) if name == "pellet" => {
            // The built-in pellet is the scene file of every default, written out beside it.
            let scene = PelletScene {
                scene: Some("pellet".into()),
                ..PelletScene::default()
            };
            let toml = toml::to_string(&scene).map_err(|e| e.to_string())?;
            let path = args.out.join("scene.toml");
            let ctx = ctx(&path, &args.out, &FileSystem);
            let run = run_scene(&toml, &ctx).map_err(|e| e.to_string())?;
            (run, vec![("scene.toml".to_string(), toml.into_bytes())])
        }
        (None, Some(name)) if BUILTIN_CONTACT_SCENES.contains(&name.as_str()) => {
            let output = run_builtin_contact(name)
                .map_err(|e| e.to_string())?
                .ok_or_else(|| format!("no built-in contact scene named \"{name}\""))?;
            let ctx = ctx(Path::new(name.as_str()), &args.out, &FileSystem);
            let run = mortar_scenes::write_scene_output("contact", output, &ctx)
                .map_err(|e| e.to_string())?;
            (run, Vec::new())
        }
        (None, Some(name)) => {
            let scene = builtin_scene(name).map_err(|e| e.to_string())?;
            // The scene runs from its meshes in memory, as if written into DIR; they are
            // written there with its scene file, beside the results.
            let base = args.out.clone();
            let path = base.join("scene.toml");
            let source = InMemory {
                files: scene
                    .meshes
                    .iter()
                    .map(|(name, bytes)| (base.join(name), bytes.clone()))
                    .collect(),
            };
            let ctx = ctx(&path, &base, &source);
            let run = run_scene(&scene.toml, &ctx).map_err(|e| e.to_string())?;
            let mut extra = scene.meshes;
            extra.push(("scene.toml".to_string(), scene.toml.into_bytes()));
            (run, extra)
        }
        _ => return Err("give a scene file or --scene NAME (not both)".into()),
    };
    let extra_files: Vec<(&str, Vec<u8>)> =
        extra.iter().map(|(n, b)| (n.as_str(), b.clone())).collect();
    write_outputs(&args.out, &extra_files).map_err(|e| e.to_string())?;
    if run.kind == "pellet" {
        print_pellet(&run.report, &args.out, json);
        return Ok(());
    }
    for w in &run.warnings {
        eprintln!("mortar: warning: {w}");
    }
    if json {
        print!("{}", run.report_json);
    } else {
        say!("{}", run.summary);
        let names: Vec<&str> = run
            .files
            .iter()
            .map(String::as_str)
            .chain(extra.iter().map(|(n, _)| n.as_str()))
            .collect();
        say!("output: {} ({})", args.out.display(), names.join(", "));
    }
    Ok(())
}
