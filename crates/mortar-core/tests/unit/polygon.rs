//! Polygon basics: signed area, orientation, fan triangulation, diameter, deduplication.

use mortar_core::geometry::{Polygon, MAX_POLYGON_VERTICES};
use nalgebra::Vector2;
use proptest::prelude::*;

use super::strategies::{convex_polygon, distance_outside};

fn shoelace(v: &[Vector2<f64>]) -> f64 {
    let n = v.len();
    0.5 * (0..n)
        .map(|i| v[i].x * v[(i + 1) % n].y - v[(i + 1) % n].x * v[i].y)
        .sum::<f64>()
}

proptest! {
    #![proptest_config(crate::unit::config(128))]

    #[test]
    fn signed_area_matches_the_shoelace_formula_and_flips_with_order(p in convex_polygon(12)) {
        let area = p.signed_area();
        prop_assert!(area > 0.0);
        prop_assert!((area - shoelace(&p.vertices)).abs() <= 1e-13 * area.max(1.0));
        let mut r = p.clone();
        r.reverse();
        prop_assert!((r.signed_area() + area).abs() <= 1e-13 * area.max(1.0));
    }

    #[test]
    fn fan_triangles_cover_the_polygon(p in convex_polygon(12)) {
        let mut count = 0;
        let mut sum = 0.0;
        p.for_each_triangle(|t| {
            count += 1;
            let a = shoelace(&t);
            assert!(a > 0.0, "a fan triangle of a convex CCW polygon is CCW");
            sum += a;
        });
        prop_assert_eq!(count, p.triangle_count());
        prop_assert!((sum - p.signed_area()).abs() <= 1e-13 * p.signed_area().max(1.0));
        prop_assert!(distance_outside(&p, p.vertex_centroid()) == 0.0);
    }

    #[test]
    fn vertex_fan_triangles_cover_the_convex_polygon(p in convex_polygon(12)) {
        let mut count = 0;
        let mut sum = 0.0;
        p.for_each_fan_triangle(|t| {
            count += 1;
            let a = shoelace(&t);
            assert!(a >= 0.0, "a vertex-fan triangle of a convex CCW polygon is not clockwise");
            sum += a;
        });
        prop_assert_eq!(count, p.vertices.len() - 2);
        prop_assert!((sum - p.signed_area()).abs() <= 1e-13 * p.signed_area().max(1.0));
    }

    #[test]
    fn diameter_is_the_largest_vertex_distance(p in convex_polygon(12)) {
        let d = p.diameter();
        for a in &p.vertices {
            for b in &p.vertices {
                prop_assert!((a - b).norm() <= d);
            }
        }
        prop_assert!(p.vertices.iter().any(|a| p.vertices.iter().any(|b| (a - b).norm() == d)));
    }

    #[test]
    fn dedup_removes_repeated_and_closing_vertices(p in convex_polygon(6), copies in 1..3usize) {
        let mut v = Vec::new();
        for x in &p.vertices {
            for _ in 0..copies {
                v.push(*x + Vector2::new(1e-15, 0.0));
            }
        }
        v.push(p.vertices[0]);
        let mut q = Polygon::from_slice(&v);
        q.dedup(1e-12);
        prop_assert_eq!(q.len(), p.len());
        prop_assert!((q.signed_area() - p.signed_area()).abs() <= 1e-12);
    }
}

#[test]
fn small_polygons_have_no_area_and_no_triangles() {
    for n in 0..3 {
        let p = Polygon::from_slice(&vec![Vector2::new(1.0, 2.0); n]);
        assert_eq!(p.signed_area(), 0.0);
        assert_eq!(p.triangle_count(), 0);
        let mut called = false;
        p.for_each_triangle(|_| called = true);
        assert!(!called);
    }
}

#[test]
fn from_slice_keeps_at_most_the_capacity() {
    let v: Vec<Vector2<f64>> = (0..MAX_POLYGON_VERTICES + 5)
        .map(|i| Vector2::new(i as f64, 0.0))
        .collect();
    let p = Polygon::from_slice(&v);
    assert_eq!(p.len(), MAX_POLYGON_VERTICES);
    assert_eq!(p.vertices[..], v[..MAX_POLYGON_VERTICES]);
}
