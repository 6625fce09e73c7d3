//! Planar polygons on the stack (`Polygon`): signed area, diameter, deduplication of close
//! vertices and triangulation into the triangles that the quadrature integrates.

use arrayvec::ArrayVec;
use nalgebra::Vector2;

use super::stable_norm;

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
        signed_area(&self.vertices)
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
        polygon_diameter(&self.vertices)
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

    /// Triangulates a convex polygon by the fan from its first vertex: `n - 2` triangles
    /// instead of the `n` of [`for_each_triangle`](Self::for_each_triangle), so that a
    /// quadrature on the triangles needs fewer points. Calls `f` with each triangle's vertices
    /// (counter-clockwise if the polygon is). On a polygon that is not convex some of the
    /// triangles overlap or turn clockwise: use `for_each_triangle` there.
    pub fn for_each_fan_triangle(&self, mut f: impl FnMut([Vector2<f64>; 3])) {
        let v = &self.vertices;
        for i in 1..v.len().saturating_sub(1) {
            f([v[0], v[i], v[i + 1]]);
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

/// The signed area of the polygon of vertices `v` (positive for counter-clockwise order), as
/// [`Polygon::signed_area`].
pub fn signed_area(v: &[Vector2<f64>]) -> f64 {
    let n = v.len();
    if n < 3 {
        return 0.0;
    }
    // Relative to the first vertex, to keep round-off small.
    let o = v[0];
    let mut twice = 0.0;
    for i in 1..n - 1 {
        let a = v[i] - o;
        let b = v[i + 1] - o;
        twice += a.x * b.y - a.y * b.x;
    }
    0.5 * twice
}

/// The largest distance between two of the points `v`.
pub fn polygon_diameter(v: &[Vector2<f64>]) -> f64 {
    let mut d: f64 = 0.0;
    for (i, a) in v.iter().enumerate() {
        for b in &v[i + 1..] {
            d = d.max((a - b).norm());
        }
    }
    d
}

/// Whether a polygon of vertices `v` and (positive) `area` is wider than `width`: more area
/// than a strip `width` wide along its whole diameter. Rounding turns two faces that only
/// touch into a sliver no wider than the coordinates' rounding, whose area can still exceed
/// that of a genuine small overlap; its width tells them apart.
pub fn wider_than(area: f64, v: &[Vector2<f64>], width: f64) -> bool {
    area > width * polygon_diameter(v)
}

/// Clips `subject` by the convex, counter-clockwise polygon `clip` (Sutherland-Hodgman).
///
/// Both polygons must be counter-clockwise; `subject` should be convex too, so that the
/// result is a single convex polygon. A point counts as inside an edge when it lies on it or to
/// its left within `tol` (a length). Consecutive vertices closer than `tol` are merged. The
/// result is written into `out` (cleared first). To clip many polygons by the same `clip`,
/// build its [`ConvexClipper`] once.
pub fn clip_convex(subject: &Polygon, clip: &Polygon, tol: f64, out: &mut Polygon) {
    ConvexClipper::new(clip).clip(&subject.vertices, tol, out);
}

/// The two vertex buffers the clipping passes use in turn, kept from call to call by a
/// caller that clips many polygons ([`ConvexClipper::clip_reversed_in`]): plain arrays, so
/// that a call neither allocates nor fills them first.
#[derive(Debug, Clone)]
pub struct ClipBuffers([[Vector2<f64>; MAX_POLYGON_VERTICES]; 2]);

impl Default for ClipBuffers {
    fn default() -> Self {
        Self([[Vector2::zeros(); MAX_POLYGON_VERTICES]; 2])
    }
}

/// A convex, counter-clockwise clip polygon ready to clip many subjects: its edges with their
/// inverse lengths, computed once ([`clip_convex`] with one clip polygon, the same bits).
#[derive(Debug, Clone, Default)]
pub struct ConvexClipper {
    /// Per edge of positive length: its start, its vector and its inverse length.
    edges: ArrayVec<(Vector2<f64>, Vector2<f64>, f64), MAX_POLYGON_VERTICES>,
}

impl ConvexClipper {
    /// The clipper of `clip` (convex, counter-clockwise).
    pub fn new(clip: &Polygon) -> Self {
        let mut clipper = Self::default();
        clipper.set(&clip.vertices);
        clipper
    }

    /// Makes this the clipper of the convex, counter-clockwise polygon of vertices `clip` (at
    /// most [`MAX_POLYGON_VERTICES`] are read), in place.
    pub fn set(&mut self, clip: &[Vector2<f64>]) {
        let clip = &clip[..clip.len().min(MAX_POLYGON_VERTICES)];
        let n = clip.len();
        self.edges.clear();
        for i in 0..n {
            let a = clip[i];
            let e = clip[(i + 1) % n] - a;
            let elen = e.norm();
            if elen != 0.0 {
                self.edges.push((a, e, 1.0 / elen));
            }
        }
    }

    /// Clips the polygon of vertices `subject` (counter-clockwise, convex; at most
    /// [`MAX_POLYGON_VERTICES`] are read) into `out`, as [`clip_convex`] does.
    pub fn clip(&self, subject: &[Vector2<f64>], tol: f64, out: &mut Polygon) {
        let mut bufs = ClipBuffers::default();
        let len = subject.len().min(MAX_POLYGON_VERTICES);
        bufs.0[0][..len].copy_from_slice(&subject[..len]);
        self.clip_buffered(len, tol, &mut bufs, out);
    }

    /// [`clip`](Self::clip) of the polygon of vertices `subject` taken in reverse order (a
    /// clockwise polygon, counter-clockwise reversed), with the caller's buffers: the same
    /// bits as `clip` of the reversed vertices.
    pub fn clip_reversed_in(
        &self,
        subject: &[Vector2<f64>],
        tol: f64,
        bufs: &mut ClipBuffers,
        out: &mut Polygon,
    ) {
        let len = subject.len().min(MAX_POLYGON_VERTICES);
        for (b, v) in bufs.0[0].iter_mut().zip(subject[..len].iter().rev()) {
            *b = *v;
        }
        self.clip_buffered(len, tol, bufs, out);
    }

    /// Clips the first `len` vertices of `bufs.0[0]`.
    fn clip_buffered(&self, mut len: usize, tol: f64, bufs: &mut ClipBuffers, out: &mut Polygon) {
        const N: usize = MAX_POLYGON_VERTICES;
        // Two buffers used in turn (plain arrays and a length: the clip runs once per
        // overlapping pair, and a vector's capacity checks cost as much as its arithmetic).
        let buf = &mut bufs.0;
        let mut cur = 0usize;
        for &(a, e, inv) in &self.edges {
            if len == 0 {
                break;
            }
            let [x, y] = &mut *buf;
            let (src, dst) = if cur == 0 { (&*x, y) } else { (&*y, x) };
            // Signed distance to the left of the edge.
            let dist = |p: &Vector2<f64>| (e.x * (p.y - a.y) - e.y * (p.x - a.x)) * inv;
            let mut d = [0.0; N];
            let mut inside = 0;
            for (dq, q) in d.iter_mut().zip(&src[..len]) {
                *dq = dist(q);
                inside += usize::from(*dq >= -tol);
            }
            if inside == len {
                // Every vertex inside: the pass would copy the polygon as it is (most edges
                // of the slave face do not cut a small master face).
                continue;
            }
            if inside == 0 {
                // Every vertex outside: nothing is left.
                len = 0;
                break;
            }
            let mut n = 0;
            let mut p = src[len - 1];
            let mut dp = d[len - 1];
            for (&q, &dq) in src[..len].iter().zip(&d) {
                let p_in = dp >= -tol;
                let q_in = dq >= -tol;
                if p_in != q_in && n < N {
                    // A point inside only by the tolerance can put the crossing of the zero
                    // line outside the segment: clamp, so the vertex stays on the subject's
                    // edge.
                    let t = (dp / (dp - dq)).clamp(0.0, 1.0);
                    dst[n] = p + (q - p) * t;
                    n += 1;
                }
                if q_in && n < N {
                    dst[n] = q;
                    n += 1;
                }
                p = q;
                dp = dq;
            }
            len = n;
            cur = 1 - cur;
        }
        out.vertices.clear();
        // Distances, not their squares: `tol` squared underflows for the smallest faces of a
        // mesh at 1e-140 (see `stable_norm`).
        for v in &buf[cur][..len] {
            if out
                .vertices
                .last()
                .is_none_or(|l: &Vector2<f64>| stable_norm(&(v - l)) > tol)
            {
                out.vertices.push(*v);
            }
        }
        while out.vertices.len() > 1
            && stable_norm(&(out.vertices[0] - out.vertices[out.vertices.len() - 1])) <= tol
        {
            out.vertices.pop();
        }
    }
}
