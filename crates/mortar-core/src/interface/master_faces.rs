//! The master faces of an interface, addressed in a spatial order.

use nalgebra::Vector3;
use rayon::prelude::*;

use super::Interface;
use crate::element::{ElementRef, MAX_FACE_NODES};

/// The master faces of an [`Interface`] addressed by *slot*: their position in a given order
/// (the Morton order of the search tree), so that the master faces a slave face meets have
/// neighbouring slots.
///
/// When the file's face numbering is already spatially coherent (most consecutive faces are
/// near each other in the order), a face is read from the mesh itself. When it is not (a
/// mesher that numbers faces far apart, or a shuffled file), reading the mesh would jump all
/// over memory (1.4x to 2x the per-face work): the faces are then copied face after face in
/// slot order (element, tag, column of each node in M, node coordinates), at a cost of about
/// 120 bytes per Tri3 face. [`MasterFaces::is_packed`] says which.
#[derive(Debug, Clone, Default)]
pub struct MasterFaces {
    /// Per slot, the face's index in the master mesh.
    face: Vec<u32>,
    /// The packed copy, when the numbering is not spatially coherent.
    packed: Option<Packed>,
}

#[derive(Debug, Clone, Default)]
struct Packed {
    /// Per slot, where its nodes start in `columns` and `coords` (one more than the faces).
    start: Vec<u32>,
    /// Per slot, the element type.
    element: Vec<ElementRef>,
    /// Per slot, the face tag.
    tag: Vec<u64>,
    /// Per packed node, its column in M.
    columns: Vec<u32>,
    /// Per packed node, its coordinates.
    coords: Vec<Vector3<f64>>,
}

/// Slot distance beyond which two faces consecutive in the file count as far apart.
const NEAR_SLOTS: u32 = 256;

/// Faces per block of the packed copy, and blocks per wave.
const COPY_BLOCK: usize = 4096;
const COPY_WAVE: usize = 64;

impl Packed {
    /// The faces `faces` of `interface`'s master surface copied in the given order (`start`
    /// relative to the block, without its leading zero).
    fn copy(interface: &Interface, faces: &[u32]) -> Self {
        let mesh = interface.master();
        let xyz = mesh.coords();
        let mut out = Packed {
            start: Vec::with_capacity(faces.len()),
            element: Vec::with_capacity(faces.len()),
            tag: Vec::with_capacity(faces.len()),
            columns: Vec::with_capacity(faces.len() * 4),
            coords: Vec::with_capacity(faces.len() * 4),
        };
        // In three sweeps of independent reads (the faces, their node lists, the nodes), so
        // that the cache misses of many faces overlap instead of queueing behind each other.
        let views: Vec<_> = faces.iter().map(|&f| mesh.face(f as usize)).collect();
        let mut nodes: Vec<u32> = Vec::with_capacity(faces.len() * 4);
        for view in &views {
            out.element.push(view.element);
            out.tag.push(view.tag);
            nodes.extend_from_slice(view.nodes);
            out.start.push(nodes.len() as u32);
        }
        out.coords.extend(nodes.iter().map(|&i| xyz[i as usize]));
        out.columns.extend(nodes.iter().map(|&i| {
            interface
                .master_col(i)
                .expect("the nodes of a master face are on the interface")
        }));
        out
    }

    /// Appends a block made by [`copy`](Self::copy).
    ///
    /// # Panics
    /// If the faces have 2^32 nodes or more in all.
    fn append(&mut self, block: Packed) {
        let base = *self.start.last().unwrap_or(&0);
        self.start.extend(block.start.iter().map(|&e| {
            base.checked_add(e)
                .expect("fewer than 2^32 master face nodes")
        }));
        self.element.extend_from_slice(&block.element);
        self.tag.extend_from_slice(&block.tag);
        self.columns.extend_from_slice(&block.columns);
        self.coords.extend_from_slice(&block.coords);
    }
}

impl MasterFaces {
    /// The master faces of `interface` in `order` (a permutation of the master face indices),
    /// copied in that order if the mesh's own numbering is not spatially coherent (more than
    /// a tenth of the faces far, in slots, from the face numbered after them).
    ///
    /// # Panics
    /// If `order` is not a permutation of the master face indices, or the master faces have
    /// 2^32 nodes or more in all.
    pub fn new(interface: &Interface, order: impl IntoIterator<Item = u32>) -> Self {
        let mesh = interface.master();
        let n = mesh.face_count();
        let face: Vec<u32> = order.into_iter().collect();
        assert_eq!(face.len(), n, "every master face given");
        let mut slot = vec![u32::MAX; n];
        for (s, &f) in face.iter().enumerate() {
            assert_eq!(slot[f as usize], u32::MAX, "face {f} given twice");
            slot[f as usize] = s as u32;
        }
        let far = slot
            .windows(2)
            .filter(|w| w[0].abs_diff(w[1]) > NEAR_SLOTS)
            .count();
        drop(slot);
        if far * 10 <= n {
            return Self { face, packed: None };
        }
        // One pass over the faces in slot order reads each face and its nodes once, in
        // blocks on the current rayon pool (the mesh is read in random order: the reads of a
        // block overlap); the blocks are appended in order, a wave at a time, so that the
        // copy is the same whatever the thread count and the transient memory is a wave's.
        let mut packed = Packed {
            start: Vec::with_capacity(n + 1),
            element: Vec::with_capacity(n),
            tag: Vec::with_capacity(n),
            columns: Vec::new(),
            coords: Vec::new(),
        };
        packed.start.push(0);
        for wave in face.chunks(COPY_BLOCK * COPY_WAVE) {
            let parts: Vec<Packed> = wave
                .par_chunks(COPY_BLOCK)
                .map(|faces| Packed::copy(interface, faces))
                .collect();
            for part in parts {
                packed.append(part);
            }
        }
        Self {
            face,
            packed: Some(packed),
        }
    }

    /// Writes the node coordinates of the master face in slot `s` of `interface` (the
    /// interface these were built for) into `out` and returns its element type and node
    /// count.
    #[inline]
    pub fn coords_into(
        &self,
        interface: &Interface,
        s: usize,
        out: &mut [Vector3<f64>; MAX_FACE_NODES],
    ) -> (ElementRef, usize) {
        match &self.packed {
            Some(p) => {
                let (a, b) = (p.start[s] as usize, p.start[s + 1] as usize);
                out[..b - a].copy_from_slice(&p.coords[a..b]);
                (p.element[s], b - a)
            }
            None => {
                let mesh = interface.master();
                let view = mesh.face(self.face[s] as usize);
                for (o, &n) in out.iter_mut().zip(view.nodes) {
                    *o = mesh.coords()[n as usize];
                }
                (view.element, view.nodes.len())
            }
        }
    }

    /// Writes the node coordinates of the master face in slot `s` into `out` and returns the
    /// node count: [`coords_into`](Self::coords_into) without the element type (which costs
    /// a read of its own where the faces are not copied).
    #[inline]
    pub fn node_coords_into(
        &self,
        interface: &Interface,
        s: usize,
        out: &mut [Vector3<f64>; MAX_FACE_NODES],
    ) -> usize {
        match &self.packed {
            Some(p) => {
                let (a, b) = (p.start[s] as usize, p.start[s + 1] as usize);
                out[..b - a].copy_from_slice(&p.coords[a..b]);
                b - a
            }
            None => interface
                .master()
                .face_coords_into(self.face[s] as usize, out),
        }
    }

    /// Writes the columns in M of the nodes of the master face in slot `s` into `out` and
    /// returns the node count.
    #[inline]
    pub fn columns_into(
        &self,
        interface: &Interface,
        s: usize,
        out: &mut [u32; MAX_FACE_NODES],
    ) -> usize {
        match &self.packed {
            Some(p) => {
                let (a, b) = (p.start[s] as usize, p.start[s + 1] as usize);
                out[..b - a].copy_from_slice(&p.columns[a..b]);
                b - a
            }
            None => {
                let nodes = interface.master().face(self.face[s] as usize).nodes;
                for (o, &n) in out.iter_mut().zip(nodes) {
                    *o = interface
                        .master_col(n)
                        .expect("the nodes of a master face are on the interface");
                }
                nodes.len()
            }
        }
    }

    /// The tag of the master face in slot `s`.
    pub fn tag(&self, interface: &Interface, s: usize) -> u64 {
        match &self.packed {
            Some(p) => p.tag[s],
            None => interface.master().face(self.face[s] as usize).tag,
        }
    }

    /// The element type of the master face in slot `s`.
    #[inline]
    pub fn element(&self, interface: &Interface, s: usize) -> ElementRef {
        match &self.packed {
            Some(p) => p.element[s],
            None => interface.master().face(self.face[s] as usize).element,
        }
    }

    /// The index in the master mesh of the face in slot `s`.
    #[inline]
    pub fn face_index(&self, s: usize) -> usize {
        self.face[s] as usize
    }

    /// Whether the faces were copied in slot order (the mesh's numbering is not spatially
    /// coherent).
    pub fn is_packed(&self) -> bool {
        self.packed.is_some()
    }

    /// The number of faces.
    pub fn len(&self) -> usize {
        self.face.len()
    }

    /// Whether there is no face.
    pub fn is_empty(&self) -> bool {
        self.face.is_empty()
    }

    /// Bytes held.
    pub fn memory_bytes(&self) -> usize {
        self.face.len() * 4
            + self.packed.as_ref().map_or(0, |p| {
                p.start.len() * 4
                    + p.element.len() * std::mem::size_of::<ElementRef>()
                    + p.tag.len() * 8
                    + p.columns.len() * 4
                    + p.coords.len() * 24
            })
    }
}
