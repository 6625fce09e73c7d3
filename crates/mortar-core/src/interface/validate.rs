//! Checks of the faces of an interface, and the averaged nodal normals.

use nalgebra::{Vector2, Vector3};

use super::SpatialDim;
use crate::element::{ReferenceDomain, MAX_FACE_NODES};
use crate::error::{FaceLocation, MortarError, Result, Side};
use crate::mesh::SurfaceMesh;
use crate::tolerances::Tolerances;

/// All faces of both sides must share one reference dimension; lines make a 2D problem whose
/// nodes must lie in the plane `z = 0`.
pub(super) fn check_dimension(
    slave: &SurfaceMesh,
    master: &SurfaceMesh,
    tol: &Tolerances,
) -> Result<SpatialDim> {
    let first = slave.face(0).element.domain().dim();
    for (mesh, side) in [(slave, Side::Slave), (master, Side::Master)] {
        for f in 0..mesh.face_count() {
            let view = mesh.face(f);
            if view.element.domain().dim() != first {
                return Err(MortarError::DimensionMismatch(format!(
                    "{side} face {} is a {} but slave face {} is a {}: an interface is all lines (2D) or all faces (3D)",
                    view.tag,
                    view.element.name(),
                    slave.face(0).tag,
                    slave.face(0).element.name()
                )));
            }
        }
    }
    if first == 2 {
        return Ok(SpatialDim::Three);
    }
    for (mesh, side) in [(slave, Side::Slave), (master, Side::Master)] {
        let Some((lo, hi)) = mesh.bounding_box() else {
            continue;
        };
        let scale = (hi - lo).norm().max(lo.abs().max().max(hi.abs().max()));
        for (i, x) in mesh.coords().iter().enumerate() {
            if x.z.abs() > tol.degenerate * scale.max(f64::MIN_POSITIVE) {
                return Err(MortarError::DimensionMismatch(format!(
                    "{side} node {} has z = {:e}: line elements make a 2D problem in the plane z = 0",
                    mesh.node_tags()[i],
                    x.z
                )));
            }
        }
    }
    Ok(SpatialDim::Two)
}

/// Faces given twice (the same nodes, whatever their order): their area would count twice.
/// The first repeat (in face order) is a [`MortarError::Topology`] naming both faces and the
/// nodes. Faces are keyed by a hash of their sorted nodes, sorted (in parallel), and faces of
/// equal keys compared node by node: no allocation per face.
pub(super) fn check_duplicates(mesh: &SurfaceMesh, side: Side) -> Result<()> {
    use rayon::prelude::*;
    use std::hash::{Hash, Hasher};
    let sorted = |f: usize| {
        let nodes = mesh.face(f).nodes;
        let mut key = [u32::MAX; MAX_FACE_NODES];
        key[..nodes.len()].copy_from_slice(nodes);
        key[..nodes.len()].sort_unstable();
        key
    };
    let mut keys: Vec<(u64, u32)> = (0..mesh.face_count())
        .into_par_iter()
        .map(|f| {
            // A fixed hasher: the same keys, hence the same report, on every run.
            let mut h = std::collections::hash_map::DefaultHasher::new();
            sorted(f).hash(&mut h);
            (h.finish(), f as u32)
        })
        .collect();
    keys.par_sort_unstable();
    let mut repeat: Option<(usize, usize)> = None;
    for run in keys.chunk_by(|a, b| a.0 == b.0).filter(|r| r.len() > 1) {
        for (i, &(_, a)) in run.iter().enumerate() {
            for &(_, b) in &run[i + 1..] {
                let (a, b) = (a.min(b) as usize, a.max(b) as usize);
                if sorted(a) == sorted(b) && repeat.is_none_or(|(_, r)| b < r) {
                    repeat = Some((a, b));
                }
            }
        }
    }
    let Some((first, f)) = repeat else {
        return Ok(());
    };
    let tags: Vec<u64> = mesh
        .face(f)
        .nodes
        .iter()
        .map(|&n| mesh.node_tags()[n as usize])
        .collect();
    Err(MortarError::Topology {
        face: FaceLocation {
            side: Some(side),
            tag: mesh.face(f).tag,
        },
        reason: format!(
            "{side} faces {} and {} have the same nodes {tags:?}: a duplicated face (its area \
             would count twice); remove one",
            mesh.face(first).tag,
            mesh.face(f).tag
        ),
    })
}

/// Degenerate faces (repeated nodes, zero length or area) and inverted ones (a Jacobian that
/// changes sign over the face: folded, self-intersecting or non-convex quadrilaterals).
pub(super) fn check_faces(
    mesh: &SurfaceMesh,
    side: Side,
    scale: f64,
    tol: &Tolerances,
) -> Result<()> {
    for f in 0..mesh.face_count() {
        let view = mesh.face(f);
        let loc = FaceLocation {
            side: Some(side),
            tag: view.tag,
        };
        let degenerate = |reason: String| MortarError::DegenerateFace { face: loc, reason };
        for (i, a) in view.nodes.iter().enumerate() {
            if view.nodes[i + 1..].contains(a) {
                return Err(degenerate(format!(
                    "node {} appears twice",
                    mesh.node_tags()[*a as usize]
                )));
            }
        }
        let el = view.element;
        let nodes = face_coords(mesh, view.nodes);
        let corners = el.corner_count();
        let mut diameter: f64 = 0.0;
        for i in 0..corners {
            for j in i + 1..corners {
                diameter = diameter.max((nodes[i] - nodes[j]).norm());
            }
        }
        if diameter <= tol.degenerate * scale {
            return Err(degenerate(format!(
                "its size {diameter:e} is negligible against the interface size {scale:e}"
            )));
        }
        if el.domain() == ReferenceDomain::Line {
            continue;
        }
        let area_scale = diameter * diameter;
        // Jacobians at the nodes: a sign change between two of them means the face folds over
        // itself (a bow-tie), whatever its centre looks like.
        let node_normals: Vec<Vector3<f64>> = el
            .node_reference_coords()
            .iter()
            .map(|xi| el.scaled_normal(&nodes, &Vector2::new(xi[0], xi[1])))
            .collect();
        for (a, na) in node_normals.iter().enumerate() {
            for (b, nb) in node_normals.iter().enumerate().skip(a + 1) {
                if na.dot(nb) < -(tol.degenerate * area_scale).powi(2) {
                    return Err(MortarError::InvertedFace {
                        face: loc,
                        reason: format!(
                            "its Jacobian changes sign between nodes {} and {} (self-intersecting or non-convex)",
                            mesh.node_tags()[view.nodes[a] as usize],
                            mesh.node_tags()[view.nodes[b] as usize]
                        ),
                    });
                }
            }
        }
        let centre = el.scaled_normal(&nodes, &el.domain().centre());
        if centre.norm() * el.domain().measure() <= tol.degenerate * area_scale {
            return Err(degenerate(format!(
                "its area is negligible against its size {diameter:e} squared (collinear corners)"
            )));
        }
        for (c, n) in node_normals.iter().enumerate() {
            if n.dot(&centre) <= tol.degenerate * area_scale * centre.norm() {
                return Err(MortarError::InvertedFace {
                    face: loc,
                    reason: format!(
                        "its Jacobian vanishes or changes sign at node {} (self-intersecting or non-convex)",
                        mesh.node_tags()[view.nodes[c] as usize]
                    ),
                });
            }
        }
    }
    Ok(())
}

/// The coordinates of a face's nodes.
fn face_coords(mesh: &SurfaceMesh, nodes: &[u32]) -> Vec<Vector3<f64>> {
    nodes.iter().map(|&n| mesh.coords()[n as usize]).collect()
}

/// Averaged unit nodal normals (sum of the faces' unit normals at the node, normalised), and
/// the check that every face agrees in orientation with its neighbours.
pub(super) fn nodal_normals(mesh: &SurfaceMesh, side: Side) -> Result<Vec<Vector3<f64>>> {
    let mut sum = vec![Vector3::zeros(); mesh.node_count()];
    let mut count = vec![0u32; mesh.node_count()];
    for f in 0..mesh.face_count() {
        let view = mesh.face(f);
        let nodes = face_coords(mesh, view.nodes);
        for (i, xi) in view.element.node_reference_coords().iter().enumerate() {
            let n = view
                .element
                .unit_normal(&nodes, &Vector2::new(xi[0], xi[1]));
            sum[view.nodes[i] as usize] += n;
            count[view.nodes[i] as usize] += 1;
        }
    }
    for f in 0..mesh.face_count() {
        let view = mesh.face(f);
        let nodes = face_coords(mesh, view.nodes);
        for (i, xi) in view.element.node_reference_coords().iter().enumerate() {
            let node = view.nodes[i] as usize;
            let n = view
                .element
                .unit_normal(&nodes, &Vector2::new(xi[0], xi[1]));
            // A face whose normal does not point to the side of the average (sum) is folded
            // back on its neighbours, or numbered the other way round.
            if n.dot(&sum[node]) <= 1e-8 * count[node] as f64 {
                return Err(MortarError::InvertedFace {
                    face: FaceLocation {
                        side: Some(side),
                        tag: view.tag,
                    },
                    reason: format!(
                        "it is oriented against its neighbours at node {} (check the node order of the faces around it)",
                        mesh.node_tags()[node]
                    ),
                });
            }
        }
    }
    Ok(sum
        .into_iter()
        .map(|s| s.try_normalize(0.0).unwrap_or_default())
        .collect())
}
