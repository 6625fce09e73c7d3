//! The formulas the quadratic elements share, each driven by an element's own node list (its
//! reference coordinates, in Gmsh order), so that an element file states its nodes and faces
//! and nothing is written twice: the quadratic Lagrange polynomials on `[-1, 1]` and their
//! tensor products (Line3, Quad9, Hex27), the serendipity functions (Quad8, Hex20) and the
//! quadratic functions of the barycentric coordinates (Tri6, Tet10).

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
/// at the middle of edge `(a, b)`, `4 L_a L_b`. `out` gets the values of the `D + 1` corners
/// then of `edges` in order; `grads`, when given, their gradients.
#[inline]
pub(crate) fn barycentric<const D: usize>(
    xi: &[f64; D],
    edges: &[[usize; 2]],
    out: &mut [f64],
    mut grads: Option<&mut [[f64; D]]>,
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
        out[i] = l[i] * (2.0 * l[i] - 1.0);
        if let Some(g) = grads.as_deref_mut() {
            g[i] = dl[i].map(|v| (4.0 * l[i] - 1.0) * v);
        }
    }
    for (e, &[a, b]) in edges.iter().enumerate() {
        out[D + 1 + e] = 4.0 * l[a] * l[b];
        if let Some(g) = grads.as_deref_mut() {
            g[D + 1 + e] = std::array::from_fn(|k| 4.0 * (l[a] * dl[b][k] + l[b] * dl[a][k]));
        }
    }
}
