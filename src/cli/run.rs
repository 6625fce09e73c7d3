//! `mortar run`: a scene file (or a built-in scene) in, VTU files and `report.json` out.
//!
//! The scene file's `kind` picks the problem ([`run_scene`] of the scenes).

use std::path::Path;

use mortar::io::write_outputs;
use mortar_scenes::file::{
    builtin_scene, run_builtin_contact_on, FileSystem, InMemory, BUILTIN_CONTACT_SCENES,
};
use mortar_scenes::linear_solver::{with_backend, BackendChoice};
use mortar_scenes::pellet::PelletScene;
use mortar_scenes::{run_scene, SceneContext};

use mortar::extend::Registries;
use mortar_scenes::pellet;

use super::pellet_report::print_pellet;
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
            let text = backend_in(text, args.backend)?;
            let base = path.parent().unwrap_or(Path::new(""));
            let ctx = ctx(path, base, &FileSystem);
            (
                run_scene(&text, &ctx).map_err(|e| e.to_string())?,
                Vec::new(),
            )
        }
        (None, Some(name)) if name == "pellet" => {
            // The built-in pellet is the scene file of every default, written out beside it.
            let mut scene = PelletScene {
                scene: Some("pellet".into()),
                ..PelletScene::default()
            };
            if let Some(b) = args.backend {
                scene.solver.backend = b;
            }
            let toml = toml::to_string(&scene).map_err(|e| e.to_string())?;
            let path = args.out.join("scene.toml");
            let ctx = ctx(&path, &args.out, &FileSystem);
            let run = run_scene(&toml, &ctx).map_err(|e| e.to_string())?;
            (run, vec![("scene.toml".to_string(), toml.into_bytes())])
        }
        (None, Some(name)) if BUILTIN_CONTACT_SCENES.contains(&name.as_str()) => {
            let output = run_builtin_contact_on(name, args.backend)
                .map_err(|e| e.to_string())?
                .ok_or_else(|| format!("no built-in contact scene named \"{name}\""))?;
            let ctx = ctx(Path::new(name.as_str()), &args.out, &FileSystem);
            let run = mortar_scenes::write_scene_output("contact", output, &ctx)
                .map_err(|e| e.to_string())?;
            (run, Vec::new())
        }
        (None, Some(name)) => {
            let mut scene = builtin_scene(name).map_err(|e| e.to_string())?;
            scene.toml = backend_in(scene.toml, args.backend)?;
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

/// The scene file `text` with `--backend`'s choice, if given.
fn backend_in(text: String, backend: Option<BackendChoice>) -> Result<String, String> {
    match backend {
        Some(b) => with_backend(&text, b),
        None => Ok(text),
    }
}
