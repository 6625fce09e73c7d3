//! Cell set-up shared by the assemblies of every field (heat, elasticity).

use mortar_core::element::MAX_FACE_NODES;
use mortar_core::linalg::{CompressWorkspace, PartList, SparseMatrix, Triplets};
use mortar_core::quadrature::{Quadrature, QuadratureRule};
use mortar_core::{ModelGeometry, MortarError};
use mortar_fem::element::{CellValues, VolumeDomain, MAX_CELL_NODES};
use mortar_fem::mesh::{BoundaryFace, VolumeMesh};
use mortar_fem::quadrature::{max_volume_degree, VolumeQuadratureRule};
use nalgebra::{Vector2, Vector3};

use crate::error::PhysicsError;

/// Cells per work chunk of the parallel assemblies. Fixed, so that the summation order (and
/// every bit of the result) does not depend on the thread count.
pub(crate) const CELL_CHUNK: usize = 512;

/// The triplets `raw` of chunk `key` compressed into a part list of their own (sorted,
/// duplicates summed in insertion order), so that a parallel assembly holds each chunk's
/// compressed entries (12 bytes each, the chunk's duplicates summed) rather than every
/// chunk's raw triplets (16 bytes each) until the end: on a 3D Tet4 body a third to a
/// quarter of the memory. [`merged_csr`] of the chunks' lists is bit for bit the matrix
/// `Triplets::to_csr_from_parts` makes of the raw chunks (the same compression of each
/// part, the parts summed in key order).
pub(crate) fn compressed_chunk(key: usize, mut raw: Triplets) -> PartList {
    let mut list = PartList::default();
    list.push_compressed(key as u64, &mut raw, &mut CompressWorkspace::default());
    list
}

/// The `nrows x ncols` matrix of the chunks' part lists (see [`compressed_chunk`]).
pub(crate) fn merged_csr(
    chunks: impl IntoIterator<Item = PartList>,
    nrows: usize,
    ncols: usize,
) -> SparseMatrix {
    let mut list = PartList::default();
    for chunk in chunks {
        list.append(chunk);
    }
    list.to_csr(nrows, ncols)
}

/// The weight of point `q` of `cv` in the measure of `geometry`: `jxw(q)` (Cartesian) or
/// `jxw(q) 2 pi r(x_q)` (axisymmetric).
#[inline]
pub(crate) fn weight(cv: &CellValues, q: usize, geometry: ModelGeometry) -> f64 {
    match geometry {
        ModelGeometry::Cartesian => cv.jxw(q),
        ModelGeometry::Axisymmetric => cv.jxw(q) * geometry.weight(&cv.point(q)),
    }
}

/// Checks that the mesh of body `body` can be integrated in `geometry`: the axisymmetric
/// geometry needs a 2D mesh whose nodes lie at radii `x >= 0` (within
/// [`ModelGeometry::axis_tolerance`]).
///
/// # Errors
/// [`PhysicsError::InvalidInput`] for an axisymmetric 3D mesh,
/// [`PhysicsError::NegativeRadius`] for a node at a negative radius (the first).
pub(crate) fn check_geometry(
    body: &str,
    mesh: &VolumeMesh,
    geometry: ModelGeometry,
) -> Result<(), PhysicsError> {
    if !geometry.is_axisymmetric() {
        return Ok(());
    }
    if let Some(dim) = mesh.dim().filter(|&d| d != 2) {
        return Err(PhysicsError::InvalidInput {
            body: body.to_string(),
            what: format!(
                "the axisymmetric (r-z) geometry needs a 2D mesh in the plane z = 0 (x the \
                 radius, y the axis); this mesh is {dim}D"
            ),
        });
    }
    if let Some((i, radius)) = geometry.first_negative_radius(mesh.coords()) {
        return Err(PhysicsError::NegativeRadius {
            body: body.to_string(),
            node: mesh.node_tags()[i],
            radius,
        });
    }
    Ok(())
}

/// Checks that a coupling and the bodies it couples integrate in the same geometry (an r-z
/// coupling of Cartesian bodies, or the reverse, would mix W with W/m).
///
/// # Errors
/// [`PhysicsError::InvalidInput`] (body `"options"`) naming both geometries.
pub(crate) fn check_same_geometry(
    coupling: ModelGeometry,
    bodies: ModelGeometry,
) -> Result<(), PhysicsError> {
    if coupling == bodies {
        return Ok(());
    }
    Err(PhysicsError::InvalidInput {
        body: "options".into(),
        what: format!(
            "the coupling options' geometry ({coupling}) differs from the body options' \
             ({bodies}): give both the same"
        ),
    })
}

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

/// Calls `f(x, w, jac, nodes, shape)` at each point of the degree-`degree(p)` rule on a
/// boundary face of `mesh` (`p` its shape degree): the point `x`, the rule's weight `w`, the
/// face's Jacobian `jac`, the face's node indices and its shape values there. The face loads
/// of every field (heat flux, traction) are sums of `w * jac * value(x) * shape` over these
/// points (times the measure factor [`ModelGeometry::weight`] of `x`).
///
/// # Errors
/// The core's error for a degree no cached rule reaches.
pub(crate) fn for_each_face_point(
    mesh: &VolumeMesh,
    face: &BoundaryFace,
    degree: impl Fn(u32) -> u32,
    mut f: impl FnMut(&Vector3<f64>, f64, f64, &[u32], &[f64]),
) -> Result<(), MortarError> {
    let el = face.element;
    let rule = QuadratureRule::cached(el.domain(), degree(el.shape_degree()))?;
    let k = face.nodes.len();
    let mut x = [Vector3::zeros(); MAX_FACE_NODES];
    let mut nvals = [0.0; MAX_FACE_NODES];
    for (xi, &n) in x.iter_mut().zip(&face.nodes) {
        *xi = mesh.coords()[n as usize];
    }
    for (p, w) in rule.points().iter().zip(rule.weights()) {
        let p: &Vector2<f64> = p;
        el.shape_values_into(p, &mut nvals[..k]);
        let xp = el.map(&x[..k], p);
        f(
            &xp,
            *w,
            el.jacobian_det(&x[..k], p),
            &face.nodes,
            &nvals[..k],
        );
    }
    Ok(())
}

/// The boundary faces of `mesh` for which `select` is true (the faces a flux or traction
/// condition applies to).
///
/// # Errors
/// The mesh's error for a broken boundary.
pub(crate) fn boundary_faces_where(
    mesh: &VolumeMesh,
    select: impl Fn(&BoundaryFace) -> bool,
) -> Result<Vec<BoundaryFace>, mortar_fem::mesh::VolumeMeshError> {
    Ok(mesh
        .boundary_faces()?
        .into_iter()
        .filter(|f| select(f))
        .collect())
}
