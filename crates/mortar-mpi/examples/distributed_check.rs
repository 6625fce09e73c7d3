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

use mortar::generate::{cylinder_surface, half_circle_mesh, line_mesh, square_triangles, Diagonal};
use mortar_core::multiplier::DualMultipliers;
use mortar_core::{assemble_coupling, CouplingOptions, Interface, SurfaceMesh};
use mortar_mpi::{couple_distributed, gather, DistributedOptions, Exchange, Mpi};

type Res<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// The master's cell count for a slave of `n`: not a multiple, so the meshes do not match.
fn master_n(n: usize) -> usize {
    (n * 7).div_ceil(5) + 1
}

/// The two surfaces of `case` at size `n`.
fn surfaces(case: &str, n: usize) -> Res<(SurfaceMesh, SurfaceMesh)> {
    Ok(match case {
        "plane3d" | "plane3d-dual" => (
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
        // An open gap five slave faces wide: the search widens to the master (a second
        // exchange of master faces).
        "arc2d-gap" => {
            let mut master = half_circle_mesh(master_n(n), true, 1)?;
            let gap = 1.0 + 5.0 * std::f64::consts::PI / n as f64;
            master.transform(|x| x * gap)?;
            (half_circle_mesh(n, false, 1)?, master)
        }
        _ => return Err(format!("unknown case {case:?}").into()),
    })
}

/// The rank of face `f` (centre `x`, `x[0]` scaled to `[0, 1]` over the mesh) among `p` ranks
/// by `split`; `salt` makes the slave's and the master's splits differ.
fn rank_of(split: &str, f: usize, x: [f64; 3], p: usize, salt: u64) -> Res<usize> {
    Ok(match split {
        // Strips across x, the master's reversed.
        "strips" => {
            let s = ((x[0] * p as f64) as usize).min(p - 1);
            if salt == 0 {
                s
            } else {
                p - 1 - s
            }
        }
        "round-robin" => (f + salt as usize) % p,
        // Every slave face on the last rank, every master face on the first: the other ranks
        // hold nothing, and the last receives all its master faces.
        "apart" => {
            if salt == 0 {
                p - 1
            } else {
                0
            }
        }
        "random" => {
            let mut h = (f as u64 ^ (salt << 32)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
            h ^= h >> 29;
            (h % p as u64) as usize
        }
        _ => return Err(format!("unknown split {split:?}").into()),
    })
}

/// The faces of `mesh` that `keep` selects, with their nodes, tags kept.
fn part_of(mesh: &SurfaceMesh, keep: impl Fn(usize) -> Res<bool>) -> Res<SurfaceMesh> {
    let mut out = SurfaceMesh::new();
    for f in 0..mesh.face_count() {
        if !keep(f)? {
            continue;
        }
        let face = mesh.face(f);
        let mut tags = Vec::new();
        for &n in face.nodes {
            let t = mesh.node_tags()[n as usize];
            if out.node_index(t).is_none() {
                let x = mesh.coords()[n as usize];
                out.add_node(t, [x.x, x.y, x.z])?;
            }
            tags.push(t);
        }
        out.add_face_with_tag(face.tag, face.element, &tags)?;
    }
    Ok(out)
}

/// The smallest and largest x of `mesh`'s nodes.
fn x_range(mesh: &SurfaceMesh) -> (f64, f64) {
    let range = (f64::INFINITY, f64::NEG_INFINITY);
    mesh.coords()
        .iter()
        .fold(range, |(l, h), x| (l.min(x.x), h.max(x.x)))
}

/// The centre of face `f`, its x scaled to `[0, 1]` over `(lo, hi)`.
fn centre(mesh: &SurfaceMesh, f: usize, (lo, hi): (f64, f64)) -> [f64; 3] {
    let nodes = mesh.face(f).nodes;
    let mut c = [0.0; 3];
    for &n in nodes {
        let x = mesh.coords()[n as usize];
        for k in 0..3 {
            c[k] += x[k] / nodes.len() as f64;
        }
    }
    c[0] = (c[0] - lo) / (hi - lo).max(f64::MIN_POSITIVE);
    c
}

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
    let (sx, mx) = (x_range(&slave), x_range(&master));
    let mut my_slave = part_of(&slave, |f| {
        Ok(rank_of(&a.split, f, centre(&slave, f, sx), p, 0)? == rank)
    })?;
    let my_master = part_of(&master, |f| {
        Ok(rank_of(&a.split, f, centre(&master, f, mx), p, 1)? == rank)
    })?;
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
    let serial = assemble_coupling(&Interface::new(slave, master)?, &options.coupling)?;
    let nodes_match =
        all.slave_nodes == serial.slave_nodes && all.master_nodes == serial.master_nodes;
    let d = compare(&serial.d, &all.d);
    let m = compare(&serial.m, &all.m);
    let ok = nodes_match
        && [d, m]
            .iter()
            .all(|c| c.is_some_and(|(rel, _)| rel <= 1e-12));
    let per_rank: Vec<serde_json::Value> = all
        .counts
        .iter()
        .map(|c| {
            serde_json::json!({
                "slave_faces": c.slave_faces,
                "ghost_slave_faces": c.ghost_slave_faces,
                "master_faces": c.master_faces,
                "ghost_master_faces": c.ghost_master_faces,
                "pairs": c.pairs,
                "messages_sent": c.messages_sent,
                "bytes_sent": c.bytes_sent,
                "passes": c.passes,
            })
        })
        .collect();
    let json = serde_json::json!({
        "case": a.case,
        "split": a.split,
        "n": a.n,
        "ranks": p,
        "nodes_match": nodes_match,
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
