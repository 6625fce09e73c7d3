//! What every field of a body shares, scalar (a temperature) or vector (a displacement): the
//! numbering of its unknowns, `node * components + component` ([`DofLayout`]), the choice of
//! components a condition applies to ([`ComponentSet`]), and the set-up of a cell for the
//! assemblies. The tie of two bodies serves a field of any number of components the same way
//! ([`Tie::with_components`](crate::tied::Tie::with_components)).

pub(crate) mod cells;
mod dofs;
pub(crate) mod free;

pub use dofs::{ComponentSet, DofLayout};
