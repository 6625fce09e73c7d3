//! How a distributed coupling's per-rank work and messages fall with the rank count, counted
//! in one process (no MPI): the plane3d interface (a plane of Tri3 against a finer one) split
//! into P = 2..1024 parts by recursive coordinate bisection of the slave faces' centres (the
//! master faces follow the same cuts, as a finite-element code's partition of two touching
//! bodies would put them), and `modelled_counts` taking each part through the same rules as
//! `couple_distributed` (the faces each rank would receive and keep, the messages encoded and
//! their bytes counted). Prints a JSON line per P and a table a person can read.
//!
//! ```sh
//! cargo run --release -p mortar-mpi --example partition_model -- --n 708 --json docs/partition_model.json
//! ```

use mortar::generate::{square_triangles, Diagonal};
use mortar_core::SurfaceMesh;
use mortar_mpi::{modelled_counts, DistributedOptions, ModelledRank};

mod support;

use support::{master_n, split_mesh, Res};

/// A cut of the bisection: below `value` along `axis` to `low`, else to `high`.
enum Tree {
    Leaf(usize),
    Cut {
        axis: usize,
        value: f64,
        low: Box<Tree>,
        high: Box<Tree>,
    },
}

impl Tree {
    /// Splits `faces` (indices into `centres`) into `parts` parts numbered from `first`,
    /// writing each face's part into `part`.
    fn build(
        centres: &[[f64; 3]],
        faces: &mut [u32],
        first: usize,
        parts: usize,
        part: &mut [usize],
    ) -> Tree {
        if parts == 1 || faces.len() < 2 {
            for &f in faces.iter() {
                part[f as usize] = first;
            }
            return Tree::Leaf(first);
        }
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for &f in faces.iter() {
            for k in 0..3 {
                lo[k] = lo[k].min(centres[f as usize][k]);
                hi[k] = hi[k].max(centres[f as usize][k]);
            }
        }
        let axis = (0..3)
            .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
            .expect("three axes");
        let low_parts = parts / 2;
        let k = faces.len() * low_parts / parts;
        faces.select_nth_unstable_by(k, |&a, &b| {
            centres[a as usize][axis].total_cmp(&centres[b as usize][axis])
        });
        let value = centres[faces[k] as usize][axis];
        let (low, high) = faces.split_at_mut(k);
        Tree::Cut {
            axis,
            value,
            low: Box::new(Tree::build(centres, low, first, low_parts, part)),
            high: Box::new(Tree::build(
                centres,
                high,
                first + low_parts,
                parts - low_parts,
                part,
            )),
        }
    }

    /// The part of a point.
    fn part_of(&self, x: &[f64; 3]) -> usize {
        match self {
            Tree::Leaf(p) => *p,
            Tree::Cut {
                axis,
                value,
                low,
                high,
            } => {
                if x[*axis] < *value {
                    low.part_of(x)
                } else {
                    high.part_of(x)
                }
            }
        }
    }
}

fn centres(mesh: &SurfaceMesh) -> Vec<[f64; 3]> {
    (0..mesh.face_count())
        .map(|f| {
            let nodes = mesh.face(f).nodes;
            let mut c = [0.0; 3];
            for &n in nodes {
                let x = mesh.coords()[n as usize];
                for k in 0..3 {
                    c[k] += x[k] / nodes.len() as f64;
                }
            }
            c
        })
        .collect()
}

fn stats(ranks: &[ModelledRank], of: impl Fn(&ModelledRank) -> f64) -> (f64, f64) {
    let max = ranks.iter().map(&of).fold(0.0, f64::max);
    let mean = ranks.iter().map(&of).sum::<f64>() / ranks.len() as f64;
    (max, mean)
}

fn main() -> Res<()> {
    let mut n = 200;
    let mut json_path = None;
    let mut largest = 1024;
    let mut it = std::env::args().skip(1);
    while let Some(k) = it.next() {
        let v = it.next().ok_or(format!("{k} needs a value"))?;
        match k.as_str() {
            "--n" => n = v.parse()?,
            "--json" => json_path = Some(std::path::PathBuf::from(v)),
            "--largest" => largest = v.parse()?,
            _ => return Err(format!("unknown argument {k:?}").into()),
        }
    }
    let slave = square_triangles(n, Diagonal::Main, 0.0, false, 1)?;
    let master = square_triangles(master_n(n), Diagonal::Anti, 0.0, true, 1)?;
    let (sc, mc) = (centres(&slave), centres(&master));
    let options = DistributedOptions::default();
    let mut lines = Vec::new();
    println!(
        "plane3d, {} slave faces, {} master faces",
        slave.face_count(),
        master.face_count()
    );
    println!("| P | slave faces per rank, max | ghost slave, max | ghost master, max | messages sent, max | bytes sent, max | ghost master / sqrt(N / P) |");
    println!("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    let mut p = 2;
    while p <= largest {
        let mut order: Vec<u32> = (0..slave.face_count() as u32).collect();
        let mut slave_part = vec![0usize; slave.face_count()];
        let tree = Tree::build(&sc, &mut order, 0, p, &mut slave_part);
        let master_part: Vec<usize> = mc.iter().map(|c| tree.part_of(c)).collect();
        let ranks = modelled_counts(
            &split_mesh(&slave, &slave_part, p)?,
            &split_mesh(&master, &master_part, p)?,
            &options,
        )?;
        let faces = stats(&ranks, |r| r.slave_faces as f64);
        let ghost_s = stats(&ranks, |r| r.ghost_slave_faces as f64);
        let ghost_m = stats(&ranks, |r| r.ghost_master_faces as f64);
        let messages = stats(&ranks, |r| r.messages_sent as f64);
        let bytes = stats(&ranks, |r| r.bytes_sent as f64);
        // Constant where the ghost faces are a band of fixed width along a part's boundary.
        let surface = ghost_m.0 / (slave.face_count() as f64 / p as f64).sqrt();
        let json = serde_json::json!({
            "case": "plane3d", "n": n, "ranks": p,
            "slave_faces": slave.face_count(), "master_faces": master.face_count(),
            "slave_faces_per_rank": {"max": faces.0, "mean": faces.1},
            "ghost_slave_faces": {"max": ghost_s.0, "mean": ghost_s.1},
            "ghost_master_faces": {"max": ghost_m.0, "mean": ghost_m.1},
            "messages_sent": {"max": messages.0, "mean": messages.1},
            "bytes_sent": {"max": bytes.0, "mean": bytes.1},
            "ghost_master_per_sqrt_faces_per_rank": surface,
        });
        println!(
            "| {p} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {surface:.2} |",
            faces.0, ghost_s.0, ghost_m.0, messages.0, bytes.0
        );
        lines.push(json);
        p *= 2;
    }
    if let Some(path) = json_path {
        std::fs::write(path, serde_json::to_string_pretty(&lines)? + "\n")?;
    }
    Ok(())
}
