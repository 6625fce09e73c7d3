//! Lagrange multiplier spaces on the slave surface.
//!
//! A space is a transformation of the slave shape functions on each face:
//! `Phi_j = sum_k A_jk N_k`. The standard space has `A = I`; the dual (biorthogonal) space has
//! `A = D_e M_e^-1` with `M_e[j][k] = int N_j N_k` and `D_e = diag(int N_j)` over the face, so
//! that `int Phi_j N_k = delta_jk int N_k`: D becomes diagonal. The linear space on
//! second-order faces has `Phi_c` the first-order function of corner `c` and no multiplier
//! (an empty row of D and M) on the other nodes.
//!
//! A space of one's own implements [`MultiplierSpace`] (a name and the basis on a face); what
//! the coupling's fast paths rely on is apart, in [`MultiplierFastPaths`], which only a space
//! that wants them implements (the shipped standard and dual spaces do).

mod basis;
mod dual;
mod linear;
mod standard;

pub use basis::{LmBasis, MultiplierFastPaths, MultiplierSpace};
pub use dual::{recombination, slave_recombination, DualMultipliers, RECOMBINATION_ALPHA};
pub use linear::LinearMultipliers;
pub use standard::StandardMultipliers;
