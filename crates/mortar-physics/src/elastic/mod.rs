//! Small-strain isotropic linear elasticity, `-div sigma = b`, `sigma = C : (eps(u) - eps_th)`,
//! `eps(u) = sym(grad u)`, `eps_th = alpha (T - T_ref) I`, on 2D plane-strain (Tri3, Quad4 in
//! the plane `z = 0`, unit thickness) and 3D (Tet4, Hex8) volume meshes, and on 2D meshes as
//! the r-z section of a body of revolution (axisymmetric, `x = r`, `y = z`, the hoop strain
//! `u_r / r`, weight `2 pi r`: [`ElasticOptions::geometry`]).
//!
//! - [`ElasticBody`]: mesh, [`ElasticMaterial`] (E, nu, alpha, T_ref), body force, nodal
//!   temperature field, displacement conditions per component ([`ComponentSet`]) and
//!   tractions on boundary faces.
//! - [`DofLayout`]: the unknowns, interleaved by node, `dof = node * dim + component`
//!   (general: a scalar field is `components = 1`).
//! - [`assemble_elastic_stiffness`] (K) and [`assemble_elastic_load`] (body force, traction
//!   and thermal load): sparse, in parallel over fixed chunks of cells merged in order, so
//!   the result is the same bit for bit whatever the thread count.
//! - [`recover_stress`]: the Cauchy stress (Voigt `[xx, yy, zz, yz, xz, xy]`) per cell and
//!   averaged at the nodes, with the von Mises stress ([`StressField`]).
//!
//! - [`GeneralizedPlaneStrain`]: a 2D cross-section of a long body with one uniform axial
//!   strain unknown fixed by the axial force ([`AxialForce`]), instead of plane strain;
//!   [`solve_generalized_plane_strain`] for one body.
//! - [`solve_elastic`] ([`solve_elastic_with`] for given options): the static solve of one
//!   body held by its own displacement conditions (sparse Cholesky on the free unknowns), with
//!   compiled examples.
//!
//! Weak form: `int eps(v) : C eps(u) = int v . b + int_Gamma_t v . t + int eps(v) : C eps_th`
//! for every `v` vanishing on the prescribed components. The Dirichlet unknowns and values
//! come from [`ElasticBody::dirichlet_dofs`]; [`solve_elastic`] eliminates them for one body,
//! tying and contact (`crate::tied`, `crate::contact`) for two.

mod assembly;
mod axial;
mod body;
mod material;
mod solve;
mod stress;
#[cfg(test)]
mod tests;

pub use crate::field::{ComponentSet, DofLayout};
pub use assembly::{
    assemble_elastic_load, assemble_elastic_stiffness, assemble_thermal_load_matrix, ElasticOptions,
};
pub use axial::{solve_generalized_plane_strain, AxialForce, GeneralizedPlaneStrain};
pub use body::{DisplacementCondition, ElasticBody, TractionCondition, VectorField};
pub use material::{von_mises, ElasticMaterial};
pub use solve::{solve_elastic, solve_elastic_on, solve_elastic_with};
pub use stress::{recover_stress, recover_stress_with_axial_strain, StressField};
