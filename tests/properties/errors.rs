//! Typed errors on bad input, each naming where it is: non-finite coordinates, degenerate and
//! inverted faces, faces oriented against their neighbours, no overlap, mixed dimensions, and
//! invalid options.

use std::collections::HashMap;

use mortar::core::error::{FaceLocation, Inversion};
use mortar::elements::{LINE2, QUAD4, TRI3};
use mortar::generate::{line_mesh, square_quads, square_triangles, Diagonal};
use mortar::testing::{cell_kind, perturbed_square, CellKind, MAX_SQUARE_JITTER};
use mortar::{
    assemble_coupling, CouplingOptions, Interface, MortarError, Side, SpatialDim, SurfaceMesh,
};
use nalgebra::Vector3;
use proptest::prelude::*;

use super::common::config;

/// A copy of `mesh` with face `face` given the node tags `nodes` (same element and tag).
fn with_face(mesh: &SurfaceMesh, face: usize, nodes: &[u64]) -> SurfaceMesh {
    let mut out = SurfaceMesh::new();
    for (t, x) in mesh.node_tags().iter().zip(mesh.coords()) {
        out.add_node(*t, (*x).into()).unwrap();
    }
    for f in 0..mesh.face_count() {
        let view = mesh.face(f);
        let tags: Vec<u64> = if f == face {
            nodes.to_vec()
        } else {
            view.nodes
                .iter()
                .map(|&n| mesh.node_tags()[n as usize])
                .collect()
        };
        out.add_face_with_tag(view.tag, view.element, &tags)
            .unwrap();
    }
    out
}

fn face_tags(mesh: &SurfaceMesh, face: usize) -> Vec<u64> {
    mesh.face(face)
        .nodes
        .iter()
        .map(|&n| mesh.node_tags()[n as usize])
        .collect()
}

/// A master that covers the unit square.
fn master() -> SurfaceMesh {
    square_triangles(3, Diagonal::Anti, 0.0, true, 1).unwrap()
}

fn slave_face(tag: u64) -> FaceLocation {
    FaceLocation {
        side: Some(Side::Slave),
        tag,
    }
}

/// Faces all of whose nodes are shared by at least three faces: reversing one of them leaves
/// its neighbours a majority at every one of its nodes.
fn interior_faces(mesh: &SurfaceMesh) -> Vec<usize> {
    let mut valence: HashMap<u32, usize> = HashMap::new();
    for f in 0..mesh.face_count() {
        for &n in mesh.face(f).nodes {
            *valence.entry(n).or_insert(0) += 1;
        }
    }
    (0..mesh.face_count())
        .filter(|&f| mesh.face(f).nodes.iter().all(|n| valence[n] >= 3))
        .collect()
}

proptest! {
    #![proptest_config(config(32))]

    /// A NaN or infinite coordinate is refused when the node is added, and when a transform
    /// produces it; the error names the node.
    #[test]
    fn non_finite_coordinates_are_refused(
        mesh in (cell_kind(), 1..=4usize).prop_flat_map(|(k, n)| perturbed_square(k, n..=n, MAX_SQUARE_JITTER, false)),
        node in any::<prop::sample::Index>(),
        component in 0..3usize,
        bad in prop::sample::select(vec![f64::NAN, f64::INFINITY, f64::NEG_INFINITY]),
    ) {
        let i = node.index(mesh.node_count());
        let tag = mesh.node_tags()[i];
        let mut x: [f64; 3] = mesh.coords()[i].into();
        x[component] = bad;
        let mut copy = SurfaceMesh::new();
        let err = copy.add_node(tag, x).unwrap_err();
        prop_assert!(
            matches!(err, MortarError::NonFiniteCoordinate { tag: t, .. } if t == tag),
            "{:?}", err
        );
        prop_assert!(err.to_string().contains(&format!("node {tag}")), "{err}");

        let mut moved = mesh.clone();
        let target = mesh.coords()[i];
        let err = moved
            .transform(|p| if p == target { Vector3::from(x) } else { p })
            .unwrap_err();
        prop_assert!(
            matches!(err, MortarError::NonFiniteCoordinate { tag: t, .. } if t == tag),
            "{:?}", err
        );
        prop_assert_eq!(moved.coords(), mesh.coords());
    }

    /// A triangle on three collinear nodes (along the bottom edge of the square).
    #[test]
    fn zero_area_triangle_is_degenerate(
        mesh in (cell_kind(), 2..=5usize).prop_flat_map(|(k, n)| perturbed_square(k, n..=n, MAX_SQUARE_JITTER, false)),
        start in 0..3usize,
    ) {
        let mut mesh = mesh;
        // Bottom-edge nodes have tags 1..=n+1 and y = 0 exactly.
        let t = [1u64, 2, 3];
        let tri = [t[start], t[(start + 1) % 3], t[(start + 2) % 3]];
        let tag = mesh.face_count() as u64 + 1;
        mesh.add_face(&TRI3, &tri).unwrap();
        let err = Interface::new(mesh, master()).unwrap_err();
        prop_assert!(
            matches!(err, MortarError::DegenerateFace { face, .. } if face == slave_face(tag)),
            "{err:?}"
        );
        prop_assert!(err.to_string().contains(&format!("face {tag}")), "{err}");
    }

    /// A quad whose corners are taken in bow-tie order `[a, c, b, d]`: self-intersecting.
    /// With one cell per side (corners fixed) the bow-tie is symmetric.
    #[test]
    fn bow_tie_quad_is_inverted(
        mesh in (1..=4usize).prop_flat_map(|n| perturbed_square(CellKind::Quads, n..=n, MAX_SQUARE_JITTER, false)),
        face in any::<prop::sample::Index>(),
    ) {
        let f = face.index(mesh.face_count());
        let q = face_tags(&mesh, f);
        let tag = mesh.face(f).tag;
        let bad = with_face(&mesh, f, &[q[0], q[2], q[1], q[3]]);
        let err = Interface::new(bad, master()).unwrap_err();
        prop_assert!(
            matches!(err, MortarError::InvertedFace { face, kind: Inversion::SelfIntersecting, .. } if face == slave_face(tag)),
            "{err:?}"
        );
        prop_assert!(err.to_string().contains(&format!("face {tag}")), "{err}");
    }

    /// One face numbered the other way round among neighbours that outnumber it at each of
    /// its nodes: the error names that face.
    #[test]
    fn face_flipped_against_its_neighbours_is_inverted(
        mesh in (cell_kind(), 3..=6usize).prop_flat_map(|(k, n)| perturbed_square(k, n..=n, MAX_SQUARE_JITTER, false)),
        pick in any::<prop::sample::Index>(),
        as_master in any::<bool>(),
    ) {
        let candidates = interior_faces(&mesh);
        prop_assume!(!candidates.is_empty());
        let f = candidates[pick.index(candidates.len())];
        let mut nodes = face_tags(&mesh, f);
        nodes.reverse();
        let tag = mesh.face(f).tag;
        let bad = with_face(&mesh, f, &nodes);
        let (result, side) = if as_master {
            let slave = square_quads(2, 0.0, true, 1).unwrap();
            (Interface::new(slave, bad), Side::Master)
        } else {
            (Interface::new(bad, master()), Side::Slave)
        };
        let err = result.unwrap_err();
        prop_assert!(
            matches!(err, MortarError::InvertedFace { face, kind: Inversion::AgainstNeighbours, .. } if face == FaceLocation { side: Some(side), tag }),
            "{err:?}"
        );
        prop_assert!(err.to_string().contains(&format!("{side} face {tag}")), "{err}");
    }

    /// Two squares side by side with a gap: far apart (no candidate pair) or close enough
    /// that the inflated boxes meet (candidates, but no overlap).
    #[test]
    fn disjoint_squares_have_no_overlap(
        gap in prop_oneof![1e-3..0.1f64, 2.0..10.0f64],
        angle in 0.0..std::f64::consts::TAU,
        kind in cell_kind(),
        n in 1..=4usize,
    ) {
        let slave = square_quads(n, 0.0, false, 1).unwrap();
        let mut master = if kind == CellKind::Quads {
            square_quads(n + 1, 0.0, true, 1).unwrap()
        } else {
            square_triangles(n + 1, Diagonal::Main, 0.0, true, 1).unwrap()
        };
        // Shift the master by (1 + gap) along an axis-aligned direction chosen by `angle`.
        let dir = match (angle / std::f64::consts::FRAC_PI_2) as usize {
            0 => Vector3::x(),
            1 => Vector3::y(),
            2 => -Vector3::x(),
            _ => -Vector3::y(),
        };
        master.transform(|x| x + dir * (1.0 + gap)).unwrap();
        let interface = Interface::new(slave, master).unwrap();
        let err = assemble_coupling(&interface, &CouplingOptions::default()).unwrap_err();
        prop_assert!(matches!(err, MortarError::NoOverlap { .. }), "{err:?}");
        let msg = err.to_string();
        prop_assert!(msg.contains(&format!("{} slave faces", n * n)), "{msg}");
    }
}

#[test]
fn symmetric_bow_tie_quad_is_inverted_not_degenerate() {
    // The unit square's corners in bow-tie order: the two lobes have equal area, so the
    // Jacobian vanishes at the centre; the corners are not collinear.
    let square = square_quads(1, 0.0, false, 1).unwrap();
    let bad = with_face(&square, 0, &[1, 4, 2, 3]);
    let err = Interface::new(bad, master()).unwrap_err();
    assert!(
        matches!(err, MortarError::InvertedFace { face, kind: Inversion::SelfIntersecting, .. } if face == slave_face(1)),
        "a symmetric bow-tie quad should be an InvertedFace, got {err:?}"
    );
}

/// Consistently oriented lines that fold back onto each other (a hairpin: the second line
/// returns along the first): the normals at their shared node cancel, so the averaged normal
/// there is undefined; an inverted-face error naming the node and both lines.
#[test]
fn a_surface_folded_back_onto_itself_is_refused() {
    let mut hairpin = SurfaceMesh::new();
    for (tag, x) in [
        (1, [0.0, 0.0, 0.0]),
        (2, [1.0, 0.0, 0.0]),
        (3, [0.0, 0.0, 0.0]),
    ] {
        hairpin.add_node(tag, x).unwrap();
    }
    hairpin.add_face(&LINE2, &[1, 2]).unwrap();
    hairpin.add_face(&LINE2, &[2, 3]).unwrap();
    let err = Interface::new(hairpin, line_mesh(3, true, 10).unwrap()).unwrap_err();
    assert!(
        matches!(
            err,
            MortarError::InvertedFace {
                kind: Inversion::FoldsBack,
                ..
            }
        ),
        "{err:?}"
    );
    let text = err.to_string();
    assert!(
        text.contains("folds back") && text.contains("node 2") && text.contains("faces 1, 2"),
        "{text}"
    );
}

#[test]
fn repeated_node_is_degenerate() {
    let mut mesh = square_quads(1, 0.0, false, 1).unwrap();
    mesh.add_face(&TRI3, &[1, 2, 2]).unwrap();
    let err = Interface::new(mesh, master()).unwrap_err();
    assert!(
        matches!(err, MortarError::DegenerateFace { face, .. } if face == slave_face(2)),
        "{err:?}"
    );
    assert!(err.to_string().contains("node 2"), "{err}");
}

#[test]
fn lines_against_triangles_is_a_dimension_mismatch() {
    let lines = line_mesh(3, false, 1).unwrap();
    let err = Interface::new(lines.clone(), master()).unwrap_err();
    assert!(
        matches!(
            err,
            MortarError::DimensionMismatch {
                expected: SpatialDim::Two,
                found: SpatialDim::Three,
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("master face 1"), "{err}");

    // One mesh with a line and a triangle.
    let mut mixed = square_triangles(1, Diagonal::Main, 0.0, false, 1).unwrap();
    mixed.add_face(&LINE2, &[1, 2]).unwrap();
    let err = Interface::new(mixed, master()).unwrap_err();
    assert!(
        matches!(
            err,
            MortarError::DimensionMismatch {
                expected: SpatialDim::Three,
                found: SpatialDim::Two,
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("slave face 3"), "{err}");
}

#[test]
fn line_off_the_xy_plane_is_a_dimension_mismatch() {
    let mut lines = line_mesh(3, false, 10).unwrap();
    let master = line_mesh(4, true, 1).unwrap();
    lines
        .transform(|x| {
            if x.x == 1.0 {
                x + Vector3::z() * 0.5
            } else {
                x
            }
        })
        .unwrap();
    let err = Interface::new(lines, master).unwrap_err();
    assert!(
        matches!(
            err,
            MortarError::DimensionMismatch {
                expected: SpatialDim::Two,
                found: SpatialDim::Three,
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("node 13"), "{err}");
}

#[test]
fn mesh_building_errors_name_the_node_or_face() {
    let mut mesh = SurfaceMesh::new();
    mesh.add_node(7, [0.0; 3]).unwrap();
    let err = mesh.add_node(7, [1.0, 0.0, 0.0]).unwrap_err();
    assert_eq!(err, MortarError::DuplicateNode { tag: 7 });
    let err = mesh.add_face(&TRI3, &[7, 8, 9]).unwrap_err();
    assert!(
        matches!(err, MortarError::UnknownNode { node: 8, .. }),
        "{err:?}"
    );
    let err = mesh.add_face_with_tag(42, &QUAD4, &[7, 7, 7]).unwrap_err();
    assert!(
        matches!(
            err,
            MortarError::WrongNodeCount {
                expected: 4,
                got: 3,
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("face 42"), "{err}");
    assert_eq!(mesh.face_count(), 0);
}

/// A refused duplicate node leaves the mesh as it was, in either way of numbering: the
/// first node keeps its tag, and a face built after the refusal uses it. Regression: with
/// tags out of sequence, the refusal replaced the tag's node by the refused one's index, one
/// past the last node, and the face built after it read past the coordinates (a panic).
#[test]
fn a_refused_duplicate_node_changes_nothing() {
    for tags in [[1u64, 2, 3], [5, 1, 9]] {
        let mut mesh = SurfaceMesh::new();
        for (k, &t) in tags.iter().enumerate() {
            mesh.add_node(t, [k as f64, (k * k) as f64, 0.0]).unwrap();
        }
        let err = mesh.add_node(tags[0], [7.0, 7.0, 7.0]).unwrap_err();
        assert_eq!(err, MortarError::DuplicateNode { tag: tags[0] });
        assert_eq!(mesh.node_count(), 3);
        mesh.add_face(&TRI3, &tags).unwrap();
        let face = mesh.face(0);
        let first = mesh.coords()[face.nodes[0] as usize];
        assert_eq!([first.x, first.y, first.z], [0.0; 3], "tags {tags:?}");
    }
}

#[test]
fn empty_surfaces_and_invalid_options_are_refused() {
    let err = Interface::new(SurfaceMesh::new(), master()).unwrap_err();
    assert_eq!(err, MortarError::EmptySurface { side: Side::Slave });
    let err = Interface::new(master(), SurfaceMesh::new()).unwrap_err();
    assert_eq!(err, MortarError::EmptySurface { side: Side::Master });

    for d in [0, 21] {
        for result in [
            CouplingOptions::default().segment_based(Some(d)),
            CouplingOptions::default().element_based(Some(d)),
        ] {
            match result {
                Err(MortarError::InvalidOption { option, value, .. }) => {
                    assert_eq!((option, value), ("quadrature degree", d.to_string()));
                }
                other => panic!("{other:?}"),
            }
        }
    }
    let interface = Interface::new(square_quads(2, 0.0, false, 1).unwrap(), master()).unwrap();
    let err = assemble_coupling(&interface, &CouplingOptions::default().threads(0)).unwrap_err();
    assert!(
        matches!(err, MortarError::InvalidOption { option: "threads", ref value, .. } if value == "0"),
        "{err:?}"
    );
    assert_eq!(err.to_string(), "invalid option: threads 0: at least 1");
}

/// The edges shared by two faces (node indices, lower first) and those faces.
fn interior_edges(mesh: &SurfaceMesh) -> Vec<((u32, u32), [usize; 2])> {
    let mut faces_of: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for f in 0..mesh.face_count() {
        let nodes = mesh.face(f).nodes;
        let k = nodes.len();
        for i in 0..k {
            let (a, b) = (nodes[i], nodes[(i + 1) % k]);
            faces_of.entry((a.min(b), a.max(b))).or_default().push(f);
        }
    }
    let mut out: Vec<_> = faces_of
        .into_iter()
        .filter(|(_, f)| f.len() == 2)
        .map(|(e, f)| (e, [f[0], f[1]]))
        .collect();
    out.sort_unstable();
    out
}

/// `mesh` with face `face` added again, under the tag `tag`, its nodes rotated by `turn`
/// (the same face, another starting node).
fn with_duplicate(mesh: &SurfaceMesh, face: usize, tag: u64, turn: usize) -> SurfaceMesh {
    let mut out = mesh.clone();
    let mut nodes = face_tags(mesh, face);
    let k = nodes.len();
    nodes.rotate_left(turn % k);
    out.add_face_with_tag(tag, mesh.face(face).element, &nodes)
        .unwrap();
    out
}

proptest! {
    #![proptest_config(config(32))]

    /// A face given twice (same nodes, any starting node) would count its area twice (sum(D)
    /// 1.12 for a unit square, exit 0), so it is a topology error
    /// naming both faces, on either side, in 2D and 3D.
    #[test]
    fn a_duplicated_face_is_a_topology_error_naming_both(
        (mesh, as_master) in (cell_kind(), 1..=4usize, any::<bool>()).prop_flat_map(|(k, n, m)| {
            (perturbed_square(k, n..=n, MAX_SQUARE_JITTER, m), Just(m))
        }),
        pick in any::<prop::sample::Index>(),
        turn in 0..4usize,
    ) {
        let f = pick.index(mesh.face_count());
        let (first, extra) = (mesh.face(f).tag, 9_999_999);
        let bad = with_duplicate(&mesh, f, extra, turn);
        let err = if as_master {
            Interface::new(square_quads(2, 0.0, false, 1).unwrap(), bad)
        } else {
            Interface::new(bad, master())
        }
        .unwrap_err();
        prop_assert!(matches!(err, MortarError::Topology { .. }), "{err:?}");
        let text = err.to_string();
        prop_assert!(text.contains(&first.to_string()) && text.contains(&extra.to_string()), "{text}");
        prop_assert!(text.contains("duplicate"), "{text}");
    }

    /// A third face on an interior edge (a fin standing out of the surface, above or below it)
    /// would add its area to the interface's, so it is a topology error naming the three faces, on either side.
    #[test]
    fn a_fin_on_an_interior_edge_is_a_topology_error_naming_its_faces(
        (mesh, as_master) in (cell_kind(), 2..=4usize, any::<bool>()).prop_flat_map(|(k, n, m)| {
            (perturbed_square(k, n..=n, MAX_SQUARE_JITTER, m), Just(m))
        }),
        pick in any::<prop::sample::Index>(),
        height in prop_oneof![-1.0..-0.1f64, 0.1..1.0f64],
    ) {
        let edges = interior_edges(&mesh);
        let ((a, b), faces) = edges[pick.index(edges.len())];
        let mut bad = mesh.clone();
        let (xa, xb) = (mesh.coords()[a as usize], mesh.coords()[b as usize]);
        let apex = 0.5 * (xa + xb) + Vector3::z() * height;
        let (ta, tb) = (mesh.node_tags()[a as usize], mesh.node_tags()[b as usize]);
        bad.add_node(8_888_888, apex.into()).unwrap();
        bad.add_face_with_tag(9_999_999, &TRI3, &[ta, tb, 8_888_888]).unwrap();
        let err = if as_master {
            Interface::new(square_quads(2, 0.0, false, 1).unwrap(), bad)
        } else {
            Interface::new(bad, master())
        }
        .unwrap_err();
        prop_assert!(matches!(err, MortarError::Topology { .. }), "{err:?}");
        let text = err.to_string();
        for f in [mesh.face(faces[0]).tag, mesh.face(faces[1]).tag, 9_999_999] {
            prop_assert!(text.contains(&f.to_string()), "face {f} not named: {text}");
        }
        prop_assert!(text.contains("fin") && text.contains("shared by 3"), "{text}");
        if let MortarError::Topology { faces: named, .. } = &err {
            prop_assert_eq!(named.len(), 3);
        }
    }

    /// A third line at an interior node of a 2D interface (a T junction) is a topology error
    /// naming the three lines.
    #[test]
    fn a_t_junction_of_three_lines_is_a_topology_error_naming_them(
        n in 2..=8usize,
        pick in any::<prop::sample::Index>(),
        up in any::<bool>(),
        outward in any::<bool>(),
    ) {
        let slave = line_mesh(n, false, 1).unwrap();
        // Interior nodes have tags 2..=n; the lines at node t are t - 1 and t.
        let t = 2 + pick.index(n - 1) as u64;
        let mut bad = slave.clone();
        let x = slave.coords()[slave.node_index(t).unwrap() as usize];
        bad.add_node(500, [x.x, if up { 0.3 } else { -0.3 }, 0.0]).unwrap();
        let nodes = if outward { [t, 500] } else { [500, t] };
        bad.add_face_with_tag(777_777, &LINE2, &nodes).unwrap();
        let err = Interface::new(bad, line_mesh(n + 1, true, 1).unwrap()).unwrap_err();
        prop_assert!(matches!(err, MortarError::Topology { .. }), "{err:?}");
        let text = err.to_string();
        for f in [t - 1, t, 777_777] {
            prop_assert!(text.contains(&f.to_string()), "line {f} not named: {text}");
        }
        prop_assert!(text.contains("T junction") && text.contains(&format!("node {t}")), "{text}");
    }

    /// The same in 2D: a line given twice.
    #[test]
    fn a_duplicated_line_is_a_topology_error(n in 2..=8usize, pick in any::<prop::sample::Index>(), turn in 0..2usize) {
        let slave = line_mesh(n, false, 1).unwrap();
        let f = pick.index(slave.face_count());
        let bad = with_duplicate(&slave, f, 777_777, turn);
        let err = Interface::new(bad, line_mesh(n + 1, true, 1).unwrap()).unwrap_err();
        prop_assert!(matches!(err, MortarError::Topology { .. }), "{err:?}");
        prop_assert!(err.to_string().contains("777777"), "{err}");
    }
}
