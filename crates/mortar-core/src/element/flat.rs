//! Face shapes recognised by their behaviour, not their names: the linear triangle and the
//! bilinear quad, whose shape functions the closed-form integration kernels and the search's
//! padding rely on bit for bit (a user's element with the same functions qualifies too).

use nalgebra::Vector2;

use super::{ElementRef, ReferenceDomain};

/// The flat face shapes the closed-form integrals know: whose shape functions are
/// polynomials of degree at most 2 of their reference coordinates, bit for bit as their
/// element types compute them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FlatShape {
    /// The linear triangle ([`is_linear_triangle`]).
    Triangle,
    /// The bilinear quad ([`is_bilinear_quad`]).
    Quad,
}

impl FlatShape {
    /// The shape of `element`, if it is one of these.
    pub(crate) fn of(element: ElementRef) -> Option<Self> {
        if is_linear_triangle(element) {
            Some(Self::Triangle)
        } else if is_bilinear_quad(element) {
            Some(Self::Quad)
        } else {
            None
        }
    }
}

/// Whether `element` is the four-node quad with bilinear shape functions: corners at
/// `(+-1, +-1)` and `N_k = (1 + xi_k xi)(1 + eta_k eta) / 4`, checked at sample points to
/// four ulps.
pub(crate) fn is_bilinear_quad(element: ElementRef) -> bool {
    if element.node_count() != 4
        || element.corner_count() != 4
        || element.domain() != ReferenceDomain::Quadrilateral
        || element.shape_degree() != 2
    {
        return false;
    }
    let nodes = element.node_reference_coords();
    if nodes.len() != 4 || nodes.iter().any(|c| c[0].abs() != 1.0 || c[1].abs() != 1.0) {
        return false;
    }
    let mut n = [0.0; 4];
    [
        [0.0, 0.0],
        [0.3, -0.7],
        [-0.45, 0.125],
        [1.0, 1.0],
        [-0.9, 0.6],
    ]
    .iter()
    .all(|&[x, y]| {
        element.shape_values_into(&Vector2::new(x, y), &mut n);
        nodes.iter().zip(&n).all(|(c, v)| {
            let want = 0.25 * (1.0 + c[0] * x) * (1.0 + c[1] * y);
            (v - want).abs() <= 4.0 * f64::EPSILON
        })
    })
}

/// Whether `element` is the three-node triangle with linear shape functions, bit for bit:
/// nodes at `(0, 0)`, `(1, 0)`, `(0, 1)` and `N = (1 - xi - eta, xi, eta)`, so that each
/// shape function of a face is the barycentric coordinate of its node.
pub(crate) fn is_linear_triangle(element: ElementRef) -> bool {
    if element.node_count() != 3
        || element.corner_count() != 3
        || element.domain() != ReferenceDomain::Triangle
        || !element.is_affine()
        || element.shape_degree() != 1
        || element.node_reference_coords() != [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
    {
        return false;
    }
    let mut n = [0.0; 3];
    [
        [0.0, 0.0],
        [1.0, 0.0],
        [0.0, 1.0],
        [0.25, 0.5],
        [0.6, 0.125],
    ]
    .iter()
    .all(|&[x, y]| {
        element.shape_values_into(&Vector2::new(x, y), &mut n);
        n == [1.0 - x - y, x, y]
    })
}
