//! `mortar run`: a scene file (or a built-in scene) in, VTU files and `report.json` out.
//!
//! The scene file's `kind` picks the problem; add a kind with one arm in [`run_kind`].

use std::path::Path;

use mortar::io::write_outputs;
use mortar::scenes::file::{
    builtin_scene, scene_kind, tied_heat::TiedHeatSpec, FileSystem, InMemory, SceneOutput,
    SceneSource,
};

use super::RunArgs;

/// Runs the command; the error is the message for the user.
pub(super) fn run(args: &RunArgs, json: bool) -> Result<(), String> {
    let (output, extra) = match (&args.scene_file, &args.scene) {
        (Some(path), None) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| format!("cannot read scene file {}: {e}", path.display()))?;
            let base = path.parent().unwrap_or(Path::new("")).to_path_buf();
            (run_kind(&text, path, &base, &FileSystem)?, Vec::new())
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
            let output = run_kind(&scene.toml, &path, &base, &source)?;
            let mut extra = scene.meshes;
            extra.push(("scene.toml".to_string(), scene.toml.into_bytes()));
            (output, extra)
        }
        _ => return Err("give a scene file or --scene NAME (not both)".into()),
    };
    let mut files: Vec<(&str, Vec<u8>)> = output
        .files
        .iter()
        .map(|(n, b)| (n.as_str(), b.clone()))
        .collect();
    files.extend(extra.iter().map(|(n, b)| (n.as_str(), b.clone())));
    write_outputs(&args.out, &files).map_err(|e| e.to_string())?;
    if json {
        let report = output
            .files
            .iter()
            .find(|(n, _)| n == "report.json")
            .map(|(_, b)| String::from_utf8_lossy(b).into_owned())
            .unwrap_or_default();
        print!("{report}");
    } else {
        println!("{}", output.summary);
        let names: Vec<&str> = files.iter().map(|(n, _)| *n).collect();
        println!("output: {} ({})", args.out.display(), names.join(", "));
    }
    Ok(())
}

/// Dispatches on the scene's `kind`.
fn run_kind(
    text: &str,
    path: &Path,
    base: &Path,
    source: &dyn SceneSource,
) -> Result<SceneOutput, String> {
    let kind = scene_kind(text, path).map_err(|e| e.to_string())?;
    match kind.as_str() {
        "tied_heat" => {
            let spec = TiedHeatSpec::parse(text, path).map_err(|e| e.to_string())?;
            spec.run(path, base, source).map_err(|e| e.to_string())
        }
        // Wired to `mortar::scenes::pellet` when that scene lands.
        "pellet" => Err(format!(
            "{}: scene kind 'pellet' is not available in this build",
            path.display()
        )),
        other => Err(format!(
            "{}: kind: unknown scene kind \"{other}\" (known kinds: tied_heat)",
            path.display()
        )),
    }
}
