//! Pairs of meshes that cover the same surface: non-matching covered interfaces.

use std::fmt;
use std::ops::RangeInclusive;

use mortar_core::error::Result;
use mortar_core::mesh::SurfaceMesh;
use mortar_core::Interface;
use nalgebra::Vector3;
use proptest::prelude::*;

use super::mesh::{perturbed_line, perturbed_square, CellKind, MAX_LINE_JITTER, MAX_SQUARE_JITTER};

/// A slave and a master mesh, ready to make an [`Interface`].
///
/// Its `Debug` output is compact, one line per node (`tag: [x, y, z]`, coordinates printed
/// exactly) and per face (`tag Element [node tags]`), so a shrunk failing case can be pasted
/// into a test.
#[derive(Clone)]
pub struct MeshPair {
    /// The slave (non-mortar) surface.
    pub slave: SurfaceMesh,
    /// The master (mortar) surface.
    pub master: SurfaceMesh,
}

impl MeshPair {
    /// The validated interface of the pair (clones both meshes).
    ///
    /// # Errors
    /// The validation errors of [`Interface::new`].
    pub fn interface(&self) -> Result<Interface> {
        Interface::new(self.slave.clone(), self.master.clone())
    }

    /// A copy with every node of both meshes moved by `f`.
    ///
    /// # Errors
    /// [`MortarError::NonFiniteCoordinate`](mortar_core::MortarError::NonFiniteCoordinate)
    /// if `f` returns a non-finite point.
    pub fn transformed(&self, f: impl Fn(Vector3<f64>) -> Vector3<f64>) -> Result<Self> {
        let mut out = self.clone();
        out.slave.transform(&f)?;
        out.master.transform(&f)?;
        Ok(out)
    }

    /// The shortest edge of the faces of both meshes: the length `h` that sets the round-off
    /// of a pair moved by `t` (its coordinates carry `eps |t|`, so relative figures carry
    /// `eps |t| / h`), the scale of an invariance test's tolerance.
    ///
    /// ```
    /// use mortar::generate::{square_triangles, Diagonal};
    /// use mortar::testing::MeshPair;
    ///
    /// let pair = MeshPair {
    ///     slave: square_triangles(4, Diagonal::Main, 0.0, false, 1).unwrap(),
    ///     master: square_triangles(5, Diagonal::Main, 0.0, true, 1000).unwrap(),
    /// };
    /// assert!((pair.shortest_edge() - 0.2).abs() < 1e-15);
    /// ```
    pub fn shortest_edge(&self) -> f64 {
        shortest_edge(&self.slave).min(shortest_edge(&self.master))
    }
}

/// The shortest edge of `mesh`'s faces (corner to corner, in the faces' node order).
fn shortest_edge(mesh: &SurfaceMesh) -> f64 {
    let x = mesh.coords();
    let mut h = f64::INFINITY;
    for f in 0..mesh.face_count() {
        let n = mesh.face(f).nodes;
        for i in 0..n.len() {
            let (a, b) = (n[i] as usize, n[(i + 1) % n.len()] as usize);
            h = h.min((x[a] - x[b]).norm());
        }
    }
    h
}

impl fmt::Debug for MeshPair {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("MeshPair")
            .field("slave", &CompactMesh(&self.slave))
            .field("master", &CompactMesh(&self.master))
            .finish()
    }
}

/// A mesh printed one node and one face per line.
struct CompactMesh<'a>(&'a SurfaceMesh);

impl fmt::Debug for CompactMesh<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mesh = self.0;
        writeln!(f, "SurfaceMesh {{")?;
        for (tag, x) in mesh.node_tags().iter().zip(mesh.coords()) {
            writeln!(f, "    node {tag}: [{:?}, {:?}, {:?}]", x.x, x.y, x.z)?;
        }
        for i in 0..mesh.face_count() {
            let face = mesh.face(i);
            let tags: Vec<u64> = face
                .nodes
                .iter()
                .map(|&n| mesh.node_tags()[n as usize])
                .collect();
            writeln!(f, "    face {} {} {tags:?}", face.tag, face.element.name())?;
        }
        write!(f, "}}")
    }
}

/// What [`covered_pair_3d_with`] draws from.
#[derive(Debug, Clone, PartialEq)]
pub struct PairConfig {
    /// Cell kinds the slave mesh may have.
    pub slave_kinds: Vec<CellKind>,
    /// Cell kinds the master mesh may have.
    pub master_kinds: Vec<CellKind>,
    /// Cells per side of the slave mesh.
    pub slave_cells: RangeInclusive<usize>,
    /// Cells per side of the master mesh.
    pub master_cells: RangeInclusive<usize>,
    /// Node jitter of the slave mesh (fraction of its cell size, below 0.35).
    pub slave_jitter: f64,
    /// Node jitter of the master mesh (fraction of its cell size, below 0.35).
    pub master_jitter: f64,
}

impl Default for PairConfig {
    /// Any kinds, 2 to 6 slave cells and 2 to 7 master cells per side, the largest jitter.
    fn default() -> Self {
        Self {
            slave_kinds: CellKind::ALL.to_vec(),
            master_kinds: CellKind::ALL.to_vec(),
            slave_cells: 2..=6,
            master_cells: 2..=7,
            slave_jitter: MAX_SQUARE_JITTER,
            master_jitter: MAX_SQUARE_JITTER,
        }
    }
}

/// A covered, non-matching 3D interface: two [`perturbed_square`] meshes of the unit square
/// in the plane `z = 0`, slave and master of the kinds and sizes of `config`, facing each
/// other (the slave normal is `+z` or `-z` at random, the master's the opposite). When both
/// kinds and sizes coincide, the master gets one more cell per side, so the two meshes never
/// match node for node (even without jitter).
///
/// # Panics
/// If a kind list is empty, or as [`perturbed_square`].
pub fn covered_pair_3d_with(config: PairConfig) -> impl Strategy<Value = MeshPair> {
    assert!(
        !config.slave_kinds.is_empty() && !config.master_kinds.is_empty(),
        "each side needs at least one cell kind"
    );
    let PairConfig {
        slave_kinds,
        master_kinds,
        slave_cells,
        master_cells,
        slave_jitter,
        master_jitter,
    } = config;
    (
        prop::sample::select(slave_kinds),
        prop::sample::select(master_kinds),
        slave_cells,
        master_cells,
        any::<bool>(),
    )
        .prop_flat_map(move |(ks, km, ns, nm, flip)| {
            let nm = if ks == km && ns == nm { nm + 1 } else { nm };
            (
                perturbed_square(ks, ns..=ns, slave_jitter, flip),
                perturbed_square(km, nm..=nm, master_jitter, !flip),
            )
                .prop_map(|(slave, master)| MeshPair { slave, master })
        })
}

/// [`covered_pair_3d_with`] the default [`PairConfig`]: any cell kinds, 2 to 7 cells per
/// side, the largest jitter.
pub fn covered_pair_3d() -> impl Strategy<Value = MeshPair> {
    covered_pair_3d_with(PairConfig::default())
}

/// A covered, non-matching 2D interface: two [`perturbed_line`] meshes of `[0, 1]`, `2..=8`
/// slave and `2..=9` master elements (never the same count), facing each other (slave normal
/// `-y` or `+y` at random, the master's the opposite), the largest jitter.
pub fn covered_pair_2d() -> impl Strategy<Value = MeshPair> {
    (2..=8usize, 2..=9usize, any::<bool>()).prop_flat_map(|(ns, nm, flip)| {
        let nm = if ns == nm { nm + 1 } else { nm };
        (
            perturbed_line(ns..=ns, MAX_LINE_JITTER, flip),
            perturbed_line(nm..=nm, MAX_LINE_JITTER, !flip),
        )
            .prop_map(|(slave, master)| MeshPair { slave, master })
    })
}

/// A covered, non-matching interface, 2D ([`covered_pair_2d`]) or 3D ([`covered_pair_3d`]).
pub fn covered_pair() -> impl Strategy<Value = MeshPair> {
    prop_oneof![covered_pair_2d(), covered_pair_3d()]
}
