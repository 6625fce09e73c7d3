//! The distributed coupling on the one-rank exchange (no MPI): the whole interface on one
//! rank gives the one-process coupling's D and M bit for bit, and the failures are typed.

use mortar::generate::{half_circle_mesh, square_quads, square_triangles, Diagonal};
use mortar_core::{assemble_coupling, CouplingOptions, Interface, SurfaceMesh};
use mortar_mpi::{couple_distributed, gather, DistributedError, DistributedOptions, SelfExchange};

fn same_bits(a: &mortar_core::linalg::SparseMatrix, b: &mortar_core::linalg::SparseMatrix) {
    assert_eq!(a.shape(), b.shape());
    assert_eq!(a.indptr().raw_storage(), b.indptr().raw_storage());
    assert_eq!(a.indices(), b.indices());
    let bits = |m: &mortar_core::linalg::SparseMatrix| -> Vec<u64> {
        m.data().iter().map(|v| v.to_bits()).collect()
    };
    assert_eq!(bits(a), bits(b));
}

fn one_rank_is_one_process(slave: SurfaceMesh, master: SurfaceMesh) {
    let options = DistributedOptions::default();
    let rows = couple_distributed(&SelfExchange, &slave, &master, &options).expect("couples");
    assert_eq!(rows.counts.ghost_slave_faces, 0);
    assert_eq!(rows.counts.messages_sent, 0);
    let all = gather(&SelfExchange, &rows, 0)
        .expect("gathers")
        .expect("root");
    let serial = assemble_coupling(
        &Interface::new(slave, master).expect("valid"),
        &CouplingOptions::default(),
    )
    .expect("couples");
    assert_eq!(all.slave_nodes, serial.slave_nodes);
    assert_eq!(all.master_nodes, serial.master_nodes);
    same_bits(&all.d, &serial.d);
    same_bits(&all.m, &serial.m);
}

#[test]
fn one_rank_gives_the_one_process_coupling_in_3d() {
    one_rank_is_one_process(
        square_triangles(6, Diagonal::Main, 0.0, false, 1).expect("mesh"),
        square_quads(9, 0.0, true, 1).expect("mesh"),
    );
}

#[test]
fn one_rank_gives_the_one_process_coupling_in_2d() {
    one_rank_is_one_process(
        half_circle_mesh(20, false, 1).expect("mesh"),
        half_circle_mesh(29, true, 1).expect("mesh"),
    );
}

#[test]
fn surfaces_that_do_not_meet_are_no_overlap() {
    let slave = square_triangles(3, Diagonal::Main, 0.0, false, 1).expect("mesh");
    let mut master = square_quads(4, 0.0, true, 1).expect("mesh");
    master
        .transform(|x| x + nalgebra::Vector3::new(10.0, 0.0, 0.0))
        .expect("moved");
    let err = couple_distributed(
        &SelfExchange,
        &slave,
        &master,
        &DistributedOptions::default(),
    )
    .expect_err("apart");
    assert!(
        matches!(
            err,
            DistributedError::NoOverlap {
                ranks: 1,
                slave_faces: 18,
                master_faces: 16
            }
        ),
        "{err}"
    );
}

#[test]
fn a_degenerate_face_is_the_cores_error_with_the_rank() {
    let mut slave = SurfaceMesh::new();
    for (t, x) in [
        (1, [0.0, 0.0, 0.0]),
        (2, [1.0, 0.0, 0.0]),
        (3, [2.0, 0.0, 0.0]),
    ] {
        slave.add_node(t, x).expect("node");
    }
    slave
        .add_face(&mortar_elements::TRI3, &[1, 2, 3])
        .expect("face");
    let master = square_quads(2, 0.0, true, 1).expect("mesh");
    let err = couple_distributed(
        &SelfExchange,
        &slave,
        &master,
        &DistributedOptions::default(),
    )
    .expect_err("degenerate");
    assert!(
        matches!(err, DistributedError::Coupling { rank: 0, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("degenerate"), "{err}");
}

#[test]
fn the_coupling_takes_an_exchange_behind_a_trait_object() {
    let exchange: &dyn mortar_mpi::Exchange = &SelfExchange;
    let rows = couple_distributed(
        exchange,
        &half_circle_mesh(6, false, 1).expect("mesh"),
        &half_circle_mesh(9, true, 1).expect("mesh"),
        &DistributedOptions::default(),
    )
    .expect("couples");
    let all = gather(exchange, &rows, 0).expect("gathers").expect("root");
    assert_eq!(all.slave_nodes, (1..=7).collect::<Vec<u64>>());
}
