//! Shape functions on the reference element.

use mortar_core::element::{ReferenceDomain, ReferenceElement, MAX_FACE_NODES};
use mortar_elements::{
    Line2, Line3, Quad4, Quad8, Quad9, Tri3, Tri6, LINE2, LINE3, QUAD4, QUAD8, QUAD9, TRI3, TRI6,
};
use nalgebra::{Matrix2, Vector2};
use proptest::prelude::*;

/// A grid of points covering the closed reference domain (corners, edges, interior).
fn sample_points(domain: ReferenceDomain) -> Vec<Vector2<f64>> {
    let m = 12;
    let mut out = Vec::new();
    for i in 0..=m {
        for j in 0..=m {
            let (u, v) = (i as f64 / m as f64, j as f64 / m as f64);
            let p = match domain {
                ReferenceDomain::Line => Vector2::new(2.0 * u - 1.0, 0.0),
                ReferenceDomain::Triangle => Vector2::new(u * (1.0 - v), v),
                ReferenceDomain::Quadrilateral => Vector2::new(2.0 * u - 1.0, 2.0 * v - 1.0),
            };
            if domain != ReferenceDomain::Line || j == 0 {
                out.push(p);
            }
        }
    }
    out
}

fn values<E: ReferenceElement + ?Sized>(e: &E, xi: &Vector2<f64>) -> Vec<f64> {
    let mut n = vec![0.0; e.node_count()];
    e.shape_values_into(xi, &mut n);
    n
}

fn gradients<E: ReferenceElement + ?Sized>(e: &E, xi: &Vector2<f64>) -> Vec<[f64; 2]> {
    let mut g = vec![[0.0; 2]; e.node_count()];
    e.shape_gradients_into(xi, &mut g);
    g
}

fn nodes<E: ReferenceElement + ?Sized>(e: &E) -> Vec<Vector2<f64>> {
    e.node_reference_coords()
        .iter()
        .map(|p| Vector2::new(p[0], p[1]))
        .collect()
}

/// Node layout: as many reference coordinates as nodes, at most `MAX_FACE_NODES`, all in the
/// closed domain and distinct; the corners first, counter-clockwise (lines: from -1 to 1).
fn check_node_layout<E: ReferenceElement + ?Sized>(e: &E) {
    let x = nodes(e);
    assert_eq!(x.len(), e.node_count(), "{}", e.name());
    assert!(e.node_count() <= MAX_FACE_NODES);
    assert!(e.corner_count() <= e.node_count());
    for (i, p) in x.iter().enumerate() {
        assert!(
            e.domain().contains(p, 0.0),
            "{} node {i} at {p:?}",
            e.name()
        );
        for q in &x[i + 1..] {
            assert!((p - q).norm() > 1e-12, "{}: repeated node", e.name());
        }
        if e.domain() == ReferenceDomain::Line {
            assert_eq!(p.y, 0.0);
        }
    }
    let c = e.corner_count();
    if e.domain() == ReferenceDomain::Line {
        assert_eq!(c, 2);
        assert_eq!((x[0].x, x[1].x), (-1.0, 1.0));
    } else {
        let twice: f64 = (0..c)
            .map(|i| {
                let (a, b) = (x[i], x[(i + 1) % c]);
                a.x * b.y - b.x * a.y
            })
            .sum();
        assert!(
            (0.5 * twice - e.domain().measure()).abs() < 1e-15,
            "{}: the corners must go counter-clockwise round the whole domain",
            e.name()
        );
    }
}

/// `sum_i N_i = 1` everywhere.
fn check_partition_of_unity<E: ReferenceElement + ?Sized>(e: &E, points: &[Vector2<f64>]) {
    for xi in points {
        let s: f64 = values(e, xi).iter().sum();
        assert!(
            (s - 1.0).abs() < 1e-15,
            "{} at {xi:?}: sum N = {s}",
            e.name()
        );
    }
}

/// `N_i(x_j) = delta_ij`.
fn check_kronecker_delta<E: ReferenceElement + ?Sized>(e: &E) {
    for (j, xj) in nodes(e).iter().enumerate() {
        for (i, v) in values(e, xj).iter().enumerate() {
            let want = if i == j { 1.0 } else { 0.0 };
            assert!((v - want).abs() < 1e-15, "{}: N_{i}(x_{j}) = {v}", e.name());
        }
    }
}

/// `sum_i grad N_i = 0`, lines have no second component, and the gradients match central
/// finite differences of the values.
fn check_gradients<E: ReferenceElement + ?Sized>(e: &E, points: &[Vector2<f64>]) {
    let h = 1e-6;
    let dims = e.domain().dim();
    for xi in points {
        let g = gradients(e, xi);
        for d in 0..2 {
            let s: f64 = g.iter().map(|gi| gi[d]).sum();
            assert!(
                s.abs() < 1e-14,
                "{} at {xi:?}: sum dN/dxi_{d} = {s}",
                e.name()
            );
        }
        for d in 0..dims {
            let mut step = Vector2::zeros();
            step[d] = h;
            let (plus, minus) = (values(e, &(xi + step)), values(e, &(xi - step)));
            for i in 0..e.node_count() {
                let fd = (plus[i] - minus[i]) / (2.0 * h);
                assert!(
                    (fd - g[i][d]).abs() < 1e-8,
                    "{} at {xi:?}: dN_{i}/dxi_{d} = {} but finite difference {fd}",
                    e.name(),
                    g[i][d]
                );
            }
        }
        if dims == 1 {
            assert!(g.iter().all(|gi| gi[1] == 0.0), "{}", e.name());
        }
    }
}

/// Isoparametric completeness: the shape functions reproduce linear functions of the
/// reference coordinates, `sum_i N_i(xi) xi_i = xi`, and `sum_i xi_i (grad N_i)^T = I`.
fn check_linear_completeness<E: ReferenceElement + ?Sized>(e: &E, points: &[Vector2<f64>]) {
    let x = nodes(e);
    for xi in points {
        let n = values(e, xi);
        let g = gradients(e, xi);
        let mut p = Vector2::zeros();
        let mut j = Matrix2::zeros();
        for i in 0..e.node_count() {
            p += x[i] * n[i];
            j += x[i] * Vector2::new(g[i][0], g[i][1]).transpose();
        }
        assert!(
            (p - xi).norm() < 1e-15,
            "{} at {xi:?}: sum N_i xi_i = {p:?}",
            e.name()
        );
        let want = if e.domain() == ReferenceDomain::Line {
            Matrix2::new(1.0, 0.0, 0.0, 0.0)
        } else {
            Matrix2::identity()
        };
        assert!((j - want).norm() < 1e-14, "{} at {xi:?}: {j:?}", e.name());
    }
}

/// The shape functions are polynomials of total degree `shape_degree()`: along any line, the
/// `(p+1)`-th finite difference vanishes, and some shape function's `p`-th one does not.
fn check_shape_degree<E: ReferenceElement + ?Sized>(e: &E) {
    let p = e.shape_degree() as usize;
    let dirs: Vec<Vector2<f64>> = if e.domain() == ReferenceDomain::Line {
        vec![Vector2::new(1.0, 0.0)]
    } else {
        vec![
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(0.6, 0.8),
        ]
    };
    let base = e.domain().centre() * 0.5;
    let step = 0.1;
    // k-th forward difference of f at base along d: sum_m (-1)^(k-m) C(k,m) f(base + m h d).
    let diff = |d: &Vector2<f64>, k: usize| -> Vec<f64> {
        let mut out = vec![0.0; e.node_count()];
        let mut binom = 1.0;
        for m in 0..=k {
            let sign = if (k - m).is_multiple_of(2) { 1.0 } else { -1.0 };
            let v = values(e, &(base + d * (m as f64 * step)));
            for (o, vi) in out.iter_mut().zip(v) {
                *o += sign * binom * vi;
            }
            binom = binom * (k - m) as f64 / (m + 1) as f64;
        }
        out
    };
    let mut highest = 0.0f64;
    for d in &dirs {
        for v in diff(d, p + 1) {
            assert!(
                v.abs() < 1e-12,
                "{}: degree above {p} along {d:?}",
                e.name()
            );
        }
        highest = highest.max(diff(d, p).iter().fold(0.0, |m, v| m.max(v.abs())));
    }
    assert!(
        highest > 1e-6,
        "{}: no shape function reaches degree {p}",
        e.name()
    );
}

/// C0 conformity: on each edge between consecutive corners, the shape functions of nodes
/// not on that edge vanish.
fn check_edge_conformity<E: ReferenceElement + ?Sized>(e: &E) {
    if e.domain() == ReferenceDomain::Line {
        return;
    }
    let x = nodes(e);
    let c = e.corner_count();
    for k in 0..c {
        let (a, b) = (x[k], x[(k + 1) % c]);
        let on_edge = |p: &Vector2<f64>| {
            let (u, w) = (b - a, p - a);
            (u.x * w.y - u.y * w.x).abs() < 1e-14
                && w.dot(&u) >= -1e-14
                && w.dot(&u) <= u.dot(&u) + 1e-14
        };
        for s in 0..=10 {
            let p = a + (b - a) * (s as f64 / 10.0);
            let n = values(e, &p);
            for (i, xi) in x.iter().enumerate() {
                if !on_edge(xi) {
                    assert!(
                        n[i].abs() < 1e-15,
                        "{}: N_{i} = {} on edge {k}",
                        e.name(),
                        n[i]
                    );
                }
            }
        }
    }
}

/// Quadratic completeness of the second-order elements: the shape functions reproduce the
/// quadratic monomials of the reference coordinates, `sum_i N_i(xi) m(xi_i) = m(xi)` for
/// `m` in `xi^2, xi eta, eta^2` (lines: `xi^2`).
fn check_quadratic_completeness<E: ReferenceElement + ?Sized>(e: &E, points: &[Vector2<f64>]) {
    let x = nodes(e);
    let monomials: [fn(&Vector2<f64>) -> f64; 3] = [|p| p.x * p.x, |p| p.x * p.y, |p| p.y * p.y];
    for xi in points {
        let n = values(e, xi);
        for m in monomials {
            let p: f64 = x.iter().zip(&n).map(|(xj, nj)| m(xj) * nj).sum();
            assert!(
                (p - m(xi)).abs() < 1e-14,
                "{} at {xi:?}: {p} vs {}",
                e.name(),
                m(xi)
            );
        }
    }
}

/// Everything above, for one element type.
fn check_reference_element<E: ReferenceElement + ?Sized>(e: &E) {
    let points = sample_points(e.domain());
    check_node_layout(e);
    check_partition_of_unity(e, &points);
    check_kronecker_delta(e);
    check_gradients(e, &points);
    check_linear_completeness(e, &points);
    check_shape_degree(e);
    check_edge_conformity(e);
}

#[test]
fn line2_shape_functions() {
    check_reference_element(&LINE2);
    assert_eq!(
        (LINE2.name(), LINE2.node_count(), LINE2.shape_degree()),
        ("Line2", 2, 1)
    );
}

#[test]
fn tri3_shape_functions() {
    check_reference_element(&TRI3);
    assert_eq!(
        (TRI3.name(), TRI3.node_count(), TRI3.shape_degree()),
        ("Tri3", 3, 1)
    );
}

#[test]
fn quad4_shape_functions() {
    check_reference_element(&QUAD4);
    assert_eq!(
        (QUAD4.name(), QUAD4.node_count(), QUAD4.shape_degree()),
        ("Quad4", 4, 2)
    );
}

#[test]
fn line3_shape_functions() {
    check_reference_element(&LINE3);
    check_quadratic_completeness(&LINE3, &sample_points(ReferenceDomain::Line));
    assert_eq!((LINE3.node_count(), LINE3.shape_degree()), (3, 2));
}

#[test]
fn tri6_shape_functions() {
    check_reference_element(&TRI6);
    check_quadratic_completeness(&TRI6, &sample_points(ReferenceDomain::Triangle));
    assert_eq!((TRI6.node_count(), TRI6.shape_degree()), (6, 2));
}

#[test]
fn quad8_shape_functions() {
    check_reference_element(&QUAD8);
    check_quadratic_completeness(&QUAD8, &sample_points(ReferenceDomain::Quadrilateral));
    assert_eq!((QUAD8.node_count(), QUAD8.shape_degree()), (8, 3));
}

#[test]
fn quad9_shape_functions() {
    check_reference_element(&QUAD9);
    check_quadratic_completeness(&QUAD9, &sample_points(ReferenceDomain::Quadrilateral));
    assert_eq!((QUAD9.node_count(), QUAD9.shape_degree()), (9, 4));
}

/// A point of a reference domain from two uniform numbers in [0, 1].
fn point_in(domain: ReferenceDomain, u: f64, v: f64) -> Vector2<f64> {
    match domain {
        ReferenceDomain::Line => Vector2::new(2.0 * u - 1.0, 0.0),
        ReferenceDomain::Triangle => {
            if u + v <= 1.0 {
                Vector2::new(u, v)
            } else {
                Vector2::new(1.0 - u, 1.0 - v)
            }
        }
        ReferenceDomain::Quadrilateral => Vector2::new(2.0 * u - 1.0, 2.0 * v - 1.0),
    }
}

proptest! {
    #![proptest_config(crate::unit::config(64))]

    /// The same checks at random points of each domain (the element types listed by hand).
    #[test]
    fn shape_functions_at_random_points(u in 0.0..=1.0f64, v in 0.0..=1.0f64) {
        let line = [point_in(ReferenceDomain::Line, u, v)];
        check_partition_of_unity(&Line2, &line);
        check_gradients(&Line2, &line);
        check_linear_completeness(&Line2, &line);
        let tri = [point_in(ReferenceDomain::Triangle, u, v)];
        check_partition_of_unity(&Tri3, &tri);
        check_gradients(&Tri3, &tri);
        check_linear_completeness(&Tri3, &tri);
        let quad = [point_in(ReferenceDomain::Quadrilateral, u, v)];
        check_partition_of_unity(&Quad4, &quad);
        check_gradients(&Quad4, &quad);
        check_linear_completeness(&Quad4, &quad);
        check_partition_of_unity(&Line3, &line);
        check_gradients(&Line3, &line);
        check_quadratic_completeness(&Line3, &line);
        check_partition_of_unity(&Tri6, &tri);
        check_gradients(&Tri6, &tri);
        check_quadratic_completeness(&Tri6, &tri);
        for e in [&Quad8 as &dyn ReferenceElement, &Quad9] {
            check_partition_of_unity(e, &quad);
            check_gradients(e, &quad);
            check_quadratic_completeness(e, &quad);
        }
    }
}
