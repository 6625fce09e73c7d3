//! The static solve of one elastic body held by its own displacement conditions.

use mortar_fem::linalg::{
    inf_norm, well_conditioned, MatrixKind, SolverError, SparseMatrix, SparseSolver,
};

use crate::field::free::{free_block, free_numbering, FIXED};

use super::{assemble_elastic_load, assemble_elastic_stiffness, ElasticBody, ElasticOptions};
use crate::{PhysicsError, SOLVER};

/// The displacement of `body` (`node * dim + k`) under its loads (body force, tractions,
/// thermal eigenstrain) with its prescribed components eliminated: `K_ff u_f = f_f - K_fd u_d`
/// by sparse Cholesky.
///
/// ```
/// use mortar_fem::mesh::VolumeMesh;
/// use mortar_elements::volume::QUAD4;
/// use mortar_physics::elastic::{solve_elastic, ComponentSet, ElasticBody, ElasticMaterial};
/// use nalgebra::Vector3;
/// // A unit square (one Quad4, plane strain) heated by 100 K, held at one corner and
/// // against rotation: it expands freely, u = (1 + nu) alpha dT x.
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
/// let u = solve_elastic(&body)?;
/// let expected = 1.3 * 1e-5 * 100.0;
/// assert!((u[2] - expected).abs() < 1e-12 * expected); // node 2 = (1, 0): u_x
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// The errors of the assembly; [`PhysicsError::InvalidInput`] if the body is not held
/// against rigid motion (the stiffness of the free unknowns is not positive definite, or its
/// solution has no correct digit: [`well_conditioned`]).
pub fn solve_elastic(body: &ElasticBody) -> Result<Vec<f64>, PhysicsError> {
    solve_elastic_with(body, &ElasticOptions::default())
}

/// [`solve_elastic`] with the assembly options `options` (a quadrature degree, the
/// axisymmetric geometry).
///
/// ```
/// use mortar_fem::mesh::VolumeMesh;
/// use mortar_core::ModelGeometry;
/// use mortar_elements::volume::QUAD4;
/// use mortar_physics::elastic::{
///     solve_elastic_with, ComponentSet, ElasticBody, ElasticMaterial, ElasticOptions,
/// };
/// use nalgebra::Vector3;
/// // A solid cylinder of radius 1 and height 1 as one r-z Quad4, heated by 100 K, its axis
/// // held radially (u_r = 0 at r = 0, as every axis node needs) and its bottom axially: it
/// // expands freely, u = alpha dT (r, z).
/// let mut mesh = VolumeMesh::new();
/// for (tag, x) in [(1, [0.0, 0.0, 0.0]), (2, [1.0, 0.0, 0.0]), (3, [1.0, 1.0, 0.0]), (4, [0.0, 1.0, 0.0])] {
///     mesh.add_node(tag, x)?;
/// }
/// mesh.add_cell(&QUAD4, &[1, 2, 3, 4])?;
/// let material = ElasticMaterial::new(200e9, 0.3).with_expansion(1e-5, 300.0);
/// let body = ElasticBody::new("pellet", mesh, material)
///     .with_temperature(vec![400.0; 4])?
///     .with_dirichlet_nodes(vec![0, 3], ComponentSet::One(0), |_| Vector3::zeros())
///     .with_dirichlet_nodes(vec![0, 1], ComponentSet::One(1), |_| Vector3::zeros());
/// let options = ElasticOptions::default().with_geometry(ModelGeometry::Axisymmetric);
/// let u = solve_elastic_with(&body, &options)?;
/// let expected = 1e-5 * 100.0;
/// assert!((u[2] - expected).abs() < 1e-12 * expected); // node 2 = (1, 0): u_r
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`solve_elastic`].
pub fn solve_elastic_with(
    body: &ElasticBody,
    options: &ElasticOptions,
) -> Result<Vec<f64>, PhysicsError> {
    solve_elastic_on(body, options, SOLVER)
}

/// [`solve_elastic_with`] by the sparse solver `solver` (the direct backend
/// [`FaerSolver`](mortar_fem::linalg::FaerSolver) by default; an iterative one, PETSc's say,
/// solves to its own tolerance): `K_ff` is handed over as a symmetric positive definite
/// matrix.
///
/// # Errors
/// As [`solve_elastic`], and the solver's errors (an iterative solve that does not
/// converge).
pub fn solve_elastic_on(
    body: &ElasticBody,
    options: &ElasticOptions,
    solver: &dyn SparseSolver,
) -> Result<Vec<f64>, PhysicsError> {
    let k = assemble_elastic_stiffness(body, options)?;
    let f = assemble_elastic_load(body, options)?;
    let (fixed, values) = body.dirichlet_dofs();
    solve_held(body, &k, &f, &fixed, &values, solver)
}

/// Solves `k u = f` for the unknowns not in `fixed` (held at `values`) by `solver`
/// (symmetric positive definite): `K_ff u_f = f_f - K_fd u_d`. `body` names the errors.
pub(crate) fn solve_held(
    body: &ElasticBody,
    k: &SparseMatrix,
    f: &[f64],
    fixed: &[u32],
    values: &[f64],
    solver: &dyn SparseSolver,
) -> Result<Vec<f64>, PhysicsError> {
    let (free, m) = free_numbering(f.len(), fixed);
    let mut u = vec![0.0; f.len()];
    for (&d, &v) in fixed.iter().zip(values) {
        u[d as usize] = v;
    }
    let kff = free_block(&[k], &free, m);
    // The right-hand side less the prescribed displacements' forces.
    let mut rhs = Vec::with_capacity(m);
    for (r, row) in k.outer_iterator().enumerate() {
        if free[r] != FIXED {
            let prescribed: f64 = row
                .iter()
                .filter(|(c, _)| free[*c] == FIXED)
                .map(|(c, v)| v * u[c])
                .sum();
            rhs.push(f[r] - prescribed);
        }
    }
    let not_held = |why: String| PhysicsError::InvalidInput {
        body: body.name.clone(),
        what: format!(
            "{why}: the body is not held against rigid motion by its displacement conditions"
        ),
    };
    let factor = solver
        .factor(&kff, MatrixKind::SymmetricPositiveDefinite)
        .map_err(|e| match e {
            SolverError::NotPositiveDefinite { .. } | SolverError::Singular { .. } => not_held(
                format!("the stiffness of the free displacements is not positive definite ({e})"),
            ),
            e => e.into(),
        })?;
    let b_norm = inf_norm(&rhs);
    factor.solve_in_place(&mut rhs)?;
    // A singular stiffness whose round-off left a small positive pivot factorises: its
    // solution has no correct digit.
    if !well_conditioned(&kff, &rhs, b_norm) {
        return Err(not_held(
            "the solution has no correct digit (|K| |u| / |f| above 1e-3 / eps)".into(),
        ));
    }
    for (i, &p) in free.iter().enumerate() {
        if p != FIXED {
            u[i] = rhs[p as usize];
        }
    }
    Ok(u)
}
