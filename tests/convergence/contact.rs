//! Frictionless contact: the contact patch test.
//!
//! Source of the reference (closed form): two stacked blocks of the same material, the lower
//! held by symmetry conditions (`u_y = 0` at its bottom, `u_x = 0` on `x = 0`; in 3D also
//! `u_z = 0` on `z = 0` for both), the upper held laterally only (`u_x = 0` on `x = 0`), with a
//! uniform pressure `sigma` on top. The stress is uniaxial, `sigma_yy = -sigma`, everywhere, so
//! the displacement is linear: `u_y = -sigma (1 - nu^2) y / E`, `u_x = sigma nu (1 + nu) x / E`
//! in plane strain; `u_y = -sigma y / E`, `u_x = sigma nu x / E`, `u_z = sigma nu z / E` in 3D.
//! The contact pressure is `sigma` at every slave node. The contact faces do not match (the
//! slave and master meshes have other sizes and cell kinds).

use mortar::generate::{box_mesh, rectangle_mesh, CellShape};
use mortar::physics::contact::{
    automatic_complementarity, solve_contact, ContactOptions, NormalGap,
};
use mortar::physics::elastic::{
    assemble_elastic_load, assemble_elastic_stiffness, ComponentSet, ElasticBody, ElasticMaterial,
    ElasticOptions,
};
use mortar::physics::laws::ContactComplementarity;
use mortar::physics::tied::Tie;
use mortar::CouplingOptions;
use nalgebra::Vector3;

const E: f64 = 210e9;
const NU: f64 = 0.3;
const SIGMA: f64 = 50e6;

fn exact(x: &Vector3<f64>, dim: usize) -> Vector3<f64> {
    if dim == 2 {
        Vector3::new(
            SIGMA * NU * (1.0 + NU) * x.x / E,
            -SIGMA * (1.0 - NU * NU) * x.y / E,
            0.0,
        )
    } else {
        Vector3::new(SIGMA * NU * x.x / E, -SIGMA * x.y / E, SIGMA * NU * x.z / E)
    }
}

fn patch(dim: usize) {
    let material = ElasticMaterial::new(E, NU);
    let (lower, upper) = if dim == 2 {
        (
            rectangle_mesh([0.0, 0.0], [1.0, 1.0], [4, 4], CellShape::Tensor, 1).unwrap(),
            rectangle_mesh([0.0, 1.0], [1.0, 2.0], [5, 5], CellShape::Simplex, 1000).unwrap(),
        )
    } else {
        (
            box_mesh([0.0; 3], [1.0; 3], [3, 3, 3], CellShape::Tensor, 1).unwrap(),
            box_mesh(
                [0.0, 1.0, 0.0],
                [1.0, 2.0, 1.0],
                [4, 4, 4],
                CellShape::Simplex,
                1000,
            )
            .unwrap(),
        )
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
            |f| near(f.centroid.y, 2.0),
            |_| Vector3::new(0.0, -SIGMA, 0.0),
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
    let on_interface = |f: &mortar::core::mesh::BoundaryFace| near(f.centroid.y, 1.0);
    let tie = Tie::new(
        &slave.mesh,
        &master.mesh,
        slave.mesh.boundary_surface(on_interface).unwrap(),
        master.mesh.boundary_surface(on_interface).unwrap(),
        &CouplingOptions::default().dual(),
    )
    .unwrap();
    let options = ElasticOptions::default();
    let k = [
        assemble_elastic_stiffness(&slave, &options).unwrap(),
        assemble_elastic_stiffness(&master, &options).unwrap(),
    ];
    let f = [
        assemble_elastic_load(&slave, &options).unwrap(),
        assemble_elastic_load(&master, &options).unwrap(),
    ];
    let dir = [slave.dirichlet_dofs(), master.dirichlet_dofs()];
    let gap = NormalGap::new(&tie, dim, slave.mesh.node_count(), master.mesh.node_count()).unwrap();
    let c = automatic_complementarity(&k[0], &tie, &gap, dim);
    let law = ContactComplementarity::try_new(c).unwrap();
    let sol = solve_contact(
        [&k[0], &k[1]],
        [&f[0], &f[1]],
        [(&dir[0].0, &dir[0].1), (&dir[1].0, &dir[1].1)],
        &gap,
        &law,
        &ContactOptions::default(),
    )
    .unwrap();
    let worst_p = sol
        .pressure
        .iter()
        .map(|p| (p - SIGMA).abs() / SIGMA)
        .fold(0.0f64, f64::max);
    assert!(
        worst_p < 1e-8,
        "{dim}D: pressure off by {worst_p:e} (relative)"
    );
    let scale = exact(&Vector3::new(1.0, 2.0, 1.0), dim).amax();
    let mut worst_u = 0.0f64;
    for (b, body) in [&slave, &master].iter().enumerate() {
        for (node, x) in body.mesh.coords().iter().enumerate() {
            let e = exact(x, dim);
            for a in 0..dim {
                let u = sol.displacements[b][node * dim + a];
                worst_u = worst_u.max((u - e[a]).abs() / scale);
            }
        }
    }
    assert!(
        worst_u < 1e-10,
        "{dim}D: displacement off by {worst_u:e} (relative)"
    );
    eprintln!(
        "contact patch {dim}D: pressure error {worst_p:.1e}, displacement error {worst_u:.1e}, \
         {} Newton steps, active set settled at {:?}, c = {c:.3e}",
        sol.steps[0].newton_steps, sol.steps[0].settled_at
    );
    // Every slave node in contact; the force is the applied one (the top's area is 1).
    assert_eq!(sol.steps[0].active, sol.pressure.len());
    assert!(
        (sol.force - SIGMA).abs() < 1e-8 * SIGMA,
        "force {}",
        sol.force
    );
    // The active set is right from the start (touching surfaces start closed): one step to
    // the solution, one to confirm it.
    assert!(sol.steps[0].newton_steps <= 2, "{:?}", sol.steps[0]);
}

#[test]
fn contact_patch_test_2d() {
    patch(2);
}

#[test]
fn contact_patch_test_3d() {
    patch(3);
}
