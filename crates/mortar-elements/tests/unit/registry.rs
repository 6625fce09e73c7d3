//! The element registry: built-in elements by Gmsh type and name; registering replaces an
//! element of the same Gmsh type.

use mortar_core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
use mortar_elements::{ElementRegistry, QUAD4};
use nalgebra::Vector2;

#[test]
fn built_in_elements_are_found_by_type_and_name() {
    let r = ElementRegistry::new();
    assert_eq!(r.elements().len(), 7);
    for (t, name) in [
        (1, "Line2"),
        (2, "Tri3"),
        (3, "Quad4"),
        (8, "Line3"),
        (9, "Tri6"),
        (16, "Quad8"),
        (10, "Quad9"),
    ] {
        assert_eq!(r.by_gmsh_type(t).unwrap().name(), name);
        assert_eq!(r.by_name(name).unwrap().gmsh_type(), Some(t));
    }
    assert!(r.by_gmsh_type(21).is_none());
    assert!(r.by_name("Tri10").is_none());
}

/// A Quad4 under another name, to check replacement by Gmsh type.
#[derive(Debug)]
struct MyQuad;

impl ReferenceElement for MyQuad {
    fn name(&self) -> &'static str {
        "MyQuad"
    }
    fn domain(&self) -> ReferenceDomain {
        QUAD4.domain()
    }
    fn node_count(&self) -> usize {
        4
    }
    fn corner_count(&self) -> usize {
        4
    }
    fn shape_degree(&self) -> u32 {
        2
    }
    fn node_reference_coords(&self) -> &'static [[f64; 2]] {
        QUAD4.node_reference_coords()
    }
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
        QUAD4.shape_values_into(xi, out)
    }
    fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        QUAD4.shape_gradients_into(xi, out)
    }
}

impl SurfaceElement for MyQuad {
    fn gmsh_type(&self) -> Option<u32> {
        Some(3)
    }
}

static MY_QUAD: MyQuad = MyQuad;

#[test]
fn registering_replaces_the_same_gmsh_type() {
    let mut r = ElementRegistry::new();
    r.register(&MY_QUAD);
    assert_eq!(r.elements().len(), 7);
    assert_eq!(r.by_gmsh_type(3).unwrap().name(), "MyQuad");
    assert!(r.by_name("Quad4").is_none());
    assert_eq!(r.by_gmsh_type(2).unwrap().name(), "Tri3");
}
