//! The `mortar` command line as a library function, so that a program of one's own gets the
//! same commands (`couple`, `run`, `demo`, the default pellet) with its own elements and laws:
//!
//! ```no_run
//! use mortar::extend::Registries;
//!
//! fn main() -> std::process::ExitCode {
//!     let registries = Registries::default(); // ... plus the program's own elements and laws
//!     mortar_app::cli::main_with(registries)
//! }
//! ```
//!
//! These are a program's `main`, not library routines: they parse the command line, install
//! the Ctrl-C handler, print to standard output and standard error, and end the process with
//! status 141 when the reader of standard output has gone (`mortar ... | head`). Errors print
//! one line on stderr and give status 1 (2 for a bad command line, 130 for a run stopped by
//! Ctrl-C).

/// `say!` for the command's output: a reader that has gone (`mortar ... | head`) ends the
/// process quietly with the status of a broken pipe, 141, as the Unix tools do, instead of a
/// panic; any other failure to write is an error message and status 1.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::cli::print_line(format_args!($($arg)*))
    };
}

mod couple;
mod pellet_report;
mod report;
mod run;
mod scene;

use std::ffi::OsString;
use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use mortar::extend::Registries;
use mortar::settings::{parse_name, CouplingSettings, Integration, Multipliers};
use mortar_scenes::linear_solver::BackendChoice;

/// Mortar coupling of non-conforming interfaces: the operators D and M, tied heat, gap
/// conductance.
///
/// With no command, runs the built-in pellet scene (a fuel pellet in its cladding: heat
/// conduction with k(T), thermal expansion free axially, helium gap conductance on the
/// mechanical gap, contact, plenum pressure) into `out/pellet` with a progress bar.
#[derive(Debug, Parser)]
#[command(name = "mortar", version, about, long_about, disable_help_flag = true)]
struct Cli {
    /// Print the summary as JSON instead of text.
    #[arg(long, global = true)]
    json: bool,

    /// Print help (`-h` and `--help` print the same).
    #[arg(short = 'h', long = "help", global = true, action = clap::ArgAction::HelpLong, display_order = 1000)]
    help: Option<bool>,

    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Couple two Gmsh 4.1 surfaces: write DIR/D.mtx, DIR/M.mtx, DIR/gap.mtx (the weighted
    /// gap G = D x_s - M x_m), DIR/normals.mtx (the slave's nodal normals) and
    /// DIR/summary.json.
    ///
    /// FILE#GROUP selects the elements of a physical group (by name, or by physical tag);
    /// FILE alone takes all elements of dimension 2 of the file, or of dimension 1 if it has
    /// none (a 2D problem with lines in the plane z = 0); a flat file of both needs a group.
    /// Each surface is oriented first (outward from the cells of its file when it bounds
    /// them, else made consistent and turned to face the other surface; --keep-orientation
    /// trusts the files). Slave area no master face covers is a warning (an error with
    /// --require-full-coverage). Rows of D and M are the slave nodes, columns the slave (D)
    /// or master (M) nodes, each by ascending node tag; gap.mtx and normals.mtx are dense
    /// arrays, a row per slave node (as D's rows), a column per coordinate (2 in 2D). Nothing
    /// is written unless everything succeeds. Under `mpirun -n P` (a build with `--features
    /// mpi`), the P ranks each couple a block of the faces and rank 0 writes D.mtx, M.mtx (the
    /// one-process operators, to round-off) and summary.json with every rank's counts.
    #[command(
        disable_help_flag = true,
        after_help = "Example:\n  mortar couple --slave block.msh#contact --master plate.msh#top --out out --lm dual\n  mpirun -n 2 mortar couple --slave block.msh#contact --master plate.msh#top --out out"
    )]
    Couple(CoupleArgs),

    /// Solve a scene: a scene file (TOML, kind = "tied_heat", "contact" or "pellet") naming
    /// Gmsh meshes, physical groups, materials, boundary conditions and the interface, or a
    /// built-in scene. Writes DIR/report.json (formulation and why, unknowns, seconds per
    /// phase) and, for tied_heat, DIR/BODY.vtu per body (temperature); for contact,
    /// DIR/BODY.vtu per body (displacement, stresses, von Mises) and DIR/interface.vtu (gap,
    /// contact pressure on the slave surface); for pellet, VTU snapshots over time and PNG
    /// plots. The built-in tied_heat, hertz2d, hertz3d and shrink_fit also write their scene
    /// file (scene.toml) and meshes; the contact ones put the closed forms beside the
    /// computed values in report.json. Nothing is written unless everything succeeds.
    #[command(
        disable_help_flag = true,
        after_help = "Examples:\n  mortar run examples/scenes/tied_square.toml --out out\n  mortar run --scene tied_heat --out out"
    )]
    Run(RunArgs),

    /// Couple a built-in pair of non-matching meshes of the unit square (Tri3 24 x 24 against
    /// Quad4 35 x 35) and print the summary.
    #[command(disable_help_flag = true)]
    Demo,
}

/// Arguments of `mortar run`.
#[derive(Debug, Args)]
struct RunArgs {
    /// The scene file (TOML; `kind = "tied_heat"`, `"contact"` or `"pellet"`).
    #[arg(
        value_name = "SCENE.toml",
        required_unless_present = "scene",
        conflicts_with = "scene"
    )]
    scene_file: Option<PathBuf>,

    /// A built-in scene instead of a file (tied_heat, pellet, hertz2d, hertz3d, shrink_fit).
    #[arg(long, value_name = "NAME")]
    scene: Option<String>,

    /// Output directory (created if missing).
    #[arg(short, long, value_name = "DIR")]
    out: PathBuf,

    /// Where the scene's linear systems go, in place of its `[solve] backend` (`[solver]` for
    /// a pellet): auto, direct or petsc (a build with `--features petsc`).
    #[arg(long, value_name = "BACKEND", value_parser = parse_name::<BackendChoice>)]
    backend: Option<BackendChoice>,
}

/// Arguments of `mortar couple`.
#[derive(Debug, Args)]
struct CoupleArgs {
    /// Slave (non-mortar) surface: carries the multipliers; its normal points to the master.
    #[arg(long, value_name = "FILE[#GROUP]")]
    slave: String,

    /// Master (mortar) surface.
    #[arg(long, value_name = "FILE[#GROUP]")]
    master: String,

    /// Output directory (created if missing).
    #[arg(short, long, value_name = "DIR")]
    out: PathBuf,

    /// Lagrange-multiplier space: standard, dual (D diagonal; the default, as in scene files
    /// and Python) or linear (second-order faces: corner nodes only).
    #[arg(long, value_name = "SPACE", value_parser = parse_name::<Multipliers>,
          default_value_t = Multipliers::default())]
    lm: Multipliers,

    /// Integration strategy: segment (exact segmentation, the default) or element (slave
    /// quadrature points projected).
    #[arg(long, value_name = "STRATEGY", value_parser = parse_name::<Integration>,
          default_value_t = Integration::default())]
    integration: Integration,

    /// Quadrature degree (1 to 20; default: automatic, exact on flat faces).
    #[arg(long, value_name = "N")]
    degree: Option<u32>,

    /// Segment-based, curved second-order faces in 3D: the subdivision tolerance (bend left
    /// per flat sub-triangle, relative to the face size; default 1e-2).
    #[arg(long, value_name = "TOL")]
    curved_tolerance: Option<f64>,

    /// Segment-based, curved second-order faces in 3D: a fixed subdivision level (1 to 16)
    /// instead of the tolerance's.
    #[arg(long, value_name = "L")]
    subdivision: Option<u32>,

    /// Segment-based, slave quads that are not parallelograms: cut each clip triangle into
    /// M^2 (1 to 16; default 1) so that M follows the master edges' curved images more
    /// closely (error about M^-4, cost M^2 on such faces).
    #[arg(long, value_name = "M")]
    quad_subdivision: Option<u32>,

    /// Worker threads (default: all cores, or RAYON_NUM_THREADS).
    #[arg(long, value_name = "N")]
    threads: Option<usize>,

    /// How far along the slave normals (both ways) to look for master faces, in the mesh's
    /// units (default: as far as the nearest master surface, within a quarter of the
    /// interface's size). Master faces beyond it are not coupled.
    #[arg(long, value_name = "DISTANCE")]
    search_radius: Option<f64>,

    /// Fail (and write nothing) if part of the slave surface finds no master face or a pair
    /// is skipped, instead of warning.
    #[arg(long)]
    require_full_coverage: bool,

    /// Trust the node order of the files: do not orient the surfaces. By default each surface
    /// is oriented outward from the cells of its file when the file has them, otherwise made
    /// consistent piece by piece and turned so that the slave faces the master.
    #[arg(long)]
    keep_orientation: bool,
}

impl CoupleArgs {
    fn settings(&self) -> CouplingSettings {
        CouplingSettings {
            multipliers: self.lm,
            integration: self.integration,
            degree: self.degree,
            curved_tolerance: self.curved_tolerance,
            subdivision: self.subdivision,
            quad_subdivision: self.quad_subdivision,
            threads: self.threads,
            search_radius: self.search_radius,
            require_full_coverage: self.require_full_coverage,
        }
    }
}

/// The `mortar` program with the shipped elements and laws: [`main_with`] of
/// [`Registries::default`].
pub fn main() -> ExitCode {
    main_with(Registries::default())
}

/// The `mortar` program with the elements and laws of `registries`: parses the process's
/// command line ([`run_from`]).
pub fn main_with(registries: Registries) -> ExitCode {
    run_from(std::env::args_os(), &registries)
}

/// Runs the `mortar` command line `args` (the program name first, as
/// [`std::env::args_os`] gives it) with the elements and laws of `registries`: `couple` reads
/// surfaces of `registries.elements`, `run` reads bodies of `registries.cells` and makes the
/// laws a scene names by `registries.laws`. Returns the exit status; a failure is one line on
/// stderr (`mortar: error: ...`), a bad command line clap's message and status 2.
pub fn run_from<I, T>(args: I, registries: &Registries) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            // Help and version go to stdout with status 0, mistakes to stderr with 2.
            let _ = e.print();
            return ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(2));
        }
    };
    if let Err(e) = crate::interrupt::install_handler() {
        eprintln!("mortar: warning: {e}; Ctrl-C will end the run without its outputs");
    }
    crate::progress::install();
    let result = match &cli.command {
        None => run::default_job(std::path::Path::new("out/pellet"), cli.json),
        Some(Command::Demo) => scene::run(cli.json),
        Some(Command::Couple(args)) => couple::run(args, cli.json, registries),
        Some(Command::Run(args)) => run::run(args, cli.json, registries),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            let line: String = message
                .chars()
                .map(|c| if c == '\n' || c == '\r' { ' ' } else { c })
                .collect();
            eprintln!("mortar: error: {line}");
            if mortar_scenes::interrupt::requested() {
                // 128 + SIGINT, as a shell reports an interrupted command.
                ExitCode::from(130)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}

/// The exit status of a process whose standard output was closed by its reader (128 +
/// SIGPIPE, what a shell reports for a Unix tool killed by the signal).
const BROKEN_PIPE_STATUS: i32 = 141;

/// Writes one line to standard output (see `say!`).
pub(crate) fn print_line(args: std::fmt::Arguments<'_>) {
    let mut out = std::io::stdout().lock();
    if let Err(e) = out
        .write_fmt(args)
        .and_then(|()| out.write_all(b"\n"))
        .and_then(|()| out.flush())
    {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(BROKEN_PIPE_STATUS);
        }
        eprintln!("mortar: cannot write to standard output: {e}");
        std::process::exit(1);
    }
}
