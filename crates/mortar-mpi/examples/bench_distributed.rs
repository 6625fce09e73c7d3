//! The distributed coupling's time on P ranks against one rank's and the one-process
//! coupling's on one thread, measured in one run: every rank couples its part
//! (`couple_distributed`, one thread per rank), then rank 0 builds and couples the whole
//! interface alone (`Interface::new` and `assemble_coupling`, one thread) and runs
//! `couple_distributed` of the whole interface on the one-rank exchange, while the others
//! wait. Mesh generation and the split are not timed. Prints one JSON line and
//! a line a person can read; each time is the median of `--repeats` runs.
//!
//! ```sh
//! mpirun -n 2 target/release/examples/bench_distributed --case plane3d --n 708 --repeats 5 \
//!     --split strips-together --json docs/bench_distributed.jsonl
//! ```
//!
//! `--json FILE` appends the JSON line to FILE.

mod support;

use std::time::Instant;

use mortar_core::{assemble_coupling, CouplingOptions, Interface};
use mortar_mpi::{couple_distributed, DistributedOptions, Exchange, Mpi, SelfExchange};
use support::{parts, surfaces, Res};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The largest of every rank's `x`.
fn max_over_ranks(ex: &impl Exchange, x: f64) -> f64 {
    ex.all_gather(&x.to_le_bytes())
        .iter()
        .map(|b| f64::from_le_bytes(b[..8].try_into().expect("8 bytes")))
        .fold(0.0, f64::max)
}

fn run(mpi: &Mpi) -> Res<()> {
    let (mut case, mut split, mut n, mut repeats) =
        ("plane3d".to_string(), "strips-together".to_string(), 200, 3);
    let mut json_path = None;
    let mut it = std::env::args().skip(1);
    while let Some(k) = it.next() {
        let v = it.next().ok_or(format!("{k} needs a value"))?;
        match k.as_str() {
            "--case" => case = v,
            "--split" => split = v,
            "--n" => n = v.parse()?,
            "--repeats" => repeats = v.parse()?,
            "--json" => json_path = Some(std::path::PathBuf::from(v)),
            _ => return Err(format!("unknown argument {k:?}").into()),
        }
    }
    let ex = mpi.world();
    let (rank, p) = (ex.rank(), ex.size());
    let (slave, master) = surfaces(&case, n)?;
    let (my_slave, my_master) = parts(&slave, &master, &split, rank, p)?;
    let mut options = DistributedOptions::default();
    options.coupling.threads = Some(1);
    let mut distributed = Vec::new();
    let mut pairs = 0;
    let mut counts = None;
    for _ in 0..repeats {
        ex.all_gather(&[]);
        let t = Instant::now();
        let rows = couple_distributed(&ex, &my_slave, &my_master, &options)?;
        let mine = t.elapsed().as_secs_f64();
        distributed.push(max_over_ranks(&ex, mine));
        pairs = rows.counts.pairs;
        counts = Some((rows.counts, rows.seconds));
        drop(rows);
    }
    let all_pairs: usize = ex
        .all_gather(&(pairs as u64).to_le_bytes())
        .iter()
        .map(|b| u64::from_le_bytes(b[..8].try_into().expect("8 bytes")) as usize)
        .sum();
    let mut serial = Vec::new();
    let mut serial_interface = Vec::new();
    let mut one_rank = Vec::new();
    let mut serial_pairs = 0;
    if rank == 0 {
        for _ in 0..repeats {
            let t = Instant::now();
            let interface = Interface::new(slave.clone(), master.clone())?;
            serial_interface.push(t.elapsed().as_secs_f64());
            drop(interface);
        }
        let interface = Interface::new(slave.clone(), master.clone())?;
        let one = CouplingOptions {
            threads: Some(1),
            ..CouplingOptions::default()
        };
        for _ in 0..repeats {
            let t = Instant::now();
            let c = assemble_coupling(&interface, &one)?;
            serial.push(t.elapsed().as_secs_f64());
            serial_pairs = c.stats.pairs;
        }
        // The distributed coupling of the whole interface on one rank: the same algorithm on
        // the one-rank exchange.
        for _ in 0..repeats {
            let t = Instant::now();
            let rows = couple_distributed(&SelfExchange, &slave, &master, &options)?;
            one_rank.push(t.elapsed().as_secs_f64());
            drop(rows);
        }
    }
    ex.all_gather(&[]);
    if rank == 0 {
        let (d, s) = (median(distributed), median(serial));
        let si = median(serial_interface);
        let o = median(one_rank);
        let (c, sec) = counts.expect("one repeat at least");
        let json = serde_json::json!({
            "case": case, "split": split, "n": n, "ranks": p, "repeats": repeats,
            "slave_faces": slave.face_count(), "master_faces": master.face_count(),
            "serial_pairs": serial_pairs, "distributed_pairs": all_pairs,
            "distributed_seconds": d, "one_process_seconds": s, "speedup": s / d,
            "one_process_interface_seconds": si, "speedup_with_interface": (s + si) / d,
            "one_rank_seconds": o, "speedup_over_one_rank": o / d,
            "rank0_ghost_slave_faces": c.ghost_slave_faces,
            "rank0_ghost_master_faces": c.ghost_master_faces,
            "rank0_bytes_sent": c.bytes_sent,
            "rank0_seconds_last": {
                "summaries": sec.summaries, "slave_exchange": sec.slave_exchange,
                "ghosts": sec.ghosts, "master_exchange": sec.master_exchange,
                "interface": sec.interface, "coupling": sec.coupling, "rows": sec.rows,
                "total": sec.total,
            },
        });
        println!("{json}");
        if let Some(path) = &json_path {
            // One line per run, appended: the runs of several rank counts in one file.
            use std::io::Write;
            let mut file = std::fs::OpenOptions::new()
                .create(true)
                .append(true)
                .open(path)?;
            writeln!(file, "{json}")?;
        }
        println!(
            "{case} {split} n={n} ({} slave faces): {p} ranks {d:.3} s; one rank {o:.3} s ({:.2}x); one process on one thread: coupling {s:.3} s ({:.2}x), interface built and checked {si:.3} s more ({:.2}x with it); medians of {repeats}",
            slave.face_count(),
            o / d,
            s / d,
            (s + si) / d
        );
    }
    Ok(())
}

fn main() {
    let Some(mpi) = Mpi::initialize() else {
        eprintln!("MPI was already started");
        std::process::exit(2);
    };
    if let Err(e) = run(&mpi) {
        eprintln!("error: {e}");
        mpi.abort(4)
    }
}
