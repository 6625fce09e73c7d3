//! Benchmark of the assembly of the mortar operators D and M, and the speed-for-accuracy table.
//!
//! ```text
//! cargo run --release --example bench_coupling -- --json docs/bench.json   # the full benchmark
//! cargo run --release --example bench_coupling -- --quick                  # a smoke run (seconds)
//! cargo run --release --example bench_coupling -- --max-n 316 --json b.json
//! cargo run --release --example bench_coupling -- --tradeoff               # docs/tradeoff.{md,png}
//! ```
//!
//! Cases, built in memory (mesh generation is not timed):
//! - `plane3d`: the unit square at z = 0; slave `n x n` cells cut into triangles along the
//!   (0,0)-(1,1) diagonal, master `floor(1.5 n) + 1` cells per side cut along the other one;
//! - `cylinder`: the lateral surface of the unit cylinder (radius 1, height 1); slave `n` x
//!   `n / 4` quads, master `floor(1.5 n) + 1` x `floor(1.5 n / 4) + 1` cells cut into triangles;
//! - `line2d`: [0, 1] with `n` and `floor(1.5 n) + 1` two-node elements (straight: the sorted
//!   merge);
//! - `arc2d`: the upper half of the unit circle with `n` and `floor(1.5 n) + 1` two-node
//!   chords (curved: the chain walk and the fused kernel);
//! - `arc2d-split` (only with `--at`): arc2d with the master in two chains meeting at the top,
//!   so that each walk also asks whether the other chain reaches the slave face;
//! - `ratio2d`, `ratio3d`: one slave face (a line, a Quad4) against `n` master lines or
//!   `n x n` master quads covering it: the work of one face must stay linear in its partners.
//!
//! Each case also runs `faces-shuffled`: the same meshes with the faces of slave and master
//! stored in a seeded random order (`mortar::testing::shuffled_faces`), the order a mesher that
//! numbers faces far apart writes, and `shuffled`: nodes and faces in random order
//! (`mortar::testing::shuffled`), the worst case; `shuffled_vs_sorted` is the total time over
//! the one of the generator's (spatially coherent) order at the same size and threads, from the
//! same run.
//!
//! Each (case, n, threads, order) runs in a child process (this program re-executed with the
//! hidden `--single CASE N THREADS ORDER`), so that its peak memory (`VmHWM`) is its own, and
//! resets that peak once its meshes are built (Linux `clear_refs`), so that it is the
//! coupling's with the meshes resident, not the mesh shuffler's. The child assembles
//! D and M (segment-based, standard multipliers) `--repeats` times (once for 1e6 slave faces and
//! more, unless `--repeat-large`: on a virtual machine the first write of gigabytes the
//! system has not handed out lately can cost twice the coupling, and the runs after the first
//! show the coupling's own time per pair) and prints one JSON line with the phases of the run
//! of median total time. The parent
//! writes the JSON array to `--json PATH` and prints a table. `bit_identical_to_1_thread`
//! compares a SipHash digest of the bit patterns (`f64::to_bits`) of `data`, `indices` and
//! `indptr` of D and M with the one of the 1-thread run of the same case.
//!
//! `--save-reference DIR` keeps D and M of every case, `--reference DIR` compares each case's
//! with those (largest row-relative difference, and whether it is within 1e-13; see
//! `reference.rs`): run the previous build with the first and this one with the second.
//! `--cases line2d,ratio2d` runs only the named cases.
//!
//! `--tradeoff` writes `docs/tradeoff.md` and `docs/tradeoff.png` instead (see `tradeoff.rs`).
//!
//! `--against OTHER --at cylinder:1024,plane3d:708 --threads-list 1,2 --rounds 3` runs this
//! build and the `bench_coupling` at `OTHER` (a copy of the previous build's) alternately and
//! prints the ratios of their medians and whether D and M are bit-identical (see
//! `against.rs`): a speed change measured against the build before it, each run beside one
//! of the previous build.

#[path = "bench_coupling/against.rs"]
mod against;
#[allow(dead_code)]
#[path = "curved_segmentation.rs"]
mod curved_segmentation;
#[path = "bench_coupling/plot.rs"]
mod plot;
#[path = "bench_coupling/reference.rs"]
mod reference;
#[path = "bench_coupling/tradeoff.rs"]
mod tradeoff;

use std::ffi::OsStr;
use std::hash::Hasher;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use clap::Parser;
use mortar::generate::{
    cylinder_surface, half_circle_mesh, line_mesh, square_quads, square_triangles, Diagonal,
};
use mortar::testing::{shuffled, shuffled_faces};
use mortar::{
    assemble_coupling, assemble_coupling_reusing, Coupling, CouplingOptions, Interface, SurfaceMesh,
};
use serde_json::{json, Value};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

#[derive(Parser, Debug)]
#[command(about = "Benchmark of the mortar coupling assembly, and the speed-for-accuracy table")]
struct Args {
    /// Write the benchmark records (a JSON array) here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Runs per (case, n, threads); the median total is reported. Sizes of 1e6 slave faces and
    /// more run once.
    #[arg(long, default_value_t = 3)]
    repeats: usize,
    /// Run sizes of 1e6 slave faces and more `--repeats` times too (each run after the first
    /// then writes memory the process has written before; `totals_all_repeats` keeps every
    /// run, the first included).
    #[arg(long)]
    repeat_large: bool,
    /// Each run after the first goes through `assemble_coupling_reusing` with the previous
    /// run's coupling (a coupling repeated in a loop: D and M written into its arrays where
    /// the path allows). With `--against`, passed to both builds (the other must know it).
    #[arg(long)]
    reuse: bool,
    /// Largest n of the plane3d and cylinder cases (line2d is not capped).
    #[arg(long)]
    max_n: Option<usize>,
    /// A small smoke run of a few seconds.
    #[arg(long)]
    quick: bool,
    /// Produce the speed-for-accuracy table and plot instead of the benchmark.
    #[arg(long)]
    tradeoff: bool,
    /// Runs per option in the tradeoff table (median time).
    #[arg(long, default_value_t = 7)]
    tradeoff_repeats: usize,
    /// Folder of tradeoff.md and tradeoff.png.
    #[arg(long, default_value = "docs")]
    out_dir: PathBuf,
    /// Save D and M of each case in this folder (for `--reference` of a later build).
    #[arg(long)]
    save_reference: Option<PathBuf>,
    /// Compare D and M of each case with those saved in this folder by `--save-reference`.
    #[arg(long)]
    reference: Option<PathBuf>,
    /// Run only these cases (comma-separated: plane3d, cylinder, line2d, arc2d, ratio2d, ratio3d).
    #[arg(long, value_delimiter = ',')]
    cases: Vec<String>,
    /// Run this build and the `bench_coupling` binary at this path alternately, case by case
    /// (`--at`, `--threads-list`, `--rounds`), and report the ratios of their times and
    /// whether their D and M are bit-identical (see `against.rs`).
    #[arg(long)]
    against: Option<PathBuf>,
    /// With `--against`: the cases and sizes, as CASE:N (comma-separated).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "cylinder:1024,plane3d:708"
    )]
    at: Vec<String>,
    /// With `--against`: the thread counts (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "1")]
    threads_list: Vec<usize>,
    /// With `--against`: rounds (each runs every case with both builds, in alternating order).
    #[arg(long, default_value_t = 3)]
    rounds: usize,
    /// Internal: run one case in this process and print one JSON line.
    #[arg(long, num_args = 4, value_names = ["CASE", "N", "THREADS", "ORDER"], hide = true)]
    single: Option<Vec<String>>,
}

fn main() -> Res<()> {
    let args = Args::parse();
    if let Some(s) = &args.single {
        let record = single(&s[0], s[1].parse()?, s[2].parse()?, &s[3], &args)?;
        println!("{record}");
        return Ok(());
    }
    if args.tradeoff {
        return tradeoff::run(&args.out_dir, args.tradeoff_repeats.max(1));
    }
    if let Some(other) = &args.against {
        let at = args
            .at
            .iter()
            .map(|s| {
                let (case, n) = s.split_once(':').ok_or(format!("--at {s}: not CASE:N"))?;
                Ok((case.to_owned(), n.parse()?))
            })
            .collect::<Res<Vec<(String, usize)>>>()?;
        let this = std::env::current_exe()?;
        return against::run(
            &this,
            other,
            &at,
            &args.threads_list,
            args.rounds.max(1),
            args.repeats.max(1),
            args.repeat_large,
            args.reuse,
            args.json.as_deref(),
        );
    }
    bench(&args)
}

/// `floor(1.5 n) + 1`: the master resolution.
fn master_n(n: usize) -> usize {
    n * 3 / 2 + 1
}

/// The seed of the shuffled order (fixed: the same copy in every run).
const SHUFFLE_SEED: u64 = 0x5eed;

/// `mesh` (a chain of two-node lines, faces in chain order) as two chains meeting at the node
/// its middle face shares with the face before: the faces from the middle on take a copy of
/// that node (tagged past the others).
fn split_in_two(mesh: &SurfaceMesh) -> Res<SurfaceMesh> {
    let mut out = SurfaceMesh::with_capacity(mesh.node_count() + 1, mesh.face_count());
    let tags = mesh.node_tags();
    for (t, x) in tags.iter().zip(mesh.coords()) {
        out.add_node(*t, [x.x, x.y, x.z])?;
    }
    let middle = mesh.face_count() / 2;
    let before = mesh.face(middle - 1).nodes;
    let node = *mesh
        .face(middle)
        .nodes
        .iter()
        .find(|k| before.contains(k))
        .ok_or("the middle face does not follow the one before it")?;
    let copy = tags.iter().max().copied().unwrap_or(0) + 1;
    let x = mesh.coords()[node as usize];
    out.add_node(copy, [x.x, x.y, x.z])?;
    for f in 0..mesh.face_count() {
        let face = mesh.face(f);
        let nodes: Vec<u64> = face
            .nodes
            .iter()
            .map(|&k| {
                if f >= middle && k == node {
                    copy
                } else {
                    tags[k as usize]
                }
            })
            .collect();
        out.add_face(face.element, &nodes)?;
    }
    Ok(out)
}

/// The interface of `case` at size `n`, in the generator's order (`sorted`) or with the nodes
/// and faces of both sides in a seeded random order (`shuffled`).
fn build(case: &str, n: usize, order: &str) -> Res<Interface> {
    let (slave, master) = match case {
        "plane3d" => (
            square_triangles(n, Diagonal::Main, 0.0, false, 1)?,
            square_triangles(master_n(n), Diagonal::Anti, 0.0, true, 1)?,
        ),
        "cylinder" => {
            let along = (n / 4).max(1);
            (
                cylinder_surface(1.0, n, along, false, false, 1)?,
                cylinder_surface(1.0, master_n(n), master_n(along), true, true, 1)?,
            )
        }
        "line2d" => (line_mesh(n, false, 1)?, line_mesh(master_n(n), true, 1)?),
        "arc2d" => (
            half_circle_mesh(n, false, 1)?,
            half_circle_mesh(master_n(n), true, 1)?,
        ),
        // Not in the default run (`--at arc2d-split:N`): arc2d with the master in two bodies
        // that meet at the top, so that the walk along the master checks for the other chain
        // under each slave face.
        "arc2d-split" => (
            half_circle_mesh(n, false, 1)?,
            split_in_two(&half_circle_mesh(master_n(n), true, 1)?)?,
        ),
        // One slave face against n master lines (2D) or n x n master quads (3D): the work of
        // a face must stay linear in its partners.
        "ratio2d" => (line_mesh(1, false, 1)?, line_mesh(n, true, 1)?),
        "ratio3d" => (
            square_quads(1, 0.0, false, 1)?,
            square_quads(n, 0.0, true, 1)?,
        ),
        _ => return Err(format!("unknown case {case:?}").into()),
    };
    match order {
        "sorted" => Ok(Interface::new(slave, master)?),
        "shuffled" => Ok(Interface::new(
            shuffled(&slave, SHUFFLE_SEED)?,
            shuffled(&master, SHUFFLE_SEED + 1)?,
        )?),
        "faces-shuffled" => Ok(Interface::new(
            shuffled_faces(&slave, SHUFFLE_SEED)?,
            shuffled_faces(&master, SHUFFLE_SEED + 1)?,
        )?),
        "shuffled-slave" => Ok(Interface::new(shuffled(&slave, SHUFFLE_SEED)?, master)?),
        "shuffled-master" => Ok(Interface::new(slave, shuffled(&master, SHUFFLE_SEED + 1)?)?),
        _ => Err(format!("unknown order {order:?}").into()),
    }
}

/// The peak resident set size of this process (`VmHWM`), in bytes.
fn peak_memory() -> u64 {
    status_bytes("VmHWM:")
}

/// A size in `/proc/self/status` (the line starting with `key`), in bytes; 0 where there is
/// none.
fn status_bytes(key: &str) -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix(key))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        .map_or(0, |kb| kb * 1024)
}

/// Resets the process's peak resident size (`VmHWM`) to its current size (Linux: `5` written
/// to `/proc/self/clear_refs`), so that the peak read after the coupling is the coupling's,
/// not the mesh generator's (shuffling a mesh of 10^6 faces peaks above the coupling). Whether
/// it could.
fn reset_peak_memory() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

fn load_average() -> f64 {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(f64::NAN)
}

/// A digest of the exact bits of D and M (structure and values).
fn digest(c: &Coupling) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for a in [&c.d, &c.m] {
        h.write_usize(a.rows());
        h.write_usize(a.cols());
        for &p in a.indptr().raw_storage() {
            h.write_usize(p);
        }
        for &i in a.indices() {
            h.write_usize(i);
        }
        for &v in a.data() {
            h.write_u64(v.to_bits());
        }
    }
    h.finish()
}

/// Bytes the two meshes hold (`SurfaceMesh::memory_bytes`: coordinates, tags, tag lookup,
/// connectivity, element types).
fn mesh_bytes(i: &Interface) -> usize {
    i.slave().memory_bytes() + i.master().memory_bytes()
}

/// Bytes of the CSR arrays of D and M: 8 + 8 per entry, 8 per row.
fn output_bytes(c: &Coupling) -> usize {
    [&c.d, &c.m]
        .iter()
        .map(|a| a.nnz() * 16 + a.rows() * 8)
        .sum()
}

/// Runs `exe --single CASE N THREADS ORDER` (this program, or another build's with
/// `--against`) with `--repeats`, `--repeat-large` if asked and `extra` arguments, in its own
/// process: the JSON record it prints last, or what failed (its exit status and standard
/// error).
fn run_single<'a>(
    exe: &Path,
    (case, n, threads, order): (&str, usize, usize, &str),
    repeats: usize,
    repeat_large: bool,
    extra: impl IntoIterator<Item = &'a OsStr>,
) -> Res<Value> {
    let out = Command::new(exe)
        .args([
            "--single",
            case,
            &n.to_string(),
            &threads.to_string(),
            order,
        ])
        .args(["--repeats", &repeats.to_string()])
        .args(repeat_large.then_some("--repeat-large"))
        .args(extra)
        .output()
        .map_err(|e| format!("cannot run {}: {e}", exe.display()))?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    match stdout.lines().last().map(serde_json::from_str::<Value>) {
        Some(Ok(v)) if out.status.success() => Ok(v),
        _ => Err(format!(
            "{} --single {case} {n} {threads} {order} failed ({}): {}",
            exe.display(),
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        )
        .into()),
    }
}

/// Sizes of 1e6 slave faces and more run once (unless `repeat_large`).
fn repeats_for(case: &str, n: usize, repeats: usize, repeat_large: bool) -> usize {
    let faces = match case {
        "plane3d" => 2 * n * n,
        "cylinder" => n * (n / 4).max(1),
        _ => n,
    };
    if faces >= 1_000_000 && !repeat_large {
        1
    } else {
        repeats.max(1)
    }
}

/// One (case, n, threads), in this process.
fn single(case: &str, n: usize, threads: usize, order: &str, args: &Args) -> Res<Value> {
    let repeats = args.repeats;
    let baseline = peak_memory();
    let load = load_average();
    let t = Instant::now();
    let interface = build(case, n, order)?;
    let mesh_seconds = t.elapsed().as_secs_f64();
    // The peak so far: mesh generation and the interface's set-up, before any coupling; then
    // the peak starts again from what is resident (the meshes).
    let peak_before_coupling = peak_memory();
    let peak_reset = reset_peak_memory();
    let resident_before_coupling = status_bytes("VmRSS:");
    let options = CouplingOptions::default().threads(threads);
    let mut runs = Vec::new();
    let mut digests = Vec::new();
    let mut last = None;
    for _ in 0..repeats_for(case, n, repeats, args.repeat_large) {
        // One coupling alive at a time: the previous one dropped, or its arrays reused.
        let c = match last.take() {
            Some(previous) if args.reuse => {
                assemble_coupling_reusing(&interface, &options, previous)?
            }
            previous => {
                drop(previous);
                assemble_coupling(&interface, &options)?
            }
        };
        runs.push(c.stats);
        digests.push(digest(&c));
        last = Some(c);
    }
    let c = last.ok_or("no run")?;
    let peak = peak_memory();
    let mut by_total: Vec<usize> = (0..runs.len()).collect();
    by_total.sort_by(|&a, &b| runs[a].seconds.total.total_cmp(&runs[b].seconds.total));
    let med = runs[by_total[by_total.len() / 2]];
    let s = med.seconds;
    let (mesh, out) = (mesh_bytes(&interface), output_bytes(&c));
    if let Some(dir) = &args.save_reference {
        if threads == 1 {
            reference::save(&reference::file(dir, case, n, order), &c)?;
        }
    }
    let vs_reference = match &args.reference {
        Some(dir) => reference::compare(&reference::file(dir, case, n, order), &c)?,
        None => Value::Null,
    };
    Ok(json!({
        "vs_reference": vs_reference,
        "case": case, "n": n, "threads": threads, "order": order,
        "slave_faces": interface.slave().face_count(),
        "master_faces": interface.master().face_count(),
        "slave_nodes": c.slave_nodes.len(), "master_nodes": c.master_nodes.len(),
        "candidates": med.candidates, "pairs": med.pairs, "segments": med.segments,
        "straight_line_faces": med.straight_line_faces,
        "fused_line_faces": med.fused_line_faces,
        "closed_form_faces": med.closed_form_faces,
        "slave_box_inflation": med.slave_box_inflation,
        "master_box_inflation": med.master_box_inflation,
        "area": med.area,
        "seconds": {"tree": s.tree, "faces": s.faces, "assembly": s.assembly, "total": s.total},
        "thread_seconds": {"search": s.thread.search, "segments": s.thread.segments,
                           "integration": s.thread.integration},
        "seconds_note": "wall time by phase; thread_seconds: the per-face work by kind, summed \
                         over threads",
        "repeats": runs.len(),
        "reuse": args.reuse,
        "totals_all_repeats": runs.iter().map(|r| r.seconds.total).collect::<Vec<_>>(),
        "pairs_per_second_per_thread": med.pairs as f64 / s.total / threads as f64,
        "ns_per_pair": s.total / med.pairs as f64 * 1e9,
        "mesh_seconds_untimed": mesh_seconds,
        "baseline_memory_bytes": baseline,
        "peak_memory_bytes": peak,
        "peak_before_coupling_bytes": peak_before_coupling,
        "peak_reset_before_coupling": peak_reset,
        "resident_before_coupling_bytes": resident_before_coupling,
        "mesh_bytes": mesh, "output_bytes": out,
        "memory_ratio": (peak.saturating_sub(baseline)) as f64 / (mesh + out) as f64,
        "memory_ratio_note": "(peak - baseline) / (mesh_bytes + output_bytes)",
        "dm_digest": format!("{:016x}", digests[0]),
        "deterministic_across_repeats": digests.iter().all(|&d| d == digests[0]),
        "load_average_1min": load,
    }))
}

fn bench(args: &Args) -> Res<()> {
    let cap = args.max_n.unwrap_or(usize::MAX);
    let mut sizes: Vec<(&str, Vec<usize>)> = if args.quick {
        vec![
            ("plane3d", vec![16, 32, 100]),
            ("cylinder", vec![64]),
            ("line2d", vec![1_000, 10_000]),
            ("arc2d", vec![1_000, 10_000]),
            ("ratio2d", vec![10_000]),
            ("ratio3d", vec![100]),
        ]
    } else {
        vec![
            ("plane3d", vec![16, 32, 100, 316, 708, 1000]),
            ("cylinder", vec![64, 256, 1024]),
            ("line2d", vec![1_000, 10_000, 100_000, 1_000_000]),
            ("arc2d", vec![1_000, 10_000, 100_000, 1_000_000]),
            ("ratio2d", vec![100_000, 1_000_000]),
            ("ratio3d", vec![316, 1000]),
        ]
    };
    if !args.cases.is_empty() {
        sizes.retain(|(case, _)| args.cases.iter().any(|c| c == case));
    }
    for (case, ns) in &mut sizes {
        if !case.ends_with("2d") {
            ns.retain(|&n| n <= cap);
        }
    }
    let repeats = args.repeats;
    let exe = std::env::current_exe()?;
    let start = Instant::now();
    let mut records: Vec<Value> = Vec::new();
    for (case, ns) in &sizes {
        for &n in ns {
            for order in ["sorted", "faces-shuffled", "shuffled"] {
                let mut one_thread_digest = None;
                for threads in [1usize, 2] {
                    eprint!("{case} n={n} threads={threads} {order} ... ");
                    let references = [
                        ("--save-reference", &args.save_reference),
                        ("--reference", &args.reference),
                    ];
                    let extra = references.iter().flat_map(|(flag, dir)| {
                        dir.iter().flat_map(|d| [OsStr::new(flag), d.as_os_str()])
                    });
                    let params = (*case, n, threads, order);
                    let mut r = match run_single(&exe, params, repeats, args.repeat_large, extra) {
                        Ok(r) => r,
                        Err(e) => {
                            eprintln!("{e}");
                            continue;
                        }
                    };
                    let dig = r["dm_digest"].as_str().map(str::to_owned);
                    if threads == 1 {
                        one_thread_digest = dig.clone();
                    }
                    r["bit_identical_to_1_thread"] = match &one_thread_digest {
                        Some(d) => json!(Some(d) == dig.as_ref()),
                        None => Value::Null,
                    };
                    let total = |p: &Value| p["seconds"]["total"].as_f64().unwrap_or(f64::NAN);
                    let (rc, rn) = (r["case"].clone(), r["n"].clone());
                    let same = |p: &&Value, threads: usize, order: &str| {
                        p["case"] == rc
                            && p["n"] == rn
                            && p["threads"] == threads
                            && p["order"] == order
                    };
                    if threads > 1 {
                        if let Some(t1) = records.iter().rev().find(|p| same(p, 1, order)) {
                            r["speedup_vs_1_thread"] = json!(total(t1) / total(&r));
                        }
                    }
                    if order != "sorted" {
                        if let Some(s) = records.iter().rev().find(|p| same(p, threads, "sorted")) {
                            r["shuffled_vs_sorted"] = json!(total(&r) / total(s));
                        }
                    }
                    eprintln!("{:.3} s", total(&r));
                    records.push(r);
                }
            }
        }
    }
    print_table(&records);
    println!(
        "wall time of the benchmark: {:.0} s; load average (1 min) now {:.2} on {} cores",
        start.elapsed().as_secs_f64(),
        load_average(),
        std::thread::available_parallelism().map_or(0, |n| n.get())
    );
    if let Some(path) = &args.json {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)?;
        }
        std::fs::write(path, serde_json::to_string_pretty(&records)? + "\n")?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

fn print_table(records: &[Value]) {
    let f = |r: &Value, k: &str| r[k].as_f64().unwrap_or(f64::NAN);
    let s = |r: &Value, k: &str| r["seconds"][k].as_f64().unwrap_or(f64::NAN);
    let ts = |r: &Value, k: &str| r["thread_seconds"][k].as_f64().unwrap_or(f64::NAN);
    let u = |r: &Value, k: &str| r[k].as_u64().unwrap_or(0);
    println!(
        "{:<8} {:>7} {:>3} {:>5} {:>9} {:>9} {:>9} {:>6} {:>7} {:>8} {:>8} {:>7} {:>8} {:>10} {:>7} {:>8} {:>5} {:>5} {:>6} {:>6} {:>5} {:>8}",
        "case", "n", "thr", "order", "slave_f", "master_f", "pairs", "tree", "search*", "segm*",
        "integr*", "assem", "total", "pairs/s/t", "ns/pair", "peak MB", "mem", "rep", "speed",
        "shuf", "bits", "vs ref"
    );
    for r in records {
        let ratio = f(r, "memory_ratio");
        let bits = match r["bit_identical_to_1_thread"].as_bool() {
            Some(true) => "same",
            Some(false) => "DIFF",
            None => "?",
        };
        let ratio_of = |k: &str| {
            r.get(k)
                .and_then(Value::as_f64)
                .map_or(String::from("-"), |v| format!("{v:.2}x"))
        };
        let vs_ref = match r["vs_reference"]["within_1e-13"].as_bool() {
            Some(ok) => {
                let d = r["vs_reference"]["d_max_row_relative"]
                    .as_f64()
                    .unwrap_or(f64::NAN);
                let m = r["vs_reference"]["m_max_row_relative"]
                    .as_f64()
                    .unwrap_or(f64::NAN);
                format!("{}{:.0e}", if ok { "" } else { "!" }, d.max(m))
            }
            None => String::from("-"),
        };
        let (speed, shuf) = (
            ratio_of("speedup_vs_1_thread"),
            ratio_of("shuffled_vs_sorted"),
        );
        println!(
            "{:<8} {:>7} {:>3} {:>5} {:>9} {:>9} {:>9} {:>6.3} {:>7.3} {:>8.3} {:>8.3} {:>7.3} {:>8.3} {:>10.3e} {:>7.0} {:>8.1} {:>5.2} {:>5} {:>6} {:>6} {:>5} {:>8}",
            r["case"].as_str().unwrap_or("?"),
            u(r, "n"),
            u(r, "threads"),
            match r["order"].as_str() {
                Some("shuffled") => "shuf",
                Some("faces-shuffled") => "face",
                _ => "sort",
            },
            u(r, "slave_faces"),
            u(r, "master_faces"),
            u(r, "pairs"),
            s(r, "tree"),
            ts(r, "search"),
            ts(r, "segments"),
            ts(r, "integration"),
            s(r, "assembly"),
            s(r, "total"),
            f(r, "pairs_per_second_per_thread"),
            f(r, "ns_per_pair"),
            f(r, "peak_memory_bytes") / 1e6,
            ratio,
            u(r, "repeats"),
            speed,
            shuf,
            bits,
            vs_ref,
        );
    }
    println!(
        "times in seconds (median total of `rep` runs); * search, segm and integr are \
         thread-seconds (summed over threads); shuf = total of this order (face: faces shuffled; shuf: nodes and faces) / sorted; mem = (peak - baseline) / (meshes + D and M); bits: D and M bit-identical \
         to the 1-thread run; vs ref: largest row-relative difference of D and M from the \
         --reference build's (! beyond 1e-13)"
    );
    let compared: Vec<&Value> = records
        .iter()
        .filter(|r| r["vs_reference"].is_object())
        .collect();
    if !compared.is_empty() {
        let worst = compared.iter().fold(0.0f64, |w, r| {
            let v = &r["vs_reference"];
            w.max(v["d_max_row_relative"].as_f64().unwrap_or(f64::NAN))
                .max(v["m_max_row_relative"].as_f64().unwrap_or(f64::NAN))
        });
        let bad = compared
            .iter()
            .filter(|r| r["vs_reference"]["within_1e-13"].as_bool() != Some(true))
            .count();
        println!(
            "D and M against the reference build: {} of {} runs within {:e} (largest row-relative \
             difference {worst:.2e})",
            compared.len() - bad,
            compared.len(),
            reference::TOLERANCE
        );
    }
}
