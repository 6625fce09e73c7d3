//! A bounding-volume hierarchy over leaves that come in a spatial order.
//!
//! The search hands its leaves over already in the Morton order of their faces (groups of
//! consecutive faces along a space-filling curve), so the tree needs no clustering of its
//! own: each level's node is the box of [`FANOUT`] consecutive nodes of the level below, the
//! leaves' boxes at the bottom. Its build is one pass of box unions over the leaves (a third
//! of a union per leaf), where a surface-area-heuristic build (parry's binned BVH, used here
//! until it cost 11% of the whole coupling on plane3d) sorts and bins them at every level; a
//! query visits the nodes whose boxes meet it, as in any BVH. Boxes are `f64` and the tests
//! inclusive, so a query finds exactly the leaves whose boxes meet its box, whatever the
//! tree's shape.

use arrayvec::ArrayVec;
use nalgebra::Vector3;

/// An axis-aligned box as `(min, max)`.
pub(super) type Box3 = (Vector3<f64>, Vector3<f64>);

/// Children per node. Four: a query tests four boxes per visited node and descends
/// log4(leaves) levels.
const FANOUT: usize = 4;

/// A BVH over axis-aligned boxes, 2D (z ignored) or 3D, over leaves in a spatial order.
#[derive(Debug, Clone)]
pub(super) struct BoxTree {
    /// `levels[0]`: the leaves' boxes; `levels[k + 1][i]`: the box of
    /// `levels[k][FANOUT * i..FANOUT * (i + 1)]`. The last level has one box (none without
    /// leaves).
    levels: Vec<Vec<Box3>>,
    /// Whether z is ignored.
    planar: bool,
}

impl BoxTree {
    /// Builds the tree over the boxes `leaves` (leaf `i` is `leaves[i]`), which should come
    /// in a spatial order (consecutive leaves near each other) for the queries to be fast;
    /// `planar` tests x and y only.
    pub(super) fn build(leaves: Vec<Box3>, planar: bool) -> Self {
        let mut levels = vec![leaves];
        while let Some(below) = levels.last().filter(|l| l.len() > 1) {
            let above: Vec<Box3> = below
                .chunks(FANOUT)
                .map(|c| c[1..].iter().fold(c[0], |acc, b| union(&acc, b)))
                .collect();
            levels.push(above);
        }
        Self { levels, planar }
    }

    /// Appends to `out` the leaves whose boxes meet `query`, in ascending order.
    pub(super) fn append_intersecting(&self, query: &Box3, out: &mut Vec<u32>) {
        let Some(top) = self.levels.len().checked_sub(1) else {
            return;
        };
        if top == 0 {
            self.append_leaves_meeting(query, 0..self.levels[0].len(), out);
            return;
        }
        // Nodes above the leaves whose boxes meet the query, as (level, index), to be opened
        // depth first, children in ascending order (pushed last to first), so that the
        // leaves come out ascending; the leaves under a node of level 1 go straight to
        // `out`. The top level has one node and each level pushes at most FANOUT, so the
        // stack holds at most 1 + FANOUT * levels nodes (u32 indices: at most 16 levels).
        let mut stack: ArrayVec<(u8, u32), { 1 + FANOUT * 16 }> = ArrayVec::new();
        if overlaps(query, &self.levels[top][0], self.planar) {
            stack.push((top as u8, 0));
        }
        while let Some((level, i)) = stack.pop() {
            let (level, i) = (level as usize, i as usize);
            let below = &self.levels[level - 1];
            let first = i * FANOUT;
            let children = first..(first + FANOUT).min(below.len());
            if level == 1 {
                self.append_leaves_meeting(query, children, out);
                continue;
            }
            for (j, b) in children.clone().zip(&below[children]).rev() {
                if overlaps(query, b, self.planar) {
                    stack.push(((level - 1) as u8, j as u32));
                }
            }
        }
    }

    /// Appends to `out` the leaves in `range` whose boxes meet `query`.
    #[inline]
    fn append_leaves_meeting(
        &self,
        query: &Box3,
        range: std::ops::Range<usize>,
        out: &mut Vec<u32>,
    ) {
        let leaves = &self.levels[0][range.clone()];
        for (j, b) in range.zip(leaves) {
            if overlaps(query, b, self.planar) {
                out.push(j as u32);
            }
        }
    }

    /// Whether `b` meets the box of leaf `i` (as [`overlaps`] with the tree's axes).
    #[inline]
    pub(super) fn meets_leaf(&self, b: &Box3, i: usize) -> bool {
        overlaps(b, &self.levels[0][i], self.planar)
    }
}

/// Whether `a` meets `b`, boundaries included; `planar` ignores z.
#[inline]
pub(super) fn overlaps(a: &Box3, b: &Box3, planar: bool) -> bool {
    let xy = a.0.x <= b.1.x && b.0.x <= a.1.x && a.0.y <= b.1.y && b.0.y <= a.1.y;
    xy && (planar || (a.0.z <= b.1.z && b.0.z <= a.1.z))
}

/// The smallest box holding `a` and `b`.
pub(super) fn union(a: &Box3, b: &Box3) -> Box3 {
    (a.0.inf(&b.0), a.1.sup(&b.1))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(x: f64, y: f64, z: f64, h: f64) -> Box3 {
        (Vector3::new(x, y, z), Vector3::new(x + h, y + h, z + h))
    }

    /// A query finds exactly the leaves whose boxes meet it, touching ones included, for
    /// leaf counts that fill the levels partly (1, 4, 5, 17, 64 and 100 leaves), in 3D and in
    /// the plane (where z is ignored): against the test of every leaf, in ascending order.
    #[test]
    fn queries_find_exactly_the_leaves_that_meet_them() {
        for n in [1usize, 4, 5, 17, 64, 100] {
            // A row of unit cubes along a zigzag, each leaf one cube.
            let leaves: Vec<Box3> = (0..n)
                .map(|i| cube(i as f64, (i % 3) as f64, (i % 2) as f64 * 5.0, 1.0))
                .collect();
            for planar in [false, true] {
                let tree = BoxTree::build(leaves.clone(), planar);
                let dims = if planar { 2 } else { 3 };
                for q in [
                    cube(-0.5, -0.5, -0.5, 1.0),
                    cube(2.0, 1.0, 0.5, 0.0),
                    cube(3.5, 0.2, 4.0, 3.0),
                    cube(-10.0, -10.0, -10.0, 200.0),
                    cube(1000.0, 0.0, 0.0, 1.0),
                ] {
                    let mut got = Vec::new();
                    tree.append_intersecting(&q, &mut got);
                    let want: Vec<u32> = (0..n as u32)
                        .filter(|&i| {
                            let b = &leaves[i as usize];
                            (0..dims).all(|k| q.0[k] <= b.1[k] && b.0[k] <= q.1[k])
                        })
                        .collect();
                    assert_eq!(got, want, "n = {n}, planar = {planar}, query {q:?}");
                }
            }
        }
    }

    /// A tree without leaves finds nothing.
    #[test]
    fn an_empty_tree_finds_nothing() {
        let tree = BoxTree::build(Vec::new(), false);
        let mut out = Vec::new();
        tree.append_intersecting(&cube(0.0, 0.0, 0.0, 1.0), &mut out);
        assert!(out.is_empty());
    }
}
