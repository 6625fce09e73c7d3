use arrayvec::ArrayVec;
use nalgebra::Vector2;

/// The most vertices a clip polygon can have: two convex polygons of at most 4 corners give at
/// most 8, and room is left for higher-order faces' corner polygons.
pub const MAX_POLYGON_VERTICES: usize = 16;

/// A planar polygon on the stack.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Polygon {
    /// The vertices, in order.
    pub vertices: ArrayVec<Vector2<f64>, MAX_POLYGON_VERTICES>,
}

impl Polygon {
    /// A polygon with the given vertices (at most [`MAX_POLYGON_VERTICES`]; extra ones are
    /// dropped).
    pub fn from_slice(vertices: &[Vector2<f64>]) -> Self {
        let mut p = Self::default();
        for v in vertices.iter().take(MAX_POLYGON_VERTICES) {
            p.vertices.push(*v);
        }
        p
    }

    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// Whether there are no vertices.
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }

    /// Signed area (positive for counter-clockwise order).
    pub fn signed_area(&self) -> f64 {
        let n = self.vertices.len();
        if n < 3 {
            return 0.0;
        }
        // Relative to the first vertex, to keep round-off small.
        let o = self.vertices[0];
        let mut twice = 0.0;
        for i in 1..n - 1 {
            let a = self.vertices[i] - o;
            let b = self.vertices[i + 1] - o;
            twice += a.x * b.y - a.y * b.x;
        }
        0.5 * twice
    }

    /// Reverses the vertex order.
    pub fn reverse(&mut self) {
        self.vertices.reverse();
    }

    /// The vertex average (the centre used for the fan triangulation).
    pub fn vertex_centroid(&self) -> Vector2<f64> {
        let mut c = Vector2::zeros();
        for v in &self.vertices {
            c += v;
        }
        c / self.vertices.len().max(1) as f64
    }

    /// The largest distance between two vertices.
    pub fn diameter(&self) -> f64 {
        let mut d: f64 = 0.0;
        for (i, a) in self.vertices.iter().enumerate() {
            for b in &self.vertices[i + 1..] {
                d = d.max((a - b).norm());
            }
        }
        d
    }

    /// Triangulates the polygon: itself if it is a triangle, else a fan from the vertex
    /// centroid. Calls `f` with each triangle's vertices (counter-clockwise if the polygon is).
    pub fn for_each_triangle(&self, mut f: impl FnMut([Vector2<f64>; 3])) {
        let n = self.vertices.len();
        if n < 3 {
            return;
        }
        if n == 3 {
            f([self.vertices[0], self.vertices[1], self.vertices[2]]);
            return;
        }
        let c = self.vertex_centroid();
        for i in 0..n {
            f([c, self.vertices[i], self.vertices[(i + 1) % n]]);
        }
    }

    /// Number of triangles [`for_each_triangle`](Self::for_each_triangle) produces.
    pub fn triangle_count(&self) -> usize {
        match self.vertices.len() {
            0..=2 => 0,
            3 => 1,
            n => n,
        }
    }

    /// Removes consecutive vertices closer than `tol` (and a closing duplicate).
    pub fn dedup(&mut self, tol: f64) {
        let mut out: ArrayVec<Vector2<f64>, MAX_POLYGON_VERTICES> = ArrayVec::new();
        for v in &self.vertices {
            if out
                .last()
                .is_none_or(|l: &Vector2<f64>| (v - l).norm() > tol)
            {
                out.push(*v);
            }
        }
        while out.len() > 1 && (out[0] - out[out.len() - 1]).norm() <= tol {
            out.pop();
        }
        self.vertices = out;
    }
}

/// Clips `subject` by the convex, counter-clockwise polygon `clip` (Sutherland-Hodgman).
///
/// Both polygons must be counter-clockwise; `subject` should be convex too, so that the
/// result is a single convex polygon. A point counts as inside an edge when it lies on it or to
/// its left within `tol` (a length). Consecutive vertices closer than `tol` are merged. The
/// result is written into `out` (cleared first).
pub fn clip_convex(subject: &Polygon, clip: &Polygon, tol: f64, out: &mut Polygon) {
    out.vertices.clear();
    out.vertices.extend(subject.vertices.iter().copied());
    let n = clip.vertices.len();
    let mut input = Polygon::default();
    for i in 0..n {
        if out.vertices.is_empty() {
            return;
        }
        let a = clip.vertices[i];
        let b = clip.vertices[(i + 1) % n];
        let e = b - a;
        let len = e.norm();
        if len == 0.0 {
            continue;
        }
        // Signed distance to the left of edge a->b.
        let dist = |p: &Vector2<f64>| (e.x * (p.y - a.y) - e.y * (p.x - a.x)) / len;
        std::mem::swap(&mut input, out);
        out.vertices.clear();
        let m = input.vertices.len();
        for j in 0..m {
            let p = input.vertices[j];
            let q = input.vertices[(j + 1) % m];
            let dp = dist(&p);
            let dq = dist(&q);
            let p_in = dp >= -tol;
            let q_in = dq >= -tol;
            if p_in {
                push(out, p);
            }
            if p_in != q_in {
                let t = dp / (dp - dq);
                push(out, p + (q - p) * t);
            }
        }
    }
    out.dedup(tol);
}

#[inline]
fn push(poly: &mut Polygon, v: Vector2<f64>) {
    // Convex inputs give at most n + m vertices; the capacity check only guards bad input.
    let _ = poly.vertices.try_push(v);
}
