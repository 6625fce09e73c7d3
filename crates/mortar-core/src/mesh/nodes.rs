//! `NodeSet`: the coordinates and tags of a mesh's nodes and the index of each tag, shared by
//! the surface meshes here and the volume meshes of `mortar-fem`.

use std::collections::hash_map::Entry;

use nalgebra::Vector3;
use rustc_hash::FxHashMap;

/// The nodes of a mesh: coordinates and tags in insertion order, and the index of each tag.
/// Shared by [`SurfaceMesh`](super::SurfaceMesh) and the volume mesh of `mortar-fem`, which
/// report its refusals with their own error types.
#[derive(Debug, Clone, Default)]
pub struct NodeSet {
    pub(crate) coords: Vec<Vector3<f64>>,
    pub(crate) tags: Vec<u64>,
    index: TagIndex,
}

/// Where each tag is among the nodes. Meshes mostly number their nodes consecutively in the
/// order they list them (Gmsh's files, the generators): then a node's index is its tag minus
/// the first, with no table at all. The first tag out of that sequence builds a hash map of
/// every tag so far, kept from then on. (A map for every mesh cost a cache miss per lookup:
/// building a mesh of 10^6 line faces took 1.7 s, most of it in the lookups of the faces'
/// node tags, against 0.25 s for its coupling.)
#[derive(Debug, Clone)]
enum TagIndex {
    /// The tags are `first, first + 1, ...` in insertion order.
    Consecutive { first: u64 },
    /// Any tags.
    Map(FxHashMap<u64, u32>),
}

impl Default for TagIndex {
    fn default() -> Self {
        Self::Consecutive { first: 0 }
    }
}

/// Why a node was refused.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NodeRefusal {
    /// A NaN or infinite coordinate.
    NonFinite,
    /// The tag is already used.
    Duplicate,
}

impl NodeSet {
    /// Room for `n` nodes.
    pub fn reserve(&mut self, n: usize) {
        self.coords.reserve(n);
        self.tags.reserve(n);
        if let TagIndex::Map(map) = &mut self.index {
            map.reserve(n);
        }
    }

    /// Adds a node and returns its index; a non-finite coordinate or a used tag is refused and
    /// leaves the set unchanged.
    pub fn add(&mut self, tag: u64, coords: [f64; 3]) -> Result<u32, NodeRefusal> {
        if coords.iter().any(|c| !c.is_finite()) {
            return Err(NodeRefusal::NonFinite);
        }
        let len = self.coords.len();
        let index = len as u32;
        match &mut self.index {
            TagIndex::Consecutive { first } if len == 0 => *first = tag,
            TagIndex::Consecutive { first } if first.checked_add(len as u64) == Some(tag) => {}
            TagIndex::Consecutive { .. } => {
                // Out of sequence: every tag so far into a map (they are distinct, being
                // consecutive), then this one.
                let mut map = FxHashMap::default();
                map.reserve(self.tags.capacity().max(len + 1));
                map.extend(self.tags.iter().zip(0u32..).map(|(&t, i)| (t, i)));
                self.index = TagIndex::Map(map);
                return self.add(tag, coords);
            }
            TagIndex::Map(map) => match map.entry(tag) {
                // Refused without touching the index: the tag keeps its node.
                Entry::Occupied(_) => return Err(NodeRefusal::Duplicate),
                Entry::Vacant(slot) => {
                    slot.insert(index);
                }
            },
        }
        self.coords.push(Vector3::from(coords));
        self.tags.push(tag);
        Ok(index)
    }

    /// The coordinates, in insertion order.
    #[inline]
    pub fn coords(&self) -> &[Vector3<f64>] {
        &self.coords
    }

    /// The coordinates, to move the nodes (the tags and their index stay).
    #[inline]
    pub fn coords_mut(&mut self) -> &mut [Vector3<f64>] {
        &mut self.coords
    }

    /// The tags, in insertion order.
    #[inline]
    pub fn tags(&self) -> &[u64] {
        &self.tags
    }

    /// The index of the node with tag `tag`.
    #[inline]
    pub fn index_of(&self, tag: u64) -> Option<u32> {
        match &self.index {
            TagIndex::Consecutive { first } => tag
                .checked_sub(*first)
                .filter(|&i| i < self.tags.len() as u64)
                .map(|i| i as u32),
            TagIndex::Map(map) => map.get(&tag).copied(),
        }
    }

    /// The heap memory held, in bytes (arrays at their capacity, an estimate for the lookup).
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        self.coords.capacity() * size_of::<Vector3<f64>>()
            + self.tags.capacity() * size_of::<u64>()
            + match &self.index {
                TagIndex::Consecutive { .. } => 0,
                TagIndex::Map(map) => map.capacity() * (size_of::<(u64, u32)>() + 1),
            }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every tag added is found at its index and nothing else is, whether the tags are
    /// consecutive (no table), leave the sequence (the map from then on) or start anywhere;
    /// used tags and non-finite coordinates are refused in both modes, leaving the set as it
    /// was. (Regression: the map's `insert` of a used tag replaced that tag's index with the
    /// refused node's, one past the last node, before the refusal was returned.)
    #[test]
    fn tags_are_found_in_both_modes() {
        let check = |set: &NodeSet| {
            for (i, &t) in set.tags.iter().enumerate() {
                assert_eq!(set.index_of(t), Some(i as u32), "tag {t}");
            }
            for t in [0, 1, 6, 99, 1_000, u64::MAX] {
                if !set.tags.contains(&t) {
                    assert_eq!(set.index_of(t), None, "tag {t}");
                }
            }
        };
        let mut set = NodeSet::default();
        assert_eq!(set.index_of(0), None);
        for t in 7..12 {
            set.add(t, [t as f64, 0.0, 0.0]).unwrap();
        }
        assert!(matches!(set.index, TagIndex::Consecutive { first: 7 }));
        check(&set);
        assert_eq!(set.add(9, [0.0; 3]), Err(NodeRefusal::Duplicate));
        assert_eq!(
            set.add(12, [f64::NAN, 0.0, 0.0]),
            Err(NodeRefusal::NonFinite)
        );
        assert_eq!(set.tags.len(), 5);
        check(&set);
        // Out of sequence: the map, with the same answers.
        set.add(1_000, [1.0; 3]).unwrap();
        assert!(matches!(set.index, TagIndex::Map(_)));
        set.add(12, [2.0; 3]).unwrap();
        set.add(3, [3.0; 3]).unwrap();
        assert_eq!(set.add(1_000, [0.0; 3]), Err(NodeRefusal::Duplicate));
        assert_eq!(set.add(7, [0.0; 3]), Err(NodeRefusal::Duplicate));
        assert_eq!(set.tags, [7, 8, 9, 10, 11, 1_000, 12, 3]);
        check(&set);
        // A duplicate as the first tag out of sequence: refused, the set unchanged.
        let mut set = NodeSet::default();
        for t in [1, 2, 3] {
            set.add(t, [0.0; 3]).unwrap();
        }
        assert_eq!(set.add(2, [0.0; 3]), Err(NodeRefusal::Duplicate));
        assert_eq!(set.tags, [1, 2, 3]);
        check(&set);
        set.add(4, [0.0; 3]).unwrap();
        check(&set);
        // Near the end of u64: no overflow.
        let mut set = NodeSet::default();
        set.add(u64::MAX - 1, [0.0; 3]).unwrap();
        set.add(u64::MAX, [0.0; 3]).unwrap();
        set.add(0, [0.0; 3]).unwrap();
        check(&set);
    }
}
