//! Master faces that overlap as seen from the slave: two master layers within the search
//! radius (or a master that folds over) cover part of the slave surface twice, and D and M
//! count that area once per layer (a tied slave follows the layers' mean there). Nothing is
//! wrong with the meshes one by one; the coupling must say so, by a counted, named warning
//! ([`CouplingWarning::OverlappingMasterFaces`]) that gives the doubly covered area and
//! where, and it must say so on every path (the 2D walk along master chains and the fused
//! line kernel as well as the tree and the general kernel).
//!
//! Verification: the covered area is a closed form (the layers' shadows on the slave are
//! intervals and rectangles), and so are D's and M's sums (each the slave area each master
//! layer covers, summed over the layers).

use super::common::append_offset;
use mortar::generate::{line_mesh, square_quads, square_triangles, Diagonal};
use mortar::{assemble_coupling, CouplingOptions, CouplingWarning, Interface, SurfaceMesh};

/// The faces of `layers` in one mesh, each layer's node and face tags moved past the
/// previous one's.
fn stack(layers: &[SurfaceMesh]) -> SurfaceMesh {
    let mut out = SurfaceMesh::new();
    let (mut nodes, mut faces) = (0, 0);
    for layer in layers {
        append_offset(&mut out, layer, nodes, faces);
        nodes += layer.node_tags().iter().max().unwrap();
        faces += (0..layer.face_count())
            .map(|f| layer.face(f).tag)
            .max()
            .unwrap();
    }
    out
}

/// `mesh` with every node moved by `f`.
fn moved(mut mesh: SurfaceMesh, f: impl Fn([f64; 3]) -> [f64; 3]) -> SurfaceMesh {
    mesh.transform(|x| f([x.x, x.y, x.z]).into()).unwrap();
    mesh
}

fn sum(m: &mortar::core::linalg::SparseMatrix) -> f64 {
    m.data().iter().sum()
}

fn overlap_warning(w: &[CouplingWarning]) -> Option<&CouplingWarning> {
    w.iter()
        .find(|w| matches!(w, CouplingWarning::OverlappingMasterFaces { .. }))
}

/// 2D: the slave [0, 1] under two master layers, one over [0, 1] at y = 0.02 and one over
/// [0.25, 0.75] at y = 0.04 (both within the default search radius of the slave's faces,
/// one face size, 0.125). Every path of the 2D coupling: the fused line kernel on the
/// walk's candidates (standard and dual multipliers), on 1 and 2 threads.
#[test]
fn two_master_layers_over_a_line_are_reported() {
    let slave = line_mesh(8, true, 1).unwrap();
    let lower = moved(line_mesh(12, false, 1).unwrap(), |[x, _, z]| [x, 0.02, z]);
    let upper = moved(line_mesh(5, false, 1).unwrap(), |[x, _, z]| {
        [0.25 + 0.5 * x, 0.04, z]
    });
    for layers in [[lower.clone(), upper.clone()], [upper, lower]] {
        let interface = Interface::new(slave.clone(), stack(&layers)).unwrap();
        for options in [
            CouplingOptions::default(),
            CouplingOptions::default().dual(),
        ] {
            for threads in [1, 2] {
                let c = assemble_coupling(&interface, &options.clone().threads(threads)).unwrap();
                let name = format!("{} threads, {}", threads, options.describe());
                // D and M: the length each layer covers, 1 + 0.5.
                assert!((sum(&c.d) - 1.5).abs() < 1e-14, "{name}: {}", sum(&c.d));
                assert!((sum(&c.m) - 1.5).abs() < 1e-14, "{name}: {}", sum(&c.m));
                let Some(CouplingWarning::OverlappingMasterFaces {
                    area,
                    total,
                    faces,
                    examples,
                }) = overlap_warning(&c.warnings)
                else {
                    panic!("{name}: no overlap warning in {:?}", c.warnings);
                };
                assert!((area - 0.5).abs() < 1e-14, "{name}: {area}");
                assert!((total - 1.0).abs() < 1e-14, "{name}: {total}");
                // Slave faces 3..=6 (tags from 1) lie under the upper layer.
                assert_eq!(*faces, 4, "{name}");
                assert_eq!(examples, &[3, 4, 5, 6], "{name}");
                assert_eq!(c.warnings.len(), 1, "{name}: {:?}", c.warnings);
            }
        }
    }
}

/// 3D: the unit square of triangles under a master of quads at z = 0.02 over all of it,
/// and a second of triangles at z = 0.04 over [0.25, 0.75]^2: 0.25 of the slave covered
/// twice. Also one layer alone: no warning.
#[test]
fn two_master_layers_over_a_plane_are_reported() {
    let slave = square_triangles(4, Diagonal::Main, 0.0, false, 1).unwrap();
    let lower = square_quads(6, 0.02, true, 1).unwrap();
    let upper = moved(
        square_triangles(3, Diagonal::Anti, 0.04, true, 1).unwrap(),
        |[x, y, z]| [0.25 + 0.5 * x, 0.25 + 0.5 * y, z],
    );
    let single = Interface::new(slave.clone(), lower.clone()).unwrap();
    let c = assemble_coupling(&single, &CouplingOptions::default()).unwrap();
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
    let interface = Interface::new(slave, stack(&[lower, upper])).unwrap();
    for threads in [1, 2] {
        let options = CouplingOptions::default().threads(threads);
        let c = assemble_coupling(&interface, &options).unwrap();
        assert!((sum(&c.d) - 1.25).abs() < 1e-13, "{}", sum(&c.d));
        assert!((sum(&c.m) - 1.25).abs() < 1e-13, "{}", sum(&c.m));
        let Some(CouplingWarning::OverlappingMasterFaces {
            area, total, faces, ..
        }) = overlap_warning(&c.warnings)
        else {
            panic!("no overlap warning in {:?}", c.warnings);
        };
        assert!((area - 0.25).abs() < 1e-13, "{area}");
        assert!((total - 1.0).abs() < 1e-13, "{total}");
        // The 4x4 grid's cells 1..=2 in each direction, two triangles each.
        assert_eq!(*faces, 8);
        let message = overlap_warning(&c.warnings).unwrap().to_string();
        assert!(message.contains("covered more than once"), "{message}");
        // Under `require_full_coverage` it is an error.
        let strict = options.clone().require_full_coverage(true);
        assert!(assemble_coupling(&interface, &strict).is_err());
    }
}

fn slave_overlap_warning(w: &[CouplingWarning]) -> Option<&CouplingWarning> {
    w.iter()
        .find(|w| matches!(w, CouplingWarning::OverlappingSlaveFaces { .. }))
}

/// Both sides of a thin plate (0.001 thick) given as the slave over a master plane, each
/// side facing the master (as the facing step of `mortar couple` turns them): each layer is
/// covered once, so no slave-side warning can see it, but the master is covered twice. Before,
/// the coupling said nothing (D summed to 2 over a master of area 1); now it warns of
/// overlapping slave faces, the master area covered more than once being 1 (the closed form:
/// the whole unit square, once more). One layer alone is not warned of; with
/// `require_full_coverage` the two are an error.
#[test]
fn two_slave_layers_over_one_master_are_reported() {
    let master = square_triangles(6, Diagonal::Main, 0.0, false, 1).unwrap();
    let bottom = square_quads(5, 0.0, true, 1).unwrap();
    let top = square_quads(4, 0.001, true, 1).unwrap();
    let plate = stack(&[bottom.clone(), top]);
    for options in [
        CouplingOptions::default(),
        CouplingOptions::default().dual(),
    ] {
        let interface = Interface::new(plate.clone(), master.clone()).unwrap();
        let c = assemble_coupling(&interface, &options).unwrap();
        assert!((sum(&c.d) - 2.0).abs() < 1e-12, "{}", sum(&c.d));
        let Some(CouplingWarning::OverlappingSlaveFaces {
            area,
            total,
            master_nodes,
            ..
        }) = slave_overlap_warning(&c.warnings)
        else {
            panic!("{:?}", c.warnings);
        };
        assert!((total - 1.0).abs() < 1e-12, "{total}");
        assert!((area - 1.0).abs() < 1e-12, "{area}");
        assert_eq!(*master_nodes, 49);
        assert!(c.warnings[0]
            .to_string()
            .starts_with("overlapping slave faces"));
        let one = Interface::new(bottom.clone(), master.clone()).unwrap();
        let c = assemble_coupling(&one, &options).unwrap();
        assert!(c.warnings.is_empty(), "{:?}", c.warnings);
        let strict = options.clone().require_full_coverage(true);
        let e = assemble_coupling(&interface, &strict).unwrap_err();
        assert!(e.to_string().contains("overlapping slave faces"), "{e}");
    }
}
