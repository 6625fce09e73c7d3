use std::collections::HashMap;

use nalgebra::Vector3;

/// The nodes of a mesh: coordinates and tags in insertion order, and the index of each tag.
/// Shared by [`SurfaceMesh`](super::SurfaceMesh) and [`VolumeMesh`](super::VolumeMesh), which
/// report its refusals with their own error types.
#[derive(Debug, Clone, Default)]
pub(crate) struct NodeSet {
    pub(crate) coords: Vec<Vector3<f64>>,
    pub(crate) tags: Vec<u64>,
    index: HashMap<u64, u32>,
}

/// Why a node was refused.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum NodeRefusal {
    /// A NaN or infinite coordinate.
    NonFinite,
    /// The tag is already used.
    Duplicate,
}

impl NodeSet {
    /// Room for `n` nodes.
    pub(crate) fn reserve(&mut self, n: usize) {
        self.coords.reserve(n);
        self.tags.reserve(n);
        self.index.reserve(n);
    }

    /// Adds a node and returns its index; a non-finite coordinate or a used tag is refused and
    /// leaves the set unchanged.
    pub(crate) fn add(&mut self, tag: u64, coords: [f64; 3]) -> Result<u32, NodeRefusal> {
        if coords.iter().any(|c| !c.is_finite()) {
            return Err(NodeRefusal::NonFinite);
        }
        let index = self.coords.len() as u32;
        if self.index.insert(tag, index).is_some() {
            return Err(NodeRefusal::Duplicate);
        }
        self.coords.push(Vector3::from(coords));
        self.tags.push(tag);
        Ok(index)
    }

    /// The index of the node with tag `tag`.
    #[inline]
    pub(crate) fn index_of(&self, tag: u64) -> Option<u32> {
        self.index.get(&tag).copied()
    }

    /// The heap memory held, in bytes (arrays at their capacity, an estimate for the lookup).
    pub(crate) fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        self.coords.capacity() * size_of::<Vector3<f64>>()
            + self.tags.capacity() * size_of::<u64>()
            + self.index.capacity() * (size_of::<(u64, u32)>() + 1)
    }
}
