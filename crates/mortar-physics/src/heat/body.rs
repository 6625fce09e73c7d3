//! `HeatBody`: a volume mesh with its thermal material (`HeatMaterial`), source, and Dirichlet
//! and Neumann conditions.

use std::fmt;
use std::sync::Arc;

use mortar_fem::mesh::{BoundaryFace, VolumeMesh};
use nalgebra::Vector3;

use crate::error::PhysicsError;

/// A scalar field of space and time, `f(x, t)`: a heat source (W/m^3), a temperature (K) or a
/// heat flux (W/m^2). Steady problems evaluate it at a fixed time.
pub type Field = Arc<dyn Fn(&Vector3<f64>, f64) -> f64 + Send + Sync>;

/// Thermal properties of a body (constant over it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatMaterial {
    /// Conductivity k (W/m/K), positive.
    pub conductivity: f64,
    /// Volumetric heat capacity rho c_p (J/m^3/K), non-negative (only transient problems use it).
    pub capacity: f64,
}

impl HeatMaterial {
    /// A material of conductivity `k` and volumetric heat capacity `rho_cp`.
    pub fn new(conductivity: f64, capacity: f64) -> Self {
        Self {
            conductivity,
            capacity,
        }
    }
}

/// A Dirichlet condition: prescribed temperatures at some nodes.
#[derive(Clone)]
pub struct DirichletCondition {
    /// Node indices of the body's mesh, ascending.
    pub nodes: Vec<u32>,
    /// The temperature `T(x, t)`.
    pub value: Field,
}

/// A Neumann condition: a heat flux entering the body through some boundary faces,
/// `q = k dT/dn` with `n` the outward normal (positive heats the body).
#[derive(Clone)]
pub struct NeumannCondition {
    /// The boundary faces.
    pub faces: Vec<BoundaryFace>,
    /// The flux `q(x, t)` (W/m^2).
    pub flux: Field,
}

/// A body of a heat conduction problem: its mesh, material, heat source, and boundary
/// conditions. Boundary faces without a condition are insulated (zero flux), except those
/// tied to another body.
///
/// Where Dirichlet conditions overlap (a corner node on two sides), the one added last wins.
#[derive(Clone)]
pub struct HeatBody {
    /// A name used in error messages and reports.
    pub name: String,
    /// The mesh.
    pub mesh: VolumeMesh,
    /// The material.
    pub material: HeatMaterial,
    /// The heat source `Q(x, t)` (W/m^3), if any.
    pub source: Option<Field>,
    /// Dirichlet conditions.
    pub dirichlet: Vec<DirichletCondition>,
    /// Neumann conditions.
    pub neumann: Vec<NeumannCondition>,
}

impl fmt::Debug for HeatBody {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("HeatBody")
            .field("name", &self.name)
            .field("nodes", &self.mesh.node_count())
            .field("cells", &self.mesh.cell_count())
            .field("material", &self.material)
            .field("source", &self.source.is_some())
            .field(
                "dirichlet_nodes",
                &self.dirichlet.iter().map(|d| d.nodes.len()).sum::<usize>(),
            )
            .field(
                "neumann_faces",
                &self.neumann.iter().map(|n| n.faces.len()).sum::<usize>(),
            )
            .finish()
    }
}

impl HeatBody {
    /// A body without source or boundary conditions.
    pub fn new(name: impl Into<String>, mesh: VolumeMesh, material: HeatMaterial) -> Self {
        Self {
            name: name.into(),
            mesh,
            material,
            source: None,
            dirichlet: Vec::new(),
            neumann: Vec::new(),
        }
    }

    /// Sets the heat source `Q(x, t)`.
    pub fn with_source(
        mut self,
        source: impl Fn(&Vector3<f64>, f64) -> f64 + Send + Sync + 'static,
    ) -> Self {
        self.source = Some(Arc::new(source));
        self
    }

    /// Prescribes `T(x, t)` at the nodes of the boundary faces for which `select` is true.
    ///
    /// # Errors
    /// [`PhysicsError::Mesh`] for a broken mesh; [`PhysicsError::InvalidInput`] if no face
    /// is selected.
    pub fn with_dirichlet_where(
        self,
        select: impl Fn(&BoundaryFace) -> bool,
        value: impl Fn(&Vector3<f64>, f64) -> f64 + Send + Sync + 'static,
    ) -> Result<Self, PhysicsError> {
        let nodes = self.mesh.boundary_nodes(select)?;
        if nodes.is_empty() {
            return Err(self.invalid("no boundary face selected for a Dirichlet condition"));
        }
        Ok(self.with_dirichlet_nodes(nodes, value))
    }

    /// Prescribes `T(x, t)` at the given node indices of the mesh.
    pub fn with_dirichlet_nodes(
        mut self,
        mut nodes: Vec<u32>,
        value: impl Fn(&Vector3<f64>, f64) -> f64 + Send + Sync + 'static,
    ) -> Self {
        nodes.sort_unstable();
        nodes.dedup();
        self.dirichlet.push(DirichletCondition {
            nodes,
            value: Arc::new(value),
        });
        self
    }

    /// Prescribes the entering heat flux `q(x, t) = k dT/dn` on the boundary faces for which
    /// `select` is true.
    ///
    /// # Errors
    /// [`PhysicsError::Mesh`] for a broken mesh; [`PhysicsError::InvalidInput`] if no face
    /// is selected.
    pub fn with_neumann_where(
        mut self,
        select: impl Fn(&BoundaryFace) -> bool,
        flux: impl Fn(&Vector3<f64>, f64) -> f64 + Send + Sync + 'static,
    ) -> Result<Self, PhysicsError> {
        let faces = crate::field::cells::boundary_faces_where(&self.mesh, select)?;
        if faces.is_empty() {
            return Err(self.invalid("no boundary face selected for a Neumann condition"));
        }
        self.neumann.push(NeumannCondition {
            faces,
            flux: Arc::new(flux),
        });
        Ok(self)
    }

    /// The Dirichlet nodes (ascending, each once) and, for each, the condition that sets it
    /// (the last one listing it). Node indices beyond the mesh are left out (see
    /// [`check`](Self::check)).
    pub fn dirichlet_nodes(&self) -> (Vec<u32>, Vec<usize>) {
        let mut by_node = vec![usize::MAX; self.mesh.node_count()];
        for (c, d) in self.dirichlet.iter().enumerate() {
            for &n in &d.nodes {
                // Out-of-range nodes are reported by `check`.
                if let Some(slot) = by_node.get_mut(n as usize) {
                    *slot = c;
                }
            }
        }
        by_node
            .iter()
            .enumerate()
            .filter(|(_, c)| **c != usize::MAX)
            .map(|(n, c)| (n as u32, *c))
            .unzip()
    }

    /// The Dirichlet values at time `t`, in the order of
    /// [`dirichlet_nodes`](Self::dirichlet_nodes).
    ///
    /// # Panics
    /// If a node index is beyond the mesh or a condition index beyond the conditions.
    pub fn dirichlet_values(&self, nodes: &[u32], conditions: &[usize], t: f64) -> Vec<f64> {
        nodes
            .iter()
            .zip(conditions)
            .map(|(&n, &c)| (self.dirichlet[c].value)(&self.mesh.coords()[n as usize], t))
            .collect()
    }

    /// The nodal interpolant of `f(x, t)` (an initial condition, an exact solution).
    pub fn interpolate(&self, f: impl Fn(&Vector3<f64>, f64) -> f64, t: f64) -> Vec<f64> {
        self.mesh.coords().iter().map(|x| f(x, t)).collect()
    }

    pub(crate) fn invalid(&self, what: impl Into<String>) -> PhysicsError {
        PhysicsError::InvalidInput {
            body: self.name.clone(),
            what: what.into(),
        }
    }

    /// Checks the material data.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a non-positive or non-finite conductivity, a
    /// negative or non-finite capacity, a mesh without cells, or a Dirichlet node index beyond
    /// the mesh.
    pub fn check(&self) -> Result<(), PhysicsError> {
        let m = self.material;
        if !(m.conductivity > 0.0 && m.conductivity.is_finite()) {
            return Err(self.invalid(format!(
                "conductivity {} is not positive and finite",
                m.conductivity
            )));
        }
        if !(m.capacity >= 0.0 && m.capacity.is_finite()) {
            return Err(self.invalid(format!(
                "heat capacity {} is not non-negative and finite",
                m.capacity
            )));
        }
        if self.mesh.cell_count() == 0 {
            return Err(self.invalid("the mesh has no cells"));
        }
        let n = self.mesh.node_count();
        if let Some(bad) = self
            .dirichlet
            .iter()
            .flat_map(|d| d.nodes.iter())
            .find(|&&i| i as usize >= n)
        {
            return Err(self.invalid(format!(
                "Dirichlet node index {bad} is beyond the mesh's {n} nodes"
            )));
        }
        Ok(())
    }
}
