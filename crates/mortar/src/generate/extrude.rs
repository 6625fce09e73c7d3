//! Extrusion of a 2D mesh along z.

use mortar_elements::volume::HEX8;
use mortar_fem::mesh::{VolumeMesh, VolumeMeshError};

/// The 3D mesh swept by the Quad4 mesh `mesh` (in the plane `z = 0`) through the levels
/// `z_levels` (ascending): one Hex8 per quad and layer, bottom face the quad at the lower
/// level, in Gmsh node order (so positively oriented when the quads are counter-clockwise
/// seen from `+z`). Node `i` of level `k` gets the tag `first_node_tag + k n + i` (`n` the
/// 2D node count, in the 2D mesh's node order); cells are tagged from 1.
///
/// ```
/// use mortar::generate::{extrude_mesh, rectangle_mesh, CellShape};
/// let square = rectangle_mesh([0.0, 0.0], [1.0, 1.0], [2, 2], CellShape::Tensor, 1)?;
/// let cube = extrude_mesh(&square, &[0.0, 0.5, 1.0], 1)?;
/// assert_eq!((cube.node_count(), cube.cell_count()), (27, 8));
/// # Ok::<(), mortar::core::mesh::VolumeMeshError>(())
/// ```
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for a cell that is not a Quad4, fewer than two levels, levels
/// not finite and strictly ascending, or a 2D node off the plane `z = 0`.
pub fn extrude_mesh(
    mesh: &VolumeMesh,
    z_levels: &[f64],
    first_node_tag: u64,
) -> Result<VolumeMesh, VolumeMeshError> {
    let bad = |cell: u64, reason: String| VolumeMeshError::BadCell {
        cell,
        element: "extrusion",
        reason,
    };
    if z_levels.len() < 2
        || !z_levels.iter().all(|z| z.is_finite())
        || z_levels.windows(2).any(|w| w[1] <= w[0])
    {
        return Err(bad(
            0,
            format!("levels {z_levels:?} are not at least two, finite and strictly ascending"),
        ));
    }
    let n = mesh.node_count();
    let coords = mesh.coords();
    if let Some(i) = coords.iter().position(|x| x.z != 0.0) {
        return Err(bad(0, format!("2D node {i} is off the plane z = 0")));
    }
    let mut out = VolumeMesh::new();
    let tag = |k: usize, i: usize| first_node_tag + (k * n + i) as u64;
    for (k, &z) in z_levels.iter().enumerate() {
        for (i, x) in coords.iter().enumerate() {
            out.add_node(tag(k, i), [x.x, x.y, z])?;
        }
    }
    for k in 0..z_levels.len() - 1 {
        for c in 0..mesh.cell_count() {
            let cell = mesh.cell(c);
            if cell.element.name() != "Quad4" {
                return Err(bad(
                    cell.tag,
                    format!("a {} cell: only Quad4 is extruded", cell.element.name()),
                ));
            }
            let nodes: Vec<u64> = (0..2)
                .flat_map(|level| cell.nodes.iter().map(move |&i| tag(k + level, i as usize)))
                .collect();
            out.add_cell(&HEX8, &nodes)?;
        }
    }
    Ok(out)
}
