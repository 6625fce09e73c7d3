//! Heat conduction in the axisymmetric (r-z) geometry ([`HeatOptions::geometry`]): a 2D mesh
//! with `x = r`, `y = z`, every integral weighted by `2 pi r`.
//!
//! Sources of the references (closed forms of steady radial conduction, e.g. Carslaw and
//! Jaeger, *Conduction of Heat in Solids*, 2nd ed., section 7.2; Incropera and DeWitt,
//! *Fundamentals of Heat and Mass Transfer*, sections 3.3.2 and 3.5.2):
//!
//! - a hollow cylinder `a <= r <= b`, insulated ends, `T(a)` and `T(b)` fixed:
//!   `T = A + B ln r`; with the flux `q` entering at `r = b` instead:
//!   `T = T(a) + (q b / k) ln(r / a)`;
//! - a solid cylinder of radius `a` with the uniform source `Q`, `T(a) = T_s`:
//!   `T = T_s + Q (a^2 - r^2) / (4 k)`, so `T_0 - T_s = Q a^2 / (4 k)`;
//! - with `k(T) = 1 / (A + B T)` the Kirchhoff transform `u = ln(A + B T) / B` is harmonic:
//!   `u = u_a + (u_b - u_a) ln(r / a) / ln(b / a)`, `T = (exp(B u) - A) / B`;
//! - volumes and areas of revolution: `pi (b^2 - a^2) H` and `2 pi b H`.
//!
//! Linear elements converge at the second order in L2 (and at the nodes): the measured rates
//! are checked, not error values.

use mortar::core::linalg::{solve_sparse_lu, SparseMatrix, Triplets};
use mortar::core::mesh::BoundaryFace;
use mortar::core::ModelGeometry;
use mortar::generate::{rectangle_mesh, CellShape};
use mortar::physics::heat::{
    assemble_conduction, assemble_heat_load, assemble_heat_matrices, error_norms, Conductivity,
    HeatBody, HeatMaterial, HeatOptions, Linearization,
};
use mortar::physics::PhysicsError;
use mortar::VolumeMesh;
use nalgebra::Vector3;
use std::f64::consts::PI;

pub(super) fn axisymmetric() -> HeatOptions {
    HeatOptions::default().with_geometry(ModelGeometry::Axisymmetric)
}

/// `a x = f` with the rows of `fixed` replaced by `x_i = value_i` (sparse LU).
pub(super) fn solve_with_dirichlet(
    a: &SparseMatrix,
    f: &[f64],
    fixed: &[u32],
    values: &[f64],
) -> Vec<f64> {
    let n = f.len();
    let mut is_fixed = vec![None; n];
    for (&i, &v) in fixed.iter().zip(values) {
        is_fixed[i as usize] = Some(v);
    }
    let mut t = Triplets::default();
    let mut rhs = f.to_vec();
    for (r, row) in a.outer_iterator().enumerate() {
        if let Some(v) = is_fixed[r] {
            t.push(r as u32, r as u32, 1.0);
            rhs[r] = v;
        } else {
            for (c, &v) in row.iter() {
                t.push(r as u32, c as u32, v);
            }
        }
    }
    solve_sparse_lu(&t.to_csr(n, n), &rhs).unwrap()
}

/// The steady temperature of one body: `K T = F` with its Dirichlet data.
fn solve_steady(body: &HeatBody, options: &HeatOptions) -> Vec<f64> {
    let m = assemble_heat_matrices(body, options).unwrap();
    let f = assemble_heat_load(body, 0.0, options).unwrap();
    let (nodes, conds) = body.dirichlet_nodes();
    let values = body.dirichlet_values(&nodes, &conds, 0.0);
    solve_with_dirichlet(&m.stiffness, &f, &nodes, &values)
}

fn at_r(r: f64) -> impl Fn(&BoundaryFace) -> bool {
    move |f| (f.centroid.x - r).abs() < 1e-9 && f.nodes.len() == 2
}

/// The r-z rectangle `[r0, r1] x [0, h]` with `n` cells radially and `m` axially.
fn section(r0: f64, r1: f64, h: f64, n: usize, m: usize, shape: CellShape) -> VolumeMesh {
    rectangle_mesh([r0, 0.0], [r1, h], [n, m], shape, 1).unwrap()
}

/// The r-z rectangle `[r0, r1] x [0, h]` with `n` cells radially and as many axially as
/// keep them about square (at least one): a uniform refinement in both directions.
fn square_cells(r0: f64, r1: f64, h: f64, n: usize, shape: CellShape) -> VolumeMesh {
    let m = ((n as f64 * h / (r1 - r0)).round() as usize).max(1);
    section(r0, r1, h, n, m, shape)
}

/// Values in scientific notation, for the printed tables.
pub(super) fn sci(v: &[f64]) -> String {
    let s: Vec<String> = v.iter().map(|x| format!("{x:.2e}")).collect();
    format!("[{}]", s.join(", "))
}

/// `log2` of successive ratios.
pub(super) fn rates(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// A hollow cylinder with both radii at fixed temperatures: `T = A + B ln r` to
/// discretisation error, at the second order in L2 and at the nodes (Quad4 and Tri3). The
/// Cartesian assembly of the same mesh gives the linear profile instead, far from it.
#[test]
fn annulus_reproduces_the_logarithmic_profile_at_second_order() {
    let (a, b, h, k) = (1.0, 2.0, 0.25, 3.0);
    let (ta, tb) = (500.0, 300.0);
    let exact = move |x: &Vector3<f64>| ta + (tb - ta) * (x.x / a).ln() / (b / a).ln();
    let grad = move |x: &Vector3<f64>| Vector3::new((tb - ta) / ((b / a).ln() * x.x), 0.0, 0.0);
    for shape in [CellShape::Tensor, CellShape::Simplex] {
        let (mut l2, mut nodal) = (Vec::new(), Vec::new());
        for n in [4, 8, 16, 32] {
            let body = HeatBody::new(
                "tube",
                square_cells(a, b, h, n, shape),
                HeatMaterial::new(k, 1.0),
            )
            .with_dirichlet_where(at_r(a), move |_, _| ta)
            .unwrap()
            .with_dirichlet_where(at_r(b), move |_, _| tb)
            .unwrap();
            let t = solve_steady(&body, &axisymmetric());
            let e = error_norms(&body.mesh, &t, &exact, &grad, None).unwrap();
            l2.push(e.l2);
            nodal.push(e.max_nodal);
            if n == 8 {
                // The planar (Cartesian) problem is the linear profile: off by ~10 K.
                let planar = solve_steady(&body, &HeatOptions::default());
                let e = error_norms(&body.mesh, &planar, &exact, &grad, None).unwrap();
                assert!(e.max_nodal > 5.0, "{shape:?}: planar error {}", e.max_nodal);
            }
        }
        println!(
            "annulus {shape:?}: L2 {sci_l2}, nodal {sci_nodal}, rates L2 {:.3?} nodal {:.3?}",
            rates(&l2),
            rates(&nodal),
            sci_l2 = sci(&l2),
            sci_nodal = sci(&nodal)
        );
        for r in rates(&l2) {
            assert!(r > 1.9, "{shape:?}: L2 rates {:?}", rates(&l2));
        }
        for r in rates(&nodal) {
            assert!(r > 1.8, "{shape:?}: nodal rates {:?}", rates(&nodal));
        }
        assert!(nodal[3] < 2e-3 * (ta - tb), "{shape:?}: {nodal:?}");
    }
}

/// A hollow cylinder with `T(a)` fixed and the heat flux `q` entering through `r = b` (a
/// Neumann face weighted by `2 pi r`): `T = T(a) + (q b / k) ln(r / a)`, second order.
#[test]
fn annulus_with_a_neumann_flux_at_second_order() {
    let (a, b, h, k, q) = (0.5, 1.5, 0.3, 2.0, 40.0);
    let ta = 350.0;
    let exact = move |x: &Vector3<f64>| ta + q * b / k * (x.x / a).ln();
    let grad = move |x: &Vector3<f64>| Vector3::new(q * b / (k * x.x), 0.0, 0.0);
    let mut l2 = Vec::new();
    for n in [4, 8, 16, 32] {
        let body = HeatBody::new(
            "tube",
            square_cells(a, b, h, n, CellShape::Simplex),
            HeatMaterial::new(k, 1.0),
        )
        .with_dirichlet_where(at_r(a), move |_, _| ta)
        .unwrap()
        .with_neumann_where(at_r(b), move |_, _| q)
        .unwrap();
        let t = solve_steady(&body, &axisymmetric());
        l2.push(error_norms(&body.mesh, &t, &exact, &grad, None).unwrap().l2);
    }
    println!(
        "annulus with flux: L2 {sci_l2}, rates {:.3?}",
        rates(&l2),
        sci_l2 = sci(&l2)
    );
    for r in rates(&l2) {
        assert!(r > 1.9, "rates {:?}", rates(&l2));
    }
}

/// A solid cylinder (`0 <= r <= a`, the axis a boundary without condition) with the uniform
/// source `Q` and `T(a) = T_s`: `T_0 - T_s = Q a^2 / (4 k)` at the axis nodes, to 1e-3 at
/// 64 radial cells (Quad4 and Tri3), and `T = T_s + Q (a^2 - r^2) / (4 k)` at the second
/// order in L2. The error at the axis nodes converges more slowly than in L2 (measured rates
/// 1.6 to 1.8 from 4 to 64 cells, growing towards 2, as `h^2 ln(1/h)` would).
#[test]
fn solid_cylinder_with_a_source_has_the_parabolic_profile() {
    let (a, h, k, q, ts) = (0.5, 0.125, 2.0, 8.0e3, 400.0);
    let rise = q * a * a / (4.0 * k);
    let exact = move |x: &Vector3<f64>| ts + q * (a * a - x.x * x.x) / (4.0 * k);
    let grad = move |x: &Vector3<f64>| Vector3::new(-q * x.x / (2.0 * k), 0.0, 0.0);
    for shape in [CellShape::Tensor, CellShape::Simplex] {
        let (mut errors, mut l2) = (Vec::new(), Vec::new());
        for n in [4, 8, 16, 32, 64] {
            let body = HeatBody::new(
                "pellet",
                square_cells(0.0, a, h, n, shape),
                HeatMaterial::new(k, 1.0),
            )
            .with_source(move |_, _| q)
            .with_dirichlet_where(at_r(a), move |_, _| ts)
            .unwrap();
            let t = solve_steady(&body, &axisymmetric());
            let centre = body
                .mesh
                .coords()
                .iter()
                .zip(&t)
                .filter(|(x, _)| x.x == 0.0)
                .map(|(_, t)| ((t - ts) - rise).abs() / rise)
                .fold(0.0, f64::max);
            errors.push(centre);
            l2.push(error_norms(&body.mesh, &t, &exact, &grad, None).unwrap().l2);
        }
        println!(
        "solid cylinder {shape:?}: relative error of T0 - Ts {}, rates {:.3?}; L2 {}, rates {:.3?}",
        sci(&errors),
        rates(&errors),
        sci(&l2),
        rates(&l2)
    );
        assert!(errors[4] < 1e-3, "{shape:?}: {errors:?}");
        for r in rates(&errors) {
            assert!(
                r > 1.55,
                "{shape:?}: rates at the axis {:?}",
                rates(&errors)
            );
        }
        // (1.89 from 4 to 8 Tri3 cells, pre-asymptotic; 1.99 from 32 to 64.)
        for r in rates(&l2) {
            assert!(r > 1.85, "{shape:?}: L2 rates {:?}", rates(&l2));
        }
    }
}

/// The capacity, source and Neumann loads integrate the revolved volume and area exactly:
/// `1^T C 1 = rho c_p pi (b^2 - a^2) H`, `sum F_Q = Q pi (b^2 - a^2) H`,
/// `sum F_q = q 2 pi b H`, `K 1 = 0`; and a backward Euler step of an insulated body with a
/// uniform source raises every node by `Q dt / (rho c_p)` to round-off (the capacity and the
/// source weighted alike).
#[test]
fn capacity_source_and_flux_integrate_the_revolved_measure() {
    let (a, b, h) = (0.3, 1.1, 0.7);
    let (rho_cp, q_src, q_flux, dt) = (2.5e6, 3.0e7, 1.5e4, 0.4);
    let volume = PI * (b * b - a * a) * h;
    for shape in [CellShape::Tensor, CellShape::Simplex] {
        let mut mesh = section(a, b, h, 5, 4, shape);
        // Interior nodes moved: general quadrilaterals and triangles.
        let moved: Vec<[f64; 3]> = mesh
            .coords()
            .iter()
            .map(|x| {
                let interior = x.x > a + 1e-9 && x.x < b - 1e-9 && x.y > 1e-9 && x.y < h - 1e-9;
                let s = if interior {
                    0.03 * (7.0 * x.x + 3.0 * x.y).sin()
                } else {
                    0.0
                };
                [x.x + s, x.y - s, 0.0]
            })
            .collect();
        mesh = rebuild(&mesh, &moved);
        let source_only = HeatBody::new("ring", mesh.clone(), HeatMaterial::new(1.7, rho_cp))
            .with_source(move |_, _| q_src);
        let m = assemble_heat_matrices(&source_only, &axisymmetric()).unwrap();
        let c_total: f64 = m.capacity.data().iter().sum();
        assert!(
            (c_total - rho_cp * volume).abs() < 1e-12 * rho_cp * volume,
            "{shape:?}"
        );
        let k1 = m
            .stiffness
            .outer_iterator()
            .map(|r| r.iter().map(|(_, v)| v).sum::<f64>().abs())
            .fold(0.0, f64::max);
        assert!(k1 < 1e-12, "{shape:?}: K 1 = {k1:e}");
        let f = assemble_heat_load(&source_only, 0.0, &axisymmetric()).unwrap();
        let f_total: f64 = f.iter().sum();
        assert!(
            (f_total - q_src * volume).abs() < 1e-12 * q_src * volume,
            "{shape:?}"
        );
        // Backward Euler from 300 K: (K + C/dt) T1 = C T0 / dt + F.
        let t0 = vec![300.0; f.len()];
        let c_t0 = matvec(&m.capacity, &t0);
        let rhs: Vec<f64> = c_t0.iter().zip(&f).map(|(c, f)| c / dt + f).collect();
        let t1 = solve_with_dirichlet(&m.backward_euler(dt), &rhs, &[], &[]);
        let want = 300.0 + q_src * dt / rho_cp;
        let worst = t1.iter().map(|t| (t - want).abs()).fold(0.0, f64::max);
        assert!(worst < 1e-10 * want, "{shape:?}: {worst:e}");
        let flux = HeatBody::new("ring", mesh, HeatMaterial::new(1.7, rho_cp))
            .with_neumann_where(at_r(b), move |_, _| q_flux)
            .unwrap();
        let f: f64 = assemble_heat_load(&flux, 0.0, &axisymmetric())
            .unwrap()
            .iter()
            .sum();
        let want = q_flux * 2.0 * PI * b * h;
        assert!((f - want).abs() < 1e-12 * want, "{shape:?}: {f} vs {want}");
    }
}

/// `a v`.
pub(super) fn matvec(a: &SparseMatrix, v: &[f64]) -> Vec<f64> {
    a.outer_iterator()
        .map(|row| row.iter().map(|(c, x)| x * v[c]).sum())
        .collect()
}

/// The same cells on moved node coordinates.
pub(super) fn rebuild(mesh: &VolumeMesh, coords: &[[f64; 3]]) -> VolumeMesh {
    let mut m = VolumeMesh::new();
    for (tag, x) in mesh.node_tags().iter().zip(coords) {
        m.add_node(*tag, *x).unwrap();
    }
    for c in 0..mesh.cell_count() {
        let cell = mesh.cell(c);
        let tags: Vec<u64> = cell
            .nodes
            .iter()
            .map(|&n| mesh.node_tags()[n as usize])
            .collect();
        m.add_cell(cell.element, &tags).unwrap();
    }
    m
}

/// `k(T) = 1 / (A + B T)` (the pellet law) across a hollow cylinder: Newton on
/// [`assemble_conduction`] converges quadratically, Picard linearly to the same solution, and
/// both reproduce the Kirchhoff closed form at the second order. The Newton matrix is the
/// derivative of the weighted heat flow (checked against a finite difference).
#[test]
fn temperature_dependent_conductivity_in_r_z() {
    let (a, b, h) = (1.0e-3, 4.0e-3, 1.0e-3);
    let (ca, cb) = (0.0375, 2.165e-4);
    let law = Conductivity::InverseLinear { a: ca, b: cb };
    let (t_in, t_out) = (1400.0, 700.0);
    let u = |t: f64| (ca + cb * t).ln() / cb;
    let (ua, ub) = (u(t_in), u(t_out));
    let exact = move |x: &Vector3<f64>| {
        let uu = ua + (ub - ua) * (x.x / a).ln() / (b / a).ln();
        ((cb * uu).exp() - ca) / cb
    };
    let grad = move |x: &Vector3<f64>| {
        let t = exact(x);
        // k(T) dT/dr = du/dr.
        let dudr = (ub - ua) / ((b / a).ln() * x.x);
        Vector3::new(dudr * (ca + cb * t), 0.0, 0.0)
    };
    let options = axisymmetric();
    let mut l2 = Vec::new();
    for n in [8, 16, 32, 64] {
        let body = HeatBody::new(
            "fuel",
            square_cells(a, b, h, n, CellShape::Tensor),
            HeatMaterial::new(1.0, 1.0),
        )
        .with_dirichlet_where(at_r(a), move |_, _| t_in)
        .unwrap()
        .with_dirichlet_where(at_r(b), move |_, _| t_out)
        .unwrap();
        let (nodes, conds) = body.dirichlet_nodes();
        let values = body.dirichlet_values(&nodes, &conds, 0.0);
        let mut newton_steps = 0;
        let mut solutions = Vec::new();
        for lin in [Linearization::Newton, Linearization::Picard] {
            let mut t = vec![0.5 * (t_in + t_out); body.mesh.node_count()];
            for (&i, &v) in nodes.iter().zip(&values) {
                t[i as usize] = v;
            }
            let mut history = Vec::new();
            for step in 0..200 {
                let (f, j) = assemble_conduction(&body, &law, &t, &options, Some(lin)).unwrap();
                let mut r: Vec<f64> = f.iter().map(|v| -v).collect();
                for &i in &nodes {
                    r[i as usize] = 0.0;
                }
                let norm = r.iter().map(|v| v * v).sum::<f64>().sqrt();
                history.push(norm);
                if norm < 1e-10 * history[0] || norm < 1e-13 {
                    if lin == Linearization::Newton {
                        newton_steps = step;
                    }
                    break;
                }
                let dt = solve_with_dirichlet(&j.unwrap(), &r, &nodes, &vec![0.0; nodes.len()]);
                for (ti, d) in t.iter_mut().zip(&dt) {
                    *ti += d;
                }
            }
            assert!(
                history.last().unwrap() < &(1e-10 * history[0]).max(1e-13),
                "{lin:?} n {n}: {history:?}"
            );
            solutions.push(t);
        }
        assert!(newton_steps <= 6, "n {n}: Newton took {newton_steps} steps");
        let diff = solutions[0]
            .iter()
            .zip(&solutions[1])
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        assert!(
            diff < 1e-8 * t_in,
            "n {n}: Newton and Picard differ by {diff:e} K"
        );
        l2.push(
            error_norms(&body.mesh, &solutions[0], &exact, &grad, None)
                .unwrap()
                .l2,
        );
        if n == 16 {
            // The Newton matrix against a central difference of the heat flow.
            let t = &solutions[0];
            let dir: Vec<f64> = (0..t.len())
                .map(|i| ((i * 7 % 11) as f64 - 5.0) * 3.0)
                .collect();
            let (_, j) =
                assemble_conduction(&body, &law, t, &options, Some(Linearization::Newton)).unwrap();
            let jv = matvec(&j.unwrap(), &dir);
            let eps = 1e-4;
            let shifted = |s: f64| {
                let ts: Vec<f64> = t.iter().zip(&dir).map(|(a, d)| a + s * d).collect();
                assemble_conduction(&body, &law, &ts, &options, None)
                    .unwrap()
                    .0
            };
            let (fp, fm) = (shifted(eps), shifted(-eps));
            let scale = jv.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let worst = (0..t.len())
                .map(|i| ((fp[i] - fm[i]) / (2.0 * eps) - jv[i]).abs())
                .fold(0.0, f64::max);
            assert!(
                worst < 1e-6 * scale,
                "Jacobian check {worst:e} vs {scale:e}"
            );
            // With a constant k the Picard matrix is the stiffness of assemble_heat_matrices.
            let k = 2.5;
            let body_k = HeatBody::new("fuel", body.mesh.clone(), HeatMaterial::new(k, 1.0));
            let (_, p) = assemble_conduction(
                &body_k,
                &Conductivity::Constant(k),
                t,
                &options,
                Some(Linearization::Picard),
            )
            .unwrap();
            let s = assemble_heat_matrices(&body_k, &options).unwrap().stiffness;
            let d = (&p.unwrap() - &s)
                .data()
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(d < 1e-12 * k, "Picard vs stiffness {d:e}");
        }
    }
    println!(
        "k(T) annulus: L2 {sci_l2}, rates {:.3?}",
        rates(&l2),
        sci_l2 = sci(&l2)
    );
    for r in rates(&l2) {
        assert!(r > 1.9, "rates {:?}", rates(&l2));
    }
}

/// The axisymmetric geometry refuses a 3D mesh and a node at a negative radius, naming the
/// body and the node.
#[test]
fn axisymmetric_heat_refuses_bad_meshes() {
    let cube =
        mortar::generate::box_mesh([0.0; 3], [1.0; 3], [1, 1, 1], CellShape::Tensor, 1).unwrap();
    let body = HeatBody::new("cube", cube, HeatMaterial::new(1.0, 1.0));
    match assemble_heat_matrices(&body, &axisymmetric()) {
        Err(PhysicsError::InvalidInput { body, what }) => {
            assert_eq!(body, "cube");
            assert!(what.contains("2D mesh"), "{what}");
        }
        other => panic!("expected InvalidInput, got {other:?}"),
    }
    let left = section(-0.5, 1.0, 1.0, 3, 1, CellShape::Tensor);
    let body = HeatBody::new("left", left, HeatMaterial::new(1.0, 1.0));
    for result in [
        assemble_heat_matrices(&body, &axisymmetric()).map(|_| ()),
        assemble_heat_load(&body, 0.0, &axisymmetric()).map(|_| ()),
        assemble_conduction(
            &body,
            &Conductivity::Constant(1.0),
            &[0.0; 8],
            &axisymmetric(),
            None,
        )
        .map(|_| ()),
    ] {
        match result {
            Err(PhysicsError::NegativeRadius { body, node, radius }) => {
                assert_eq!((body.as_str(), node, radius), ("left", 1, -0.5));
            }
            other => panic!("expected NegativeRadius, got {other:?}"),
        }
    }
    // The Cartesian assembly of the same mesh is fine.
    assert!(assemble_heat_matrices(&body, &HeatOptions::default()).is_ok());
}
