//! Where a physics solve's linear systems go ([`LinearSolve`]): the toolkit's own direct
//! solves, or a backend of the solver interface (PETSc's Krylov methods with algebraic
//! multigrid, say), told what it may use of each system.

use mortar_fem::linalg::{SparseSolver, SystemInfo, UnknownPlaces};
use nalgebra::Vector3;

/// Where a physics solve's linear systems go, and what a backend is told of them.
#[derive(Clone, Copy, Debug, Default)]
pub struct LinearSolve<'a> {
    /// The backend; `None`: the toolkit's direct solves (faer's Cholesky, by body where that
    /// pays, or LU), as every solve without a backend.
    pub backend: Option<&'a dyn SparseSolver>,
    /// Each body's node coordinates (its mesh's [`coords`](mortar_fem::VolumeMesh::coords),
    /// `z = 0` in 2D), its displacement unknowns numbered node by node: where each unknown of
    /// a system sits, so that an algebraic multigrid knows the bodies' rigid motions. Empty:
    /// not told.
    pub nodes: [&'a [Vector3<f64>]; 2],
    /// Whether the bodies are axisymmetric (r-z, `x` the radius).
    pub axisymmetric: bool,
}

impl<'a> LinearSolve<'a> {
    /// The systems to `backend`, told where the unknowns of the bodies with node coordinates
    /// `nodes` sit.
    pub fn on(backend: &'a dyn SparseSolver, nodes: [&'a [Vector3<f64>]; 2]) -> Self {
        Self {
            backend: Some(backend),
            nodes,
            axisymmetric: false,
        }
    }
}

/// Where each unknown of a system of displacements sits: per unknown its node's position and
/// its component, owned (see [`UnknownPlaces`], which borrows them).
#[derive(Clone, Debug, Default)]
pub(crate) struct Places {
    pub dim: usize,
    pub axisymmetric: bool,
    pub points: Vec<[f64; 3]>,
    pub components: Vec<u8>,
}

impl Places {
    /// The places of the unknowns `dofs` (in the system's order, each `(body, local dof)`,
    /// `dim` components per node), or `None` if a body's nodes were not told or do not
    /// cover the dofs.
    pub fn of(
        linear: &LinearSolve<'_>,
        dim: usize,
        dofs: impl Iterator<Item = (usize, usize)>,
    ) -> Option<Self> {
        let mut points = Vec::new();
        let mut components = Vec::new();
        for (body, dof) in dofs {
            let p = linear.nodes[body].get(dof / dim)?;
            points.push([p.x, p.y, p.z]);
            components.push((dof % dim) as u8);
        }
        Some(Self {
            dim,
            axisymmetric: linear.axisymmetric,
            points,
            components,
        })
    }

    /// The places of the unknowns `keep` picks, in their order: `keep[i]` the new index of
    /// unknown `i`, or `None`.
    pub fn restricted(&self, keep: impl Iterator<Item = Option<usize>>, n: usize) -> Self {
        let mut points = vec![[0.0; 3]; n];
        let mut components = vec![0u8; n];
        for (i, k) in keep.enumerate() {
            if let Some(k) = k {
                points[k] = self.points[i];
                components[k] = self.components[i];
            }
        }
        Self {
            dim: self.dim,
            axisymmetric: self.axisymmetric,
            points,
            components,
        }
    }

    /// What the backend is told of the system of these unknowns.
    pub fn info(&self) -> SystemInfo<'_> {
        SystemInfo {
            displacements: Some(UnknownPlaces {
                dim: self.dim,
                axisymmetric: self.axisymmetric,
                points: &self.points,
                components: &self.components,
            }),
            multipliers_last: 0,
        }
    }
}
