//! The built-in elements as tables. A built-in element is its node coordinates (Gmsh order,
//! corners first), the family of its shape functions ([`Shapes`](crate::shape::Shapes)) and a
//! few numbers (corners, degree, Gmsh type, and for a cell its faces); [`face_element!`] and
//! [`cell_element!`] turn such a table into the unit type, its shared instance and the trait
//! impls, so that the name, the node count, the node table and the loops of the shape
//! functions over the nodes are written once for all elements. [`concat`] builds a node table
//! from that of the element it refines (Quad9 from Quad8, Hex27 from Hex20) and [`in_plane`]
//! the table of a 2D cell from that of the surface element of the same shape.
//!
//! The tests check each element by hand (they list every type), not through these tables.

/// The unit struct `$name` of an element (documented by the doc comments given) and its shared
/// instance `$instance`, named `$prefix$name` in the instance's documentation.
macro_rules! unit_element {
    ($(#[$doc:meta])* $name:ident, $instance:ident, $prefix:literal) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
        pub struct $name;

        #[doc = concat!("The shared `", $prefix, stringify!($name), "` instance.")]
        pub static $instance: $name = $name;
    };
}
pub(crate) use unit_element;

/// The methods that `ReferenceElement` and `VolumeElement` have alike, from an element's
/// table: the name (that of the type), the node count and table, the shape degree, and the
/// shape values and gradients by the element's family, on reference points of `$width`
/// coordinates (the components `$c` of `xi`).
macro_rules! shared_methods {
    ($name:ident, $degree:literal, $nodes:path, $shapes:expr, $vector:ident, $width:literal,
     [$($c:ident),+]) => {
        fn name(&self) -> &'static str {
            stringify!($name)
        }
        fn node_count(&self) -> usize {
            $nodes.len()
        }
        fn shape_degree(&self) -> u32 {
            $degree
        }
        fn node_reference_coords(&self) -> &'static [[f64; $width]] {
            &$nodes
        }
        #[inline]
        fn shape_values_into(&self, xi: &::nalgebra::$vector<f64>, out: &mut [f64]) {
            $crate::shape::Shapes::values(&$shapes, &$nodes, &[$(xi.$c),+], out);
        }
        #[inline]
        fn shape_gradients_into(&self, xi: &::nalgebra::$vector<f64>, out: &mut [[f64; $width]]) {
            $crate::shape::Shapes::gradients(&$shapes, &$nodes, &[$(xi.$c),+], out);
        }
    };
}
pub(crate) use shared_methods;

/// Declares a built-in surface element from its table: the unit struct `$name` (documented by
/// the doc comments given), its shared instance `$instance`, and its `ReferenceElement` and
/// `SurfaceElement` impls. The table: the reference domain (a `ReferenceDomain` variant), the
/// corner count, the shape degree, the Gmsh type, the node table (a constant
/// `[[f64; 2]; N]`; lines leave the second coordinate zero), the shape family (a `Shapes<2>`
/// value) and, for an element with nodes besides its corners, the node order of the reversed
/// face (`reversed[i]` is the old position of new node `i`; elements of corners alone are
/// reversed by the trait's own method). The geometric map is affine for every placement of the
/// nodes exactly when the degree is 1.
macro_rules! face_element {
    (
        $(#[$doc:meta])*
        $name:ident, $instance:ident: $domain:ident, corners $corners:literal,
        degree $degree:literal, gmsh $gmsh:literal, nodes $nodes:path, shapes $shapes:expr
        $(, reversed $reversed:expr)? $(,)?
    ) => {
        $crate::table::unit_element!($(#[$doc])* $name, $instance, "");

        impl ::mortar_core::element::ReferenceElement for $name {
            $crate::table::shared_methods!($name, $degree, $nodes, $shapes, Vector2, 2, [x, y]);
            fn domain(&self) -> ::mortar_core::element::ReferenceDomain {
                ::mortar_core::element::ReferenceDomain::$domain
            }
            fn corner_count(&self) -> usize {
                $corners
            }
        }

        impl ::mortar_core::element::SurfaceElement for $name {
            fn is_affine(&self) -> bool {
                ::mortar_core::element::ReferenceElement::shape_degree(self) == 1
            }
            fn gmsh_type(&self) -> Option<u32> {
                Some($gmsh)
            }
            $(
                fn reverse_nodes(&self, nodes: &mut [u32]) -> bool {
                    $crate::table::reorder(nodes, &$reversed)
                }
            )?
        }
    };
}
pub(crate) use face_element;

/// Declares a built-in volume element from its table: the unit struct `$name` (documented by
/// the doc comments given), its shared instance `$instance` and its `VolumeElement` impl. The
/// table: the reference domain (a `VolumeDomain` variant), the shape degree, the Gmsh type, the
/// node table (a constant `[[f64; 3]; N]`; 2D cells leave the third coordinate zero), the
/// shape family (a `Shapes<3>` value), the surface element of every face (a static) and the
/// faces as local node lists, outward for a positively oriented cell. The geometric map is
/// affine for every placement of the nodes exactly when the degree is 1.
#[cfg(feature = "volume")]
macro_rules! cell_element {
    (
        $(#[$doc:meta])*
        $name:ident, $instance:ident: $domain:ident, degree $degree:literal,
        gmsh $gmsh:literal, nodes $nodes:path, shapes $shapes:expr,
        face $face:path, faces $faces:expr $(,)?
    ) => {
        $crate::table::unit_element!($(#[$doc])* $name, $instance, "volume::");

        impl ::mortar_fem::element::VolumeElement for $name {
            $crate::table::shared_methods!($name, $degree, $nodes, $shapes, Vector3, 3, [x, y, z]);
            fn domain(&self) -> ::mortar_fem::element::VolumeDomain {
                ::mortar_fem::element::VolumeDomain::$domain
            }
            fn gmsh_type(&self) -> Option<u32> {
                Some($gmsh)
            }
            fn is_affine(&self) -> bool {
                self.shape_degree() == 1
            }
            fn faces(&self) -> &'static [&'static [usize]] {
                $faces
            }
            fn face_element(&self, face: usize) -> ::mortar_core::element::ElementRef {
                let count = self.faces().len();
                let what = if self.dim() == 2 { "edges" } else { "faces" };
                assert!(face < count, "a {} has {count} {what}", self.name());
                &$face
            }
        }
    };
}
#[cfg(feature = "volume")]
pub(crate) use cell_element;

/// The node table `a` followed by `b`: the nodes of an element after those of the element it
/// refines. `N` must be `A + B` (checked where the constant is evaluated, at compile time).
pub(crate) const fn concat<const W: usize, const A: usize, const B: usize, const N: usize>(
    a: &[[f64; W]; A],
    b: &[[f64; W]; B],
) -> [[f64; W]; N] {
    assert!(A + B == N, "the table has the nodes of both");
    let mut out = [[0.0; W]; N];
    let mut i = 0;
    while i < A {
        out[i] = a[i];
        i += 1;
    }
    while i < N {
        out[i] = b[i - A];
        i += 1;
    }
    out
}

/// The nodes of a surface element in the plane `z = 0`: the node table of the 2D cell of the
/// same shape.
#[cfg(feature = "volume")]
pub(crate) const fn in_plane<const N: usize>(nodes: &[[f64; 2]; N]) -> [[f64; 3]; N] {
    let mut out = [[0.0; 3]; N];
    let mut i = 0;
    while i < N {
        out[i] = [nodes[i][0], nodes[i][1], 0.0];
        i += 1;
    }
    out
}

/// Puts `nodes` in the order `order` (new node `i` is old node `order[i]`); `false`, leaving
/// them as they are, when there are not `K` of them.
pub(crate) fn reorder<const K: usize>(nodes: &mut [u32], order: &[usize; K]) -> bool {
    let Ok(old) = <[u32; K]>::try_from(&*nodes) else {
        return false;
    };
    for (n, &i) in nodes.iter_mut().zip(order) {
        *n = old[i];
    }
    true
}
