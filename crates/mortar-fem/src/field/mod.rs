//! What every nodal field of a body shares, scalar (a temperature) or vector (a
//! displacement): the numbering of its unknowns, `node * components + component`
//! ([`DofLayout`]), the choice of components a condition applies to ([`ComponentSet`]), and
//! the numbering of the unknowns a set of prescribed values leaves free ([`free`]).

mod dofs;
pub mod free;
#[cfg(test)]
mod tests;

pub use dofs::{ComponentSet, DofLayout};

/// What is wrong with a component set or a node list for a [`DofLayout`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum FieldError {
    /// A component name that is none of x, y, z, all.
    #[error("unknown component {text:?}: expected x, y, z or all")]
    UnknownComponent {
        /// The text given.
        text: String,
    },
    /// A component beyond the field's components.
    #[error(
        "component {name} ({component}) does not exist: the field has {components} component(s)"
    )]
    NoSuchComponent {
        /// Its name (x, y, z, or its number).
        name: String,
        /// Its index.
        component: usize,
        /// The field's number of components.
        components: usize,
    },
    /// More unknowns than `u32` numbers.
    #[error("{nodes} nodes x {components} components do not fit u32 unknown numbers")]
    TooLarge {
        /// The layout's nodes.
        nodes: usize,
        /// Its components per node.
        components: usize,
    },
    /// A node index beyond the layout.
    #[error("node index {node} is beyond the layout's {nodes} nodes")]
    NodeBeyondLayout {
        /// The index given.
        node: u32,
        /// The layout's nodes.
        nodes: usize,
    },
}
