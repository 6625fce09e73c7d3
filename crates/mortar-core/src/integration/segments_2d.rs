//! 2D segment-based integration on line interfaces.

use nalgebra::{Vector2, Vector3};

use super::{default_degree, PairedPoint, PairedRule, SegmentContext};
use crate::element::{ElementRef, ReferenceDomain, MAX_FACE_NODES};
use crate::error::{MortarError, Result};
use crate::geometry::{bracketed_root, invert_line_map, ModelGeometry};
use crate::interface::FaceGeometry;
use crate::multiplier::LmBasis;
use crate::quadrature::{Quadrature, QuadratureRule};
use crate::search::{MasterLine, MasterLineCache};

/// z-component of the cross product of two vectors of the xy-plane.
#[inline]
fn cross2(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Bracketed root finding: relative tolerance and step limit (each step at least halves the
/// bracket, so 200 steps reach round-off from any bracket).
const ROOT_TOL: f64 = 4.0 * f64::EPSILON;
const ROOT_STEPS: usize = 200;

/// How far outside `[-1, 1]` a master coordinate is searched for (reference units).
const MASTER_MARGIN: f64 = 0.5;

pub(super) fn segments_into(
    ctx: &SegmentContext<'_>,
    slave: &FaceGeometry,
    candidates: &[u32],
    degree: Option<u32>,
    out: &mut PairedRule,
) -> Result<()> {
    let centre = Vector2::zeros();
    let (n_s, _) = ctx.projector.direction(slave, &centre);
    // The orientation of the projection: F(xi) = (y - x(xi)) x d(xi) grows with xi when
    // `orientation` is positive.
    let [t, _] = slave.element.tangents(slave.node_coords(), &centre);
    let orientation = -cross2(&t, &n_s).signum();
    let mut line = SlaveLine::new(ctx, slave, orientation);
    let mut covered = 0.0;
    for &m in candidates {
        let master = ctx.master_face(m);
        let n_m = master.element.unit_normal(master.node_coords(), &centre);
        if n_m.dot(&n_s) >= 0.0 {
            // The master line does not face the slave (far side of a thin body, or oriented
            // the wrong way round).
            out.back_facing += 1;
            continue;
        }
        let pushed = out.points.len();
        match pair_points(ctx, &mut line, &master, m, degree, out) {
            Ok(Some(length)) => covered += length,
            Ok(None) => continue,
            Err(e) => {
                out.points.truncate(pushed);
                out.skip(e);
            }
        }
    }
    out.covered = Some(0.5 * covered);
    Ok(())
}

/// The paired points of `slave` against master face `m`, and the length of their overlap in
/// the slave's reference coordinates; `Ok(None)` when they do not overlap.
fn pair_points(
    ctx: &SegmentContext<'_>,
    line: &mut SlaveLine<'_>,
    master: &FaceGeometry,
    m: u32,
    degree: Option<u32>,
    out: &mut PairedRule,
) -> Result<Option<f64>> {
    let slave = line.face;
    let tol = ctx.interface.tolerances();
    // The master's end nodes, projected onto the slave line along the direction field.
    let a = line.project(ctx, &master.nodes[0])?;
    let b = line.project(ctx, &master.nodes[1])?;
    let lo = a.min(b);
    let hi = a.max(b);
    if hi - lo <= tol.clip_area * 2.0 {
        return Ok(None);
    }
    // The dual basis is biorthogonal with respect to the face's own measure: the automatic
    // degree integrates that measure too, so that a covered face's D stays diagonal.
    let deg = degree.unwrap_or_else(|| {
        (default_degree(slave.element, master.element) + line.extra_degree).min(20)
    });
    let rule = QuadratureRule::cached(ReferenceDomain::Line, deg)?;
    let half = 0.5 * (hi - lo);
    let mut values = [0.0; MAX_FACE_NODES];
    let km = master.node_count();
    let mel = master.element;
    // The master nodes as offsets from the slave's first node on the affine path (exact for
    // nodes near the face), as they are otherwise.
    let origin = line.affine.map_or(Vector3::zeros(), |a| a.x0);
    let mut rel = [Vector3::zeros(); MAX_FACE_NODES];
    for (r, y) in rel.iter_mut().zip(&master.nodes[..km]) {
        *r = y - origin;
    }
    // Affine from the type or from the node positions (a straight Line3 with its middle node
    // at the centre): then a point maps back in one exact step.
    let master_affine = master.is_affine();
    for (g, w) in rule.points().iter().zip(rule.weights()) {
        let xi = Vector2::new(lo + half * (g.x + 1.0), 0.0);
        let (x, d) = match &line.affine {
            Some(a) => a.at(AffineLine::s(xi.x)),
            None => (slave.map(&xi), ctx.projector.direction(slave, &xi).0),
        };
        for i in 0..km {
            values[i] = cross2(&(rel[i] - x), &d);
        }
        let failed = |iterations, residual| MortarError::ProjectionFailed {
            face: master.location(),
            point: (origin + x).into(),
            iterations,
            residual,
        };
        let eta = if master_affine {
            invert_line_map(mel, true, &values[..km], 0.0, tol.newton, 1)
                .map_err(|f| failed(f.iterations, f.residual))?
        } else {
            let mut n = [0.0; MAX_FACE_NODES];
            let mut dn = [[0.0; 2]; MAX_FACE_NODES];
            let f = |eta: f64| {
                let e = Vector2::new(eta, 0.0);
                mel.shape_values_into(&e, &mut n[..km]);
                mel.shape_gradients_into(&e, &mut dn[..km]);
                (0..km).fold((0.0, 0.0), |(v, dv), i| {
                    (v + n[i] * values[i], dv + dn[i][0] * values[i])
                })
            };
            let (a, b) = (-1.0 - MASTER_MARGIN, 1.0 + MASTER_MARGIN);
            bracketed_root(f, a, b, ROOT_TOL, ROOT_STEPS)
                .ok_or_else(|| failed(ROOT_STEPS, f64::INFINITY))?
        };
        let det = match &line.affine {
            Some(a) => a.det,
            None => slave.element.jacobian_det(slave.node_coords(), &xi),
        };
        let weight = w * half * det;
        out.points.push(PairedPoint {
            master: m,
            xi_slave: xi,
            xi_master: Vector2::new(eta.clamp(-1.0, 1.0), 0.0),
            weight,
        });
    }
    out.pairs += 1;
    out.cells += 1;
    out.degrees |= 1 << deg;
    Ok(Some(hi - lo))
}

/// Where `y` projects onto the slave line along the direction field, clamped to `[-1, 1]`:
/// the `xi` with `F(xi) = (y - x(xi)) x d(xi) = 0`. `F` is evaluated at both ends first: a
/// root outside `[-1, 1]` gives the nearer end (nothing beyond the face is needed), a root
/// inside is found by Newton safeguarded by bisection, which converges whatever the face's
/// curvature (no extrapolation, no absolute tolerance). `None` when `F` decreases across the
/// face (the direction field turns faster than the face: the projection is not one-to-one
/// there); [`SlaveLine::project`] names that as [`MortarError::ProjectionFailed`]. A plain
/// `f64` comes back in a register, which the fused kernel's loop needs.
fn try_project_onto_slave(
    ctx: &SegmentContext<'_>,
    line: &SlaveLine<'_>,
    y: &Vector3<f64>,
) -> Option<f64> {
    let slave = line.face;
    let g = |xi: f64| {
        if xi == -1.0 {
            line.ends[0].g(y, line.orientation)
        } else if xi == 1.0 {
            line.ends[1].g(y, line.orientation)
        } else {
            LinePoint::at(ctx, slave, xi).g(y, line.orientation)
        }
    };
    if let Some(end) = root_beyond_ends(g(-1.0).0, g(1.0).0)? {
        return Some(end);
    }
    if let Some(xi) = line
        .affine
        .as_ref()
        .and_then(|a| a.root(y, line.orientation))
    {
        return Some(xi);
    }
    bracketed_root(g, -1.0, 1.0, ROOT_TOL, ROOT_STEPS)
}

/// What `orientation F` at the ends of the slave line, `ga` at `-1` and `gb` at `1`, says of
/// its root: `None` where it is not finite or decreases across the face (the projection is
/// not one-to-one there), `Some(Some(end))` where the root lies at or beyond that end (the
/// point projects onto it), `Some(None)` where it lies inside.
#[inline]
fn root_beyond_ends(ga: f64, gb: f64) -> Option<Option<f64>> {
    if !(ga.is_finite() && gb.is_finite()) || (ga > 0.0 && gb < 0.0) {
        None
    } else if ga >= 0.0 {
        Some(Some(-1.0))
    } else if gb <= 0.0 {
        Some(Some(1.0))
    } else {
        Some(None)
    }
}

/// Whether the slave line `face` and the projector's direction field on it are both affine
/// in the reference coordinate (so that [`AffineLine`] describes them).
fn is_affine_line(ctx: &SegmentContext<'_>, face: &FaceGeometry) -> bool {
    face.element.is_affine()
        && face.element.shape_degree() == 1
        && ctx
            .projector
            .fast_paths()
            .is_some_and(|f| f.direction_is_affine(face))
}

/// What `F` needs at one point of the slave line: position, tangent, direction and its
/// derivative.
#[derive(Debug, Clone, Copy)]
struct LinePoint {
    x: Vector3<f64>,
    t: Vector3<f64>,
    d: Vector3<f64>,
    dd: Vector3<f64>,
}

impl LinePoint {
    fn at(ctx: &SegmentContext<'_>, slave: &FaceGeometry, xi: f64) -> Self {
        let xi = Vector2::new(xi, 0.0);
        let x = slave.map(&xi);
        let [t, _] = slave.element.tangents(slave.node_coords(), &xi);
        let (d, dd) = ctx.projector.direction(slave, &xi);
        Self { x, t, d, dd: dd[0] }
    }

    /// `orientation F` at this point for the point `y`, and its derivative.
    #[inline]
    fn g(&self, y: &Vector3<f64>, orientation: f64) -> (f64, f64) {
        let r = y - self.x;
        let f = cross2(&r, &self.d);
        let df = -cross2(&self.t, &self.d) + cross2(&r, &self.dd);
        (orientation * f, orientation * df)
    }
}

/// Master nodes remembered per slave face: neighbouring master lines share a node, so
/// each node is projected once rather than twice.
const REMEMBERED: usize = 4;

/// A slave line set up for projecting master nodes onto it: its ends evaluated once (every
/// projection starts there) and the last few projections remembered. Both give the bits of
/// the projection done from scratch.
struct SlaveLine<'a> {
    face: &'a FaceGeometry,
    orientation: f64,
    ends: [LinePoint; 2],
    /// The line and the direction as affine functions of `xi`, when both are
    /// ([`AffineLine`]).
    affine: Option<AffineLine>,
    /// The degree added to the automatic one for the face's Jacobian
    /// ([`FaceGeometry::jacobian_extra_degree`]): a curved Line3's is not a polynomial.
    extra_degree: u32,
    last: arrayvec::ArrayVec<([u64; 3], f64), REMEMBERED>,
}

/// An affine slave line with an affine direction field, written from its first end `x0`:
/// `x = x0 + s e`, `d = d0 + s dd` with `s = (xi + 1) / 2` in `[0, 1]`. Then
/// `F = (y - x) x d` is a quadratic in `s`, whose root is found in closed form. Every point is
/// handled by its offset from `x0` (`y - x0` is exact for a point near the face), so rounding
/// errors are relative to the face's length, not to the coordinates' magnitude.
#[derive(Debug, Clone, Copy)]
struct AffineLine {
    x0: Vector3<f64>,
    e: Vector3<f64>,
    d0: Vector3<f64>,
    dd: Vector3<f64>,
    /// The Jacobian determinant (constant).
    det: f64,
}

impl AffineLine {
    /// The line of `face` from the positions and directions `(x, d)` at its ends.
    fn new(face: &FaceGeometry, [(x0, d0), (x1, d1)]: [(Vector3<f64>, Vector3<f64>); 2]) -> Self {
        Self {
            x0,
            e: x1 - x0,
            d0,
            dd: d1 - d0,
            det: face
                .element
                .jacobian_det(face.node_coords(), &Vector2::zeros()),
        }
    }

    /// `s` of the reference coordinate `xi`.
    #[inline]
    fn s(xi: f64) -> f64 {
        0.5 * (xi + 1.0)
    }

    /// The offset from `x0` of the point at `s`, and the direction there.
    #[inline]
    fn at(&self, s: f64) -> (Vector3<f64>, Vector3<f64>) {
        (self.e * s, self.d0 + self.dd * s)
    }

    /// The root in `[-1, 1]` (as `xi`) of `orientation F` for the point `y`, known to change
    /// sign from negative at `-1` to positive at `1` (so exactly one root lies between): the
    /// quadratic `A + B s + C s^2` solved by the cancellation-free formula. `None` if rounding
    /// put the root out of reach (the caller then iterates).
    fn root(&self, y: &Vector3<f64>, orientation: f64) -> Option<f64> {
        let r = y - self.x0;
        let a = orientation * cross2(&r, &self.d0);
        let b = orientation * (cross2(&r, &self.dd) - cross2(&self.e, &self.d0));
        let c = -orientation * cross2(&self.e, &self.dd);
        let s = if c == 0.0 {
            -a / b
        } else {
            let disc = (b * b - 4.0 * a * c).max(0.0);
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            // The two roots are q / c and a / q; the one sought is where F increases.
            let (r1, r2) = (q / c, a / q);
            let slope = |x: f64| b + 2.0 * c * x;
            let inside = |x: f64| x.is_finite() && (0.0..=1.0).contains(&x);
            match (inside(r1), inside(r2)) {
                (true, false) => r1,
                (false, true) => r2,
                (true, true) if slope(r1) >= slope(r2) => r1,
                (true, true) => r2,
                (false, false) => return None,
            }
        };
        s.is_finite().then(|| (2.0 * s - 1.0).clamp(-1.0, 1.0))
    }
}

impl<'a> SlaveLine<'a> {
    fn new(ctx: &SegmentContext<'_>, face: &'a FaceGeometry, orientation: f64) -> Self {
        let ends = [
            LinePoint::at(ctx, face, -1.0),
            LinePoint::at(ctx, face, 1.0),
        ];
        let affine =
            is_affine_line(ctx, face).then(|| AffineLine::new(face, ends.map(|p| (p.x, p.d))));
        Self {
            face,
            orientation,
            ends,
            affine,
            extra_degree: face.jacobian_extra_degree(),
            last: Default::default(),
        }
    }

    /// [`try_project_onto_slave`], remembered for the last few points (by the bits of their
    /// coordinates).
    ///
    /// # Errors
    /// [`MortarError::ProjectionFailed`] where the projection is not one-to-one.
    fn project(&mut self, ctx: &SegmentContext<'_>, y: &Vector3<f64>) -> Result<f64> {
        self.try_project(ctx, y)
            .ok_or_else(|| MortarError::ProjectionFailed {
                face: self.face.location(),
                point: (*y).into(),
                iterations: 0,
                residual: f64::INFINITY,
            })
    }

    /// [`project`](Self::project) without the error (`None` where it fails).
    #[inline]
    fn try_project(&mut self, ctx: &SegmentContext<'_>, y: &Vector3<f64>) -> Option<f64> {
        let key = [y.x.to_bits(), y.y.to_bits(), y.z.to_bits()];
        if let Some(&(_, xi)) = self.last.iter().find(|(k, _)| *k == key) {
            return Some(xi);
        }
        let xi = try_project_onto_slave(ctx, self, y)?;
        if self.last.is_full() {
            self.last.remove(0);
        }
        self.last.push((key, xi));
        Some(xi)
    }
}

/// The slave line of [`fused_line_face`]: the affine line and direction field of
/// [`SlaveLine`] (the same calls on the same numbers), without what only the bracketed root
/// needs (the tangents and the direction's derivative at the ends), and the projections of
/// the last few master nodes remembered by their column in M (a node's column names it as
/// its coordinates do). A projection that [`SlaveLine`] would find by the bracketed root
/// (rounding put the closed-form root out of reach) is `None` here: the face then goes to
/// the general path.
struct FusedLine {
    orientation: f64,
    /// Position and direction at the ends.
    ends: [(Vector3<f64>, Vector3<f64>); 2],
    affine: AffineLine,
    /// `(column, xi)` of the last projections, `u32::MAX` where none, filled round robin.
    last: [(u32, f64); REMEMBERED],
    next: usize,
}

impl FusedLine {
    /// `None` where the line or its direction field is not affine.
    fn new(ctx: &SegmentContext<'_>, face: &FaceGeometry, orientation: f64) -> Option<Self> {
        if !is_affine_line(ctx, face) {
            return None;
        }
        let end = |xi: f64| {
            let xi = Vector2::new(xi, 0.0);
            (face.map(&xi), ctx.projector.direction(face, &xi).0)
        };
        let ends = [end(-1.0), end(1.0)];
        Some(Self {
            orientation,
            ends,
            affine: AffineLine::new(face, ends),
            last: [(u32::MAX, 0.0); REMEMBERED],
            next: 0,
        })
    }

    /// [`try_project_onto_slave`] of the master node `y` in column `col` on the affine path,
    /// remembered by `col`.
    #[inline]
    fn project(&mut self, y: &Vector3<f64>, col: u32) -> Option<f64> {
        if let Some(&(_, xi)) = self.last.iter().find(|(c, _)| *c == col) {
            return Some(xi);
        }
        let g = |(x, d): &(Vector3<f64>, Vector3<f64>)| self.orientation * cross2(&(y - x), d);
        let xi = match root_beyond_ends(g(&self.ends[0]), g(&self.ends[1]))? {
            Some(end) => end,
            None => self.affine.root(y, self.orientation)?,
        };
        self.last[self.next] = (col, xi);
        self.next = (self.next + 1) % REMEMBERED;
        Some(xi)
    }
}

/// Whether `element` is the two-node line with the linear Lagrange shape functions
/// `N_0 = (1 - xi) / 2`, `N_1 = (1 + xi) / 2` (checked bit for bit at a few points, so that
/// [`fused_line_face`] may use them in closed form): straight (affine), of shape degree one.
pub(crate) fn is_linear_line(element: ElementRef) -> bool {
    if element.node_count() != 2
        || element.domain() != ReferenceDomain::Line
        || !element.is_affine()
        || element.shape_degree() != 1
    {
        return false;
    }
    let mut n = [0.0; 2];
    let mut g = [[0.0; 2]; 2];
    [-1.0, -0.3, 0.0, 0.7, 1.0].iter().all(|&xi| {
        let p = Vector2::new(xi, 0.0);
        element.shape_values_into(&p, &mut n);
        element.shape_gradients_into(&p, &mut g);
        n == [0.5 * (1.0 - xi), 0.5 * (1.0 + xi)] && g[0][0] == -0.5 && g[1][0] == 0.5
    })
}

/// Adds one point of a pair of two-node linear lines, at slave coordinate `xi` and master
/// coordinate `eta`, to D's block `d` and the pair's M block `m`: `weight Phi_j N_k^s` and
/// `weight Phi_j N_l^m`, `Phi = basis N^s` (the coupling's integration of a paired point, in
/// its order of operations).
#[inline(always)]
pub(crate) fn add_line_point(
    basis: &LmBasis,
    weight: f64,
    xi: f64,
    eta: f64,
    d: &mut [[f64; 2]; 2],
    m: &mut [[f64; 2]; 2],
) {
    let ns = [0.5 * (1.0 - xi), 0.5 * (1.0 + xi)];
    let phi = if basis.identity {
        ns
    } else {
        let mut phi = [0.0; 2];
        for (j, p) in phi.iter_mut().enumerate() {
            *p = 0.0 + basis.a[j][0] * ns[0] + basis.a[j][1] * ns[1];
        }
        phi
    };
    let nm = [0.5 * (1.0 - eta), 0.5 * (1.0 + eta)];
    for j in 0..2 {
        let wp = weight * phi[j];
        for k in 0..2 {
            d[j][k] += wp * ns[k];
        }
        for l in 0..2 {
            m[j][l] += wp * nm[l];
        }
    }
}

/// What [`fused_line_face`] computes for one slave face.
#[derive(Debug, Clone, Default)]
pub(crate) struct LineFace {
    /// `D[j][k] = int Phi_j N_k^s` over the face's overlap.
    pub d: [[f64; 2]; 2],
    /// The master columns the face meets, in the order first met.
    pub cols: Vec<u32>,
    /// Their M values, one per slave node: `M[j][col] = int Phi_j N_col^m`.
    pub vals: Vec<[f64; 2]>,
    /// Master faces with a non-empty overlap.
    pub pairs: u32,
    /// Candidates facing away from the slave.
    pub back_facing: u32,
    /// The quadrature degree used.
    pub degree: u32,
}

/// One slave face of two-node linear lines against its candidates (two-node linear lines, as
/// slots of `ctx.masters`, read through `lines`), segmented and integrated in one loop: the work of
/// [`segments_into`] followed by the coupling's integration of the paired points, the same
/// operations on the same numbers, without the points in between. The caller checks that the
/// faces are linear lines ([`is_linear_line`]).
///
/// Returns `false`, leaving the face to the general path, when anything needs more than the
/// clean case: the direction field is not affine, a projection fails, or the candidates
/// cover less than `1 - coverage` of the face (no overlap at all, a face at the end of the
/// master, or a candidate the caller's search did not give) or more than `1 + coverage` (two
/// master layers over it, which the general path reports).
///
/// # Errors
/// A quadrature rule that cannot be built for `degree`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn fused_line_face(
    ctx: &SegmentContext<'_>,
    slave: &FaceGeometry,
    candidates: &[u32],
    degree: Option<u32>,
    basis: &LmBasis,
    geometry: ModelGeometry,
    lines: &mut MasterLineCache,
    out: &mut LineFace,
) -> Result<bool> {
    out.d = [[0.0; 2]; 2];
    out.cols.clear();
    out.vals.clear();
    out.pairs = 0;
    out.back_facing = 0;
    let tol = ctx.interface.tolerances();
    let centre = Vector2::zeros();
    let (n_s, _) = ctx.projector.direction(slave, &centre);
    let [t, _] = slave.element.tangents(slave.node_coords(), &centre);
    let orientation = -cross2(&t, &n_s).signum();
    let Some(mut line) = FusedLine::new(ctx, slave, orientation) else {
        return Ok(false);
    };
    let affine = line.affine;
    let deg = degree.unwrap_or_else(|| default_degree(slave.element, slave.element));
    let rule = QuadratureRule::cached(ReferenceDomain::Line, deg)?;
    out.degree = deg;
    let mut covered = 0.0;
    // D in registers, not through `out` (which the compiler must assume aliased).
    let mut dl = [[0.0; 2]; 2];
    for &m in candidates {
        let &MasterLine {
            nodes: y,
            normal: n_m,
            cols,
            ..
        } = lines.get(ctx.interface, ctx.masters, m);
        if n_m.dot(&n_s) >= 0.0 {
            out.back_facing += 1;
            continue;
        }
        let (Some(a), Some(b)) = (line.project(&y[0], cols[0]), line.project(&y[1], cols[1]))
        else {
            return Ok(false);
        };
        let (lo, hi) = (a.min(b), a.max(b));
        if hi - lo <= tol.clip_area * 2.0 {
            continue;
        }
        let half = 0.5 * (hi - lo);
        let rel = [y[0] - affine.x0, y[1] - affine.x0];
        let mut mb = [[0.0; 2]; 2];
        for (g, w) in rule.points().iter().zip(rule.weights()) {
            let xi = lo + half * (g.x + 1.0);
            let (x, d) = affine.at(AffineLine::s(xi));
            let v = [cross2(&(rel[0] - x), &d), cross2(&(rel[1] - x), &d)];
            // `invert_line_map` of the linear line: one Newton step from 0, in its order.
            let r = -0.0 + v[0] * 0.5 + v[1] * 0.5;
            let slope = 0.0 + v[0] * -0.5 + v[1] * 0.5;
            if slope == 0.0 || !slope.is_finite() {
                return Ok(false);
            }
            let eta = (0.0 - r / slope).clamp(-1.0, 1.0);
            let mut weight = w * half * affine.det;
            if geometry.is_axisymmetric() {
                weight *= geometry.weight(&slave.map(&Vector2::new(xi, 0.0)));
            }
            add_line_point(basis, weight, xi, eta, &mut dl, &mut mb);
        }
        for (l, &c) in cols.iter().enumerate() {
            let at = match out.cols.iter().position(|&k| k == c) {
                Some(at) => at,
                None => {
                    out.cols.push(c);
                    out.vals.push([0.0; 2]);
                    out.cols.len() - 1
                }
            };
            for j in 0..2 {
                out.vals[at][j] += mb[j][l];
            }
        }
        out.pairs += 1;
        covered += hi - lo;
    }
    out.d = dl;
    // Covered once, to the tolerance: less is a face the walk's candidates may not settle
    // (the general path looks again), more is master faces overlapping over it, which the
    // general path reports.
    Ok(out.pairs > 0 && (1.0 - 0.5 * covered).abs() <= tol.coverage)
}
