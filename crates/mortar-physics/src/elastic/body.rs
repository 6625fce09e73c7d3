//! An elastic body: its mesh, material, temperature field, displacement conditions per
//! component and tractions on boundary faces, and the unknowns they fix.

use std::fmt;
use std::sync::Arc;

use mortar_fem::mesh::{BoundaryFace, VolumeMesh};
use nalgebra::Vector3;

use super::material::ElasticMaterial;
use crate::error::PhysicsError;
use crate::field::{ComponentSet, DofLayout};

/// A vector field of space: a body force (N/m^3), a traction (N/m^2) or a prescribed
/// displacement (m). In 2D only the x and y components are used.
pub type VectorField = Arc<dyn Fn(&Vector3<f64>) -> Vector3<f64> + Send + Sync>;

/// A Dirichlet condition: prescribed displacement components at some nodes.
#[derive(Clone)]
pub struct DisplacementCondition {
    /// Node indices of the body's mesh, ascending.
    pub nodes: Vec<u32>,
    /// The components prescribed.
    pub components: ComponentSet,
    /// The displacement `u(x)`; only the components in `components` are used.
    pub value: VectorField,
}

/// A traction condition: a force per unit area (per unit length in 2D, for a unit
/// thickness) applied to some boundary faces.
#[derive(Clone)]
pub struct TractionCondition {
    /// The boundary faces.
    pub faces: Vec<BoundaryFace>,
    /// The traction `t(x)` (N/m^2), the force the outside exerts on the body per unit area
    /// (a pressure `p` on a face of outward normal `n` is `t = -p n`).
    pub traction: VectorField,
}

/// A body of a small-strain linear elasticity problem: its mesh, material, body force,
/// temperature field (for the thermal strain) and boundary conditions.
///
/// The unknowns are the nodal displacements, [`DofLayout`] with `components = dim`,
/// interleaved: `dof = node * dim + component`. A 2D mesh (Tri3, Quad4 in the plane `z = 0`)
/// is a plane-strain slice of unit thickness (`eps_zz = eps_xz = eps_yz = 0`, `sigma_zz` is
/// not an unknown but follows from the in-plane strain), or, assembled with the axisymmetric
/// [`ElasticOptions::geometry`](super::ElasticOptions::geometry), the r-z section of a body
/// of revolution (components `(u_r, u_z)`; `u_r = 0` must be prescribed on the axis); a 3D
/// mesh uses Tet4 or Hex8.
///
/// Boundary faces without a condition are traction free. Where Dirichlet conditions overlap
/// (a node and component set by two conditions), the one added last wins.
#[derive(Clone)]
pub struct ElasticBody {
    /// A name used in error messages and reports.
    pub name: String,
    /// The mesh.
    pub mesh: VolumeMesh,
    /// The material.
    pub material: ElasticMaterial,
    /// The body force `b(x)` (N/m^3), if any.
    pub body_force: Option<VectorField>,
    /// Dirichlet (displacement) conditions.
    pub dirichlet: Vec<DisplacementCondition>,
    /// Traction conditions.
    pub tractions: Vec<TractionCondition>,
    /// The nodal temperature (K), one value per mesh node, if any: the thermal strain is
    /// `alpha (T - T_ref) I` with `T` interpolated by the shape functions.
    pub temperature: Option<Vec<f64>>,
    /// A uniform eigenstrain (stress-free strain) `eps*` over the body, if any, in the Voigt
    /// order of [`ElasticMaterial::stress`] (`[xx, yy, zz, yz, xz, xy]`, engineering shear
    /// strains; in the axisymmetric geometry `[rr, zz, tt, 0, 0, rz]`, the hoop strain in the
    /// `zz` slot): the stress is `C : (eps - eps_th - eps*)`. A cracked fuel pellet's
    /// relocation is one (an outward strain in the plane across its axis).
    pub eigenstrain: Option<[f64; 6]>,
}

impl fmt::Debug for ElasticBody {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ElasticBody")
            .field("name", &self.name)
            .field("nodes", &self.mesh.node_count())
            .field("cells", &self.mesh.cell_count())
            .field("material", &self.material)
            .field("body_force", &self.body_force.is_some())
            .field(
                "dirichlet_nodes",
                &self.dirichlet.iter().map(|d| d.nodes.len()).sum::<usize>(),
            )
            .field(
                "traction_faces",
                &self.tractions.iter().map(|t| t.faces.len()).sum::<usize>(),
            )
            .field("temperature", &self.temperature.is_some())
            .field("eigenstrain", &self.eigenstrain)
            .finish()
    }
}

impl ElasticBody {
    /// A body without loads or boundary conditions.
    pub fn new(name: impl Into<String>, mesh: VolumeMesh, material: ElasticMaterial) -> Self {
        Self {
            name: name.into(),
            mesh,
            material,
            body_force: None,
            dirichlet: Vec::new(),
            tractions: Vec::new(),
            temperature: None,
            eigenstrain: None,
        }
    }

    /// The number of displacement components per node: the mesh's dimension (2 or 3), zero
    /// for a mesh without cells (which [`check`](Self::check) refuses).
    pub fn components(&self) -> usize {
        self.mesh.dim().unwrap_or(0)
    }

    /// The numbering of the unknowns: `node * dim + component`.
    pub fn layout(&self) -> DofLayout {
        DofLayout::new(self.mesh.node_count(), self.components())
    }

    /// Sets the body force `b(x)` (N/m^3; gravity is `rho g`).
    pub fn with_body_force(
        mut self,
        force: impl Fn(&Vector3<f64>) -> Vector3<f64> + Send + Sync + 'static,
    ) -> Self {
        self.body_force = Some(Arc::new(force));
        self
    }

    /// Sets the nodal temperature field (K, one value per mesh node) whose difference to the
    /// material's reference temperature gives the thermal strain `alpha (T - T_ref) I`.
    ///
    /// # Errors
    /// [`PhysicsError::WrongLength`] if there is not one value per node,
    /// [`PhysicsError::InvalidInput`] for a non-finite value.
    pub fn with_temperature(mut self, temperature: Vec<f64>) -> Result<Self, PhysicsError> {
        let n = self.mesh.node_count();
        if temperature.len() != n {
            return Err(PhysicsError::WrongLength {
                what: format!("body {:?}: nodal temperature", self.name),
                expected: n,
                got: temperature.len(),
            });
        }
        if let Some(i) = temperature.iter().position(|t| !t.is_finite()) {
            return Err(self.invalid(format!(
                "the temperature {} at node {} is not finite",
                temperature[i],
                self.mesh.node_tags()[i]
            )));
        }
        self.temperature = Some(temperature);
        Ok(self)
    }

    /// Sets the uniform eigenstrain `eps*` ([`ElasticBody::eigenstrain`]): the body's loads
    /// gain `int B^T C eps*`, its recovered stress loses `C eps*`, and in generalized plane
    /// strain its axial balance loses `(C eps*)_zz A`.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a non-finite component.
    pub fn with_eigenstrain(mut self, eigenstrain: [f64; 6]) -> Result<Self, PhysicsError> {
        if let Some(i) = eigenstrain.iter().position(|e| !e.is_finite()) {
            return Err(self.invalid(format!(
                "eigenstrain component {i} ({}) is not finite",
                eigenstrain[i]
            )));
        }
        self.eigenstrain = Some(eigenstrain);
        Ok(self)
    }

    /// Prescribes the displacement components `components` of `u(x)` at the nodes of the
    /// boundary faces for which `select` is true (a symmetry plane: `ComponentSet::One(0)`
    /// with `u = 0` on `x = 0`).
    ///
    /// # Errors
    /// [`PhysicsError::Mesh`] for a broken mesh; [`PhysicsError::InvalidInput`] if no face
    /// is selected or the mesh has no component `components` (z in 2D).
    pub fn with_dirichlet_where(
        self,
        select: impl Fn(&BoundaryFace) -> bool,
        components: ComponentSet,
        value: impl Fn(&Vector3<f64>) -> Vector3<f64> + Send + Sync + 'static,
    ) -> Result<Self, PhysicsError> {
        if let Some(dim) = self.mesh.dim() {
            components
                .fits(dim)
                .map_err(|w| self.invalid(format!("Dirichlet condition: {w}")))?;
        }
        let nodes = self.mesh.boundary_nodes(select)?;
        if nodes.is_empty() {
            return Err(self.invalid("no boundary face selected for a Dirichlet condition"));
        }
        Ok(self.with_dirichlet_nodes(nodes, components, value))
    }

    /// Prescribes the displacement components `components` of `u(x)` at the given node
    /// indices of the mesh (indices and components are checked by [`check`](Self::check)).
    pub fn with_dirichlet_nodes(
        mut self,
        mut nodes: Vec<u32>,
        components: ComponentSet,
        value: impl Fn(&Vector3<f64>) -> Vector3<f64> + Send + Sync + 'static,
    ) -> Self {
        nodes.sort_unstable();
        nodes.dedup();
        self.dirichlet.push(DisplacementCondition {
            nodes,
            components,
            value: Arc::new(value),
        });
        self
    }

    /// Applies the traction `t(x)` (force per unit area; per unit length in 2D, unit
    /// thickness) to the boundary faces for which `select` is true.
    ///
    /// # Errors
    /// [`PhysicsError::Mesh`] for a broken mesh; [`PhysicsError::InvalidInput`] if no face
    /// is selected.
    pub fn with_traction_where(
        mut self,
        select: impl Fn(&BoundaryFace) -> bool,
        traction: impl Fn(&Vector3<f64>) -> Vector3<f64> + Send + Sync + 'static,
    ) -> Result<Self, PhysicsError> {
        let faces = crate::field::cells::boundary_faces_where(&self.mesh, select)?;
        if faces.is_empty() {
            return Err(self.invalid("no boundary face selected for a traction condition"));
        }
        self.tractions.push(TractionCondition {
            faces,
            traction: Arc::new(traction),
        });
        Ok(self)
    }

    /// The prescribed unknowns (ascending, each once, numbered by [`layout`](Self::layout))
    /// and their values: for each, the condition added last that sets it. Nodes beyond the
    /// mesh and components beyond its dimension are left out (see [`check`](Self::check)).
    pub fn dirichlet_dofs(&self) -> (Vec<u32>, Vec<f64>) {
        let layout = self.layout();
        if layout.is_empty() || !layout.fits_u32() {
            return (Vec::new(), Vec::new());
        }
        let mut by_dof = vec![usize::MAX; layout.len()];
        for (k, d) in self.dirichlet.iter().enumerate() {
            for &n in d.nodes.iter().filter(|&&n| (n as usize) < layout.nodes) {
                for c in d.components.components(layout.components) {
                    by_dof[layout.dof(n, c) as usize] = k;
                }
            }
        }
        let coords = self.mesh.coords();
        let mut dofs = Vec::new();
        let mut values = Vec::new();
        // One evaluation of a condition's field per node, however many components it sets.
        let mut last: Option<(usize, u32, Vector3<f64>)> = None;
        for (dof, &k) in by_dof.iter().enumerate().filter(|(_, k)| **k != usize::MAX) {
            let (n, c) = layout.node_component(dof as u32);
            let u = match last {
                Some((lk, ln, u)) if lk == k && ln == n => u,
                _ => {
                    let u = (self.dirichlet[k].value)(&coords[n as usize]);
                    last = Some((k, n, u));
                    u
                }
            };
            dofs.push(dof as u32);
            values.push(u[c]);
        }
        (dofs, values)
    }

    /// The nodal interpolant of a vector field (an exact displacement), numbered by
    /// [`layout`](Self::layout).
    pub fn interpolate(&self, f: impl Fn(&Vector3<f64>) -> Vector3<f64>) -> Vec<f64> {
        let dim = self.components();
        self.mesh
            .coords()
            .iter()
            .flat_map(|x| {
                let u = f(x);
                (0..dim).map(move |c| u[c])
            })
            .collect()
    }

    pub(crate) fn invalid(&self, what: impl Into<String>) -> PhysicsError {
        PhysicsError::InvalidInput {
            body: self.name.clone(),
            what: what.into(),
        }
    }

    /// Checks the material, the mesh and the conditions.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for bad material data (see
    /// [`ElasticMaterial::check`]), a mesh without cells or too large for `u32` unknown
    /// numbers, a Dirichlet node index beyond the mesh or component beyond its dimension;
    /// [`PhysicsError::WrongLength`] for a temperature field (set by hand) without one value
    /// per node.
    pub fn check(&self) -> Result<(), PhysicsError> {
        self.material.check(&self.name)?;
        if self.mesh.cell_count() == 0 {
            return Err(self.invalid("the mesh has no cells"));
        }
        let layout = self.layout();
        if !layout.fits_u32() {
            return Err(self.invalid(format!(
                "{} nodes x {} components do not fit u32 unknown numbers",
                layout.nodes, layout.components
            )));
        }
        let n = self.mesh.node_count();
        for d in &self.dirichlet {
            if let Some(bad) = d.nodes.iter().find(|&&i| i as usize >= n) {
                return Err(self.invalid(format!(
                    "Dirichlet node index {bad} is beyond the mesh's {n} nodes"
                )));
            }
            d.components
                .fits(layout.components)
                .map_err(|w| self.invalid(format!("Dirichlet condition: {w}")))?;
        }
        if let Some(t) = &self.temperature {
            if t.len() != n {
                return Err(PhysicsError::WrongLength {
                    what: format!("body {:?}: nodal temperature", self.name),
                    expected: n,
                    got: t.len(),
                });
            }
        }
        Ok(())
    }
}
