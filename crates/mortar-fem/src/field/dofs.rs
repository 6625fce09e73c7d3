//! Numbering of a nodal field's unknowns (`DofLayout`: `node * components + k`) and
//! `ComponentSet`, the components a condition acts on.

use std::fmt;
use std::str::FromStr;

use super::FieldError;

/// Which components of a nodal field a condition acts on.
///
/// Parsed from `"x"`, `"y"`, `"z"` (components 0, 1, 2) or `"all"` (case-insensitive,
/// surrounding white space ignored):
///
/// ```
/// use mortar_fem::field::ComponentSet;
/// assert_eq!("y".parse::<ComponentSet>().unwrap(), ComponentSet::One(1));
/// assert!("w".parse::<ComponentSet>().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ComponentSet {
    /// Every component.
    All,
    /// One component (0 = x, 1 = y, 2 = z).
    One(usize),
}

impl ComponentSet {
    /// Whether component `c` is in the set.
    pub fn contains(self, c: usize) -> bool {
        match self {
            ComponentSet::All => true,
            ComponentSet::One(k) => k == c,
        }
    }

    /// The components of the set among `0..components`, ascending.
    pub fn components(self, components: usize) -> impl Iterator<Item = usize> {
        (0..components).filter(move |&c| self.contains(c))
    }

    /// Checks that the set fits a field of `components` components.
    ///
    /// # Errors
    /// [`FieldError::NoSuchComponent`] (saying which component and how many there are) if
    /// the set is `One(c)` with `c >= components`.
    pub fn fits(self, components: usize) -> Result<(), FieldError> {
        match self {
            ComponentSet::One(c) if c >= components => Err(FieldError::NoSuchComponent {
                name: component_name(c),
                component: c,
                components,
            }),
            _ => Ok(()),
        }
    }
}

/// `"x"`, `"y"`, `"z"`, or the number for a higher component.
fn component_name(c: usize) -> String {
    match c {
        0 => "x".into(),
        1 => "y".into(),
        2 => "z".into(),
        c => c.to_string(),
    }
}

impl fmt::Display for ComponentSet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ComponentSet::All => f.write_str("all"),
            ComponentSet::One(c) => f.write_str(&component_name(*c)),
        }
    }
}

impl FromStr for ComponentSet {
    type Err = FieldError;

    /// # Errors
    /// [`FieldError::UnknownComponent`] for anything but x, y, z or all.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "x" => Ok(ComponentSet::One(0)),
            "y" => Ok(ComponentSet::One(1)),
            "z" => Ok(ComponentSet::One(2)),
            "all" => Ok(ComponentSet::All),
            _ => Err(FieldError::UnknownComponent {
                text: s.to_string(),
            }),
        }
    }
}

/// The numbering of the unknowns of a nodal field with `components` components per node,
/// interleaved by node: `dof = node * components + component`. A scalar field (temperature)
/// has one component, so that its unknowns are the node indices; a displacement field has
/// the mesh's dimension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct DofLayout {
    /// Number of nodes.
    pub nodes: usize,
    /// Components per node.
    pub components: usize,
}

impl DofLayout {
    /// The layout of `nodes` nodes with `components` components each.
    pub fn new(nodes: usize, components: usize) -> Self {
        Self { nodes, components }
    }

    /// The unknown of component `comp` at node `node`: `node * components + comp`.
    ///
    /// Does not check its arguments: callers keep `node < nodes`, `comp < components`, and
    /// [`len`](Self::len) within `u32` (see [`fits_u32`](Self::fits_u32)).
    #[inline]
    pub fn dof(&self, node: u32, comp: usize) -> u32 {
        node * self.components as u32 + comp as u32
    }

    /// The node and component of unknown `dof` (the inverse of [`dof`](Self::dof)).
    ///
    /// # Panics
    /// If the layout has no components.
    #[inline]
    pub fn node_component(&self, dof: u32) -> (u32, usize) {
        let k = self.components as u32;
        (dof / k, (dof % k) as usize)
    }

    /// Number of unknowns, `nodes * components`.
    pub fn len(&self) -> usize {
        self.nodes * self.components
    }

    /// Whether there is no unknown.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether every unknown can be numbered by a `u32` (as the sparse matrices do).
    pub fn fits_u32(&self) -> bool {
        self.nodes
            .checked_mul(self.components)
            .is_some_and(|n| n <= u32::MAX as usize + 1)
    }

    /// The unknowns of the components `set` at the nodes `nodes`, node by node in the order
    /// given, components ascending within a node.
    ///
    /// # Errors
    /// [`FieldError::NoSuchComponent`] for a component set that does not fit the layout,
    /// [`FieldError::TooLarge`] for a layout too large for `u32` numbering,
    /// [`FieldError::NodeBeyondLayout`] for a node index beyond it.
    pub fn expand_nodes(&self, nodes: &[u32], set: ComponentSet) -> Result<Vec<u32>, FieldError> {
        set.fits(self.components)?;
        if !self.fits_u32() {
            return Err(FieldError::TooLarge {
                nodes: self.nodes,
                components: self.components,
            });
        }
        if let Some(&bad) = nodes.iter().find(|&&n| n as usize >= self.nodes) {
            return Err(FieldError::NodeBeyondLayout {
                node: bad,
                nodes: self.nodes,
            });
        }
        let per_node = set.components(self.components).count();
        let mut out = Vec::with_capacity(nodes.len() * per_node);
        for &n in nodes {
            out.extend(set.components(self.components).map(|c| self.dof(n, c)));
        }
        Ok(out)
    }
}
