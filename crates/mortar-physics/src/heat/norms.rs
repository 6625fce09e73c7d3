//! L2, H1-seminorm and largest nodal errors of a discrete temperature against an exact
//! solution (`error_norms`), for convergence studies.

use mortar_fem::element::{CellValues, MAX_CELL_NODES};
use mortar_fem::mesh::VolumeMesh;
use mortar_fem::quadrature::VolumeQuadratureRule;
use nalgebra::Vector3;
use rayon::prelude::*;

use super::assembly::CELL_CHUNK;
use crate::error::PhysicsError;

/// Errors of a discrete field against an exact solution.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ErrorNorms {
    /// `||u_h - u||_L2`, by quadrature.
    pub l2: f64,
    /// The H1 seminorm `||grad u_h - grad u||_L2`, by quadrature.
    pub h1_seminorm: f64,
    /// The largest nodal error `max |u_h(x_i) - u(x_i)|`.
    pub max_nodal: f64,
}

/// The L2 and H1-seminorm errors of the nodal field `u` (by mesh node index) against the exact
/// solution `exact` with gradient `gradient`, by quadrature of degree `degree` on every cell
/// (`None`: `2 p + 3` for shape functions of degree `p`, at most the domain's highest degree).
/// Parallel over fixed chunks of cells, summed in order.
///
/// # Errors
/// [`PhysicsError::WrongLength`] if `u` does not have one value per node,
/// [`PhysicsError::InvertedCell`], [`PhysicsError::InvalidInput`] for a degree without rule.
pub fn error_norms(
    mesh: &VolumeMesh,
    u: &[f64],
    exact: &(dyn Fn(&Vector3<f64>) -> f64 + Sync),
    gradient: &(dyn Fn(&Vector3<f64>) -> Vector3<f64> + Sync),
    degree: Option<u32>,
) -> Result<ErrorNorms, PhysicsError> {
    if u.len() != mesh.node_count() {
        return Err(PhysicsError::WrongLength {
            what: "nodal field".into(),
            expected: mesh.node_count(),
            got: u.len(),
        });
    }
    let cells = mesh.cell_count();
    let parts: Vec<Result<(f64, f64), PhysicsError>> = (0..cells.div_ceil(CELL_CHUNK))
        .into_par_iter()
        .map(|ch| {
            let mut cv = CellValues::new();
            let mut x = [Vector3::zeros(); MAX_CELL_NODES];
            let mut ue = [0.0; MAX_CELL_NODES];
            let (mut l2, mut h1) = (0.0, 0.0);
            for c in ch * CELL_CHUNK..((ch + 1) * CELL_CHUNK).min(cells) {
                let cell = mesh.cell(c);
                let domain = cell.element.domain();
                let max = mortar_fem::quadrature::max_volume_degree(domain);
                let deg = degree
                    .unwrap_or(2 * cell.element.shape_degree() + 3)
                    .min(max);
                let rule = VolumeQuadratureRule::cached(domain, deg).map_err(|e| {
                    PhysicsError::InvalidInput {
                        body: "error norms".into(),
                        what: e.to_string(),
                    }
                })?;
                let nn = mesh.cell_coords_into(c, &mut x);
                for (v, &n) in ue.iter_mut().zip(cell.nodes) {
                    *v = u[n as usize];
                }
                cv.reinit(cell.element, rule, &x[..nn]).map_err(|source| {
                    PhysicsError::InvertedCell {
                        body: "error norms".into(),
                        cell: cell.tag,
                        source,
                    }
                })?;
                for q in 0..cv.len() {
                    let p = cv.point(q);
                    let e = cv.value(q, &ue[..nn]) - exact(&p);
                    let mut g = cv.gradient(q, &ue[..nn]) - gradient(&p);
                    if cell.element.dim() == 2 {
                        g.z = 0.0;
                    }
                    l2 += e * e * cv.jxw(q);
                    h1 += g.norm_squared() * cv.jxw(q);
                }
            }
            Ok((l2, h1))
        })
        .collect();
    let (mut l2, mut h1) = (0.0, 0.0);
    for p in parts {
        let (a, b) = p?;
        l2 += a;
        h1 += b;
    }
    let max_nodal = mesh
        .coords()
        .iter()
        .zip(u)
        .map(|(x, v)| (v - exact(x)).abs())
        .fold(0.0, f64::max);
    Ok(ErrorNorms {
        l2: l2.sqrt(),
        h1_seminorm: h1.sqrt(),
        max_nodal,
    })
}
