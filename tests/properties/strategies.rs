//! The strategies themselves: the meshes they draw are valid, cover the unit square (or
//! segment), keep boundary nodes on the boundary and faces convex; motions are rigid;
//! relabelling keeps the geometry.

use std::collections::HashMap;

use mortar::core::element::ReferenceDomain;
use mortar::testing::{
    cell_kind, covered_pair_2d, covered_pair_3d, log_uniform, perturbed_line, perturbed_square,
    relabelled, rigid_motion_2d, rigid_motion_3d, scale_factor, unit_quaternion, CellKind,
    MAX_LINE_JITTER, MAX_SQUARE_JITTER,
};
use mortar::{Interface, SurfaceMesh};
use nalgebra::Vector3;
use proptest::prelude::*;

use super::common::{config, ok, surface_measure};

/// Every face of a planar mesh in z = 0 is convex with positive orientation about `normal_z`
/// (signed area of every corner triangle), and no node leaves the unit square.
fn check_planar(mesh: &SurfaceMesh, normal_z: f64) -> Result<(), TestCaseError> {
    for x in mesh.coords() {
        prop_assert!((0.0..=1.0).contains(&x.x) && (0.0..=1.0).contains(&x.y) && x.z == 0.0);
    }
    for f in 0..mesh.face_count() {
        let face = mesh.face(f);
        let p: Vec<Vector3<f64>> = face
            .nodes
            .iter()
            .map(|&n| mesh.coords()[n as usize])
            .collect();
        let k = p.len();
        for i in 0..k {
            let (a, b, c) = (p[(i + k - 1) % k], p[i], p[(i + 1) % k]);
            let turn = (b - a).cross(&(c - b)).z * normal_z;
            let scale = (b - a).norm() * (c - b).norm();
            prop_assert!(
                turn > 1e-3 * scale,
                "face {} turns by {turn} at corner {i}",
                face.tag
            );
        }
    }
    Ok(())
}

/// Nodes on the boundary of the square lie exactly on it, and the boundary of the mesh (edges
/// used by one face) lies on the square's boundary.
fn check_boundary(mesh: &SurfaceMesh) -> Result<(), TestCaseError> {
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for f in 0..mesh.face_count() {
        let n = mesh.face(f).nodes;
        for i in 0..n.len() {
            let (a, b) = (n[i], n[(i + 1) % n.len()]);
            *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let on_boundary = |x: &Vector3<f64>| x.x == 0.0 || x.x == 1.0 || x.y == 0.0 || x.y == 1.0;
    for (&(a, b), &count) in &edges {
        prop_assert!(count <= 2);
        if count == 1 {
            let (xa, xb) = (mesh.coords()[a as usize], mesh.coords()[b as usize]);
            let same_side = (xa.x == xb.x && (xa.x == 0.0 || xa.x == 1.0))
                || (xa.y == xb.y && (xa.y == 0.0 || xa.y == 1.0));
            prop_assert!(on_boundary(&xa) && on_boundary(&xb) && same_side);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(48))]

    #[test]
    fn perturbed_squares_are_valid_and_cover_the_unit_square(
        (kind, flip, mesh) in (cell_kind(), any::<bool>(), 1..=8usize).prop_flat_map(|(k, f, n)| {
            (Just(k), Just(f), perturbed_square(k, n..=n, MAX_SQUARE_JITTER, f))
        })
    ) {
        let names: Vec<&str> = (0..mesh.face_count()).map(|f| mesh.face(f).element.name()).collect();
        match kind {
            CellKind::Triangles => prop_assert!(names.iter().all(|n| *n == "Tri3")),
            CellKind::Quads => prop_assert!(names.iter().all(|n| *n == "Quad4")),
            CellKind::Mixed => prop_assert!(names.iter().all(|n| *n == "Tri3" || *n == "Quad4")),
        }
        check_planar(&mesh, if flip { -1.0 } else { 1.0 })?;
        check_boundary(&mesh)?;
        prop_assert!((surface_measure(&mesh) - 1.0).abs() < 1e-13);
    }

    #[test]
    fn perturbed_lines_are_ordered_and_cover_the_segment(
        (flip, mesh) in any::<bool>().prop_flat_map(|f| (Just(f), perturbed_line(1..=12, MAX_LINE_JITTER, f)))
    ) {
        let xs: Vec<f64> = mesh.coords().iter().map(|x| x.x).collect();
        prop_assert_eq!(xs[0], 0.0);
        prop_assert_eq!(*xs.last().unwrap(), 1.0);
        prop_assert!(xs.windows(2).all(|w| w[1] > w[0]));
        for f in 0..mesh.face_count() {
            let n = mesh.face(f).nodes;
            let (a, b) = (xs[n[0] as usize], xs[n[1] as usize]);
            prop_assert_eq!(b < a, flip);
        }
        prop_assert!(mesh.face(0).element.domain() == ReferenceDomain::Line);
    }

    #[test]
    fn covered_pairs_make_valid_non_matching_interfaces(
        pair in prop_oneof![covered_pair_3d(), covered_pair_2d()]
    ) {
        let interface = ok(pair.interface())?;
        let _ = interface.dim();
        let (s, m) = (&pair.slave, &pair.master);
        let same = s.node_count() == m.node_count()
            && s.face_count() == m.face_count()
            && s.coords() == m.coords();
        prop_assert!(!same, "slave and master match node for node");
        prop_assert!((surface_measure(s) - 1.0).abs() < 1e-13);
        prop_assert!((surface_measure(m) - 1.0).abs() < 1e-13);
    }

    #[test]
    fn rigid_motions_preserve_distances(
        m3 in rigid_motion_3d(),
        m2 in rigid_motion_2d(),
        a in prop::array::uniform3(-1.0..1.0f64),
        b in prop::array::uniform3(-1.0..1.0f64),
    ) {
        let (a, b) = (Vector3::from(a), Vector3::from(b));
        for m in [m3, m2] {
            let d = (m.apply(a) - m.apply(b)).norm();
            let tol = 1e-14 * (1.0 + m.translation.norm());
            prop_assert!((d - (a - b).norm()).abs() <= tol);
            prop_assert!(m.translation.norm() <= 1e6 * (1.0 + 1e-12));
        }
        prop_assert_eq!(m2.apply(Vector3::new(a.x, a.y, 0.0)).z, 0.0);
    }

    #[test]
    fn quaternions_are_unit_and_scales_in_range(
        q in unit_quaternion(),
        s in scale_factor(),
        l in log_uniform(1e-3, 1e3),
    ) {
        prop_assert!((q.quaternion().norm() - 1.0).abs() < 1e-14);
        prop_assert!((1e-6..=1e6).contains(&s));
        prop_assert!((1e-3..=1e3).contains(&l));
    }

    #[test]
    fn relabelling_keeps_the_geometry(
        r in perturbed_square(CellKind::Mixed, 1..=5, MAX_SQUARE_JITTER, false)
            .prop_flat_map(|m| (Just(m.clone()), relabelled(m)))
    ) {
        let (mesh, relabelled) = r;
        let new = &relabelled.mesh;
        prop_assert_eq!(new.node_count(), mesh.node_count());
        prop_assert_eq!(new.face_count(), mesh.face_count());
        let mut new_tags: Vec<u64> = relabelled.tag_map.values().copied().collect();
        new_tags.sort_unstable();
        new_tags.dedup();
        prop_assert_eq!(new_tags.len(), mesh.node_count());
        for (i, &t) in mesh.node_tags().iter().enumerate() {
            let j = new.node_index(relabelled.tag_map[&t]).unwrap() as usize;
            prop_assert_eq!(new.coords()[j], mesh.coords()[i]);
        }
        // Same faces (by tag), same node sets, same orientation.
        let face_key = |m: &SurfaceMesh, f: usize, map: &dyn Fn(u64) -> u64| {
            let face = m.face(f);
            let tags: Vec<u64> = face.nodes.iter().map(|&n| map(m.node_tags()[n as usize])).collect();
            let p: Vec<Vector3<f64>> = face.nodes.iter().map(|&n| m.coords()[n as usize]).collect();
            let normal = (p[1] - p[0]).cross(&(p[2] - p[1])).z.signum();
            let mut sorted = tags.clone();
            sorted.sort_unstable();
            (face.tag, sorted, normal)
        };
        let mut a: Vec<_> = (0..mesh.face_count())
            .map(|f| face_key(&mesh, f, &|t| relabelled.tag_map[&t]))
            .collect();
        let mut b: Vec<_> = (0..new.face_count()).map(|f| face_key(new, f, &|t| t)).collect();
        a.sort_by(|x, y| x.partial_cmp(y).unwrap());
        b.sort_by(|x, y| x.partial_cmp(y).unwrap());
        prop_assert_eq!(a, b);
        ok(Interface::new(new.clone(), mesh.clone()))?;
    }
}
