//! Generalized plane strain: a 2D cross-section of a long prismatic body whose axial strain
//! `eps_zz = e` is one uniform unknown, fixed by the balance of the axial force, instead of
//! zero (plane strain). The operators that border the plane stiffness, and the static solve
//! of one body with them.

use mortar_core::linalg::{SparseMatrix, Triplets};
use mortar_fem::element::{CellValues, MAX_CELL_NODES};
use nalgebra::Vector3;
use rayon::prelude::*;

use super::assembly::{check, reinit_cell, CELL_CHUNK};
use super::solve::solve_held;
use super::{assemble_elastic_load, assemble_elastic_stiffness, ElasticBody, ElasticOptions};
use crate::field::cells;
use crate::PhysicsError;

/// The axial force on a body's cross-section, `F = force + per_gas_pressure P_gas` (N): the
/// value of `int sigma_zz dA` that the axial balance asks for. A pellet whose ends carry the
/// plenum pressure has `force = 0`, `per_gas_pressure = -A_pellet`; a cladding tube with
/// closed ends, the plenum inside and the coolant outside, has
/// `force = -P_coolant A_outer`, `per_gas_pressure = A_inner` (areas enclosed by its outer
/// and inner surfaces).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AxialForce {
    /// The force that does not depend on the gas pressure (N).
    pub force: f64,
    /// The force per pascal of gas pressure (m^2).
    pub per_gas_pressure: f64,
}

impl AxialForce {
    /// No axial force: free ends.
    pub const FREE: AxialForce = AxialForce {
        force: 0.0,
        per_gas_pressure: 0.0,
    };

    /// The force at the gas pressure `gas` (Pa).
    pub fn at(&self, gas: f64) -> f64 {
        self.force + self.per_gas_pressure * gas
    }
}

/// The operators of generalized plane strain of one 2D body (unit thickness, Cartesian):
/// with `sigma = lambda (tr eps_2D + e) I + 2 mu eps - 3 K alpha (T - T_ref) I` and
/// `eps_zz = e`, the in-plane equilibrium gains `coupling e` and the axial balance reads
///
/// ```text
/// int sigma_zz dA = coupling . u + stiffness e - thermal . (T - T_ref) - eigenstress = F
/// ```
///
/// so the bordered system `[K c; c^T k] [u; e] = [f; F + h . (T - T_ref)]` is symmetric
/// (positive definite when the plane problem is held against rigid motion).
#[derive(Debug, Clone, PartialEq)]
pub struct GeneralizedPlaneStrain {
    /// `c[(a, i)] = int lambda dN_a/dx_i` (numbered by the body's layout).
    pub coupling: Vec<f64>,
    /// `k = int (lambda + 2 mu) = (lambda + 2 mu) A`.
    pub stiffness: f64,
    /// `h[a] = int 3 K alpha N_a`, one per mesh node.
    pub thermal: Vec<f64>,
    /// The cross-section's area `A` (m^2).
    pub area: f64,
    /// `(C eps*)_zz A` of the body's eigenstrain ([`ElasticBody::eigenstrain`]; zero
    /// without).
    pub eigenstress: f64,
}

impl GeneralizedPlaneStrain {
    /// Assembles the operators of `body` (a 2D mesh, the Cartesian geometry).
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a 3D body or the axisymmetric geometry (whose axial
    /// direction is in the mesh: hold or free its end faces instead), and the errors of
    /// [`assemble_elastic_stiffness`].
    pub fn assemble(body: &ElasticBody, options: &ElasticOptions) -> Result<Self, PhysicsError> {
        check(body, options)?;
        let dim = body.layout().components;
        if dim != 2 || options.geometry.is_axisymmetric() {
            return Err(body.invalid(format!(
                "generalized plane strain needs a 2D Cartesian cross-section, not a {dim}D {} \
                 body",
                if options.geometry.is_axisymmetric() {
                    "axisymmetric"
                } else {
                    "Cartesian"
                }
            )));
        }
        let (lambda, mu) = body.material.lame();
        let beta = body.material.thermal_stress_coefficient();
        let mesh = &body.mesh;
        let cells = mesh.cell_count();
        // Per cell: its nodes' (c_x, c_y, h) and its area.
        type CellPart = (Vec<[f64; 3]>, f64);
        let chunks: Vec<Result<Vec<CellPart>, PhysicsError>> = (0..cells.div_ceil(CELL_CHUNK))
            .into_par_iter()
            .map(|ch| {
                let mut out = Vec::with_capacity(CELL_CHUNK);
                let mut cv = CellValues::new();
                let mut x = [Vector3::zeros(); MAX_CELL_NODES];
                for c in ch * CELL_CHUNK..((ch + 1) * CELL_CHUNK).min(cells) {
                    let nn = reinit_cell(body, options, c, &mut cv, &mut x)?;
                    let mut part = vec![[0.0; 3]; nn];
                    let mut area = 0.0;
                    for q in 0..cv.len() {
                        let w = cells::weight(&cv, q, options.geometry);
                        let (n, g) = (cv.shape(q), cv.gradients(q));
                        for (a, p) in part.iter_mut().enumerate() {
                            p[0] += lambda * g[a][0] * w;
                            p[1] += lambda * g[a][1] * w;
                            p[2] += beta * n[a] * w;
                        }
                        area += w;
                    }
                    out.push((part, area));
                }
                Ok(out)
            })
            .collect();
        let layout = body.layout();
        let mut coupling = vec![0.0; layout.len()];
        let mut thermal = vec![0.0; mesh.node_count()];
        let mut area = 0.0;
        let mut c = 0;
        for ch in chunks {
            for (part, a) in ch? {
                for (&node, p) in mesh.cell(c).nodes.iter().zip(&part) {
                    coupling[layout.dof(node, 0) as usize] += p[0];
                    coupling[layout.dof(node, 1) as usize] += p[1];
                    thermal[node as usize] += p[2];
                }
                area += a;
                c += 1;
            }
        }
        let eigenstress = body
            .eigenstrain
            .map_or(0.0, |e| body.material.stress(&e, 0.0)[2] * area);
        Ok(Self {
            coupling,
            stiffness: (lambda + 2.0 * mu) * area,
            thermal,
            area,
            eigenstress,
        })
    }

    /// `int sigma_zz dA` (N) of the displacement `u`, the axial strain `e` and the
    /// temperature change `dt = T - T_ref` per node (less the eigenstrain's
    /// [`eigenstress`](Self::eigenstress)).
    pub fn axial_force(&self, u: &[f64], e: f64, dt: &[f64]) -> f64 {
        let cu: f64 = self.coupling.iter().zip(u).map(|(c, u)| c * u).sum();
        let ht: f64 = self.thermal.iter().zip(dt).map(|(h, t)| h * t).sum();
        cu + self.stiffness * e - ht - self.eigenstress
    }
}

/// The static solve of one 2D body in generalized plane strain: the displacement
/// (`node * 2 + k`) and the axial strain `e` under the body's loads (body force, tractions,
/// thermal strain of its temperature field) with `int sigma_zz dA = axial.at(0)` (no gas
/// pressure here: give the whole axial force in `axial.force`). The bordered system
/// ([`GeneralizedPlaneStrain`]) is solved by sparse Cholesky on the free unknowns.
///
/// ```
/// use mortar_fem::mesh::VolumeMesh;
/// use mortar_elements::volume::QUAD4;
/// use mortar_physics::elastic::{
///     solve_generalized_plane_strain, AxialForce, ComponentSet, ElasticBody, ElasticMaterial,
///     ElasticOptions,
/// };
/// use nalgebra::Vector3;
/// // A unit square section heated by 100 K, free ends: it expands freely in all three
/// // directions, u = alpha dT x and e = alpha dT, with no stress.
/// let mut mesh = VolumeMesh::new();
/// for (tag, x) in [(1, [0.0, 0.0, 0.0]), (2, [1.0, 0.0, 0.0]), (3, [1.0, 1.0, 0.0]), (4, [0.0, 1.0, 0.0])] {
///     mesh.add_node(tag, x)?;
/// }
/// mesh.add_cell(&QUAD4, &[1, 2, 3, 4])?;
/// let material = ElasticMaterial::new(200e9, 0.3).with_expansion(1e-5, 300.0);
/// let body = ElasticBody::new("square", mesh, material)
///     .with_temperature(vec![400.0; 4])?
///     .with_dirichlet_nodes(vec![0], ComponentSet::All, |_| Vector3::zeros())
///     .with_dirichlet_nodes(vec![1], ComponentSet::One(1), |_| Vector3::zeros());
/// let (u, e) = solve_generalized_plane_strain(&body, AxialForce::FREE, &ElasticOptions::default())?;
/// assert!((u[2] - 1e-3).abs() < 1e-15 && (e - 1e-3).abs() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`GeneralizedPlaneStrain::assemble`] and [`solve_elastic`](super::solve_elastic).
pub fn solve_generalized_plane_strain(
    body: &ElasticBody,
    axial: AxialForce,
    options: &ElasticOptions,
) -> Result<(Vec<f64>, f64), PhysicsError> {
    let gps = GeneralizedPlaneStrain::assemble(body, options)?;
    let k = assemble_elastic_stiffness(body, options)?;
    let mut f = assemble_elastic_load(body, options)?;
    let n = f.len();
    let t_ref = body.material.reference_temperature;
    let ht: f64 = match &body.temperature {
        Some(t) => gps
            .thermal
            .iter()
            .zip(t)
            .map(|(h, t)| h * (t - t_ref))
            .sum(),
        None => 0.0,
    };
    f.push(axial.at(0.0) + ht + gps.eigenstress);
    let bordered = border(&k, &gps.coupling, gps.stiffness);
    let (fixed, values) = body.dirichlet_dofs();
    let mut x = solve_held(body, &bordered, &f, &fixed, &values, crate::SOLVER)?;
    let e = x[n];
    x.truncate(n);
    Ok((x, e))
}

/// `[k c; c^T s]`: the matrix `k` bordered by the column and row `c` and the corner `s`.
fn border(k: &SparseMatrix, c: &[f64], s: f64) -> SparseMatrix {
    let n = c.len();
    let mut t = Triplets::default();
    for (r, row) in k.outer_iterator().enumerate() {
        for (col, v) in row.iter() {
            t.push(r as u32, col as u32, *v);
        }
        if c[r] != 0.0 {
            t.push(r as u32, n as u32, c[r]);
        }
    }
    for (col, &v) in c.iter().enumerate() {
        if v != 0.0 {
            t.push(n as u32, col as u32, v);
        }
    }
    t.push(n as u32, n as u32, s);
    t.to_csr(n + 1, n + 1)
}
