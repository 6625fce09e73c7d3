//! Broken files give typed errors that name the file and the place: line (ASCII) or byte
//! offset (binary), group, element or node tag.

use std::path::Path;

use mortar::elements::ElementRegistry;
use mortar::generate::{square_triangles, Diagonal};
use mortar::io::{msh41_bytes, parse_gmsh_surface, Endianness, IoError, Location, MshFormat};

use crate::common::{ascii_text, gmsh_style_file, line_number, replace_line};

fn read(text: impl AsRef<[u8]>, group: Option<&str>) -> IoError {
    parse_gmsh_surface(
        text.as_ref(),
        Path::new("t.msh"),
        group,
        &ElementRegistry::new(),
    )
    .expect_err("the file should be refused")
}

fn small() -> String {
    ascii_text(
        &square_triangles(2, Diagonal::Main, 0.0, false, 1).unwrap(),
        "top",
    )
}

#[test]
fn a_bad_number_names_its_line_and_token() {
    let text = small();
    let bad = replace_line(&text, "0.5 0.5 0", "0.5 0.5x 0");
    let e = read(&bad, None);
    let line = line_number(&bad, "0.5 0.5x 0");
    match &e {
        IoError::Malformed { at, message, .. } => {
            assert_eq!(*at, Location::Line(line));
            assert!(
                message.contains("y coordinate of node 5") && message.contains("0.5x"),
                "{e}"
            );
        }
        _ => panic!("{e:?}"),
    }
    assert!(
        e.to_string().starts_with(&format!("t.msh, line {line}: ")),
        "{e}"
    );
}

#[test]
fn wrong_versions_and_headers_are_refused() {
    let text = small();
    let e = read(text.replace("4.1 0 8", "2.2 0 8"), None);
    assert!(
        matches!(&e, IoError::UnsupportedVersion { version, at: Location::Line(2), .. } if version == "2.2"),
        "{e:?}"
    );
    let e = read(text.replace("4.1 0 8", "4 0 8"), None);
    assert!(matches!(e, IoError::UnsupportedVersion { .. }), "{e:?}");
    let e = read(text.replace("$MeshFormat\n", "$MeshFormal\n"), None);
    assert!(
        e.to_string().contains("not a Gmsh MSH file") && e.to_string().contains("line 1"),
        "{e}"
    );
    let e = read(text.replace("4.1 0 8", "4.1 0 4"), None);
    assert!(e.to_string().contains("data size must be 8"), "{e}");
    let e = read("", None);
    assert!(
        matches!(e, IoError::Malformed { .. } | IoError::Truncated { .. }),
        "{e:?}"
    );
}

#[test]
fn truncated_files_say_where_they_end() {
    let text = small();
    let cut = &text[..text.find("$EndNodes").unwrap() - 10];
    let e = read(cut, None);
    let lines = cut.lines().count();
    assert!(
        matches!(&e, IoError::Truncated { at: Location::Line(l), .. } if *l == lines),
        "{e:?}"
    );
    let mesh = square_triangles(2, Diagonal::Main, 0.0, false, 1).unwrap();
    let bytes = msh41_bytes(&[(&mesh, "top")], MshFormat::Binary(Endianness::Big)).unwrap();
    let cut = &bytes[..bytes.len() - 40];
    let e = read(cut, None);
    assert!(
        matches!(&e, IoError::Truncated { at: Location::Offset(o), .. } if *o == cut.len()),
        "{e:?}"
    );
    assert!(
        e.to_string()
            .contains(&format!("byte offset {}", cut.len())),
        "{e}"
    );
}

#[test]
fn binary_errors_give_byte_offsets() {
    let mesh = square_triangles(2, Diagonal::Main, 0.0, false, 1).unwrap();
    let mut bytes = msh41_bytes(&[(&mesh, "top")], MshFormat::Binary(Endianness::Little)).unwrap();
    // The endianness marker follows "4.1 1 8\n".
    let marker = bytes.windows(8).position(|w| w == b"4.1 1 8\n").unwrap() + 8;
    bytes[marker] = 7;
    let e = read(&bytes, None);
    assert!(
        matches!(&e, IoError::Malformed { at: Location::Offset(o), .. } if *o == marker),
        "{e:?}"
    );
    // A node count larger than the file is an error, not an allocation.
    let mut bytes = msh41_bytes(&[(&mesh, "top")], MshFormat::Binary(Endianness::Little)).unwrap();
    let nodes = bytes.windows(7).position(|w| w == b"$Nodes\n").unwrap() + 7;
    bytes[nodes + 8..nodes + 16].copy_from_slice(&u64::MAX.to_le_bytes());
    let e = read(&bytes, None);
    assert!(
        matches!(&e, IoError::Malformed { at: Location::Offset(o), .. } if *o == nodes + 8),
        "{e:?}"
    );
}

#[test]
fn undefined_and_non_finite_nodes_name_the_node() {
    let text = small();
    // Element 1 is "1 1 2 5": make it refer to node 99.
    let bad = replace_line(&text, "1 1 2 5", "1 1 2 99");
    match read(&bad, None) {
        IoError::UndefinedNode {
            at, element, node, ..
        } => {
            assert_eq!(
                (at, element, node),
                (Location::Line(line_number(&bad, "1 1 2 99")), 1, 99)
            );
        }
        e => panic!("{e:?}"),
    }
    let bad = replace_line(&text, "0.5 0.5 0", "nan 0.5 0");
    match read(&bad, None) {
        IoError::NonFiniteCoordinate { at, node, .. } => {
            assert_eq!(
                (at, node),
                (Location::Line(line_number(&bad, "nan 0.5 0")), 5)
            );
        }
        e => panic!("{e:?}"),
    }
    // An element line with a node missing.
    let bad = replace_line(&text, "1 1 2 5", "1 1 2");
    let e = read(&bad, None);
    assert!(
        e.to_string()
            .contains("element 1 has 2 node tags, but a 3-node triangle"),
        "{e}"
    );
}

#[test]
fn group_errors_name_the_group() {
    let text = gmsh_style_file(true, 2);
    match read(&text, Some("nope")) {
        IoError::GroupNotFound {
            group, available, ..
        } => {
            assert_eq!(group, "nope");
            assert!(
                available.iter().any(|a| a.contains("\"face\"")),
                "{available:?}"
            );
        }
        e => panic!("{e:?}"),
    }
    assert!(matches!(
        read(&text, Some("vol")),
        IoError::GroupDimension { dim: 3, .. }
    ));
    assert!(matches!(read(&text, None), IoError::GroupRequired { .. }));
    let e = read(gmsh_style_file(true, 21), Some("face"));
    match &e {
        IoError::UnsupportedElement {
            element,
            element_type,
            at,
            ..
        } => {
            assert_eq!((*element, *element_type), (3, 21));
            assert_eq!(
                *at,
                Location::Line(line_number(
                    &gmsh_style_file(true, 21),
                    "3 1 2 3 4 5 6 7 8 1 2"
                ))
            );
        }
        _ => panic!("{e:?}"),
    }
    assert!(e.to_string().contains("10-node triangle"), "{e}");
    // Cubic elements are not shipped: the message says how to mesh at order one or two, or
    // to register one's own element.
    assert!(e.to_string().contains("gmsh -order 2"), "{e}");
    assert!(e.to_string().contains("examples/extend_element.rs"), "{e}");
}

#[test]
fn no_prefix_or_corrupted_byte_makes_the_reader_panic() {
    let registry = ElementRegistry::new();
    let mesh = square_triangles(1, Diagonal::Main, 0.0, false, 1).unwrap();
    for format in [
        MshFormat::Ascii,
        MshFormat::Binary(Endianness::Little),
        MshFormat::Binary(Endianness::Big),
    ] {
        let bytes = msh41_bytes(&[(&mesh, "top")], format).unwrap();
        let end = bytes
            .windows(12)
            .rposition(|w| w == b"$EndElements")
            .unwrap();
        for cut in 0..bytes.len() {
            let r = parse_gmsh_surface(&bytes[..cut], Path::new("p.msh"), Some("top"), &registry);
            assert!(
                cut >= end + 12 || r.is_err(),
                "prefix of {cut} bytes accepted"
            );
        }
        for at in 0..bytes.len() {
            for b in [0u8, 0xff, b'9', b' ', b'\n', b'-', b'$'] {
                let mut bad = bytes.clone();
                bad[at] = b;
                // Any result but a panic.
                let _ = parse_gmsh_surface(&bad, Path::new("p.msh"), Some("top"), &registry);
                let _ = parse_gmsh_surface(&bad, Path::new("p.msh"), None, &registry);
            }
        }
    }
}
