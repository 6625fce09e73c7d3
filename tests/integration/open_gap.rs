//! An open gap is coupled whatever the element size (the default search,
//! `SearchRadius::Nearest`): a pellet's surface (radius 4.1 mm) inside its cladding (inner
//! radius 4.18 mm, an 80 um gap), as lines in 2D and as cylinders in 3D, at faces from
//! several times the gap down to a fraction of it. Before, the search reached one slave face
//! diameter: at faces of 50 um, 67 % of the slave was left uncovered with exit 0.
//!
//! Closed forms: the coupled length (area) is the slave polygon's, `sum(D) = n |chord|` (times
//! the height in 3D); the normal gap at a slave node is the distance along the radial normal
//! from the node, at radius `a`, to the master polygon, between `b cos(pi / m) - a` (a master
//! edge's midpoint, the polygon's inner radius) and `b - a` (a master node).

use std::f64::consts::PI;

use mortar::elements::LINE2;
use mortar::generate::cylinder_surface;
use mortar::io::{msh41_bytes, GapSummary, MshFormat};
use mortar::{assemble_coupling, CouplingOptions, CouplingWarning, Interface, SurfaceMesh};
use serde_json::Value;

use crate::common::{mortar, TempDir};

const A: f64 = 4.1e-3;
const B: f64 = 4.18e-3;

/// A circle of radius `r` as `n` two-node lines, counter-clockwise (normals outward) or
/// clockwise (`inward`).
fn circle(r: f64, n: usize, first_tag: u64, inward: bool) -> SurfaceMesh {
    let mut m = SurfaceMesh::new();
    for i in 0..n {
        let t = 2.0 * PI * i as f64 / n as f64;
        m.add_node(first_tag + i as u64, [r * t.cos(), r * t.sin(), 0.0])
            .unwrap();
    }
    for i in 0..n as u64 {
        let (p, q) = (first_tag + i, first_tag + (i + 1) % n as u64);
        let nodes = if inward { [q, p] } else { [p, q] };
        m.add_face(&LINE2, &nodes).unwrap();
    }
    m
}

/// Asserts full coverage, the coupled measure and the gap's closed-form bounds.
fn check(interface: &Interface, measure: f64, m: usize, what: &str) -> GapSummary {
    let c = assemble_coupling(interface, &CouplingOptions::default().dual()).unwrap();
    assert!(c.warnings.is_empty(), "{what}: {:?}", c.warnings);
    assert_eq!(c.stats.faces_without_partner, 0, "{what}");
    assert_eq!(c.stats.faces_partly_covered, 0, "{what}");
    assert!(
        (c.stats.area - measure).abs() <= 1e-12 * measure,
        "{what}: sum(D) {} against {measure}",
        c.stats.area
    );
    let g = GapSummary::of(interface, &c).unwrap();
    let (lo, hi) = (B * (PI / m as f64).cos() - A, B - A);
    assert!(
        g.min >= lo * (1.0 - 1e-9) && g.max <= hi * (1.0 + 1e-9),
        "{what}: gap {g:?} outside [{lo:e}, {hi:e}]"
    );
    assert_eq!(g.nodes, c.slave_nodes.len(), "{what}: every node covered");
    g
}

#[test]
fn a_pellet_gap_is_coupled_at_every_face_size_2d() {
    // Slave faces of 0.40 mm, 50 um and 20 um: 5, 0.6 and 0.25 times the gap.
    for n in [64usize, 515, 1288] {
        let m = n * 3 / 4;
        let interface = Interface::new(circle(A, n, 1, false), circle(B, m, 10_000, true)).unwrap();
        let chord = 2.0 * A * (PI / n as f64).sin();
        let g = check(&interface, n as f64 * chord, m, &format!("n = {n}"));
        assert!(g.mean > 0.0);
    }
}

#[test]
fn a_pellet_gap_is_coupled_at_every_face_size_3d() {
    // Radii and gap scaled by 100 against a unit height: the same ratios.
    let (a, b) = (100.0 * A, 100.0 * B);
    for (around, along) in [(48usize, 4usize), (400, 10)] {
        let m = around * 3 / 4;
        let slave = cylinder_surface(a, around, along, true, false, 1).unwrap();
        let master = cylinder_surface(b, m, along + 1, false, true, 100_000).unwrap();
        let interface = Interface::new(slave, master).unwrap();
        let c = assemble_coupling(&interface, &CouplingOptions::default().dual()).unwrap();
        assert!(c.warnings.is_empty(), "{around}: {:?}", c.warnings);
        let chord = 2.0 * a * (PI / around as f64).sin();
        let area = around as f64 * chord;
        assert!(
            (c.stats.area - area).abs() <= 1e-12 * area,
            "{around}: {} against {area}",
            c.stats.area
        );
        let g = GapSummary::of(&interface, &c).unwrap();
        let (lo, hi) = (b * (PI / m as f64).cos() - a, b - a);
        assert!(
            g.min >= lo * (1.0 - 1e-9) && g.max <= hi * (1.0 + 1e-9),
            "{around}: {g:?} outside [{lo:e}, {hi:e}]"
        );
    }
}

/// Only the nearest master layer is reached: a second cladding circle 80 um beyond the first
/// (both in the master surface) is not coupled, where a search radius reaching both couples
/// both and says so (`OverlappingMasterFaces`).
#[test]
fn the_search_stops_at_the_nearest_master_layer() {
    let n = 515;
    let mut master = circle(B, 400, 10_000, true);
    let outer = circle(2.0 * B - A, 420, 20_000, true);
    for (tag, x) in outer.node_tags().iter().zip(outer.coords()) {
        master.add_node(*tag, [x.x, x.y, x.z]).unwrap();
    }
    for f in 0..outer.face_count() {
        let nodes: Vec<u64> = outer
            .face(f)
            .nodes
            .iter()
            .map(|&k| outer.node_tags()[k as usize])
            .collect();
        master.add_face(&LINE2, &nodes).unwrap();
    }
    let interface = Interface::new(circle(A, n, 1, false), master.clone()).unwrap();
    let chord = 2.0 * A * (PI / n as f64).sin();
    check(&interface, n as f64 * chord, 400, "two layers");
    let far = mortar::Tolerances {
        search_radius: mortar::SearchRadius::Distance(3.0 * (B - A)),
        ..Default::default()
    };
    let both = Interface::with_tolerances(circle(A, n, 1, false), master, far).unwrap();
    let c = assemble_coupling(&both, &CouplingOptions::default().dual()).unwrap();
    assert!(
        c.warnings
            .iter()
            .any(|w| matches!(w, CouplingWarning::OverlappingMasterFaces { .. })),
        "{:?}",
        c.warnings
    );
}

/// `mortar couple` on Gmsh files of the 2D gap at faces of 50 um: fully coupled, the gap
/// statistics in summary.json and in the printed summary, the widened search reported; with
/// a search radius below the gap, the uncovered-area warning says how far the search looked
/// and which option widens it.
#[test]
fn couple_reports_the_gap_and_how_to_widen_the_search() {
    let dir = TempDir::new("open-gap");
    let slave = dir.file(
        "pellet.msh",
        msh41_bytes(
            &[(&circle(A, 515, 1, false), "pellet_surface")],
            MshFormat::Ascii,
        )
        .unwrap(),
    );
    let master = dir.file(
        "cladding.msh",
        msh41_bytes(
            &[(&circle(B, 386, 1, true), "cladding_inner")],
            MshFormat::Ascii,
        )
        .unwrap(),
    );
    let out = dir.join("out");
    let args = [
        "couple",
        "--slave",
        &format!("{slave}#pellet_surface"),
        "--master",
        &format!("{master}#cladding_inner"),
        "-o",
        out.to_str().unwrap(),
    ];
    let o = mortar(&args);
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(!stderr.contains("warning"), "{stderr}");
    assert!(
        stdout.contains("normal gap at 515 covered slave nodes"),
        "{stdout}"
    );
    assert!(
        stdout.contains("widened to the nearest master surface"),
        "{stdout}"
    );
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let gap = &summary["gap"];
    assert_eq!(gap["nodes"], 515);
    let mean = gap["mean"].as_f64().unwrap();
    assert!((mean - (B - A)).abs() < 0.01 * (B - A), "{gap}");
    assert_eq!(summary["uncovered_area"], 0.0);
    assert!(summary["widened_search_faces"].as_u64().unwrap() > 0);

    let mut narrow = args.to_vec();
    narrow.extend(["--search-radius", "3e-5"]);
    let o = mortar(&narrow);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("uncovered slave area")
            && stderr.contains("the search looked 3.000e-5 along the slave normals")
            && stderr.contains("set --search-radius above"),
        "{stderr}"
    );
}
