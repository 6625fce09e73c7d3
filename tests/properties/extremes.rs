//! No false diagnosis: coarse closed surfaces whose neighbouring faces turn
//! by 120 degrees are valid, and a valid interface stays valid, with D and M scaled by the
//! scale's power, from 1e-100 to 1e100; beyond what double precision carries, a typed error
//! names the range.

use mortar::core::element::ElementRef;
use mortar::core::error::RangeLimit;
use mortar::core::mesh::orient::face_each_other;
use mortar::elements::{LINE2, QUAD4, TRI3};
use mortar::generate::{line_mesh, square_quads, square_triangles, Diagonal};
use mortar::testing::MeshPair;
use mortar::{
    assemble_coupling, CouplingOptions, CouplingWarning, Interface, MortarError, SurfaceMesh,
};
use nalgebra::Vector3;

use super::common::{by_tags, compare_mapped};

/// A regular `k`-gon of circumradius 1 in the plane `z = 0`, its first corner at angle
/// `phase`, each side cut into `cuts` Line2. Counter-clockwise (outward normals), or clockwise
/// if `inward`. Node tags from `first_tag`.
fn polygon_loop(k: usize, cuts: usize, phase: f64, inward: bool, first_tag: u64) -> SurfaceMesh {
    let n = k * cuts;
    let mut mesh = SurfaceMesh::new();
    let corner = |i: usize| {
        let a = phase + std::f64::consts::TAU * (i % k) as f64 / k as f64;
        Vector3::new(a.cos(), a.sin(), 0.0)
    };
    for i in 0..k {
        for c in 0..cuts {
            let t = c as f64 / cuts as f64;
            let x = corner(i) * (1.0 - t) + corner(i + 1) * t;
            mesh.add_node(first_tag + (i * cuts + c) as u64, x.into())
                .unwrap();
        }
    }
    for i in 0..n {
        let (a, b) = (first_tag + i as u64, first_tag + ((i + 1) % n) as u64);
        let nodes = if inward { [b, a] } else { [a, b] };
        mesh.add_face(&LINE2, &nodes).unwrap();
    }
    mesh
}

/// The closed surface of a prism over a regular `k`-gon (circumradius 1, first corner at angle
/// `phase`) from `z = 0` to `z = 1`: `k` side facets (one Quad4 each, or two Tri3 if
/// `split`) and two caps (a fan of `k` Tri3 about the axis). Normals outward, or inward if
/// `inward`. Node tags from `first_tag`.
fn prism_surface(k: usize, phase: f64, split: bool, inward: bool, first_tag: u64) -> SurfaceMesh {
    let mut mesh = SurfaceMesh::new();
    let bottom = |i: usize| first_tag + (i % k) as u64;
    let top = |i: usize| first_tag + (k + i % k) as u64;
    let (bc, tc) = (first_tag + 2 * k as u64, first_tag + 2 * k as u64 + 1);
    for (level, z) in [0.0, 1.0].into_iter().enumerate() {
        for i in 0..k {
            let a = phase + std::f64::consts::TAU * i as f64 / k as f64;
            mesh.add_node(first_tag + (level * k + i) as u64, [a.cos(), a.sin(), z])
                .unwrap();
        }
    }
    mesh.add_node(bc, [0.0, 0.0, 0.0]).unwrap();
    mesh.add_node(tc, [0.0, 0.0, 1.0]).unwrap();
    let mut add = |nodes: &[u64]| {
        let mut nodes = nodes.to_vec();
        if inward {
            nodes[1..].reverse();
        }
        let el: ElementRef = if nodes.len() == 4 { &QUAD4 } else { &TRI3 };
        mesh.add_face(el, &nodes).unwrap();
    };
    for i in 0..k {
        let (a, b, c, d) = (bottom(i), bottom(i + 1), top(i + 1), top(i));
        if split {
            add(&[a, b, c]);
            add(&[a, c, d]);
        } else {
            add(&[a, b, c, d]);
        }
        add(&[bc, bottom(i + 1), bottom(i)]);
        add(&[tc, top(i), top(i + 1)]);
    }
    mesh
}

/// Regression: the three lines of a triangle (a 3-facet prism in 2D), and the closed surface
/// of a triangular prism (sides as quads or split into triangles), coupled with the same
/// surface facing them, or with one turned by half a facet: neighbouring faces turn by 120
/// degrees, which the angle test between normals took for faces "oriented against their
/// neighbours". The surfaces are consistently oriented (each shared edge traversed both ways),
/// so they are valid; on the coincident pair, sum(D) is the surface's measure.
#[test]
fn coarse_closed_surfaces_turning_by_120_degrees_are_valid() {
    let half = std::f64::consts::PI / 3.0;
    for cuts in [1, 2, 3] {
        for phase in [0.0, half] {
            let slave = polygon_loop(3, cuts, 0.0, false, 1);
            let master = polygon_loop(3, cuts + 1, phase, true, 1000);
            let interface = Interface::new(slave, master)
                .unwrap_or_else(|e| panic!("2D, {cuts} cuts, phase {phase}: {e}"));
            if phase == 0.0 {
                let c = assemble_coupling(&interface, &CouplingOptions::default()).unwrap();
                let length = 3.0 * 3f64.sqrt();
                assert!(
                    (c.stats.area - length).abs() < 1e-12 * length,
                    "{}",
                    c.stats.area
                );
            }
        }
    }
    for split in [false, true] {
        for phase in [0.0, half] {
            let slave = prism_surface(3, 0.0, split, false, 1);
            let master = prism_surface(3, phase, !split, true, 1000);
            let interface = Interface::new(slave, master)
                .unwrap_or_else(|e| panic!("3D, split {split}, phase {phase}: {e}"));
            let c = assemble_coupling(&interface, &CouplingOptions::default()).unwrap();
            // Three unit-high sides of width sqrt(3), two caps of area 3 sqrt(3) / 4.
            let area = 3.0 * 3f64.sqrt() * 1.5;
            if phase == 0.0 {
                assert!(
                    (c.stats.area - area).abs() < 1e-12 * area,
                    "{}",
                    c.stats.area
                );
            } else {
                // Turned by half a facet, the master leaves the slave's corners uncovered:
                // said as uncovered area (what sum(D) misses of the surface), no pair skipped.
                match c.warnings.as_slice() {
                    [CouplingWarning::UncoveredSlaveArea {
                        area: uncovered,
                        total,
                        ..
                    }] => {
                        assert!((total - area).abs() < 1e-12 * area, "{total}");
                        assert!(
                            (c.stats.area + uncovered - area).abs() < 1e-12 * area,
                            "{} + {uncovered}",
                            c.stats.area
                        );
                    }
                    other => panic!("split {split}: {other:?}"),
                }
            }
        }
    }
}

/// Regression: `mortar couple` orients surfaces given alone (`face_each_other`) by where the
/// master lies along each slave face's normal. On the triangle and the triangular prism, master
/// faces of the neighbouring facets (turned by 120 degrees, their centres within reach), and
/// of the prism's far cap, voted the slave inward: the slave was turned, a third of it left
/// uncovered. Each slave face heeds only the nearest master faces along its normal now (here
/// the coincident ones, which leave the slave as given); a master given the same way round as
/// the slave is turned, and the coupling covers the whole surface.
#[test]
fn coarse_closed_surfaces_are_turned_to_face_each_other() {
    let cases = [
        (
            polygon_loop(3, 1, 0.0, false, 1),
            polygon_loop(3, 2, 0.0, false, 1000),
        ),
        (
            prism_surface(3, 0.0, false, false, 1),
            prism_surface(3, 0.0, true, false, 1000),
        ),
        (
            prism_surface(3, 0.0, true, false, 1),
            prism_surface(3, 0.0, false, false, 1000),
        ),
    ];
    for (mut slave, mut master) in cases {
        let measure = if slave.face(0).element.domain().dim() == 1 {
            3.0 * 3f64.sqrt()
        } else {
            3.0 * 3f64.sqrt() * 1.5
        };
        let (ns, nm) = (slave.face_count(), master.face_count());
        let [rs, rm] = face_each_other(&mut slave, &mut master, 2.0, false, false).unwrap();
        assert_eq!((rs.flipped, rm.flipped), (0, nm), "{ns} slave faces");
        let c = assemble_coupling(
            &Interface::new(slave, master).unwrap(),
            &CouplingOptions::default(),
        )
        .unwrap();
        assert!(c.warnings.is_empty(), "{:?}", c.warnings);
        assert!(
            (c.stats.area - measure).abs() < 1e-12 * measure,
            "{}",
            c.stats.area
        );
    }
}

/// The pairs the scale tests couple: 2D lines, and 3D triangles and quads.
fn pairs() -> Vec<(&'static str, MeshPair)> {
    vec![
        (
            "lines",
            MeshPair {
                slave: line_mesh(5, false, 1).unwrap(),
                master: line_mesh(7, true, 100).unwrap(),
            },
        ),
        (
            "triangles",
            MeshPair {
                slave: square_triangles(3, Diagonal::Main, 0.0, false, 1).unwrap(),
                master: square_triangles(4, Diagonal::Anti, 0.0, true, 100).unwrap(),
            },
        ),
        (
            "quads",
            MeshPair {
                slave: square_quads(3, 0.0, false, 1).unwrap(),
                master: square_triangles(4, Diagonal::Anti, 0.0, true, 100).unwrap(),
            },
        ),
        (
            "triangular prism",
            MeshPair {
                slave: prism_surface(3, 0.0, true, false, 1),
                master: prism_surface(3, 0.0, false, true, 100),
            },
        ),
    ]
}

/// Regression: a valid interface scaled by 1e-100 or 1e100 was called degenerate or inverted
/// (products of the coordinates' squares, 1e-400 or 1e400, under- or overflowed). At every
/// scale `s` from 1e-100 to 1e100, D and M are `s` (2D) or `s^2` (3D) times those at scale 1,
/// to 1e-12 relative, with standard and dual multipliers, segment- and element-based, from
/// the same candidate pairs of the search (whose `f32` boxes held absolute coordinates: at
/// 1e100 they were infinite, at 1e-100 zero, and every face of a hit leaf was a candidate).
#[test]
fn scaling_by_1e100_either_way_scales_d_and_m() {
    let options = [
        CouplingOptions::default(),
        CouplingOptions::default().dual(),
        CouplingOptions::default().element_based(None).unwrap(),
    ];
    for (name, pair) in pairs() {
        let planar = name == "lines";
        for options in &options {
            let unit = assemble_coupling(&pair.interface().unwrap(), options).unwrap();
            let d0 = by_tags(&unit.d, &unit.slave_nodes, &unit.slave_nodes);
            let m0 = by_tags(&unit.m, &unit.slave_nodes, &unit.master_nodes);
            for s in [1e-135, 1e-100, 1e-50, 1e-20, 1e20, 1e50, 1e100, 1e145] {
                let moved = pair.transformed(|x| x * s).unwrap();
                let interface = moved
                    .interface()
                    .unwrap_or_else(|e| panic!("{name} at scale {s:e}: {e}"));
                let c = assemble_coupling(&interface, options)
                    .unwrap_or_else(|e| panic!("{name} at scale {s:e}: {e}"));
                let factor = if planar { s } else { s * s };
                let d1 = by_tags(&c.d, &c.slave_nodes, &c.slave_nodes);
                let m1 = by_tags(&c.m, &c.slave_nodes, &c.master_nodes);
                let dev_d = compare_mapped(&d0, &d1, |t| t, |t| t, factor);
                let dev_m = compare_mapped(&m0, &m1, |t| t, |t| t, factor);
                assert!(
                    dev_d <= 1e-12 && dev_m <= 1e-12,
                    "{name}, {}, scale {s:e}: D deviates by {dev_d:e}, M by {dev_m:e}",
                    c.formulation
                );
                // The same work too: the search's candidate pairs do not depend on the scale.
                assert_eq!(
                    (c.stats.candidates, c.stats.pairs),
                    (unit.stats.candidates, unit.stats.pairs),
                    "{name} at scale {s:e}"
                );
            }
        }
    }
}

/// Coordinates whose products overflow (1e200: areas of 1e400) or underflow (1e-200) are
/// refused with a typed error that names the range, not coupled into infinite or zero
/// operators, nor called degenerate.
#[test]
fn scales_beyond_double_precision_are_a_typed_error_naming_the_range() {
    for (name, pair) in pairs() {
        for s in [1e-200, 1e200, 1e-300, 1e300] {
            let moved = pair.transformed(|x| x * s).unwrap();
            let err = moved.interface().unwrap_err();
            let limit = if s > 1.0 {
                RangeLimit::Overflow
            } else {
                RangeLimit::Underflow
            };
            assert!(
                matches!(err, MortarError::CoordinateRange { limit: l, .. } if l == limit),
                "{name} at scale {s:e}: {err:?}"
            );
            let text = err.to_string();
            assert!(
                text.contains("e200")
                    || text.contains("e-200")
                    || text.contains("e300")
                    || text.contains("e-300"),
                "{text}"
            );
        }
    }
}

/// Regression: the orientation step of `mortar couple` (surfaces made consistent, then turned
/// to face each other) measured the faces' normals by their squared length, a product of four
/// lengths: at 1e-100 every normal was zero and nothing was turned. A master given the same
/// way round as the slave is turned to face it at every scale, and the coupling is the same.
#[test]
fn surfaces_are_turned_to_face_each_other_at_any_scale() {
    for s in [1e-100, 1.0, 1e100] {
        let mut slave = square_triangles(3, Diagonal::Main, 0.0, false, 1).unwrap();
        let mut master = square_quads(4, 0.0, false, 100).unwrap();
        slave.transform(|x| x * s).unwrap();
        master.transform(|x| x * s).unwrap();
        let [rs, rm] = face_each_other(&mut slave, &mut master, 2.0, false, false).unwrap();
        assert_eq!((rs.flipped, rm.flipped), (0, 16), "scale {s:e}");
        let c = assemble_coupling(
            &Interface::new(slave, master).unwrap(),
            &CouplingOptions::default(),
        )
        .unwrap();
        assert!(
            (c.stats.area / (s * s) - 1.0).abs() < 1e-12,
            "scale {s:e}: {}",
            c.stats.area
        );
    }
}
