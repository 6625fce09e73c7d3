//! Two stacked elastic blocks with non-matching meshes of their contact faces, the contact
//! tests' set-up: the lower block `[0,1]^dim` (master, Quad4 4 x 4 or Hex8 3 x 3 x 3) held by
//! symmetry conditions (`u_y = 0` at its bottom, `u_x = 0` on `x = 0`, and `u_z = 0` on `z = 0`
//! in 3D, as for the upper block), the upper block `[0,1] x [1 + lift, 2 + lift] (x [0,1])`
//! (slave, Tri3 5 x 5 or Tet4 4 x 4 x 4, in 3D turned in the plane of the interface by up to
//! [`TWIST_DEGREES`]) held laterally only (`u_x = 0` on `x = 0`), a uniform
//! pressure `SIGMA` on its top. Steel: E = 210 GPa, nu = 0.3.

use mortar::core::linalg::SparseMatrix;
use mortar::generate::{box_mesh, rectangle_mesh, CellShape};
use mortar::physics::contact::NormalGap;
use mortar::physics::elastic::{
    assemble_elastic_load, assemble_elastic_stiffness, ComponentSet, ElasticBody, ElasticMaterial,
    ElasticOptions,
};
use mortar::physics::tied::Tie;
use mortar::CouplingOptions;
use nalgebra::Vector3;

pub const E: f64 = 210e9;
pub const NU: f64 = 0.3;
pub const SIGMA: f64 = 50e6;

/// The blocks (slave, master), their tie, stiffness, loads, Dirichlet data and normal gap.
pub struct Blocks {
    pub bodies: [ElasticBody; 2],
    pub tie: Tie,
    pub stiffness: [SparseMatrix; 2],
    pub load: [Vec<f64>; 2],
    pub dirichlet: [(Vec<u32>, Vec<f64>); 2],
    pub gap: NormalGap,
}

/// The blocks in `dim` dimensions, the upper one lifted by `lift`, pressed by `pressure` on
/// its top (negative: pulled).
pub fn stacked_blocks(dim: usize, lift: f64, pressure: f64) -> Blocks {
    stacked_blocks_with(dim, lift, pressure, &CouplingOptions::default().dual())
}

/// In 3D, the in-plane rotation of the upper mesh at the centre of the interface, degrees.
pub const TWIST_DEGREES: f64 = 5.0;

/// [`stacked_blocks`] with the coupling options `coupling` (dual multipliers by default).
pub fn stacked_blocks_with(
    dim: usize,
    lift: f64,
    pressure: f64,
    coupling: &CouplingOptions,
) -> Blocks {
    stacked_blocks_of_order(dim, lift, pressure, coupling, None)
}

/// [`stacked_blocks_with`], both blocks raised to second order by `order` (straight cells).
pub fn stacked_blocks_of_order(
    dim: usize,
    lift: f64,
    pressure: f64,
    coupling: &CouplingOptions,
    order: Option<mortar::generate::SecondOrder>,
) -> Blocks {
    let material = ElasticMaterial::new(E, NU);
    let (top, bottom) = (1.0 + lift, 2.0 + lift);
    let (lower, upper) = if dim == 2 {
        (
            rectangle_mesh([0.0, 0.0], [1.0, 1.0], [4, 4], CellShape::Tensor, 1).unwrap(),
            rectangle_mesh([0.0, top], [1.0, bottom], [5, 5], CellShape::Simplex, 1000).unwrap(),
        )
    } else {
        let mut upper = box_mesh(
            [0.0, top, 0.0],
            [1.0, bottom, 1.0],
            [4, 4, 4],
            CellShape::Simplex,
            1000,
        )
        .unwrap();
        // The upper mesh turned in the plane of the interface by up to TWIST_DEGREES (at the
        // centre; the angle falls to zero on the sides, so the block stays a box): its
        // contact faces cross the lower ones at an angle.
        upper
            .transform(|x| {
                let (dx, dz) = (x.x - 0.5, x.z - 0.5);
                let bump = 16.0 * x.x * (1.0 - x.x) * x.z * (1.0 - x.z);
                let (s, c) = (TWIST_DEGREES.to_radians() * bump).sin_cos();
                Vector3::new(0.5 + c * dx - s * dz, x.y, 0.5 + s * dx + c * dz)
            })
            .unwrap();
        (
            box_mesh([0.0; 3], [1.0; 3], [3, 3, 3], CellShape::Tensor, 1).unwrap(),
            upper,
        )
    };
    let (lower, upper) = match order {
        None => (lower, upper),
        Some(family) => {
            let raise = |m| mortar::generate::second_order_mesh(&m, family, |x, _| *x).unwrap();
            (raise(lower), raise(upper))
        }
    };
    let near = |a: f64, b: f64| (a - b).abs() < 1e-9;
    let zero = |_: &Vector3<f64>| Vector3::zeros();
    let mut master = ElasticBody::new("lower", lower, material)
        .with_dirichlet_where(|f| near(f.centroid.y, 0.0), ComponentSet::One(1), zero)
        .unwrap()
        .with_dirichlet_where(|f| near(f.centroid.x, 0.0), ComponentSet::One(0), zero)
        .unwrap();
    let mut slave = ElasticBody::new("upper", upper, material)
        .with_dirichlet_where(|f| near(f.centroid.x, 0.0), ComponentSet::One(0), zero)
        .unwrap()
        .with_traction_where(
            move |f| near(f.centroid.y, bottom),
            move |_| Vector3::new(0.0, -pressure, 0.0),
        )
        .unwrap();
    if dim == 3 {
        master = master
            .with_dirichlet_where(|f| near(f.centroid.z, 0.0), ComponentSet::One(2), zero)
            .unwrap();
        slave = slave
            .with_dirichlet_where(|f| near(f.centroid.z, 0.0), ComponentSet::One(2), zero)
            .unwrap();
    }
    let tie = Tie::new(
        &slave.mesh,
        &master.mesh,
        slave
            .mesh
            .boundary_surface(|f| near(f.centroid.y, top))
            .unwrap(),
        master
            .mesh
            .boundary_surface(|f| near(f.centroid.y, 1.0))
            .unwrap(),
        coupling,
    )
    .unwrap();
    let options = ElasticOptions::default();
    let stiffness = [
        assemble_elastic_stiffness(&slave, &options).unwrap(),
        assemble_elastic_stiffness(&master, &options).unwrap(),
    ];
    let load = [
        assemble_elastic_load(&slave, &options).unwrap(),
        assemble_elastic_load(&master, &options).unwrap(),
    ];
    let dirichlet = [slave.dirichlet_dofs(), master.dirichlet_dofs()];
    let gap = NormalGap::new(&tie, dim, slave.mesh.node_count(), master.mesh.node_count()).unwrap();
    Blocks {
        bodies: [slave, master],
        tie,
        stiffness,
        load,
        dirichlet,
        gap,
    }
}
