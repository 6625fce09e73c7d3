//! No false diagnosis (issue 14, item 8): coarse closed surfaces whose neighbouring faces turn
//! by 120 degrees are valid.

use mortar::core::element::ElementRef;
use mortar::elements::{LINE2, QUAD4, TRI3};
use mortar::{assemble_coupling, CouplingOptions, Interface, SurfaceMesh};
use nalgebra::Vector3;

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
            if phase == 0.0 {
                let c = assemble_coupling(&interface, &CouplingOptions::default()).unwrap();
                // Three unit-high sides of width sqrt(3), two caps of area 3 sqrt(3) / 4.
                let area = 3.0 * 3f64.sqrt() * 1.5;
                assert!(
                    (c.stats.area - area).abs() < 1e-12 * area,
                    "{}",
                    c.stats.area
                );
            }
        }
    }
}
