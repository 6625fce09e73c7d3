//! The closed-form integration of clip polygons (3D linear triangles, segment-based) against
//! the general path it replaces: the same D and M, to round-off, on every interface it takes,
//! and the same counts and warnings.
//!
//! Reference: the general path, forced by `common::Plain` (the strategy's quadrature points
//! on the clip triangles, integrated by the coupling), whose exactness on affine faces the
//! patch and conservation tests establish. Both integrate the same degree-2 polynomials over
//! the same clip polygons exactly, the one by the vertex-fan midpoint rule, the other by the
//! polygons' moments (Green's theorem): D and M agree to 1e-13 of their largest entry, the
//! counts of pairs, back-facing candidates and the uncovered area exactly.

use std::sync::Arc;

use mortar::core::integration::SegmentBased;
use mortar::core::projector::ElementNormal;
use mortar::elements::TRI3;
use mortar::generate::{cylinder_surface, sphere_surface, square_triangles, Diagonal};
use mortar::testing::{covered_pair_3d_with, rigid_motion_3d, CellKind, PairConfig};
use mortar::{assemble_coupling, CouplingOptions, Interface, SurfaceMesh};
use nalgebra::Vector3;
use proptest::prelude::*;

use super::common::{
    both_ways, both_ways_with, both_ways_within, config, dm_bits, ok, plain, plain_with,
};

/// Triangles on both sides, any size and jitter of the default configuration.
fn triangles() -> PairConfig {
    PairConfig {
        slave_kinds: vec![CellKind::Triangles],
        master_kinds: vec![CellKind::Triangles],
        ..PairConfig::default()
    }
}

/// Standard or dual multipliers.
fn options(dual: bool) -> CouplingOptions {
    if dual {
        CouplingOptions::default().dual()
    } else {
        CouplingOptions::default()
    }
}

/// Cells of any kind, parallelograms (no jitter) on one side or both, moved rigidly anywhere
/// within 1e6 of the origin.
fn flat_cells(slave_jitter: f64, master_jitter: f64) -> PairConfig {
    PairConfig {
        slave_jitter,
        master_jitter,
        ..PairConfig::default()
    }
}

proptest! {
    #![proptest_config(config(48))]

    /// Random covered pairs of quads, triangles or both, each cell a parallelogram: the
    /// moments of the clip polygons (or, for triangles on both sides, the vertex formulas)
    /// take every slave face and give the general path's D and M (the strategy's degree-4
    /// points on each clip triangle against the moments' vertex formulas on the polygon's
    /// fan in the slave's reference coordinates). Moved rigidly anywhere within 1e6 of the
    /// origin, the same D and M: far from the origin a quad's projection is affine only to
    /// the rounding of its coordinates, finer than the test of an affine map
    /// ([`PlanarMap`](mortar::core::geometry::PlanarMap), 1e-13 of its Jacobian), and such
    /// faces go to the strategy. Moved, each path computes from coordinates that carry a
    /// rounding of `eps |t|`, `eps |t| / h` of the shortest edge `h`, and the two paths round
    /// differently (the strategy maps its points back to both faces, the moments work about
    /// the clip polygon's first vertex): the moved comparison allows `1e-13 + eps |t| / h`.
    /// A saved case (translation 1.3e5, dual, from a run of 20,000 cases) deviates in D by
    /// 5.0e-13, and one a clean-clone CI run found (translation 5.5e4, dual) by 3.1e-13:
    /// 0.004 and 0.005 `eps |t| / h`, beyond the 1e-13 that the comparison allowed before.
    #[test]
    fn moments_give_the_general_paths_operators_on_parallelograms(
        pair in covered_pair_3d_with(flat_cells(0.0, 0.0)),
        motion in rigid_motion_3d(),
        dual in any::<bool>(),
    ) {
        let interface = ok(pair.interface())?;
        let c = both_ways(&interface, &options(dual), "parallelograms");
        prop_assert_eq!(c.stats.closed_form_faces, interface.slave().face_count());
        let moved = ok(pair.transformed(|x| motion.apply(x)))?;
        let h = pair.shortest_edge();
        let tol = 1e-13 + f64::EPSILON * (motion.translation.norm() + 2.0) / h;
        let options = options(dual);
        let general = plain(&options);
        both_ways_within(&ok(moved.interface())?, &options, &general, tol, "moved parallelograms");
    }

    /// Jittered quads on one side (bilinear maps that are not affine): the faces the moments
    /// cannot take (a warped slave quad, or a slave face over a warped master quad) go to the
    /// strategy, the others are integrated by moments; either way, the general path's D and
    /// M.
    #[test]
    fn moments_leave_warped_quads_to_the_strategy(
        pair in covered_pair_3d_with(flat_cells(0.0, 0.3)),
        swap in any::<bool>(),
        dual in any::<bool>(),
    ) {
        let interface = if swap {
            let (s, m) = (pair.master.clone(), pair.slave.clone());
            ok(Interface::new(s, m))?
        } else {
            ok(pair.interface())?
        };
        both_ways(&interface, &options(dual), "warped quads");
    }

    /// Random covered triangle pairs (jittered, either orientation), moved rigidly anywhere
    /// within 1e6 of the origin, standard or dual, nodal-normal or element-normal
    /// projection: the closed form takes every slave face and gives the general path's D
    /// and M. Unmoved to 1e-13; moved, to `1e-13 + eps |t| / h` as the parallelograms above
    /// (both paths compute from coordinates rounded to `eps |t|`, and round differently). A
    /// saved case (translation 1.0e4, dual) deviates in D by 2.4e-13, and the case it shrank
    /// from by 1.0e-12, in a run of 4,000 cases: both beyond the 1e-13 the moved comparison
    /// allowed before, far within `eps |t| / h`.
    #[test]
    fn closed_form_gives_the_general_paths_operators(
        pair in covered_pair_3d_with(triangles()),
        motion in rigid_motion_3d(),
        dual in any::<bool>(),
        element_normal in any::<bool>(),
    ) {
        let mut options = options(dual);
        if element_normal {
            options.projector = Arc::new(ElementNormal);
        }
        let general = plain(&options);
        let interface = ok(pair.interface())?;
        let c = both_ways_with(&interface, &options, &general, "random pair");
        prop_assert_eq!(c.stats.closed_form_faces, interface.slave().face_count());
        let moved = ok(pair.transformed(|x| motion.apply(x)))?;
        let interface = ok(moved.interface())?;
        let h = pair.shortest_edge();
        let tol = 1e-13 + f64::EPSILON * (motion.translation.norm() + 2.0) / h;
        let c = both_ways_within(&interface, &options, &general, tol, "moved random pair");
        prop_assert_eq!(c.stats.closed_form_faces, interface.slave().face_count());
    }
}

/// Curved surfaces, where the plane of a slave face follows its averaged nodal normals and
/// the face's measure differs from the plane's by `1 / cos` of the tilt: a sphere against a
/// finer sphere (closed, every face covered), a triangulated cylinder against another, each
/// with an open gap of 1e-3 of the radius.
#[test]
fn curved_triangle_surfaces() {
    let cases = [
        (
            sphere_surface(1.0, 5, false, 1).unwrap(),
            sphere_surface(1.001, 7, true, 10_000).unwrap(),
            "spheres",
        ),
        (
            cylinder_surface(1.0, 24, 5, true, false, 1).unwrap(),
            cylinder_surface(1.001, 37, 7, true, true, 10_000).unwrap(),
            "cylinders",
        ),
    ];
    every_face_in_closed_form(cases, false);
}

/// For each `(slave, master, what)`, standard and dual: the closed form takes every slave face
/// and gives the general path's D and M; with `threads`, the same bits on 1, 2 and 3 threads.
fn every_face_in_closed_form(cases: [(SurfaceMesh, SurfaceMesh, &str); 2], threads: bool) {
    for (slave, master, what) in cases {
        let faces = slave.face_count();
        let interface = Interface::new(slave, master).unwrap();
        for dual in [false, true] {
            let c = both_ways(&interface, &options(dual), what);
            assert_eq!(c.stats.closed_form_faces, faces, "{what}");
            if threads {
                let bits = |t: usize| {
                    dm_bits(&assemble_coupling(&interface, &options(dual).threads(t)).unwrap())
                };
                let one = bits(1);
                assert_eq!(one, bits(2), "{what}");
                assert_eq!(one, bits(3), "{what}");
            }
        }
    }
}

/// A slave larger than its master, shifted by a third of a cell, and beside the master a
/// second body that faces the same way as the slave (its far side, say): faces uncovered
/// and partly covered, and back-facing master faces, counted as the general path counts
/// them.
#[test]
fn uncovered_area_and_back_facing_faces_are_counted_alike() {
    let slave = square_triangles(9, Diagonal::Main, 0.0, false, 1).unwrap();
    let mut master = square_triangles(7, Diagonal::Anti, 0.0, true, 10_000).unwrap();
    master
        .transform(|x| Vector3::new(0.3 + 0.6 * x.x, 0.05 + 0.6 * x.y, x.z))
        .unwrap();
    let mut far = square_triangles(3, Diagonal::Main, -1e-3, false, 20_000).unwrap();
    far.transform(|x| Vector3::new(0.25 * x.x, 0.7 + 0.25 * x.y, x.z))
        .unwrap();
    let tags = far.node_tags().to_vec();
    for (t, x) in tags.iter().zip(far.coords()) {
        master.add_node(*t, [x.x, x.y, x.z]).unwrap();
    }
    for f in 0..far.face_count() {
        let nodes: Vec<u64> = far
            .face(f)
            .nodes
            .iter()
            .map(|&n| tags[n as usize])
            .collect();
        master.add_face(&TRI3, &nodes).unwrap();
    }
    let interface = Interface::new(slave, master).unwrap();
    for dual in [false, true] {
        let c = both_ways(&interface, &options(dual), "uncovered");
        let s = &c.stats;
        assert!(
            s.faces_without_partner > 0 && s.faces_partly_covered > 0 && s.back_facing > 0,
            "{s:?}"
        );
        assert_eq!(s.closed_form_faces + s.faces_without_partner, 162, "{s:?}");
    }
}

/// A fixed degree at least the integrands' (2) keeps the closed form; degree 1 (inexact on
/// purpose) is the strategy's, as is a strategy that is not `SegmentBased` itself; a
/// triangle against quads takes the moments at its integrands' degree (3) and not below it.
#[test]
fn what_the_closed_form_takes() {
    let tris = |n, flip, tag, d| square_triangles(n, d, 0.0, flip, tag).unwrap();
    let interface = Interface::new(
        tris(6, false, 1, Diagonal::Main),
        tris(7, true, 1000, Diagonal::Anti),
    )
    .unwrap();
    for degree in [2, 5] {
        let strategy = SegmentBased::new(Some(degree)).unwrap();
        let fast = CouplingOptions::default()
            .segment_based(Some(degree))
            .unwrap();
        let general = plain_with(&fast, strategy);
        let c = both_ways_with(&interface, &fast, &general, "fixed degree");
        assert_eq!(c.stats.closed_form_faces, 72);
        assert_eq!(c.degrees_used(), vec![degree]);
    }
    let low = CouplingOptions::default().segment_based(Some(1)).unwrap();
    let c = assemble_coupling(&interface, &low).unwrap();
    assert_eq!(c.stats.closed_form_faces, 0);
    let c = assemble_coupling(&interface, &plain_with(&low, SegmentBased::default())).unwrap();
    assert_eq!(c.stats.closed_form_faces, 0);
    // Quad masters: the moments of the clip polygons, down to the integrands' degree (3 for a
    // triangle against a quad).
    let quads = mortar::generate::square_quads(5, 0.0, true, 1000).unwrap();
    let interface = Interface::new(tris(6, false, 1, Diagonal::Main), quads).unwrap();
    let c = both_ways(&interface, &CouplingOptions::default(), "quad master");
    assert_eq!(c.stats.closed_form_faces, 72);
    let three = CouplingOptions::default().segment_based(Some(3)).unwrap();
    let c = both_ways_with(
        &interface,
        &three,
        &plain_with(&three, SegmentBased::new(Some(3)).unwrap()),
        "degree 3",
    );
    assert_eq!(c.stats.closed_form_faces, 72);
    let two = CouplingOptions::default().segment_based(Some(2)).unwrap();
    let c = assemble_coupling(&interface, &two).unwrap();
    assert_eq!(c.stats.closed_form_faces, 0);
}

/// The closed form is bit-for-bit the same on 1, 2 and 3 threads (2,888 slave faces, twelve
/// chunks).
#[test]
fn closed_form_is_bit_identical_across_thread_counts() {
    let slave = square_triangles(38, Diagonal::Main, 0.0, false, 1).unwrap();
    let master = square_triangles(53, Diagonal::Anti, 0.0, true, 100_000).unwrap();
    let interface = Interface::new(slave, master).unwrap();
    let bits = |t: usize| {
        let c = assemble_coupling(&interface, &CouplingOptions::default().threads(t)).unwrap();
        assert_eq!(c.stats.closed_form_faces, 2 * 38 * 38);
        dm_bits(&c)
    };
    let one = bits(1);
    assert_eq!(one, bits(2));
    assert_eq!(one, bits(3));
}

/// A quad cylinder against a finer triangulated one (the benchmark's cylinder, small), each
/// slave face a flat rectangle whose plane follows its averaged nodal normals, with an open
/// gap of 1e-3 of the radius; and a quad cylinder against a quad cylinder: the moments take
/// every slave face and give the general path's D and M, standard and dual, the same bits on
/// 1, 2 and 3 threads.
#[test]
fn quad_cylinders_by_moments() {
    let cases = [
        (
            cylinder_surface(1.0, 24, 5, false, false, 1).unwrap(),
            cylinder_surface(1.001, 37, 7, true, true, 10_000).unwrap(),
            "quads against triangles",
        ),
        (
            cylinder_surface(1.0, 24, 5, false, false, 1).unwrap(),
            cylinder_surface(1.001, 37, 7, false, true, 10_000).unwrap(),
            "quads against quads",
        ),
    ];
    every_face_in_closed_form(cases, true);
}

/// One flat Quad4 slave face over 100 x 100 master quads (the benchmark's ratio3d, smaller):
/// D is the mass matrix of the unit square, `[4 2 1 2] / 36` by rows (closed form), to 1e-15,
/// and M is the general path's. Each pair is integrated about its clip polygon's first
/// vertex: composed about the slave's centre instead, the master's shape functions have
/// coefficients of 1e2 and 1e4 whose sums cancel, and M strayed by 1e-12 here (3.5e-11 of its
/// row at 316 x 316, 2.8e-10 at 1000 x 1000).
#[test]
fn a_coarse_quad_over_a_fine_master_keeps_its_accuracy() {
    use mortar::generate::square_quads;
    let interface = Interface::new(
        square_quads(1, 0.0, false, 1).unwrap(),
        square_quads(100, 0.0, true, 100).unwrap(),
    )
    .unwrap();
    let c = both_ways(&interface, &options(false), "ratio 100");
    assert_eq!(c.stats.closed_form_faces, 1);
    let exact = [4.0 / 36.0, 2.0 / 36.0, 1.0 / 36.0];
    for r in 0..4 {
        let mut row: Vec<f64> = (0..4).map(|k| *c.d.get(r, k).unwrap_or(&0.0)).collect();
        row.sort_by(|a, b| b.total_cmp(a));
        for (got, want) in row.iter().zip([exact[0], exact[1], exact[1], exact[2]]) {
            assert!((got - want).abs() <= 1e-15, "D row {r}: {row:?}");
        }
    }
}
