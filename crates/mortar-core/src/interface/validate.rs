//! Checks of the faces of an interface, and the averaged nodal normals.

use nalgebra::{Vector2, Vector3};

use super::SpatialDim;
use crate::element::{ReferenceDomain, MAX_FACE_NODES};
use crate::error::{FaceLocation, Inversion, MortarError, RangeLimit, Result, Side};
use crate::geometry::stable_norm;
use crate::mesh::orient::{consistent_flips, EdgeNeighbours};
use crate::mesh::SurfaceMesh;
use crate::tolerances::{Tolerances, MAX_COORDINATE, MIN_EXTENT};

/// The coordinates must be within what double precision carries through the coupling:
/// magnitudes up to [`MAX_COORDINATE`] (products of two below 1e300) and an interface at least
/// [`MIN_EXTENT`] across (areas of its non-degenerate faces above 1e-300). An interface whose
/// nodes all coincide is left to [`check_faces`] (degenerate faces).
pub(super) fn check_range(slave: &SurfaceMesh, master: &SurfaceMesh) -> Result<()> {
    let (lo, hi) = match (slave.bounding_box(), master.bounding_box()) {
        (Some((a, b)), Some((c, d))) => (a.inf(&c), b.sup(&d)),
        (Some(x), None) | (None, Some(x)) => x,
        (None, None) => return Ok(()),
    };
    let largest = lo.abs().max().max(hi.abs().max());
    // Sides, not the diagonal: no squares, so no overflow before the test.
    let extent = (hi - lo).amax();
    let refuse = |limit: RangeLimit, reason: String| MortarError::CoordinateRange {
        largest,
        extent,
        limit,
        reason,
    };
    let power = |x: f64| (2.0 * x.log10()).round();
    let supported = format!(
        "coordinates up to {MAX_COORDINATE:e} in magnitude, on an interface at least \
         {MIN_EXTENT:e} across, are supported: rescale the meshes (change their units)"
    );
    if largest > MAX_COORDINATE {
        return Err(refuse(
            RangeLimit::Overflow,
            format!(
                "products of two (areas, the entries of D and M) of about 1e{} would overflow \
             double precision; {supported}",
                power(largest)
            ),
        ));
    }
    if extent > 0.0 && extent < MIN_EXTENT {
        return Err(refuse(
            RangeLimit::Underflow,
            format!(
                "products of two of its lengths (areas, the entries of D and M) of about 1e{} \
             would underflow double precision; {supported}",
                power(extent)
            ),
        ));
    }
    Ok(())
}

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
                let dim = |d: usize| {
                    if d == 1 {
                        SpatialDim::Two
                    } else {
                        SpatialDim::Three
                    }
                };
                return Err(MortarError::DimensionMismatch {
                    expected: dim(first),
                    found: dim(view.element.domain().dim()),
                    what: format!(
                        "{side} face {} is a {} but slave face {} is a {}: an interface is all lines (2D) or all faces (3D)",
                        view.tag,
                        view.element.name(),
                        slave.face(0).tag,
                        slave.face(0).element.name()
                    ),
                });
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
                return Err(MortarError::DimensionMismatch {
                    expected: SpatialDim::Two,
                    found: SpatialDim::Three,
                    what: format!(
                        "{side} node {} has z = {:e}: line elements make a 2D problem in the plane z = 0",
                        mesh.node_tags()[i],
                        x.z
                    ),
                });
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
        faces: Box::new([mesh.face(first).tag, mesh.face(f).tag]),
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
                diameter = diameter.max(stable_norm(&(nodes[i] - nodes[j])));
            }
        }
        if diameter <= tol.degenerate * scale {
            return Err(degenerate(format!(
                "its size {diameter:e} is negligible against the interface size {scale:e}"
            )));
        }
        if el.domain() == ReferenceDomain::Line {
            // A curved line (Line3 and higher) must run one way from end to end: its tangent
            // at every node along its tangent at the centre (a middle node outside its ends
            // folds it back).
            if el.node_count() > corners {
                let tangent =
                    |xi: &[f64; 2]| el.tangents(&nodes, &Vector2::new(xi[0], xi[1]))[0] / diameter;
                let centre = tangent(&[0.0, 0.0]);
                for (i, xi) in el.node_reference_coords().iter().enumerate() {
                    if tangent(xi).dot(&centre) <= tol.degenerate {
                        return Err(MortarError::InvertedFace {
                            face: loc,
                            kind: Inversion::SelfIntersecting,
                            reason: format!(
                                "its tangent vanishes or turns back at node {} (a middle node \
                                 outside its ends, or far off their middle)",
                                mesh.node_tags()[view.nodes[i] as usize]
                            ),
                        });
                    }
                }
            }
            continue;
        }
        // Scaled normals are products of two lengths and their dot products of four: they are
        // compared in units of the face's size squared, so that no scale (1e-100, 1e100)
        // underflows or overflows them.
        let area_scale = diameter * diameter;
        // Jacobians at the nodes: a sign change between two of them means the face folds over
        // itself (a bow-tie), whatever its centre looks like.
        let node_normals: Vec<Vector3<f64>> = el
            .node_reference_coords()
            .iter()
            .map(|xi| el.scaled_normal(&nodes, &Vector2::new(xi[0], xi[1])) / area_scale)
            .collect();
        for (a, na) in node_normals.iter().enumerate() {
            for (b, nb) in node_normals.iter().enumerate().skip(a + 1) {
                if na.dot(nb) < -tol.degenerate.powi(2) {
                    return Err(MortarError::InvertedFace {
                        face: loc,
                        kind: Inversion::SelfIntersecting,
                        reason: format!(
                            "its Jacobian changes sign between nodes {} and {} (self-intersecting or non-convex)",
                            mesh.node_tags()[view.nodes[a] as usize],
                            mesh.node_tags()[view.nodes[b] as usize]
                        ),
                    });
                }
            }
        }
        let centre = el.scaled_normal(&nodes, &el.domain().centre()) / area_scale;
        if centre.norm() * el.domain().measure() <= tol.degenerate {
            return Err(degenerate(format!(
                "its area is negligible against its size {diameter:e} squared (collinear corners)"
            )));
        }
        for (c, n) in node_normals.iter().enumerate() {
            if n.dot(&centre) <= tol.degenerate * centre.norm() {
                return Err(MortarError::InvertedFace {
                    face: loc,
                    kind: Inversion::SelfIntersecting,
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

/// Every face must agree in orientation with its neighbours, by connectivity alone: two faces
/// sharing an edge must traverse it in opposite directions (two lines sharing a node: one
/// ends where the other starts), whatever the angle between them. In each connected piece the
/// faces at odds with the majority are the inverted ones; the first of them (in face order) is
/// named, with an edge and a neighbour it disagrees with.
///
/// # Errors
/// [`MortarError::Topology`] for an edge shared by more than two faces (a fin) or a node by
/// more than two lines (a T junction), and for a one-sided piece (a Moebius strip);
/// [`MortarError::InvertedFace`] for a face oriented against its neighbours.
pub(super) fn check_orientation(mesh: &SurfaceMesh, side: Side) -> Result<()> {
    let neighbours = EdgeNeighbours::build(mesh, Some(side))?;
    let (pieces, flips) = consistent_flips(mesh, Some(side), &neighbours)?;
    let count = pieces.iter().map(|&p| p as usize + 1).max().unwrap_or(0);
    let mut flipped = vec![0usize; count];
    let mut size = vec![0usize; count];
    for (&p, &flip) in pieces.iter().zip(&flips) {
        size[p as usize] += 1;
        flipped[p as usize] += usize::from(flip);
    }
    // A tie keeps the sense of the piece's first face.
    let majority = |p: u32| 2 * flipped[p as usize] > size[p as usize];
    let Some(f) = (0..mesh.face_count()).find(|&f| flips[f] != majority(pieces[f])) else {
        return Ok(());
    };
    // A face at odds with its piece has a neighbour (a piece of one face agrees with itself);
    // one that agrees with the majority, where there is one, is named.
    let all = neighbours.of(f);
    let nb = all
        .iter()
        .find(|nb| flips[nb.face as usize] == majority(pieces[f]))
        .or(all.first());
    let how = if let Some(nb) = nb {
        let other = mesh.face(nb.face as usize).tag;
        let (a, b) = nb.edge;
        how_against(mesh, f, a, b, other)
    } else {
        "its node order is reversed".to_string()
    };
    Err(MortarError::InvertedFace {
        face: FaceLocation {
            side: Some(side),
            tag: mesh.face(f).tag,
        },
        kind: Inversion::AgainstNeighbours,
        reason: format!(
            "it is oriented against its neighbours: {how}; check the node order of the faces \
             around it"
        ),
    })
}

/// How face `f` disagrees with face `other` (tag) across their shared edge `(a, b)` (node
/// indices; a line's shared node twice).
fn how_against(mesh: &SurfaceMesh, f: usize, a: u32, b: u32, other: u64) -> String {
    let tags = mesh.node_tags();
    if a == b {
        let starts = mesh.face(f).nodes[0] == a;
        format!(
            "it {} at node {} as line {other} does (a chain of lines runs one way: each line \
             starts where the previous one ends)",
            if starts { "starts" } else { "ends" },
            tags[a as usize]
        )
    } else {
        format!(
            "it runs along the edge between nodes {} and {} in the same direction as face \
             {other} (neighbouring faces run along their shared edge in opposite directions)",
            tags[a as usize], tags[b as usize]
        )
    }
}

/// Averaged unit nodal normals: the sum of the unit normals of the faces at each node,
/// normalised. The faces' orientation is checked by [`check_orientation`] (connectivity,
/// not angles); here only a node where the normals cancel (the surface folds back onto
/// itself, the averaged normal is undefined) is refused.
///
/// # Errors
/// [`MortarError::InvertedFace`] naming a face at such a node.
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
    // Unit normals: the cancellation test is independent of the scale.
    let cancelled = |node: usize| sum[node].norm() <= 1e-8 * count[node] as f64;
    let at = |node: usize| {
        (0..mesh.face_count()).filter(move |&f| mesh.face(f).nodes.contains(&(node as u32)))
    };
    if let Some((node, first)) = (0..mesh.node_count())
        .filter(|&n| count[n] > 0 && cancelled(n))
        .find_map(|n| at(n).next().map(|f| (n, f)))
    {
        let faces: Vec<String> = at(node).map(|f| mesh.face(f).tag.to_string()).collect();
        return Err(MortarError::InvertedFace {
            face: FaceLocation {
                side: Some(side),
                tag: mesh.face(first).tag,
            },
            kind: Inversion::FoldsBack,
            reason: format!(
                "the surface folds back onto itself at node {}: the normals of faces {} cancel, \
                 so the averaged normal there is undefined",
                mesh.node_tags()[node],
                faces.join(", ")
            ),
        });
    }
    Ok(sum
        .into_iter()
        .map(|s| s.try_normalize(0.0).unwrap_or_default())
        .collect())
}
