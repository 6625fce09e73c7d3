//! Geometric maps of the surface elements: interpolation of the nodes, measure, normal
//! convention, affinity, rigid-motion invariance and inverse maps.

use std::f64::consts::TAU;

use mortar_core::element::{ReferenceDomain, SurfaceElement};
use mortar_core::geometry::{invert_line_map, invert_surface_map};
use mortar_core::quadrature::{Quadrature, QuadratureRule};
use mortar_elements::{
    Line2, Line3, Quad4, Quad8, Quad9, Tri3, Tri6, LINE2, LINE3, QUAD4, QUAD8, QUAD9, TRI3, TRI6,
};
use nalgebra::{Rotation3, Vector2, Vector3};
use proptest::prelude::*;

/// A random convex face in the plane z = 0 with `k` corners counter-clockwise (k = 2: a
/// segment from left to right), at angles with gaps below pi on a random ellipse.
fn planar_face(k: usize) -> impl Strategy<Value = Vec<Vector3<f64>>> {
    (
        prop::collection::vec(1.0..1.9f64, k),
        0.0..TAU,
        (0.1..3.0f64, 0.1..3.0f64),
        prop::array::uniform2(-5.0..5.0f64),
    )
        .prop_map(move |(w, start, (rx, ry), c)| {
            if k == 2 {
                return vec![
                    Vector3::new(c[0] - rx, c[1] - ry * 0.1, 0.0),
                    Vector3::new(c[0] + rx, c[1] + ry * 0.1, 0.0),
                ];
            }
            let total: f64 = w.iter().sum();
            let mut a = start;
            w.iter()
                .map(|wi| {
                    let p = Vector3::new(c[0] + rx * a.cos(), c[1] + ry * a.sin(), 0.0);
                    a += wi / total * TAU;
                    p
                })
                .collect()
        })
}

/// The exact measure of a planar face (shoelace) or segment.
fn exact_measure(x: &[Vector3<f64>]) -> f64 {
    if x.len() == 2 {
        return (x[1] - x[0]).norm();
    }
    let n = x.len();
    0.5 * (0..n)
        .map(|i| x[i].x * x[(i + 1) % n].y - x[(i + 1) % n].x * x[i].y)
        .sum::<f64>()
}

fn point_in(domain: ReferenceDomain, u: f64, v: f64) -> Vector2<f64> {
    match domain {
        ReferenceDomain::Line => Vector2::new(2.0 * u - 1.0, 0.0),
        ReferenceDomain::Triangle if u + v > 1.0 => Vector2::new(1.0 - u, 1.0 - v),
        ReferenceDomain::Triangle => Vector2::new(u, v),
        ReferenceDomain::Quadrilateral => Vector2::new(2.0 * u - 1.0, 2.0 * v - 1.0),
    }
}

/// The map interpolates the nodes; `int det J` over the reference domain is the face's
/// measure; the scaled normal's length is `det J` and the unit normal has length one and
/// points to `+z` (faces counter-clockwise in the xy-plane) or along `(t_y, -t_x)` (lines).
fn check_map_and_measure<E: SurfaceElement + ?Sized>(e: &E, x: &[Vector3<f64>], xi: &Vector2<f64>) {
    for (j, r) in e.node_reference_coords().iter().enumerate() {
        let p = e.map(x, &Vector2::new(r[0], r[1]));
        assert!(
            (p - x[j]).norm() < 1e-13 * (1.0 + x[j].norm()),
            "{}: node {j}",
            e.name()
        );
    }
    let rule = QuadratureRule::for_domain(e.domain(), 4).unwrap();
    let measure: f64 = rule
        .points()
        .iter()
        .zip(rule.weights())
        .map(|(p, w)| w * e.jacobian_det(x, p))
        .sum();
    let want = exact_measure(&x[..e.corner_count()]);
    assert!(
        (measure - want).abs() < 1e-12 * want,
        "{}: measure {measure}, want {want}",
        e.name()
    );

    let n = e.scaled_normal(x, xi);
    assert!((n.norm() - e.jacobian_det(x, xi)).abs() < 1e-14 * n.norm());
    let u = e.unit_normal(x, xi);
    assert!((u.norm() - 1.0).abs() < 1e-14);
    if e.domain() == ReferenceDomain::Line {
        let [t, t2] = e.tangents(x, xi);
        assert_eq!(t2, Vector3::z());
        let want = Vector3::new(t.y, -t.x, 0.0).normalize();
        assert!((u - want).norm() < 1e-14, "{}: normal {u:?}", e.name());
    } else {
        assert!(
            (u - Vector3::z()).norm() < 1e-14,
            "{}: normal {u:?}",
            e.name()
        );
    }
}

/// `is_affine()` is honest: an affine element's Jacobian is the same everywhere.
fn check_affinity<E: SurfaceElement + ?Sized>(
    e: &E,
    x: &[Vector3<f64>],
    a: &Vector2<f64>,
    b: &Vector2<f64>,
) {
    if e.is_affine() {
        let (ta, tb) = (e.tangents(x, a), e.tangents(x, b));
        assert!(
            (ta[0] - tb[0]).norm() + (ta[1] - tb[1]).norm() < 1e-13 * (1.0 + ta[0].norm()),
            "{}",
            e.name()
        );
    }
}

/// A rigid motion leaves `det J` unchanged and rotates the normal.
fn check_rigid_motion<E: SurfaceElement + ?Sized>(
    e: &E,
    x: &[Vector3<f64>],
    xi: &Vector2<f64>,
    axis: Vector3<f64>,
    angle: f64,
) {
    // Lines live in the xy-plane: rotate them about z only.
    let axis = if e.domain() == ReferenceDomain::Line {
        Vector3::z()
    } else {
        axis
    };
    let r = Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle);
    let t = Vector3::new(
        3.0,
        -2.0,
        if e.domain() == ReferenceDomain::Line {
            0.0
        } else {
            1.0
        },
    );
    let y: Vec<Vector3<f64>> = x.iter().map(|p| r * p + t).collect();
    let (d0, d1) = (e.jacobian_det(x, xi), e.jacobian_det(&y, xi));
    assert!(
        (d0 - d1).abs() < 1e-12 * d0,
        "{}: det J {d0} -> {d1}",
        e.name()
    );
    let (n0, n1) = (e.unit_normal(x, xi), e.unit_normal(&y, xi));
    assert!((r * n0 - n1).norm() < 1e-12, "{}", e.name());
}

/// The inverse maps of `mortar_core::geometry` find `xi` back from `x(xi)`. Coordinates are
/// taken relative to the first node, as the segmenter takes them relative to the auxiliary
/// plane's origin; Newton stops at `1e-13` reference units.
fn check_inverse_map<E: SurfaceElement + ?Sized>(e: &E, x: &[Vector3<f64>], xi: &Vector2<f64>) {
    let p = e.map(x, xi);
    if e.domain() == ReferenceDomain::Line {
        let values: Vec<f64> = x.iter().map(|q| q.x - x[0].x).collect();
        let back = invert_line_map(e, e.is_affine(), &values, p.x - x[0].x, 1e-13, 30).unwrap();
        assert!(
            (back - xi.x).abs() < 1e-12,
            "{}: {back} for {}",
            e.name(),
            xi.x
        );
    } else {
        let planar: Vec<Vector2<f64>> = x.iter().map(|q| (q - x[0]).xy()).collect();
        let target = (p - x[0]).xy();
        let back = invert_surface_map(e, e.is_affine(), &planar, &target, 1e-13, 30).unwrap();
        assert!(
            (back - xi).norm() < 1e-11,
            "{}: {back:?} for {xi:?}",
            e.name()
        );
    }
}

fn check_surface_element<E: SurfaceElement + ?Sized>(
    e: &E,
    x: &[Vector3<f64>],
    (u, v): (f64, f64),
    axis: Vector3<f64>,
    angle: f64,
) {
    let xi = point_in(e.domain(), u, v);
    check_map_and_measure(e, x, &xi);
    check_affinity(e, x, &xi, &e.domain().centre());
    check_rigid_motion(e, x, &xi, axis, angle);
    check_inverse_map(e, x, &xi);
}

/// The nodes of a second-order face with straight edges and centred middle nodes on the
/// corners `corners` (each node where the linear element of the corners puts it).
fn second_order_nodes<E: SurfaceElement + ?Sized>(
    e: &E,
    corners: &[Vector3<f64>],
) -> Vec<Vector3<f64>> {
    let linear: &dyn SurfaceElement = match corners.len() {
        2 => &LINE2,
        3 => &TRI3,
        _ => &QUAD4,
    };
    e.node_reference_coords()
        .iter()
        .map(|r| linear.map(corners, &Vector2::new(r[0], r[1])))
        .collect()
}

/// Reversing a face's nodes keeps its geometry and turns its normal round.
fn check_reversal<E: SurfaceElement + ?Sized>(e: &E, x: &[Vector3<f64>]) {
    let mut order: Vec<u32> = (0..e.node_count() as u32).collect();
    assert!(e.reverse_nodes(&mut order), "{}", e.name());
    let y: Vec<Vector3<f64>> = order.iter().map(|&i| x[i as usize]).collect();
    // The corners are still the first nodes, and each node is where the reversed map puts it.
    let c = e.domain().centre();
    let (n0, n1) = (e.unit_normal(x, &c), e.unit_normal(&y, &c));
    assert!((n0 + n1).norm() < 1e-12, "{}: {n0:?} {n1:?}", e.name());
    let rule = QuadratureRule::for_domain(e.domain(), 6).unwrap();
    let area = |z: &[Vector3<f64>]| -> f64 {
        rule.points()
            .iter()
            .zip(rule.weights())
            .map(|(p, w)| w * e.jacobian_det(z, p))
            .sum()
    };
    assert!((area(x) - area(&y)).abs() < 1e-12 * area(x), "{}", e.name());
    for (j, r) in e.node_reference_coords().iter().enumerate() {
        let p = e.map(&y, &Vector2::new(r[0], r[1]));
        assert!((p - y[j]).norm() < 1e-12 * (1.0 + p.norm()), "{}", e.name());
    }
    // Reversing twice gives the original order.
    assert!(e.reverse_nodes(&mut order));
    assert_eq!(
        order,
        (0..e.node_count() as u32).collect::<Vec<_>>(),
        "{}",
        e.name()
    );
}

fn axis() -> impl Strategy<Value = Vector3<f64>> {
    prop::array::uniform3(-1.0..1.0f64)
        .prop_filter("non-zero", |a| a.iter().map(|c| c * c).sum::<f64>() > 1e-2)
        .prop_map(Vector3::from)
}

proptest! {
    #![proptest_config(crate::unit::config(64))]

    #[test]
    fn line2_geometry(x in planar_face(2), uv in (0.0..=1.0f64, 0.0..=1.0f64), axis in axis(), angle in 0.0..TAU) {
        check_surface_element(&Line2, &x, uv, axis, angle);
    }

    #[test]
    fn tri3_geometry(x in planar_face(3), uv in (0.0..=1.0f64, 0.0..=1.0f64), axis in axis(), angle in 0.0..TAU) {
        check_surface_element(&Tri3, &x, uv, axis, angle);
    }

    #[test]
    fn quad4_geometry(x in planar_face(4), uv in (0.0..=1.0f64, 0.0..=1.0f64), axis in axis(), angle in 0.0..TAU) {
        check_surface_element(&Quad4, &x, uv, axis, angle);
    }

    /// The second-order elements with straight edges and centred middle nodes: the same
    /// checks (their map is then that of the linear element, so the exact measure holds),
    /// and reversal.
    #[test]
    fn second_order_geometry(
        x2 in planar_face(2), x3 in planar_face(3), x4 in planar_face(4),
        uv in (0.0..=1.0f64, 0.0..=1.0f64), axis in axis(), angle in 0.0..TAU,
    ) {
        let faces: [(&dyn SurfaceElement, &[Vector3<f64>]); 4] =
            [(&Line3, &x2), (&Tri6, &x3), (&Quad8, &x4), (&Quad9, &x4)];
        for (e, corners) in faces {
            let x = second_order_nodes(e, corners);
            check_surface_element(e, &x, uv, axis, angle);
            check_reversal(e, &x);
        }
    }
}

/// A curved Line3 (middle node off the chord) measures the arc of its parabola: the chord
/// `(0,0)-(2,0)` with the middle node at `(1, h)` is `y = h (1 - (x-1)^2)`, of length
/// `int_0^2 sqrt(1 + 4 h^2 (x - 1)^2) dx` (closed form below).
#[test]
fn curved_line3_measures_its_parabola() {
    let h = 0.3f64;
    let x = [
        Vector3::zeros(),
        Vector3::new(2.0, 0.0, 0.0),
        Vector3::new(1.0, h, 0.0),
    ];
    let rule = QuadratureRule::for_domain(ReferenceDomain::Line, 20).unwrap();
    let len: f64 = rule
        .points()
        .iter()
        .zip(rule.weights())
        .map(|(p, w)| w * LINE3.jacobian_det(&x, p))
        .sum();
    // int_-1^1 sqrt(1 + a^2 t^2) dt = sqrt(1 + a^2) + asinh(a) / a, a = 2 h.
    let a = 2.0 * h;
    let want = (1.0 + a * a).sqrt() + a.asinh() / a;
    assert!((len - want).abs() < 1e-10, "{len} vs {want}");
}

#[test]
fn affinity_and_gmsh_types() {
    assert!(LINE2.is_affine() && TRI3.is_affine() && !QUAD4.is_affine());
    assert_eq!(LINE2.gmsh_type(), Some(1));
    assert_eq!(TRI3.gmsh_type(), Some(2));
    assert_eq!(QUAD4.gmsh_type(), Some(3));
    // Second-order faces are affine or not by their node positions, never by type.
    assert!(!LINE3.is_affine() && !TRI6.is_affine() && !QUAD8.is_affine() && !QUAD9.is_affine());
    let types = [
        LINE3.gmsh_type(),
        TRI6.gmsh_type(),
        QUAD8.gmsh_type(),
        QUAD9.gmsh_type(),
    ];
    assert_eq!(types, [Some(8), Some(9), Some(16), Some(10)]);
}

#[test]
fn quad4_jacobian_varies_on_a_trapezoid() {
    // Sanity for `check_affinity`: a non-affine element really has a varying Jacobian.
    let x = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0, 0.0, 0.0),
        Vector3::new(1.0, 1.0, 0.0),
        Vector3::new(0.0, 0.5, 0.0),
    ];
    let a = QUAD4.jacobian_det(&x, &Vector2::new(-1.0, -1.0));
    let b = QUAD4.jacobian_det(&x, &Vector2::new(1.0, 1.0));
    assert!((a - b).abs() > 0.01, "{a} {b}");
}

#[test]
fn line2_normal_points_down_when_running_to_plus_x() {
    let x = [Vector3::zeros(), Vector3::x()];
    let n = LINE2.unit_normal(&x, &Vector2::zeros());
    assert!((n + Vector3::y()).norm() < 1e-15, "{n:?}");
    assert!((LINE2.jacobian_det(&x, &Vector2::zeros()) - 0.5).abs() < 1e-15);
}
