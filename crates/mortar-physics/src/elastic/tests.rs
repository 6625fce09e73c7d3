//! Verification of the elasticity against closed-form solutions: patch tests, uniaxial
//! tension, free thermal expansion, rigid body modes, and the refusal of bad input.
//!
//! Meshes are built by hand (the structured generators live in the facade crate): the unit
//! square or cube, interior nodes moved by a deterministic jitter so that the cells are
//! irregular (general quadrilaterals and hexahedra, not parallelograms). Systems are solved
//! densely after eliminating the Dirichlet unknowns.

use mortar_core::linalg::SparseMatrix;
use mortar_elements::volume::{HEX8, QUAD4, TET4, TRI3};
use mortar_fem::element::VolumeElementRef;
use mortar_fem::mesh::VolumeMesh;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

use super::*;
use crate::error::PhysicsError;

const E: f64 = 70e9;
const NU: f64 = 0.33;

/// A deterministic value in [-1, 1] for node `i`, coordinate `d`.
fn jitter(i: usize, d: usize) -> f64 {
    ((i as f64 + 1.0) * (d as f64 + 1.7) * 12.9898).sin()
}

/// The unit square with `n x n` cells (Tri3: two per square; Quad4), the interior nodes moved
/// by up to `amp` cell sizes in each direction.
fn square(n: usize, simplex: bool, amp: f64) -> VolumeMesh {
    let mut m = VolumeMesh::new();
    let id = |i: usize, j: usize| (i + (n + 1) * j) as u64 + 1;
    let h = 1.0 / n as f64;
    for j in 0..=n {
        for i in 0..=n {
            let mut p = [i as f64 * h, j as f64 * h, 0.0];
            if i > 0 && i < n && j > 0 && j < n {
                for (d, p) in p.iter_mut().take(2).enumerate() {
                    *p += amp * h * jitter(id(i, j) as usize, d);
                }
            }
            m.add_node(id(i, j), p).unwrap();
        }
    }
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if simplex {
                m.add_cell(&TRI3, &[a, b, c]).unwrap();
                m.add_cell(&TRI3, &[a, c, d]).unwrap();
            } else {
                m.add_cell(&QUAD4, &[a, b, c, d]).unwrap();
            }
        }
    }
    m
}

/// The six tetrahedra of a cube (Gmsh hexahedron corners) around its diagonal 0-6.
const KUHN: [[usize; 4]; 6] = [
    [0, 1, 2, 6],
    [0, 2, 3, 6],
    [0, 3, 7, 6],
    [0, 7, 4, 6],
    [0, 4, 5, 6],
    [0, 5, 1, 6],
];

/// The unit cube with `n^3` cells (Tet4: six per cube; Hex8), the interior nodes moved by up
/// to `amp` cell sizes in each direction.
fn cube(n: usize, simplex: bool, amp: f64) -> VolumeMesh {
    let mut m = VolumeMesh::new();
    let id = |i: usize, j: usize, k: usize| (i + (n + 1) * (j + (n + 1) * k)) as u64 + 1;
    let h = 1.0 / n as f64;
    let inner = |i: usize| i > 0 && i < n;
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                let mut p = [i as f64 * h, j as f64 * h, k as f64 * h];
                if inner(i) && inner(j) && inner(k) {
                    for (d, p) in p.iter_mut().enumerate() {
                        *p += amp * h * jitter(id(i, j, k) as usize, d);
                    }
                }
                m.add_node(id(i, j, k), p).unwrap();
            }
        }
    }
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let c = [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ];
                if simplex {
                    for t in KUHN {
                        m.add_cell(&TET4, &t.map(|a| c[a])).unwrap();
                    }
                } else {
                    m.add_cell(&HEX8, &c).unwrap();
                }
            }
        }
    }
    m
}

/// The four test meshes: (element, mesh).
fn meshes() -> Vec<(VolumeElementRef, VolumeMesh)> {
    vec![
        (&TRI3 as VolumeElementRef, square(3, true, 0.25)),
        (&QUAD4 as VolumeElementRef, square(3, false, 0.25)),
        (&TET4 as VolumeElementRef, cube(3, true, 0.1)),
        (&HEX8 as VolumeElementRef, cube(3, false, 0.15)),
    ]
}

/// `y = K x`.
fn matvec(k: &SparseMatrix, x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; k.rows()];
    for (v, (r, c)) in k.iter() {
        y[r] += v * x[c];
    }
    y
}

/// Assembles and solves `K u = f` with the body's Dirichlet values (eliminated; dense
/// Cholesky on the free unknowns).
fn solve(body: &ElasticBody) -> Vec<f64> {
    let opts = ElasticOptions::default();
    let k = assemble_elastic_stiffness(body, &opts).unwrap();
    let f = assemble_elastic_load(body, &opts).unwrap();
    let (fixed, values) = body.dirichlet_dofs();
    let n = f.len();
    let mut u = vec![0.0; n];
    let mut pos = vec![usize::MAX; n];
    for (&d, &v) in fixed.iter().zip(&values) {
        u[d as usize] = v;
        pos[d as usize] = usize::MAX - 1;
    }
    let free: Vec<usize> = (0..n).filter(|&i| pos[i] == usize::MAX).collect();
    for (p, &i) in free.iter().enumerate() {
        pos[i] = p;
    }
    let m = free.len();
    let mut a = DMatrix::<f64>::zeros(m, m);
    let mut b = DVector::from_iterator(m, free.iter().map(|&i| f[i]));
    for (v, (r, c)) in k.iter() {
        if pos[r] >= m {
            continue;
        }
        if pos[c] < m {
            a[(pos[r], pos[c])] += v;
        } else {
            b[pos[r]] -= v * u[c];
        }
    }
    let x = a.cholesky().expect("K_ff is SPD").solve(&b);
    for (p, &i) in free.iter().enumerate() {
        u[i] = x[p];
    }
    u
}

/// `max |a - b| / max |b|`.
fn rel_err(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    err / scale
}

/// The largest component error of a stress field (nodal and cell values) against the constant
/// stress `exact`, relative to `scale`.
fn stress_err(s: &StressField, exact: &[f64; 6], scale: f64) -> f64 {
    s.nodal
        .iter()
        .chain(&s.cells)
        .flat_map(|v| v.iter().zip(exact).map(|(a, b)| (a - b).abs()))
        .fold(0.0f64, f64::max)
        / scale
}

/// `lambda tr(eps) I + 2 mu eps` for the symmetric part `eps` of `a`, Voigt order.
fn hooke(a: &Matrix3<f64>, material: &ElasticMaterial) -> [f64; 6] {
    let (lambda, mu) = material.lame();
    let eps = (a + a.transpose()) * 0.5;
    let tr = eps.trace();
    [
        lambda * tr + 2.0 * mu * eps[(0, 0)],
        lambda * tr + 2.0 * mu * eps[(1, 1)],
        lambda * tr + 2.0 * mu * eps[(2, 2)],
        2.0 * mu * eps[(1, 2)],
        2.0 * mu * eps[(0, 2)],
        2.0 * mu * eps[(0, 1)],
    ]
}

fn on_plane(d: usize, v: f64) -> impl Fn(&mortar_fem::mesh::BoundaryFace) -> bool {
    move |f| (f.centroid[d] - v).abs() < 1e-12
}

/// The symmetry conditions `u_d = 0` on `x_d = 0` for every direction of the mesh.
fn symmetry(mut body: ElasticBody) -> ElasticBody {
    for d in 0..body.components() {
        body = body
            .with_dirichlet_where(on_plane(d, 0.0), ComponentSet::One(d), |_| Vector3::zeros())
            .unwrap();
    }
    body
}

/// Patch test (Irons; Zienkiewicz & Taylor, The Finite Element Method, vol. 1, ch. 9): with
/// the linear displacement `u = A x + b` (a general `A`) prescribed on the whole boundary and
/// no load, the exact solution is `u` itself, which every conforming element of this module
/// represents; the stress is the constant `C : sym(A)`. Tri3 and Quad4 (plane strain, the
/// third row and column of A zero) on the unit square, Tet4 and Hex8 on the unit cube, all
/// with irregular interior nodes.
#[test]
fn patch_test_reproduces_linear_fields_and_their_stress() {
    let material = ElasticMaterial::new(E, NU);
    for (el, mesh) in meshes() {
        let dim = mesh.dim().unwrap();
        let mut a = Matrix3::new(
            1.3e-3, -0.7e-3, 0.4e-3, 0.9e-3, -1.1e-3, 0.6e-3, -0.2e-3, 0.5e-3, 0.8e-3,
        );
        let mut b = Vector3::new(1e-4, -2e-4, 3e-4);
        if dim == 2 {
            for k in 0..3 {
                a[(2, k)] = 0.0;
                a[(k, 2)] = 0.0;
            }
            b.z = 0.0;
        }
        let exact = move |x: &Vector3<f64>| a * x + b;
        let body = ElasticBody::new("patch", mesh, material)
            .with_dirichlet_where(|_| true, ComponentSet::All, exact)
            .unwrap();
        let u = solve(&body);
        let err_u = rel_err(&u, &body.interpolate(exact));
        let s = recover_stress(&body, &u, &ElasticOptions::default()).unwrap();
        let sigma = hooke(&a, &material);
        let scale = sigma.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let err_s = stress_err(&s, &sigma, scale);
        eprintln!(
            "patch {}: displacement {err_u:.2e}, stress {err_s:.2e}",
            el.name()
        );
        assert!(err_u < 1e-12, "{}: displacement error {err_u:e}", el.name());
        assert!(err_s < 1e-10, "{}: stress error {err_s:e}", el.name());
        if dim == 2 {
            // Plane strain: sigma_zz = lambda (eps_xx + eps_yy), no out-of-plane shear.
            let (lambda, _) = material.lame();
            let zz = lambda * (a[(0, 0)] + a[(1, 1)]);
            assert!((s.nodal[0][2] - zz).abs() < 1e-10 * scale);
        }
    }
}

/// Uniaxial tension of the unit cube (Timoshenko & Goodier, Theory of Elasticity, sec. 1-5,
/// Hooke's law): symmetry conditions on the three planes through the origin, traction
/// `sigma e_x` on `x = 1`. Exact: `u_x = sigma x / E`, `u_y = -nu sigma y / E`,
/// `u_z = -nu sigma z / E`, stress `sigma e_x e_x`.
#[test]
fn uniaxial_tension_3d() {
    let material = ElasticMaterial::new(E, NU);
    let sigma = 1e8;
    for (el, mesh) in meshes().into_iter().filter(|(e, _)| e.dim() == 3) {
        let body = symmetry(ElasticBody::new("bar", mesh, material))
            .with_traction_where(on_plane(0, 1.0), move |_| Vector3::new(sigma, 0.0, 0.0))
            .unwrap();
        let u = solve(&body);
        let exact = |x: &Vector3<f64>| Vector3::new(x.x, -NU * x.y, -NU * x.z) * (sigma / E);
        let err_u = rel_err(&u, &body.interpolate(exact));
        let s = recover_stress(&body, &u, &ElasticOptions::default()).unwrap();
        let err_s = stress_err(&s, &[sigma, 0.0, 0.0, 0.0, 0.0, 0.0], sigma);
        let vm = s
            .von_mises
            .iter()
            .fold(0.0f64, |m, v| m.max((v - sigma).abs()))
            / sigma;
        eprintln!(
            "uniaxial 3D {}: displacement {err_u:.2e}, stress {err_s:.2e}, von Mises {vm:.2e}",
            el.name()
        );
        assert!(err_u < 1e-12, "{}: displacement error {err_u:e}", el.name());
        assert!(err_s < 1e-10, "{}: stress error {err_s:e}", el.name());
        assert!(vm < 1e-10);
    }
}

/// Uniaxial tension in plane strain (Timoshenko & Goodier, sec. 1-5 with `eps_zz = 0`):
/// `sigma_xx = sigma`, `sigma_yy = 0`, hence `sigma_zz = nu sigma`,
/// `eps_xx = sigma (1 - nu^2) / E`, `eps_yy = -nu (1 + nu) sigma / E`.
#[test]
fn uniaxial_tension_plane_strain() {
    let material = ElasticMaterial::new(E, NU);
    let sigma = 1e8;
    for (el, mesh) in meshes().into_iter().filter(|(e, _)| e.dim() == 2) {
        let body = symmetry(ElasticBody::new("strip", mesh, material))
            .with_traction_where(on_plane(0, 1.0), move |_| Vector3::new(sigma, 0.0, 0.0))
            .unwrap();
        let u = solve(&body);
        let exact = |x: &Vector3<f64>| {
            Vector3::new((1.0 - NU * NU) * x.x, -NU * (1.0 + NU) * x.y, 0.0) * (sigma / E)
        };
        let err_u = rel_err(&u, &body.interpolate(exact));
        let s = recover_stress(&body, &u, &ElasticOptions::default()).unwrap();
        let err_s = stress_err(&s, &[sigma, 0.0, NU * sigma, 0.0, 0.0, 0.0], sigma);
        eprintln!(
            "uniaxial plane strain {}: displacement {err_u:.2e}, stress {err_s:.2e}",
            el.name()
        );
        assert!(err_u < 1e-12, "{}: displacement error {err_u:e}", el.name());
        assert!(err_s < 1e-10, "{}: stress error {err_s:e}", el.name());
    }
}

/// Free thermal expansion (Timoshenko & Goodier, ch. 13, uniform heating): a uniform
/// temperature rise `dT` with only the symmetry conditions gives `u = alpha dT x` and no
/// stress in 3D; in plane strain `eps_zz = 0` makes `u = (1 + nu) alpha dT x` and the only
/// stress `sigma_zz = -E alpha dT`.
#[test]
fn free_thermal_expansion() {
    let (alpha, t_ref, dt) = (2.3e-5, 293.0, 150.0);
    let material = ElasticMaterial::new(E, NU).with_expansion(alpha, t_ref);
    for (el, mesh) in meshes() {
        let dim = mesh.dim().unwrap();
        let n = mesh.node_count();
        let body = symmetry(ElasticBody::new("heated", mesh, material))
            .with_temperature(vec![t_ref + dt; n])
            .unwrap();
        let u = solve(&body);
        let strain = if dim == 3 {
            alpha * dt
        } else {
            (1.0 + NU) * alpha * dt
        };
        let err_u = rel_err(&u, &body.interpolate(|x| x * strain));
        let s = recover_stress(&body, &u, &ElasticOptions::default()).unwrap();
        let szz = if dim == 3 { 0.0 } else { -E * alpha * dt };
        // Relative to the stress of the fully constrained body, 3 K alpha dT.
        let scale = material.thermal_stress_coefficient() * dt;
        let err_s = stress_err(&s, &[0.0, 0.0, szz, 0.0, 0.0, 0.0], scale);
        eprintln!(
            "thermal {}: displacement {err_u:.2e}, stress {err_s:.2e} of 3K alpha dT",
            el.name()
        );
        assert!(err_u < 1e-12, "{}: displacement error {err_u:e}", el.name());
        assert!(err_s < 1e-10, "{}: stress error {err_s:e}", el.name());
    }
}

/// A displacement field.
type Mode = dyn Fn(&Vector3<f64>) -> Vector3<f64>;

/// Rigid body modes (any linear elasticity text: `eps(u) = 0` for a translation `c` and an
/// infinitesimal rotation `w x x`): `K r = 0`. Checked to round-off relative to
/// `max |K_ij| max |r|`.
#[test]
fn rigid_body_modes_are_in_the_kernel() {
    let material = ElasticMaterial::new(E, NU);
    for (el, mesh) in meshes() {
        let dim = mesh.dim().unwrap();
        let body = ElasticBody::new("free", mesh, material);
        let k = assemble_elastic_stiffness(&body, &ElasticOptions::default()).unwrap();
        let kmax = k.data().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut modes: Vec<Box<Mode>> = Vec::new();
        for d in 0..dim {
            modes.push(Box::new(move |_| Vector3::ith(d, 1.0)));
        }
        let axes = if dim == 3 { vec![0, 1, 2] } else { vec![2] };
        for d in axes {
            modes.push(Box::new(move |x| Vector3::<f64>::ith(d, 1.0).cross(x)));
        }
        let mut worst = 0.0f64;
        for mode in &modes {
            let r = body.interpolate(mode);
            let rmax = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let kr = matvec(&k, &r);
            let e = kr.iter().fold(0.0f64, |m, v| m.max(v.abs())) / (kmax * rmax);
            worst = worst.max(e);
        }
        eprintln!(
            "rigid modes {}: max |K r| / (max|K| max|r|) = {worst:.2e}",
            el.name()
        );
        assert!(worst < 1e-13, "{}: {worst:e}", el.name());
    }
}

/// The stiffness is symmetric bit for bit, and the stiffness and the load are the same bit
/// for bit on one thread and on several (750 Tet4 cells: two chunks).
#[test]
fn assembly_is_symmetric_and_independent_of_the_thread_count() {
    let material = ElasticMaterial::new(E, NU).with_expansion(1e-5, 0.0);
    let mesh = cube(5, true, 0.1);
    let n = mesh.node_count();
    let body = ElasticBody::new("chunks", mesh, material)
        .with_temperature((0..n).map(|i| 10.0 * jitter(i, 0)).collect())
        .unwrap()
        .with_body_force(|x| Vector3::new(x.y, -x.z, 3.0 * x.x))
        .with_traction_where(on_plane(2, 1.0), |x| Vector3::new(0.0, x.x, -1.0))
        .unwrap();
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let o = ElasticOptions::default();
                (
                    assemble_elastic_stiffness(&body, &o).unwrap(),
                    assemble_elastic_load(&body, &o).unwrap(),
                )
            })
    };
    let (k1, f1) = run(1);
    let (k3, f3) = run(3);
    assert_eq!(k1.indptr(), k3.indptr());
    assert_eq!(k1.indices(), k3.indices());
    assert!(k1
        .data()
        .iter()
        .zip(k3.data())
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    assert!(f1.iter().zip(&f3).all(|(a, b)| a.to_bits() == b.to_bits()));
    let kt: SparseMatrix = k1.transpose_view().to_csr();
    assert_eq!(k1.indices(), kt.indices());
    assert!(k1
        .data()
        .iter()
        .zip(kt.data())
        .all(|(a, b)| a.to_bits() == b.to_bits()));
}

/// The load of a uniform body force and a uniform traction sums to the total force
/// (`b |body| + t |face|`), per component.
#[test]
fn loads_sum_to_the_total_force() {
    let material = ElasticMaterial::new(E, NU);
    for (el, mesh) in meshes() {
        let dim = mesh.dim().unwrap();
        let body = ElasticBody::new("loaded", mesh, material)
            .with_body_force(|_| Vector3::new(1.0, -2.0, 3.0))
            .with_traction_where(on_plane(1, 1.0), |_| Vector3::new(5.0, 7.0, -11.0))
            .unwrap();
        let f = assemble_elastic_load(&body, &ElasticOptions::default()).unwrap();
        let expected = [6.0, 5.0, -8.0];
        for c in 0..dim {
            let total: f64 = f.iter().skip(c).step_by(dim).sum();
            assert!(
                (total - expected[c]).abs() < 1e-12,
                "{}: {total} vs {}",
                el.name(),
                expected[c]
            );
        }
    }
}

/// Poisson's ratio 0.5 and a zero Young's modulus are refused with an error naming the body
/// and the allowed range.
#[test]
fn invalid_material_is_refused_naming_the_body() {
    let cases = [
        (ElasticMaterial::new(E, 0.5), "Poisson's ratio", "(-1, 0.5)"),
        (
            ElasticMaterial::new(E, -1.0),
            "Poisson's ratio",
            "(-1, 0.5)",
        ),
        (ElasticMaterial::new(0.0, NU), "Young's modulus", "0 < E"),
        (
            ElasticMaterial::new(f64::NAN, NU),
            "Young's modulus",
            "0 < E",
        ),
        (
            ElasticMaterial::new(E, NU).with_expansion(f64::INFINITY, 0.0),
            "expansion",
            "finite",
        ),
    ];
    for (material, which, range) in cases {
        let body = ElasticBody::new("bad block", square(1, false, 0.0), material);
        for result in [
            assemble_elastic_stiffness(&body, &ElasticOptions::default()).map(|_| ()),
            assemble_elastic_load(&body, &ElasticOptions::default()).map(|_| ()),
            recover_stress(&body, &[0.0; 8], &ElasticOptions::default()).map(|_| ()),
        ] {
            match result {
                Err(PhysicsError::InvalidInput { body, what }) => {
                    assert_eq!(body, "bad block");
                    assert!(what.contains(which) && what.contains(range), "{what}");
                }
                other => panic!("expected InvalidInput, got {other:?}"),
            }
        }
    }
}

/// Other bad input: a temperature or displacement of the wrong length, a z condition in 2D,
/// a Dirichlet node beyond the mesh, an inverted cell, a quadrature degree out of range.
#[test]
fn other_bad_input_is_refused() {
    let material = ElasticMaterial::new(E, NU);
    let body = ElasticBody::new("plate", square(2, true, 0.0), material);
    assert!(matches!(
        body.clone().with_temperature(vec![0.0; 3]),
        Err(PhysicsError::WrongLength {
            expected: 9,
            got: 3,
            ..
        })
    ));
    assert!(matches!(
        body.clone().with_temperature(vec![f64::NAN; 9]),
        Err(PhysicsError::InvalidInput { .. })
    ));
    assert!(matches!(
        recover_stress(&body, &[0.0; 9], &ElasticOptions::default()),
        Err(PhysicsError::WrongLength {
            expected: 18,
            got: 9,
            ..
        })
    ));
    match body
        .clone()
        .with_dirichlet_where(|_| true, ComponentSet::One(2), |_| Vector3::zeros())
    {
        Err(PhysicsError::InvalidInput { body, what }) => {
            assert_eq!(body, "plate");
            assert!(what.contains("component z"), "{what}");
        }
        other => panic!("expected InvalidInput, got {other:?}"),
    }
    assert!(matches!(
        body.clone()
            .with_dirichlet_where(|_| false, ComponentSet::All, |_| Vector3::zeros()),
        Err(PhysicsError::InvalidInput { .. })
    ));
    let far = body
        .clone()
        .with_dirichlet_nodes(vec![99], ComponentSet::All, |_| Vector3::zeros());
    assert!(matches!(
        far.check(),
        Err(PhysicsError::InvalidInput { .. })
    ));
    let z = body
        .clone()
        .with_dirichlet_nodes(vec![0], ComponentSet::One(2), |_| Vector3::zeros());
    assert!(matches!(z.check(), Err(PhysicsError::InvalidInput { .. })));
    assert!(matches!(
        assemble_elastic_stiffness(
            &body,
            &ElasticOptions {
                quadrature_degree: Some(99),
                ..Default::default()
            }
        ),
        Err(PhysicsError::InvalidInput { .. })
    ));
    let mut mesh = VolumeMesh::new();
    for (t, p) in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]].iter().enumerate() {
        mesh.add_node(t as u64 + 1, [p[0], p[1], 0.0]).unwrap();
    }
    mesh.add_cell_with_tag(7, &TRI3, &[1, 3, 2]).unwrap();
    let inverted = ElasticBody::new("flipped", mesh, material);
    match assemble_elastic_stiffness(&inverted, &ElasticOptions::default()) {
        Err(PhysicsError::InvertedCell { body, cell, .. }) => {
            assert_eq!((body.as_str(), cell), ("flipped", 7));
        }
        other => panic!("expected InvertedCell, got {other:?}"),
    }
    let empty = ElasticBody::new("empty", VolumeMesh::new(), material);
    assert!(matches!(
        assemble_elastic_stiffness(&empty, &ElasticOptions::default()),
        Err(PhysicsError::InvalidInput { .. })
    ));
}

/// Overlapping Dirichlet conditions: the one added last wins, per component; values are the
/// field's components at the node.
#[test]
fn dirichlet_dofs_last_condition_wins() {
    let body = ElasticBody::new("plate", square(1, false, 0.0), ElasticMaterial::new(E, NU))
        .with_dirichlet_where(on_plane(0, 0.0), ComponentSet::All, |x| {
            Vector3::new(1.0, 2.0 + x.y, 0.0)
        })
        .unwrap()
        .with_dirichlet_where(on_plane(1, 0.0), ComponentSet::One(1), |x| {
            Vector3::new(9.0, -x.x, 9.0)
        })
        .unwrap();
    // Nodes: 0 (0,0), 1 (1,0), 2 (0,1), 3 (1,1).
    let (dofs, values) = body.dirichlet_dofs();
    assert_eq!(dofs, vec![0, 1, 3, 4, 5]);
    assert_eq!(values, vec![1.0, -0.0, -1.0, 1.0, 3.0]);
}

/// A field's numbering error reaches the physics as the `InvalidInput` it always was: body
/// `"options"` for a user's component name, `"dof layout"` for the rest, the same text.
#[test]
fn field_errors_keep_their_physics_form() {
    match "xy".parse::<ComponentSet>().map_err(PhysicsError::from) {
        Err(PhysicsError::InvalidInput { body, what }) => {
            assert_eq!(body, "options");
            assert!(what.contains("x, y, z or all"), "{what}");
        }
        other => panic!("expected InvalidInput, got {other:?}"),
    }
    match DofLayout::new(4, 3)
        .expand_nodes(&[4], ComponentSet::All)
        .map_err(PhysicsError::from)
    {
        Err(PhysicsError::InvalidInput { body, what }) => {
            assert_eq!(body, "dof layout");
            assert!(
                what.contains("node index 4 is beyond the layout's 4 nodes"),
                "{what}"
            );
        }
        other => panic!("expected InvalidInput, got {other:?}"),
    }
}

/// `solve_elastic` agrees with the dense solve of these tests, and refuses a body held in x
/// only (free to move in y and to turn): an error that says so, not a solution of round-off
/// size.
#[test]
fn solve_elastic_solves_and_refuses_a_body_not_held() {
    let material = ElasticMaterial::new(210e9, 0.3).with_expansion(1e-5, 300.0);
    let held = ElasticBody::new("held", square(4, true, 0.1), material)
        .with_temperature(vec![350.0; 25])
        .unwrap()
        .with_traction_where(
            |f| (f.centroid.x - 1.0).abs() < 1e-12,
            |_| Vector3::new(1e6, 2e5, 0.0),
        )
        .unwrap()
        .with_dirichlet_where(
            |f| f.centroid.x.abs() < 1e-12,
            ComponentSet::All,
            |_| Vector3::zeros(),
        )
        .unwrap();
    let sparse = solve_elastic(&held).unwrap();
    assert!(rel_err(&sparse, &solve(&held)) < 1e-12);

    let floating = ElasticBody::new("floating", square(4, true, 0.1), material)
        .with_traction_where(
            |f| (f.centroid.x - 1.0).abs() < 1e-12,
            |_| Vector3::new(1e6, 2e5, 0.0),
        )
        .unwrap()
        .with_dirichlet_where(
            |f| f.centroid.x.abs() < 1e-12,
            ComponentSet::One(0),
            |_| Vector3::zeros(),
        )
        .unwrap();
    match solve_elastic(&floating) {
        Err(e @ PhysicsError::InvalidInput { .. }) => {
            assert!(e.to_string().contains("not held"), "{e}")
        }
        other => panic!("expected a refusal, got {other:?}"),
    }
}
