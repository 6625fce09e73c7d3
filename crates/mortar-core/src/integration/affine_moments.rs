//! The mortar integrals of flat quads by the moments of their clip polygons (3D).
//!
//! Where a slave face is a linear triangle or a bilinear quad whose map into its auxiliary
//! plane is affine (a flat parallelogram), and every master face it meets is a linear triangle
//! or a bilinear quad whose projection into that plane is affine, every integrand of D and M
//! is a polynomial of degree at most 4 in the slave's reference coordinates `r = (xi, eta)`:
//! the slave's shape functions, and the multipliers (their combinations), lie in
//! `P2 = {1, xi, eta, xi^2, xi eta, eta^2}` of `r`; a master's shape functions lie in `P2` of
//! its own reference coordinates, which are an affine function of `r` (the composition of two
//! affine maps through the plane), hence in `P2` of `r`. Each pair's integrals are therefore
//! combinations of the clip polygon's fifteen moments `int u^a v^b` (`a + b <= 4`) about its
//! first vertex (`r = o + (u, v)`), which vertex formulas on the polygon's fan of triangles
//! give exactly (to round-off); the slave's functions are re-expanded about that vertex and
//! the master's coordinates taken from there, so that a pair much smaller than the slave face
//! keeps its relative accuracy. This replaces the strategy's points on each clip triangle
//! (their mapping back to both faces through the inverse maps and the shape functions
//! evaluated at each) by one pass over the polygon's vertices and a few dozen products per
//! pair: the integrals of any exact quadrature, to round-off.
//!
//! Triangles against triangles keep the vertex formulas of [`closed_form`](super::closed_form)
//! (degree 2, cheaper). The coupling runs this where the strategy says it is the exact
//! segmentation of [`SegmentBased`](super::SegmentBased), with a degree that integrates these
//! integrands exactly ([`closed_form::applies`](super::closed_form::applies)).

use nalgebra::{Matrix2, Vector2};

use super::closed_form::{ClosedForm, ClosedFormScratch};
use super::segments_3d::SlavePlane;
use super::{default_degree, PairedRule, SegmentContext};
use crate::element::flat::FlatShape;
use crate::element::{ElementRef, MAX_FACE_NODES};
use crate::error::Result;
use crate::geometry::{PlanarMap, Polygon, MAX_POLYGON_VERTICES};
use crate::interface::FaceGeometry;
use crate::multiplier::LmBasis;
use crate::search::MasterCorners;

/// The monomials `xi^a eta^b` with `a + b <= 4`, the one of `(a, b)` at
/// `(a + b)(a + b + 1) / 2 + b`: `1; xi, eta; xi^2, xi eta, eta^2; xi^3, ...; ..., eta^4`.
const MONOMIALS: usize = 15;

/// The first six monomials: a basis of `P2`.
const P2: usize = 6;

/// A polynomial of `P2` by its coefficients on `1, xi, eta, xi^2, xi eta, eta^2`.
type Poly = [f64; P2];

/// The exponents of the `P2` monomials.
const EXPONENTS: [(usize, usize); P2] = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)];

/// `PRODUCT[i][j]`: the monomial of the product of `P2` monomials `i` and `j`.
const PRODUCT: [[usize; P2]; P2] = {
    let mut t = [[0; P2]; P2];
    let mut i = 0;
    while i < P2 {
        let mut j = 0;
        while j < P2 {
            let (a, b) = (
                EXPONENTS[i].0 + EXPONENTS[j].0,
                EXPONENTS[i].1 + EXPONENTS[j].1,
            );
            t[i][j] = (a + b) * (a + b + 1) / 2 + b;
            j += 1;
        }
        i += 1;
    }
    t
};

/// The `P2` monomials a slave face's shape functions (and multipliers) may use: `1, xi, eta,
/// xi eta` (a triangle's coefficient of `xi eta` is zero).
const SLAVE_TERMS: [usize; 4] = [0, 1, 2, 4];

/// The shape functions of `element` (of this shape), node by node, in `P2` of its
/// reference coordinates.
fn shape_polynomials(shape: FlatShape, element: ElementRef) -> [Poly; 4] {
    match shape {
        FlatShape::Triangle => [
            [1.0, -1.0, -1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
            [0.0; P2],
        ],
        FlatShape::Quad => {
            let c = element.node_reference_coords();
            std::array::from_fn(|k| {
                let (x, y) = (c[k][0], c[k][1]);
                [0.25, 0.25 * x, 0.25 * y, 0.0, 0.25 * x * y, 0.0]
            })
        }
    }
}

/// `p(c + B r)` as a polynomial of `r`, for `p` in `P2` of `s`.
fn compose(p: &Poly, c: &Vector2<f64>, b: &Matrix2<f64>) -> Poly {
    let sx = [c.x, b[(0, 0)], b[(0, 1)]];
    let sy = [c.y, b[(1, 0)], b[(1, 1)]];
    if p[3] == 0.0 && p[4] == 0.0 && p[5] == 0.0 {
        // Affine (a triangle's shape functions): no products.
        return [
            p[0] + p[1] * sx[0] + p[2] * sy[0],
            p[1] * sx[1] + p[2] * sy[1],
            p[1] * sx[2] + p[2] * sy[2],
            0.0,
            0.0,
            0.0,
        ];
    }
    // The product of two affine functions `u0 + ux xi + uy eta`.
    let mul = |u: [f64; 3], v: [f64; 3]| -> Poly {
        [
            u[0] * v[0],
            u[0] * v[1] + u[1] * v[0],
            u[0] * v[2] + u[2] * v[0],
            u[1] * v[1],
            u[1] * v[2] + u[2] * v[1],
            u[2] * v[2],
        ]
    };
    let terms: [Poly; P2] = [
        [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [sx[0], sx[1], sx[2], 0.0, 0.0, 0.0],
        [sy[0], sy[1], sy[2], 0.0, 0.0, 0.0],
        mul(sx, sx),
        mul(sx, sy),
        mul(sy, sy),
    ];
    let mut out = [0.0; P2];
    for (&coef, t) in p.iter().zip(&terms) {
        if coef != 0.0 {
            for (o, v) in out.iter_mut().zip(t) {
                *o += coef * v;
            }
        }
    }
    out
}

/// Adds the moments `int (r - v_0)^alpha dr` of the polygon of vertices `v` about its first
/// vertex to `out`, signed by its orientation (positive counter-clockwise), summed over the fan
/// of triangles from that vertex in closed form: all fifteen with `ALL`, else only those of
/// the products of `1, xi, eta, xi eta` with themselves and with `1, xi, eta` (the integrands
/// against a triangle master: `xi^3`, `eta^3` and the quartics but `xi^2 eta^2` stay zero).
///
/// For the triangle `0, a, b` of doubled signed area `J = a x b`, the map `r = s a + t b` of
/// the reference triangle gives `int x^i y^j = J int (s a_x + t b_x)^i (s a_y + t b_y)^j` and
/// `int s^k t^l = k! l! / (k + l + 2)!` over the reference triangle (C. Steger, "On the
/// calculation of arbitrary moments of polygons", TU Munich FGBV-96-05, 1996): for the
/// quartics, `(12 c_0 + 3 c_1 + 2 c_2 + 3 c_3 + 12 c_4) / 360` of the coefficients `c_k` of
/// `s^(4-k) t^k`. A degree-4 rule takes six points per triangle, about 300 flops for the
/// nine moments a triangle master needs; these take about 84.
fn add_moments<const ALL: bool>(v: &[Vector2<f64>], out: &mut [f64; MONOMIALS]) {
    let o = v[0];
    for w in v[1..].windows(2) {
        let (a, b) = (w[0] - o, w[1] - o);
        let (ax, ay, bx, by) = (a.x, a.y, b.x, b.y);
        let j = ax * by - ay * bx;
        let (ax2, bx2, axbx) = (ax * ax, bx * bx, ax * bx);
        let (ay2, by2, ayby) = (ay * ay, by * by, ay * by);
        // The mixed products: `p = a_x a_y`, `q = b_x b_y`, `r = a_x b_y + b_x a_y`.
        let (p, q, r) = (ax * ay, bx * by, ax * by + bx * ay);
        out[0] += j * 0.5;
        out[1] += j * (ax + bx) / 6.0;
        out[2] += j * (ay + by) / 6.0;
        out[3] += j * (ax2 + axbx + bx2) / 12.0;
        out[4] += j * (2.0 * (p + q) + r) / 24.0;
        out[5] += j * (ay2 + ayby + by2) / 12.0;
        // x^2 y and x y^2.
        out[7] +=
            j * (ay * (3.0 * ax2 + 2.0 * axbx + bx2) + by * (ax2 + 2.0 * axbx + 3.0 * bx2)) / 60.0;
        out[8] +=
            j * (ax * (3.0 * ay2 + 2.0 * ayby + by2) + bx * (ay2 + 2.0 * ayby + 3.0 * by2)) / 60.0;
        // x^2 y^2: c = p^2, 2 p r, r^2 + 2 p q, 2 q r, q^2.
        out[12] +=
            j * (12.0 * (p * p + q * q) + 6.0 * r * (p + q) + 2.0 * r * r + 4.0 * p * q) / 360.0;
        if ALL {
            // x^3, y^3: the complete sums of degree 3 over 20.
            out[6] += j * (ax + bx) * (ax2 + bx2) / 20.0;
            out[9] += j * (ay + by) * (ay2 + by2) / 20.0;
            // x^4, y^4: the complete sums of degree 4 over 30.
            out[10] += j * (ax2 * ax2 + ax2 * axbx + ax2 * bx2 + axbx * bx2 + bx2 * bx2) / 30.0;
            out[14] += j * (ay2 * ay2 + ay2 * ayby + ay2 * by2 + ayby * by2 + by2 * by2) / 30.0;
            // x^3 y: c = ax^3 ay, ax^3 by + 3 ax^2 bx ay, 3 ax bx (ax by + bx ay),
            // 3 ax bx^2 by + bx^3 ay, bx^3 by.
            let c1 = ax2 * (ax * by + 3.0 * bx * ay);
            let c3 = bx2 * (3.0 * ax * by + bx * ay);
            out[11] += j * (12.0 * (ax2 * p + bx2 * q) + 3.0 * (c1 + c3) + 6.0 * axbx * r) / 360.0;
            // x y^3, by symmetry.
            let c1 = ay2 * (ay * bx + 3.0 * by * ax);
            let c3 = by2 * (3.0 * ay * bx + by * ax);
            out[13] += j * (12.0 * (ay2 * p + by2 * q) + 3.0 * (c1 + c3) + 6.0 * ayby * r) / 360.0;
        }
    }
}

/// `p(o + u)` as a polynomial of `u`, for `p` in the span of `1, xi, eta, xi eta` (the
/// [`SLAVE_TERMS`]; so is the result).
#[inline]
fn shift(p: &Poly, o: &Vector2<f64>) -> Poly {
    [
        p[0] + p[1] * o.x + p[2] * o.y + p[4] * o.x * o.y,
        p[1] + p[4] * o.y,
        p[2] + p[4] * o.x,
        0.0,
        p[4],
        0.0,
    ]
}

/// The arguments of [`pair_products`]: the clip polygon's moments about its first vertex
/// `o`, the multipliers and the slave's shape functions about `o`, the master's shape
/// functions in `u`, the area factor, the pair's M block (out) and the face's D (added to).
type Products<'a> = (
    &'a [f64; MONOMIALS],
    &'a [Poly; 4],
    &'a [Poly; 4],
    &'a [Poly; 4],
    f64,
    &'a mut [f64; 16],
    &'a mut [[f64; 4]; 4],
);

/// One pair's M block (`KS x KM`, row-major) and its terms of D, for a slave of `KS` nodes
/// and a master of `KM` whose shape functions use the first `USED` monomials of `P2`: fixed
/// counts, so that the loops unroll. `w[j][g] = int Phi_j u^g` for the `P2` monomials `g`
/// (the master's shape functions use the first `USED`, the slave's `1, xi, eta, xi eta`),
/// then each entry a dot product. (Against a triangle, `w[j][3]` and `w[j][5]` read moments
/// left at zero and are not used.)
#[inline(always)]
fn pair_products<const KS: usize, const KM: usize, const USED: usize>(
    (mom, phi_o, ns_o, nm, scale, block, dface): Products<'_>,
) {
    let mut gathered = [[0.0; P2]; 4];
    for (row, &a) in gathered.iter_mut().zip(&SLAVE_TERMS) {
        for (v, &k) in row.iter_mut().zip(&PRODUCT[a]) {
            *v = mom[k];
        }
    }
    let mut w = [[0.0; P2]; KS];
    for (wj, p) in w.iter_mut().zip(phi_o) {
        for (t, &a) in SLAVE_TERMS.iter().enumerate() {
            for (wg, v) in wj.iter_mut().zip(&gathered[t]) {
                *wg += p[a] * v;
            }
        }
    }
    for (j, wj) in w.iter().enumerate() {
        for (l, n) in nm.iter().enumerate().take(KM) {
            let s: f64 = (0..USED).map(|g| n[g] * wj[g]).sum();
            block[j * KM + l] = scale * s;
        }
        for (k, n) in ns_o.iter().enumerate().take(KS) {
            let s: f64 = SLAVE_TERMS.iter().map(|&t| n[t] * wj[t]).sum();
            dface[j][k] += s;
        }
    }
}

/// One pair's M block, kept until the face is known to be integrated here.
pub(crate) type PendingBlock = ([u32; 4], usize, [f64; 16]);

/// D and M of a slave face of shape `slave_shape` against its `candidates` (as slots of
/// `ctx.masters`, read through `masters`), for the closed form `form`, by the moments of the
/// clip polygons: D added to `d`, each master face's `ks x km` M block (row-major) given to
/// `add_m` with the columns of its nodes, in candidate order; `out` gets the counts the
/// strategy would give (pairs, back-facing candidates, the covered fraction, the degree the
/// strategy would have used; one cell per clip polygon) and no points. `pending` is a buffer
/// (its contents are replaced).
///
/// Returns `false`, with nothing added, when the slave face is not affine in its plane, a
/// master face it overlaps is neither a linear triangle nor a bilinear quad, or that master
/// face's projection is not affine: the strategy then takes the face.
///
/// # Errors
/// As the strategy's segmentation: a slave face with a zero projection direction or one that
/// turns against it.
#[allow(clippy::too_many_arguments)]
pub(crate) fn affine_moments_into(
    ctx: &SegmentContext<'_>,
    slave: &FaceGeometry,
    slave_shape: FlatShape,
    candidates: &[u32],
    form: &ClosedForm,
    basis: &LmBasis,
    d: &mut [[f64; MAX_FACE_NODES]; MAX_FACE_NODES],
    scratch: &mut ClosedFormScratch,
    pending: &mut Vec<PendingBlock>,
    mut add_m: impl FnMut(&[u32], &[f64]),
    out: &mut PairedRule,
) -> Result<bool> {
    out.clear();
    pending.clear();
    let ClosedFormScratch { masters, plane } = scratch;
    let setup = SlavePlane::reuse(plane, ctx, slave)?;
    if setup.in_reference {
        return Ok(false);
    }
    let Some((centre, x_c, inv)) = setup.slave_map.affine_parts() else {
        return Ok(false);
    };
    let Some(jac) = inv.try_inverse() else {
        return Ok(false);
    };
    // Plane area per reference area, times the face's area element per the plane's.
    let scale = jac.determinant() * setup.measure;
    let ks = slave.node_count();
    let ns = shape_polynomials(slave_shape, slave.element);
    let phi = multiplier_polynomials(basis, &ns, ks);
    let mut mp = [Vector2::zeros(); MAX_FACE_NODES];
    let mut clip = Polygon::default();
    let mut dface = [[0.0; 4]; 4];
    let mut covered = 0.0;
    for &m in candidates {
        let MasterCorners {
            element,
            count,
            nodes,
            cols,
        } = masters.get(ctx.interface, ctx.masters, m);
        let bf = &mut out.back_facing;
        let Some((mel, km, area)) =
            setup.clip_face(*element, &nodes[..*count], &mut mp, &mut clip, bf)
        else {
            continue;
        };
        let Some(mshape) = form.shape(mel) else {
            return Ok(false);
        };
        // The master's reference coordinates `s = mc + minv (p - mx)`.
        let Some((mc, mx, minv)) = master_coordinates(mshape, mel, &mp[..km]) else {
            return Ok(false);
        };
        // Everything about the clip polygon's first vertex `p0` (`o` in the slave's reference
        // coordinates): with `r = o + u`, the moments are those of `u`, small where the pair
        // is small, and the master's coordinates `s = s0 + B u` start from `s0`, O(1), rather
        // than from the slave's origin, where a master face 1000 times smaller than the slave
        // gives coefficients of 1e3 and 1e6 whose sum cancels (M off by 1e-10).
        let p0 = clip.vertices[0];
        let o = centre + inv * (p0 - x_c);
        let b = minv * jac;
        let s0 = mc + minv * (p0 - mx);
        let mut nm = [[0.0; P2]; 4];
        for (n, poly) in nm.iter_mut().zip(shape_polynomials(mshape, mel)).take(km) {
            *n = compose(&poly, &s0, &b);
        }
        let mut uv = [Vector2::zeros(); MAX_POLYGON_VERTICES];
        for (u, p) in uv.iter_mut().zip(&clip.vertices) {
            *u = inv * (p - p0);
        }
        let uv = &uv[..clip.vertices.len()];
        let mut mom = [0.0; MONOMIALS];
        match mshape {
            FlatShape::Triangle => add_moments::<false>(uv, &mut mom),
            FlatShape::Quad => add_moments::<true>(uv, &mut mom),
        }
        // The multipliers and the slave's shape functions about `o`.
        let phi_o = phi.map(|p| shift(&p, &o));
        let ns_o = if basis.identity {
            phi_o
        } else {
            ns.map(|p| shift(&p, &o))
        };
        let mut block = [0.0; 16];
        let products = (&mom, &phi_o, &ns_o, &nm, scale, &mut block, &mut dface);
        match (slave_shape, mshape) {
            (FlatShape::Quad, FlatShape::Triangle) => pair_products::<4, 3, 3>(products),
            (FlatShape::Quad, FlatShape::Quad) => pair_products::<4, 4, P2>(products),
            (FlatShape::Triangle, FlatShape::Triangle) => pair_products::<3, 3, 3>(products),
            (FlatShape::Triangle, FlatShape::Quad) => pair_products::<3, 4, P2>(products),
        }
        pending.push((*cols, km, block));
        out.pairs += 1;
        out.cells += 1;
        out.degrees |= 1
            << form
                .rule
                .degree
                .unwrap_or_else(|| default_degree(slave.element, mel));
        covered += area;
    }
    for (cols, km, block) in pending.iter() {
        add_m(&cols[..*km], &block[..ks * km]);
    }
    for (row, dr) in d.iter_mut().zip(&dface).take(ks) {
        for (v, dv) in row.iter_mut().zip(dr).take(ks) {
            *v += scale * dv;
        }
    }
    out.covered = Some(covered / setup.area_s);
    Ok(true)
}

/// The multipliers as polynomials, `Phi_j = sum_k a_jk N_k` of the slave's shape
/// polynomials `ns` (the first `ks` of them), or `ns` themselves for a standard basis.
fn multiplier_polynomials(basis: &LmBasis, ns: &[Poly; 4], ks: usize) -> [Poly; 4] {
    if basis.identity {
        return *ns;
    }
    std::array::from_fn(|j| {
        let mut p = [0.0; P2];
        for (k, n) in ns.iter().enumerate().take(ks) {
            for (pv, nv) in p.iter_mut().zip(n) {
                *pv += basis.a[j][k] * nv;
            }
        }
        p
    })
}

/// The affine map to a master face's reference coordinates from the plane,
/// `s = mc + minv (p - mx)`, of the face of shape `shape` with the nodes `mp` in the plane (a
/// triangle's from its corners: the map of the linear triangle, `p = p0 + [p1 - p0, p2 - p0]
/// s`); `None` where the face is degenerate or its map not affine.
fn master_coordinates(
    shape: FlatShape,
    element: ElementRef,
    mp: &[Vector2<f64>],
) -> Option<(Vector2<f64>, Vector2<f64>, Matrix2<f64>)> {
    match shape {
        FlatShape::Triangle => {
            let e = Matrix2::from_columns(&[mp[1] - mp[0], mp[2] - mp[0]]);
            Some((Vector2::zeros(), mp[0], e.try_inverse()?))
        }
        FlatShape::Quad => PlanarMap::new(element, mp).affine_parts(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::ReferenceDomain;
    use crate::quadrature::{Quadrature, QuadratureRule};

    /// The moments of the unit square `[0, 1]^2` from two fan triangles: `int x^a y^b =
    /// 1 / ((a + 1)(b + 1))` (closed form), for every `a + b <= 4`.
    #[test]
    fn moments_of_the_unit_square() {
        let sq = [
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(0.0, 1.0),
        ];
        let mut m = [0.0; MONOMIALS];
        add_moments::<true>(&sq, &mut m);
        for d in 0..=4usize {
            for b in 0..=d {
                let a = d - b;
                let want = 1.0 / ((a + 1) * (b + 1)) as f64;
                let got = m[d * (d + 1) / 2 + b];
                assert!((got - want).abs() < 1e-15, "x^{a} y^{b}: {got} vs {want}");
            }
        }
    }

    /// The vertex formulas give the moments a degree-4 quadrature rule gives on each fan
    /// triangle (exact for these integrands: the reference), on a skewed pentagon off the
    /// origin and in either orientation; without `ALL`, the moments they leave are zero.
    #[test]
    fn vertex_formulas_match_a_degree_4_rule() {
        let poly = [
            Vector2::new(0.3, -0.2),
            Vector2::new(1.9, 0.1),
            Vector2::new(2.2, 1.3),
            Vector2::new(0.8, 2.1),
            Vector2::new(-0.4, 0.9),
        ];
        let rule = QuadratureRule::cached(ReferenceDomain::Triangle, 4).unwrap();
        for reversed in [false, true] {
            let mut v = poly;
            if reversed {
                v[1..].reverse();
            }
            let o = v[0];
            let mut want = [0.0; MONOMIALS];
            for w in v[1..].windows(2) {
                let (ea, eb) = (w[0] - o, w[1] - o);
                let twice = ea.x * eb.y - ea.y * eb.x;
                for (q, wq) in rule.points().iter().zip(rule.weights()) {
                    let r = ea * q.x + eb * q.y;
                    for d in 0..=4usize {
                        for b in 0..=d {
                            let k = d * (d + 1) / 2 + b;
                            want[k] += wq * twice * r.x.powi((d - b) as i32) * r.y.powi(b as i32);
                        }
                    }
                }
            }
            let mut all = [0.0; MONOMIALS];
            add_moments::<true>(&v, &mut all);
            let mut some = [0.0; MONOMIALS];
            add_moments::<false>(&v, &mut some);
            for k in 0..MONOMIALS {
                let tol = 1e-14 * want[k].abs().max(1.0);
                assert!(
                    (all[k] - want[k]).abs() < tol,
                    "{k}: {} vs {}",
                    all[k],
                    want[k]
                );
                if [6, 9, 10, 11, 13, 14].contains(&k) {
                    assert_eq!(some[k], 0.0, "{k}");
                } else {
                    assert_eq!(some[k], all[k], "{k}");
                }
            }
        }
    }

    /// Composing with an affine map agrees with evaluating at the mapped point.
    #[test]
    fn composition_is_evaluation_at_the_mapped_point() {
        let p: Poly = [0.3, -1.2, 0.7, 2.0, -0.5, 1.1];
        let c = Vector2::new(0.2, -0.4);
        let b = Matrix2::new(1.5, -0.3, 0.25, 0.8);
        let q = compose(&p, &c, &b);
        let eval = |p: &Poly, x: f64, y: f64| {
            p[0] + p[1] * x + p[2] * y + p[3] * x * x + p[4] * x * y + p[5] * y * y
        };
        for (x, y) in [(0.0, 0.0), (1.0, -2.0), (0.37, 0.81)] {
            let s = c + b * Vector2::new(x, y);
            assert!((eval(&q, x, y) - eval(&p, s.x, s.y)).abs() < 1e-13);
        }
    }
}
