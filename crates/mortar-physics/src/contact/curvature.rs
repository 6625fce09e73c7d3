//! The slave surface's curvature at its interface nodes (from its nodal normals) and the
//! change of its nodal areas with the displacement: what turns the nodal gaps into the
//! gap's volume, to second order in the gap and first in the displacement.

use std::collections::HashMap;

use mortar_core::element::MAX_FACE_NODES;
use mortar_core::linalg::{SparseMatrix, Triplets};
use mortar_core::quadrature::{Quadrature, QuadratureRule};
use mortar_core::{Coupling, Interface, ModelGeometry};
use nalgebra::{Vector2, Vector3};

use crate::error::PhysicsError;

/// The slave surface's measures at its interface nodes (the rows of a coupling): its
/// curvature and the first-order change of its nodal areas with the displacement
/// ([`slave_surface_measures`]).
#[derive(Debug, Clone)]
pub struct SlaveSurfaceMeasures {
    /// Per row `j`, the mean curvature sum `kappa_j` of the slave surface: the surface
    /// divergence of the interpolated nodal normal field `n_h = sum n_k N_k` (the slave's
    /// averaged unit normals) averaged with the node's shape function,
    /// `kappa_j = int div_s(n_h) N_j dS / int N_j dS`, with, in the axisymmetric geometry, the
    /// hoop curvature `n_h,r / r` added and the revolved measure `2 pi r dS` in both
    /// integrals. Positive where the surface is convex along its normal (a pellet: `1 / a`
    /// across its axis, exactly on a polygon whose nodal normals are radial), zero where it is
    /// flat.
    pub curvature: Vec<f64>,
    /// The change of the nodal areas `int N_j dS` with the slave body's displacement `u`
    /// (`node * dim + i`, the body's node numbering): `d(int N_j dS) = int N_j div_s(u) dS`,
    /// a row per coupling row, `[A u]_j = sum_k int N_j grad_s N_k dS . u_k` (in the
    /// axisymmetric geometry plus the hoop stretch `int N_j N_k u_k,r / r`), without the
    /// stretch along the axis when one is given (its components `u_k,axis` left out).
    pub area_change: SparseMatrix,
}

/// The measures of the slave surface of `coupling` on `interface` in `geometry`
/// ([`SlaveSurfaceMeasures`]); `body_nodes[j]` is the slave body's node of row `j`, whose
/// displacement has `dim` components; `axis`, if given, the component along which the
/// surface's stretch is not counted (a rod's axis, whose volumes are per as-built length). The volume between the surface and its offset by `g`
/// along the normal is `int (g + kappa g^2 / 2 + ...) dS` (Steiner's formula; the Gaussian
/// curvature's `g^3` term vanishes on cylinders), over the surface as it moved:
/// [`GapThermoMechanics`](crate::thermomech::GapThermoMechanics) takes its gas volume so.
///
/// # Errors
/// [`PhysicsError::InvalidInput`] for a face node that is not a coupling row, a row without
/// a body node, or a quadrature rule that cannot be built.
pub fn slave_surface_measures(
    interface: &Interface,
    coupling: &Coupling,
    geometry: ModelGeometry,
    body_nodes: &[u32],
    dim: usize,
    axis: Option<usize>,
) -> Result<SlaveSurfaceMeasures, PhysicsError> {
    let c = coupling;
    let surface = interface.slave();
    let invalid = |what: String| PhysicsError::InvalidInput {
        body: "contact".into(),
        what,
    };
    let row: HashMap<u64, usize> = c
        .slave_nodes
        .iter()
        .enumerate()
        .map(|(j, &tag)| (tag, j))
        .collect();
    let rows = c.slave_nodes.len();
    if body_nodes.len() != rows {
        return Err(invalid(format!(
            "{} body nodes for {rows} coupling rows",
            body_nodes.len()
        )));
    }
    let (mut sum, mut area) = (vec![0.0; rows], vec![0.0; rows]);
    let mut change = Triplets::default();
    let mut x = [Vector3::zeros(); MAX_FACE_NODES];
    let mut normals = [Vector3::zeros(); MAX_FACE_NODES];
    let mut face_rows = [0usize; MAX_FACE_NODES];
    let mut shape = [0.0; MAX_FACE_NODES];
    let mut grads = [[0.0; 2]; MAX_FACE_NODES];
    let mut surface_grads = [Vector3::zeros(); MAX_FACE_NODES];
    for f in 0..surface.face_count() {
        let face = surface.face(f);
        let (e, nn) = (face.element, face.nodes.len());
        for (k, &i) in face.nodes.iter().enumerate() {
            let tag = surface.node_tags()[i as usize];
            let j = *row
                .get(&tag)
                .ok_or_else(|| invalid(format!("slave node {tag} is not a row of the coupling")))?;
            x[k] = surface.coords()[i as usize];
            normals[k] = c.slave_normals[j];
            face_rows[k] = j;
        }
        let rule = QuadratureRule::cached(e.domain(), 2 * e.shape_degree() + 1)
            .map_err(|err| invalid(format!("no face quadrature for the curvature: {err}")))?;
        let surface_dim = e.domain().dim();
        for (xi, w) in rule.points().iter().zip(rule.weights()) {
            let xi: &Vector2<f64> = xi;
            e.shape_values_into(xi, &mut shape[..nn]);
            e.shape_gradients_into(xi, &mut grads[..nn]);
            let a = e.tangents(&x[..nn], xi);
            let point = e.map(&x[..nn], xi);
            let ds = e.jacobian_det(&x[..nn], xi) * w * geometry.weight(&point);
            let (mut divergence, n_h) = surface_gradients(
                &a,
                surface_dim,
                &grads[..nn],
                &shape[..nn],
                &normals[..nn],
                &mut surface_grads[..nn],
            );
            // The hoop terms of the revolved surface.
            let hoop = if geometry.is_axisymmetric() && point.x > 0.0 {
                1.0 / point.x
            } else {
                0.0
            };
            divergence += n_h.x * hoop;
            for a_row in 0..nn {
                let j = face_rows[a_row];
                sum[j] += divergence * shape[a_row] * ds;
                area[j] += shape[a_row] * ds;
                for k in 0..nn {
                    let node = body_nodes[face_rows[k]] as usize;
                    for i in (0..dim).filter(|&i| Some(i) != axis) {
                        let mut v = surface_grads[k][i];
                        if i == 0 {
                            v += shape[k] * hoop;
                        }
                        change.push(j as u32, (node * dim + i) as u32, shape[a_row] * v * ds);
                    }
                }
            }
        }
    }
    Ok(SlaveSurfaceMeasures::from_sums(
        &sum, &area, change, body_nodes, dim,
    ))
}

impl SlaveSurfaceMeasures {
    /// The measures of the per-row sums `sum = int div_s(n_h) N_j dS` and
    /// `area = int N_j dS` (a curvature of zero where the area is) and of the triplets
    /// `change` of the area change, over the slave body's unknowns up to its largest node of
    /// `body_nodes`, `dim` components each.
    fn from_sums(
        sum: &[f64],
        area: &[f64],
        change: Triplets,
        body_nodes: &[u32],
        dim: usize,
    ) -> Self {
        let cols = body_nodes
            .iter()
            .map(|&n| n as usize + 1)
            .max()
            .unwrap_or(0)
            * dim;
        Self {
            curvature: sum
                .iter()
                .zip(area)
                .map(|(s, a)| if *a > 0.0 { s / a } else { 0.0 })
                .collect(),
            area_change: change.to_csr(sum.len(), cols),
        }
    }
}

/// At a point of a face with the tangents `a` (the first `surface_dim` of them), the
/// reference shape gradients `grads` and values `shape` of its nodes and their unit normals
/// `normals`: the surface gradient of each shape function into `surface_grads`,
/// `g^{ab} dN_k/dxi_a t_b` (the inverse metric), and the surface divergence (without the
/// hoop term) and the value of the interpolated normal field `n_h = sum n_k N_k`.
fn surface_gradients(
    a: &[Vector3<f64>; 2],
    surface_dim: usize,
    grads: &[[f64; 2]],
    shape: &[f64],
    normals: &[Vector3<f64>],
    surface_grads: &mut [Vector3<f64>],
) -> (f64, Vector3<f64>) {
    let inverse = if surface_dim == 1 {
        [[1.0 / a[0].norm_squared(), 0.0], [0.0, 0.0]]
    } else {
        let (g11, g12, g22) = (a[0].dot(&a[0]), a[0].dot(&a[1]), a[1].dot(&a[1]));
        let det = g11 * g22 - g12 * g12;
        [[g22 / det, -g12 / det], [-g12 / det, g11 / det]]
    };
    let mut divergence = 0.0;
    let mut n_h = Vector3::zeros();
    for k in 0..grads.len() {
        let mut grad = Vector3::zeros();
        for (p, row) in inverse.iter().enumerate().take(surface_dim) {
            for (q, t) in a.iter().enumerate().take(surface_dim) {
                grad += row[q] * grads[k][p] * t;
            }
        }
        divergence += normals[k].dot(&grad);
        n_h += shape[k] * normals[k];
        surface_grads[k] = grad;
    }
    (divergence, n_h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use mortar_core::mesh::SurfaceMesh;
    use mortar_core::{assemble_coupling, CouplingOptions, SearchRadius, Tolerances};
    use mortar_elements::{LINE2, QUAD4};
    use std::f64::consts::PI;

    /// Two coaxial circles (`n` and `m` edges, radii `a` and `b`), the inner one's normals
    /// outward, the outer one's inward.
    fn rings(n: usize, m: usize, a: f64, b: f64) -> (SurfaceMesh, SurfaceMesh) {
        let ring = |count: usize, r: f64, first: u64, inward: bool| {
            let mut s = SurfaceMesh::new();
            for i in 0..count {
                let t = 2.0 * PI * i as f64 / count as f64;
                s.add_node(first + i as u64, [r * t.cos(), r * t.sin(), 0.0])
                    .unwrap();
            }
            for i in 0..count as u64 {
                let (p, q) = (first + i, first + (i + 1) % count as u64);
                let nodes = if inward { [q, p] } else { [p, q] };
                s.add_face(&LINE2, &nodes).unwrap();
            }
            s
        };
        (ring(n, a, 1, false), ring(m, b, 1000, true))
    }

    /// The curvature of `slave` coupled to `master` across the gap `gap`.
    fn curvature(
        slave: SurfaceMesh,
        master: SurfaceMesh,
        geometry: ModelGeometry,
        gap: f64,
    ) -> Vec<f64> {
        let tolerances = Tolerances {
            search_radius: SearchRadius::Distance(4.0 * gap),
            ..Tolerances::default()
        };
        let interface = Interface::with_tolerances(slave, master, tolerances).unwrap();
        let options = CouplingOptions::default().dual().with_geometry(geometry);
        let coupling = assemble_coupling(&interface, &options).unwrap();
        let body_nodes: Vec<u32> = (0..coupling.slave_nodes.len() as u32).collect();
        slave_surface_measures(&interface, &coupling, geometry, &body_nodes, 3, None)
            .unwrap()
            .curvature
    }

    /// Moving a circle's polygon radially by `d` (the field `u = d x / a`, linear along each
    /// chord) stretches every chord by `1 + d / a`: the nodal areas change by `w_j d / a`
    /// exactly; in r-z a cylinder moved out by `d` gains its hoop stretch `w_j d / r`.
    #[test]
    fn nodal_areas_change_with_the_displacement_as_the_surface_stretches() {
        let (s, m) = rings(24, 31, 2.0, 2.1);
        let tolerances = Tolerances {
            search_radius: SearchRadius::Distance(0.4),
            ..Tolerances::default()
        };
        let interface = Interface::with_tolerances(s, m, tolerances).unwrap();
        let coupling = assemble_coupling(&interface, &CouplingOptions::default().dual()).unwrap();
        let rows = coupling.slave_nodes.len();
        let body_nodes: Vec<u32> = (0..rows as u32).collect();
        let measures = slave_surface_measures(
            &interface,
            &coupling,
            ModelGeometry::Cartesian,
            &body_nodes,
            2,
            None,
        )
        .unwrap();
        let d = 1e-3;
        // Row j's body node is j: its coordinates are those of the slave node of tag j's row.
        let coords = interface.slave().coords();
        let tags = interface.slave().node_tags();
        let mut u = vec![0.0; 2 * rows];
        for (i, x) in coords.iter().enumerate() {
            let j = coupling
                .slave_nodes
                .iter()
                .position(|&t| t == tags[i])
                .unwrap();
            u[2 * j] = d * x.x / 2.0;
            u[2 * j + 1] = d * x.y / 2.0;
        }
        for (j, row) in measures.area_change.outer_iterator().enumerate() {
            let w: f64 = coupling
                .d
                .outer_view(j)
                .unwrap()
                .iter()
                .map(|(_, v)| v)
                .sum();
            let du: f64 = row.iter().map(|(k, v)| v * u[k]).sum();
            assert!((du - w * d / 2.0).abs() < 1e-14 * w, "{du} {}", w * d / 2.0);
        }
    }

    /// A polygon of a circle with radial nodal normals has curvature `1 / a` at every node
    /// (the closed form of the divergence of the interpolated normals on a chord), to rounding.
    #[test]
    fn a_circle_has_the_curvature_of_its_radius() {
        let (s, m) = rings(24, 31, 2.0, 2.1);
        let k = curvature(s, m, ModelGeometry::Cartesian, 0.1);
        assert_eq!(k.len(), 24);
        for v in k {
            assert!((v - 0.5).abs() < 1e-13, "{v}");
        }
    }

    /// The r-z section of a cylinder `r = a` (a vertical line) has only its hoop curvature,
    /// `1 / a`; a flat plate in 3D has none.
    #[test]
    fn a_cylinder_in_r_z_has_its_hoop_curvature_and_a_plane_none() {
        let line = |r: f64, n: usize, first: u64, up: bool| {
            let mut s = SurfaceMesh::new();
            for i in 0..=n {
                s.add_node(first + i as u64, [r, i as f64 / n as f64, 0.0])
                    .unwrap();
            }
            for i in 0..n as u64 {
                let (p, q) = (first + i, first + i + 1);
                let nodes = if up { [p, q] } else { [q, p] };
                s.add_face(&LINE2, &nodes).unwrap();
            }
            s
        };
        // Outward (+r) normals on the inner line: its faces run upward.
        let (s, m) = (line(3.0, 4, 1, true), line(3.2, 5, 100, false));
        let rz = ModelGeometry::Axisymmetric;
        for v in curvature(s.clone(), m.clone(), rz, 0.2) {
            assert!((v - 1.0 / 3.0).abs() < 1e-13, "{v}");
        }
        // Moved out by d, its nodal areas gain the hoop stretch w_j d / r.
        let tolerances = Tolerances {
            search_radius: SearchRadius::Distance(0.8),
            ..Tolerances::default()
        };
        let interface = Interface::with_tolerances(s, m, tolerances).unwrap();
        let options = CouplingOptions::default().dual().with_geometry(rz);
        let coupling = assemble_coupling(&interface, &options).unwrap();
        let rows = coupling.slave_nodes.len();
        let body_nodes: Vec<u32> = (0..rows as u32).collect();
        let measures =
            slave_surface_measures(&interface, &coupling, rz, &body_nodes, 2, Some(1)).unwrap();
        let d = 1e-3;
        // Out by d, and stretched along the axis (z = y here), which is not counted.
        let coords = interface.slave().coords();
        let tags = interface.slave().node_tags();
        let mut u = vec![0.0; 2 * rows];
        for (i, x) in coords.iter().enumerate() {
            let j = coupling
                .slave_nodes
                .iter()
                .position(|&t| t == tags[i])
                .unwrap();
            u[2 * j] = d;
            u[2 * j + 1] = 0.01 * x.y;
        }
        for (j, row) in measures.area_change.outer_iterator().enumerate() {
            let w: f64 = coupling
                .d
                .outer_view(j)
                .unwrap()
                .iter()
                .map(|(_, v)| v)
                .sum();
            let du: f64 = row.iter().map(|(k, v)| v * u[k]).sum();
            assert!((du - w * d / 3.0).abs() < 1e-14 * w, "{du} {}", w * d / 3.0);
        }
        let square = |z: f64, n: usize, first: u64, up: bool| {
            let mut s = SurfaceMesh::new();
            for i in 0..=n {
                for j in 0..=n {
                    let tag = first + (i * (n + 1) + j) as u64;
                    s.add_node(tag, [i as f64 / n as f64, j as f64 / n as f64, z])
                        .unwrap();
                }
            }
            for i in 0..n {
                for j in 0..n {
                    let t = |a: usize, b: usize| first + (a * (n + 1) + b) as u64;
                    let q = [t(i, j), t(i + 1, j), t(i + 1, j + 1), t(i, j + 1)];
                    let nodes = if up { q } else { [q[0], q[3], q[2], q[1]] };
                    s.add_face(&QUAD4, &nodes).unwrap();
                }
            }
            s
        };
        let (s, m) = (square(0.0, 3, 1, true), square(0.1, 4, 100, false));
        let c = ModelGeometry::Cartesian;
        for v in curvature(s, m, c, 0.1) {
            assert!(v.abs() < 1e-13, "{v}");
        }
    }
}
