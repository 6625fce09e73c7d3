//! The master faces of an interface, copied in a spatial order.

use nalgebra::Vector3;

use super::Interface;
use crate::element::ElementRef;

/// The master faces of an [`Interface`] copied face after face in a given order (the Morton
/// order of the search tree): element type, column of each node in M, node coordinates. A
/// face is addressed by its *slot*, its position in that order. Faces near in space are then
/// near in memory whatever the file's numbering, so the master faces a slave face meets are
/// read from a few cache lines instead of from all over the mesh (a randomly numbered master
/// otherwise costs about 1.5x in the per-face work).
#[derive(Debug, Clone, Default)]
pub struct MasterFaces {
    /// Per slot, the face's index in the master mesh.
    face: Vec<u32>,
    /// Per slot, where its nodes start in `columns` and `coords` (one more than the faces).
    start: Vec<u32>,
    /// Per slot, the element type.
    element: Vec<ElementRef>,
    /// Per packed node, its column in M.
    columns: Vec<u32>,
    /// Per packed node, its coordinates.
    coords: Vec<Vector3<f64>>,
}

/// One master face of [`MasterFaces`].
#[derive(Debug, Clone, Copy)]
pub struct MasterFace<'a> {
    /// The element type.
    pub element: ElementRef,
    /// The column in M of each node, in element order.
    pub columns: &'a [u32],
    /// The coordinates of each node, in element order.
    pub coords: &'a [Vector3<f64>],
}

impl MasterFaces {
    /// The master faces of `interface`, stored in `order` (a permutation of the master face
    /// indices).
    ///
    /// # Panics
    /// If `order` is not a permutation of the master face indices, or the master faces have
    /// 2^32 nodes or more in all.
    pub fn new(interface: &Interface, order: impl IntoIterator<Item = u32>) -> Self {
        let mesh = interface.master();
        let n = mesh.face_count();
        let mut seen = vec![false; n];
        let mut out = Self {
            face: Vec::with_capacity(n),
            start: Vec::with_capacity(n + 1),
            element: Vec::with_capacity(n),
            columns: Vec::new(),
            coords: Vec::new(),
        };
        let xyz = mesh.coords();
        out.start.push(0);
        for f in order {
            let face = mesh.face(f as usize);
            assert!(
                !std::mem::replace(&mut seen[f as usize], true),
                "face {f} given twice"
            );
            out.face.push(f);
            out.element.push(face.element);
            for &i in face.nodes {
                out.columns.push(
                    interface
                        .master_col(i)
                        .expect("the nodes of a master face are on the interface"),
                );
                out.coords.push(xyz[i as usize]);
            }
            out.start
                .push(u32::try_from(out.coords.len()).expect("fewer than 2^32 master face nodes"));
        }
        assert_eq!(out.element.len(), n, "every master face given");
        out
    }

    /// The master face in slot `s`.
    #[inline]
    pub fn get(&self, s: usize) -> MasterFace<'_> {
        let (a, b) = (self.start[s] as usize, self.start[s + 1] as usize);
        MasterFace {
            element: self.element[s],
            columns: &self.columns[a..b],
            coords: &self.coords[a..b],
        }
    }

    /// The index in the master mesh of the face in slot `s`.
    #[inline]
    pub fn face_index(&self, s: usize) -> usize {
        self.face[s] as usize
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
            + self.start.len() * 4
            + self.element.len() * std::mem::size_of::<ElementRef>()
            + self.columns.len() * 4
            + self.coords.len() * 24
    }
}
