//! `Tie`: an interface's mortar coupling mapped onto the node indices of the two bodies'
//! volume meshes, for fields of any number of components (`D (x) I_c`, `M (x) I_c`).

use mortar_core::linalg::{SparseMatrix, Triplets};
use mortar_core::mesh::SurfaceMesh;
use mortar_core::multiplier::{LinearMultipliers, MultiplierSpace};
use mortar_core::{assemble_coupling, Coupling, CouplingOptions, Interface, Side};
use mortar_fem::mesh::VolumeMesh;

use crate::error::PhysicsError;

/// Two bodies' interface and its mortar coupling, with the map from the coupling's rows
/// (slave interface nodes) and columns (master interface nodes) to the node indices of the two
/// bodies' volume meshes.
///
/// A tie serves fields of any number of components per node (one for a temperature, the
/// dimension for a displacement; see [`with_components`](Self::with_components)): unknowns
/// are numbered node by node, the components of a node together (`node * c + k`), and the
/// constraint of component `k` at coupling row `r` is row `r * c + k` of `D (x) I_c` and
/// `M (x) I_c`: each component is tied on its own.
#[derive(Debug, Clone)]
pub struct Tie {
    interface: Interface,
    coupling: Coupling,
    slave_nodes: Vec<u32>,
    master_nodes: Vec<u32>,
    components: usize,
    /// `D (x) I_c` and `M (x) I_c`, when `c > 1`.
    expanded: Option<(SparseMatrix, SparseMatrix)>,
    slave_dofs: Vec<u32>,
    master_dofs: Vec<u32>,
}

/// A coupling row without multiplier and the `(row, weight)` pairs its value is interpolated
/// from (see [`Tie::rows_without_multiplier`]).
pub type Interpolated = (u32, Vec<(u32, f64)>);

/// `a (x) I_c`: each entry `a_ij` becomes the diagonal block `a_ij I_c` (rows and columns
/// `i * c + k`, the numbering of a field of `c` components).
pub fn kron_identity(a: &SparseMatrix, c: usize) -> SparseMatrix {
    let mut t = Triplets::default();
    for (i, row) in a.outer_iterator().enumerate() {
        for k in 0..c {
            for (j, v) in row.iter() {
                t.push((i * c + k) as u32, (j * c + k) as u32, *v);
            }
        }
    }
    t.to_csr(a.rows() * c, a.cols() * c)
}

/// Per row of `a`, whether it has a stored entry.
fn nonempty_rows(a: &SparseMatrix) -> Vec<bool> {
    a.outer_iterator().map(|row| row.nnz() > 0).collect()
}

/// Node indices to unknowns of `c` components: `node * c + k`.
fn expand(nodes: &[u32], c: usize) -> Vec<u32> {
    nodes
        .iter()
        .flat_map(|&n| (0..c as u32).map(move |k| n * c as u32 + k))
        .collect()
}

impl Tie {
    /// Builds the interface of two surfaces (each extracted from its body, e.g. by
    /// [`VolumeMesh::boundary_surface`], so that their node tags are the bodies' node tags)
    /// and assembles D and M.
    ///
    /// # Errors
    /// [`PhysicsError::Mortar`] for an invalid interface or coupling,
    /// [`PhysicsError::InterfaceNodeNotInBody`] if a surface node is not in its body.
    pub fn new(
        slave_body: &VolumeMesh,
        master_body: &VolumeMesh,
        slave_surface: SurfaceMesh,
        master_surface: SurfaceMesh,
        options: &CouplingOptions,
    ) -> Result<Self, PhysicsError> {
        let interface = Interface::new(slave_surface, master_surface)?;
        Self::on_interface(slave_body, master_body, interface, options)
    }

    /// [`new`](Self::new) on an interface the caller built (with its own
    /// [`Tolerances`](mortar_core::Tolerances), such as a search radius, through
    /// [`Interface::with_tolerances`]).
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn on_interface(
        slave_body: &VolumeMesh,
        master_body: &VolumeMesh,
        interface: Interface,
        options: &CouplingOptions,
    ) -> Result<Self, PhysicsError> {
        let coupling = assemble_coupling(&interface, options)?;
        Self::from_coupling(slave_body, master_body, interface, coupling)
    }

    /// A tie from an interface and a coupling computed by the caller.
    ///
    /// # Errors
    /// [`PhysicsError::InterfaceNodeNotInBody`] if a coupling node is not in its body.
    pub fn from_coupling(
        slave_body: &VolumeMesh,
        master_body: &VolumeMesh,
        interface: Interface,
        coupling: Coupling,
    ) -> Result<Self, PhysicsError> {
        let map = |mesh: &VolumeMesh, tags: &[u64], side: Side| {
            tags.iter()
                .map(|&tag| {
                    mesh.node_index(tag)
                        .ok_or(PhysicsError::InterfaceNodeNotInBody { side, tag })
                })
                .collect::<Result<Vec<u32>, PhysicsError>>()
        };
        let slave_nodes = map(slave_body, &coupling.slave_nodes, Side::Slave)?;
        let master_nodes = map(master_body, &coupling.master_nodes, Side::Master)?;
        Ok(Self {
            interface,
            coupling,
            slave_dofs: slave_nodes.clone(),
            master_dofs: master_nodes.clone(),
            slave_nodes,
            master_nodes,
            components: 1,
            expanded: None,
        })
    }

    /// The same tie for a field of `components` unknowns per node (at least one): `D (x) I_c`
    /// and `M (x) I_c` over the unknowns `node * c + k`.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for zero components.
    pub fn with_components(mut self, components: usize) -> Result<Self, PhysicsError> {
        if components == 0 {
            return Err(PhysicsError::InvalidInput {
                body: "tie".into(),
                what: "a field needs at least one component per node".into(),
            });
        }
        self.components = components;
        self.slave_dofs = expand(&self.slave_nodes, components);
        self.master_dofs = expand(&self.master_nodes, components);
        self.expanded = (components > 1).then(|| {
            (
                kron_identity(&self.coupling.d, components),
                kron_identity(&self.coupling.m, components),
            )
        });
        Ok(self)
    }

    /// Unknowns per node of the tied field.
    pub fn components(&self) -> usize {
        self.components
    }

    /// The constraint's slave operator over the field's unknowns: D, or `D (x) I_c`.
    pub fn d(&self) -> &SparseMatrix {
        self.expanded.as_ref().map_or(&self.coupling.d, |(d, _)| d)
    }

    /// The constraint's master operator over the field's unknowns: M, or `M (x) I_c`.
    pub fn m(&self) -> &SparseMatrix {
        self.expanded.as_ref().map_or(&self.coupling.m, |(_, m)| m)
    }

    /// For each row of [`d`](Self::d), the slave body's unknown (`node * c + k`).
    pub fn slave_dofs(&self) -> &[u32] {
        &self.slave_dofs
    }

    /// For each column of [`m`](Self::m), the master body's unknown (`node * c + k`).
    pub fn master_dofs(&self) -> &[u32] {
        &self.master_dofs
    }

    /// The slave node tag of constraint row `row` (of [`d`](Self::d)).
    pub fn row_tag(&self, row: usize) -> u64 {
        self.coupling.slave_nodes[row / self.components]
    }

    /// The interface (slave and master surfaces).
    pub fn interface(&self) -> &Interface {
        &self.interface
    }

    /// D, M and the node tags of their rows and columns.
    pub fn coupling(&self) -> &Coupling {
        &self.coupling
    }

    /// For each row of D and M, the slave body's node index.
    pub fn slave_nodes(&self) -> &[u32] {
        &self.slave_nodes
    }

    /// For each column of M, the master body's node index.
    pub fn master_nodes(&self) -> &[u32] {
        &self.master_nodes
    }

    /// Per row of [`d`](Self::d) (unknown rows: a node's components together), whether it
    /// carries a multiplier: every row but the empty ones (the edge and centre nodes of
    /// linear multipliers on second-order faces), which constrain nothing.
    pub fn rows_with_multiplier(&self) -> Vec<bool> {
        nonempty_rows(self.d())
    }

    /// For each coupling row that carries no multiplier (its row of D empty: the edge and
    /// centre nodes of linear multipliers on second-order faces), the rows of the corners of a
    /// slave face of its node and the first-order functions of those corners at it (the
    /// coefficients of [`LinearMultipliers`]): a value the corners' multipliers stand for
    /// there is `sum w value[row]`. Empty when every row carries one.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] naming the node when a corner of its face carries no
    /// multiplier either; [`PhysicsError::Mortar`] if the linear basis cannot be built on
    /// the face.
    pub fn rows_without_multiplier(&self) -> Result<Vec<Interpolated>, PhysicsError> {
        let c = &self.coupling;
        let carries = nonempty_rows(&c.d);
        let mut out = Vec::new();
        if carries.iter().all(|d| *d) {
            return Ok(out);
        }
        let interface = &self.interface;
        let slave = interface.slave();
        let mut done = carries.clone();
        for f in 0..slave.face_count() {
            let rows: Vec<u32> = slave
                .face(f)
                .nodes
                .iter()
                .map(|&n| interface.slave_row(n).expect("a face's node has a row"))
                .collect();
            if rows.iter().all(|&r| done[r as usize]) {
                continue;
            }
            let face = interface.slave_face(f);
            let basis = LinearMultipliers.basis(&face, interface.tolerances())?;
            let corners = face.element.corner_count();
            for (k, &r) in rows.iter().enumerate().skip(corners) {
                if done[r as usize] {
                    continue;
                }
                let mut from = Vec::new();
                for (corner, &rc) in rows.iter().enumerate().take(corners) {
                    let w = basis.a[corner][k];
                    if w == 0.0 {
                        continue;
                    }
                    if !carries[rc as usize] {
                        return Err(PhysicsError::InvalidInput {
                            body: "interface".into(),
                            what: format!(
                                "slave node {} carries no multiplier, nor does the corner {} \
                                 of its face {}",
                                c.slave_nodes[r as usize], c.slave_nodes[rc as usize], face.tag
                            ),
                        });
                    }
                    from.push((rc, w));
                }
                done[r as usize] = true;
                out.push((r, from));
            }
        }
        Ok(out)
    }
}
