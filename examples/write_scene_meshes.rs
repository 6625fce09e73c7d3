//! Writes the two Gmsh meshes of `examples/scenes/tied_square.toml` (ASCII Gmsh 4.1):
//! `tied_square_left.msh` and `tied_square_right.msh`, a unit square cut at x = 1/2 into two
//! bodies meshed independently with a 2:3 size ratio (see
//! `mortar_scenes::file::tied_block`).
//!
//! ```text
//! cargo run --example write_scene_meshes [-- DIR]     # default DIR: examples/scenes
//! cargo run --release -- run examples/scenes/tied_square.toml --out out
//! ```

use std::path::PathBuf;

use mortar::io::MshFormat;
use mortar_scenes::file::tied_block;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run(&std::env::args().skip(1).collect::<Vec<_>>())
}

/// Runs the example with the arguments `[DIR]`.
pub fn run(args: &[String]) -> Result<(), Box<dyn std::error::Error>> {
    let dir = args
        .first()
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/scenes"));
    std::fs::create_dir_all(&dir)?;
    let scene = tied_block(2, 8, MshFormat::Ascii)?;
    for (name, bytes) in &scene.meshes {
        let path = dir.join(format!("tied_square_{name}"));
        std::fs::write(&path, bytes)?;
        println!("wrote {} ({} bytes)", path.display(), bytes.len());
    }
    Ok(())
}
