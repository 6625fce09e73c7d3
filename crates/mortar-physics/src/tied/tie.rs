use mortar_core::mesh::{SurfaceMesh, VolumeMesh};
use mortar_core::{assemble_coupling, Coupling, CouplingOptions, Interface, Side};

use crate::error::PhysicsError;

/// Two bodies' interface and its mortar coupling, with the map from the coupling's rows
/// (slave interface nodes) and columns (master interface nodes) to the node indices of the two
/// bodies' volume meshes.
#[derive(Debug, Clone)]
pub struct Tie {
    interface: Interface,
    coupling: Coupling,
    slave_nodes: Vec<u32>,
    master_nodes: Vec<u32>,
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
            slave_nodes,
            master_nodes,
        })
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
}
