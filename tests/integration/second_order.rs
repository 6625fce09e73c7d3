//! Second-order meshes made by Gmsh 4.15 itself (`tests/meshes/make_second_order_meshes.py`:
//! `Mesh.ElementOrder = 2`, complete and incomplete, Gmsh's own node order): the cells and
//! faces are read as the shipped quadratic elements, the bodies' measures and boundaries are
//! exact, and the non-conforming interfaces of two bodies meshed apart (Tri6 against Quad8 and
//! Quad9 lines in 2D; Quad8 against Tri6, Tri6 against Quad9 faces in 3D) are coupled exactly.
//!
//! Closed forms: the unit square and the box `[0,1]^2 x [0,0.5]`; on the flat interface of
//! measure 1, `sum(D) = 1`, constants tied (`D 1 = M 1`) and linear fields tied
//! (`D x_s = M x_m`, each coordinate), for standard and dual multipliers.

use std::path::{Path, PathBuf};

use mortar::core::element::volume::CellValues;
use mortar::core::multiplier::slave_recombination;
use mortar::core::quadrature::{Quadrature, QuadratureRule, VolumeQuadratureRule};
use mortar::elements::volume::VolumeRegistry;
use mortar::elements::ElementRegistry;
use mortar::io::{read_gmsh_surface, read_gmsh_volume};
use mortar::{assemble_coupling, CouplingOptions, Interface};
use nalgebra::Vector3;

fn mesh(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/meshes")
        .join(name)
}

/// One file: its two bodies with their cell types and measures, and the interface groups
/// (slave first) with their face types.
struct Case {
    file: &'static str,
    bodies: [(&'static str, &'static str, f64); 2],
    interface: [(&'static str, &'static str); 2],
}

const CASES: [Case; 5] = [
    Case {
        file: "so_2d_quad8.msh",
        bodies: [("left", "Tri6", 1.0), ("right", "Quad8", 1.0)],
        interface: [("right_x0", "Line3"), ("left_x1", "Line3")],
    },
    Case {
        file: "so_2d_quad9.msh",
        bodies: [("left", "Quad9", 1.0), ("right", "Tri6", 1.0)],
        interface: [("left_x1", "Line3"), ("right_x0", "Line3")],
    },
    Case {
        file: "so_3d_hex20.msh",
        bodies: [("bottom", "Hex20", 0.5), ("top", "Tet10", 0.5)],
        interface: [("bottom_top", "Quad8"), ("top_bottom", "Tri6")],
    },
    Case {
        file: "so_3d_hex20.msh",
        bodies: [("bottom", "Hex20", 0.5), ("top", "Tet10", 0.5)],
        interface: [("top_bottom", "Tri6"), ("bottom_top", "Quad8")],
    },
    Case {
        file: "so_3d_hex27.msh",
        bodies: [("bottom", "Tet10", 0.5), ("top", "Hex27", 0.5)],
        interface: [("top_bottom", "Quad9"), ("bottom_top", "Tri6")],
    },
];

#[test]
fn second_order_cells_are_read_with_exact_measures_and_boundaries() {
    let registry = VolumeRegistry::new();
    for case in &CASES {
        for (group, kind, volume) in case.bodies {
            let body = read_gmsh_volume(mesh(case.file), group, &registry).unwrap();
            let m = &body.mesh;
            let mut cv = CellValues::new();
            let mut x = [Vector3::zeros(); 27];
            let mut total = 0.0;
            for c in 0..m.cell_count() {
                let el = m.cell(c).element;
                assert_eq!(el.name(), kind, "{} {group}", case.file);
                let k = m.cell_coords_into(c, &mut x);
                let rule = VolumeQuadratureRule::cached(el.domain(), 2).unwrap();
                cv.reinit(el, rule, &x[..k]).unwrap();
                total += (0..cv.len()).map(|q| cv.jxw(q)).sum::<f64>();
            }
            assert!(
                (total - volume).abs() < 1e-13,
                "{} {group}: {total}",
                case.file
            );
            // The boundary: closed (outward area vectors sum to zero), of the box's measure
            // (perimeter 4; surface 4 for the 1 x 1 x 0.5 box), and the divergence theorem
            // `int x n_x = volume` holds on it.
            let surf = m.boundary_surface(|_| true).unwrap();
            let (mut sum, mut flux, mut measure) = (Vector3::zeros(), 0.0, 0.0);
            for f in 0..surf.face_count() {
                let view = surf.face(f);
                assert!(
                    view.nodes.len() > view.element.corner_count(),
                    "{}",
                    case.file
                );
                let xs: Vec<Vector3<f64>> = view
                    .nodes
                    .iter()
                    .map(|&n| surf.coords()[n as usize])
                    .collect();
                let rule = QuadratureRule::cached(view.element.domain(), 6).unwrap();
                for (p, w) in rule.points().iter().zip(rule.weights()) {
                    let n = view.element.scaled_normal(&xs, p);
                    sum += n * *w;
                    flux += view.element.map(&xs, p).x * n.x * w;
                    measure += n.norm() * w;
                }
            }
            assert!(sum.norm() < 1e-13, "{} {group}: {sum:?}", case.file);
            assert!(
                (flux - volume).abs() < 1e-13,
                "{} {group}: {flux}",
                case.file
            );
            assert!(
                (measure - 4.0).abs() < 1e-13,
                "{} {group}: {measure}",
                case.file
            );
        }
    }
}

#[test]
fn second_order_interfaces_tie_constants_and_linear_fields() {
    let registry = ElementRegistry::new();
    for case in &CASES {
        for options in [
            CouplingOptions::default(),
            CouplingOptions::default().dual(),
            CouplingOptions::default().linear(),
        ] {
            let read = |(group, kind): (&str, &str)| {
                let mut s = read_gmsh_surface(mesh(case.file), Some(group), &registry).unwrap();
                for f in 0..s.mesh.face_count() {
                    assert_eq!(s.mesh.face(f).element.name(), kind, "{} {group}", case.file);
                }
                s.orient_outward().unwrap();
                s.mesh
            };
            let (slave, master) = (read(case.interface[0]), read(case.interface[1]));
            let interface = Interface::new(slave, master).unwrap();
            let t = slave_recombination(&interface).unwrap();
            let c = assemble_coupling(&interface, &options)
                .unwrap_or_else(|e| panic!("{} {options:?}: {e}", case.file));
            let what = format!("{} ({})", case.file, c.formulation);
            assert!(
                (c.stats.area - 1.0).abs() < 1e-12,
                "{what}: sum(D) {}",
                c.stats.area
            );
            assert!(c.warnings.is_empty(), "{what}: {:?}", c.warnings);
            let worst = linear_fields_untied(&interface, &c);
            assert!(worst < 1e-12, "{what}: |D f_s - M f_m| = {worst:e}");
            if options.multipliers.name() == "linear" {
                // A row for each corner node, none for the others.
                let slave = interface.slave();
                let mut corner = vec![false; slave.node_count()];
                for f in 0..slave.face_count() {
                    let face = slave.face(f);
                    for &n in &face.nodes[..face.element.corner_count()] {
                        corner[n as usize] = true;
                    }
                }
                for (r, tag) in c.slave_nodes.iter().enumerate() {
                    let node = slave.node_index(*tag).unwrap() as usize;
                    assert_eq!(
                        c.d.outer_view(r).unwrap().nnz() > 0,
                        corner[node],
                        "{what}: row {r} (node {tag}, corner {})",
                        corner[node]
                    );
                    assert_eq!(
                        c.m.outer_view(r).unwrap().nnz() > 0,
                        corner[node],
                        "{what}: M row {r}"
                    );
                }
            }
            if options
                .multipliers
                .fast_paths()
                .is_some_and(|f| f.diagonal_d())
            {
                assert_eq!(c.stats.d_off_diagonal, 0, "{what}");
                recombined_condenses(&interface, &c, t.as_ref(), &what);
                // Dual: D~ = D T^T (D itself where nothing is recombined) is diagonal to
                // round-off, every diagonal entry positive (Popp, Gee and Wall 2012).
                let dt = match &t {
                    Some(t) => &c.d * &t.transpose_view().to_csr(),
                    None => c.d.clone(),
                };
                for (r, row) in dt.outer_iterator().enumerate() {
                    let diag = row.get(r).copied().unwrap_or(0.0);
                    assert!(diag > 0.0, "{what}: D~ row {r} diagonal {diag}");
                    for (j, v) in row.iter() {
                        assert!(
                            j == r || v.abs() < 1e-12 * diag,
                            "{what}: D~[{r}][{j}] = {v}"
                        );
                    }
                }
            }
        }
    }
}

/// The coupling's recombined D (Popp, Gee and Wall 2012): there exactly where the slave faces
/// are recombined (`t`), with the same `T`, diagonal as written, and condensing: the slave
/// values `u_s = T^T D~^-1 M u_m` of the fields `1, x, y, z` at the master nodes are the
/// fields at the slave nodes (the interface is flat, so both sides interpolate them exactly).
fn recombined_condenses(
    interface: &Interface,
    c: &mortar::Coupling,
    t: Option<&sprs::CsMat<f64>>,
    what: &str,
) {
    let Some(r) = &c.recombined else {
        assert!(t.is_none(), "{what}: recombined faces, no recombined D");
        return;
    };
    assert_eq!(Some(&r.t), t, "{what}: T");
    for (j, row) in r.d.outer_iterator().enumerate() {
        let entries: Vec<_> = row.iter().collect();
        assert!(
            entries.len() == 1 && entries[0].0 == j && *entries[0].1 > 0.0,
            "{what}: D~ row {j}: {entries:?}"
        );
    }
    let coords = |mesh: &mortar::SurfaceMesh, tags: &[u64]| -> Vec<nalgebra::Vector3<f64>> {
        tags.iter()
            .map(|t| mesh.coords()[mesh.node_index(*t).unwrap() as usize])
            .collect()
    };
    let xs = coords(interface.slave(), &c.slave_nodes);
    let xm = coords(interface.master(), &c.master_nodes);
    let tt = r.t.transpose_view().to_csr();
    for f in 0..4 {
        let field = |x: &nalgebra::Vector3<f64>| if f == 0 { 1.0 } else { x[f - 1] };
        let mu = product(&c.m, &xm.iter().map(field).collect::<Vec<_>>());
        let scaled: Vec<f64> = mu
            .iter()
            .enumerate()
            .map(|(j, v)| v / r.d.get(j, j).unwrap())
            .collect();
        let us = product(&tt, &scaled);
        for (j, (u, x)) in us.iter().zip(&xs).enumerate() {
            assert!(
                (u - field(x)).abs() < 1e-12,
                "{what}: field {f}, slave row {j}: {u} against {}",
                field(x)
            );
        }
    }
}

/// Dual multipliers on curved Line3 faces: the Gmsh arcs of `so_2d_arc.msh` (a disc of radius
/// 1 in 20 Line3 against the annulus around it in 27, middle nodes on the circle). The dual
/// basis is biorthogonal with respect to the face's own measure, `int Phi_j N_k J = delta_jk
/// int N_k J` (Wohlmuth 2000; Popp, Gee and Wall 2012), and D on a covered face is that
/// integral: diagonal, if its quadrature integrates the curved Line3's Jacobian (the norm of
/// a linear vector, not a polynomial) as the basis does. With the integrands' degree alone
/// (4) D kept 162 off-diagonal entries up to 5.8e-4 of the diagonal, with no warning; that
/// degree, asked for, is reported as a warning naming the departure.
#[test]
fn dual_d_is_diagonal_on_curved_line3_arcs() {
    use mortar::core::integration::SegmentBased;
    use mortar::CouplingWarning;
    let registry = ElementRegistry::new();
    let read = |group: &str| {
        let mut s = read_gmsh_surface(mesh("so_2d_arc.msh"), Some(group), &registry).unwrap();
        for f in 0..s.mesh.face_count() {
            assert_eq!(s.mesh.face(f).element.name(), "Line3");
        }
        s.orient_outward().unwrap();
        s.mesh
    };
    let interface = Interface::new(read("annulus_inner"), read("disc_edge")).unwrap();
    let dual = CouplingOptions::default().dual();
    for options in [dual.clone(), dual.clone().element_based(None).unwrap()] {
        let c = assemble_coupling(&interface, &options).unwrap();
        let what = c.formulation.clone();
        assert!(c.warnings.is_empty(), "{what}: {:?}", c.warnings);
        assert_eq!(c.stats.d_off_diagonal, 0, "{what}");
        assert_eq!(c.d.nnz(), c.slave_nodes.len(), "{what}: D diagonal");
        assert!(c.stats.d_roundoff_largest < 1e-13, "{what}");
        assert!(c.recombined.is_none(), "{what}: Line3 is not recombined");
        // The length of the slave's Line3 polygon of the circle.
        assert!(
            (c.stats.area - 2.0 * std::f64::consts::PI).abs() < 1e-4,
            "{what}"
        );
    }
    let mut low = dual;
    low.integration = std::sync::Arc::new(SegmentBased::new(Some(4)).unwrap());
    let c = assemble_coupling(&interface, &low).unwrap();
    let [CouplingWarning::DualNotDiagonal {
        entries, largest, ..
    }] = c.warnings.as_slice()
    else {
        panic!("one warning: {:?}", c.warnings);
    };
    assert_eq!(*entries, c.stats.d_off_diagonal);
    assert!(
        *entries > 0 && *largest > 1e-5,
        "{entries} up to {largest:e}"
    );
    assert!(c.warnings[0]
        .to_string()
        .starts_with("dual D not diagonal: "));
}

/// The largest `|D f_s - M f_m|` over the fields `f = 1, x, y, z` at the interface's slave
/// and master nodes (zero when the coupling ties constants and linear fields).
fn linear_fields_untied(interface: &Interface, c: &mortar::Coupling) -> f64 {
    let at = |mesh: &mortar::SurfaceMesh, tags: &[u64], f: usize| -> Vec<f64> {
        tags.iter()
            .map(|t| {
                let x = mesh.coords()[mesh.node_index(*t).expect("a node of the mesh") as usize];
                if f == 0 {
                    1.0
                } else {
                    x[f - 1]
                }
            })
            .collect()
    };
    (0..4)
        .map(|f| {
            let du = product(&c.d, &at(interface.slave(), &c.slave_nodes, f));
            let mu = product(&c.m, &at(interface.master(), &c.master_nodes, f));
            du.iter()
                .zip(&mu)
                .fold(0.0f64, |w, (a, b)| w.max((a - b).abs()))
        })
        .fold(0.0, f64::max)
}

/// `a u` for a sparse matrix.
fn product(a: &sprs::CsMat<f64>, u: &[f64]) -> Vec<f64> {
    a.outer_iterator()
        .map(|row| row.iter().map(|(j, v)| v * u[j]).sum())
        .collect()
}

/// The VTU writer puts the second-order cells' nodes in VTK's order (VTK's documentation of
/// vtkQuadraticTetra, vtkQuadraticHexahedron, vtkTriQuadraticHexahedron): in the written
/// connectivity of each Tet10, Hex20 and Hex27 of the Gmsh meshes, every edge node is the
/// middle of VTK's edge at its position, and every face centre the centre of VTK's face.
#[test]
fn vtu_writes_second_order_cells_in_vtk_order() {
    // VTK's edges: tetrahedron 01 12 02 03 13 23; hexahedron bottom 01 12 23 30, top 45 56 67
    // 74, verticals 04 15 26 37; hexahedron faces -x +x -y +y -z +z.
    let tet_edges = [[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]];
    let hex_edges = [
        [0, 1],
        [1, 2],
        [2, 3],
        [3, 0],
        [4, 5],
        [5, 6],
        [6, 7],
        [7, 4],
        [0, 4],
        [1, 5],
        [2, 6],
        [3, 7],
    ];
    let hex_faces = [
        [0, 3, 7, 4],
        [1, 2, 6, 5],
        [0, 1, 5, 4],
        [3, 2, 6, 7],
        [0, 1, 2, 3],
        [4, 5, 6, 7],
    ];
    let registry = VolumeRegistry::new();
    for (file, group, vtk_type) in [
        ("so_3d_hex20.msh", "top", 24u8),
        ("so_3d_hex20.msh", "bottom", 25),
        ("so_3d_hex27.msh", "top", 29),
    ] {
        let body = read_gmsh_volume(mesh(file), group, &registry).unwrap();
        let piece = mortar::io::vtu::VtuPiece {
            mesh: &body.mesh,
            point_data: vec![],
        };
        let text = mortar::io::vtu::vtu_string(Path::new("x.vtu"), &[piece]).unwrap();
        let array = |name: &str| -> Vec<f64> {
            let start = match name {
                "Points" => text.find("<Points>").unwrap(),
                _ => text.find(&format!("Name=\"{name}\"")).unwrap(),
            };
            let body = &text[start..];
            let a = body.find("format=\"ascii\">").unwrap() + "format=\"ascii\">".len();
            let b = body.find("</DataArray>").unwrap();
            body[a..b]
                .split_whitespace()
                .map(|v| v.parse().unwrap())
                .collect()
        };
        let (points, conn, offsets, types) = (
            array("Points"),
            array("connectivity"),
            array("offsets"),
            array("types"),
        );
        let p = |i: f64| {
            Vector3::new(
                points[3 * i as usize],
                points[3 * i as usize + 1],
                points[3 * i as usize + 2],
            )
        };
        let mut start = 0;
        for (c, end) in offsets.iter().enumerate() {
            let cell = &conn[start..*end as usize];
            start = *end as usize;
            assert_eq!(types[c] as u8, vtk_type, "{file} {group}");
            let (edges, corners): (&[[usize; 2]], usize) = if vtk_type == 24 {
                (&tet_edges, 4)
            } else {
                (&hex_edges, 8)
            };
            for (e, [a, b]) in edges.iter().enumerate() {
                let mid = 0.5 * (p(cell[*a]) + p(cell[*b]));
                assert!(
                    (p(cell[corners + e]) - mid).norm() < 1e-12,
                    "{file} {group} cell {c} edge {e}"
                );
            }
            if vtk_type == 29 {
                for (f, face) in hex_faces.iter().enumerate() {
                    let centre = face.iter().map(|&i| p(cell[i])).sum::<Vector3<f64>>() / 4.0;
                    assert!(
                        (p(cell[20 + f]) - centre).norm() < 1e-12,
                        "{file} cell {c} face {f}"
                    );
                }
                let centre = (0..8).map(|i| p(cell[i])).sum::<Vector3<f64>>() / 8.0;
                assert!((p(cell[26]) - centre).norm() < 1e-12);
            }
        }
    }
}

/// The tied-heat scene on the Gmsh second-order bodies (2D Tri6 | Quad8, 3D Hex20 | Tet10,
/// standard and dual): `T = 0` on one far side, a flux of 2 into the other, conductivities 1
/// and 2, so the exact temperature is piecewise linear (slope 2, then 1), which quadratic
/// elements and the mortar tie reproduce to round-off.
#[test]
fn tied_heat_scene_on_second_order_bodies_is_exact() {
    use mortar_scenes::file::{tied_heat::TiedHeatSpec, FileScene, FileSystem};
    let dir = mesh("");
    let scenes = [
        (
            "so_2d_quad8.msh",
            [
                "left", "right", "left_x0", "right_x1", "right_x0", "left_x1",
            ],
            0,
        ),
        (
            "so_3d_hex20.msh",
            [
                "bottom",
                "top",
                "bottom_z0",
                "top_z1",
                "top_bottom",
                "bottom_top",
            ],
            2,
        ),
    ];
    for (file, [a, b, a0, b1, slave, master], axis) in scenes {
        for multipliers in ["standard", "dual"] {
            let text = format!(
                "kind = \"tied_heat\"\n\
                 [bodies.{a}]\nmesh = \"{file}\"\ngroup = \"{a}\"\nconductivity = 1.0\n\
                 dirichlet = [{{ group = \"{a0}\", value = 0.0 }}]\n\
                 [bodies.{b}]\nmesh = \"{file}\"\ngroup = \"{b}\"\nconductivity = 2.0\n\
                 neumann = [{{ group = \"{b1}\", flux = 2.0 }}]\n\
                 [interface]\nslave = {{ body = \"{b}\", group = \"{slave}\" }}\n\
                 master = {{ body = \"{a}\", group = \"{master}\" }}\n\
                 multipliers = \"{multipliers}\"\n"
            );
            let path = dir.join("scene.toml");
            let solved = TiedHeatSpec::parse(&text, &path)
                .unwrap()
                .solve(&path, &dir, &FileSystem)
                .unwrap_or_else(|e| panic!("{file} {multipliers}: {e}"));
            // The interface is at 1 (2D, x) or 0.5 (3D, z).
            let at = if axis == 0 { 1.0 } else { 0.5 };
            let mut worst: f64 = 0.0;
            for (body, t) in solved
                .problem
                .bodies()
                .iter()
                .zip(&solved.solution.temperatures)
            {
                for (x, t) in body.mesh.coords().iter().zip(t) {
                    let s = x[axis];
                    let exact = if s <= at {
                        2.0 * s
                    } else {
                        2.0 * at + (s - at)
                    };
                    worst = worst.max((t - exact).abs());
                }
            }
            assert!(
                worst < 1e-11,
                "{file} {multipliers}: |T - T_exact| = {worst:e}"
            );
        }
    }
}

/// Curved second-order faces in 3D: the sphere of radius 0.3 between a Hex27
/// ball (master) and a Hex27 box around it (slave; `box_with_hole_mesh` makes hexahedra in
/// 3D), their second-order nodes on the sphere.
/// The slave is fully covered, so sum(D) is its own area (its Jacobian integrated by a
/// degree-20 rule) at every subdivision level, and D 1 = M 1; M converges as the level grows:
/// its distance from the level-16 M falls at least fourfold from level 1 to 4 and again from
/// 4 to 8 (about `L^-2`, the sub-triangles' chord error).
#[test]
fn curved_second_order_sphere_converges_with_the_subdivision_level() {
    use mortar::core::integration::SegmentBased;
    use mortar::generate::{
        ball_mesh, box_with_hole_mesh, onto_sphere, second_order_mesh, CellShape, Inclusion,
        SecondOrder,
    };
    let g = Inclusion::unit(3, 0.3);
    let place = || onto_sphere(g.centre, g.radius);
    let raise = |m| second_order_mesh(&m, SecondOrder::Complete, place()).unwrap();
    let master = raise(ball_mesh(&g, 2, 1, 1).unwrap());
    let slave = raise(box_with_hole_mesh(&g, 3, 1, CellShape::Simplex, 1_000_001).unwrap());
    let c = Vector3::from(g.centre);
    let near = |f: &mortar::core::mesh::BoundaryFace| (f.centroid - c).norm() < 0.4;
    let (ms, ss) = (
        master.boundary_surface(near).unwrap(),
        slave.boundary_surface(near).unwrap(),
    );
    let area: f64 = (0..ss.face_count())
        .map(|f| {
            let face = ss.face(f);
            let x: Vec<Vector3<f64>> = face
                .nodes
                .iter()
                .map(|&n| ss.coords()[n as usize])
                .collect();
            let rule = QuadratureRule::cached(face.element.domain(), 20).unwrap();
            rule.points()
                .iter()
                .zip(rule.weights())
                .map(|(p, w)| w * face.element.jacobian_det(&x, p))
                .sum::<f64>()
        })
        .sum();
    let interface = Interface::new(ss, ms).unwrap();
    let couple = |level: u32| {
        let mut options = CouplingOptions::default().dual();
        options.integration =
            std::sync::Arc::new(SegmentBased::default().with_subdivision(level).unwrap());
        assemble_coupling(&interface, &options).unwrap()
    };
    let reference = couple(16);
    let mut distance = Vec::new();
    for level in [1, 4, 8] {
        let c = couple(level);
        assert!(
            (c.stats.area - area).abs() < 1e-12 * area,
            "level {level}: {} vs {area}",
            c.stats.area
        );
        let (d1, m1) = (
            product(&c.d, &vec![1.0; c.d.cols()]),
            product(&c.m, &vec![1.0; c.m.cols()]),
        );
        let worst = d1
            .iter()
            .zip(&m1)
            .fold(0.0f64, |w, (a, b)| w.max((a - b).abs()));
        assert!(worst < 1e-13, "level {level}: |D 1 - M 1| = {worst:e}");
        let diff = &c.m - &reference.m;
        let scale = reference
            .m
            .data()
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        distance.push(diff.data().iter().fold(0.0f64, |m, v| m.max(v.abs())) / scale);
    }
    assert!(
        distance[1] < distance[0] / 4.0 && distance[2] < distance[1] / 2.5,
        "{distance:?}"
    );
    assert!(SegmentBased::default().with_subdivision(0).is_err());
    assert!(SegmentBased::default().with_curved_tolerance(0.0).is_err());
}

/// A quadratic field (`u = 0.7 x^2 - 0.4 y^2 + 0.2 z^2 + 0.5 x y`, with its source) on the
/// straight interface of the tied-heat study raised to second order (Quad9 | Tri6 in 2D,
/// Hex27 | Tet10 in 3D, meshes 2:3), standard multipliers: reproduced to 1e-10 at every node,
/// the Dirichlet slave nodes' multipliers redistributed so that linear
/// fluxes stay representable (equal shares gave 7.8e-6 in 2D). Dual multipliers represent
/// only constants across faces (each face's coefficients of a linear function differ), so the
/// linear flux of this field is not in their space: in 3D they miss it by 3.8e-5 at this
/// size (n = 4); in 2D (Line3) they happen to reproduce it; both are checked as measured.
/// Linear multipliers on the second-order faces (corner nodes only, continuous linear
/// functions) contain that flux: to 1e-10 as the standard ones, in both families, and the
/// flux itself (exact at the corners, interpolated at the edge nodes) to 1e-9.
#[test]
fn second_order_tie_reproduces_a_quadratic_field() {
    use mortar::generate::SecondOrder;
    use mortar_scenes::tied_heat::{Exact, Geometry, TiedHeatScene};
    for dim in [2, 3] {
        for (family, space) in [
            (SecondOrder::Complete, "standard"),
            (SecondOrder::Serendipity, "standard"),
            (SecondOrder::Complete, "dual"),
            (SecondOrder::Complete, "linear"),
            (SecondOrder::Serendipity, "linear"),
        ] {
            let dual = space == "dual";
            let mut scene = TiedHeatScene::new(dim, Geometry::Straight, 4);
            scene.order = Some(family);
            scene.exact = Exact::Quadratic {
                a: [0.7, -0.4, 0.2],
                c: 0.5,
            };
            match space {
                "standard" => scene.coupling = CouplingOptions::default(),
                "linear" => scene.coupling = CouplingOptions::default().linear(),
                _ => {}
            }
            let run = scene.run().unwrap();
            let bound = if dual && dim == 3 { 1e-4 } else { 1e-10 };
            assert!(
                run.max_nodal < bound,
                "{dim}D {family:?} {space}: max nodal error {:e}",
                run.max_nodal
            );
            if space == "linear" {
                // The flux is linear, so the corners' multipliers carry it exactly and the
                // edge nodes' fluxes, interpolated from them, are exact too.
                let c = run.problem.tie().coupling();
                let coords = run.problem.bodies()[0].mesh.coords();
                let (mut edge_nodes, mut worst) = (0, 0.0f64);
                for (j, (&node, flux)) in run
                    .problem
                    .tie()
                    .slave_nodes()
                    .iter()
                    .zip(&run.solution.flux)
                    .enumerate()
                {
                    let empty = c.d.outer_view(j).is_none_or(|r| r.nnz() == 0);
                    if !flux.is_finite() {
                        continue;
                    }
                    edge_nodes += usize::from(empty);
                    let x = coords[node as usize];
                    let exact = -scene.conductivity
                        * scene.exact.gradient(dim, &x).dot(&c.slave_normals[j]);
                    worst = worst.max((flux - exact).abs());
                }
                assert!(edge_nodes > 0, "{dim}D {family:?}: no edge node flux");
                assert!(worst < 1e-9, "{dim}D {family:?}: flux off by {worst:e}");
            }
        }
    }
}

/// Mixed first- and second-order sides: a Tri3 or Quad4 plane (`generate`) against the
/// Gmsh-made Quad8 and Quad9 faces, and the Gmsh-made Tri6 faces against a Quad4 plane, at the
/// interface `z = 0.5`: sum(D) = 1 and D f = M f for f = 1, x, y, z to 1e-12, standard and
/// dual.
#[test]
fn first_order_faces_couple_with_second_order_ones() {
    use mortar::generate::{square_quads, square_triangles, Diagonal};
    let registry = ElementRegistry::new();
    let gmsh = |file: &str, group: &str| {
        let mut s = read_gmsh_surface(mesh(file), Some(group), &registry).unwrap();
        s.orient_outward().unwrap();
        s.mesh
    };
    let cases = [
        // Linear slaves below the top faces of the bottom bodies (normals -z, facing them).
        (
            square_triangles(5, Diagonal::Main, 0.5, true, 1).unwrap(),
            gmsh("so_3d_hex20.msh", "bottom_top"),
        ),
        (
            square_quads(4, 0.5, true, 1).unwrap(),
            gmsh("so_3d_hex20.msh", "bottom_top"),
        ),
        // A linear slave above the Hex27 top body's bottom face (normal +z).
        (
            square_triangles(5, Diagonal::Anti, 0.5, false, 1).unwrap(),
            gmsh("so_3d_hex27.msh", "top_bottom"),
        ),
        // A second-order slave (Tri6, normal -z) against a linear master facing it.
        (
            gmsh("so_3d_hex20.msh", "top_bottom"),
            square_quads(3, 0.5, false, 1).unwrap(),
        ),
    ];
    for (k, (slave, master)) in cases.into_iter().enumerate() {
        let interface = Interface::new(slave, master).unwrap();
        for options in [
            CouplingOptions::default(),
            CouplingOptions::default().dual(),
            CouplingOptions::default().linear(),
        ] {
            let c = assemble_coupling(&interface, &options)
                .unwrap_or_else(|e| panic!("case {k} {options:?}: {e}"));
            assert!(
                (c.stats.area - 1.0).abs() < 1e-12,
                "case {k}: {}",
                c.stats.area
            );
            let worst = linear_fields_untied(&interface, &c);
            assert!(worst < 1e-12, "case {k} ({}): {worst:e}", c.formulation);
            // Second-order faces bulge out of their nodes' hull: their side's boxes are
            // inflated, the linear side's are not.
            let inflation = (c.stats.slave_box_inflation, c.stats.master_box_inflation);
            let want = if k < 3 { (0.0, 0.1) } else { (0.1, 0.0) };
            assert_eq!(inflation, want, "case {k}");
        }
    }
}

/// A Line3 whose middle node lies outside its ends folds back on itself: refused when the
/// interface is built, naming the face (it was taken, and gave no overlap or wrong
/// integrals), on either side; a bent Line3 (middle node off the chord) is accepted.
#[test]
fn folded_line3_faces_are_refused() {
    use mortar::core::element::ElementRef;
    use mortar::MortarError;
    let line = |mid: [f64; 3], first_tag: u64| {
        let mut m = mortar::SurfaceMesh::new();
        m.add_node(first_tag, [0.0, 0.0, 0.0]).unwrap();
        m.add_node(first_tag + 1, [1.0, 0.0, 0.0]).unwrap();
        m.add_node(first_tag + 2, mid).unwrap();
        let el: ElementRef = &mortar::elements::LINE3;
        m.add_face(el, &[first_tag, first_tag + 1, first_tag + 2])
            .unwrap();
        m
    };
    let master = |mid| {
        let mut m = mortar::SurfaceMesh::new();
        m.add_node(1, [1.0, 0.0, 0.0]).unwrap();
        m.add_node(2, [0.0, 0.0, 0.0]).unwrap();
        m.add_node(3, mid).unwrap();
        m.add_face(&mortar::elements::LINE3, &[1, 2, 3]).unwrap();
        m
    };
    for (slave_mid, master_mid) in [
        ([1.3, 0.0, 0.0], [0.5, 0.0, 0.0]),
        ([0.5, 0.0, 0.0], [-0.2, 0.0, 0.0]),
    ] {
        match Interface::new(line(slave_mid, 10), master(master_mid)) {
            Err(MortarError::InvertedFace { reason, .. }) => {
                assert!(reason.contains("turns back"), "{reason}")
            }
            other => panic!("{other:?}"),
        }
    }
    assert!(Interface::new(line([0.5, 0.1, 0.0], 10), master([0.5, 0.0, 0.0])).is_ok());
}

/// The linear multiplier basis (`LinearMultipliers`) on every shipped second-order face: in
/// the face's own shape functions it is the first-order basis of the corners (closed form:
/// `Phi_c(corner d) = delta_cd`, `sum_c Phi_c = 1`, linear along each edge, so its value at
/// an edge's middle is the mean of its ends, and the bilinear value 1/4 at a Quad9's centre),
/// with zero rows on the other nodes; first-order faces keep the standard basis.
#[test]
fn linear_multipliers_are_the_corner_functions() {
    use mortar::core::element::{ElementRef, MAX_FACE_NODES};
    use mortar::core::interface::FaceGeometry;
    use mortar::core::multiplier::{LinearMultipliers, MultiplierSpace};
    use mortar::core::{Side, Tolerances};
    use mortar::elements::{LINE2, LINE3, QUAD4, QUAD8, QUAD9, TRI3, TRI6};
    use nalgebra::Vector2;
    let elements: [ElementRef; 7] = [&LINE2, &TRI3, &QUAD4, &LINE3, &TRI6, &QUAD8, &QUAD9];
    for el in elements {
        let (k, c) = (el.node_count(), el.corner_count());
        let mut nodes = [Vector3::zeros(); MAX_FACE_NODES];
        for (x, xi) in nodes.iter_mut().zip(el.node_reference_coords()) {
            *x = Vector3::new(xi[0], xi[1], 0.0);
        }
        let face = FaceGeometry {
            index: 0,
            tag: 1,
            side: Side::Slave,
            element: el,
            nodes,
            normals: [Vector3::z(); MAX_FACE_NODES],
        };
        let basis = LinearMultipliers
            .basis(&face, &Tolerances::default())
            .unwrap();
        assert_eq!(basis.identity, k == c, "{}", el.name());
        let phi = |xi: [f64; 2]| {
            let mut n = [0.0; MAX_FACE_NODES];
            let mut p = [0.0; MAX_FACE_NODES];
            el.shape_values_into(&Vector2::new(xi[0], xi[1]), &mut n[..k]);
            basis.eval_into(&n, &mut p);
            p
        };
        let xi = el.node_reference_coords();
        for (node, x) in xi.iter().enumerate() {
            let p = phi(*x);
            assert!(
                (p[..c].iter().sum::<f64>() - 1.0).abs() < 1e-14,
                "{}: partition of unity at node {node}",
                el.name()
            );
            for (corner, v) in p[..c].iter().enumerate() {
                // The first-order function of `corner` at `x`, from the corners' coordinates.
                let expected = if node < c {
                    f64::from(u8::from(node == corner))
                } else {
                    // An edge's middle: the mean of the ends it lies between; a centre: 1/4.
                    let ends: Vec<usize> = (0..c)
                        .filter(|&d| {
                            (0..c).any(|e| {
                                e != d
                                    && (0..2)
                                        .all(|i| ((xi[d][i] + xi[e][i]) / 2.0 - x[i]).abs() < 1e-14)
                            })
                        })
                        .collect();
                    if ends.contains(&corner) {
                        1.0 / ends.len() as f64
                    } else {
                        0.0
                    }
                };
                assert!(
                    (v - expected).abs() < 1e-14,
                    "{}: Phi_{corner} at node {node} = {v}, expected {expected}",
                    el.name()
                );
            }
            assert!(p[c..k].iter().all(|v| *v == 0.0), "{}", el.name());
        }
        for j in 0..k {
            assert_eq!(basis.carries(j), j < c, "{} node {j}", el.name());
        }
    }
}
