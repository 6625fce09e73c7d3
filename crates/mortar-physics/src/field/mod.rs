//! What every field of a body shares, scalar (a temperature) or vector (a displacement): the
//! numbering of its unknowns and the components a condition applies to (from
//! [`mortar_fem::field`]), and the set-up of a cell for the assemblies. The tie of two bodies
//! serves a field of any number of components the same way
//! ([`Tie::with_components`](crate::tied::Tie::with_components)).

pub(crate) mod cells;
pub(crate) use mortar_fem::field::free;

pub use mortar_fem::field::{ComponentSet, DofLayout, FieldError};
