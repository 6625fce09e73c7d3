//! `Interface`: a validated slave/master pair of surface meshes with the slave's averaged
//! nodal normals and the maps from mesh nodes to rows of D and columns of M.

use std::sync::OnceLock;

use nalgebra::Vector3;

use super::validate::{
    check_dimension, check_duplicates, check_faces, check_orientation, check_range, nodal_normals,
};
use super::FaceGeometry;
use crate::error::{MortarError, Result, Side};
use crate::mesh::SurfaceMesh;
use crate::tolerances::Tolerances;

/// The spatial dimension of an interface problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SpatialDim {
    /// Line elements in the xy-plane.
    Two,
    /// Triangles and quadrilaterals in space.
    Three,
}

/// Marks a mesh node that no face of the interface uses.
const NOT_ON_INTERFACE: u32 = u32::MAX;

/// A validated pair of surfaces: the slave (non-mortar, carries the multipliers) and the
/// master (mortar).
///
/// Construction checks the coordinates' range (products of two must stay within double
/// precision, see [`MAX_COORDINATE`](crate::tolerances::MAX_COORDINATE)), every face
/// (degenerate or inverted faces, duplicated faces, mixed dimensions, with tolerances relative
/// to the faces' and the interface's own size) and the connectivity of each surface (an edge
/// joins at most two faces, a node at most two lines; neighbouring faces run along their
/// shared edge in opposite directions), and computes the slave's averaged nodal normals: at
/// each node, the normalised sum of the unit normals of the faces around it. Rows of the
/// coupling operators are the slave nodes used by a face, in ascending tag order; columns of M
/// the master nodes likewise.
#[derive(Debug, Clone)]
pub struct Interface {
    slave: SurfaceMesh,
    master: SurfaceMesh,
    dim: SpatialDim,
    tolerances: Tolerances,
    slave_nodes: Vec<u32>,
    slave_rows: Vec<u32>,
    master_nodes: Vec<u32>,
    master_cols: Vec<u32>,
    slave_normals: Vec<Vector3<f64>>,
    /// The largest bend of the master faces, computed on first use.
    master_bend: OnceLock<f64>,
}

impl Interface {
    /// Builds and validates an interface with default tolerances.
    ///
    /// # Errors
    /// [`MortarError::EmptySurface`], [`MortarError::CoordinateRange`],
    /// [`MortarError::DimensionMismatch`], [`MortarError::DegenerateFace`],
    /// [`MortarError::InvertedFace`] (a folded face, or one oriented against its neighbours),
    /// [`MortarError::Topology`] (a duplicated face, a fin, a T junction, a one-sided piece).
    pub fn new(slave: SurfaceMesh, master: SurfaceMesh) -> Result<Self> {
        Self::with_tolerances(slave, master, Tolerances::default())
    }

    /// Builds and validates an interface with the given tolerances.
    ///
    /// # Errors
    /// As [`Interface::new`].
    pub fn with_tolerances(
        slave: SurfaceMesh,
        master: SurfaceMesh,
        tolerances: Tolerances,
    ) -> Result<Self> {
        for (mesh, side) in [(&slave, Side::Slave), (&master, Side::Master)] {
            if mesh.face_count() == 0 {
                return Err(MortarError::EmptySurface { side });
            }
        }
        check_range(&slave, &master)?;
        let dim = check_dimension(&slave, &master, &tolerances)?;
        let scale = interface_scale(&slave, &master);
        check_faces(&slave, Side::Slave, scale, &tolerances)?;
        check_faces(&master, Side::Master, scale, &tolerances)?;
        check_duplicates(&slave, Side::Slave)?;
        check_duplicates(&master, Side::Master)?;
        check_orientation(&slave, Side::Slave)?;
        check_orientation(&master, Side::Master)?;
        let slave_normals = nodal_normals(&slave, Side::Slave)?;
        nodal_normals(&master, Side::Master)?;
        let (slave_nodes, slave_rows) = node_map(&slave);
        let (master_nodes, master_cols) = node_map(&master);
        Ok(Self {
            slave,
            master,
            dim,
            tolerances,
            slave_nodes,
            slave_rows,
            master_nodes,
            master_cols,
            slave_normals,
            master_bend: OnceLock::new(),
        })
    }

    /// The slave surface.
    pub fn slave(&self) -> &SurfaceMesh {
        &self.slave
    }

    /// The master surface.
    pub fn master(&self) -> &SurfaceMesh {
        &self.master
    }

    /// The spatial dimension.
    pub fn dim(&self) -> SpatialDim {
        self.dim
    }

    /// The tolerances in use.
    pub fn tolerances(&self) -> &Tolerances {
        &self.tolerances
    }

    /// Slave mesh node indices in row order (ascending tag).
    pub fn slave_nodes(&self) -> &[u32] {
        &self.slave_nodes
    }

    /// Master mesh node indices in column order (ascending tag).
    pub fn master_nodes(&self) -> &[u32] {
        &self.master_nodes
    }

    /// The row of slave mesh node `node`, if a face uses it.
    #[inline]
    pub fn slave_row(&self, node: u32) -> Option<u32> {
        let r = self.slave_rows[node as usize];
        (r != NOT_ON_INTERFACE).then_some(r)
    }

    /// The column of master mesh node `node`, if a face uses it.
    #[inline]
    pub fn master_col(&self, node: u32) -> Option<u32> {
        let c = self.master_cols[node as usize];
        (c != NOT_ON_INTERFACE).then_some(c)
    }

    /// Averaged unit nodal normals of the slave surface, indexed by slave mesh node.
    pub fn slave_nodal_normals(&self) -> &[Vector3<f64>] {
        &self.slave_normals
    }

    /// Gathers a slave face with its nodal normals.
    pub fn slave_face(&self, face: usize) -> FaceGeometry {
        FaceGeometry::gather(&self.slave, Side::Slave, face, Some(&self.slave_normals))
    }

    /// Gathers a slave face into `out`, which holds a face gathered before (see
    /// [`FaceGeometry::gather_into`]).
    pub fn slave_face_into(&self, face: usize, out: &mut FaceGeometry) {
        out.gather_into(&self.slave, Side::Slave, face, Some(&self.slave_normals));
    }

    /// Gathers a master face.
    pub fn master_face(&self, face: usize) -> FaceGeometry {
        FaceGeometry::gather(&self.master, Side::Master, face, None)
    }

    /// The largest [`bend`](crate::integration::curved_3d::bend) of the master faces (0 for a
    /// first-order master), computed on first use and kept: the curved segmentation cuts
    /// every master face at the level of this bend, so that neighbouring faces cut their
    /// shared curved edges alike. Computed on the calling thread: the first call comes from
    /// a worker of the coupling, and parallel work inside the initialisation could let that
    /// worker pick up another face of the coupling, call this again and wait on itself.
    pub fn master_bend(&self) -> f64 {
        *self.master_bend.get_or_init(|| {
            (0..self.master.face_count())
                .filter(|&f| {
                    let el = self.master.face(f).element;
                    el.node_count() > el.corner_count()
                })
                .map(|f| crate::integration::curved_3d::bend(&self.master_face(f)))
                .fold(0.0, f64::max)
        })
    }
}

/// The diagonal of the bounding box of both surfaces: the length scale of relative tolerances.
fn interface_scale(slave: &SurfaceMesh, master: &SurfaceMesh) -> f64 {
    let boxes = [slave.bounding_box(), master.bounding_box()];
    let (lo, hi) = boxes
        .iter()
        .flatten()
        .fold(
            None::<(Vector3<f64>, Vector3<f64>)>,
            |acc, (l, h)| match acc {
                None => Some((*l, *h)),
                Some((a, b)) => Some((a.inf(l), b.sup(h))),
            },
        )
        .unwrap_or_default();
    (hi - lo).norm()
}

/// The nodes used by a face, sorted by tag, and the inverse map.
fn node_map(mesh: &SurfaceMesh) -> (Vec<u32>, Vec<u32>) {
    let mut used = vec![false; mesh.node_count()];
    for f in 0..mesh.face_count() {
        for &n in mesh.face(f).nodes {
            used[n as usize] = true;
        }
    }
    let mut nodes: Vec<u32> = (0..mesh.node_count() as u32)
        .filter(|&n| used[n as usize])
        .collect();
    let tags = mesh.node_tags();
    nodes.sort_unstable_by_key(|&n| tags[n as usize]);
    let mut inverse = vec![NOT_ON_INTERFACE; mesh.node_count()];
    for (i, &n) in nodes.iter().enumerate() {
        inverse[n as usize] = i as u32;
    }
    (nodes, inverse)
}
