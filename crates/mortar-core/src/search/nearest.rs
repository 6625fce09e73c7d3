//! The default search's second look ([`SearchRadius::Nearest`](crate::SearchRadius::Nearest)):
//! how far along its normal each slave face must look to reach the nearest master surface,
//! and the candidates within that distance.
//!
//! Distances are measured from a slave face's centroid `c` along its mean nodal normal `n`,
//! both ways: a master face's is that of its node nearest to the face's plane, zero where
//! its nodes lie on both sides of the plane. The search's boxes are axis-aligned, so at a
//! slant they hold master faces up to `sqrt(d)` times the radius away; the candidates of a
//! widened search are therefore kept by this distance, so that a second master layer beyond
//! the nearest is not reached through a box's corner.

use nalgebra::Vector3;
use rayon::prelude::*;

use super::candidates::face_search_radius;
use super::{MasterTree, Padding};
use crate::element::MAX_FACE_NODES;
use crate::interface::{FaceGeometry, Interface, MasterFaces, SpatialDim};

/// A slave face's centroid, mean unit normal and extent (its nodes' largest distance from
/// the centroid), and the directions of its plane.
struct Column {
    centre: Vector3<f64>,
    normal: Vector3<f64>,
    extent: f64,
    /// One direction across the face in 2D (the second is zero: z plays no part), two in
    /// 3D.
    across: [Vector3<f64>; 2],
}

impl Column {
    /// The column of `face`; `None` where its nodal normals cancel.
    fn of(face: &FaceGeometry, dim: SpatialDim) -> Option<Self> {
        let k = face.node_count();
        let centre = face.nodes[..k].iter().sum::<Vector3<f64>>() / k as f64;
        let normal = face.normals[..k]
            .iter()
            .sum::<Vector3<f64>>()
            .try_normalize(0.0)?;
        let extent = face.nodes[..k]
            .iter()
            .map(|p| (p - centre).norm())
            .fold(0.0f64, f64::max);
        let across = if dim == SpatialDim::Two {
            [Vector3::new(-normal.y, normal.x, 0.0), Vector3::zeros()]
        } else {
            let t = normal.cross(&Vector3::ith(normal.iamin(), 1.0)).normalize();
            [t, normal.cross(&t)]
        };
        Some(Self {
            centre,
            normal,
            extent,
            across,
        })
    }

    /// The distance along the normal to the face of nodes `x`.
    fn distance(&self, x: &[Vector3<f64>]) -> f64 {
        let (below, above) = x
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(b, a), p| {
                let o = self.normal.dot(&(p - self.centre));
                (b.min(o), a.max(o))
            });
        if below <= 0.0 && above >= 0.0 {
            0.0
        } else {
            below.abs().min(above.abs())
        }
    }

    /// Whether the face of nodes `x`, seen along the normal, comes within the slave face's
    /// extent of its centroid (the box of the nodes' projections onto the face's plane meets
    /// the disc of the extent): a master face across the slave face, not off to its side.
    fn is_across(&self, x: &[Vector3<f64>]) -> bool {
        self.across.iter().all(|t| {
            let (lo, hi) = x
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                    let o = t.dot(&(p - self.centre));
                    (l.min(o), h.max(o))
                });
            lo <= self.extent && hi >= -self.extent
        })
    }
}

/// For each slave face, the search radius that reaches the nearest master surface across it,
/// within `bound` times the interface's size (the diagonal of the slave surface's bounding
/// box), where that is more than the face's one-diameter radius; `None` where it is not, or
/// where no master face lies across the face within the bound.
///
/// The master faces across a slave face are those among the search's candidates at the bound
/// that come within the face's extent of its centroid, seen along its normal (the search's
/// axis-aligned box also holds faces off to the side, whose distance along the normal says
/// nothing of the gap). The radius is the nearest one's distance plus one face diameter (the
/// allowance the default search has always given for a master surface tilted across the
/// face), at most the bound.
pub(crate) fn nearest_master_radii(
    interface: &Interface,
    padding: Padding,
    bound: f64,
) -> Vec<Option<f64>> {
    let slave = interface.slave();
    let empty = || {
        (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY),
        )
    };
    let (lo, hi) = slave
        .coords()
        .par_iter()
        .fold(empty, |(lo, hi), x| (lo.inf(x), hi.sup(x)))
        .reduce(empty, |a, b| (a.0.inf(&b.0), a.1.sup(&b.1)));
    let reach = bound * (hi - lo).norm();
    let (tree, masters) = MasterTree::build_with_faces(interface, padding);
    (0..slave.face_count())
        .into_par_iter()
        .map_init(
            || (Vec::new(), [Vector3::zeros(); MAX_FACE_NODES]),
            |(found, x), f| {
                let face = interface.slave_face(f);
                let own = face_search_radius(interface, &face, None);
                if reach <= own {
                    return None;
                }
                let column = Column::of(&face, interface.dim())?;
                tree.candidates_within(interface, &face, Some(reach), found);
                let nearest = found
                    .iter()
                    .filter_map(|&slot| {
                        let (_, n) = masters.coords_into(interface, slot as usize, x);
                        column.is_across(&x[..n]).then(|| column.distance(&x[..n]))
                    })
                    .fold(f64::INFINITY, f64::min);
                let radius = (nearest + own).min(reach);
                (radius > own).then_some(radius)
            },
        )
        .collect()
}

/// Keeps, of the candidates `slots` of slave face `face`, those whose distance along its
/// normal is within `radius` (in order).
pub(crate) fn keep_within_radius(
    interface: &Interface,
    masters: &MasterFaces,
    face: &FaceGeometry,
    radius: f64,
    slots: &mut Vec<u32>,
) {
    let Some(column) = Column::of(face, interface.dim()) else {
        return;
    };
    let mut x = [Vector3::zeros(); MAX_FACE_NODES];
    slots.retain(|&slot| {
        let (_, n) = masters.coords_into(interface, slot as usize, &mut x);
        column.distance(&x[..n]) <= radius
    });
}
