//! The mortar integrals of linear triangles in closed form (3D).
//!
//! Where the slave and the master faces are three-node triangles with linear shape functions
//! and the slave's map into space is affine, every integrand of D and M, `Phi_j N_k` and
//! `Phi_j N_l^m`, is the product of two affine functions of the auxiliary plane's
//! coordinates (the multipliers are combinations of the slave's shape functions, each master
//! shape function is a barycentric coordinate of the master's projection). Its integral over
//! a clip polygon is then a quadratic form in the polygon's moments of order 0, 1 and 2,
//! which the polygon's vertices give exactly (Green's theorem, summed over the fan of
//! triangles from the first vertex: for the triangle `0, a, b` of signed area `t`,
//! `int 1 = t`, `int p = t (a + b) / 3`, `int p p^T = t (2 a a^T + 2 b b^T + a b^T + b a^T) / 12`;
//! C. Steger, "On the calculation of arbitrary moments of polygons", TU Munich FGBV-96-05,
//! 1996). This replaces the strategy's quadrature points on the clip triangles and their
//! mapping back to both faces (2n - 3 points per n-gon, each mapped to two faces and
//! multiplied into the local blocks) by one pass over the vertices and a few products per
//! pair; the result is the one of any exact quadrature, to round-off.
//!
//! The coupling runs it instead of the strategy when the strategy is
//! [`SegmentBased`](super::SegmentBased) (found by its type) with a degree that integrates
//! these integrands exactly, and every face of both sides is such a triangle ([`applies`]).

use nalgebra::Vector2;

use super::segments_3d::SlavePlane;
use super::{default_degree, PairedRule, PolygonSegments, SegmentContext};
use crate::element::flat::FlatShape;
use crate::element::{ElementRef, MAX_FACE_NODES};
use crate::error::Result;
use crate::geometry::Polygon;
use crate::interface::{FaceGeometry, Interface, SpatialDim};
use crate::multiplier::LmBasis;
use crate::search::{MasterCorners, MasterCornersCache};

/// What the closed forms keep from one slave face to the next (one per worker): the master
/// faces read, and the set-up of the slave face in its plane.
#[derive(Default)]
pub(crate) struct ClosedFormScratch {
    /// The master faces read, by slot.
    pub masters: MasterCornersCache,
    /// The last slave face's set-up (its clip buffers reused).
    pub plane: Option<SlavePlane>,
}

/// How the coupling integrates clip polygons in closed form.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ClosedForm {
    /// The strategy's exact segmentation.
    pub rule: PolygonSegments,
    /// Whether every face of both sides is a linear triangle: the vertex formulas of
    /// [`closed_form_into`]; else the moments of
    /// [`affine_moments_into`](super::affine_moments::affine_moments_into).
    pub triangles: bool,
    /// The shapes of the interface's element types (the first few), so that a face's is a
    /// pointer comparison rather than [`FlatShape::of`]'s sample evaluations.
    shapes: [Option<(ElementRef, FlatShape)>; 4],
}

impl ClosedForm {
    /// The shape of `element` (an element type of the interface's faces).
    #[inline]
    pub(crate) fn shape(&self, element: ElementRef) -> Option<FlatShape> {
        self.shapes
            .iter()
            .flatten()
            .find(|(e, _)| std::ptr::eq(*e, element))
            .map(|(_, s)| *s)
            .or_else(|| FlatShape::of(element))
    }
}

/// How the coupling of `interface` may integrate in closed form for a strategy whose exact
/// segmentation has the degree of `rule`: on a 3D interface whose faces are all linear
/// triangles ([`is_linear_triangle`]) or bilinear quads
/// ([`is_bilinear_quad`](super::affine_moments::is_bilinear_quad)), with a degree (if fixed)
/// at least the integrands'. `None` where it may not.
pub(crate) fn applies(
    interface: &Interface,
    rule: PolygonSegments,
    whole: Option<(&[ElementRef], &[ElementRef])>,
) -> Option<ClosedForm> {
    if interface.dim() != SpatialDim::Three {
        return None;
    }
    let (slave, master) = (interface.slave(), interface.master());
    // Every element type's shape, once; the first few kept for the faces' lookups.
    let mut shapes = [None; 4];
    let types = slave.element_types().iter().chain(master.element_types());
    for (i, &e) in types.enumerate() {
        let shape = FlatShape::of(e)?;
        if let Some(slot) = shapes.get_mut(i) {
            *slot = Some((e, shape));
        }
    }
    // Whether they apply, and whether every face is a triangle, is the whole interface's
    // choice where this one is a part of it.
    let (slave, master) = whole.unwrap_or((slave.element_types(), master.element_types()));
    let mut triangles = true;
    for &e in slave.iter().chain(master) {
        triangles &= FlatShape::of(e)? == FlatShape::Triangle;
    }
    let exact = rule.degree.is_none_or(|d| {
        slave
            .iter()
            .all(|s| master.iter().all(|m| d >= default_degree(*s, *m)))
    });
    exact.then_some(ClosedForm {
        rule,
        triangles,
        shapes,
    })
}

/// The moments of a polygon of order 0, 1 and 2 about its first vertex `o`: `int 1`,
/// `int (p - o)` and `int (p - o)(p - o)^T` (as `xx, xy, yy`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Moments {
    area: f64,
    first: Vector2<f64>,
    second: [f64; 3],
}

impl Moments {
    /// The moments of `poly` (counter-clockwise: a positive area) in the coordinates
    /// `scale p`, summed over the fan of triangles from its first vertex.
    fn of(poly: &Polygon, scale: f64) -> Self {
        let v = &poly.vertices;
        let o = v[0];
        let mut m = Self::default();
        let mut a = (v[1] - o) * scale;
        for w in &v[2..] {
            let b = (w - o) * scale;
            let t = 0.5 * (a.x * b.y - a.y * b.x);
            m.area += t;
            m.first += (a + b) * (t / 3.0);
            let t6 = t / 6.0;
            m.second[0] += t6 * (a.x * a.x + b.x * b.x + a.x * b.x);
            m.second[1] += t6 * (a.x * a.y + b.x * b.y + 0.5 * (a.x * b.y + b.x * a.y));
            m.second[2] += t6 * (a.y * a.y + b.y * b.y + a.y * b.y);
            a = b;
        }
        m
    }
}

/// An affine function `c + g . p` of the plane's coordinates.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Affine {
    c: f64,
    g: Vector2<f64>,
}

impl Affine {
    #[inline]
    fn at(&self, p: &Vector2<f64>) -> f64 {
        self.c + self.g.dot(p)
    }
}

/// The barycentric coordinates of the triangle `t` (either orientation, not degenerate) as
/// affine functions of the coordinates `scale p`:
/// `lambda_i(p) = cross(t_i+2 - t_i+1, p - t_i+1) / cross(t_1 - t_0, t_2 - t_0)`.
fn barycentric(t: &[Vector2<f64>], scale: f64) -> [Affine; 3] {
    let t = [t[0] * scale, t[1] * scale, t[2] * scale];
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let inv = 1.0 / (e1.x * e2.y - e1.y * e2.x);
    std::array::from_fn(|i| {
        let (a, b) = (t[(i + 1) % 3], t[(i + 2) % 3]);
        let e = b - a;
        let g = Vector2::new(-e.y, e.x) * inv;
        Affine { c: -g.dot(&a), g }
    })
}

/// The integrals of one multiplier against affine functions over a polygon: with `w0 = int
/// Phi` and `w1 = int Phi (p - o)`, `int Phi f = f(o) w0 + g_f . w1`.
#[derive(Debug, Clone, Copy)]
struct Weighted {
    w0: f64,
    w1: Vector2<f64>,
}

impl Weighted {
    /// The integrals of `phi` over the polygon of moments `m` about `o`.
    #[inline]
    fn of(phi: &Affine, o: &Vector2<f64>, m: &Moments) -> Self {
        let c = phi.at(o);
        let g = phi.g;
        Self {
            w0: c * m.area + g.dot(&m.first),
            w1: Vector2::new(
                c * m.first.x + m.second[0] * g.x + m.second[1] * g.y,
                c * m.first.y + m.second[1] * g.x + m.second[2] * g.y,
            ),
        }
    }

    /// `int Phi f` for the affine `f` whose value at `o` is `at_o`.
    #[inline]
    fn times(&self, at_o: f64, f: &Affine) -> f64 {
        at_o * self.w0 + f.g.dot(&self.w1)
    }
}

/// D and M of a slave linear triangle against its `candidates` (linear triangles, as slots of
/// `ctx.masters`, read through `masters`) in closed form: D added to `d`, each master face's
/// `3 x 3` M block (row-major) given to `add_m` with the columns of the face's nodes, in
/// candidate order. The
/// work of the strategy's segmentation and the coupling's integration of its points. `out`
/// gets the counts the strategy would give (pairs, back-facing candidates, the covered
/// fraction, the degree the strategy would have used; one cell per clip polygon) and no
/// points. The caller checks [`applies`].
///
/// Returns `false`, with nothing added, when the slave face is not integrated in the plane
/// (its projection is not affine): the strategy then takes it.
///
/// # Errors
/// As the strategy's segmentation: a slave face with a zero projection direction or one that
/// turns against it.
#[allow(clippy::too_many_arguments)]
pub(crate) fn closed_form_into(
    ctx: &SegmentContext<'_>,
    slave: &FaceGeometry,
    candidates: &[u32],
    degree: Option<u32>,
    basis: &LmBasis,
    d: &mut [[f64; MAX_FACE_NODES]; MAX_FACE_NODES],
    scratch: &mut ClosedFormScratch,
    mut add_m: impl FnMut(&[u32], &[f64]),
    out: &mut PairedRule,
) -> Result<bool> {
    out.clear();
    let ClosedFormScratch { masters, plane } = scratch;
    let setup = SlavePlane::reuse(plane, ctx, slave)?;
    if setup.in_reference {
        return Ok(false);
    }
    // The plane's coordinates scaled by a power of two (exactly) to the face's size: the
    // second moments are products of four lengths, which would under- or overflow for faces
    // of 1e-80 or 1e80; the area unit comes back as a factor of the moments.
    let scale = pow2_near_inverse(setup.diameter);
    let unit = setup.measure / scale / scale;
    let ns = barycentric(&setup.sp[..3], scale);
    // The multipliers as affine functions, `Phi_j = sum_k a_jk N_k`.
    let phi: [Affine; 3] = if basis.identity {
        ns
    } else {
        std::array::from_fn(|j| {
            let a = &basis.a[j];
            Affine {
                c: a[0] * ns[0].c + a[1] * ns[1].c + a[2] * ns[2].c,
                g: ns[0].g * a[0] + ns[1].g * a[1] + ns[2].g * a[2],
            }
        })
    };
    let mut mp = [Vector2::zeros(); MAX_FACE_NODES];
    let mut clip = Polygon::default();
    let mut covered = 0.0;
    let mut dface = [[0.0; 3]; 3];
    for &m in candidates {
        let MasterCorners {
            element,
            nodes,
            cols,
            ..
        } = masters.get(ctx.interface, ctx.masters, m);
        let bf = &mut out.back_facing;
        let Some(area_m) =
            setup.clip_face_unmeasured(*element, &nodes[..3], &mut mp, &mut clip, bf)
        else {
            continue;
        };
        let mut mom = Moments::of(&clip, scale);
        // The polygon's area in the plane from its moments: the fan's sum, scaled by powers
        // of two (exact), is `signed_area`'s to the bit.
        let area = mom.area / scale / scale;
        if !setup.overlap_counts(area, area_m, &clip) {
            continue;
        }
        // The unit of area, and the plane's measure to the face's (1 when the face lies in
        // the plane).
        mom.area *= unit;
        mom.first *= unit;
        for s in &mut mom.second {
            *s *= unit;
        }
        let o = clip.vertices[0] * scale;
        let nm = barycentric(&mp[..3], scale);
        // The shape functions at `o`, once for the three multipliers.
        let (ns_o, nm_o) = (ns.map(|n| n.at(&o)), nm.map(|n| n.at(&o)));
        let mut block = [0.0; 9];
        for (j, p) in phi.iter().enumerate() {
            let w = Weighted::of(p, &o, &mom);
            for (k, n) in ns.iter().enumerate() {
                dface[j][k] += w.times(ns_o[k], n);
            }
            for (l, n) in nm.iter().enumerate() {
                block[j * 3 + l] = w.times(nm_o[l], n);
            }
        }
        add_m(&cols[..3], &block);
        out.pairs += 1;
        out.cells += 1;
        out.degrees |= 1 << degree.unwrap_or_else(|| default_degree(slave.element, *element));
        covered += area;
    }
    for (row, dr) in d.iter_mut().zip(&dface) {
        for (v, dv) in row.iter_mut().zip(dr) {
            *v += dv;
        }
    }
    out.covered = Some(covered / setup.area_s);
    Ok(true)
}

/// The power of two nearest `1 / length` (a positive, finite length), so that scaling by it
/// is exact.
fn pow2_near_inverse(length: f64) -> f64 {
    let e = length.log2().round().clamp(-1000.0, 1000.0) as i32;
    2f64.powi(-e)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The moments of the unit square `[0, 1]^2` about its corner, from its four vertices:
    /// 1, (1/2, 1/2), (1/3, 1/4, 1/3) (closed form).
    #[test]
    fn moments_of_the_unit_square() {
        let sq = Polygon::from_slice(&[
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(0.0, 1.0),
        ]);
        let m = Moments::of(&sq, 1.0);
        assert!((m.area - 1.0).abs() < 1e-15);
        assert!((m.first - Vector2::new(0.5, 0.5)).norm() < 1e-15);
        for (got, want) in m.second.iter().zip([1.0 / 3.0, 0.25, 1.0 / 3.0]) {
            assert!((got - want).abs() < 1e-15, "{:?}", m.second);
        }
    }

    /// A triangle's barycentric coordinates are one at their vertex and zero at the others,
    /// in either orientation.
    #[test]
    fn barycentric_coordinates_are_nodal() {
        let t = [
            Vector2::new(0.3, -0.2),
            Vector2::new(1.7, 0.4),
            Vector2::new(0.1, 2.0),
        ];
        for tri in [t, [t[0], t[2], t[1]]] {
            let b = barycentric(&tri, 1.0);
            for (i, bi) in b.iter().enumerate() {
                for (k, v) in tri.iter().enumerate() {
                    let want = if i == k { 1.0 } else { 0.0 };
                    assert!((bi.at(v) - want).abs() < 1e-14);
                }
            }
        }
    }
}
