//! Parallel assembly and solves are deterministic: the matrices, loads and solutions are the
//! same bit for bit on one thread and on several (fixed chunks of cells, merged in order).

use mortar::generate::{box_mesh, rectangle_mesh, CellShape};
use mortar::physics::heat::{
    assemble_heat_load, assemble_heat_matrices, HeatBody, HeatMaterial, HeatOptions,
};
use mortar::VolumeMesh;

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

fn assemble(body: &HeatBody, threads: usize) -> (Vec<u64>, Vec<u64>, Vec<u64>, Vec<usize>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let m = assemble_heat_matrices(body, &HeatOptions::default()).unwrap();
        let f = assemble_heat_load(body, 0.5, &HeatOptions::default()).unwrap();
        (
            bits(m.stiffness.data()),
            bits(m.capacity.data()),
            bits(&f),
            m.stiffness.indices().to_vec(),
        )
    })
}

#[test]
fn assembly_is_bit_identical_across_thread_counts() {
    let meshes: Vec<VolumeMesh> = vec![
        rectangle_mesh([0.0, 0.0], [1.0, 1.0], [40, 40], CellShape::Tensor, 1).unwrap(),
        box_mesh([0.0; 3], [1.0; 3], [8, 8, 8], CellShape::Simplex, 1).unwrap(),
    ];
    for mesh in meshes {
        assert!(mesh.cell_count() > 1500, "several chunks of cells");
        let body = HeatBody::new("b", mesh, HeatMaterial::new(1.7, 3.1))
            .with_source(|x, t| (x.x * 3.0).sin() + x.y * x.y + t)
            .with_neumann_where(|f| f.centroid.y < 1e-12, |x, _| 1.0 + x.x)
            .unwrap();
        let one = assemble(&body, 1);
        for threads in [2, 3] {
            assert_eq!(one, assemble(&body, threads), "{threads} threads");
        }
    }
}

/// The coupling operators of `slave` against `master` on `threads` threads, keyed by node
/// tags: `(slave tag, slave tag) -> D` and `(slave tag, master tag) -> M`.
type Keyed = std::collections::BTreeMap<(u64, u64), f64>;
fn keyed_operators(
    slave: mortar::SurfaceMesh,
    master: mortar::SurfaceMesh,
    threads: usize,
) -> (Keyed, Keyed) {
    let interface = mortar::Interface::new(slave, master).unwrap();
    let options = mortar::CouplingOptions {
        threads: Some(threads),
        ..Default::default()
    };
    let c = mortar::assemble_coupling(&interface, &options).unwrap();
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
    let key = |m: &mortar::core::linalg::SparseMatrix, cols: &[u64]| -> Keyed {
        m.iter()
            .map(|(v, (r, k))| ((c.slave_nodes[r], cols[k]), *v))
            .collect()
    };
    (key(&c.d, &c.slave_nodes), key(&c.m, &c.master_nodes))
}

/// The unit square at height 0, `n x n` cells: Quad4, and every third cell cut into two Tri3
/// (two element types of different node counts on one surface).
fn mixed_square(n: usize, flip: bool) -> mortar::SurfaceMesh {
    use mortar::elements::{QUAD4, TRI3};
    let mut mesh = mortar::SurfaceMesh::new();
    let id = |i: usize, j: usize| 1 + (j * (n + 1) + i) as u64;
    for j in 0..=n {
        for i in 0..=n {
            let h = 1.0 / n as f64;
            mesh.add_node(id(i, j), [i as f64 * h, j as f64 * h, 0.0])
                .unwrap();
        }
    }
    for j in 0..n {
        for i in 0..n {
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            let q = if flip { [q[0], q[3], q[2], q[1]] } else { q };
            if (i + j) % 3 == 0 {
                mesh.add_face(&TRI3, &[q[0], q[1], q[2]]).unwrap();
                mesh.add_face(&TRI3, &[q[0], q[2], q[3]]).unwrap();
            } else {
                mesh.add_face(&QUAD4, &q).unwrap();
            }
        }
    }
    mesh
}

/// Files whose nodes and faces are numbered far apart (a seeded shuffle, as a mesher that
/// numbers faces in its own order writes them) give the operators of the sorted file: the
/// same entries by node tags, to round-off (the search and the per-face work run in a spatial
/// order of their own, and the master faces are copied in it). Sizes that take several
/// blocks and waves of the master copy (more than 64 x 4096 faces in 2D); a master of two
/// element types of different node counts (the copy then keeps each face's type and where
/// its nodes start).
#[test]
fn shuffled_files_give_the_operators_of_sorted_ones() {
    use mortar::generate::{line_mesh, square_triangles, Diagonal};
    use mortar::testing::{shuffled, shuffled_faces};
    let cases: Vec<(mortar::SurfaceMesh, mortar::SurfaceMesh)> = vec![
        (
            line_mesh(200_000, false, 1).unwrap(),
            line_mesh(300_001, true, 1).unwrap(),
        ),
        (
            square_triangles(40, Diagonal::Main, 0.0, false, 1).unwrap(),
            square_triangles(61, Diagonal::Anti, 0.0, true, 1).unwrap(),
        ),
        (
            square_triangles(30, Diagonal::Main, 0.0, false, 1).unwrap(),
            mixed_square(47, true),
        ),
    ];
    for (slave, master) in cases {
        let sorted = keyed_operators(slave.clone(), master.clone(), 2);
        let orders = [
            (shuffled(&slave, 7).unwrap(), shuffled(&master, 8).unwrap()),
            (
                shuffled_faces(&slave, 7).unwrap(),
                shuffled_faces(&master, 8).unwrap(),
            ),
        ];
        for (s, m) in orders {
            let got = keyed_operators(s, m, 2);
            for (want, got) in [(&sorted.0, &got.0), (&sorted.1, &got.1)] {
                assert_eq!(
                    want.keys().collect::<Vec<_>>(),
                    got.keys().collect::<Vec<_>>(),
                    "the same sparsity by node tags"
                );
                let scale = want.values().fold(0.0f64, |a, v| a.max(v.abs()));
                for (k, v) in want {
                    assert!(
                        (v - got[k]).abs() <= 1e-12 * scale,
                        "{k:?}: {v} vs {}",
                        got[k]
                    );
                }
            }
        }
    }
}

/// The tied system solved by body (two domains on two threads, the interface last) gives the
/// same temperatures bit for bit on one thread and on several; as does the single factor.
#[test]
fn tied_solutions_are_bit_identical_across_thread_counts() {
    use mortar::physics::tied::TiedOptions;
    use mortar_scenes::tied_heat::{Geometry, TiedHeatScene};
    for (dim, n) in [(2, 64), (3, 8)] {
        let problem = TiedHeatScene::new(dim, Geometry::Straight, n)
            .build()
            .unwrap();
        let solve = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let s = problem.solve_steady(&TiedOptions::default(), 0.0).unwrap();
                let by_body = s.formulation.factorisation.contains("by body");
                (by_body, bits(&s.temperatures[0]), bits(&s.temperatures[1]))
            })
        };
        let one = solve(1);
        assert_eq!(one.0, dim == 2, "{dim}D: factorised by body");
        for threads in [2, 3] {
            assert_eq!(one, solve(threads), "{dim}D, {threads} threads");
        }
    }
}
