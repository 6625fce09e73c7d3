//! `VolumeRegistry`: volume elements by Gmsh type number (per reference dimension) and by
//! name, the built-in cells first, user cells added with `register`.

use mortar_fem::element::{VolumeElement, VolumeElementRef};

use super::{HEX20, HEX27, HEX8, QUAD4, QUAD8, QUAD9, TET10, TET4, TRI3, TRI6};

/// Maps Gmsh element types to volume elements, per reference dimension (Gmsh type 2 is a
/// triangle cell in a 2D mesh and an interface face in a 3D one). Starts with the built-in
/// cells; register your own with [`VolumeRegistry::register`].
#[derive(Debug, Clone)]
pub struct VolumeRegistry {
    elements: Vec<VolumeElementRef>,
}

impl Default for VolumeRegistry {
    fn default() -> Self {
        Self {
            elements: vec![
                &TRI3, &QUAD4, &TET4, &HEX8, &TRI6, &QUAD8, &QUAD9, &TET10, &HEX20, &HEX27,
            ],
        }
    }
}

impl VolumeRegistry {
    /// A registry of the built-in cells (Tri3, Quad4, Tet4, Hex8, Tri6, Quad8, Quad9, Tet10,
    /// Hex20, Hex27).
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds (or replaces, for the same Gmsh type and dimension) an element.
    pub fn register(&mut self, element: VolumeElementRef) {
        if let Some(t) = element.gmsh_type() {
            self.elements
                .retain(|e| e.gmsh_type() != Some(t) || e.dim() != element.dim());
        }
        self.elements.push(element);
    }

    /// Registers a cell built at run time (a [`LagrangeCell`](crate::LagrangeCell), say) and
    /// gives it back as the `&'static` reference meshes hold: the cell is moved to the heap and
    /// kept for the rest of the program (register each one once, not in a loop).
    pub fn add(&mut self, element: impl VolumeElement + 'static) -> VolumeElementRef {
        let element: VolumeElementRef = Box::leak(Box::new(element));
        self.register(element);
        element
    }

    /// The element of a Gmsh type number in a mesh of reference dimension `dim`.
    pub fn by_gmsh_type(&self, gmsh_type: u32, dim: usize) -> Option<VolumeElementRef> {
        self.elements
            .iter()
            .copied()
            .find(|e| e.gmsh_type() == Some(gmsh_type) && e.dim() == dim)
    }

    /// The element with a name.
    pub fn by_name(&self, name: &str) -> Option<VolumeElementRef> {
        self.elements.iter().copied().find(|e| e.name() == name)
    }

    /// All registered elements.
    pub fn elements(&self) -> &[VolumeElementRef] {
        &self.elements
    }
}
