//! # mortar-elements
//!
//! Concrete surface elements for the mortar toolkit: [`Line2`] and [`Line3`] (2D), [`Tri3`],
//! [`Quad4`], [`Tri6`], [`Quad8`] and [`Quad9`] (3D), and an [`ElementRegistry`] that maps Gmsh
//! element types to them; and, in [`volume`], the cells of the bodies: Tri3, Quad4, Tri6,
//! Quad8 and Quad9 (2D), Tet4, Hex8, Tet10, Hex20 and Hex27 (3D).
//!
//! The cells implement the volume element trait of `mortar-fem` (their faces are the surface
//! elements here); the feature `volume` (on by default) brings them. Without it the crate
//! depends on `mortar-core` alone: no solver, no C build.
//!
//! Reference domains: line `[-1, 1]`; triangle `(0,0), (1,0), (0,1)`; quad `[-1, 1]^2`.
//! Node order follows Gmsh.
//!
//! ## Adding an element
//!
//! The elements shipped here are each a table: the node coordinates, the family of the shape
//! functions (one formula per node for any dimension, or the barycentric ones of the
//! simplices), the corner count, the degree, the Gmsh type and, for a cell, its faces; a
//! macro of the crate writes the type and its trait impls from it, so that a new built-in
//! element is its nodes and little more, and a 2D cell shares the shape functions of the
//! interface face of the same shape.
//!
//! A program's own element is one new type implementing
//! [`ReferenceElement`](mortar_core::element::ReferenceElement) and
//! [`SurfaceElement`](mortar_core::element::SurfaceElement) (or a [`LagrangeFace`], from its
//! nodes alone); nothing else changes. A three-node quadratic line, say:
//!
//! ```
//! use mortar_core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
//! use nalgebra::Vector2;
//!
//! #[derive(Debug)]
//! pub struct Line3;
//!
//! impl ReferenceElement for Line3 {
//!     fn name(&self) -> &'static str { "Line3" }
//!     fn domain(&self) -> ReferenceDomain { ReferenceDomain::Line }
//!     fn node_count(&self) -> usize { 3 }
//!     fn corner_count(&self) -> usize { 2 }
//!     fn shape_degree(&self) -> u32 { 2 }
//!     // Gmsh order: the two ends, then the middle node.
//!     fn node_reference_coords(&self) -> &'static [[f64; 2]] {
//!         &[[-1.0, 0.0], [1.0, 0.0], [0.0, 0.0]]
//!     }
//!     fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
//!         let x = xi.x;
//!         out[0] = 0.5 * x * (x - 1.0);
//!         out[1] = 0.5 * x * (x + 1.0);
//!         out[2] = 1.0 - x * x;
//!     }
//!     fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
//!         let x = xi.x;
//!         out[0] = [x - 0.5, 0.0];
//!         out[1] = [x + 0.5, 0.0];
//!         out[2] = [-2.0 * x, 0.0];
//!     }
//! }
//!
//! impl SurfaceElement for Line3 {
//!     fn gmsh_type(&self) -> Option<u32> { Some(8) }
//! }
//!
//! static LINE3: Line3 = Line3;
//! let mut registry = mortar_elements::ElementRegistry::new();
//! registry.register(&LINE3);
//! assert_eq!(registry.by_gmsh_type(8).unwrap().name(), "Line3");
//! ```

// What a run has to say goes into its results; only the command-line program prints.
#![cfg_attr(
    not(test),
    deny(clippy::print_stdout, clippy::print_stderr, clippy::dbg_macro)
)]

mod lagrange;
mod line2;
mod line3;
mod quad4;
mod quad8;
mod quad9;
mod registry;
mod shape;
mod table;
mod tri3;
mod tri6;
#[cfg(feature = "volume")]
pub mod volume;

#[cfg(feature = "volume")]
pub use lagrange::LagrangeCell;
pub use lagrange::{LagrangeError, LagrangeFace};
pub use line2::{Line2, LINE2};
pub use line3::{Line3, LINE3};
pub use quad4::{Quad4, QUAD4};
pub use quad8::{Quad8, QUAD8};
pub use quad9::{Quad9, QUAD9};
pub use registry::ElementRegistry;
pub use tri3::{Tri3, TRI3};
pub use tri6::{Tri6, TRI6};
