//! The PETSc backend on the systems the toolkit hands it: Poisson (SPD), plane-strain
//! elasticity (SPD, vector-valued, rigid body modes), a tied saddle point, inputs that must
//! fail with a typed error, and PETSc options passed through. Needs the `petsc` feature
//! (`cargo test -p mortar-petsc --features petsc`).

mod solvers {
    pub mod common;
    mod elasticity;
    mod errors;
    mod interface;
    mod options;
    mod poisson;
    mod saddle;
}
