//! `mortar`: the command-line program of the mortar toolkit, [`mortar_app::cli::main`] with the
//! shipped elements and laws (a program of one's own calls [`mortar_app::cli::main_with`]).
//!
//! - `mortar` (no arguments): runs the built-in thermomechanical pellet scene into
//!   `out/pellet` with a progress bar and prints what it modelled and its results;
//!   `mortar --json` prints the report as JSON. `mortar demo` couples a built-in pair of
//!   non-matching meshes of the unit square and prints the coupling summary.
//! - `mortar run SCENE.toml --out DIR` (or `--scene NAME`): a scene file or a built-in scene.
//! - `mortar couple --slave FILE[#GROUP] --master FILE[#GROUP] --out DIR [...]`: reads two
//!   Gmsh 4.1 surfaces, computes the mortar operators and writes `DIR/D.mtx`, `DIR/M.mtx` and
//!   `DIR/summary.json`.
//!
//! Errors print one line on stderr and exit with status 1 (2 for a bad command line, 130 for a
//! run stopped by Ctrl-C, 141 when the reader of the output has gone).

fn main() -> std::process::ExitCode {
    mortar_app::cli::main()
}
