//! Parallel assembly is deterministic: the matrices and loads are the same bit for bit on one
//! thread and on several (fixed chunks of cells, merged in order).

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
