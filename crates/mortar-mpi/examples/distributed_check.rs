//! The distributed coupling against the one-process coupling, run under `mpirun`: every rank
//! builds the same two surfaces, keeps its part of each (the slave and the master split
//! differently), couples its part with `couple_distributed`, and rank 0 compares the gathered
//! D and M with `assemble_coupling` of the whole interface. Prints one JSON line (rank 0) and
//! exits with 1 when an entry differs by more than 1e-12 of the matrix's largest entry.
//!
//! ```sh
//! mpirun -n 3 target/release/examples/distributed_check --case plane3d --split strips --n 16
//! ```
//!
//! `--fail-rank K` gives rank K a degenerate slave face: every rank must then stop with an
//! error naming rank K (exit code 3), none waiting for the others.

use std::process::ExitCode;
use std::sync::Arc;

mod support;

use mortar_core::multiplier::DualMultipliers;
use mortar_core::{assemble_coupling, CouplingOptions, Interface};
use mortar_mpi::{couple_distributed, gather, modelled_counts, DistributedOptions, Exchange, Mpi};
use support::{parts, surfaces, Res};

struct Args {
    case: String,
    split: String,
    n: usize,
    fail_rank: Option<usize>,
}

fn args() -> Res<Args> {
    let mut a = Args {
        case: "plane3d".into(),
        split: "strips".into(),
        n: 12,
        fail_rank: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(k) = it.next() {
        let mut v = || it.next().ok_or(format!("{k} needs a value"));
        match k.as_str() {
            "--case" => a.case = v()?,
            "--split" => a.split = v()?,
            "--n" => a.n = v()?.parse()?,
            "--fail-rank" => a.fail_rank = Some(v()?.parse()?),
            _ => return Err(format!("unknown argument {k:?}").into()),
        }
    }
    Ok(a)
}

/// The largest difference of two matrices of the same pattern over `a`'s largest entry, and
/// whether every entry is the same bits; `None` if the patterns differ.
fn compare(
    a: &mortar_core::linalg::SparseMatrix,
    b: &mortar_core::linalg::SparseMatrix,
) -> Option<(f64, bool)> {
    if a.shape() != b.shape() || a.indptr().raw_storage() != b.indptr().raw_storage() {
        return None;
    }
    if a.indices() != b.indices() {
        return None;
    }
    let scale = a.data().iter().fold(0.0f64, |s, v| s.max(v.abs()));
    let mut worst = 0.0f64;
    let mut same = true;
    for (x, y) in a.data().iter().zip(b.data()) {
        worst = worst.max((x - y).abs());
        same &= x.to_bits() == y.to_bits();
    }
    Some((worst / scale.max(f64::MIN_POSITIVE), same))
}

fn run(mpi: &Mpi) -> Res<u8> {
    let a = args()?;
    let ex = mpi.world();
    let (rank, p) = (ex.rank(), ex.size());
    let (slave, master) = surfaces(&a.case, a.n)?;
    let (mut my_slave, my_master) = parts(&slave, &master, &a.split, rank, p)?;
    if a.fail_rank == Some(rank) {
        // A face whose three nodes lie on one line: the core refuses it as degenerate.
        let base = 1 << 40;
        for (i, x) in [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0]]
            .iter()
            .enumerate()
        {
            my_slave.add_node(base + i as u64, *x)?;
        }
        let element = slave.face(0).element;
        let tags: Vec<u64> = (0..element.node_count() as u64)
            .map(|i| base + i.min(2))
            .collect();
        my_slave.add_face_with_tag(base, element, &tags)?;
    }
    let mut options = DistributedOptions::default();
    if a.case == "plane3d-dual" {
        options.coupling = CouplingOptions {
            multipliers: Arc::new(DualMultipliers),
            ..CouplingOptions::default()
        };
    }
    let rows = match couple_distributed(&ex, &my_slave, &my_master, &options) {
        Ok(r) => r,
        Err(e) => {
            // One write, so that the ranks' lines do not interleave.
            let line = format!("rank {rank}: error: {e}\n");
            std::io::Write::write_all(&mut std::io::stderr(), line.as_bytes())?;
            return Ok(3);
        }
    };
    let Some(all) = gather(&ex, &rows, 0)? else {
        return Ok(0);
    };
    // The partition model's counts of the same parts against the ranks' own (first pass).
    let mut slave_parts = Vec::new();
    let mut master_parts = Vec::new();
    for q in 0..p {
        let (s, m) = parts(&slave, &master, &a.split, q, p)?;
        slave_parts.push(s);
        master_parts.push(m);
    }
    let model = modelled_counts(&slave_parts, &master_parts, &options)?;
    let model_matches = all.counts.iter().zip(&model).all(|(c, m)| {
        c.passes != 1
            || (c.ghost_slave_faces == m.ghost_slave_faces
                && c.ghost_master_faces == m.ghost_master_faces
                && c.messages_sent == m.messages_sent
                && c.bytes_sent == m.bytes_sent)
    });
    let serial = assemble_coupling(&Interface::new(slave, master)?, &options.coupling)?;
    let nodes_match =
        all.slave_nodes == serial.slave_nodes && all.master_nodes == serial.master_nodes;
    let d = compare(&serial.d, &all.d);
    let m = compare(&serial.m, &all.m);
    let ok = nodes_match
        && model_matches
        && [d, m]
            .iter()
            .all(|c| c.is_some_and(|(rel, _)| rel <= 1e-12));
    let per_rank: Vec<serde_json::Value> = all
        .counts
        .iter()
        .map(|c| {
            let fields = c
                .named()
                .map(|(k, v)| (k.to_string(), serde_json::Value::from(v)));
            serde_json::Value::Object(fields.into_iter().collect())
        })
        .collect();
    let json = serde_json::json!({
        "case": a.case,
        "split": a.split,
        "n": a.n,
        "ranks": p,
        "nodes_match": nodes_match,
        "model_matches": model_matches,
        "d_max_rel_diff": d.map(|c| c.0),
        "m_max_rel_diff": m.map(|c| c.0),
        "d_bit_identical": d.is_some_and(|c| c.1),
        "m_bit_identical": m.is_some_and(|c| c.1),
        "per_rank": per_rank,
    });
    println!("{json}");
    println!(
        "{} {} n={} on {p} ranks: D {}, M {} against one process",
        a.case,
        a.split,
        a.n,
        d.map_or("pattern differs".to_string(), |c| format!(
            "max rel diff {:.2e}{}",
            c.0,
            if c.1 { " (bit-identical)" } else { "" }
        )),
        m.map_or("pattern differs".to_string(), |c| format!(
            "max rel diff {:.2e}{}",
            c.0,
            if c.1 { " (bit-identical)" } else { "" }
        )),
    );
    Ok(if ok { 0 } else { 1 })
}

fn main() -> ExitCode {
    let Some(mpi) = Mpi::initialize() else {
        eprintln!("MPI was already started");
        return ExitCode::from(2);
    };
    match run(&mpi) {
        Ok(code) => ExitCode::from(code),
        Err(e) => {
            eprintln!("error: {e}");
            // A failure outside the collectives (an argument, a mesh): stop every rank.
            mpi.abort(4)
        }
    }
}
