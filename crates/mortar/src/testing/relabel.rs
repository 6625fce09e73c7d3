//! Node relabelling: the same surface under other node tags and another storage order.

use std::collections::HashMap;

use mortar_core::element::ReferenceDomain;
use mortar_core::error::Result;
use mortar_core::mesh::SurfaceMesh;
use proptest::prelude::*;

/// A relabelling of a mesh of a given node and face count: new node tags, and the order in
/// which nodes and faces are stored. Apply it with [`Relabelling::apply`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Relabelling {
    /// The new tag of each node, by node index of the original mesh (distinct).
    pub tags: Vec<u64>,
    /// The original node indices in the order the new mesh stores them.
    pub node_order: Vec<usize>,
    /// The original face indices in the order the new mesh stores them.
    pub face_order: Vec<usize>,
    /// Per original face, how many places its node list is rotated. Only faces whose nodes
    /// are all corners (Tri3, Quad4) are rotated, which keeps their orientation; lines and
    /// higher-order faces keep their node order.
    pub rotations: Vec<usize>,
}

impl Relabelling {
    /// The relabelled copy of `mesh`: node `i` gets tag `tags[i]`, nodes and faces are stored
    /// in the new orders, face node lists are rotated, face tags are kept.
    ///
    /// # Errors
    /// The mesh-building errors of [`SurfaceMesh`] (none for a relabelling drawn for this
    /// mesh's sizes).
    ///
    /// # Panics
    /// If the relabelling was drawn for a mesh with other node or face counts.
    pub fn apply(&self, mesh: &SurfaceMesh) -> Result<SurfaceMesh> {
        assert_eq!(self.tags.len(), mesh.node_count(), "one tag per node");
        assert_eq!(
            self.face_order.len(),
            mesh.face_count(),
            "one entry per face"
        );
        let mut out = SurfaceMesh::with_capacity(mesh.node_count(), mesh.face_count());
        for &i in &self.node_order {
            out.add_node(self.tags[i], mesh.coords()[i].into())?;
        }
        let mut nodes = Vec::new();
        for &f in &self.face_order {
            let face = mesh.face(f);
            nodes.clear();
            nodes.extend(face.nodes.iter().map(|&n| self.tags[n as usize]));
            let el = face.element;
            if el.domain() != ReferenceDomain::Line && el.node_count() == el.corner_count() {
                let k = nodes.len();
                nodes.rotate_left(self.rotations[f] % k);
            }
            out.add_face_with_tag(face.tag, el, &nodes)?;
        }
        Ok(out)
    }

    /// The map from the original node tags of `mesh` to the new ones.
    pub fn tag_map(&self, mesh: &SurfaceMesh) -> HashMap<u64, u64> {
        mesh.node_tags()
            .iter()
            .zip(&self.tags)
            .map(|(&old, &new)| (old, new))
            .collect()
    }
}

/// A relabelling for a mesh of `nodes` nodes and `faces` faces: new tags
/// `base + stride * p(i)` for a random permutation `p`, a base up to `1e12` and a stride up
/// to 1000 (so tags are sparse, large and in another order), random storage orders of nodes
/// and faces, and random rotations of face node lists. Shrinks towards small bases, stride 1
/// and the original orders.
pub fn relabelling(nodes: usize, faces: usize) -> impl Strategy<Value = Relabelling> {
    let identity = |n: usize| (0..n).collect::<Vec<usize>>();
    (
        0..=1_000_000_000_000u64,
        1..=1000u64,
        Just(identity(nodes)).prop_shuffle(),
        Just(identity(nodes)).prop_shuffle(),
        Just(identity(faces)).prop_shuffle(),
        prop::collection::vec(0..4usize, faces),
    )
        .prop_map(
            |(base, stride, perm, node_order, face_order, rotations)| Relabelling {
                tags: perm.iter().map(|&p| base + stride * p as u64).collect(),
                node_order,
                face_order,
                rotations,
            },
        )
}

/// A mesh relabelled, with the map from old to new tags.
#[derive(Debug, Clone)]
pub struct Relabelled {
    /// The relabelled copy.
    pub mesh: SurfaceMesh,
    /// Original node tag -> new node tag.
    pub tag_map: HashMap<u64, u64>,
}

/// A relabelled copy of `mesh` (see [`relabelling`]), with the tag map.
pub fn relabelled(mesh: SurfaceMesh) -> impl Strategy<Value = Relabelled> {
    relabelling(mesh.node_count(), mesh.face_count()).prop_map(move |r| Relabelled {
        mesh: r
            .apply(&mesh)
            .expect("a relabelling drawn for this mesh builds a valid mesh"),
        tag_map: r.tag_map(&mesh),
    })
}

/// `mesh` with its nodes and faces stored in a random order drawn from `seed` (tags, face
/// tags and node lists kept): the worst case of a file's numbering, faces and nodes far
/// apart. The same seed gives the same copy.
///
/// # Errors
/// The mesh-building errors of [`SurfaceMesh`] (none for a valid `mesh`).
pub fn shuffled(mesh: &SurfaceMesh, seed: u64) -> Result<SurfaceMesh> {
    shuffle(mesh, seed, true)
}

/// `mesh` with its faces (not its nodes) stored in a random order drawn from `seed`: a file
/// whose element order jumps around while its nodes stay in a coherent order, as Gmsh writes
/// a Frontal-Delaunay mesh. The same seed gives the same copy.
///
/// # Errors
/// The mesh-building errors of [`SurfaceMesh`] (none for a valid `mesh`).
pub fn shuffled_faces(mesh: &SurfaceMesh, seed: u64) -> Result<SurfaceMesh> {
    shuffle(mesh, seed, false)
}

fn shuffle(mesh: &SurfaceMesh, seed: u64, nodes: bool) -> Result<SurfaceMesh> {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mut bytes = [0u8; 32];
    bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &bytes);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let mut order = |n: usize| {
        Just((0..n).collect::<Vec<usize>>())
            .prop_shuffle()
            .new_tree(&mut runner)
            .map(|t| t.current())
            .unwrap_or_else(|_| (0..n).collect())
    };
    let node_order = if nodes {
        order(mesh.node_count())
    } else {
        (0..mesh.node_count()).collect()
    };
    let face_order = order(mesh.face_count());
    Relabelling {
        tags: mesh.node_tags().to_vec(),
        node_order,
        face_order,
        rotations: vec![0; mesh.face_count()],
    }
    .apply(mesh)
}
