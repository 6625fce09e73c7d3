//! The grouped tree query (`MasterTree::candidates_of_group`, what the coupling runs: one
//! descent per four neighbouring slave faces with the union of their search boxes, then each
//! face's own box tests) gives each slave face exactly the candidates of its own query
//! (`MasterTree::candidates_into`). Reference: the single-face query, whose candidates are
//! every master face whose box meets the face's search box.

use mortar::core::search::{GroupScratch, MasterTree};
use mortar::generate::cylinder_surface;
use mortar::testing::{covered_pair_3d_with, rigid_motion_3d, PairConfig};
use mortar::Interface;
use proptest::prelude::*;

use super::common::{config, ok};

/// Every slave face's candidates by the grouped query against its own query, with the slave
/// faces in the given order (the coupling's is spatial; any order must give the same sets).
fn grouped_equals_single(interface: &Interface, order: &[usize]) {
    let tree = MasterTree::build(interface);
    let faces: Vec<_> = order.iter().map(|&s| interface.slave_face(s)).collect();
    let (mut scratch, mut all, mut ends) = (GroupScratch::default(), Vec::new(), vec![0]);
    tree.candidates_of_group(interface, &faces, &mut scratch, &mut all, &mut ends);
    assert_eq!(ends.len(), faces.len() + 1);
    let mut single = Vec::new();
    for (i, &s) in order.iter().enumerate() {
        tree.candidates_into(interface, s, &mut single);
        assert_eq!(&all[ends[i]..ends[i + 1]], &single[..], "slave face {s}");
    }
}

proptest! {
    #![proptest_config(config(32))]

    /// Random covered pairs of any cell kinds, moved rigidly, the slave faces in file order
    /// and reversed.
    #[test]
    fn grouped_queries_give_each_face_its_own_candidates(
        pair in covered_pair_3d_with(PairConfig::default()),
        motion in rigid_motion_3d(),
    ) {
        let moved = ok(pair.transformed(|x| motion.apply(x)))?;
        let interface = ok(moved.interface())?;
        let n = interface.slave().face_count();
        let forward: Vec<usize> = (0..n).collect();
        grouped_equals_single(&interface, &forward);
        let backward: Vec<usize> = (0..n).rev().collect();
        grouped_equals_single(&interface, &backward);
    }
}

/// A cylinder against a finer one with an open gap (several slabs of the tree: 2 x 10^5
/// master faces), the slave faces in file order.
#[test]
fn grouped_queries_on_a_cylinder_with_several_slabs() {
    let interface = Interface::new(
        cylinder_surface(1.0, 120, 30, false, false, 1).unwrap(),
        cylinder_surface(1.001, 700, 150, true, true, 1_000_000).unwrap(),
    )
    .unwrap();
    let n = interface.slave().face_count();
    grouped_equals_single(&interface, &(0..n).collect::<Vec<_>>());
}
