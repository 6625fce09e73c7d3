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
        // The gathers read the mesh in random order: run them on the current rayon pool (the
        // collected order is the given one).
        let (element, tag): (Vec<ElementRef>, Vec<u64>) = face
            .par_iter()
            .map(|&f| {
                let view = mesh.face(f as usize);
                (view.element, view.tag)
            })
            .unzip();
        let mut start = Vec::with_capacity(n + 1);
        start.push(0u32);
        for e in &element {
            let last = *start.last().unwrap_or(&0) as usize;
            start.push(
                u32::try_from(last + e.node_count()).expect("fewer than 2^32 master face nodes"),
            );
        }
        let xyz = mesh.coords();
        let columns: Vec<u32> = face
            .par_iter()
            .flat_map_iter(|&f| {
                mesh.face(f as usize).nodes.iter().map(|&i| {
                    interface
                        .master_col(i)
                        .expect("the nodes of a master face are on the interface")
                })
            })
            .collect();
        let coords: Vec<Vector3<f64>> = face
            .par_iter()
            .flat_map_iter(|&f| mesh.face(f as usize).nodes.iter().map(|&i| xyz[i as usize]))
            .collect();
        Self {
            face,
            packed: Some(Packed {
                start,
                element,
                tag,
                columns,
                coords,
            }),
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
