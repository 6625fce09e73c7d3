//! The one place that touches parry's BVH.

use nalgebra::Vector3;

/// An axis-aligned box as `(min, max)`.
pub(super) type Box3 = (Vector3<f64>, Vector3<f64>);

/// A BVH over axis-aligned boxes, 2D or 3D.
pub(super) enum BoxTree {
    Two(parry2d_f64::partitioning::Bvh),
    Three(parry3d_f64::partitioning::Bvh),
}

impl BoxTree {
    /// Builds the tree over `leaves` (`(leaf index, box)`); `planar` uses the 2D tree and
    /// ignores z.
    pub(super) fn build(leaves: &[(u32, Box3)], planar: bool) -> Self {
        use parry2d_f64::partitioning::{Bvh as Bvh2, BvhBuildStrategy as S2};
        use parry3d_f64::partitioning::{Bvh as Bvh3, BvhBuildStrategy as S3};
        if planar {
            let it = leaves.iter().map(|(i, b)| (*i as usize, aabb2(b)));
            BoxTree::Two(Bvh2::from_iter(S2::Binned, it))
        } else {
            let it = leaves.iter().map(|(i, b)| (*i as usize, aabb3(b)));
            BoxTree::Three(Bvh3::from_iter(S3::Binned, it))
        }
    }

    /// Appends to `out` the leaves whose boxes intersect `query` (unordered).
    pub(super) fn append_intersecting(&self, query: &Box3, out: &mut Vec<u32>) {
        match self {
            BoxTree::Two(t) => {
                let q = aabb2(query);
                out.extend(t.intersect_aabb(&q));
            }
            BoxTree::Three(t) => {
                let q = aabb3(query);
                out.extend(t.intersect_aabb(&q));
            }
        }
    }
}

fn aabb2(b: &Box3) -> parry2d_f64::bounding_volume::Aabb {
    use parry2d_f64::math::Vector;
    parry2d_f64::bounding_volume::Aabb::new(Vector::new(b.0.x, b.0.y), Vector::new(b.1.x, b.1.y))
}

fn aabb3(b: &Box3) -> parry3d_f64::bounding_volume::Aabb {
    use parry3d_f64::math::Vector;
    parry3d_f64::bounding_volume::Aabb::new(
        Vector::new(b.0.x, b.0.y, b.0.z),
        Vector::new(b.1.x, b.1.y, b.1.z),
    )
}
