//! Unit tests of the volume elements: partition of unity, Kronecker delta, gradients against
//! finite differences, reference measure, outward faces, and boundary extraction of small
//! meshes. One generic check per property, called once per element type (listed by hand).

use mortar_core::element::MAX_FACE_NODES;
use mortar_elements::volume::{HEX20, HEX27, HEX8, QUAD4, QUAD8, QUAD9, TET10, TET4, TRI3, TRI6};
use mortar_fem::element::{CellValues, VolumeDomain, VolumeElementRef};
use mortar_fem::mesh::VolumeMesh;
use mortar_fem::quadrature::VolumeQuadratureRule;
use nalgebra::{Matrix3, Vector2, Vector3};

const ELEMENTS: [VolumeElementRef; 10] = [
    &TRI3, &QUAD4, &TET4, &HEX8, &TRI6, &QUAD8, &QUAD9, &TET10, &HEX20, &HEX27,
];

/// Reference points inside the domain (a fixed, irregular set).
fn sample_points(e: VolumeElementRef) -> Vec<Vector3<f64>> {
    let raw = [
        [0.1, 0.2, 0.3],
        [0.05, 0.6, 0.1],
        [0.3, 0.3, 0.3],
        [0.7, 0.1, 0.05],
        [0.01, 0.02, 0.9],
    ];
    raw.iter()
        .map(|p| {
            let v = Vector3::new(p[0], p[1], p[2]);
            let v = match e.domain().dim() {
                2 => Vector3::new(v.x, v.y, 0.0),
                _ => v,
            };
            match e.domain() {
                // [-1, 1] domains: stretch.
                VolumeDomain::Quadrilateral | VolumeDomain::Hexahedron => v.map(|c| 2.0 * c - 0.9),
                _ => v,
            }
        })
        .map(|v| {
            if e.dim() == 2 {
                Vector3::new(v.x, v.y, 0.0)
            } else {
                v
            }
        })
        .collect()
}

fn check_partition_of_unity(e: VolumeElementRef) {
    let mut n = vec![0.0; e.node_count()];
    for xi in sample_points(e) {
        assert!(e.domain().contains(&xi, 1e-12), "{} point {xi:?}", e.name());
        e.shape_values_into(&xi, &mut n);
        let s: f64 = n.iter().sum();
        assert!((s - 1.0).abs() < 1e-14, "{}: sum {s}", e.name());
        let mut g = vec![[0.0; 3]; e.node_count()];
        e.shape_gradients_into(&xi, &mut g);
        for d in 0..3 {
            let s: f64 = g.iter().map(|g| g[d]).sum();
            assert!(s.abs() < 1e-14, "{}: gradient sum {s}", e.name());
        }
    }
}

fn check_kronecker_delta(e: VolumeElementRef) {
    let mut n = vec![0.0; e.node_count()];
    for (i, x) in e.node_reference_coords().iter().enumerate() {
        e.shape_values_into(&Vector3::from(*x), &mut n);
        for (j, v) in n.iter().enumerate() {
            let want = if i == j { 1.0 } else { 0.0 };
            assert!((v - want).abs() < 1e-15, "{}: N_{j}(x_{i}) = {v}", e.name());
        }
    }
}

fn check_gradients_by_finite_differences(e: VolumeElementRef) {
    let k = e.node_count();
    let (mut g, mut np, mut nm) = (vec![[0.0; 3]; k], vec![0.0; k], vec![0.0; k]);
    let h = 1e-6;
    for xi in sample_points(e) {
        e.shape_gradients_into(&xi, &mut g);
        for d in 0..3 {
            let mut step = Vector3::zeros();
            step[d] = h;
            e.shape_values_into(&(xi + step), &mut np);
            e.shape_values_into(&(xi - step), &mut nm);
            for a in 0..k {
                let fd = if d < e.dim() {
                    (np[a] - nm[a]) / (2.0 * h)
                } else {
                    0.0
                };
                assert!(
                    (fd - g[a][d]).abs() < 1e-9,
                    "{}: dN_{a}/dxi_{d} = {} vs {fd}",
                    e.name(),
                    g[a][d]
                );
            }
        }
    }
}

/// An affine map with positive determinant: the quadrature of 1 over the image is
/// det(A) times the reference measure; the physical gradients of the linear field
/// u = b . x are b.
fn check_reference_volume_and_physical_gradients(e: VolumeElementRef) {
    let a = if e.dim() == 2 {
        Matrix3::new(1.5, 0.3, 0.0, -0.2, 0.8, 0.0, 0.0, 0.0, 1.0)
    } else {
        Matrix3::new(1.5, 0.3, 0.1, -0.2, 0.8, 0.2, 0.1, -0.3, 1.2)
    };
    let shift = Vector3::new(0.4, -1.0, if e.dim() == 2 { 0.0 } else { 2.0 });
    let nodes: Vec<Vector3<f64>> = e
        .node_reference_coords()
        .iter()
        .map(|x| a * Vector3::from(*x) + shift)
        .collect();
    let rule = VolumeQuadratureRule::cached(e.domain(), 2).unwrap();
    let wsum: f64 = rule.weights().iter().sum();
    assert!((wsum - e.domain().measure()).abs() < 1e-13, "{}", e.name());
    let mut cv = CellValues::new();
    cv.reinit(e, rule, &nodes).unwrap();
    let vol: f64 = (0..cv.len()).map(|q| cv.jxw(q)).sum();
    let want = a.determinant() * e.domain().measure();
    assert!(
        (vol - want).abs() < 1e-13 * want,
        "{}: {vol} vs {want}",
        e.name()
    );
    let b = Vector3::new(0.7, -1.3, if e.dim() == 2 { 0.0 } else { 2.1 });
    let u: Vec<f64> = nodes.iter().map(|x| 3.0 + b.dot(x)).collect();
    for q in 0..cv.len() {
        assert!((cv.gradient(q, &u) - b).norm() < 1e-12, "{}", e.name());
        let x = cv.point(q);
        assert!((cv.value(q, &u) - (3.0 + b.dot(&x))).abs() < 1e-12);
    }
    // The mirror image of the cell (x -> -x, same node order) is inverted everywhere.
    let bad: Vec<Vector3<f64>> = nodes.iter().map(|p| Vector3::new(-p.x, p.y, p.z)).collect();
    assert!(cv.reinit(e, rule, &bad).is_err(), "{}", e.name());
}

/// Each face's nodes lie on one boundary facet of the reference domain and its normal (of
/// the face's surface element, mapped by the reference coordinates) points away from the
/// reference centre.
fn check_faces_point_outwards(e: VolumeElementRef) {
    let coords = e.node_reference_coords();
    let centre = e.domain().centre();
    for (f, local) in e.faces().iter().enumerate() {
        let fe = e.face_element(f);
        assert_eq!(fe.node_count(), local.len(), "{} face {f}", e.name());
        let nodes: Vec<Vector3<f64>> = local.iter().map(|&i| Vector3::from(coords[i])).collect();
        let mut buf = [Vector3::zeros(); MAX_FACE_NODES];
        buf[..nodes.len()].copy_from_slice(&nodes);
        let mid = fe.domain().centre();
        let n = fe.unit_normal(&buf[..nodes.len()], &Vector2::new(mid.x, mid.y));
        let fc = nodes.iter().sum::<Vector3<f64>>() / nodes.len() as f64;
        let out = fc - centre;
        assert!(n.norm() > 0.99, "{} face {f} degenerate", e.name());
        assert!(
            n.dot(&out) > 0.0,
            "{} face {f}: normal {n:?} points inwards",
            e.name()
        );
    }
}

/// Each face's nodes are where the face's linear element (Line2, Tri3, Quad4) of its corners
/// puts them, in the reference coordinates of the cell: the middle nodes of a face are the
/// middles of its own edges (and the centre its centre), in the face element's node order.
fn check_face_nodes_follow_their_corners(e: VolumeElementRef) {
    let coords = e.node_reference_coords();
    for (f, local) in e.faces().iter().enumerate() {
        let fe = e.face_element(f);
        let c = fe.corner_count();
        let linear: &dyn mortar_core::element::SurfaceElement = match c {
            2 => &mortar_elements::LINE2,
            3 => &mortar_elements::TRI3,
            _ => &mortar_elements::QUAD4,
        };
        let corners: Vec<Vector3<f64>> = local[..c]
            .iter()
            .map(|&i| Vector3::from(coords[i]))
            .collect();
        for (j, r) in fe.node_reference_coords().iter().enumerate() {
            let want = linear.map(&corners, &Vector2::new(r[0], r[1]));
            let got = Vector3::from(coords[local[j]]);
            assert!(
                (want - got).norm() < 1e-15,
                "{} face {f} node {j} (cell node {}): at {got:?}, its corners put it at {want:?}",
                e.name(),
                local[j]
            );
        }
    }
}

/// Quadratic completeness of the second-order cells: `sum_i N_i(xi) m(xi_i) = m(xi)` for the
/// quadratic monomials `m` of the reference coordinates.
fn check_quadratic_completeness(e: VolumeElementRef) {
    if matches!(e.name(), "Tri3" | "Quad4" | "Tet4" | "Hex8") {
        return;
    }
    let coords = e.node_reference_coords();
    let mut n = vec![0.0; e.node_count()];
    for xi in sample_points(e) {
        e.shape_values_into(&xi, &mut n);
        for a in 0..e.dim() {
            for b in a..e.dim() {
                let m = |p: &[f64; 3]| p[a] * p[b];
                let sum: f64 = coords.iter().zip(&n).map(|(x, v)| m(x) * v).sum();
                let want = xi[a] * xi[b];
                assert!((sum - want).abs() < 1e-14, "{}: {sum} vs {want}", e.name());
            }
        }
    }
}

#[test]
fn face_nodes_follow_their_corners() {
    for e in ELEMENTS {
        check_face_nodes_follow_their_corners(e);
    }
}

#[test]
fn quadratic_completeness() {
    for e in ELEMENTS {
        check_quadratic_completeness(e);
    }
}

#[test]
fn partition_of_unity() {
    for e in ELEMENTS {
        check_partition_of_unity(e);
    }
}

#[test]
fn kronecker_delta() {
    for e in ELEMENTS {
        check_kronecker_delta(e);
    }
}

#[test]
fn gradients_match_finite_differences() {
    for e in ELEMENTS {
        check_gradients_by_finite_differences(e);
    }
}

#[test]
fn reference_volume_and_physical_gradients() {
    for e in ELEMENTS {
        check_reference_volume_and_physical_gradients(e);
    }
}

#[test]
fn faces_point_outwards() {
    for e in ELEMENTS {
        check_faces_point_outwards(e);
    }
}

/// `int x^e0 y^e1 z^e2` by the rule.
fn monomial_integral(rule: &VolumeQuadratureRule, e: [u32; 3]) -> f64 {
    rule.points()
        .iter()
        .zip(rule.weights())
        .map(|(p, w)| w * p.x.powi(e[0] as i32) * p.y.powi(e[1] as i32) * p.z.powi(e[2] as i32))
        .sum()
}

#[test]
fn volume_quadrature_is_exact_to_its_degree() {
    // Monomials x^a y^b z^c over the unit tetrahedron: a! b! c! / (a + b + c + 3)!.
    let fact = |n: u32| (1..=n).map(f64::from).product::<f64>();
    for degree in 1..=10u32 {
        let rule = VolumeQuadratureRule::for_domain(
            mortar_fem::element::VolumeDomain::Tetrahedron,
            degree,
        )
        .unwrap();
        for a in 0..=degree {
            for b in 0..=degree - a {
                let c = degree - a - b;
                let q = monomial_integral(&rule, [a, b, c]);
                let exact = fact(a) * fact(b) * fact(c) / fact(a + b + c + 3);
                assert!((q - exact).abs() < 1e-14, "degree {degree}: {q} vs {exact}");
            }
        }
    }
    let hex = VolumeQuadratureRule::for_domain(mortar_fem::element::VolumeDomain::Hexahedron, 11)
        .unwrap();
    let q = monomial_integral(&hex, [4, 4, 2]);
    assert!((q - 8.0 / 75.0).abs() < 1e-14);
    // Above the symmetric rules (degree 11), tensor Gauss rules: every monomial of total
    // degree up to 20, against prod 2 / (e + 1) for even exponents, 0 for odd ones.
    for degree in [12u32, 13, 16, 20] {
        let rule =
            VolumeQuadratureRule::for_domain(mortar_fem::element::VolumeDomain::Hexahedron, degree)
                .unwrap();
        for a in 0..=degree {
            for b in 0..=degree - a {
                let c = degree - a - b;
                let q = monomial_integral(&rule, [a, b, c]);
                let one = |e: u32| {
                    if e.is_multiple_of(2) {
                        2.0 / f64::from(e + 1)
                    } else {
                        0.0
                    }
                };
                let exact = one(a) * one(b) * one(c);
                assert!(
                    (q - exact).abs() < 1e-13,
                    "degree {degree}: x^{a} y^{b} z^{c}: {q} vs {exact}"
                );
            }
        }
    }
}

/// A 2 x 2 x 2 cube of Hex8, or of Tet4 (six per cube, Kuhn split), of side 1.
fn unit_cube(tets: bool) -> VolumeMesh {
    let mut m = VolumeMesh::new();
    let id = |i: usize, j: usize, k: usize| (1 + i + 3 * j + 9 * k) as u64;
    for k in 0..3 {
        for j in 0..3 {
            for i in 0..3 {
                m.add_node(
                    id(i, j, k),
                    [i as f64 * 0.5, j as f64 * 0.5, k as f64 * 0.5],
                )
                .unwrap();
            }
        }
    }
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..2 {
                let c = [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ];
                if tets {
                    // Kuhn: paths from corner 0 to corner 6 along the axes.
                    for t in [
                        [0, 1, 2, 6],
                        [0, 2, 3, 6],
                        [0, 3, 7, 6],
                        [0, 7, 4, 6],
                        [0, 4, 5, 6],
                        [0, 5, 1, 6],
                    ] {
                        m.add_cell(&TET4, &t.map(|a| c[a])).unwrap();
                    }
                } else {
                    m.add_cell(&HEX8, &c).unwrap();
                }
            }
        }
    }
    m
}

#[test]
fn boundary_of_a_cube_is_closed_and_outward() {
    for tets in [false, true] {
        let m = unit_cube(tets);
        let faces = m.boundary_faces().unwrap();
        assert_eq!(faces.len(), if tets { 48 } else { 24 });
        // Sum of outward area vectors of a closed surface is zero; sum of x n_x dA = volume.
        let surf = m.boundary_surface(|_| true).unwrap();
        let (mut total, mut flux, mut area) = (Vector3::zeros(), 0.0, 0.0);
        for f in 0..surf.face_count() {
            let view = surf.face(f);
            let x: Vec<Vector3<f64>> = view
                .nodes
                .iter()
                .map(|&n| surf.coords()[n as usize])
                .collect();
            let rule =
                mortar_core::quadrature::QuadratureRule::cached(view.element.domain(), 2).unwrap();
            use mortar_core::quadrature::Quadrature;
            for (p, w) in rule.points().iter().zip(rule.weights()) {
                let sn = view.element.scaled_normal(&x, p);
                let xp = view.element.map(&x, p);
                total += sn * *w;
                flux += xp.x * sn.x * w;
                area += sn.norm() * w;
            }
        }
        assert!(total.norm() < 1e-14, "tets {tets}: {total:?}");
        assert!((flux - 1.0).abs() < 1e-14, "tets {tets}: {flux}");
        assert!((area - 6.0).abs() < 1e-14);
        // The face x = 1, by a predicate and by node list.
        let right = m
            .boundary_surface(|f| (f.centroid.x - 1.0).abs() < 1e-12)
            .unwrap();
        assert_eq!(right.node_count(), 9);
        let tags: Vec<u64> = right.node_tags().to_vec();
        let again = m.boundary_surface_on_nodes(&tags).unwrap();
        assert_eq!(again.face_count(), right.face_count());
        assert!(m.boundary_surface(|_| false).is_err());
    }
}

#[test]
fn bad_cells_are_refused_with_their_tag() {
    let mut m = VolumeMesh::new();
    for (t, x) in [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ]
    .iter()
    .enumerate()
    {
        m.add_node(t as u64 + 1, *x).unwrap();
    }
    assert!(m.add_cell(&TET4, &[1, 2, 3]).is_err());
    assert!(m.add_cell(&TET4, &[1, 2, 3, 9]).is_err());
    assert!(m.add_cell(&TET4, &[1, 2, 2, 4]).is_err());
    m.add_cell_with_tag(7, &TET4, &[1, 2, 3, 4]).unwrap();
    // A 2D cell in a 3D mesh, and a 2D cell off the plane z = 0.
    let err = m.add_cell(&TRI3, &[1, 2, 3]).unwrap_err();
    assert!(err.to_string().contains("dimension"), "{err}");
    let mut flat = VolumeMesh::new();
    flat.add_node(1, [0.0, 0.0, 0.0]).unwrap();
    flat.add_node(2, [1.0, 0.0, 0.0]).unwrap();
    flat.add_node(3, [0.0, 1.0, 0.5]).unwrap();
    assert!(flat.add_cell(&TRI3, &[1, 2, 3]).is_err());
}
