//! `mortar`: the command-line program of the mortar toolkit.
//!
//! - `mortar` (no arguments): couples the built-in default scene (two non-matching meshes of
//!   the unit square) and prints its summary; `mortar --json` prints it as JSON.
//! - `mortar couple --slave FILE[#GROUP] --master FILE[#GROUP] --out DIR [...]`: reads two
//!   Gmsh 4.1 surfaces, computes the mortar operators and writes `DIR/D.mtx`, `DIR/M.mtx` and
//!   `DIR/summary.json`.
//!
//! Errors print one line on stderr and exit with status 1 (2 for a bad command line).

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
