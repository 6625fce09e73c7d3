//! Second-order meshes from first-order ones: every Tri3, Quad4, Tet4 and Hex8 cell becomes
//! its quadratic counterpart, the new nodes shared between the cells that share their edge or
//! face, and each new node placed by the caller (at the straight position, or moved onto the
//! curved surface the mesh approximates).

use std::collections::HashMap;

use mortar_elements::volume::{HEX20, HEX27, HEX8, QUAD4, QUAD8, QUAD9, TET10, TET4, TRI3, TRI6};
use mortar_fem::element::VolumeElementRef;
use mortar_fem::mesh::{VolumeMesh, VolumeMeshError};
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

/// A `place` for [`second_order_mesh`] that moves a new node onto the cylinder of `radius`
/// about the axis through `point` along `axis` when all its parents lie on it (at the radius
/// from the axis, to `1e-9` of the radius), along the radius (perpendicular to the axis, its
/// position along the axis kept); other nodes stay straight. A new node on a straight edge
/// of the cylinder (parents at one angle) stays where it is, on it already.
///
/// As [`onto_sphere`], it assumes that nodes on the cylinder are joined through the cells
/// only along the surface (as in the extruded annuli of
/// [`quarter_annulus_mesh`](super::quarter_annulus_mesh) and
/// [`extrude_mesh`](super::extrude_mesh)).
///
/// # Panics
/// If `axis` is zero or not finite.
pub fn onto_cylinder(
    point: [f64; 3],
    axis: [f64; 3],
    radius: f64,
) -> impl Fn(&Vector3<f64>, &[Vector3<f64>]) -> Vector3<f64> {
    let c = Vector3::from(point);
    let a = Vector3::from(axis)
        .try_normalize(0.0)
        .filter(|a| a.iter().all(|v| v.is_finite()))
        .expect("the cylinder's axis is a finite non-zero vector");
    // The part of `x - c` across the axis.
    let across = move |x: &Vector3<f64>| {
        let d = x - c;
        d - a * a.dot(&d)
    };
    move |x, parents| {
        let on = |p: &Vector3<f64>| (across(p).norm() - radius).abs() <= 1e-9 * radius;
        if parents.iter().all(on) {
            let r = across(x);
            x + r * (radius / r.norm() - 1.0)
        } else {
            *x
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{extrude_mesh, quarter_annulus_mesh, CellShape};
    use mortar_core::quadrature::{Quadrature, QuadratureRule};

    /// An extruded quarter annulus `0.2 <= r <= 0.5` about the z axis (height 0.7, 6 x 2 x 2
    /// cells) raised to Hex27, once with straight new nodes and once with [`onto_cylinder`] for
    /// both arcs (the outer one given by another point of the axis and a scaled, reversed
    /// direction). Checks: every node of a face on either lateral surface is at that radius
    /// (to 1e-14), every other node is where the straight mesh has it; and the outer lateral
    /// area, integrated over the curved Quad9 faces, is the quarter cylinder's closed form
    /// `(pi / 2) r h` to better than the square of the flat faces' error `1 - sin(t) / t`
    /// (t = half the angle of a cell; 2.9e-3 here, and 4.9e-6 for the curved faces).
    #[test]
    fn onto_cylinder_curves_the_lateral_faces() {
        let (inner, outer, h) = (0.2, 0.5, 0.7);
        let annulus = quarter_annulus_mesh(inner, outer, [6, 2], CellShape::Tensor, 1).unwrap();
        let hex = extrude_mesh(&annulus, &[0.0, 0.3, h], 1).unwrap();
        let straight = second_order_mesh(&hex, SecondOrder::Complete, |x, _| *x).unwrap();
        let (o, i) = (
            onto_cylinder([0.0, 0.0, 5.0], [0.0, 0.0, -2.0], outer),
            onto_cylinder([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], inner),
        );
        let raised = second_order_mesh(&hex, SecondOrder::Complete, |x, p| i(&o(x, p), p)).unwrap();
        assert_eq!(raised.node_tags(), straight.node_tags());
        let radius = |x: &Vector3<f64>| x.xy().norm();
        let mut on = vec![false; raised.node_count()];
        let (mut area, mut lateral) = (0.0, 0);
        for f in &raised.boundary_faces().unwrap() {
            let x: Vec<Vector3<f64>> = f
                .nodes
                .iter()
                .map(|&n| raised.coords()[n as usize])
                .collect();
            for r in [inner, outer] {
                if !x[..4].iter().all(|p| (radius(p) - r).abs() < 1e-12) {
                    continue;
                }
                for (p, &n) in x.iter().zip(&f.nodes) {
                    assert!((radius(p) - r).abs() < 1e-14 * r, "{p} off r = {r}");
                    on[n as usize] = true;
                }
                if r == outer {
                    lateral += 1;
                    let rule = QuadratureRule::cached(f.element.domain(), 12).unwrap();
                    area += rule
                        .points()
                        .iter()
                        .zip(rule.weights())
                        .map(|(q, w)| w * f.element.jacobian_det(&x, q))
                        .sum::<f64>();
                }
            }
        }
        assert_eq!(lateral, 12);
        for (k, (p, q)) in raised.coords().iter().zip(straight.coords()).enumerate() {
            if !on[k] {
                assert_eq!(p, q, "node {k} moved");
            }
        }
        let exact = std::f64::consts::FRAC_PI_2 * outer * h;
        let t = std::f64::consts::FRAC_PI_4 / 6.0;
        let flat = 1.0 - t.sin() / t;
        let rel = (area - exact).abs() / exact;
        assert!(
            rel < flat * flat,
            "area {area} vs {exact}: {rel:e}, flat {flat:e}"
        );
    }
}
