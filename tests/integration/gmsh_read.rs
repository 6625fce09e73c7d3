//! Reading Gmsh 4.1 files: ASCII and binary agree, groups select the right faces, only the
//! nodes in use are kept, tags are preserved.

use std::path::Path;

use mortar::elements::ElementRegistry;
use mortar::generate::{line_mesh, square_quads, square_triangles, Diagonal};
use mortar::io::{
    parse_gmsh_surface, parse_interface_arg, read_gmsh_surface, read_surface, write_msh41,
    write_msh41_ascii, write_msh41_binary, Endianness, IoError, MshFormat,
};
use mortar::SurfaceMesh;

use crate::common::{gmsh_style_file, offset_tags, TempDir};

/// Everything a reader must reproduce: node tags and coordinates, face tags, element types
/// and face node tags, in the mesh's own order.
fn assert_same_mesh(a: &SurfaceMesh, b: &SurfaceMesh) {
    assert_eq!(a.node_count(), b.node_count());
    assert_eq!(a.face_count(), b.face_count());
    // Readers order nodes by tag; compare as maps.
    let mut na: Vec<(u64, [f64; 3])> = a
        .node_tags()
        .iter()
        .zip(a.coords())
        .map(|(t, x)| (*t, [x.x, x.y, x.z]))
        .collect();
    let mut nb: Vec<(u64, [f64; 3])> = b
        .node_tags()
        .iter()
        .zip(b.coords())
        .map(|(t, x)| (*t, [x.x, x.y, x.z]))
        .collect();
    na.sort_by_key(|n| n.0);
    nb.sort_by_key(|n| n.0);
    assert_eq!(na, nb, "nodes differ (bit for bit)");
    let faces = |m: &SurfaceMesh| {
        let mut f: Vec<(u64, &'static str, Vec<u64>)> = (0..m.face_count())
            .map(|i| {
                let v = m.face(i);
                (
                    v.tag,
                    v.element.name(),
                    v.nodes.iter().map(|&n| m.node_tags()[n as usize]).collect(),
                )
            })
            .collect();
        f.sort_by_key(|x| x.0);
        f
    };
    assert_eq!(faces(a), faces(b));
}

fn awkward_mesh() -> SurfaceMesh {
    // Coordinates that do not print short: a rotated, scaled square of quads.
    let mut mesh = offset_tags(&square_quads(3, 0.1, false, 1).unwrap(), 40, 700);
    mesh.transform(|x| {
        let (s, c) = (0.3f64.sin(), 0.3f64.cos());
        nalgebra::Vector3::new(c * x.x - s * x.y, s * x.x + c * x.y, x.z) * (1.0 / 3.0)
            + nalgebra::Vector3::new(1e-7, -2.5e5, 1.0 / 7.0)
    })
    .unwrap();
    mesh
}

#[test]
fn ascii_and_binary_of_both_byte_orders_read_identically() {
    let dir = TempDir::new("formats");
    let registry = ElementRegistry::new();
    for original in [
        awkward_mesh(),
        square_triangles(3, Diagonal::Anti, 0.0, true, 5).unwrap(),
        line_mesh(5, true, 11).unwrap(),
    ] {
        let ascii = dir.join("a.msh");
        let little = dir.join("l.msh");
        let big = dir.join("b.msh");
        write_msh41_ascii(&original, &ascii, "contact").unwrap();
        write_msh41_binary(&original, &little, "contact", Endianness::Little).unwrap();
        write_msh41_binary(&original, &big, "contact", Endianness::Big).unwrap();
        let a = read_gmsh_surface(&ascii, None, &registry).unwrap();
        let l = read_gmsh_surface(&little, Some("contact"), &registry).unwrap();
        let b = read_gmsh_surface(&big, Some("contact"), &registry).unwrap();
        assert!(!a.binary && l.binary && b.binary);
        assert_same_mesh(&a.mesh, &original);
        assert_same_mesh(&l.mesh, &a.mesh);
        assert_same_mesh(&b.mesh, &a.mesh);
        let dim = if original.face(0).element.name() == "Line2" {
            1
        } else {
            2
        };
        assert_eq!((a.dimension, l.dimension, b.dimension), (dim, dim, dim));
        // The binary files really differ in byte order.
        assert_ne!(
            std::fs::read(&little).unwrap(),
            std::fs::read(&big).unwrap()
        );
    }
}

#[test]
fn physical_groups_select_their_faces_and_only_their_nodes() {
    let dir = TempDir::new("groups");
    let slave = square_triangles(2, Diagonal::Main, 0.0, false, 1).unwrap();
    let master = offset_tags(&square_quads(3, 0.0, true, 1).unwrap(), 100, 100);
    let registry = ElementRegistry::new();
    for format in [MshFormat::Ascii, MshFormat::Binary(Endianness::Little)] {
        let path = dir.join("both.msh");
        write_msh41(
            &[(&slave, "slave side"), (&master, "master")],
            &path,
            format,
        )
        .unwrap();
        let s = read_gmsh_surface(&path, Some("slave side"), &registry).unwrap();
        assert_same_mesh(&s.mesh, &slave);
        assert_eq!(s.group.as_ref().map(|g| (g.dim, g.tag)), Some((2, 1)));
        assert_eq!(s.label(), format!("{}#slave side", path.display()));
        let m = read_gmsh_surface(&path, Some("master"), &registry).unwrap();
        assert_same_mesh(&m.mesh, &master);
        // By physical tag.
        let m2 = read_surface(&path, Some("2"), &registry).unwrap();
        assert_same_mesh(&m2, &master);
        // The whole file: every face of dimension 2.
        let all = read_surface(&path, None, &registry).unwrap();
        assert_eq!(all.face_count(), slave.face_count() + master.face_count());
        assert_eq!(all.node_count(), slave.node_count() + master.node_count());
    }
}

#[test]
fn a_file_in_gmsh_style_reads_groups_points_and_parametric_nodes() {
    let registry = ElementRegistry::new();
    let path = Path::new("cube.msh");
    let text = gmsh_style_file(true, 2);
    let face = parse_gmsh_surface(text.as_bytes(), path, Some("face"), &registry).unwrap();
    assert_eq!(face.dimension, 2);
    assert_eq!(face.mesh.face_count(), 2);
    // Only the four bottom nodes, not the cube's top ones; element tags kept.
    assert_eq!(face.mesh.node_tags(), &[1, 2, 3, 4]);
    assert_eq!((face.mesh.face(0).tag, face.mesh.face(1).tag), (3, 4));
    assert_eq!(face.mesh.coords()[2], nalgebra::Vector3::new(1.0, 1.0, 0.0));
    // Where the faces are: lines 38 and 39 of the file.
    let line = |needle: &str| 1 + text.lines().position(|l| l == needle).unwrap();
    assert_eq!(
        face.face_location(4),
        Some(mortar::io::Location::Line(line("4 1 3 4")))
    );

    let edge = parse_gmsh_surface(text.as_bytes(), path, Some("edge"), &registry).unwrap();
    assert_eq!(edge.dimension, 1);
    assert_eq!(edge.mesh.face_count(), 1);
    assert_eq!(edge.mesh.node_tags(), &[1, 2]);
    // Groups by physical tag.
    let by_tag = parse_gmsh_surface(text.as_bytes(), path, Some("20"), &registry).unwrap();
    assert_eq!(by_tag.mesh.face_count(), 2);

    // Without the volume, a flat file of faces and lines is ambiguous (a 3D surface, or a 2D
    // body whose lines are the interface): a group is required, and the error names them.
    let flat = gmsh_style_file(false, 2);
    match parse_gmsh_surface(flat.as_bytes(), path, None, &registry) {
        Err(IoError::GroupRequired { available, .. }) => {
            let all = available.join(" ");
            assert!(
                all.contains("\"edge\"") && all.contains("\"face\""),
                "{all}"
            );
        }
        other => panic!("expected GroupRequired, got {other:?}"),
    }
    let face = parse_gmsh_surface(flat.as_bytes(), path, Some("face"), &registry).unwrap();
    assert_eq!(face.mesh.face_count(), 2);
    assert_eq!(face.dimension, 2);
}

#[test]
fn a_file_of_lines_only_is_a_2d_surface() {
    let dir = TempDir::new("lines");
    let path = dir.join("lines.msh");
    let mesh = line_mesh(4, false, 1).unwrap();
    write_msh41_ascii(&mesh, &path, "bottom").unwrap();
    let read = read_gmsh_surface(&path, None, &ElementRegistry::new()).unwrap();
    assert_eq!(read.dimension, 1);
    assert_same_mesh(&read.mesh, &mesh);
}

#[test]
fn crlf_line_ends_are_read() {
    let mesh = square_triangles(1, Diagonal::Main, 0.0, false, 1).unwrap();
    let text = crate::common::ascii_text(&mesh, "top").replace('\n', "\r\n");
    let read = parse_gmsh_surface(
        text.as_bytes(),
        Path::new("crlf.msh"),
        Some("top"),
        &ElementRegistry::new(),
    )
    .unwrap();
    assert_same_mesh(&read.mesh, &mesh);
}

#[test]
fn interface_arguments_split_at_the_last_hash() {
    let a = parse_interface_arg("dir#1/mesh.msh#top face").unwrap();
    assert_eq!(a.path, Path::new("dir#1/mesh.msh"));
    assert_eq!(a.group.as_deref(), Some("top face"));
    assert_eq!(a.to_string(), "dir#1/mesh.msh#top face");
    let b = parse_interface_arg("mesh.msh").unwrap();
    assert_eq!((b.path.as_path(), b.group), (Path::new("mesh.msh"), None));
    assert!(parse_interface_arg("mesh.msh#").is_err());
    assert!(parse_interface_arg("#top").is_err());
    assert!(parse_interface_arg("").is_err());
}

#[test]
fn matrix_market_values_round_trip_bit_for_bit() {
    let values = vec![
        0.1,
        1.0 / 3.0,
        -2.5e-300,
        6.02214076e23,
        f64::MIN_POSITIVE,
        1.0 - f64::EPSILON,
    ];
    let n = values.len();
    let m = sprs::CsMat::new(
        (n, n + 1),
        (0..=n).collect(),
        (0..n).collect(),
        values.clone(),
    );
    let text = mortar::io::matrix_market::to_string(&m, &["test"]);
    let back: sprs::TriMat<f64> =
        sprs::io::read_matrix_market_from_bufread(&mut text.as_bytes()).unwrap();
    assert_eq!((back.rows(), back.cols(), back.nnz()), (n, n + 1, n));
    for (v, (r, c)) in back.triplet_iter() {
        assert_eq!(r, c);
        assert_eq!(v.to_bits(), values[r].to_bits());
    }
}
