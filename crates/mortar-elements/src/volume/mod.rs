//! Volume elements (the cells of the bodies): [`Tri3`], [`Quad4`], [`Tri6`], [`Quad8`] and
//! [`Quad9`] for 2D bodies in the plane `z = 0`, [`Tet4`], [`Hex8`], [`Tet10`], [`Hex20`] and
//! [`Hex27`] for 3D bodies, and a [`VolumeRegistry`] of them by Gmsh type and dimension.
//!
//! Reference domains: triangle `(0,0), (1,0), (0,1)`; quad `[-1, 1]^2`; tetrahedron
//! `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`; hexahedron `[-1, 1]^3`. Node order follows Gmsh, and
//! each element's faces are listed with outward normals (see
//! [`VolumeElement::faces`](mortar_fem::element::VolumeElement::faces)).
//!
//! The names repeat those of the surface elements of the crate root (a 2D body's triangle is
//! a `volume::Tri3`, an interface triangle in 3D a [`crate::Tri3`]); the 2D cells use the node
//! tables and shape functions of the surface elements of the same shape.
//!
//! ```
//! use mortar_fem::element::VolumeElement;
//! use mortar_elements::volume::HEX8;
//! let mut n = [0.0; 8];
//! HEX8.shape_values_into(&nalgebra::Vector3::new(0.2, -0.4, 0.9), &mut n);
//! assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
//! assert_eq!(HEX8.faces().len(), 6);
//! ```

mod hex20;
mod hex27;
mod hex8;
mod planar;
mod registry;
mod tet10;
mod tet4;

pub use hex20::{Hex20, HEX20};
pub use hex27::{Hex27, HEX27};
pub use hex8::{Hex8, HEX8};
pub use planar::{Quad4, Quad8, Quad9, Tri3, Tri6, QUAD4, QUAD8, QUAD9, TRI3, TRI6};
pub use registry::VolumeRegistry;
pub use tet10::{Tet10, TET10};
pub use tet4::{Tet4, TET4};
