//! Second-order meshes from first-order ones: every Tri3, Quad4, Tet4 and Hex8 cell becomes
//! its quadratic counterpart, the new nodes shared between the cells that share their edge or
//! face, and each new node placed by the caller (at the straight position, or moved onto the
//! curved surface the mesh approximates).

use std::collections::HashMap;

use mortar_core::element::volume::VolumeElementRef;
use mortar_core::mesh::{VolumeMesh, VolumeMeshError};
use mortar_elements::volume::{HEX20, HEX27, HEX8, QUAD4, QUAD8, QUAD9, TET10, TET4, TRI3, TRI6};
use nalgebra::Vector3;

/// Which second-order family a mesh is raised to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SecondOrder {
    /// Tri6, Quad9, Tet10, Hex27 (complete: Gmsh's `Mesh.SecondOrderIncomplete = 0`).
    #[default]
    Complete,
    /// Tri6, Quad8, Tet10, Hex20 (serendipity: `Mesh.SecondOrderIncomplete = 1`).
    Serendipity,
}

/// The second-order mesh of `mesh`: each cell raised to its counterpart of `family`, with the
/// same cell tags; the old nodes keep their tags and positions, the new ones are tagged after
/// the largest old tag. A new node lies on an edge, a face or in a cell, between the corners
/// its reference position interpolates (`parents`); `place(straight, parents)` gives its
/// position from the straight one (the linear interpolation of the parents) and the parents'
/// positions: `|x, _| *x` keeps straight cells, a projection onto a circle or sphere for
/// nodes whose parents all lie on it curves the cells up to that surface.
///
/// # Errors
/// [`VolumeMeshError::BadCell`] for a cell that is not a Tri3, Quad4, Tet4 or Hex8; the
/// errors of building the new mesh (a placed node off the plane of a 2D mesh, an inverted
/// cell).
pub fn second_order_mesh(
    mesh: &VolumeMesh,
    family: SecondOrder,
    place: impl Fn(&Vector3<f64>, &[Vector3<f64>]) -> Vector3<f64>,
) -> Result<VolumeMesh, VolumeMeshError> {
    let mut out = VolumeMesh::new();
    let coords = mesh.coords();
    let tags = mesh.node_tags();
    for (t, x) in tags.iter().zip(coords) {
        out.add_node(*t, (*x).into())?;
    }
    let mut next = tags.iter().copied().max().unwrap_or(0) + 1;
    // New nodes by their sorted parent node indices.
    let mut added: HashMap<Vec<u32>, u64> = HashMap::new();
    for c in 0..mesh.cell_count() {
        let cell = mesh.cell(c);
        let (linear, raised) =
            counterpart(cell.element, family).ok_or_else(|| VolumeMeshError::BadCell {
                cell: cell.tag,
                element: cell.element.name(),
                reason: "only Tri3, Quad4, Tet4 and Hex8 cells are raised to second order".into(),
            })?;
        let k = linear.node_count();
        let mut n = [0.0; 8];
        let mut cell_tags: Vec<u64> = cell.nodes.iter().map(|&i| tags[i as usize]).collect();
        for r in &raised.node_reference_coords()[k..] {
            linear.shape_values_into(&Vector3::from(*r), &mut n[..k]);
            let mut parents: Vec<u32> = (0..k)
                .filter(|&i| n[i].abs() > 1e-12)
                .map(|i| cell.nodes[i])
                .collect();
            parents.sort_unstable();
            let tag = match added.get(&parents) {
                Some(&t) => t,
                None => {
                    let straight = (0..k)
                        .map(|i| coords[cell.nodes[i] as usize] * n[i])
                        .sum::<Vector3<f64>>();
                    let xs: Vec<Vector3<f64>> =
                        parents.iter().map(|&p| coords[p as usize]).collect();
                    out.add_node(next, place(&straight, &xs).into())?;
                    added.insert(parents, next);
                    next += 1;
                    next - 1
                }
            };
            cell_tags.push(tag);
        }
        out.add_cell_with_tag(cell.tag, raised, &cell_tags)?;
    }
    Ok(out)
}

/// The linear element of a cell and its second-order counterpart in `family`.
fn counterpart(
    element: VolumeElementRef,
    family: SecondOrder,
) -> Option<(VolumeElementRef, VolumeElementRef)> {
    let serendipity = family == SecondOrder::Serendipity;
    Some(match element.name() {
        "Tri3" => (&TRI3, &TRI6),
        "Quad4" => (&QUAD4, if serendipity { &QUAD8 } else { &QUAD9 }),
        "Tet4" => (&TET4, &TET10),
        "Hex8" => (&HEX8, if serendipity { &HEX20 } else { &HEX27 }),
        _ => return None,
    })
}

/// A `place` for [`second_order_mesh`] that moves a new node onto the sphere (circle, in the
/// plane `z = 0`) of `centre` and `radius` when all its parents lie on it (to `1e-9` of the
/// radius), radially from the centre; other nodes stay straight.
///
/// It assumes that nodes on the sphere are joined through the cells only along the surface
/// (as in the O-grids of [`ball_mesh`](super::ball_mesh) and
/// [`box_with_hole_mesh`](super::box_with_hole_mesh), whose cells touch the sphere with one
/// face): an edge through a cell's inside between two nodes of the sphere would be bent onto
/// it too.
pub fn onto_sphere(
    centre: [f64; 3],
    radius: f64,
) -> impl Fn(&Vector3<f64>, &[Vector3<f64>]) -> Vector3<f64> {
    let c = Vector3::from(centre);
    move |x, parents| {
        let on = |p: &Vector3<f64>| ((p - c).norm() - radius).abs() <= 1e-9 * radius;
        if parents.iter().all(on) {
            let d = x - c;
            c + d * (radius / d.norm())
        } else {
            *x
        }
    }
}
