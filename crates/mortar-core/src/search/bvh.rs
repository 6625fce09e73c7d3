//! The one place that touches parry's BVH.

use nalgebra::Vector3;

/// A BVH over axis-aligned boxes, 2D or 3D.
pub(super) enum BoxTree {
    Two(parry2d_f64::partitioning::Bvh),
    Three(parry3d_f64::partitioning::Bvh),
}

impl BoxTree {
    /// Builds the tree over `boxes` (leaf `i` is `boxes[i]`); `planar` uses the 2D tree and
    /// ignores z.
    pub(super) fn build(boxes: &[(Vector3<f64>, Vector3<f64>)], planar: bool) -> Self {
        use parry2d_f64::partitioning::BvhBuildStrategy as S2;
        use parry3d_f64::partitioning::BvhBuildStrategy as S3;
        if planar {
            let leaves: Vec<_> = boxes.iter().map(aabb2).collect();
            BoxTree::Two(parry2d_f64::partitioning::Bvh::from_leaves(
                S2::Binned,
                &leaves,
            ))
        } else {
            let leaves: Vec<_> = boxes.iter().map(aabb3).collect();
            BoxTree::Three(parry3d_f64::partitioning::Bvh::from_leaves(
                S3::Binned,
                &leaves,
            ))
        }
    }

    /// Leaves whose boxes intersect `query`, appended to `out` (cleared first) in ascending
    /// order.
    pub(super) fn intersecting_into(
        &self,
        query: &(Vector3<f64>, Vector3<f64>),
        out: &mut Vec<u32>,
    ) {
        out.clear();
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
        out.sort_unstable();
        out.dedup();
    }
}

fn aabb2(b: &(Vector3<f64>, Vector3<f64>)) -> parry2d_f64::bounding_volume::Aabb {
    use parry2d_f64::math::Vector;
    parry2d_f64::bounding_volume::Aabb::new(Vector::new(b.0.x, b.0.y), Vector::new(b.1.x, b.1.y))
}

fn aabb3(b: &(Vector3<f64>, Vector3<f64>)) -> parry3d_f64::bounding_volume::Aabb {
    use parry3d_f64::math::Vector;
    parry3d_f64::bounding_volume::Aabb::new(
        Vector::new(b.0.x, b.0.y, b.0.z),
        Vector::new(b.1.x, b.1.y, b.1.z),
    )
}
