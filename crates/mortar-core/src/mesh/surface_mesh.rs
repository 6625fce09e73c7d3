//! `SurfaceMesh`: the nodes and faces of one side of an interface (tags, coordinates, element
//! types and connectivity), and `FaceView`, one face read from it.

use nalgebra::Vector3;

use super::nodes::{NodeRefusal, NodeSet};
use crate::element::{ElementRef, MAX_FACE_NODES};
use crate::error::{FaceLocation, MortarError, Result};

/// A surface mesh: the faces of one side of an interface.
///
/// Nodes carry a tag (the node number of the input mesh) and 3D coordinates (`z = 0` for 2D
/// problems). Faces carry an element type, their node indices and a tag. Rows and columns of
/// the coupling operators follow the ascending node tags.
///
/// ```
/// # use mortar_core::mesh::SurfaceMesh;
/// # fn tri3() -> mortar_core::element::ElementRef { unimplemented!() }
/// # fn demo() -> mortar_core::error::Result<()> {
/// let mut mesh = SurfaceMesh::new();
/// mesh.add_node(1, [0.0, 0.0, 0.0])?;
/// mesh.add_node(2, [1.0, 0.0, 0.0])?;
/// mesh.add_node(3, [0.0, 1.0, 0.0])?;
/// mesh.add_face(tri3(), &[1, 2, 3])?;
/// # Ok(()) }
/// ```
#[derive(Debug, Clone, Default)]
pub struct SurfaceMesh {
    nodes: NodeSet,
    face_offsets: Vec<u32>,
    face_nodes: Vec<u32>,
    /// The distinct element types, and each face's index into them (one byte a face).
    element_types: Vec<ElementRef>,
    face_types: Vec<u8>,
    face_tags: Vec<u64>,
}

/// A borrowed view of one face.
#[derive(Debug, Clone, Copy)]
pub struct FaceView<'a> {
    /// The element type.
    pub element: ElementRef,
    /// Node indices (into the mesh's node arrays), in element order.
    pub nodes: &'a [u32],
    /// The face tag.
    pub tag: u64,
}

impl SurfaceMesh {
    /// An empty mesh.
    pub fn new() -> Self {
        Self {
            face_offsets: vec![0],
            ..Default::default()
        }
    }

    /// An empty mesh with room for `nodes` nodes and `faces` faces.
    pub fn with_capacity(nodes: usize, faces: usize) -> Self {
        let mut mesh = Self::new();
        mesh.nodes.reserve(nodes);
        mesh.face_offsets.reserve(faces);
        mesh.face_types.reserve(faces);
        mesh.face_tags.reserve(faces);
        mesh
    }

    /// Adds a node and returns its index.
    ///
    /// # Errors
    /// [`MortarError::NonFiniteCoordinate`] for NaN or infinite coordinates,
    /// [`MortarError::DuplicateNode`] if the tag is already used.
    pub fn add_node(&mut self, tag: u64, coords: [f64; 3]) -> Result<u32> {
        self.nodes.add(tag, coords).map_err(|r| match r {
            NodeRefusal::NonFinite => MortarError::NonFiniteCoordinate { tag, coords },
            NodeRefusal::Duplicate => MortarError::DuplicateNode { tag },
        })
    }

    /// Adds a face given by node tags; its tag is its position plus one.
    ///
    /// # Errors
    /// See [`add_face_with_tag`](Self::add_face_with_tag).
    pub fn add_face(&mut self, element: ElementRef, node_tags: &[u64]) -> Result<u32> {
        let tag = self.face_count() as u64 + 1;
        self.add_face_with_tag(tag, element, node_tags)
    }

    /// Adds a face with an explicit tag and returns its index.
    ///
    /// # Errors
    /// [`MortarError::WrongNodeCount`] if `node_tags` does not match the element,
    /// [`MortarError::UnknownNode`] if a node tag is not in the mesh.
    pub fn add_face_with_tag(
        &mut self,
        tag: u64,
        element: ElementRef,
        node_tags: &[u64],
    ) -> Result<u32> {
        let face = FaceLocation { side: None, tag };
        if node_tags.len() != element.node_count() || node_tags.len() > MAX_FACE_NODES {
            return Err(MortarError::WrongNodeCount {
                face,
                element: element.name(),
                expected: element.node_count(),
                got: node_tags.len(),
            });
        }
        let start = self.face_nodes.len();
        for &t in node_tags {
            match self.nodes.index_of(t).as_ref() {
                Some(&i) => self.face_nodes.push(i),
                None => {
                    self.face_nodes.truncate(start);
                    return Err(MortarError::UnknownNode { face, node: t });
                }
            }
        }
        let kind = match self
            .element_types
            .iter()
            // Same data pointer and same vtable: zero-sized element types of different kinds
            // may share an address, but not a vtable; two types whose vtables were merged have
            // the same methods and so behave the same.
            .position(|e| std::ptr::eq(*e, element))
        {
            Some(k) => k,
            None if self.element_types.len() < u8::MAX as usize => {
                self.element_types.push(element);
                self.element_types.len() - 1
            }
            None => {
                self.face_nodes.truncate(start);
                return Err(MortarError::InvalidOption {
                    option: "element types of a surface mesh",
                    value: (self.element_types.len() + 1).to_string(),
                    reason: format!("a surface mesh holds at most {}", u8::MAX),
                });
            }
        };
        self.face_offsets.push(self.face_nodes.len() as u32);
        self.face_types.push(kind as u8);
        self.face_tags.push(tag);
        Ok(self.face_types.len() as u32 - 1)
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.coords.len()
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_types.len()
    }

    /// All node coordinates.
    pub fn coords(&self) -> &[Vector3<f64>] {
        &self.nodes.coords
    }

    /// All node tags.
    pub fn node_tags(&self) -> &[u64] {
        &self.nodes.tags
    }

    /// The index of the node with tag `tag`.
    pub fn node_index(&self, tag: u64) -> Option<u32> {
        self.nodes.index_of(tag)
    }

    /// One face.
    ///
    /// # Panics
    /// If `face >= face_count()`.
    pub fn face(&self, face: usize) -> FaceView<'_> {
        let (a, b) = (
            self.face_offsets[face] as usize,
            self.face_offsets[face + 1] as usize,
        );
        FaceView {
            element: self.element_types[self.face_types[face] as usize],
            nodes: &self.face_nodes[a..b],
            tag: self.face_tags[face],
        }
    }

    /// The index of face `face`'s element type in [`element_types`](Self::element_types).
    ///
    /// # Panics
    /// If `face >= face_count()`.
    pub(crate) fn face_type_index(&self, face: usize) -> u8 {
        self.face_types[face]
    }

    /// The distinct element types of the faces (each face's type is one of these).
    pub fn element_types(&self) -> &[ElementRef] {
        &self.element_types
    }

    /// The node indices of face `face` (into the mesh's node arrays), in element order: the
    /// part of [`face`](Self::face) that reads neither the element type nor the tag.
    ///
    /// # Panics
    /// If `face >= face_count()`.
    #[inline]
    pub fn face_nodes(&self, face: usize) -> &[u32] {
        &self.face_nodes[self.face_offsets[face] as usize..self.face_offsets[face + 1] as usize]
    }

    /// The node indices of all faces, face after face (face `f`'s are
    /// [`face_nodes`](Self::face_nodes)`(f)`): `2 f` and `2 f + 1` in a mesh of two-node
    /// faces.
    pub(crate) fn all_face_nodes(&self) -> &[u32] {
        &self.face_nodes
    }

    /// Copies the coordinates of a face's nodes into `out` and returns the node count.
    ///
    /// # Panics
    /// If `face >= face_count()`.
    pub fn face_coords_into(&self, face: usize, out: &mut [Vector3<f64>; MAX_FACE_NODES]) -> usize {
        let nodes = self.face_nodes(face);
        for (o, &n) in out.iter_mut().zip(nodes) {
            *o = self.nodes.coords[n as usize];
        }
        nodes.len()
    }

    /// Reverses the orientation of face `face` (its normal), by
    /// [`SurfaceElement::reverse_nodes`](crate::element::SurfaceElement::reverse_nodes).
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] if the element cannot reverse its node order.
    ///
    /// # Panics
    /// If `face >= face_count()`.
    pub fn reverse_face(&mut self, face: usize) -> Result<()> {
        let (a, b) = (
            self.face_offsets[face] as usize,
            self.face_offsets[face + 1] as usize,
        );
        let element = self.element_types[self.face_types[face] as usize];
        if element.reverse_nodes(&mut self.face_nodes[a..b]) {
            Ok(())
        } else {
            Err(MortarError::InvalidOption {
                option: "reversing",
                value: format!("face {} ({})", self.face_tags[face], element.name()),
                reason: "the element does not say how (SurfaceElement::reverse_nodes)".into(),
            })
        }
    }

    /// The faces `faces` (indices, in that order) as a mesh of their own, with the nodes they
    /// use (in the order first used), tags kept: a rank's part of a surface, say.
    ///
    /// ```
    /// # use mortar_core::mesh::SurfaceMesh;
    /// # fn line2() -> mortar_core::element::ElementRef { unimplemented!() }
    /// # fn demo(line: &SurfaceMesh) -> mortar_core::error::Result<()> {
    /// // The second half of a line's faces.
    /// let n = line.face_count();
    /// let half = line.part(n / 2..n)?;
    /// assert_eq!(half.face_count(), n - n / 2);
    /// assert_eq!(half.face(0).tag, line.face(n / 2).tag);
    /// # Ok(()) }
    /// ```
    ///
    /// # Errors
    /// None for faces of this mesh (the `Result` carries the mesh-building errors through).
    ///
    /// # Panics
    /// If an index is not below `face_count()`.
    pub fn part(&self, faces: impl IntoIterator<Item = usize>) -> Result<SurfaceMesh> {
        let mut out = SurfaceMesh::new();
        let mut tags = Vec::new();
        for f in faces {
            let face = self.face(f);
            tags.clear();
            for &i in face.nodes {
                let tag = self.nodes.tags[i as usize];
                if out.node_index(tag).is_none() {
                    out.add_node(tag, self.nodes.coords[i as usize].into())?;
                }
                tags.push(tag);
            }
            out.add_face_with_tag(face.tag, face.element, &tags)?;
        }
        Ok(out)
    }

    /// Moves every node by `f` (rigid motions, scaling, or a deformed configuration).
    ///
    /// # Errors
    /// [`MortarError::NonFiniteCoordinate`] if `f` returns a non-finite point; the mesh is then
    /// left unchanged.
    pub fn transform(&mut self, f: impl Fn(Vector3<f64>) -> Vector3<f64>) -> Result<()> {
        let moved: Vec<Vector3<f64>> = self.nodes.coords.iter().map(|&x| f(x)).collect();
        if let Some(i) = moved.iter().position(|x| x.iter().any(|c| !c.is_finite())) {
            return Err(MortarError::NonFiniteCoordinate {
                tag: self.nodes.tags[i],
                coords: moved[i].into(),
            });
        }
        self.nodes.coords = moved;
        Ok(())
    }

    /// The heap memory the mesh holds, in bytes (its arrays at their capacity, and an estimate
    /// of the tag lookup table).
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        self.nodes.memory_bytes()
            + self.face_offsets.capacity() * size_of::<u32>()
            + self.face_nodes.capacity() * size_of::<u32>()
            + self.element_types.capacity() * size_of::<ElementRef>()
            + self.face_types.capacity()
            + self.face_tags.capacity() * size_of::<u64>()
    }

    /// The smallest axis-aligned box holding every node, as `(min, max)`; `None` if empty.
    pub fn bounding_box(&self) -> Option<(Vector3<f64>, Vector3<f64>)> {
        let first = *self.nodes.coords.first()?;
        Some(
            self.nodes
                .coords
                .iter()
                .fold((first, first), |(lo, hi), x| (lo.inf(x), hi.sup(x))),
        )
    }
}
