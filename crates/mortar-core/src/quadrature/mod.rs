//! Quadrature rules on the reference domains, with their exact polynomial degree.
//!
//! Triangle and quadrilateral rules are the symmetric, positive-weight Witherden-Vincent rules
//! (through the `fenris-quadrature` crate, mapped onto this toolkit's reference triangle
//! `(0,0), (1,0), (0,1)`); line rules are Gauss-Legendre. (The rules of volume elements are in
//! `mortar-fem`.)

mod rule;

pub use rule::{Quadrature, QuadratureRule};
