//! The shape functions of the built-in elements, as families that an element's node table
//! drives: [`Shapes`] is what the element tables (`crate::table`) call, and the families are
//! [`Nodewise`] (a formula per node, from the node's reference coordinates: the multilinear
//! functions of Line2, Quad4 and Hex8, the tensor products of the quadratic Lagrange
//! polynomials on `[-1, 1]` of Line3, Quad9 and Hex27, the serendipity functions of Quad8 and
//! Hex20), [`LinearSimplex`] (Tri3, Tet4) and [`QuadraticSimplex`] (the quadratic functions of
//! the barycentric coordinates of Tri6 and Tet10), and for the 2D cells [`InPlane`] (those of
//! the surface element of the same shape). Each formula is written once, for any
//! dimension, so that an element file states its nodes and nothing is written twice; all of
//! it is allocation-free and inlined, being called in the coupling's hot loop.

#[cfg(feature = "volume")]
use mortar_core::element::{ReferenceElement, MAX_FACE_NODES};
#[cfg(feature = "volume")]
use nalgebra::Vector2;

/// A family of shape functions evaluated on an element's node table. `W` is the width of the
/// reference points and nodes the element traits hand over (2 for faces, 3 for cells); a
/// family of fewer coordinates (a line's one, a 2D cell's two) reads the first ones and writes
/// zero into the remaining gradient components.
pub(crate) trait Shapes<const W: usize> {
    /// The values at `xi` of the functions of `nodes`, into `out` (as many as both have).
    fn values(&self, nodes: &[[f64; W]], xi: &[f64; W], out: &mut [f64]);
    /// Their gradients with respect to `xi`, into `out`.
    fn gradients(&self, nodes: &[[f64; W]], xi: &[f64; W], out: &mut [[f64; W]]);
}

/// The first `D` coordinates of a point of `W >= D`.
#[inline]
fn head<const D: usize, const W: usize>(x: &[f64; W]) -> [f64; D] {
    std::array::from_fn(|d| x[d])
}

/// A gradient of `D` components as one of `W >= D`, zero beyond `D`.
#[inline]
fn widen<const D: usize, const W: usize>(g: [f64; D]) -> [f64; W] {
    std::array::from_fn(|d| if d < D { g[d] } else { 0.0 })
}

/// The shape function of a node at `xi`, from the node's reference coordinates: its value and
/// gradient.
pub(crate) type NodeFunction<const D: usize> = fn(&[f64; D], &[f64; D]) -> (f64, [f64; D]);

/// Shape functions given node by node: `N_i(xi) = f(x_i, xi)` with its gradient, on the first
/// `D` coordinates of the node `x_i` and of `xi` (`f` is [`multilinear`], [`tensor`] or
/// [`serendipity`]). The function is a constant of the element's table, so that the compiler
/// inlines it into the element's loop over its nodes.
#[derive(Clone, Copy)]
pub(crate) struct Nodewise<const D: usize>(pub(crate) NodeFunction<D>);

impl<const D: usize, const W: usize> Shapes<W> for Nodewise<D> {
    #[inline]
    fn values(&self, nodes: &[[f64; W]], xi: &[f64; W], out: &mut [f64]) {
        let x = head(xi);
        for (o, n) in out.iter_mut().zip(nodes) {
            *o = (self.0)(&head(n), &x).0;
        }
    }
    #[inline]
    fn gradients(&self, nodes: &[[f64; W]], xi: &[f64; W], out: &mut [[f64; W]]) {
        let x = head(xi);
        for (o, n) in out.iter_mut().zip(nodes) {
            *o = widen((self.0)(&head(n), &x).1);
        }
    }
}

/// The linear functions of the unit simplex of `D` dimensions (Tri3, Tet4), its nodes the
/// origin then the unit points: the barycentric coordinates `1 - sum_d x_d`, `x_1`, ...,
/// `x_D`. The node table is not read.
#[derive(Clone, Copy)]
pub(crate) struct LinearSimplex<const D: usize>;

impl<const D: usize, const W: usize> Shapes<W> for LinearSimplex<D> {
    #[inline]
    fn values(&self, _nodes: &[[f64; W]], xi: &[f64; W], out: &mut [f64]) {
        let mut l0 = 1.0;
        for d in 0..D {
            l0 -= xi[d];
        }
        out[0] = l0;
        out[1..=D].copy_from_slice(&xi[..D]);
    }
    #[inline]
    fn gradients(&self, _nodes: &[[f64; W]], _xi: &[f64; W], out: &mut [[f64; W]]) {
        out[0] = widen([-1.0; D]);
        for d in 0..D {
            out[d + 1] = std::array::from_fn(|k| if k == d { 1.0 } else { 0.0 });
        }
    }
}

/// The quadratic functions of the barycentric coordinates of the unit simplex of `D`
/// dimensions (Tri6, Tet10; see [`barycentric`]): the corners, then the middles of the edges
/// listed (pairs of corners, in the element's node order). The node table is not read.
#[derive(Clone, Copy)]
pub(crate) struct QuadraticSimplex<const D: usize>(pub(crate) &'static [[usize; 2]]);

impl<const D: usize, const W: usize> Shapes<W> for QuadraticSimplex<D> {
    #[inline]
    fn values(&self, _nodes: &[[f64; W]], xi: &[f64; W], out: &mut [f64]) {
        barycentric::<D, W>(&head(xi), self.0, Some(out), None);
    }
    #[inline]
    fn gradients(&self, _nodes: &[[f64; W]], xi: &[f64; W], out: &mut [[f64; W]]) {
        barycentric::<D, W>(&head(xi), self.0, None, Some(out));
    }
}

/// The shape functions of a 2D cell in the plane `z = 0`: those of the surface element of the
/// same shape and node table, at `(xi, eta)`, their gradients given a zero third component
/// (through a buffer of two-component gradients, which the compiler vectorises better than
/// writing three components node by node). The cell's node table is not read.
#[cfg(feature = "volume")]
#[derive(Clone, Copy)]
pub(crate) struct InPlane<E: 'static>(pub(crate) &'static E);

#[cfg(feature = "volume")]
impl<E: ReferenceElement> Shapes<3> for InPlane<E> {
    #[inline]
    fn values(&self, _nodes: &[[f64; 3]], xi: &[f64; 3], out: &mut [f64]) {
        self.0.shape_values_into(&Vector2::new(xi[0], xi[1]), out);
    }
    #[inline]
    fn gradients(&self, _nodes: &[[f64; 3]], xi: &[f64; 3], out: &mut [[f64; 3]]) {
        let mut g = [[0.0; 2]; MAX_FACE_NODES];
        let k = self.0.node_count();
        self.0
            .shape_gradients_into(&Vector2::new(xi[0], xi[1]), &mut g[..k]);
        for (o, g) in out.iter_mut().zip(&g[..k]) {
            *o = [g[0], g[1], 0.0];
        }
    }
}

/// The multilinear function of a vertex `c` of `[-1, 1]^D` (Line2, Quad4, Hex8):
/// `2^-D prod_d (1 + c_d x_d)`, its value and gradient at `xi`, the factors multiplied in the
/// order of the coordinates.
#[inline]
pub(crate) fn multilinear<const D: usize>(node: &[f64; D], xi: &[f64; D]) -> (f64, [f64; D]) {
    let scale = 0.5f64.powi(D as i32);
    let f: [f64; D] = std::array::from_fn(|d| 1.0 + node[d] * xi[d]);
    let mut value = scale;
    for v in f {
        value *= v;
    }
    let grad = std::array::from_fn(|k| {
        let mut g = scale * node[k];
        for d in 0..D {
            if d != k {
                g *= f[d];
            }
        }
        g
    });
    (value, grad)
}

/// The 1D quadratic Lagrange polynomial of a node at `c` in `{-1, 1, 0}` and its derivative,
/// at `x`: `x (x - 1) / 2`, `x (x + 1) / 2`, `1 - x^2`.
#[inline]
fn quadratic_1d(c: f64, x: f64) -> (f64, f64) {
    if c < -0.5 {
        (0.5 * x * (x - 1.0), x - 0.5)
    } else if c > 0.5 {
        (0.5 * x * (x + 1.0), x + 0.5)
    } else {
        (1.0 - x * x, -2.0 * x)
    }
}

/// Value and gradient of the product `scale * prod_d f_d(x_d)` from the factors and their
/// derivatives.
#[inline]
fn product<const D: usize>(scale: f64, f: [(f64, f64); D]) -> (f64, [f64; D]) {
    let value = scale * f.iter().map(|p| p.0).product::<f64>();
    let grad = std::array::from_fn(|k| {
        scale
            * f.iter()
                .enumerate()
                .map(|(d, p)| if d == k { p.1 } else { p.0 })
                .product::<f64>()
    });
    (value, grad)
}

/// Tensor-product quadratic Lagrange functions (nodes at coordinates in `{-1, 0, 1}`): value
/// and gradient of node `node` at `xi`.
#[inline]
pub(crate) fn tensor<const D: usize>(node: &[f64; D], xi: &[f64; D]) -> (f64, [f64; D]) {
    product(1.0, std::array::from_fn(|d| quadratic_1d(node[d], xi[d])))
}

/// Serendipity functions of the 8-node quad (`D = 2`) and 20-node hexahedron (`D = 3`) on
/// `[-1, 1]^D`: at a corner `c` (every coordinate +-1),
/// `2^-D prod_d (1 + c_d x_d) (sum_d c_d x_d - (D - 1))`; at the middle of an edge (one
/// coordinate 0, along which the function is `1 - x^2`), `2^(1-D) (1 - x_z^2) prod_(d != z)
/// (1 + c_d x_d)`. Value and gradient at `xi`.
#[inline]
pub(crate) fn serendipity<const D: usize>(node: &[f64; D], xi: &[f64; D]) -> (f64, [f64; D]) {
    let linear = |d: usize| (1.0 + node[d] * xi[d], node[d]);
    if node.iter().all(|c| c.abs() > 0.5) {
        let (v, g): (f64, [f64; D]) = product(0.5f64.powi(D as i32), std::array::from_fn(linear));
        let s: f64 = (0..D).map(|d| node[d] * xi[d]).sum::<f64>() - (D as f64 - 1.0);
        // d/dx_k [P s] = g_k s + P c_k.
        let grad = std::array::from_fn(|k| g[k] * s + v * node[k]);
        (v * s, grad)
    } else {
        let f = std::array::from_fn(|d| {
            if node[d].abs() < 0.5 {
                (1.0 - xi[d] * xi[d], -2.0 * xi[d])
            } else {
                linear(d)
            }
        });
        product(0.5f64.powi(D as i32 - 1), f)
    }
}

/// The quadratic functions of the barycentric coordinates `L_0 = 1 - sum x_d`, `L_(d+1) =
/// x_d` of the triangle (`D = 2`) and tetrahedron (`D = 3`): at corner `i`, `L_i (2 L_i - 1)`;
/// at the middle of edge `(a, b)`, `4 L_a L_b`. `values`, when given, gets the values of the
/// `D + 1` corners then of `edges` in order; `grads`, when given, their gradients (of `W >= D`
/// components, zero beyond `D`). Always inlined, so that each caller's choice of values or
/// gradients is known where the loops are compiled.
#[inline(always)]
pub(crate) fn barycentric<const D: usize, const W: usize>(
    xi: &[f64; D],
    edges: &[[usize; 2]],
    mut values: Option<&mut [f64]>,
    mut grads: Option<&mut [[f64; W]]>,
) {
    let mut l = [0.0; 4];
    let mut dl = [[0.0; D]; 4];
    l[0] = 1.0 - xi.iter().sum::<f64>();
    dl[0] = [-1.0; D];
    for d in 0..D {
        l[d + 1] = xi[d];
        dl[d + 1][d] = 1.0;
    }
    for i in 0..=D {
        if let Some(out) = values.as_deref_mut() {
            out[i] = l[i] * (2.0 * l[i] - 1.0);
        }
        if let Some(g) = grads.as_deref_mut() {
            g[i] = widen(dl[i].map(|v| (4.0 * l[i] - 1.0) * v));
        }
    }
    for (e, &[a, b]) in edges.iter().enumerate() {
        if let Some(out) = values.as_deref_mut() {
            out[D + 1 + e] = 4.0 * l[a] * l[b];
        }
        if let Some(g) = grads.as_deref_mut() {
            g[D + 1 + e] = widen::<D, W>(std::array::from_fn(|k| {
                4.0 * (l[a] * dl[b][k] + l[b] * dl[a][k])
            }));
        }
    }
}
