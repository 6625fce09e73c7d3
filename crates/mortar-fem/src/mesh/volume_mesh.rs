//! `VolumeMesh`: the nodes and cells of a body, the extraction of its boundary faces as a
//! `SurfaceMesh`, and `VolumeMeshError`, which names the node or cell at fault.

use arrayvec::ArrayVec;
use nalgebra::Vector3;

use mortar_core::element::{ElementRef, MAX_FACE_NODES};
use mortar_core::mesh::{NodeRefusal, NodeSet, SurfaceMesh};
use mortar_core::MortarError;

use crate::element::{VolumeElementRef, MAX_CELL_NODES};

/// Errors of a [`VolumeMesh`]: bad input when it is built, or a broken mesh found when its
/// boundary is extracted. Each names the node or cell (by tag).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum VolumeMeshError {
    /// A node coordinate is NaN or infinite.
    #[error("node {tag} has a non-finite coordinate {coords:?}")]
    NonFiniteCoordinate {
        /// Node tag.
        tag: u64,
        /// The coordinates.
        coords: [f64; 3],
    },
    /// Two nodes were given the same tag.
    #[error("node tag {tag} is used twice")]
    DuplicateNode {
        /// Node tag.
        tag: u64,
    },
    /// A node of a 2D mesh lies off the plane `z = 0`.
    #[error("node {tag} of a 2D mesh has z = {z:e}; 2D bodies lie in the plane z = 0")]
    OffPlane {
        /// Node tag.
        tag: u64,
        /// Its z coordinate.
        z: f64,
    },
    /// A cell refers to a node that the mesh does not have.
    #[error("cell {cell} refers to node {node}, which the mesh does not have")]
    UnknownNode {
        /// Cell tag.
        cell: u64,
        /// The missing node tag.
        node: u64,
    },
    /// A cell was given the wrong number of nodes for its element, or repeats a node.
    #[error("cell {cell} is a {element}: {reason}")]
    BadCell {
        /// Cell tag.
        cell: u64,
        /// Element name.
        element: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// Cells of reference dimension 2 and 3 in one mesh.
    #[error("cell {cell} has reference dimension {dim}, the mesh's cells have {expected}")]
    MixedDimensions {
        /// Cell tag.
        cell: u64,
        /// Its dimension.
        dim: usize,
        /// The dimension of the mesh's first cell.
        expected: usize,
    },
    /// A face is shared by more than two cells.
    #[error("the face with nodes {nodes:?} is shared by {cells} cells (at most 2)")]
    NonManifoldFace {
        /// The face's node tags.
        nodes: Vec<u64>,
        /// How many cells share it.
        cells: usize,
    },
    /// No boundary face was selected.
    #[error("no boundary face matches the selection")]
    EmptySelection,
    /// Building the surface mesh failed (it cannot, for a valid volume mesh).
    #[error(transparent)]
    Surface(#[from] MortarError),
}

/// A mesh of a body: nodes with tags and coordinates, cells with a volume element type.
///
/// 2D bodies lie in the plane `z = 0` and use 2D cells (Tri3, Quad4); 3D bodies use Tet4 or
/// Hex8 (see `mortar_elements::volume`). All cells of a mesh have one reference dimension.
/// Cells must be positively oriented (Gmsh node order): the physics reports an inverted cell
/// by its tag.
///
/// The boundary faces (faces of exactly one cell) come out with outward orientation, as a
/// [`SurfaceMesh`] that keeps the node tags, so that a body's interface faces are obtained by
/// [`boundary_surface`](VolumeMesh::boundary_surface) with a predicate, or
/// [`boundary_surface_on_nodes`](VolumeMesh::boundary_surface_on_nodes) with a node list.
///
/// ```text
/// let interface_faces = body.boundary_surface(|f| (f.centroid.x - 0.5).abs() < 1e-9)?;
/// ```
#[derive(Debug, Clone, Default)]
pub struct VolumeMesh {
    nodes: NodeSet,
    cell_offsets: Vec<u32>,
    cell_nodes: Vec<u32>,
    cell_elements: Vec<VolumeElementRef>,
    cell_tags: Vec<u64>,
}

/// A borrowed view of one cell.
#[derive(Debug, Clone, Copy)]
pub struct CellView<'a> {
    /// The element type.
    pub element: VolumeElementRef,
    /// Node indices (into the mesh's node arrays), in element order.
    pub nodes: &'a [u32],
    /// The cell tag.
    pub tag: u64,
}

/// One boundary face: a face of exactly one cell, its nodes in outward order.
#[derive(Debug, Clone)]
pub struct BoundaryFace {
    /// The cell (index) the face belongs to.
    pub cell: u32,
    /// The face's number within its cell's element.
    pub local_face: u8,
    /// The surface element type of the face.
    pub element: ElementRef,
    /// Node indices into the volume mesh, ordered so that the face normal points out.
    pub nodes: ArrayVec<u32, MAX_FACE_NODES>,
    /// The mean of the face's node coordinates.
    pub centroid: Vector3<f64>,
}

impl VolumeMesh {
    /// An empty mesh.
    pub fn new() -> Self {
        Self {
            cell_offsets: vec![0],
            ..Default::default()
        }
    }

    /// Adds a node and returns its index.
    ///
    /// # Errors
    /// [`VolumeMeshError::NonFiniteCoordinate`], [`VolumeMeshError::DuplicateNode`].
    pub fn add_node(&mut self, tag: u64, coords: [f64; 3]) -> Result<u32, VolumeMeshError> {
        self.nodes.add(tag, coords).map_err(|r| match r {
            NodeRefusal::NonFinite => VolumeMeshError::NonFiniteCoordinate { tag, coords },
            NodeRefusal::Duplicate => VolumeMeshError::DuplicateNode { tag },
        })
    }

    /// Adds a cell given by node tags; its tag is its position plus one.
    ///
    /// # Errors
    /// See [`add_cell_with_tag`](Self::add_cell_with_tag).
    pub fn add_cell(
        &mut self,
        element: VolumeElementRef,
        node_tags: &[u64],
    ) -> Result<u32, VolumeMeshError> {
        let tag = self.cell_count() as u64 + 1;
        self.add_cell_with_tag(tag, element, node_tags)
    }

    /// Adds a cell with an explicit tag and returns its index.
    ///
    /// # Errors
    /// [`VolumeMeshError::BadCell`] for a wrong node count or a repeated node,
    /// [`VolumeMeshError::UnknownNode`], [`VolumeMeshError::MixedDimensions`],
    /// [`VolumeMeshError::OffPlane`] for a 2D cell with a node off `z = 0`.
    pub fn add_cell_with_tag(
        &mut self,
        tag: u64,
        element: VolumeElementRef,
        node_tags: &[u64],
    ) -> Result<u32, VolumeMeshError> {
        let bad = |reason: String| VolumeMeshError::BadCell {
            cell: tag,
            element: element.name(),
            reason,
        };
        if node_tags.len() != element.node_count() || node_tags.len() > MAX_CELL_NODES {
            return Err(bad(format!(
                "needs {} nodes, got {}",
                element.node_count(),
                node_tags.len()
            )));
        }
        if let Some(first) = self.cell_elements.first() {
            if first.dim() != element.dim() {
                return Err(VolumeMeshError::MixedDimensions {
                    cell: tag,
                    dim: element.dim(),
                    expected: first.dim(),
                });
            }
        }
        let mut idx = ArrayVec::<u32, MAX_CELL_NODES>::new();
        for (i, &t) in node_tags.iter().enumerate() {
            if node_tags[..i].contains(&t) {
                return Err(bad(format!("node {t} appears twice")));
            }
            let n = self
                .nodes
                .index_of(t)
                .ok_or(VolumeMeshError::UnknownNode { cell: tag, node: t })?;
            if element.dim() == 2 && self.nodes.coords()[n as usize].z != 0.0 {
                return Err(VolumeMeshError::OffPlane {
                    tag: t,
                    z: self.nodes.coords()[n as usize].z,
                });
            }
            idx.push(n);
        }
        self.cell_nodes.extend_from_slice(&idx);
        self.cell_offsets.push(self.cell_nodes.len() as u32);
        self.cell_elements.push(element);
        self.cell_tags.push(tag);
        Ok(self.cell_elements.len() as u32 - 1)
    }

    /// The reference dimension of the cells (2 or 3); `None` without cells.
    pub fn dim(&self) -> Option<usize> {
        self.cell_elements.first().map(|e| e.dim())
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.coords().len()
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.cell_elements.len()
    }

    /// All node coordinates.
    pub fn coords(&self) -> &[Vector3<f64>] {
        self.nodes.coords()
    }

    /// Moves every node by `f` (a rigid motion, a scaling, a distortion of the mesh inside a
    /// fixed boundary). Cells that `f` inverts are refused later, by whatever integrates over
    /// them.
    ///
    /// # Errors
    /// [`VolumeMeshError::NonFiniteCoordinate`] if `f` returns a non-finite point; the mesh is
    /// then left unchanged.
    pub fn transform(
        &mut self,
        f: impl Fn(Vector3<f64>) -> Vector3<f64>,
    ) -> Result<(), VolumeMeshError> {
        let moved: Vec<Vector3<f64>> = self.nodes.coords().iter().map(|&x| f(x)).collect();
        if let Some(i) = moved.iter().position(|x| x.iter().any(|c| !c.is_finite())) {
            return Err(VolumeMeshError::NonFiniteCoordinate {
                tag: self.nodes.tags()[i],
                coords: moved[i].into(),
            });
        }
        self.nodes.coords_mut().copy_from_slice(&moved);
        Ok(())
    }

    /// All node tags.
    pub fn node_tags(&self) -> &[u64] {
        self.nodes.tags()
    }

    /// The index of the node with tag `tag`.
    pub fn node_index(&self, tag: u64) -> Option<u32> {
        self.nodes.index_of(tag)
    }

    /// One cell.
    ///
    /// # Panics
    /// If `cell >= cell_count()`.
    pub fn cell(&self, cell: usize) -> CellView<'_> {
        let (a, b) = (
            self.cell_offsets[cell] as usize,
            self.cell_offsets[cell + 1] as usize,
        );
        CellView {
            element: self.cell_elements[cell],
            nodes: &self.cell_nodes[a..b],
            tag: self.cell_tags[cell],
        }
    }

    /// Copies the coordinates of a cell's nodes into `out` and returns the node count.
    ///
    /// # Panics
    /// If `cell >= cell_count()`.
    pub fn cell_coords_into(&self, cell: usize, out: &mut [Vector3<f64>; MAX_CELL_NODES]) -> usize {
        let view = self.cell(cell);
        for (o, &n) in out.iter_mut().zip(view.nodes) {
            *o = self.nodes.coords()[n as usize];
        }
        view.nodes.len()
    }

    /// The boundary faces: faces of exactly one cell, in cell order and, within a cell, in
    /// the element's face order; nodes in outward order.
    ///
    /// # Errors
    /// [`VolumeMeshError::NonManifoldFace`] if a face is shared by more than two cells.
    pub fn boundary_faces(&self) -> Result<Vec<BoundaryFace>, VolumeMeshError> {
        type Key = [u32; MAX_FACE_NODES];
        let key = |nodes: &[u32]| -> Key {
            let mut k = [u32::MAX; MAX_FACE_NODES];
            k[..nodes.len()].copy_from_slice(nodes);
            k[..nodes.len()].sort_unstable();
            k
        };
        // Group the faces by their node set (cheaper than hashing, and without a hash map's
        // memory): equal keys are the cells sharing a face. A counting sort by the smallest
        // node puts the faces that can be equal into one short bucket (the faces around a
        // node), sorted there by the whole key.
        let mut keys: Vec<Key> = Vec::with_capacity(4 * self.cell_count());
        let mut local = ArrayVec::<u32, MAX_FACE_NODES>::new();
        for c in 0..self.cell_count() {
            let cell = self.cell(c);
            for f in cell.element.faces() {
                local.clear();
                local.extend(f.iter().map(|&i| cell.nodes[i]));
                keys.push(key(&local));
            }
        }
        let mut start = vec![0usize; self.node_count() + 1];
        for k in &keys {
            start[k[0] as usize + 1] += 1;
        }
        for i in 0..self.node_count() {
            start[i + 1] += start[i];
        }
        let mut order = vec![0u32; keys.len()];
        let mut next = start.clone();
        for (id, k) in keys.iter().enumerate() {
            order[next[k[0] as usize]] = id as u32;
            next[k[0] as usize] += 1;
        }
        drop(next);
        let mut count = vec![0u32; keys.len()];
        for w in start.windows(2) {
            let bucket = &mut order[w[0]..w[1]];
            bucket.sort_unstable_by_key(|&id| (keys[id as usize], id));
            for group in bucket.chunk_by(|&a, &b| keys[a as usize] == keys[b as usize]) {
                for &id in group {
                    count[id as usize] = group.len() as u32;
                }
            }
        }
        drop((keys, order, start));
        let mut out = Vec::new();
        let mut id = 0usize;
        for c in 0..self.cell_count() {
            let cell = self.cell(c);
            for (lf, f) in cell.element.faces().iter().enumerate() {
                let shared = count[id];
                id += 1;
                local.clear();
                local.extend(f.iter().map(|&i| cell.nodes[i]));
                match shared {
                    1 => {}
                    2 => continue,
                    n => {
                        return Err(VolumeMeshError::NonManifoldFace {
                            nodes: local
                                .iter()
                                .map(|&i| self.nodes.tags()[i as usize])
                                .collect(),
                            cells: n as usize,
                        })
                    }
                }
                let centroid = local.iter().fold(Vector3::zeros(), |s, &i| {
                    s + self.nodes.coords()[i as usize]
                }) / local.len() as f64;
                out.push(BoundaryFace {
                    cell: c as u32,
                    local_face: lf as u8,
                    element: cell.element.face_element(lf),
                    nodes: local.clone(),
                    centroid,
                });
            }
        }
        Ok(out)
    }

    /// The boundary faces for which `select` is true, as an outward-oriented surface mesh.
    /// The surface keeps the node tags of this mesh (nodes in ascending index order); its
    /// faces are tagged 1, 2, ... in boundary-face order.
    ///
    /// # Errors
    /// [`VolumeMeshError::EmptySelection`] if no face is selected; the errors of
    /// [`boundary_faces`](Self::boundary_faces).
    pub fn boundary_surface(
        &self,
        select: impl Fn(&BoundaryFace) -> bool,
    ) -> Result<SurfaceMesh, VolumeMeshError> {
        let faces: Vec<BoundaryFace> = self
            .boundary_faces()?
            .into_iter()
            .filter(|f| select(f))
            .collect();
        self.surface_of(&faces)
    }

    /// The boundary faces all of whose nodes are in `node_tags`, as a surface mesh (see
    /// [`boundary_surface`](Self::boundary_surface)).
    ///
    /// # Errors
    /// As [`boundary_surface`](Self::boundary_surface).
    pub fn boundary_surface_on_nodes(
        &self,
        node_tags: &[u64],
    ) -> Result<SurfaceMesh, VolumeMeshError> {
        let mut on = vec![false; self.node_count()];
        for t in node_tags {
            if let Some(i) = self.node_index(*t) {
                on[i as usize] = true;
            }
        }
        self.boundary_surface(|f| f.nodes.iter().all(|&n| on[n as usize]))
    }

    /// The indices of the nodes on boundary faces for which `select` is true, ascending.
    ///
    /// # Errors
    /// The errors of [`boundary_faces`](Self::boundary_faces).
    pub fn boundary_nodes(
        &self,
        select: impl Fn(&BoundaryFace) -> bool,
    ) -> Result<Vec<u32>, VolumeMeshError> {
        let mut on = vec![false; self.node_count()];
        for f in self.boundary_faces()?.iter().filter(|f| select(f)) {
            for &n in &f.nodes {
                on[n as usize] = true;
            }
        }
        Ok((0..self.node_count() as u32)
            .filter(|&n| on[n as usize])
            .collect())
    }

    /// A surface mesh of the given faces (nodes in ascending index order with their tags).
    fn surface_of(&self, faces: &[BoundaryFace]) -> Result<SurfaceMesh, VolumeMeshError> {
        if faces.is_empty() {
            return Err(VolumeMeshError::EmptySelection);
        }
        let mut used = vec![false; self.node_count()];
        for f in faces {
            for &n in &f.nodes {
                used[n as usize] = true;
            }
        }
        let count = used.iter().filter(|u| **u).count();
        let mut mesh = SurfaceMesh::with_capacity(count, faces.len());
        for (i, _) in used.iter().enumerate().filter(|(_, u)| **u) {
            mesh.add_node(self.nodes.tags()[i], self.nodes.coords()[i].into())?;
        }
        let mut tags = ArrayVec::<u64, MAX_FACE_NODES>::new();
        for (k, f) in faces.iter().enumerate() {
            tags.clear();
            tags.extend(f.nodes.iter().map(|&n| self.nodes.tags()[n as usize]));
            mesh.add_face_with_tag(k as u64 + 1, f.element, &tags)?;
        }
        Ok(mesh)
    }
}
