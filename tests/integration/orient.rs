//! Orientation of surfaces before coupling (`mortar::core::mesh::orient`) and the search
//! radius across an open gap, through the library.
//!
//! Reference values are closed forms: the unit square has area 1, and what D misses of it is
//! what the warning reports uncovered.

use mortar::core::mesh::orient::{face_each_other, orient_consistently};
use mortar::core::SearchRadius;
use mortar::elements::TRI3;
use mortar::generate::{square_triangles, Diagonal};
use mortar::{
    assemble_coupling, CouplingOptions, CouplingWarning, Interface, MortarError, SurfaceMesh,
    Tolerances,
};
use nalgebra::Vector3;

/// Every third face of a consistently oriented square reversed: making it consistent flips
/// exactly those back (face 0 is kept), in one piece.
#[test]
fn a_surface_with_reversed_faces_is_made_consistent() {
    let mut mesh = square_triangles(4, Diagonal::Main, 0.0, false, 1).unwrap();
    let reversed: Vec<usize> = (1..mesh.face_count()).step_by(3).collect();
    for &f in &reversed {
        mesh.reverse_face(f).unwrap();
    }
    let (pieces, flips) = orient_consistently(&mut mesh, None).unwrap();
    assert!(pieces.iter().all(|&p| p == 0), "one piece");
    let flipped: Vec<usize> = (0..flips.len()).filter(|&f| flips[f]).collect();
    assert_eq!(flipped, reversed);
    let fresh = square_triangles(4, Diagonal::Main, 0.0, false, 1).unwrap();
    for f in 0..mesh.face_count() {
        assert_eq!(mesh.face(f).nodes, fresh.face(f).nodes, "face {f}");
    }
}

/// Both squares given looking the wrong way (slave down, away from the master above it; master
/// up, away from the slave): each is turned to face the other, and the pair then couples.
#[test]
fn surfaces_across_a_gap_are_turned_to_face_each_other() {
    let mut slave = square_triangles(3, Diagonal::Main, 0.0, true, 1).unwrap();
    let mut master = square_triangles(5, Diagonal::Anti, 0.05, false, 1000).unwrap();
    let [rs, rm] = face_each_other(&mut slave, &mut master, 2.0, false, false).unwrap();
    assert_eq!((rs.components, rs.flipped), (1, slave.face_count()));
    assert_eq!((rm.components, rm.flipped), (1, master.face_count()));
    let interface = Interface::new(slave, master).unwrap();
    let c = assemble_coupling(&interface, &CouplingOptions::default()).unwrap();
    let area: f64 = c.d.data().iter().sum();
    assert!((area - 1.0).abs() < 1e-13, "{area}");
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
}

/// Three triangles on one edge (a T junction) and a Moebius strip cannot be oriented: a typed
/// error naming a face, not a guess.
#[test]
fn non_manifold_and_non_orientable_surfaces_are_refused() {
    let tri = &TRI3;
    let mut t = SurfaceMesh::new();
    for (tag, x) in [
        (1, [0.0, 0.0, 0.0]),
        (2, [1.0, 0.0, 0.0]),
        (3, [0.5, 1.0, 0.0]),
        (4, [0.5, -1.0, 0.0]),
        (5, [0.5, 0.0, 1.0]),
    ] {
        t.add_node(tag, x).unwrap();
    }
    for nodes in [[1, 2, 3], [2, 1, 4], [1, 2, 5]] {
        t.add_face(tri, &nodes).unwrap();
    }
    match orient_consistently(&mut t, None) {
        Err(MortarError::Topology { reason, .. }) => {
            assert!(reason.contains("shared by 3 faces"), "{reason}")
        }
        other => panic!("expected a topology error, got {other:?}"),
    }

    // A Moebius strip of 8 quads split into triangles: the band's ends glued with a half turn.
    let mut strip = SurfaceMesh::new();
    let k = 8;
    for i in 0..k {
        let a = std::f64::consts::TAU * i as f64 / k as f64;
        for (j, w) in [-0.3, 0.3].into_iter().enumerate() {
            let half = a / 2.0;
            let r = 1.0 + w * half.cos();
            let x = Vector3::new(r * a.cos(), r * a.sin(), w * half.sin());
            strip.add_node((2 * i + j) as u64 + 1, x.into()).unwrap();
        }
    }
    for i in 0..k {
        let (a0, a1) = (2 * i as u64 + 1, 2 * i as u64 + 2);
        // The last cell meets the first with its sides swapped (the half turn).
        let (b0, b1) = if i + 1 == k {
            (2, 1)
        } else {
            (2 * (i as u64 + 1) + 1, 2 * (i as u64 + 1) + 2)
        };
        strip.add_face(tri, &[a0, b0, b1]).unwrap();
        strip.add_face(tri, &[a0, b1, a1]).unwrap();
    }
    match orient_consistently(&mut strip, None) {
        Err(MortarError::Topology { reason, .. }) => {
            assert!(reason.contains("orient"), "{reason}")
        }
        other => panic!("expected a topology error, got {other:?}"),
    }
}

/// A master plane tilted away from the slave (`z = 0.05 + 0.1 x`): by default the search
/// radius (one face diameter, 0.35) reaches it everywhere; a radius of 0.08 reaches only the
/// master faces that start below `x = 0.3` (the boxes of linear triangles are not inflated),
/// so only part of the slave, and the rest of the slave is reported as uncovered (a warning,
/// or an error when full coverage is required), never dropped silently.
#[test]
fn the_search_radius_reaches_across_the_gap_and_what_it_misses_is_reported() {
    let slave = square_triangles(4, Diagonal::Main, 0.0, false, 1).unwrap();
    let mut master = square_triangles(6, Diagonal::Anti, 0.0, true, 1000).unwrap();
    master
        .transform(|x| Vector3::new(x.x, x.y, 0.05 + 0.1 * x.x))
        .unwrap();
    let couple = |radius: SearchRadius, strict: bool| {
        let tol = Tolerances {
            search_radius: radius,
            ..Tolerances::default()
        };
        let interface = Interface::with_tolerances(slave.clone(), master.clone(), tol).unwrap();
        assemble_coupling(
            &interface,
            &CouplingOptions::default().require_full_coverage(strict),
        )
    };
    let full = couple(Tolerances::default().search_radius, true).unwrap();
    assert!(full.warnings.is_empty(), "{:?}", full.warnings);
    let area: f64 = full.d.data().iter().sum();
    assert!((area - 1.0).abs() < 1e-12, "{area}");

    let part = couple(SearchRadius::Distance(0.08), false).unwrap();
    let area: f64 = part.d.data().iter().sum();
    assert!(area > 0.05 && area < 0.95, "{area}");
    match part.warnings.as_slice() {
        [w @ CouplingWarning::UncoveredSlaveArea {
            area: missing,
            faces_without_partner,
            ..
        }] => {
            assert!(*faces_without_partner > 0, "{w}");
            assert!((missing + area - 1.0).abs() < 1e-12, "{w}");
            assert_eq!(w.name(), "uncovered slave area");
        }
        other => panic!("expected one uncovered-area warning, got {other:?}"),
    }
    assert_eq!(
        part.stats.faces_without_partner + part.stats.faces_partly_covered,
        match &part.warnings[0] {
            CouplingWarning::UncoveredSlaveArea {
                faces_without_partner,
                faces_partly_covered,
                ..
            } => faces_without_partner + faces_partly_covered,
            _ => unreachable!(),
        }
    );

    match couple(SearchRadius::Distance(0.02), true) {
        Err(MortarError::IncompleteCoverage(w)) => {
            assert_eq!(w.name(), "uncovered slave area")
        }
        other => panic!("expected IncompleteCoverage, got {other:?}"),
    }
}

/// A face that lists a node twice is degenerate, and orienting says so first (it was reported
/// as a fin: three "faces" on one edge), on either side, naming the face and the node.
#[test]
fn a_face_with_a_repeated_node_is_degenerate_not_a_fin() {
    let mut bad = square_triangles(2, Diagonal::Main, 0.0, false, 1).unwrap();
    bad.add_face_with_tag(99, &TRI3, &[1, 2, 2]).unwrap();
    match orient_consistently(&mut bad.clone(), None) {
        Err(MortarError::DegenerateFace { face, reason }) => {
            assert_eq!(face.tag, 99);
            assert!(reason.contains("node 2 appears twice"), "{reason}");
        }
        other => panic!("{other:?}"),
    }
    let mut good = square_triangles(3, Diagonal::Anti, 0.0, true, 1).unwrap();
    let e = face_each_other(&mut good, &mut bad, 1.0, false, false).unwrap_err();
    assert!(matches!(e, MortarError::DegenerateFace { .. }), "{e:?}");
}
