//! # mortar-fem
//!
//! The finite-element plumbing between the mortar coupling (`mortar-core`) and the physics:
//!
//! - [`element`]: volume elements, the cells of the bodies (trait, reference domains, and
//!   [`CellValues`](element::CellValues), the values an assembly loop needs at the
//!   quadrature points of one cell);
//! - [`quadrature`]: their quadrature rules;
//! - [`field`]: the numbering of a nodal field's unknowns ([`DofLayout`](field::DofLayout),
//!   [`ComponentSet`](field::ComponentSet)) and of those its prescribed values leave free;
//! - [`mesh`]: [`VolumeMesh`], the nodes and cells of a body, whose boundary faces come out as
//!   outward-oriented [`SurfaceMesh`](mortar_core::SurfaceMesh)es for an interface;
//! - [`linalg`]: sparse linear algebra behind one solver interface
//!   ([`SparseSolver`](linalg::SparseSolver), [`Factorization`](linalg::Factorization)),
//!   implemented by faer's sparse LU and Cholesky (with METIS orderings) and a restarted GMRES.
//!
//! Reference domains: triangle `(0,0), (1,0), (0,1)`; quad `[-1, 1]^2`; tetrahedron
//! `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`; hexahedron `[-1, 1]^3`. Node order follows Gmsh.
//!
//! ```
//! use mortar_fem::linalg::{FaerSolver, MatrixKind, SparseSolver, Triplets};
//! let mut t = Triplets::default();
//! t.push(0, 0, 2.0);
//! t.push(1, 1, 4.0);
//! let lu = FaerSolver.factor(&t.to_csr(2, 2), MatrixKind::General).unwrap();
//! assert_eq!(lu.solve(&[2.0, 2.0]).unwrap(), vec![1.0, 0.5]);
//! ```

// What a run has to say goes into its results; only the command-line program prints.
#![cfg_attr(
    not(test),
    deny(clippy::print_stdout, clippy::print_stderr, clippy::dbg_macro)
)]

pub mod element;
pub mod field;
pub mod linalg;
pub mod mesh;
pub mod quadrature;

pub use mesh::VolumeMesh;
