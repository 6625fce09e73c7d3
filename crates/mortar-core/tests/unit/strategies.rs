//! Random convex polygons for the geometry tests.

use std::f64::consts::TAU;

use mortar_core::geometry::Polygon;
use nalgebra::Vector2;
use proptest::prelude::*;

/// A convex, counter-clockwise polygon of 3 to `max_vertices` vertices: points on an ellipse
/// of random centre, radii (0.05 to 2) and orientation, at angles whose gaps are random
/// weights in `[1, 1.9]` scaled to a full turn, so every gap is below `pi` (the polygon is
/// strictly convex and round enough) and no two vertices nearly coincide.
pub fn convex_polygon(max_vertices: usize) -> impl Strategy<Value = Polygon> {
    (
        prop::collection::vec(1.0..1.9f64, 3..=max_vertices),
        0.0..TAU,
        prop::array::uniform2(-1.0..1.0f64),
        (0.05..2.0f64, 0.05..2.0f64),
        0.0..TAU,
    )
        .prop_map(|(weights, start, c, (rx, ry), rot)| {
            let total: f64 = weights.iter().sum();
            let (s, co) = rot.sin_cos();
            let mut angle = start;
            let vertices: Vec<Vector2<f64>> = weights
                .iter()
                .map(|w| {
                    let (x, y) = (rx * angle.cos(), ry * angle.sin());
                    angle += w / total * TAU;
                    Vector2::new(c[0] + co * x - s * y, c[1] + s * x + co * y)
                })
                .collect();
            Polygon::from_slice(&vertices)
        })
}

/// The signed distance of `p` to the left of the directed line `a -> b`.
pub fn left_distance(a: Vector2<f64>, b: Vector2<f64>, p: Vector2<f64>) -> f64 {
    let e = b - a;
    (e.x * (p.y - a.y) - e.y * (p.x - a.x)) / e.norm()
}

/// How far `p` lies outside the convex counter-clockwise polygon (0 inside).
pub fn distance_outside(poly: &Polygon, p: Vector2<f64>) -> f64 {
    let v = &poly.vertices;
    let n = v.len();
    (0..n)
        .map(|i| -left_distance(v[i], v[(i + 1) % n], p))
        .fold(0.0, f64::max)
}
