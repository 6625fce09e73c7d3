//! Linear elasticity in the axisymmetric (r-z) geometry ([`ElasticOptions::geometry`]):
//! components `(u_r, u_z)`, the hoop strain `u_r / r`, the weight `2 pi r`, the hoop stress in
//! the `zz` slot of the recovered Voigt stress.
//!
//! Sources of the references (closed forms):
//!
//! - Lamé's thick-walled cylinder under the internal pressure `p_i` and the external `p_o`,
//!   in plane strain (`eps_zz = 0`: `u_z = 0` on both ends). Timoshenko and Goodier, *Theory
//!   of Elasticity*, 3rd ed., section 33: `sigma_rr = A - B / r^2`, `sigma_tt = A + B / r^2`
//!   with `A = (p_i a^2 - p_o b^2) / (b^2 - a^2)`, `B = (p_i - p_o) a^2 b^2 / (b^2 - a^2)`,
//!   `sigma_zz = 2 nu A`, and `u_r = (1 + nu) / E ((1 - 2 nu) A r + B / r)`.
//! - Free thermal expansion of a solid cylinder in plane strain, traction-free outside
//!   (Timoshenko and Goodier, section 150):
//!   `u(r) = (1 + nu) / (1 - nu) alpha ((1 / r) int_0^r dT r dr + (1 - 2 nu) (r / a^2) int_0^a dT r dr)`,
//!   so `u(a) = (1 + nu) (2 alpha / a) int_0^a (T - T_ref) r dr`;
//!   for `dT = dT_0 (1 - r^2 / a^2)`: `u(a) = (1 + nu) alpha dT_0 a / 2`.
//! - The patch test: the uniform dilatation `u = eps (r, z)` (strains `eps` in rr, zz and tt,
//!   stress `3 K eps` in all three) lies in the discrete space and is reproduced to round-off
//!   on distorted cells, loaded by its tractions or by a uniform temperature.

use mortar::core::mesh::BoundaryFace;
use mortar::core::ModelGeometry;
use mortar::generate::{rectangle_mesh, CellShape};
use mortar::physics::elastic::{
    assemble_elastic_stiffness, recover_stress, solve_elastic_with, ComponentSet, ElasticBody,
    ElasticMaterial, ElasticOptions,
};
use mortar::physics::heat::error_norms;
use mortar::physics::PhysicsError;
use mortar::VolumeMesh;
use nalgebra::Vector3;

use super::axisymmetric_heat::{rates, rebuild, sci};

fn axisymmetric() -> ElasticOptions {
    ElasticOptions::default().with_geometry(ModelGeometry::Axisymmetric)
}

/// The r-z rectangle `[r0, r1] x [0, h]` with `n` cells radially and about square cells.
fn section(r0: f64, r1: f64, h: f64, n: usize, shape: CellShape) -> VolumeMesh {
    let m = ((n as f64 * h / (r1 - r0)).round() as usize).max(1);
    rectangle_mesh([r0, 0.0], [r1, h], [n, m], shape, 1).unwrap()
}

fn at_r(r: f64) -> impl Fn(&BoundaryFace) -> bool {
    move |f| (f.centroid.x - r).abs() < 1e-9
}

fn at_z(z: f64) -> impl Fn(&BoundaryFace) -> bool {
    move |f| (f.centroid.y - z).abs() < 1e-9
}

/// The nodes on the axis (x = 0).
fn axis_nodes(mesh: &VolumeMesh) -> Vec<u32> {
    (0..mesh.node_count() as u32)
        .filter(|&i| mesh.coords()[i as usize].x == 0.0)
        .collect()
}

/// Component `c` of a displacement vector.
fn component(u: &[f64], c: usize) -> Vec<f64> {
    u.iter().skip(c).step_by(2).copied().collect()
}

/// Lamé's cylinder (`a = 1`, `b = 2`) under internal and external pressure, plane strain:
/// `u_r(r)` at the second order in L2 (Quad4 and Tri3) and at the nodes (Quad4; Tri3 as
/// `h^2 ln(1/h)`), `u_z = 0`; the recovered cell stresses approach `sigma_rr`,
/// `sigma_zz = 2 nu A` (yy slot) and the hoop stress `sigma_tt` (zz slot) at the first order
/// or better.
#[test]
fn lame_cylinder_under_pressure_at_second_order() {
    let (a, b, h) = (1.0, 2.0, 0.5);
    let (e, nu) = (80e9, 0.4);
    let (pi, po) = (30e6, 15.5e6);
    let big_a = (pi * a * a - po * b * b) / (b * b - a * a);
    let big_b = (pi - po) * a * a * b * b / (b * b - a * a);
    let u_exact =
        move |x: &Vector3<f64>| (1.0 + nu) / e * ((1.0 - 2.0 * nu) * big_a * x.x + big_b / x.x);
    let du = move |x: &Vector3<f64>| {
        Vector3::new(
            (1.0 + nu) / e * ((1.0 - 2.0 * nu) * big_a - big_b / (x.x * x.x)),
            0.0,
            0.0,
        )
    };
    let options = axisymmetric();
    for shape in [CellShape::Tensor, CellShape::Simplex] {
        let (mut l2, mut nodal, mut stress) = (Vec::new(), Vec::new(), Vec::new());
        for n in [4, 8, 16, 32, 64] {
            let body = ElasticBody::new(
                "tube",
                section(a, b, h, n, shape),
                ElasticMaterial::new(e, nu),
            )
            .with_dirichlet_where(at_z(0.0), ComponentSet::One(1), |_| Vector3::zeros())
            .unwrap()
            .with_dirichlet_where(at_z(h), ComponentSet::One(1), |_| Vector3::zeros())
            .unwrap()
            .with_traction_where(at_r(a), move |_| Vector3::new(pi, 0.0, 0.0))
            .unwrap()
            .with_traction_where(at_r(b), move |_| Vector3::new(-po, 0.0, 0.0))
            .unwrap();
            let u = solve_elastic_with(&body, &options).unwrap();
            let ur = component(&u, 0);
            let uz = component(&u, 1);
            let err = error_norms(&body.mesh, &ur, &u_exact, &du, None).unwrap();
            let scale = u_exact(&Vector3::new(a, 0.0, 0.0)).abs();
            l2.push(err.l2);
            // The exact u_z is zero (Quad4 on rectangles: to round-off; Tri3: a discretisation
            // error).
            let uz_max = uz.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            nodal.push(err.max_nodal.max(uz_max) / scale);
            // Cell stresses against the closed form at the cell centroids.
            let s = recover_stress(&body, &u, &options).unwrap();
            let mut worst = 0.0f64;
            for (c, sc) in s.cells.iter().enumerate() {
                let cell = body.mesh.cell(c);
                let r = cell
                    .nodes
                    .iter()
                    .map(|&n| body.mesh.coords()[n as usize].x)
                    .sum::<f64>()
                    / cell.nodes.len() as f64;
                let want = [
                    big_a - big_b / (r * r),
                    2.0 * nu * big_a,
                    big_a + big_b / (r * r),
                ];
                for k in 0..3 {
                    worst = worst.max((sc[k] - want[k]).abs() / pi);
                }
                assert!(sc[3].abs() + sc[4].abs() < 1e-6 * pi, "out-of-plane shear");
            }
            stress.push(worst);
        }
        println!(
            "Lame {shape:?}: u_r L2 {} rates {:.3?}; nodal (relative) {} rates {:.3?}; \
             cell stress / p_i {} rates {:.3?}",
            sci(&l2),
            rates(&l2),
            sci(&nodal),
            rates(&nodal),
            sci(&stress),
            rates(&stress)
        );
        // Measured (Quad4 / Tri3): L2 1.95-2.00 / 1.73-1.98; nodal 1.95-2.00 / 1.39-1.75
        // (the maximum norm of linear triangles, h^2 ln(1/h)); cell stress 1.70-1.97 /
        // 0.46-0.96 (first order, pre-asymptotic on the coarsest Tri3 meshes).
        let tri = shape == CellShape::Simplex;
        let (l2_min, nodal_min, stress_min) = if tri {
            (1.7, 1.35, 0.45)
        } else {
            (1.9, 1.9, 1.65)
        };
        let check = |what: &str, r: Vec<f64>, min: f64, last: f64| {
            assert!(r.iter().all(|&x| x > min), "{shape:?}: {what} rates {r:?}");
            assert!(r[r.len() - 1] > last, "{shape:?}: {what} rates {r:?}");
        };
        check("L2", rates(&l2), l2_min, 1.95);
        check("nodal", rates(&nodal), nodal_min, 1.7);
        check("stress", rates(&stress), stress_min, 0.9);
        assert!(nodal[4] < 1e-3, "{shape:?}: {nodal:?}");
    }
}

/// Free thermal expansion of a solid cylinder with the parabolic temperature
/// `T - T_ref = dT_0 (1 - r^2 / a^2)`, `u_z = 0` on both ends (plane strain), `u_r = 0` on
/// the axis, traction-free outside: `u(a) = (1 + nu) alpha dT_0 a / 2` to 1e-3 at 32 radial
/// Quad4 (the error is that of the piecewise-linear temperature, `(h / a)^2 / 3` relative,
/// rate 2.000) or 64 radial cells cut into Tri3 (rates 1.49 to 1.73, the maximum norm of
/// linear triangles), and `u_r(r)` at the second order in L2.
#[test]
fn free_thermal_expansion_of_a_solid_cylinder() {
    let (a, h) = (4.1e-3, 1.0e-3);
    let (e, nu, alpha, t_ref, dt0) = (200e9, 0.3, 1.0e-5, 293.0, 900.0);
    let c = (1.0 + nu) / (1.0 - nu) * alpha * dt0;
    let u_exact = move |x: &Vector3<f64>| {
        let r = x.x;
        c * (r / 2.0 - r.powi(3) / (4.0 * a * a) + (1.0 - 2.0 * nu) * r / 4.0)
    };
    let du = move |x: &Vector3<f64>| {
        let r = x.x;
        Vector3::new(
            c * (0.5 - 3.0 * r * r / (4.0 * a * a) + (1.0 - 2.0 * nu) / 4.0),
            0.0,
            0.0,
        )
    };
    let u_a = (1.0 + nu) * alpha * dt0 * a / 2.0;
    assert!((u_exact(&Vector3::new(a, 0.0, 0.0)) - u_a).abs() < 1e-15 * u_a);
    let options = axisymmetric();
    for shape in [CellShape::Tensor, CellShape::Simplex] {
        let (mut l2, mut surface) = (Vec::new(), Vec::new());
        for n in [4, 8, 16, 32, 64] {
            let mesh = section(0.0, a, h, n, shape);
            let temperature: Vec<f64> = mesh
                .coords()
                .iter()
                .map(|x| t_ref + dt0 * (1.0 - x.x * x.x / (a * a)))
                .collect();
            let axis = axis_nodes(&mesh);
            let body = ElasticBody::new(
                "pellet",
                mesh,
                ElasticMaterial::new(e, nu).with_expansion(alpha, t_ref),
            )
            .with_temperature(temperature)
            .unwrap()
            .with_dirichlet_nodes(axis, ComponentSet::One(0), |_| Vector3::zeros())
            .with_dirichlet_where(at_z(0.0), ComponentSet::One(1), |_| Vector3::zeros())
            .unwrap()
            .with_dirichlet_where(at_z(h), ComponentSet::One(1), |_| Vector3::zeros())
            .unwrap();
            let u = solve_elastic_with(&body, &options).unwrap();
            let ur = component(&u, 0);
            l2.push(
                error_norms(&body.mesh, &ur, &u_exact, &du, None)
                    .unwrap()
                    .l2,
            );
            let at_surface = body
                .mesh
                .coords()
                .iter()
                .zip(&ur)
                .filter(|(x, _)| (x.x - a).abs() < 1e-12)
                .map(|(_, u)| (u - u_a).abs() / u_a)
                .fold(0.0, f64::max);
            surface.push(at_surface);
        }
        println!(
            "free expansion {shape:?}: u(a) relative error {} rates {:.3?}; L2 {} rates {:.3?}",
            sci(&surface),
            rates(&surface),
            sci(&l2),
            rates(&l2)
        );
        let tri = shape == CellShape::Simplex;
        assert!(
            surface[if tri { 4 } else { 3 }] < 1e-3,
            "{shape:?}: {surface:?}"
        );
        let min = if tri { 1.4 } else { 1.95 };
        for r in rates(&surface) {
            assert!(r > min, "{shape:?}: u(a) rates {:?}", rates(&surface));
        }
        for r in rates(&l2) {
            assert!(r > 1.85, "{shape:?}: L2 rates {:?}", rates(&l2));
        }
    }
}

/// The unit square `[0, 1]^2` (r-z) with `n x n` cells, its interior nodes moved by up to a
/// fifth of a cell (general quadrilaterals and triangles; the axis stays at r = 0).
fn distorted_square(n: usize, shape: CellShape) -> VolumeMesh {
    let mesh = rectangle_mesh([0.0, 0.0], [1.0, 1.0], [n, n], shape, 1).unwrap();
    let h = 1.0 / n as f64;
    let moved: Vec<[f64; 3]> = mesh
        .coords()
        .iter()
        .enumerate()
        .map(|(i, x)| {
            let inside = x.x > 1e-9 && x.x < 1.0 - 1e-9 && x.y > 1e-9 && x.y < 1.0 - 1e-9;
            let j = |d: f64| ((i as f64 + 1.0) * (d + 1.7) * 12.9898).sin();
            if inside {
                [x.x + 0.2 * h * j(0.0), x.y + 0.2 * h * j(1.0), 0.0]
            } else {
                [x.x, x.y, 0.0]
            }
        })
        .collect();
    rebuild(&mesh, &moved)
}

/// The patch test: the uniform dilatation `u = eps (r, z)` on distorted Quad4 and Tri3 cells
/// touching the axis, loaded by its tractions `3 K eps n` (outer radius and top, weighted by
/// `2 pi r`) or by the uniform temperature `eps / alpha` without traction, is reproduced to
/// round-off, with the stress `3 K eps` in rr, zz and the hoop slot (zero for the thermal
/// case) and a zero von Mises stress.
#[test]
fn uniform_dilatation_patch_test() {
    let (e, nu, eps) = (70e9, 0.33, 1e-3);
    let options = axisymmetric();
    for shape in [CellShape::Tensor, CellShape::Simplex] {
        for thermal in [false, true] {
            let mesh = distorted_square(4, shape);
            let axis = axis_nodes(&mesh);
            let n = mesh.node_count();
            let mut material = ElasticMaterial::new(e, nu);
            if thermal {
                material = material.with_expansion(2e-5, 300.0);
            }
            let three_k = e / (1.0 - 2.0 * nu);
            let s0 = three_k * eps;
            let mut body = ElasticBody::new("patch", mesh, material)
                .with_dirichlet_nodes(axis, ComponentSet::One(0), |_| Vector3::zeros())
                .with_dirichlet_where(at_z(0.0), ComponentSet::One(1), |_| Vector3::zeros())
                .unwrap();
            if thermal {
                body = body.with_temperature(vec![300.0 + eps / 2e-5; n]).unwrap();
            } else {
                body = body
                    .with_traction_where(at_r(1.0), move |_| Vector3::new(s0, 0.0, 0.0))
                    .unwrap()
                    .with_traction_where(at_z(1.0), move |_| Vector3::new(0.0, s0, 0.0))
                    .unwrap();
            }
            let u = solve_elastic_with(&body, &options).unwrap();
            let want = body.interpolate(|x| x * eps);
            let worst = u
                .iter()
                .zip(&want)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(
                worst < 1e-12 * eps,
                "{shape:?} thermal {thermal}: error {worst:e}"
            );
            let s = recover_stress(&body, &u, &options).unwrap();
            let expected = if thermal { 0.0 } else { s0 };
            for (sc, vm) in s.nodal.iter().zip(&s.von_mises) {
                for k in 0..3 {
                    assert!(
                        (sc[k] - expected).abs() < 1e-9 * s0,
                        "{shape:?} {thermal}: {sc:?}"
                    );
                }
                for k in 3..6 {
                    assert!(sc[k].abs() < 1e-9 * s0, "{shape:?} {thermal}: {sc:?}");
                }
                assert!(*vm < 1e-9 * s0, "{shape:?} {thermal}: von Mises {vm}");
            }
        }
    }
}

/// The hoop stress goes to the zz slot and counts in von Mises: a pure hoop strain field is
/// not representable alone, but a radial dilatation `u = eps (r, 0)` with free ends has
/// `eps_rr = eps_tt = eps`, `eps_zz = 0`: `sigma_rr = sigma_tt = (2 lambda + 2 mu) eps` (xx
/// and zz slots), `sigma_zz = 2 lambda eps` (yy slot), von Mises `2 mu eps`, to round-off.
#[test]
fn hoop_stress_is_in_the_zz_slot() {
    let (e, nu, eps) = (70e9, 0.33, 1e-3);
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    let mesh = distorted_square(3, CellShape::Tensor);
    let body = ElasticBody::new("hoop", mesh, ElasticMaterial::new(e, nu));
    let u = body.interpolate(|x| Vector3::new(eps * x.x, 0.0, 0.0));
    let s = recover_stress(&body, &u, &axisymmetric()).unwrap_err();
    // The axis nodes are free in this body: refused.
    assert!(matches!(s, PhysicsError::AxisNodeFree { .. }), "{s:?}");
    let axis = axis_nodes(&body.mesh);
    let body = body.with_dirichlet_nodes(axis, ComponentSet::One(0), |_| Vector3::zeros());
    let s = recover_stress(&body, &u, &axisymmetric()).unwrap();
    let want = [
        2.0 * (lambda + mu) * eps,
        2.0 * lambda * eps,
        2.0 * (lambda + mu) * eps,
    ];
    for (sc, vm) in s.cells.iter().zip(&s.von_mises) {
        for k in 0..3 {
            assert!(
                (sc[k] - want[k]).abs() < 1e-9 * want[0],
                "{sc:?} vs {want:?}"
            );
        }
        let _ = vm;
    }
    for vm in &s.von_mises {
        assert!(
            (vm - 2.0 * mu * eps).abs() < 1e-9 * want[0],
            "von Mises {vm}"
        );
    }
    // The plane-strain recovery of the same field has sigma_zz = lambda eps in the zz slot.
    let planar = recover_stress(&body, &u, &ElasticOptions::default()).unwrap();
    assert!((planar.cells[0][2] - lambda * eps).abs() < 1e-9 * want[0]);
}

/// Bad input: a node on the axis without a prescribed `u_r` (named), a 3D mesh, a node at a
/// negative radius.
#[test]
fn axisymmetric_elasticity_refuses_bad_input() {
    let mesh = section(0.0, 1.0, 1.0, 2, CellShape::Tensor);
    // Axis nodes: tags 1, 4, 7 (x = 0, row by row). Hold 1 and 7 only.
    let body = ElasticBody::new("pellet", mesh, ElasticMaterial::new(1e9, 0.3))
        .with_dirichlet_nodes(vec![0, 6], ComponentSet::One(0), |_| Vector3::zeros())
        .with_dirichlet_nodes(vec![0], ComponentSet::All, |_| Vector3::zeros());
    match assemble_elastic_stiffness(&body, &axisymmetric()) {
        Err(PhysicsError::AxisNodeFree { body, node }) => {
            assert_eq!((body.as_str(), node), ("pellet", 4));
        }
        other => panic!("expected AxisNodeFree, got {other:?}"),
    }
    let msg = assemble_elastic_stiffness(&body, &axisymmetric())
        .unwrap_err()
        .to_string();
    assert!(msg.contains("node 4") && msg.contains("u_r"), "{msg}");
    // Held: accepted. The Cartesian (plane-strain) assembly never asks.
    let held = body
        .clone()
        .with_dirichlet_nodes(vec![3], ComponentSet::One(0), |_| Vector3::zeros());
    assert!(assemble_elastic_stiffness(&held, &axisymmetric()).is_ok());
    assert!(assemble_elastic_stiffness(&body, &ElasticOptions::default()).is_ok());
    let cube =
        mortar::generate::box_mesh([0.0; 3], [1.0; 3], [1, 1, 1], CellShape::Tensor, 1).unwrap();
    let body = ElasticBody::new("cube", cube, ElasticMaterial::new(1e9, 0.3));
    assert!(matches!(
        assemble_elastic_stiffness(&body, &axisymmetric()),
        Err(PhysicsError::InvalidInput { .. })
    ));
    let left = section(-1.0, 1.0, 1.0, 2, CellShape::Tensor);
    let body = ElasticBody::new("left", left, ElasticMaterial::new(1e9, 0.3));
    match assemble_elastic_stiffness(&body, &axisymmetric()) {
        Err(PhysicsError::NegativeRadius { body, node, radius }) => {
            assert_eq!((body.as_str(), node, radius), ("left", 1, -1.0));
        }
        other => panic!("expected NegativeRadius, got {other:?}"),
    }
}
