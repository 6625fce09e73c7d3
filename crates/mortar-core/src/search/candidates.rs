//! The contact search: BVHs over the master faces' bounding boxes (`MasterTree`), queried with
//! each slave face for its candidate master faces (`Candidates`, sorted, so independent of
//! the thread count).

use std::sync::Arc;

use arrayvec::ArrayVec;
use nalgebra::Vector3;
use rayon::prelude::*;

use super::bvh::{overlaps, union, Box3, BoxTree};
use super::morton::{bounds_of, morton_code};
use super::padding::Padding;
use crate::element::MAX_FACE_NODES;
use crate::interface::{FaceGeometry, Interface, MasterFaces, SpatialDim};

/// Candidate master faces per slave face, in compressed rows: the candidates of slave face `s`
/// are `masters[offsets[s]..offsets[s + 1]]`, ascending.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Candidates {
    /// Row offsets, one more than the slave face count.
    pub offsets: Vec<u32>,
    /// Master face indices.
    pub masters: Vec<u32>,
}

impl Candidates {
    /// The candidates of slave face `s`.
    pub fn of(&self, s: usize) -> &[u32] {
        &self.masters[self.offsets[s] as usize..self.offsets[s + 1] as usize]
    }

    /// Total number of candidate pairs.
    pub fn len(&self) -> usize {
        self.masters.len()
    }

    /// Whether there is no candidate pair.
    pub fn is_empty(&self) -> bool {
        self.masters.is_empty()
    }
}

/// BVHs over the master faces' bounding boxes (inflated where their nodes do not bound the
/// faces, see [`Padding`]), queried one slave face at a time.
///
/// The master faces are cut into slabs of equal width along the longest axis of their
/// bounding box (by first node) and one tree is built per slab, in parallel. Within a slab
/// the faces follow the Morton order of their first nodes (whatever the file's numbering),
/// and each leaf holds up to eight consecutive ones (`LEAF_FACES`); the tree groups the
/// leaves four by four in that order (see `bvh.rs`), and a hit leaf's faces are then tested
/// one by one. A query
/// visits the slabs whose bounds meet its box. The candidates are sorted, so they depend
/// neither on the slab layout nor on the thread count.
pub struct MasterTree {
    slabs: Vec<Slab>,
    planar: bool,
    padding: Padding,
    /// Each slave face's search radius by face index, where the coupling set them one by
    /// one ([`SearchRadius::Nearest`](crate::SearchRadius::Nearest)); else the tolerances'.
    radii: Option<Arc<[f64]>>,
}

struct Slab {
    tree: BoxTree,
    bounds: Box3,
    /// The slot of the slab's first face: the slabs' faces concatenated are the slots.
    first_slot: u32,
    /// The boxes of the slab's faces (slots `first_slot..`; leaf `l` holds the faces
    /// `LEAF_FACES * l..`, up to `LEAF_FACES`), in `f32` rounded outward (conservative, half
    /// the memory), in the slab's `frame`: the per-face test of a hit leaf reads them instead
    /// of the mesh.
    boxes: Vec<[f32; 6]>,
    /// The frame of `boxes`.
    frame: Frame,
}

/// The frame of a slab's `f32` boxes: coordinates relative to the slab's lower corner, in
/// units of the power of two at or above its size. `f32` then keeps a resolution of 1e-7 of
/// the slab whatever the mesh's scale or position: absolute coordinates at 1e100 or 1e-100
/// leave `f32`'s range (every box would become infinite or round to zero, and every face of a
/// hit leaf a candidate). The map is monotone (a subtraction, then an exact product), so a
/// query box taken to the frame meets a face's box there whenever it meets it in space.
#[derive(Debug, Clone, Copy)]
struct Frame {
    origin: Vector3<f64>,
    inverse_unit: f64,
}

impl Frame {
    fn of(bounds: &Box3) -> Self {
        let size = (bounds.1 - bounds.0).amax();
        let inverse_unit = if size > 0.0 && size.is_finite() {
            // 2^-ceil(log2(size)), exact (`powi` of 2 multiplies powers of two).
            2f64.powi(-(size.log2().ceil() as i32))
        } else {
            1.0
        };
        Self {
            origin: bounds.0,
            inverse_unit: if inverse_unit.is_normal() {
                inverse_unit
            } else {
                1.0
            },
        }
    }

    fn apply(&self, b: &Box3) -> Box3 {
        (
            (b.0 - self.origin) * self.inverse_unit,
            (b.1 - self.origin) * self.inverse_unit,
        )
    }
}

/// `b` in `f32`, rounded outward.
fn box_f32(b: &Box3) -> [f32; 6] {
    let down = |x: f64| {
        let v = x as f32;
        if v as f64 > x {
            v.next_down()
        } else {
            v
        }
    };
    let up = |x: f64| {
        let v = x as f32;
        if (v as f64) < x {
            v.next_up()
        } else {
            v
        }
    };
    [
        down(b.0.x),
        down(b.0.y),
        down(b.0.z),
        up(b.1.x),
        up(b.1.y),
        up(b.1.z),
    ]
}

/// Whether `a` meets the `f32` box `b`.
#[inline]
fn overlaps_f32(a: &Box3, b: &[f32; 6], planar: bool) -> bool {
    let dims = if planar { 2 } else { 3 };
    (0..dims).all(|k| a.0[k] <= b[k + 3] as f64 && b[k] as f64 <= a.1[k])
}

/// Slave faces per query of [`MasterTree::candidates_of_group`].
const GROUP: usize = 4;

/// Buffers of [`MasterTree::candidates_of_group`], kept from call to call.
#[derive(Debug, Default)]
pub struct GroupScratch {
    leaves: Vec<u32>,
    per_face: [Vec<u32>; GROUP],
}

/// Master faces per slab, on average.
const SLAB_FACES: usize = 1 << 16;

/// Master faces per BVH leaf. Eight rather than four halves the tree (plane3d at 10^6 slave
/// faces: peak 647 -> 626 MiB) for the same time (its build 0.61 -> 0.51 s, the queries'
/// per-face tests a little longer; cylinder 2.97 -> 2.96-3.05 s); sixteen saves no more.
const LEAF_FACES: usize = 8;

impl Slab {
    /// Pushes to `out` the slots of the faces of leaf `leaf` whose boxes meet `local` (a box
    /// in the slab's frame).
    #[inline]
    fn push_faces_meeting(&self, leaf: u32, local: &Box3, planar: bool, out: &mut Vec<u32>) {
        let first = leaf as usize * LEAF_FACES;
        let last = (first + LEAF_FACES).min(self.boxes.len());
        for (k, fb) in (first..last).zip(&self.boxes[first..last]) {
            if overlaps_f32(local, fb, planar) {
                out.push(self.first_slot + k as u32);
            }
        }
    }
}

impl std::fmt::Debug for MasterTree {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "MasterTree({} slabs, {:?})",
            self.slabs.len(),
            self.padding
        )
    }
}

pub(super) const EMPTY: Box3 = (
    Vector3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY),
    Vector3::new(f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY),
);

impl MasterTree {
    /// Builds the trees over the master faces of `interface`, in parallel on the current
    /// rayon pool (see [`build_with_faces`](Self::build_with_faces)), with the padding of a
    /// search that knows no projector ([`Padding::of`] with `None`: the slave faces' search
    /// boxes inflated).
    pub fn build(interface: &Interface) -> Self {
        Self::build_with_faces(interface, Padding::of(interface, None)).0
    }

    /// Builds the trees over the master faces of `interface` and the master faces by slot
    /// ([`MasterFaces`]: a face's slot is its position in the trees' order), in parallel on
    /// the current rayon pool.
    ///
    /// The mesh is read in the file's order once, for one node per face (its first: the
    /// anchor of its Morton code and of its slab), and once in slot order, by
    /// [`MasterFaces::new`]; the boxes are computed from the faces in slot order. A file
    /// whose faces and nodes are numbered far apart thus costs two reads of the mesh in
    /// random order, not the five it took to build boxes, order them, gather them by slab
    /// and copy the faces. The master faces' boxes are inflated by `padding.master`, the slave
    /// faces' search boxes of the queries by `padding.slave`.
    pub fn build_with_faces(interface: &Interface, padding: Padding) -> (Self, MasterFaces) {
        let planar = interface.dim() == SpatialDim::Two;
        let master = interface.master();
        let n = master.face_count();
        let xyz = master.coords();
        // Each face by its first node, read twice (for the bounds, then for its key) rather
        // than stored.
        let anchor = |f: usize| xyz[master.face_nodes(f)[0] as usize];
        let (lo, hi) = bounds_of(n, anchor);
        // Slabs of equal width along the longest axis (by anchor), Morton order within a
        // slab: one sort of (slab, code, face), so that the order depends on the coordinates
        // only, not on the thread count.
        let slab_count = n.div_ceil(SLAB_FACES).max(1);
        let axis = (hi - lo).imax();
        let width = (hi[axis] - lo[axis]).max(f64::MIN_POSITIVE);
        // (slab, code, face) packed into one integer, in that order of significance: one
        // comparison per pair in the sort, the same order as the tuples'.
        let mut keyed: Vec<u128> = (0..n)
            .into_par_iter()
            .map(|f| {
                let c = &anchor(f);
                let k = if slab_count == 1 {
                    0
                } else {
                    ((((c[axis] - lo[axis]) / width) * slab_count as f64) as usize)
                        .min(slab_count - 1)
                };
                let code = morton_code(c, &lo, &hi, planar);
                (k as u128) << 96 | (code as u128) << 32 | f as u128
            })
            .collect();
        keyed.par_sort_unstable();
        let slab_of = |key: u128| (key >> 96) as u32;
        let mut ranges: Vec<(u32, u32)> = Vec::new();
        for (i, &key) in keyed.iter().enumerate() {
            match ranges.last_mut() {
                Some((first, len)) if slab_of(keyed[*first as usize]) == slab_of(key) => *len += 1,
                _ => ranges.push((i as u32, 1)),
            }
        }
        let masters = MasterFaces::new(interface, keyed.into_iter().map(|key| key as u32));
        let slabs = ranges
            .into_par_iter()
            .map(|(first_slot, len)| {
                // The slab's boxes from its faces in slot order: the leaves and the f32
                // copies then read them in sequence, whatever the file's numbering.
                let mut x = [Vector3::zeros(); MAX_FACE_NODES];
                let boxes: Vec<Box3> = (first_slot..first_slot + len)
                    .map(|s| {
                        let (_, k) = masters.coords_into(interface, s as usize, &mut x);
                        points_box(&x[..k], padding.master)
                    })
                    .collect();
                let leaves: Vec<Box3> = boxes
                    .chunks(LEAF_FACES)
                    .map(|group| group.iter().fold(EMPTY, |acc, b| union(&acc, b)))
                    .collect();
                let bounds = leaves.iter().fold(EMPTY, |acc, b| union(&acc, b));
                let frame = Frame::of(&bounds);
                Slab {
                    tree: BoxTree::build(leaves, planar),
                    bounds,
                    first_slot,
                    boxes: boxes.iter().map(|b| box_f32(&frame.apply(b))).collect(),
                    frame,
                }
            })
            .collect();
        (
            Self {
                slabs,
                planar,
                padding,
                radii: None,
            },
            masters,
        )
    }

    /// The same tree, its queries taking the search radius of slave face `f` from
    /// `radii[f]` instead of the tolerances.
    pub(crate) fn with_radii(mut self, radii: Option<Arc<[f64]>>) -> Self {
        self.radii = radii;
        self
    }

    /// The candidate master faces of slave face `s`, as slots (see
    /// [`MasterFaces::face_index`] for the face of a slot), ascending, written into `out` (cleared first).
    /// Slots near each other are faces near each other in space.
    pub fn candidates_into(&self, interface: &Interface, s: usize, out: &mut Vec<u32>) {
        self.candidates_of(interface, &interface.slave_face(s), out);
    }

    /// The candidates of a slave face already gathered (with its nodal normals), as
    /// [`candidates_into`](Self::candidates_into).
    pub fn candidates_of(&self, interface: &Interface, face: &FaceGeometry, out: &mut Vec<u32>) {
        let radius = self.radii.as_ref().map(|r| r[face.index as usize]);
        self.candidates_within(interface, face, radius, out);
    }

    /// [`candidates_of`](Self::candidates_of) with the search radius `radius` (`None`: the
    /// tolerances').
    pub(crate) fn candidates_within(
        &self,
        interface: &Interface,
        face: &FaceGeometry,
        radius: Option<f64>,
        out: &mut Vec<u32>,
    ) {
        let b = slave_search_box(interface, face, self.padding.slave, radius);
        out.clear();
        for slab in &self.slabs {
            if !overlaps(&b, &slab.bounds, self.planar) {
                continue;
            }
            // The hit leaves go to the end of `out`, are expanded into their faces after
            // them, then removed: no allocation per query.
            let start = out.len();
            slab.tree.append_intersecting(&b, out);
            let end = out.len();
            let local = slab.frame.apply(&b);
            for i in start..end {
                slab.push_faces_meeting(out[i], &local, self.planar, out);
            }
            out.drain(start..end);
        }
        out.sort_unstable();
        out.dedup();
    }

    /// The candidates of each of `faces` (slave faces already gathered, with their nodal
    /// normals; neighbours in space, for speed), as [`candidates_of`](Self::candidates_of)
    /// gives them, appended one face after the other to `out`, and the end of each face's
    /// (its index in `out`) appended to `ends`. The tree is queried once per group of
    /// consecutive faces with the union of their search boxes, and each face tests the hit
    /// leaves' boxes and then their faces' against its own box: the same candidates, fewer
    /// descents.
    pub fn candidates_of_group(
        &self,
        interface: &Interface,
        faces: &[FaceGeometry],
        scratch: &mut GroupScratch,
        out: &mut Vec<u32>,
        ends: &mut Vec<usize>,
    ) {
        let GroupScratch { leaves, per_face } = scratch;
        let mut boxes: ArrayVec<Box3, GROUP> = ArrayVec::new();
        for group in faces.chunks(GROUP) {
            boxes.clear();
            boxes.extend(group.iter().map(|f| {
                let radius = self.radii.as_ref().map(|r| r[f.index as usize]);
                slave_search_box(interface, f, self.padding.slave, radius)
            }));
            let all = boxes[1..].iter().fold(boxes[0], |acc, b| union(&acc, b));
            let first_end = ends.len();
            ends.extend(std::iter::repeat_n(out.len(), group.len()));
            // Per face, its candidates gathered slab after slab.
            for found in per_face.iter_mut() {
                found.clear();
            }
            for slab in &self.slabs {
                if !overlaps(&all, &slab.bounds, self.planar) {
                    continue;
                }
                leaves.clear();
                slab.tree.append_intersecting(&all, leaves);
                for (b, found) in boxes.iter().zip(per_face.iter_mut()) {
                    if !overlaps(b, &slab.bounds, self.planar) {
                        continue;
                    }
                    let local = slab.frame.apply(b);
                    for &l in leaves.iter() {
                        if slab.tree.meets_leaf(b, l as usize) {
                            slab.push_faces_meeting(l, &local, self.planar, found);
                        }
                    }
                }
            }
            // Ascending without a sort: the slabs hold ascending runs of slots, the tree
            // gives a slab's leaves in ascending order, and a leaf holds consecutive slots.
            for (e, found) in ends[first_end..].iter_mut().zip(per_face.iter_mut()) {
                debug_assert!(found.windows(2).all(|w| w[0] < w[1]), "ascending slots");
                out.extend_from_slice(found);
                *e = out.len();
            }
        }
    }
}

/// Finds the candidate pairs of a whole interface with the BVH (built over the master
/// faces, queried with each slave face). Runs on the current rayon pool; the result does not
/// depend on the thread count. (`assemble_coupling` queries chunk by chunk instead, without
/// storing every candidate.)
pub fn find_candidates(interface: &Interface) -> Candidates {
    let (tree, masters) = MasterTree::build_with_faces(interface, Padding::of(interface, None));
    let lists: Vec<Vec<u32>> = (0..interface.slave().face_count())
        .into_par_iter()
        .map_init(Vec::new, |scratch, s| {
            tree.candidates_into(interface, s, scratch);
            let mut faces: Vec<u32> = scratch
                .iter()
                .map(|&k| masters.face_index(k as usize) as u32)
                .collect();
            faces.sort_unstable();
            faces
        })
        .collect();
    let mut offsets = Vec::with_capacity(lists.len() + 1);
    offsets.push(0u32);
    let mut masters = Vec::with_capacity(lists.iter().map(Vec::len).sum());
    for l in &lists {
        masters.extend_from_slice(l);
        offsets.push(masters.len() as u32);
    }
    Candidates { offsets, masters }
}

/// The region where slave face `face` looks for master faces, inflated by `inflation` times
/// the face's diameter and by a margin for the rounding. It holds every point `x + s e`,
/// `|s| <= radius`, where `e` is a unit direction along a convex combination `d` of the nodal
/// normals `n_i` (see [`Padding`]). Such a `d` is no shorter than `c = min_i n_i . u`, with
/// `u` the normals' mean direction, so `s e = t d` with `|t| <= radius / c`
/// ([`normal_cone_reach`]):
/// - in 2D, with `x` the point of the face that `d` is taken at (the strategies project along
///   the direction field at the slave point): `x + t d` is the same convex combination of the
///   points `x_i +- (radius / c) n_i`, so their box;
/// - in 3D, with `x` anywhere on the face (the auxiliary plane projects along the direction
///   at the face's centre): the box of the nodes widened on each axis by the radius times
///   the largest of the nodal normals' components on that axis over `c` (at most the radius).
///
/// Where the normals fan out by more than a right angle (`c <= 0`), both widen the nodes' box
/// by the radius on every axis.
///
/// The radius is `radius`, or where `None` the tolerances' for the face's diameter.
pub(super) fn slave_search_box(
    interface: &Interface,
    face: &FaceGeometry,
    inflation: f64,
    radius: Option<f64>,
) -> Box3 {
    let k = face.node_count();
    let (nodes, normals) = (&face.nodes[..k], &face.normals[..k]);
    let (mut lo, mut hi) = (EMPTY.0, EMPTY.1);
    for x in nodes {
        lo = lo.inf(x);
        hi = hi.sup(x);
    }
    let diameter = (hi - lo).norm();
    let radius = radius.unwrap_or_else(|| interface.tolerances().search_radius.for_face(diameter));
    match normal_cone_reach(normals, radius) {
        None => {
            lo -= Vector3::repeat(radius);
            hi += Vector3::repeat(radius);
        }
        Some(reach) if interface.dim() == SpatialDim::Two => {
            for (x, n) in nodes.iter().zip(normals) {
                let d = n * reach;
                for p in [x + d, x - d] {
                    lo = lo.inf(&p);
                    hi = hi.sup(&p);
                }
            }
        }
        Some(reach) => {
            let widest = normals
                .iter()
                .fold(Vector3::zeros(), |w, n| w.sup(&n.abs()));
            let reach = (widest * reach).inf(&Vector3::repeat(radius));
            lo -= reach;
            hi += reach;
        }
    }
    let pad = Vector3::repeat(inflation * diameter);
    padded(lo - pad, hi + pad)
}

/// How far along the nodal normals `normals` (in multiples of them) a distance `radius` along
/// any unit direction of their convex cone reaches: at least `radius / c`, where `c = min_i
/// n_i . u` (`u = s / |s|` their mean direction, `s` their sum) bounds the length of each
/// convex combination `d` of them from below (`|d| >= d . u >= c`). Computed without a root
/// as `radius (1 + |s|^2 / m^2) / 2 >= radius |s| / m = radius / c`, `m = min_i n_i . s` (the
/// two agree to the square of `1 - c`); `radius` itself where the normals are one. `None`
/// where they fan out by a right angle or more (`m <= 0`).
#[inline(never)]
fn normal_cone_reach(normals: &[Vector3<f64>], radius: f64) -> Option<f64> {
    if normals.iter().all(|n| *n == normals[0]) {
        // One normal (a flat face): `c` is its length, 1 but for a few ulps that the box's
        // margin for the rounding holds.
        return Some(radius);
    }
    if let [a, b] = normals {
        // Two unit normals `p = a . b >= 0` apart (a line, the 2D search's every face): `c =
        // sqrt((1 + p) / 2)`, and `1 / c <= 1 + (sqrt 2 - 1)(1 - p)` (the chord of the
        // convex `(1 - x)^(-1/2)` over `x = (1 - p) / 2` in `[0, 1/2]`): no division.
        let p = a.dot(b);
        if p >= 0.0 {
            return Some(radius * (1.0 + (std::f64::consts::SQRT_2 - 1.0) * (1.0 - p)));
        }
    }
    let s = normals.iter().fold(Vector3::zeros(), |s, n| s + n);
    let m = normals
        .iter()
        .map(|n| n.dot(&s))
        .fold(f64::INFINITY, f64::min);
    (m > 0.0).then(|| radius * 0.5 * (1.0 + s.norm_squared() / (m * m)))
}

/// The search radius of slave face `face`: `radii[face.index]` where given, else the
/// tolerances' for its diameter (the diagonal of its nodes' box, as the search box takes it).
pub(crate) fn face_search_radius(
    interface: &Interface,
    face: &FaceGeometry,
    radii: Option<&[f64]>,
) -> f64 {
    if let Some(r) = radii {
        return r[face.index as usize];
    }
    let x = &face.nodes[..face.node_count()];
    let (lo, hi) = x[1..]
        .iter()
        .fold((x[0], x[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    interface
        .tolerances()
        .search_radius
        .for_face((hi - lo).norm())
}

/// The bounding box of a face's nodes `x`, inflated by `inflation` times its diagonal and then
/// by a margin for the rounding; without inflation, the nodes' box itself (their least and
/// greatest coordinates: nothing to round).
pub(super) fn points_box(x: &[Vector3<f64>], inflation: f64) -> Box3 {
    let (mut lo, mut hi) = (x[0], x[0]);
    for p in &x[1..] {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    if inflation == 0.0 {
        return (lo, hi);
    }
    let pad = Vector3::repeat(inflation * (hi - lo).norm());
    padded(lo - pad, hi + pad)
}

/// The box `(lo, hi)` widened by the margin of its rounding, per axis: 8 units in the last
/// place of its larger bound on that axis.
#[inline]
fn padded(lo: Vector3<f64>, hi: Vector3<f64>) -> Box3 {
    let m = lo.abs().sup(&hi.abs()) * (8.0 * f64::EPSILON);
    (lo - m, hi + m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Unit normals within `spread` radians of the z axis (azimuths and tilts from the
    /// given fractions).
    fn normals_in_cone(spread: f64, angles: &[(f64, f64)]) -> Vec<Vector3<f64>> {
        angles
            .iter()
            .map(|&(a, t)| {
                let (phi, theta) = (a * std::f64::consts::TAU, t * spread);
                Vector3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                )
            })
            .collect()
    }

    proptest! {
        /// The reach times the length of any convex combination of the normals is at least the
        /// radius (a distance `r` along the combination's direction stays within the box), for
        /// two to four unit normals fanning out by up to 80 degrees from their axis; and where
        /// they are one, the reach is the radius itself. Reference: the bound's derivation
        /// (`|d| >= d . u >= min_i n_i . u`), checked on random weights.
        ///
        /// Normals within 80 degrees of an axis can be up to 160 degrees apart, and there the
        /// bound may not exist (`None`: the caller widens the box by the radius on every
        /// axis). Within 45 degrees of the axis any two are within a right angle, so `n_j . s
        /// >= 1` for every `j` and the bound always exists: a `None` there fails. (This
        /// test first expected a bound at every spread; a CI run found three normals of up
        /// to 69 degrees from the axis, two of them more than a right angle apart.)
        #[test]
        fn the_reach_covers_every_direction_of_the_cone(
            spread in 0.0..1.4f64,
            angles in prop::collection::vec((0.0..1.0f64, 0.0..1.0f64), 2..5),
            weights in prop::collection::vec(0.0..1.0f64, 4),
        ) {
            let normals = normals_in_cone(spread, &angles);
            let Some(reach) = normal_cone_reach(&normals, 1.0) else {
                prop_assert!(spread > std::f64::consts::FRAC_PI_4, "no bound at {}", spread);
                return Ok(());
            };
            let total: f64 = weights[..normals.len()].iter().sum::<f64>().max(1e-300);
            let d = normals
                .iter()
                .zip(&weights)
                .fold(Vector3::zeros(), |d, (n, w)| d + n * (w / total));
            prop_assert!(reach * d.norm() >= 1.0 - 1e-12, "reach {} |d| {}", reach, d.norm());
            // Each normal itself (a vertex of the cone).
            for n in &normals {
                prop_assert!(reach * n.norm() >= 1.0 - 1e-12);
            }
            let one = vec![normals[0]; normals.len()];
            prop_assert_eq!(normal_cone_reach(&one, 2.5), Some(2.5));
        }
    }

    /// Opposite normals bound nothing: the box is widened by the radius on every axis. Nor
    /// do three normals of up to 69 degrees from their axis, two of them more than a right
    /// angle apart (the input a CI run found; `min_i n_i . s` is negative there).
    #[test]
    fn opposite_normals_bound_nothing() {
        let n = Vector3::new(0.0, 0.6, 0.8);
        assert_eq!(normal_cone_reach(&[n, -n], 1.0), None);
        assert_eq!(normal_cone_reach(&[n, -n, n], 1.0), None);
        let wide = normals_in_cone(
            1.3017448635447868,
            &[
                (0.144613743713137, 0.8895728901148772),
                (0.1426942320011091, 0.9253842833930782),
                (0.72005788596884, 0.8618899900032977),
            ],
        );
        assert!(wide[0].dot(&wide[2]) < 0.0);
        assert_eq!(normal_cone_reach(&wide, 1.0), None);
    }
}
