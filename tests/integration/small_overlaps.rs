//! A small overlap far from the origin is an overlap: the coupling drops clip polygons whose
//! area the coordinates' rounding alone could give (two faces that only touch become a sliver
//! as thin as the rounding), but a polygon much wider than the rounding counts however small
//! its area.
//!
//! Found by the rigid-motion property test at 3,000 cases (`tests/properties/invariance.rs`,
//! its saved case of a translation by 1.6e5): three genuine slivers of about 4e-11 each,
//! 1e-5 wide, fell below the area threshold `8 eps |x| x (the slave face's diameter)` there
//! and were dropped as noise, so that D lost 1.1e-10 of its sum (9.4e-9 of its largest entry)
//! and the coupling warned of uncovered area the unmoved meshes did not have.
//!
//! Verification (closed form): the slave triangle `(0, 0), (1, 0), (0, 1)` is covered by two
//! master faces that meet on the line `x = 1 - delta`; the second covers only the corner
//! triangle of legs `delta` (area `delta^2 / 2`). Sum(D) is the slave's area, 1/2, and M's
//! column sums split it: `delta^2 / 2` for the corner. The pair of meshes is moved by `t`
//! along x (every coordinate stays exact in floating point).

use mortar::{assemble_coupling, CouplingOptions, Interface, SurfaceMesh};

/// The slave triangle and the master faces around it, moved by `t` along x.
fn meshes(delta: f64, t: f64) -> (SurfaceMesh, SurfaceMesh) {
    let mut slave = SurfaceMesh::new();
    for (tag, [x, y]) in [(1, [0.0, 0.0]), (2, [1.0, 0.0]), (3, [0.0, 1.0])] {
        slave.add_node(tag, [x + t, y, 0.0]).unwrap();
    }
    slave.add_face(&mortar::elements::TRI3, &[1, 2, 3]).unwrap();
    // Facing the slave: clockwise seen from +z. The line x = 1 - delta splits them.
    let c = 1.0 - delta;
    let mut master = SurfaceMesh::new();
    let nodes = [
        (1, [-1.0, -1.0]),
        (2, [c, -1.0]),
        (3, [c, 3.0]),
        (4, [-1.0, 3.0]),
        (5, [3.0, -1.0]),
        (6, [3.0, 3.0]),
    ];
    for (tag, [x, y]) in nodes {
        master.add_node(tag, [x + t, y, 0.0]).unwrap();
    }
    for face in [[1, 3, 2], [1, 4, 3], [2, 6, 5], [2, 3, 6]] {
        master.add_face(&mortar::elements::TRI3, &face).unwrap();
    }
    (slave, master)
}

/// delta = 1e-5: the corner's area, 5e-11, is below `8 eps |x| x diameter` at t = 1e5
/// (2.5e-10), its width is 5e4 times that rounding. At the origin and far from it, the
/// slave is covered, sum(D) = 1/2 and the corner's master nodes carry its area.
#[test]
fn a_small_wide_overlap_far_from_the_origin_counts() {
    let delta = 1e-5;
    for t in [0.0, 1e3, 1e5, 1e6] {
        let (slave, master) = meshes(delta, t);
        let interface = Interface::new(slave, master).unwrap();
        let c = assemble_coupling(&interface, &CouplingOptions::default()).unwrap();
        let sum_d: f64 = c.d.data().iter().sum();
        assert!(
            (sum_d - 0.5).abs() <= 1e-14,
            "t = {t:e}: sum(D) = {sum_d:.17e}, the slave's area 0.5"
        );
        assert_eq!(c.stats.uncovered_area, 0.0, "t = {t:e}: {:?}", c.warnings);
        assert!(c.warnings.is_empty(), "t = {t:e}: {:?}", c.warnings);
        assert_eq!(
            c.stats.pairs, 2,
            "t = {t:e}: both master faces overlap the slave"
        );
        // The corner's master face (nodes 2, 3, 5, 6 on x >= 1 - delta): its nodes' columns
        // of M sum to the part of the corner each shares with the left face's nodes 2, 3
        // and the right face's own nodes 5, 6; the right face's nodes 5 and 6 carry only
        // corner area, at most delta^2 / 2.
        let col = |tag: u64| c.master_nodes.iter().position(|&n| n == tag).unwrap();
        let m = c.m.to_dense();
        let corner: f64 = [5, 6]
            .iter()
            .map(|&tag| (0..m.nrows()).map(|r| m[(r, col(tag))]).sum::<f64>())
            .sum();
        assert!(
            corner > 0.0 && corner <= 0.5 * delta * delta * (1.0 + 1e-6),
            "t = {t:e}: the corner's own master nodes carry {corner:e}"
        );
    }
}
