//! Lagrange elements from their nodes: with the nodes of a shipped element they are that
//! element (values and gradients at sample points), and bad node sets get typed errors.

use mortar_core::element::{ReferenceDomain, ReferenceElement};
use mortar_elements::volume::{HEX27, TET10, TRI6 as TRI6_CELL};
use mortar_elements::{LagrangeCell, LagrangeError, LagrangeFace, LINE3, QUAD9, TRI6};
use mortar_fem::element::{VolumeDomain, VolumeElement};
use nalgebra::{Vector2, Vector3};

fn leak2(e: &dyn ReferenceElement) -> &'static [[f64; 2]] {
    e.node_reference_coords()
}

fn same_face(a: &dyn ReferenceElement, b: &dyn ReferenceElement) {
    let k = a.node_count();
    assert_eq!(k, b.node_count());
    assert_eq!(a.shape_degree(), b.shape_degree(), "{}", a.name());
    for p in [[0.1, 0.2], [0.3, 0.05], [-0.4, 0.6], [0.7, -0.9]] {
        let xi = Vector2::new(p[0], p[1]);
        if !a.domain().contains(&xi, 0.0) {
            continue;
        }
        let (mut na, mut nb) = (vec![0.0; k], vec![0.0; k]);
        let (mut ga, mut gb) = (vec![[0.0; 2]; k], vec![[0.0; 2]; k]);
        a.shape_values_into(&xi, &mut na);
        b.shape_values_into(&xi, &mut nb);
        a.shape_gradients_into(&xi, &mut ga);
        b.shape_gradients_into(&xi, &mut gb);
        for i in 0..k {
            assert!((na[i] - nb[i]).abs() < 1e-13, "{} N_{i}", b.name());
            for d in 0..2 {
                assert!((ga[i][d] - gb[i][d]).abs() < 1e-12, "{} dN_{i}", b.name());
            }
        }
    }
}

fn same_cell(a: &dyn VolumeElement, b: &dyn VolumeElement) {
    let k = a.node_count();
    assert_eq!(a.shape_degree(), b.shape_degree(), "{}", a.name());
    for p in [[0.1, 0.2, 0.3], [0.3, 0.05, 0.1], [-0.4, 0.6, -0.2]] {
        let xi = Vector3::new(p[0], p[1], if a.dim() == 2 { 0.0 } else { p[2] });
        if !a.domain().contains(&xi, 0.0) {
            continue;
        }
        let (mut na, mut nb) = (vec![0.0; k], vec![0.0; k]);
        let (mut ga, mut gb) = (vec![[0.0; 3]; k], vec![[0.0; 3]; k]);
        a.shape_values_into(&xi, &mut na);
        b.shape_values_into(&xi, &mut nb);
        a.shape_gradients_into(&xi, &mut ga);
        b.shape_gradients_into(&xi, &mut gb);
        for i in 0..k {
            assert!((na[i] - nb[i]).abs() < 1e-12, "{} N_{i}", b.name());
            for d in 0..3 {
                assert!((ga[i][d] - gb[i][d]).abs() < 1e-11, "{} dN_{i}", b.name());
            }
        }
    }
}

#[test]
fn lagrange_elements_from_shipped_nodes_are_the_shipped_elements() {
    let line = LagrangeFace::new("L", ReferenceDomain::Line, 2, leak2(&LINE3), None).unwrap();
    same_face(&line, &LINE3);
    let tri = LagrangeFace::new("T", ReferenceDomain::Triangle, 3, leak2(&TRI6), None).unwrap();
    same_face(&tri, &TRI6);
    let quad =
        LagrangeFace::new("Q", ReferenceDomain::Quadrilateral, 4, leak2(&QUAD9), None).unwrap();
    same_face(&quad, &QUAD9);
    for shipped in [&TRI6_CELL as &dyn VolumeElement, &TET10, &HEX27] {
        let cell = LagrangeCell::new(
            "C",
            shipped.domain(),
            shipped.node_reference_coords(),
            shipped.faces(),
            shipped.face_element(0),
            None,
        )
        .unwrap();
        same_cell(&cell, shipped);
    }
}

#[test]
fn bad_node_sets_are_refused() {
    // Eight nodes fit no tensor space of a quad (the serendipity Quad8 is not a Lagrange
    // element of this kind).
    static EIGHT: [[f64; 2]; 8] = [[0.0; 2]; 8];
    assert!(matches!(
        LagrangeFace::new("Q8", ReferenceDomain::Quadrilateral, 4, &EIGHT, None),
        Err(LagrangeError::NodeCount { count: 8, .. })
    ));
    // Three nodes of a line in one point do not determine a quadratic.
    static SAME: [[f64; 2]; 3] = [[-1.0, 0.0], [1.0, 0.0], [1.0, 0.0]];
    assert!(matches!(
        LagrangeFace::new("L", ReferenceDomain::Line, 2, &SAME, None),
        Err(LagrangeError::NotUnisolvent { degree: 2 })
    ));
    static TET: [[f64; 3]; 5] = [[0.0; 3]; 5];
    assert!(LagrangeCell::new("T", VolumeDomain::Tetrahedron, &TET, &[], &LINE3, None).is_err());
}
