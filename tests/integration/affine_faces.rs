//! Affinity is a property of the face, not of its type: a straight Line3
//! with its middle node at the centre maps `[-1, 1]` affinely, so the 2D coupling takes the
//! affine path on it (the master point in one exact step instead of a bracketed root) without
//! the element declaring `is_affine`, and gives the bits of an element that does.

use mortar::core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
use mortar::core::integration::ElementBased;
use mortar::core::interface::FaceGeometry;
use mortar::{assemble_coupling, CouplingOptions, Interface, Side, SurfaceMesh};
use nalgebra::Vector2;

/// A three-node line (Gmsh order: ends, then middle) that does not say it is affine.
#[derive(Debug)]
struct Line3;

/// The same line, declared affine (what a straight Line3 needed before).
#[derive(Debug)]
struct DeclaredAffineLine3;

fn line3_values(xi: &Vector2<f64>, out: &mut [f64]) {
    let x = xi.x;
    out[..3].copy_from_slice(&[0.5 * x * (x - 1.0), 0.5 * x * (x + 1.0), 1.0 - x * x]);
}

fn line3_gradients(xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
    let x = xi.x;
    out[..3].copy_from_slice(&[[x - 0.5, 0.0], [x + 0.5, 0.0], [-2.0 * x, 0.0]]);
}

impl ReferenceElement for Line3 {
    fn name(&self) -> &'static str {
        "Line3"
    }
    fn domain(&self) -> ReferenceDomain {
        ReferenceDomain::Line
    }
    fn node_count(&self) -> usize {
        3
    }
    fn corner_count(&self) -> usize {
        2
    }
    fn shape_degree(&self) -> u32 {
        2
    }
    fn node_reference_coords(&self) -> &'static [[f64; 2]] {
        &[[-1.0, 0.0], [1.0, 0.0], [0.0, 0.0]]
    }
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
        line3_values(xi, out)
    }
    fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        line3_gradients(xi, out)
    }
}

/// Everything as [`Line3`], but `is_affine`.
impl ReferenceElement for DeclaredAffineLine3 {
    fn name(&self) -> &'static str {
        "Line3 (declared affine)"
    }
    fn domain(&self) -> ReferenceDomain {
        LINE3.domain()
    }
    fn node_count(&self) -> usize {
        LINE3.node_count()
    }
    fn corner_count(&self) -> usize {
        LINE3.corner_count()
    }
    fn shape_degree(&self) -> u32 {
        LINE3.shape_degree()
    }
    fn node_reference_coords(&self) -> &'static [[f64; 2]] {
        LINE3.node_reference_coords()
    }
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
        line3_values(xi, out)
    }
    fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        line3_gradients(xi, out)
    }
}

impl SurfaceElement for Line3 {}
impl SurfaceElement for DeclaredAffineLine3 {
    fn is_affine(&self) -> bool {
        true
    }
}

static LINE3: Line3 = Line3;
static DECLARED: DeclaredAffineLine3 = DeclaredAffineLine3;

/// The point at `s` along the line through the origin at an angle (irrational coordinates, so
/// that round-off shows).
fn along(s: f64) -> [f64; 3] {
    let (sin, cos) = 0.7_f64.sin_cos();
    [s * cos, s * sin, 0.0]
}

/// A slave of `n` Line3 faces from `s = 1` to `s = 0` (normal to the left of the line's
/// direction, towards the master), middle nodes at the centres, of type `element`.
fn slave(n: usize, element: mortar::core::element::ElementRef) -> SurfaceMesh {
    let mut mesh = SurfaceMesh::new();
    for i in 0..=2 * n {
        mesh.add_node(i as u64 + 1, along(1.0 - i as f64 / (2 * n) as f64))
            .unwrap();
    }
    for f in 0..n as u64 {
        mesh.add_face(element, &[2 * f + 1, 2 * f + 3, 2 * f + 2])
            .unwrap();
    }
    mesh
}

/// A master of `n` faces from `s = 0` to `s = 1` (facing the slave), of type `element`, the
/// middle nodes at `centre + offset` (a straight face with its middle node at the centre for
/// `offset = [0, 0, 0]`).
fn master(n: usize, element: mortar::core::element::ElementRef, offset: [f64; 3]) -> SurfaceMesh {
    let mut mesh = SurfaceMesh::new();
    for i in 0..=n {
        mesh.add_node(100 + i as u64, along(i as f64 / n as f64))
            .unwrap();
    }
    for f in 0..n {
        let [a, b] = [along(f as f64 / n as f64), along((f + 1) as f64 / n as f64)];
        let mid = [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]) + offset[k]);
        mesh.add_node(200 + f as u64, mid).unwrap();
        let f = f as u64;
        mesh.add_face(element, &[100 + f, 101 + f, 200 + f])
            .unwrap();
    }
    mesh
}

fn bits(c: &mortar::Coupling) -> Vec<u64> {
    c.d.data()
        .iter()
        .chain(c.m.data())
        .map(|x| x.to_bits())
        .collect()
}

#[test]
fn a_straight_centred_line3_face_is_affine_and_a_bent_one_is_not() {
    let face = |offset| FaceGeometry::gather(&master(3, &LINE3, offset), Side::Master, 1, None);
    assert!(face([0.0; 3]).is_affine());
    // The middle node off the centre along the line: straight, but not an affine map.
    assert!(!face(along(0.05)).is_affine());
    // The middle node off the line: curved.
    let (sin, cos) = 0.7_f64.sin_cos();
    assert!(!face([-0.02 * sin, 0.02 * cos, 0.0]).is_affine());
}

/// Segment- and element-based, standard and dual: the undeclared Line3 gives the bits of the
/// declared one (before, its master points were found by a bracketed root and differed in the
/// last bits).
#[test]
fn a_straight_line3_master_takes_the_affine_path_undeclared() {
    for options in [
        CouplingOptions::default(),
        CouplingOptions::default().dual(),
        CouplingOptions {
            integration: std::sync::Arc::new(ElementBased::default()),
            ..CouplingOptions::default()
        },
    ] {
        let couple = |element| {
            let interface = Interface::new(slave(4, &LINE3), master(3, element, [0.0; 3])).unwrap();
            assemble_coupling(&interface, &options).unwrap()
        };
        let (undeclared, declared) = (couple(&LINE3), couple(&DECLARED));
        assert!(
            (declared.stats.area - 1.0).abs() < 1e-14,
            "{}",
            declared.stats.area
        );
        assert_eq!(bits(&undeclared), bits(&declared), "{}", options.describe());
    }
}
