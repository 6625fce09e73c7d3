//! Gmsh element type numbers: node counts (a binary file cannot be read without them) and
//! names for messages. From Gmsh's `GmshDefines.h`.

/// `(type, shape, nodes)` for the Gmsh element types of fixed node count.
const TYPES: &[(i32, &str, usize)] = &[
    (1, "line", 2),
    (2, "triangle", 3),
    (3, "quadrangle", 4),
    (4, "tetrahedron", 4),
    (5, "hexahedron", 8),
    (6, "prism", 6),
    (7, "pyramid", 5),
    (8, "line", 3),
    (9, "triangle", 6),
    (10, "quadrangle", 9),
    (11, "tetrahedron", 10),
    (12, "hexahedron", 27),
    (13, "prism", 18),
    (14, "pyramid", 14),
    (15, "point", 1),
    (16, "quadrangle", 8),
    (17, "hexahedron", 20),
    (18, "prism", 15),
    (19, "pyramid", 13),
    (20, "triangle", 9),
    (21, "triangle", 10),
    (22, "triangle", 12),
    (23, "triangle", 15),
    (24, "triangle", 15),
    (25, "triangle", 21),
    (26, "line", 4),
    (27, "line", 5),
    (28, "line", 6),
    (29, "tetrahedron", 20),
    (30, "tetrahedron", 35),
    (31, "tetrahedron", 56),
    (32, "tetrahedron", 22),
    (33, "tetrahedron", 28),
    (36, "quadrangle", 16),
    (37, "quadrangle", 25),
    (38, "quadrangle", 36),
    (39, "quadrangle", 12),
    (40, "quadrangle", 16),
    (41, "quadrangle", 20),
    (42, "triangle", 28),
    (43, "triangle", 36),
    (44, "triangle", 45),
    (45, "triangle", 55),
    (46, "triangle", 66),
    (47, "quadrangle", 49),
    (48, "quadrangle", 64),
    (49, "quadrangle", 81),
    (50, "quadrangle", 100),
    (51, "quadrangle", 121),
    (52, "triangle", 18),
    (53, "triangle", 21),
    (54, "triangle", 24),
    (55, "triangle", 27),
    (56, "triangle", 30),
    (57, "quadrangle", 24),
    (58, "quadrangle", 28),
    (59, "quadrangle", 32),
    (60, "quadrangle", 36),
    (61, "quadrangle", 40),
    (62, "line", 7),
    (63, "line", 8),
    (64, "line", 9),
    (65, "line", 10),
    (66, "line", 11),
    (71, "tetrahedron", 84),
    (72, "tetrahedron", 120),
    (73, "tetrahedron", 165),
    (74, "tetrahedron", 220),
    (75, "tetrahedron", 286),
    (79, "tetrahedron", 34),
    (80, "tetrahedron", 40),
    (81, "tetrahedron", 46),
    (82, "tetrahedron", 52),
    (83, "tetrahedron", 58),
    (84, "line", 1),
    (85, "triangle", 1),
    (86, "quadrangle", 1),
    (87, "tetrahedron", 1),
    (88, "hexahedron", 1),
    (89, "prism", 1),
    (90, "prism", 40),
    (91, "prism", 75),
    (92, "hexahedron", 64),
    (93, "hexahedron", 125),
    (94, "hexahedron", 216),
    (95, "hexahedron", 343),
    (96, "hexahedron", 512),
    (97, "hexahedron", 729),
    (98, "hexahedron", 1000),
    (99, "hexahedron", 32),
    (100, "hexahedron", 44),
    (101, "hexahedron", 56),
    (102, "hexahedron", 68),
    (103, "hexahedron", 80),
    (104, "hexahedron", 92),
    (105, "hexahedron", 104),
    (106, "prism", 126),
    (107, "prism", 196),
    (108, "prism", 288),
    (109, "prism", 405),
    (110, "prism", 550),
    (111, "prism", 24),
    (112, "prism", 33),
    (113, "prism", 42),
    (114, "prism", 51),
    (115, "prism", 60),
    (116, "prism", 69),
    (117, "prism", 78),
    (118, "pyramid", 30),
    (119, "pyramid", 55),
    (120, "pyramid", 91),
    (121, "pyramid", 140),
    (122, "pyramid", 204),
    (123, "pyramid", 285),
    (124, "pyramid", 385),
    (125, "pyramid", 21),
    (126, "pyramid", 29),
    (127, "pyramid", 37),
    (128, "pyramid", 45),
    (129, "pyramid", 53),
    (130, "pyramid", 61),
    (131, "pyramid", 69),
    (132, "pyramid", 1),
    (137, "tetrahedron", 16),
    (140, "trihedron", 4),
];

fn entry(element_type: i32) -> Option<&'static (i32, &'static str, usize)> {
    TYPES.iter().find(|e| e.0 == element_type)
}

/// The node count of a Gmsh element type, if it is fixed and known.
pub(super) fn node_count(element_type: i32) -> Option<usize> {
    entry(element_type).map(|e| e.2)
}

/// A description such as `6-node triangle`.
pub(super) fn type_name(element_type: i32) -> String {
    match entry(element_type) {
        Some((15, _, _)) => "point".to_string(),
        Some((_, shape, n)) => format!("{n}-node {shape}"),
        None => "unknown type".to_string(),
    }
}

/// Whether a Gmsh element type is of order two or more: more nodes than its corners.
pub(super) fn is_higher_order(element_type: i32) -> bool {
    let corners = |shape: &str| match shape {
        "line" => 2,
        "triangle" => 3,
        "quadrangle" | "tetrahedron" => 4,
        "pyramid" => 5,
        "prism" => 6,
        "hexahedron" => 8,
        _ => usize::MAX,
    };
    entry(element_type).is_some_and(|(_, shape, n)| *n > corners(shape))
}

/// Advice for an unsupported element type: for a higher-order one (the shipped elements stop
/// at order two, without second-order prisms and pyramids), how to mesh at a shipped order.
pub(crate) fn unsupported_hint(element_type: i32) -> String {
    if is_higher_order(element_type) {
        "; elements of order one and two (lines, triangles, quadrangles, tetrahedra, \
         hexahedra) are shipped: mesh at one of those orders (`gmsh -order 2`, or \
         Mesh.ElementOrder = 2), or register your own element (mortar::extend::Registries, \
         mortar_app::cli::main_with; see examples/extend_element.rs)"
            .to_string()
    } else {
        String::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn higher_order_types_get_the_order_hint() {
        for t in [8, 9, 10, 11, 16, 17, 21, 26] {
            assert!(is_higher_order(t), "type {t}");
            assert!(unsupported_hint(t).contains("gmsh -order 2"));
        }
        for t in [1, 2, 3, 4, 5, 15] {
            assert!(!is_higher_order(t), "type {t}");
            assert!(unsupported_hint(t).is_empty());
        }
    }
}
