//! Small-strain isotropic linear elasticity, `-div sigma = b`, `sigma = C : (eps(u) - eps_th)`,
//! `eps(u) = sym(grad u)`, `eps_th = alpha (T - T_ref) I`, on 2D plane-strain (Tri3, Quad4 in
//! the plane `z = 0`, unit thickness) and 3D (Tet4, Hex8) volume meshes.
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
//! Weak form: `int eps(v) : C eps(u) = int v . b + int_Gamma_t v . t + int eps(v) : C eps_th`
//! for every `v` vanishing on the prescribed components. The Dirichlet unknowns and values
//! come from [`ElasticBody::dirichlet_dofs`]; eliminating them (or tying bodies) is the
//! caller's.
//!
//! ```text
//! use mortar_physics::elastic::*;
//! let body = ElasticBody::new("block", mesh, ElasticMaterial::new(210e9, 0.3))
//!     .with_dirichlet_where(|f| f.centroid.x.abs() < 1e-12, ComponentSet::One(0), |_| Vector3::zeros())?
//!     .with_traction_where(|f| (f.centroid.x - 1.0).abs() < 1e-12, |_| Vector3::new(1e6, 0.0, 0.0))?;
//! let k = assemble_elastic_stiffness(&body, &ElasticOptions::default())?;
//! let f = assemble_elastic_load(&body, &ElasticOptions::default())?;
//! let (fixed, values) = body.dirichlet_dofs();
//! // ... solve K u = f with u[fixed] = values ...
//! let stress = recover_stress(&body, &u, &ElasticOptions::default())?;
//! ```

mod assembly;
mod body;
mod material;
mod stress;
#[cfg(test)]
mod tests;

pub use crate::field::{ComponentSet, DofLayout};
pub use assembly::{assemble_elastic_load, assemble_elastic_stiffness, ElasticOptions};
pub use body::{DisplacementCondition, ElasticBody, TractionCondition, VectorField};
pub use material::{von_mises, ElasticMaterial};
pub use stress::{recover_stress, StressField};
