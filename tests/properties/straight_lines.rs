//! The sorted merge of a straight 2D interface against the general path it
//! replaces: the same D and M, to round-off, on every interface it takes, and the general
//! path's results (warnings included) on every interface it leaves.
//!
//! Reference: the general path, forced by `common::Plain` (a strategy of one's own that wraps
//! [`SegmentBased`], which the coupling does not take for it, as a user's strategy reaches the
//! coupling). The merge evaluates the same Gauss rule at the same reference points of each
//! overlap; the master coordinate of a point comes from its coordinate along the line instead
//! of from cross products with the nodal normals, which on a straight line are the same
//! affine function: D and M agree to 1e-13 of their largest entry, the counts exactly.

use std::f64::consts::PI;

use mortar::core::integration::SegmentBased;
use mortar::elements::LINE2;
use mortar::testing::{polyline, shuffled, shuffled_faces};
use mortar::{assemble_coupling, CouplingOptions, Interface, SurfaceMesh};
use proptest::prelude::*;

use super::common::{both_ways, both_ways_with, config, dm_bits, ok, plain_with, vertical_lines};

/// `n + 1` points from `a` to `b` along the x-axis at height `y`, graded by `t -> t^p`.
fn points(a: f64, b: f64, y: f64, n: usize, p: f64) -> Vec<[f64; 2]> {
    (0..=n)
        .map(|i| [a + (b - a) * (i as f64 / n as f64).powf(p), y])
        .collect()
}

/// `points` turned by `angle` about the origin and moved by `shift`.
fn turned(points: &[[f64; 2]], angle: f64, shift: [f64; 2]) -> Vec<[f64; 2]> {
    let (s, c) = angle.sin_cos();
    points
        .iter()
        .map(|p| {
            [
                c * p[0] - s * p[1] + shift[0],
                s * p[0] + c * p[1] + shift[1],
            ]
        })
        .collect()
}

/// Standard and dual multipliers, Cartesian.
fn options() -> [CouplingOptions; 2] {
    [
        CouplingOptions::default(),
        CouplingOptions::default().dual(),
    ]
}

/// The mesh as written (0), its faces stored at random (1), or nodes and faces at random (2).
fn numbered(mesh: &SurfaceMesh, how: u8, seed: u64) -> SurfaceMesh {
    match how {
        0 => mesh.clone(),
        1 => shuffled_faces(mesh, seed).unwrap(),
        _ => shuffled(mesh, seed).unwrap(),
    }
}

proptest! {
    #![proptest_config(config(64))]

    /// Random straight non-matching pairs: graded, the master reaching past the slave at
    /// both ends, a small open gap or overlap, turned and moved, either orientation, stored
    /// and numbered in any order, standard or dual multipliers, automatic degree or a fixed
    /// one (1, an under-integrating rule, to 4): D and M as the general path's, and the merge
    /// takes every slave face or none (it takes them all when the gap is within the smallest
    /// slave face's search radius).
    #[test]
    fn straight_lines_give_the_general_paths_operators(
        ns in 1..40usize,
        nm in 1..60usize,
        ps in 0.6..1.8f64,
        pm in 0.6..1.8f64,
        past in (0.0..0.2f64, 0.0..0.2f64),
        gap in -0.004..0.004f64,
        angle in 0.0..6.3f64,
        shift in (-3.0..3.0f64, -3.0..3.0f64),
        flip in any::<bool>(),
        how in (0..3u8, 0..3u8),
        seed in any::<u64>(),
        dual in any::<bool>(),
        degree in 0..5u32,
    ) {
        let s = turned(&points(0.0, 1.0, 0.0, ns, ps), angle, [shift.0, shift.1]);
        let m = turned(&points(-past.0, 1.0 + past.1, gap, nm, pm), angle, [shift.0, shift.1]);
        let slave = numbered(&polyline(&s, 1, flip), how.0, seed);
        let master = numbered(&polyline(&m, 1000, !flip), how.1, seed ^ 0x9e37);
        let interface = ok(Interface::new(slave, master))?;
        let options = options()[usize::from(dual)].clone();
        let degree = (degree > 0).then_some(degree);
        let options = ok(options.segment_based(degree))?;
        let general = plain_with(&options, ok(SegmentBased::new(degree))?);
        let merged = both_ways_with(&interface, &options, &general, "random straight pair");
        let taken = merged.stats.straight_line_faces;
        prop_assert!(taken == 0 || taken == ns, "{taken} of {ns}");
        let h_min = (0..ns)
            .map(|i| (s[i + 1][0] - s[i][0]).hypot(s[i + 1][1] - s[i][1]))
            .fold(f64::INFINITY, f64::min);
        if gap.abs() < 0.99 * h_min {
            prop_assert_eq!(taken, ns);
            prop_assert_eq!(merged.stats.fused_line_faces, 0);
        }
    }
}

/// A tilted, graded line numbered at random, on both sides, under standard and dual
/// multipliers: the merge takes every face, and says so.
#[test]
fn a_straight_interface_takes_the_merge() {
    let s = turned(&points(0.0, 2.0, 0.0, 57, 1.3), 0.3, [0.4, -1.0]);
    let m = turned(&points(-0.1, 2.05, 0.0, 83, 0.8), 0.3, [0.4, -1.0]);
    let slave = shuffled(&polyline(&s, 1, false), 7).unwrap();
    let master = shuffled(&polyline(&m, 1000, true), 8).unwrap();
    let interface = Interface::new(slave, master).unwrap();
    for options in options() {
        let merged = both_ways(&interface, &options, "tilted line");
        assert_eq!(merged.stats.straight_line_faces, 57);
        assert_eq!(merged.stats.fused_line_faces, 0);
        assert_eq!(merged.stats.candidates, merged.stats.pairs);
        assert!(merged.warnings.is_empty());
    }
}

/// Matching nodes (a conforming interface, and one where every other master node is a slave
/// node): overlaps of zero length at shared nodes are left out as the general path leaves
/// them out.
#[test]
fn matching_nodes() {
    for (ns, nm) in [(10, 10), (10, 20), (12, 6)] {
        merged_like_the_general_path(ns, nm, (0.0, 1.0), "matching nodes");
    }
}

/// `ns` uniform slave faces on `[0, 1]` against `nm` on `master` (the x span), facing each
/// other: the merge takes every slave face, with the general path's D and M, standard and
/// dual.
fn merged_like_the_general_path(ns: usize, nm: usize, master: (f64, f64), what: &str) {
    let slave = polyline(&points(0.0, 1.0, 0.0, ns, 1.0), 1, false);
    let master = polyline(&points(master.0, master.1, 0.0, nm, 1.0), 1000, true);
    let interface = Interface::new(slave, master).unwrap();
    for options in options() {
        let merged = both_ways(&interface, &options, what);
        assert_eq!(merged.stats.straight_line_faces, ns, "{what}");
    }
}

/// One slave face over 500 master faces, and 500 slave faces over one master face.
#[test]
fn very_different_sizes() {
    for (ns, nm) in [(1, 500), (500, 1)] {
        merged_like_the_general_path(ns, nm, (-0.01, 1.01), "different sizes");
    }
}

/// The axisymmetric measure (vertical lines at r = 0.7): standard multipliers by the merge,
/// weighted by `2 pi r` as the general path weights them; dual multipliers depend on each
/// face's radii (their basis is not uniform), so the fused kernel takes them.
#[test]
fn axisymmetric_measure() {
    let interface = vertical_lines();
    let [standard, dual] = options().map(|o| o.axisymmetric());
    let merged = both_ways(&interface, &standard, "axisymmetric");
    assert_eq!(merged.stats.straight_line_faces, 13);
    let fused = both_ways(&interface, &dual, "axisymmetric dual");
    assert_eq!(fused.stats.straight_line_faces, 0);
    assert_eq!(fused.stats.fused_line_faces, 13);
}

/// Interfaces the merge leaves to the walk and the fused kernel, with the general path's
/// results and warnings: a slave longer than its master, a master beyond the search radius
/// in part, a kinked slave (by 0.02 and by 1e-9), a master in two bodies, closed chains; and a
/// master facing away, the general path's error.
#[test]
fn what_the_merge_leaves() {
    let line = |a: f64, b: f64, y: f64, n: usize, tag: u64, rev: bool| {
        polyline(&points(a, b, y, n, 1.0), tag, rev)
    };
    let mut cases: Vec<(&str, SurfaceMesh, SurfaceMesh)> = vec![
        (
            "uncovered ends",
            line(-0.2, 1.2, 0.0, 14, 1, false),
            line(0.0, 1.0, 0.0, 9, 1000, true),
        ),
        (
            "master beyond the search radius at one end",
            line(0.0, 1.0, 0.0, 10, 1, false),
            polyline(&[[-0.1, 0.0], [0.5, 0.0], [1.1, 0.3]], 1000, true),
        ),
        (
            "kinked slave",
            polyline(&[[0.0, 0.0], [0.5, 0.0], [1.0, 0.01]], 1, false),
            line(-0.1, 1.1, 0.0, 7, 1000, true),
        ),
        (
            // A turn of 1e-9, far above the coordinates' resolution here (1e-15).
            "slightly kinked slave",
            polyline(
                &[[0.0, 0.0], [0.25, 0.0], [0.5, 0.0], [1.0, 5e-10]],
                1,
                false,
            ),
            line(-0.1, 1.1, 0.0, 7, 1000, true),
        ),
    ];
    let mut two = line(-0.1, 0.537, 0.0, 7, 1000, true);
    let right = points(0.537, 1.1, 0.0, 9, 1.0);
    for (i, p) in right.iter().enumerate() {
        two.add_node(2000 + i as u64, [p[0], p[1], 0.0]).unwrap();
    }
    for i in 0..right.len() as u64 - 1 {
        two.add_face(&LINE2, &[2001 + i, 2000 + i]).unwrap();
    }
    cases.push(("two master bodies", line(0.0, 1.0, 0.0, 10, 1, false), two));
    let circle = |r: f64, n: usize, tag: u64, rev: bool| {
        let p: Vec<[f64; 2]> = (0..=n)
            .map(|i| {
                let t = 2.0 * PI * (i % n) as f64 / n as f64;
                [r * t.cos(), r * t.sin()]
            })
            .collect();
        let mut m = SurfaceMesh::new();
        for (i, q) in p[..n].iter().enumerate() {
            m.add_node(tag + i as u64, [q[0], q[1], 0.0]).unwrap();
        }
        for i in 0..n as u64 {
            let (a, b) = (tag + i, tag + (i + 1) % n as u64);
            m.add_face(&LINE2, &if rev { [b, a] } else { [a, b] })
                .unwrap();
        }
        m
    };
    cases.push((
        "closed chains",
        circle(1.0, 40, 1, false),
        circle(1.001, 57, 1000, true),
    ));
    for (what, slave, master) in cases {
        let interface = Interface::new(slave, master).unwrap();
        for options in options() {
            let c = both_ways(&interface, &options, what);
            assert_eq!(c.stats.straight_line_faces, 0, "{what}");
        }
    }
    let slave = line(0.0, 1.0, 0.0, 10, 1, false);
    let away = line(-0.1, 1.1, 0.0, 7, 1000, false);
    let interface = Interface::new(slave, away).unwrap();
    for options in options() {
        let e = assemble_coupling(&interface, &options).unwrap_err();
        let g = assemble_coupling(&interface, &super::common::plain(&options)).unwrap_err();
        assert_eq!(e.to_string(), g.to_string());
        // Every master face whose node box meets a slave face's (exact boxes: two-node lines
        // are not inflated; faces that only touch end to end count).
        assert!(e.to_string().contains("16 candidate pairs"), "{e}");
    }
}

/// A user's projector that does not claim a uniform direction, or a strategy that is not
/// `SegmentBased` itself, keeps the merge out.
#[test]
fn plug_ins_that_do_not_claim_it() {
    let slave = polyline(&points(0.0, 1.0, 0.0, 10, 1.0), 1, false);
    let master = polyline(&points(-0.1, 1.1, 0.0, 13, 1.0), 1000, true);
    let interface = Interface::new(slave, master).unwrap();
    let default = CouplingOptions::default();
    for (options, want) in [
        (super::common::not_uniform(&default), (0, 10)),
        (super::common::plain(&default), (0, 0)),
    ] {
        let c = assemble_coupling(&interface, &options).unwrap();
        assert_eq!(
            (c.stats.straight_line_faces, c.stats.fused_line_faces),
            want
        );
    }
}

/// The merge is bit-for-bit the same on 1, 2 and 3 threads (9,000 slave faces: three blocks
/// of 4,096 rows and of faces), with rows along the slave chain, against it (the slave
/// numbered backwards) and at random.
#[test]
fn straight_lines_are_bit_identical_across_thread_counts() {
    let slave = polyline(&points(0.0, 1.0, 0.0, 9000, 1.1), 1, false);
    let master = polyline(&points(-0.01, 1.0, 0.0, 12001, 0.9), 100_000, true);
    let backwards = polyline(
        &points(0.0, 1.0, 0.0, 9000, 1.1)
            .into_iter()
            .rev()
            .collect::<Vec<_>>(),
        1,
        true,
    );
    for (what, s) in [
        ("along", slave.clone()),
        ("against", backwards),
        ("random", shuffled(&slave, 11).unwrap()),
    ] {
        let interface = Interface::new(s, master.clone()).unwrap();
        let bits = |t: usize| {
            let c = assemble_coupling(&interface, &CouplingOptions::default().threads(t)).unwrap();
            assert_eq!(c.stats.straight_line_faces, 9000, "{what}");
            dm_bits(&c)
        };
        let one = bits(1);
        assert_eq!(one, bits(2), "{what}");
        assert_eq!(one, bits(3), "{what}");
    }
}

/// A finely divided line far from the origin (10,000 and 15,001 faces of [1000, 1001], tilted):
/// the overlaps are computed from the coordinates relative to each slave face, as the
/// general path computes them, so their rounding is relative to the face (coordinates along
/// the whole line lose `|x| / h` of it: 1e-9 here, which an earlier version of the merge
/// did: 2e-12 in D and M).
#[test]
fn far_from_the_origin_and_finely_divided() {
    let s = turned(&points(1000.0, 1001.0, 0.0, 10_000, 1.0), 0.2, [0.0, 0.0]);
    let m = turned(&points(999.99, 1001.01, 0.0, 15_001, 1.0), 0.2, [0.0, 0.0]);
    let interface = Interface::new(polyline(&s, 1, false), polyline(&m, 100_000, true)).unwrap();
    for options in options() {
        let merged = both_ways(&interface, &options, "far and fine");
        assert_eq!(merged.stats.straight_line_faces, 10_000);
    }
}
