//! Only the side of a master body that faces the slave couples. A thin master body (a strip in
//! 2D, a slab in 3D) has its far side within the search distance of the slave; that side
//! faces away (its normal points the same way as the slave's), and projecting it onto the
//! slave as well would count the overlap twice.

use mortar::elements::{LINE2, QUAD4};
use mortar::generate::{line_mesh, square_quads};
use mortar::testing::log_uniform;
use mortar::{assemble_coupling, Interface, SurfaceMesh};
use proptest::prelude::*;

use super::common::{config, max_abs, ok, row_sums, segment_options};

/// The boundary of the strip `[0,1] x [-thickness, 0]`, counter-clockwise (outward normals):
/// the top edge (normal `+y`, facing a slave on `y = 0` whose normal is `-y`), the bottom edge
/// (normal `-y`) and the two short sides.
fn strip(cells: usize, thickness: f64) -> SurfaceMesh {
    let mut m = SurfaceMesh::new();
    let n = cells as u64;
    for i in 0..=n {
        let x = i as f64 / cells as f64;
        m.add_node(i + 1, [x, -thickness, 0.0]).unwrap();
        m.add_node(1000 + i, [x, 0.0, 0.0]).unwrap();
    }
    for i in 0..n {
        m.add_face(&LINE2, &[i + 1, i + 2]).unwrap();
    }
    m.add_face(&LINE2, &[n + 1, 1000 + n]).unwrap();
    for i in (0..n).rev() {
        m.add_face(&LINE2, &[1000 + i + 1, 1000 + i]).unwrap();
    }
    m.add_face(&LINE2, &[1000, 1]).unwrap();
    m
}

/// The top (`z = 0`, normal `+z`) and bottom (`z = -thickness`, normal `-z`) faces of the slab
/// `[0,1]^2 x [-thickness, 0]`.
fn slab(cells: usize, thickness: f64) -> SurfaceMesh {
    let top = square_quads(cells, 0.0, false, 1).unwrap();
    let bottom = square_quads(cells, -thickness, true, 1).unwrap();
    let mut m = SurfaceMesh::new();
    let offset = 10_000;
    for (mesh, shift) in [(&top, 0), (&bottom, offset)] {
        for (t, x) in mesh.node_tags().iter().zip(mesh.coords()) {
            m.add_node(t + shift, (*x).into()).unwrap();
        }
    }
    for (mesh, shift) in [(&top, 0), (&bottom, offset)] {
        for f in 0..mesh.face_count() {
            let tags: Vec<u64> = mesh
                .face(f)
                .nodes
                .iter()
                .map(|&n| mesh.node_tags()[n as usize] + shift)
                .collect();
            m.add_face(&QUAD4, &tags).unwrap();
        }
    }
    m
}

fn check_single_cover(
    slave: SurfaceMesh,
    master: SurfaceMesh,
    dual: bool,
) -> Result<(), TestCaseError> {
    let interface = ok(Interface::new(slave, master))?;
    let coupling = ok(assemble_coupling(&interface, &segment_options(dual)))?;
    let d1 = row_sums(&coupling.d);
    let m1 = row_sums(&coupling.m);
    let scale = max_abs(&d1);
    for (a, b) in d1.iter().zip(&m1) {
        prop_assert!((a - b).abs() <= 1e-12 * scale);
    }
    prop_assert!(
        (coupling.stats.area - 1.0).abs() <= 1e-12,
        "coupled area {} of a unit slave ({} pairs)",
        coupling.stats.area,
        coupling.stats.pairs
    );
    Ok(())
}

proptest! {
    #![proptest_config(config(32))]

    #[test]
    fn thin_strip_couples_only_its_facing_side_2d(
        thickness in log_uniform(1e-3, 1.0),
        (ns, nm) in (1..=6usize, 1..=7usize),
        dual in any::<bool>(),
    ) {
        // line_mesh without flip runs to +x: normal -y, towards the strip below.
        check_single_cover(line_mesh(ns, false, 1).unwrap(), strip(nm, thickness), dual)?;
    }

    #[test]
    fn thin_slab_couples_only_its_facing_side_3d(
        thickness in log_uniform(1e-3, 1.0),
        (ns, nm) in (1..=5usize, 1..=6usize),
        dual in any::<bool>(),
    ) {
        // Slave normal -z, towards the slab below.
        check_single_cover(square_quads(ns, 0.0, true, 1).unwrap(), slab(nm, thickness), dual)?;
    }
}

/// The smallest cases: a unit slave over a master body 0.01 thick.
#[test]
fn thin_master_bodies_are_not_counted_twice() {
    let interface = Interface::new(line_mesh(4, false, 1).unwrap(), strip(5, 0.01)).unwrap();
    let area_2d = assemble_coupling(&interface, &segment_options(false))
        .unwrap()
        .stats
        .area;
    let interface = Interface::new(square_quads(2, 0.0, true, 1).unwrap(), slab(3, 0.01)).unwrap();
    let area_3d = assemble_coupling(&interface, &segment_options(false))
        .unwrap()
        .stats
        .area;
    assert!(
        (area_2d - 1.0).abs() < 1e-12 && (area_3d - 1.0).abs() < 1e-12,
        "coupled area 2D {area_2d}, 3D {area_3d}; want 1 (the slave's)"
    );
}
