//! `ElementRegistry`: surface elements by Gmsh type number and by name, the built-in ones
//! first, user elements added with `register`.

use mortar_core::element::{ElementRef, SurfaceElement};

use crate::{LINE2, LINE3, QUAD4, QUAD8, QUAD9, TRI3, TRI6};

/// Maps Gmsh element type numbers to surface elements. Starts with the built-in elements;
/// register your own with [`ElementRegistry::register`].
#[derive(Debug, Clone)]
pub struct ElementRegistry {
    elements: Vec<ElementRef>,
}

impl Default for ElementRegistry {
    fn default() -> Self {
        Self {
            elements: vec![&LINE2, &TRI3, &QUAD4, &LINE3, &TRI6, &QUAD8, &QUAD9],
        }
    }
}

impl ElementRegistry {
    /// A registry of the built-in elements (Line2, Tri3, Quad4, Line3, Tri6, Quad8, Quad9).
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds (or replaces, for the same Gmsh type) an element.
    pub fn register(&mut self, element: ElementRef) {
        if let Some(t) = element.gmsh_type() {
            self.elements.retain(|e| e.gmsh_type() != Some(t));
        }
        self.elements.push(element);
    }

    /// Registers an element built at run time (a [`LagrangeFace`](crate::LagrangeFace), say)
    /// and gives it back as the `&'static` reference meshes hold: the element is moved to the
    /// heap and kept for the rest of the program (elements live as long as the meshes that
    /// use them; register each one once, not in a loop).
    pub fn add(&mut self, element: impl SurfaceElement + 'static) -> ElementRef {
        let element: ElementRef = Box::leak(Box::new(element));
        self.register(element);
        element
    }

    /// The element of a Gmsh type number.
    pub fn by_gmsh_type(&self, gmsh_type: u32) -> Option<ElementRef> {
        self.elements
            .iter()
            .copied()
            .find(|e| e.gmsh_type() == Some(gmsh_type))
    }

    /// The element with a name.
    pub fn by_name(&self, name: &str) -> Option<ElementRef> {
        self.elements.iter().copied().find(|e| e.name() == name)
    }

    /// All registered elements.
    pub fn elements(&self) -> &[ElementRef] {
        &self.elements
    }
}
