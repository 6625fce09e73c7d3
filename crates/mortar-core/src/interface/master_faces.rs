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
/// over memory (1.4x to 2x the per-face work): the faces are then copied in slot order, and
/// their nodes with them, renumbered as first met in that order (each node's coordinates and
/// column in M once, however many faces share it), at a cost of about 40 bytes per Tri3 face
/// (the slot's face, its tag, three node indices, and half a node). [`MasterFaces::is_packed`]
/// says which.
#[derive(Debug, Clone, Default)]
pub struct MasterFaces {
    /// Per slot, the face's index in the master mesh.
    face: Vec<u32>,
    /// The packed copy, when the numbering is not spatially coherent.
    packed: Option<Packed>,
}

/// The faces in slot order, their nodes renumbered as first met in that order.
#[derive(Debug, Clone, Default)]
struct Packed {
    /// The node count of every face when they all have the same; else 0, and `start` says.
    stride: usize,
    /// Per slot, where its nodes start in `nodes` (one more than the faces); empty with a
    /// stride.
    start: Vec<u32>,
    /// Per slot, the index of its element type in the master mesh's
    /// [`element_types`](crate::mesh::SurfaceMesh::element_types); empty when there is one.
    types: Vec<u8>,
    /// Per slot, the face tag.
    tag: Vec<u64>,
    /// Per node of each face, in slot order: the node's index in `coords` and `columns`.
    nodes: Vec<u32>,
    /// Per packed node, its coordinates.
    coords: Vec<Vector3<f64>>,
    /// Per packed node, its column in M.
    columns: Vec<u32>,
}

/// One block of faces as read from the mesh: their nodes (mesh indices), where each face's
/// nodes end (relative to the block), their type indices and tags.
struct Block {
    nodes: Vec<u32>,
    ends: Vec<u32>,
    types: Vec<u8>,
    tag: Vec<u64>,
}

/// The column in M of master mesh node `n`, a node of a master face.
///
/// # Panics
/// If `n` is on no master face (the interface maps every master face's nodes).
#[inline]
fn column(interface: &Interface, n: u32) -> u32 {
    interface
        .master_col(n)
        .expect("the nodes of a master face are on the interface")
}

/// Slot distance beyond which two faces consecutive in the file count as far apart.
const NEAR_SLOTS: u32 = 256;

/// Faces per block of the packed copy, and blocks per wave.
const COPY_BLOCK: usize = 4096;
const COPY_WAVE: usize = 64;

impl Block {
    /// The faces `faces` of `interface`'s master surface, in the given order.
    fn read(interface: &Interface, faces: &[u32]) -> Self {
        let mesh = interface.master();
        let mut out = Block {
            nodes: Vec::with_capacity(faces.len() * 4),
            ends: Vec::with_capacity(faces.len()),
            types: Vec::with_capacity(faces.len()),
            tag: Vec::with_capacity(faces.len()),
        };
        for &f in faces {
            let view = mesh.face(f as usize);
            out.nodes.extend_from_slice(view.nodes);
            out.ends.push(out.nodes.len() as u32);
            out.types.push(mesh.face_type_index(f as usize));
            out.tag.push(view.tag);
        }
        out
    }
}

impl Packed {
    /// The range of slot `s`'s nodes in `nodes`.
    #[inline]
    fn range(&self, s: usize) -> (usize, usize) {
        if self.stride > 0 {
            (s * self.stride, (s + 1) * self.stride)
        } else {
            (self.start[s] as usize, self.start[s + 1] as usize)
        }
    }

    /// The element type of slot `s`.
    #[inline]
    fn element(&self, interface: &Interface, s: usize) -> ElementRef {
        let types = interface.master().element_types();
        match self.types.get(s) {
            Some(&t) => types[t as usize],
            None => types[0],
        }
    }

    /// Appends a block read by [`Block::read`].
    ///
    /// # Panics
    /// If the faces have 2^32 nodes or more in all.
    fn append(&mut self, block: Block) {
        let base = *self.start.last().unwrap_or(&0);
        self.start.extend(block.ends.iter().map(|&e| {
            base.checked_add(e)
                .expect("fewer than 2^32 master face nodes")
        }));
        self.types.extend_from_slice(&block.types);
        self.tag.extend_from_slice(&block.tag);
        self.nodes.extend_from_slice(&block.nodes);
    }

    /// Renumbers `nodes` (mesh indices until then) as first met in slot order and copies
    /// each node's coordinates and column once; drops `start` and `types` where a stride and
    /// a single type say as much.
    fn finish(&mut self, interface: &Interface) {
        let mesh = interface.master();
        let mut local = vec![u32::MAX; mesh.node_count()];
        let mut order: Vec<u32> = Vec::new();
        for n in self.nodes.iter_mut() {
            let l = &mut local[*n as usize];
            if *l == u32::MAX {
                *l = order.len() as u32;
                order.push(*n);
            }
            *n = *l;
        }
        drop(local);
        let xyz = mesh.coords();
        self.coords = order.par_iter().map(|&n| xyz[n as usize]).collect();
        self.columns = order.par_iter().map(|&n| column(interface, n)).collect();
        let types = mesh.element_types();
        let first = types.first().map_or(0, |e| e.node_count());
        if types.iter().all(|e| e.node_count() == first) {
            self.stride = first;
            self.start = Vec::new();
        }
        if types.len() <= 1 {
            self.types = Vec::new();
        }
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
            types: Vec::with_capacity(n),
            tag: Vec::with_capacity(n),
            ..Default::default()
        };
        packed.start.push(0);
        for wave in face.chunks(COPY_BLOCK * COPY_WAVE) {
            let parts: Vec<Block> = wave
                .par_chunks(COPY_BLOCK)
                .map(|faces| Block::read(interface, faces))
                .collect();
            for part in parts {
                packed.append(part);
            }
        }
        packed.finish(interface);
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
                let (a, b) = p.range(s);
                for (o, &i) in out.iter_mut().zip(&p.nodes[a..b]) {
                    *o = p.coords[i as usize];
                }
                (p.element(interface, s), b - a)
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

    /// The element type of the master face in slot `s`, its node count, and the coordinates
    /// and columns of its first `nodes.len()` nodes written into `nodes` and `cols`:
    /// [`coords_into`](Self::coords_into) and [`columns_into`](Self::columns_into) in one
    /// read, for faces of few nodes.
    pub(crate) fn corners_into(
        &self,
        interface: &Interface,
        s: usize,
        nodes: &mut [Vector3<f64>],
        cols: &mut [u32],
    ) -> (ElementRef, usize) {
        match &self.packed {
            Some(p) => {
                let (a, b) = p.range(s);
                for ((x, c), &i) in nodes.iter_mut().zip(cols.iter_mut()).zip(&p.nodes[a..b]) {
                    *x = p.coords[i as usize];
                    *c = p.columns[i as usize];
                }
                (p.element(interface, s), b - a)
            }
            None => {
                let mesh = interface.master();
                let view = mesh.face(self.face[s] as usize);
                for ((x, c), &n) in nodes.iter_mut().zip(cols.iter_mut()).zip(view.nodes) {
                    *x = mesh.coords()[n as usize];
                    *c = column(interface, n);
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
                let (a, b) = p.range(s);
                for (o, &i) in out.iter_mut().zip(&p.nodes[a..b]) {
                    *o = p.coords[i as usize];
                }
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
                let (a, b) = p.range(s);
                for (o, &i) in out.iter_mut().zip(&p.nodes[a..b]) {
                    *o = p.columns[i as usize];
                }
                b - a
            }
            None => {
                let nodes = interface.master().face(self.face[s] as usize).nodes;
                for (o, &n) in out.iter_mut().zip(nodes) {
                    *o = column(interface, n);
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
            Some(p) => p.element(interface, s),
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
                    + p.types.len()
                    + p.tag.len() * 8
                    + p.nodes.len() * 4
                    + p.columns.len() * 4
                    + p.coords.len() * 24
            })
    }
}
