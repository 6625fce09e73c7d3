//! Lagrange elements of any order from their nodes alone: the shape functions are the basis
//! of the complete polynomials of degree `p` (lines, triangles, tetrahedra) or of the tensor
//! polynomials of degree `p` in each coordinate (quads, hexahedra) that is nodal at the given
//! reference points, found once by inverting the Vandermonde matrix; `p` follows from the node
//! count. A program's own element in a few lines, in any node order (Gmsh's, say):
//!
//! ```
//! use mortar_core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
//! use mortar_elements::LagrangeFace;
//!
//! // Gmsh's four-node cubic line (type 26): the ends, then the inner nodes.
//! static NODES: [[f64; 2]; 4] = [[-1.0, 0.0], [1.0, 0.0], [-1.0 / 3.0, 0.0], [1.0 / 3.0, 0.0]];
//! let line4 = LagrangeFace::new("Line4", ReferenceDomain::Line, 2, &NODES, Some(26))
//!     .unwrap()
//!     .with_reversal(&[1, 0, 3, 2]);
//! let mut n = [0.0; 4];
//! line4.shape_values_into(&nalgebra::Vector2::new(-1.0 / 3.0, 0.0), &mut n);
//! assert!((n[2] - 1.0).abs() < 1e-14 && n[0].abs() < 1e-14);
//! assert_eq!(line4.shape_degree(), 3);
//! ```

use mortar_core::element::{ReferenceDomain, ReferenceElement, SurfaceElement};
use nalgebra::{DMatrix, Vector2};
#[cfg(feature = "volume")]
use {
    mortar_core::element::ElementRef,
    mortar_fem::element::{VolumeDomain, VolumeElement},
    nalgebra::Vector3,
};

/// Why a set of nodes does not make a Lagrange element.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LagrangeError {
    /// No polynomial space of the domain has this many functions.
    #[error("{count} nodes fit no complete (or tensor) polynomial space of a {domain}")]
    NodeCount {
        /// The node count.
        count: usize,
        /// The domain.
        domain: &'static str,
    },
    /// The nodes do not determine the polynomials (some lie where a polynomial of the space
    /// vanishes at all of them, e.g. too many on one line).
    #[error("the nodes are not unisolvent for the polynomials of degree {degree}")]
    NotUnisolvent {
        /// The degree.
        degree: u32,
    },
}

/// The exponents of the monomials of a space in `dim` coordinates, and its shape degree
/// (highest total degree), for `count` nodes.
fn monomials(dim: usize, tensor: bool, count: usize) -> Option<(Vec<[u32; 3]>, u32)> {
    for p in 0..=12u32 {
        let mut m = Vec::new();
        for a in 0..=p {
            for b in 0..=if dim > 1 { p } else { 0 } {
                for c in 0..=if dim > 2 { p } else { 0 } {
                    if tensor || a + b + c <= p {
                        m.push([a, b, c]);
                    }
                }
            }
        }
        if m.len() == count {
            let degree = if tensor { p * dim as u32 } else { p };
            return Some((m, degree));
        }
        if m.len() > count {
            return None;
        }
    }
    None
}

/// The nodal basis: coefficients `c` with `N_i(x) = sum_k c[(k, i)] m_k(x)`.
#[derive(Debug, Clone)]
struct Basis {
    exponents: Vec<[u32; 3]>,
    coefficients: DMatrix<f64>,
    degree: u32,
}

impl Basis {
    fn new(
        dim: usize,
        tensor: bool,
        nodes: &[[f64; 3]],
        domain: &'static str,
    ) -> Result<Self, LagrangeError> {
        let (exponents, degree) =
            monomials(dim, tensor, nodes.len()).ok_or(LagrangeError::NodeCount {
                count: nodes.len(),
                domain,
            })?;
        let v = DMatrix::from_fn(nodes.len(), nodes.len(), |i, k| {
            monomial(&exponents[k], &nodes[i])
        });
        let coefficients = v
            .try_inverse()
            .filter(|c| c.iter().all(|x| x.is_finite()))
            .ok_or(LagrangeError::NotUnisolvent { degree })?;
        Ok(Self {
            exponents,
            coefficients,
            degree,
        })
    }

    fn values(&self, x: &[f64; 3], out: &mut [f64]) {
        let m: Vec<f64> = self.exponents.iter().map(|e| monomial(e, x)).collect();
        for (i, o) in out.iter_mut().enumerate().take(m.len()) {
            *o = (0..m.len()).map(|k| self.coefficients[(k, i)] * m[k]).sum();
        }
    }

    fn gradients(&self, x: &[f64; 3], dim: usize, out: &mut dyn FnMut(usize, usize, f64)) {
        let n = self.exponents.len();
        for d in 0..dim {
            let m: Vec<f64> = self
                .exponents
                .iter()
                .map(|e| {
                    if e[d] == 0 {
                        return 0.0;
                    }
                    let mut f = *e;
                    f[d] -= 1;
                    f64::from(e[d]) * monomial(&f, x)
                })
                .collect();
            for i in 0..n {
                out(i, d, (0..n).map(|k| self.coefficients[(k, i)] * m[k]).sum());
            }
        }
    }
}

fn monomial(e: &[u32; 3], x: &[f64; 3]) -> f64 {
    (0..3).map(|d| x[d].powi(e[d] as i32)).product()
}

/// A surface element (interface face) given by its reference nodes: see the module
/// documentation. Reference domains as everywhere: line `[-1, 1]`, triangle
/// `(0,0), (1,0), (0,1)`, quad `[-1, 1]^2`; the corners first.
#[derive(Debug, Clone)]
pub struct LagrangeFace {
    name: &'static str,
    domain: ReferenceDomain,
    corners: usize,
    nodes: &'static [[f64; 2]],
    gmsh_type: Option<u32>,
    reversal: Option<&'static [usize]>,
    basis: Basis,
}

impl LagrangeFace {
    /// The element of `name` on `domain` with `corners` corners and the reference nodes
    /// `nodes`, Gmsh type `gmsh_type`.
    ///
    /// # Errors
    /// [`LagrangeError`] when the node count fits no polynomial space of the domain or the
    /// nodes do not determine one.
    pub fn new(
        name: &'static str,
        domain: ReferenceDomain,
        corners: usize,
        nodes: &'static [[f64; 2]],
        gmsh_type: Option<u32>,
    ) -> Result<Self, LagrangeError> {
        let (dim, tensor, what) = match domain {
            ReferenceDomain::Line => (1, false, "line"),
            ReferenceDomain::Triangle => (2, false, "triangle"),
            ReferenceDomain::Quadrilateral => (2, true, "quadrilateral"),
        };
        let padded: Vec<[f64; 3]> = nodes.iter().map(|x| [x[0], x[1], 0.0]).collect();
        Ok(Self {
            name,
            domain,
            corners,
            nodes,
            gmsh_type,
            reversal: None,
            basis: Basis::new(dim, tensor, &padded, what)?,
        })
    }

    /// The node order of the reversed face (`reversed[i]` is the old position of new node
    /// `i`), for turning faces round (orientation); without it only faces of corners alone
    /// can be reversed.
    pub fn with_reversal(mut self, reversed: &'static [usize]) -> Self {
        self.reversal = Some(reversed);
        self
    }
}

impl ReferenceElement for LagrangeFace {
    fn name(&self) -> &'static str {
        self.name
    }
    fn domain(&self) -> ReferenceDomain {
        self.domain
    }
    fn node_count(&self) -> usize {
        self.nodes.len()
    }
    fn corner_count(&self) -> usize {
        self.corners
    }
    fn shape_degree(&self) -> u32 {
        self.basis.degree
    }
    fn node_reference_coords(&self) -> &'static [[f64; 2]] {
        self.nodes
    }
    fn shape_values_into(&self, xi: &Vector2<f64>, out: &mut [f64]) {
        self.basis.values(&[xi.x, xi.y, 0.0], out);
    }
    fn shape_gradients_into(&self, xi: &Vector2<f64>, out: &mut [[f64; 2]]) {
        out.iter_mut().for_each(|g| *g = [0.0; 2]);
        let dim = self.domain.dim();
        self.basis
            .gradients(&[xi.x, xi.y, 0.0], dim, &mut |i, d, v| out[i][d] = v);
    }
}

impl SurfaceElement for LagrangeFace {
    fn gmsh_type(&self) -> Option<u32> {
        self.gmsh_type
    }
    fn reverse_nodes(&self, nodes: &mut [u32]) -> bool {
        match self.reversal {
            Some(order) if nodes.len() == order.len() => {
                let old = nodes.to_vec();
                for (n, &i) in nodes.iter_mut().zip(order) {
                    *n = old[i];
                }
                true
            }
            _ => false,
        }
    }
}

/// A cell given by its reference nodes and its faces (see the module documentation and
/// [`VolumeElement::faces`]): triangle `(0,0), (1,0), (0,1)`, quad `[-1, 1]^2`, tetrahedron
/// `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`, hexahedron `[-1, 1]^3`.
#[cfg(feature = "volume")]
#[derive(Debug, Clone)]
pub struct LagrangeCell {
    name: &'static str,
    domain: VolumeDomain,
    nodes: &'static [[f64; 3]],
    faces: &'static [&'static [usize]],
    face_element: ElementRef,
    gmsh_type: Option<u32>,
    basis: Basis,
}

#[cfg(feature = "volume")]
impl LagrangeCell {
    /// The cell of `name` on `domain` with the reference nodes `nodes`, its boundary faces
    /// `faces` (node positions, outward as [`VolumeElement::faces`] says) of the element
    /// `face_element`, Gmsh type `gmsh_type`.
    ///
    /// # Errors
    /// As [`LagrangeFace::new`].
    pub fn new(
        name: &'static str,
        domain: VolumeDomain,
        nodes: &'static [[f64; 3]],
        faces: &'static [&'static [usize]],
        face_element: ElementRef,
        gmsh_type: Option<u32>,
    ) -> Result<Self, LagrangeError> {
        let (tensor, what) = match domain {
            VolumeDomain::Triangle => (false, "triangle"),
            VolumeDomain::Quadrilateral => (true, "quadrilateral"),
            VolumeDomain::Tetrahedron => (false, "tetrahedron"),
            VolumeDomain::Hexahedron => (true, "hexahedron"),
        };
        Ok(Self {
            name,
            domain,
            nodes,
            faces,
            face_element,
            gmsh_type,
            basis: Basis::new(domain.dim(), tensor, nodes, what)?,
        })
    }
}

#[cfg(feature = "volume")]
impl VolumeElement for LagrangeCell {
    fn name(&self) -> &'static str {
        self.name
    }
    fn domain(&self) -> VolumeDomain {
        self.domain
    }
    fn node_count(&self) -> usize {
        self.nodes.len()
    }
    fn shape_degree(&self) -> u32 {
        self.basis.degree
    }
    fn node_reference_coords(&self) -> &'static [[f64; 3]] {
        self.nodes
    }
    fn shape_values_into(&self, xi: &Vector3<f64>, out: &mut [f64]) {
        self.basis.values(&[xi.x, xi.y, xi.z], out);
    }
    fn shape_gradients_into(&self, xi: &Vector3<f64>, out: &mut [[f64; 3]]) {
        out.iter_mut().for_each(|g| *g = [0.0; 3]);
        let dim = self.domain.dim();
        self.basis
            .gradients(&[xi.x, xi.y, xi.z], dim, &mut |i, d, v| out[i][d] = v);
    }
    fn gmsh_type(&self) -> Option<u32> {
        self.gmsh_type
    }
    fn faces(&self) -> &'static [&'static [usize]] {
        self.faces
    }
    fn face_element(&self, _face: usize) -> ElementRef {
        self.face_element
    }
}
