//! Cell set-up shared by the assemblies of every field (heat, elasticity).

use mortar_core::element::volume::{CellValues, VolumeDomain, MAX_CELL_NODES};
use mortar_core::mesh::VolumeMesh;
use mortar_core::quadrature::{max_volume_degree, VolumeQuadratureRule};
use nalgebra::Vector3;

use crate::error::PhysicsError;

/// Cells per work chunk of the parallel assemblies. Fixed, so that the summation order (and
/// every bit of the result) does not depend on the thread count.
pub(crate) const CELL_CHUNK: usize = 512;

/// Sets `cv` up on cell `c` of the mesh of body `body` (the rule of degree `degree(p)` for
/// its shape degree `p`, its node coordinates copied into `x`) and returns the node count.
///
/// # Errors
/// [`PhysicsError::InvalidInput`] for a degree no rule reaches, [`PhysicsError::InvertedCell`]
/// for a non-positive Jacobian determinant; both name the body (and the cell).
pub(crate) fn reinit_cell(
    body: &str,
    mesh: &VolumeMesh,
    degree: impl Fn(u32) -> u32,
    c: usize,
    cv: &mut CellValues,
    x: &mut [Vector3<f64>; MAX_CELL_NODES],
) -> Result<usize, PhysicsError> {
    let cell = mesh.cell(c);
    let rule = cell_rule(
        body,
        cell.element.domain(),
        degree(cell.element.shape_degree()),
    )?;
    let nn = mesh.cell_coords_into(c, x);
    cv.reinit(cell.element, rule, &x[..nn])
        .map_err(|source| PhysicsError::InvertedCell {
            body: body.to_string(),
            cell: cell.tag,
            source,
        })?;
    Ok(nn)
}

/// The cached rule of a cell's domain, or an error naming the body.
fn cell_rule(
    body: &str,
    domain: VolumeDomain,
    degree: u32,
) -> Result<&'static VolumeQuadratureRule, PhysicsError> {
    VolumeQuadratureRule::cached(domain, degree).map_err(|_| PhysicsError::InvalidInput {
        body: body.to_string(),
        what: format!(
            "no {domain:?} quadrature of degree {degree} (at most {})",
            max_volume_degree(domain)
        ),
    })
}
