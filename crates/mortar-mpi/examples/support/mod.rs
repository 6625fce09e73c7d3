//! What the distributed examples share: the test surfaces, the ways of splitting them over the
//! ranks, and a rank's part of a surface. (Each example uses part of it.)
#![allow(dead_code)]

use mortar::generate::{cylinder_surface, half_circle_mesh, line_mesh, square_triangles, Diagonal};
use mortar_core::SurfaceMesh;

/// The examples' error type.
pub type Res<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// The master's cell count for a slave of `n`: not a multiple, so the meshes do not match.
pub fn master_n(n: usize) -> usize {
    (n * 7).div_ceil(5) + 1
}

/// The two surfaces of `case` at size `n`.
pub fn surfaces(case: &str, n: usize) -> Res<(SurfaceMesh, SurfaceMesh)> {
    Ok(match case {
        "plane3d" | "plane3d-dual" => (
            square_triangles(n, Diagonal::Main, 0.0, false, 1)?,
            square_triangles(master_n(n), Diagonal::Anti, 0.0, true, 1)?,
        ),
        // The master under the slave's first 0.4 x 0.4 only: a rank of strips beyond it
        // couples nothing.
        "plane3d-far" => {
            let mut master = square_triangles(master_n(n), Diagonal::Anti, 0.0, true, 1)?;
            master.transform(|x| x * 0.4)?;
            (square_triangles(n, Diagonal::Main, 0.0, false, 1)?, master)
        }
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
pub fn rank_of(split: &str, f: usize, x: [f64; 3], p: usize, salt: u64) -> Res<usize> {
    Ok(match split {
        // Strips across x, the master's in the same order: a finite-element code's partition
        // of two bodies that touch, each rank holding both sides of its part of the interface.
        "strips-together" => ((x[0] * p as f64) as usize).min(p - 1),
        // Strips across x, the master's reversed: every master face away from its slave faces.
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

/// `mesh` split by `part` (a part per face) into `parts` meshes, tags kept.
pub fn split_mesh(mesh: &SurfaceMesh, part: &[usize], parts: usize) -> Res<Vec<SurfaceMesh>> {
    let mut faces: Vec<Vec<usize>> = vec![Vec::new(); parts];
    for (f, &p) in part.iter().enumerate() {
        faces[p].push(f);
    }
    Ok(faces
        .into_iter()
        .map(|list| mesh.part(list))
        .collect::<Result<_, _>>()?)
}

/// The smallest and largest x of `mesh`'s nodes.
pub fn x_range(mesh: &SurfaceMesh) -> (f64, f64) {
    let range = (f64::INFINITY, f64::NEG_INFINITY);
    mesh.coords()
        .iter()
        .fold(range, |(l, h), x| (l.min(x.x), h.max(x.x)))
}

/// The centre of face `f`, its x scaled to `[0, 1]` over `(lo, hi)`.
pub fn centre(mesh: &SurfaceMesh, f: usize, (lo, hi): (f64, f64)) -> [f64; 3] {
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

/// This rank's parts of `slave` and `master` by `split` (the master split differently).
pub fn parts(
    slave: &SurfaceMesh,
    master: &SurfaceMesh,
    split: &str,
    rank: usize,
    ranks: usize,
) -> Res<(SurfaceMesh, SurfaceMesh)> {
    let mut mine = Vec::new();
    for (mesh, salt) in [(slave, 0), (master, 1)] {
        let range = x_range(mesh);
        let part = (0..mesh.face_count())
            .map(|f| rank_of(split, f, centre(mesh, f, range), ranks, salt))
            .collect::<Res<Vec<usize>>>()?;
        mine.push(split_mesh(mesh, &part, ranks)?.swap_remove(rank));
    }
    let master_part = mine.pop().expect("two sides");
    Ok((mine.pop().expect("two sides"), master_part))
}
