//! The grouped tree query (`MasterTree::candidates_of_group`, what the coupling runs: one
//! descent per four neighbouring slave faces with the union of their search boxes, then each
//! face's own box tests) gives each slave face exactly the candidates of its own query
//! (`MasterTree::candidates_into`). Reference: the single-face query, whose candidates are
//! every master face whose box meets the face's search box. And the boxes, not inflated where
//! the nodes bound the faces, miss no overlapping pair (reference: the all-pairs coupling).

use mortar::core::search::{GroupScratch, MasterTree};
use mortar::core::{SearchRadius, Tolerances};
use mortar::generate::{cylinder_surface, half_circle_mesh};
use mortar::testing::{covered_pair_3d_with, rigid_motion_3d, PairConfig};
use mortar::{assemble_coupling, CouplingOptions, Interface, SurfaceMesh};
use proptest::prelude::*;
use std::f64::consts::PI;

use super::common::{config, dm_bits, dm_deviations, ok};

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

/// Couples `slave` and `master` with the default search, whose boxes of two-node lines,
/// linear triangles and bilinear quads are not inflated (`CouplingStats::slave_box_inflation`
/// and `master_box_inflation` are 0), and with a search radius of a thousand units, so that
/// every master face a slave face's normals could reach is its candidate (on the cylinders,
/// every master face over the slave face's span in z: the normals have no z component; on the
/// planes, every master face); D and M must be the same bits, with standard and dual
/// multipliers. Reference: that all-pairs coupling (the strategy itself decides which
/// candidates overlap; a candidate that does not adds nothing to D or M).
fn exact_boxes_miss_no_pair(slave: &SurfaceMesh, master: &SurfaceMesh, what: &str) {
    exact_boxes_miss_no_pair_within(slave, master, SearchRadius::FaceSize(1.0), what);
}

/// [`exact_boxes_miss_no_pair`] with the search radius `radius` (every overlapping pair must
/// lie within it).
fn exact_boxes_miss_no_pair_within(
    slave: &SurfaceMesh,
    master: &SurfaceMesh,
    radius: SearchRadius,
    what: &str,
) {
    let within = Tolerances {
        search_radius: radius,
        ..Tolerances::default()
    };
    let exact = Interface::with_tolerances(slave.clone(), master.clone(), within).unwrap();
    let tol = Tolerances {
        search_radius: SearchRadius::Distance(1e3),
        ..Tolerances::default()
    };
    let every = Interface::with_tolerances(slave.clone(), master.clone(), tol).unwrap();
    for options in [
        CouplingOptions::default(),
        CouplingOptions::default().dual(),
    ] {
        let a = assemble_coupling(&exact, &options).unwrap();
        let b = assemble_coupling(&every, &options).unwrap();
        assert_eq!(
            (a.stats.slave_box_inflation, a.stats.master_box_inflation),
            (0.0, 0.0),
            "{what}"
        );
        assert!(a.stats.candidates <= b.stats.candidates, "{what}");
        assert_eq!(a.stats.pairs, b.stats.pairs, "{what}");
        if a.stats.fused_line_faces == 0 {
            assert_eq!(dm_bits(&a), dm_bits(&b), "{what}");
        } else {
            // The chain walk gives a face's candidates in walk order, which the reference's
            // longer walks change: D's sums may differ in the last bit.
            for (name, dev) in dm_deviations(&a, &b) {
                assert!(dev <= 1e-13, "{what}: {name} deviates by {dev:e}");
            }
        }
    }
}

proptest! {
    #![proptest_config(config(24))]

    /// Random covered 3D pairs of any cell kinds, the master moved off the slave along the
    /// slave's normal by up to 0.9 of the shortest edge (an open gap, within the default
    /// search radius of one face diameter) or into it (a penetration); as it is, and with
    /// both moved rigidly.
    #[test]
    fn exact_boxes_find_every_overlapping_pair_3d(
        pair in covered_pair_3d_with(PairConfig::default()),
        gap in -0.9..0.9f64,
        motion in rigid_motion_3d(),
    ) {
        let normal = ok(pair.interface())?.slave_nodal_normals()[0];
        let g = gap * pair.shortest_edge();
        let mut moved = pair.clone();
        ok(moved.master.transform(|x| x + normal * g))?;
        // Axis-aligned first: there the boxes are tight along the normal.
        exact_boxes_miss_no_pair(&moved.slave, &moved.master, "3D pair");
        let moved = ok(moved.transformed(|x| motion.apply(x)))?;
        exact_boxes_miss_no_pair(&moved.slave, &moved.master, "3D pair moved");
    }
}

/// Curved interfaces across an open gap, where the projection directions fan out: a Quad4
/// cylinder inside a Tri3 one (3D), a half circle of lines inside a larger one (2D, the chain
/// walk). The gaps are a tenth and a half of the slave's face size.
#[test]
fn exact_boxes_find_every_overlapping_pair_on_curved_surfaces() {
    for gap in [0.02, 0.1] {
        exact_boxes_miss_no_pair(
            &cylinder_surface(1.0, 24, 4, false, false, 1).unwrap(),
            &cylinder_surface(1.0 + gap, 31, 5, true, true, 1000).unwrap(),
            &format!("cylinders, gap {gap}"),
        );
        let mut outer = half_circle_mesh(23, true, 1000).unwrap();
        outer.transform(|x| x * (1.0 + gap)).unwrap();
        exact_boxes_miss_no_pair(
            &half_circle_mesh(16, false, 1).unwrap(),
            &outer,
            &format!("half circles, gap {gap}"),
        );
    }
}

/// Coarse curved slave faces whose nodal normals fan out (30 degrees either side of a face's
/// centre normal on a hexagonal cylinder, 18 on five lines round a half circle), against a
/// fine master across a gap `g`, with the search radius just above the farthest distance
/// any overlapping pair needs along its projection direction, `(R + g) - R cos(pi / N)` (the
/// centre of a slave chord to the master's circle of radius `R + g`): every pair must be
/// found, the same D and M as the all-pairs coupling. Regression: the boxes reached the
/// radius times the normals' own components, `cos(pi / N)` of it along a face's centre
/// normal, where the projection direction is that normal itself: pairs farther than
/// `0.87` of the radius (the cylinder) or `0.95` (the half circle) were not coupled. The
/// reach is now divided by the length the normals' convex combinations have at least.
#[test]
fn exact_boxes_reach_the_radius_where_normals_fan_out() {
    let gap = 0.05;
    let cylinder_reach = (1.0 + gap) - (PI / 6.0).cos();
    exact_boxes_miss_no_pair_within(
        &cylinder_surface(1.0, 6, 2, false, false, 1).unwrap(),
        &cylinder_surface(1.0 + gap, 60, 5, true, true, 1000).unwrap(),
        SearchRadius::Distance(1.01 * cylinder_reach),
        "hexagonal cylinder",
    );
    let mut outer = half_circle_mesh(60, true, 1000).unwrap();
    outer.transform(|x| x * (1.0 + gap)).unwrap();
    let arc_reach = (1.0 + gap) - (PI / 10.0).cos();
    exact_boxes_miss_no_pair_within(
        &half_circle_mesh(5, false, 1).unwrap(),
        &outer,
        SearchRadius::Distance(1.01 * arc_reach),
        "five lines on a half circle",
    );
}
