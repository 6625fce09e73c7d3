//! Backward Euler: a field linear in space and in time, `u = (1 + t)(a + b . x)`, with the
//! source `Q = rho c_p (a + b . x)`, is integrated exactly, by both formulations, across a
//! change of time step (a refactorisation that reuses the symbolic analysis).

use mortar::generate::{box_mesh, rectangle_mesh, CellShape};
use mortar::physics::heat::{HeatBody, HeatMaterial, HeatOptions, TiedHeat};
use mortar::physics::tied::{FormulationChoice, TiedOptions};
use mortar::CouplingOptions;
use mortar::VolumeMesh;
use nalgebra::Vector3;

fn problem(dim: usize) -> TiedHeat {
    let (k, rho_cp) = (1.3, 2.0);
    let b = Vector3::new(0.5, -1.0, if dim == 3 { 0.25 } else { 0.0 });
    let u = move |x: &Vector3<f64>, t: f64| (1.0 + t) * (2.0 + b.dot(x));
    let q = move |x: &Vector3<f64>, _t: f64| rho_cp * (2.0 + b.dot(x));
    let meshes: (VolumeMesh, VolumeMesh) = if dim == 2 {
        (
            rectangle_mesh([0.0, 0.0], [0.5, 1.0], [2, 4], CellShape::Tensor, 1).unwrap(),
            rectangle_mesh([0.5, 0.0], [1.0, 1.0], [3, 6], CellShape::Simplex, 1).unwrap(),
        )
    } else {
        (
            box_mesh([0.0; 3], [0.5, 1.0, 1.0], [2, 4, 4], CellShape::Tensor, 1).unwrap(),
            box_mesh([0.5, 0.0, 0.0], [1.0; 3], [3, 6, 6], CellShape::Simplex, 1).unwrap(),
        )
    };
    let on = |f: &mortar::core::mesh::BoundaryFace| (f.centroid.x - 0.5).abs() < 1e-12;
    let body = |name: &str, mesh: VolumeMesh| {
        HeatBody::new(name, mesh, HeatMaterial::new(k, rho_cp))
            .with_source(q)
            .with_dirichlet_where(move |f| !on(f), u)
            .unwrap()
    };
    let (master, slave) = (body("left", meshes.0), body("right", meshes.1));
    let ms = master.mesh.boundary_surface(on).unwrap();
    let ss = slave.mesh.boundary_surface(on).unwrap();
    TiedHeat::new(
        slave,
        master,
        ss,
        ms,
        &CouplingOptions::default().dual(),
        &HeatOptions::default(),
    )
    .unwrap()
}

#[test]
fn backward_euler_is_exact_for_fields_linear_in_space_and_time() {
    for dim in [2, 3] {
        let p = problem(dim);
        let b = Vector3::new(0.5, -1.0, if dim == 3 { 0.25 } else { 0.0 });
        let exact = |x: &Vector3<f64>, t: f64| (1.0 + t) * (2.0 + b.dot(x));
        for choice in [FormulationChoice::Auto, FormulationChoice::SaddlePoint] {
            let initial = [0, 1].map(|i| p.bodies()[i].interpolate(exact, 0.0));
            let mut be = p
                .backward_euler(
                    &TiedOptions::default().with_formulation(choice),
                    initial,
                    0.0,
                    0.1,
                )
                .unwrap();
            for step in 0..6 {
                if step == 3 {
                    be.set_time_step(0.05).unwrap();
                }
                be.step().unwrap();
            }
            assert!((be.time() - 0.45).abs() < 1e-14);
            for (i, body) in p.bodies().iter().enumerate() {
                let want = body.interpolate(exact, be.time());
                let err = be.solution().temperatures[i]
                    .iter()
                    .zip(&want)
                    .map(|(a, w)| (a - w).abs())
                    .fold(0.0, f64::max);
                assert!(
                    err < crate::claims::claim("tied.transient").bound,
                    "{dim}D {choice:?} body {i}: error {err:e}"
                );
            }
            // The flux leaving the slave body through x = 0.5 (n_s = -e_x).
            let want = 1.3 * (1.0 + be.time()) * b.x;
            for l in be.solution().flux.iter().filter(|l| l.is_finite()) {
                assert!(
                    (l - want).abs() < 1e-9,
                    "{dim}D {choice:?}: flux {l} vs {want}"
                );
            }
        }
        assert!(p
            .backward_euler(
                &TiedOptions::default(),
                [vec![0.0; 1], vec![0.0; 1]],
                0.0,
                0.1
            )
            .is_err());
        let init = [0, 1].map(|i| vec![0.0; p.bodies()[i].mesh.node_count()]);
        assert!(p
            .backward_euler(&TiedOptions::default(), init, 0.0, 0.0)
            .is_err());
    }
}
