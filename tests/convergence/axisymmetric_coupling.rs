//! The mortar operators in the axisymmetric (r-z) measure `2 pi r ds`
//! ([`CouplingOptions::geometry`]).
//!
//! Sources of the references (closed forms): the lateral area of a cylinder of radius `R` and
//! height `L` is `2 pi R L`; the area of a disc of radius `R` is `pi R^2`; the area of a
//! sphere of radius `R` is `4 pi R^2` (the surface of revolution of a semicircular meridian),
//! approached by the inscribed polygon of `n` sides with a relative error `O(n^-2)`. The
//! identities `D 1 = M 1` (the constant reproduced: `sum_k N_k = 1` on both sides at each
//! point) and the diagonal dual D (biorthogonality with respect to the same measure) hold
//! for any measure, to round-off.

use mortar::core::geometry::ModelGeometry;
use mortar::core::interface::FaceGeometry;
use mortar::core::linalg::SparseMatrix;
use mortar::core::multiplier::{DualMultipliers, LmBasis, MultiplierFastPaths, MultiplierSpace};
use mortar::testing::polyline;
use mortar::Tolerances;
use mortar::{assemble_coupling, Coupling, CouplingOptions, Interface, MortarError, SurfaceMesh};
use std::f64::consts::PI;
use std::sync::Arc;

/// The vertical line r = `r`, z from 0 to `l` in `n` pieces, graded by `s(t)`.
fn vertical(r: f64, l: f64, n: usize, s: impl Fn(f64) -> f64) -> Vec<[f64; 2]> {
    (0..=n).map(|i| [r, l * s(i as f64 / n as f64)]).collect()
}

/// `D 1` and `M 1`, row by row.
fn row_sums(c: &Coupling) -> (Vec<f64>, Vec<f64>) {
    let sums = |m: &SparseMatrix| {
        m.outer_iterator()
            .map(|r| r.iter().map(|(_, v)| v).sum())
            .collect()
    };
    (sums(&c.d), sums(&c.m))
}

/// The largest `|D 1 - M 1|` relative to the largest row sum.
fn constant_defect(c: &Coupling) -> f64 {
    let (d1, m1) = row_sums(c);
    let scale = d1.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    d1.iter()
        .zip(&m1)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / scale
}

/// Whether every entry of D off its diagonal is zero (stored or not).
fn d_is_diagonal(c: &Coupling) -> bool {
    c.d.iter().all(|(v, (r, k))| r == k || *v == 0.0)
}

fn options(dual: bool) -> CouplingOptions {
    let o = CouplingOptions::default().axisymmetric();
    if dual {
        o.dual()
    } else {
        o
    }
}

/// A vertical interface at r = R: `sum D = 2 pi R L` to round-off, with non-matching graded
/// meshes, standard and dual multipliers; `D 1 = M 1`; the dual D is diagonal. Without the
/// option the same meshes give the length `L` (the Cartesian measure, unchanged).
#[test]
fn vertical_interface_has_the_lateral_area() {
    let (r, l) = (0.75, 2.0);
    // Slave: the outer surface of a body at r <= R (outward normal +r), going up so that the
    // normal (t_y, -t_x) points to +x; master: going down (normal -x).
    let slave_pts = vertical(r, l, 7, |t| t * t * (3.0 - 2.0 * t));
    let mut master_pts = vertical(r, l, 11, |t| t.powf(1.3));
    master_pts.reverse();
    for dual in [false, true] {
        let interface = Interface::new(
            polyline(&slave_pts, 1, false),
            polyline(&master_pts, 100, false),
        )
        .unwrap();
        let c = assemble_coupling(&interface, &options(dual)).unwrap();
        assert!(c.warnings.is_empty(), "{:?}", c.warnings);
        let want = 2.0 * PI * r * l;
        assert!(
            (c.stats.area - want).abs() < 1e-13 * want,
            "dual {dual}: area {} vs 2 pi R L = {want}",
            c.stats.area
        );
        let defect = constant_defect(&c);
        assert!(defect < 1e-12, "dual {dual}: |D 1 - M 1| = {defect:e}");
        if dual {
            assert!(d_is_diagonal(&c), "dual D not diagonal");
            assert!(c.stats.d_roundoff_largest < 1e-13);
        }
        assert!(c.formulation.ends_with("axisymmetric (2 pi r)"));
        let cartesian = if dual {
            CouplingOptions::default().dual()
        } else {
            CouplingOptions::default()
        };
        let c = assemble_coupling(&interface, &cartesian).unwrap();
        assert!((c.stats.area - l).abs() < 1e-13 * l);
        assert!(!c.formulation.contains("axisymmetric"));
    }
}

/// A horizontal interface z = const from the axis to r = R (the face between two stacked
/// pellets), along which the radius varies: `sum D = pi R^2` to round-off, `D 1 = M 1`, and
/// the dual D, biorthogonal in the weighted measure, is diagonal to round-off (the
/// unweighted dual basis would leave off-diagonal entries of relative size ~0.1 there).
#[test]
fn horizontal_interface_from_the_axis_has_the_disc_area() {
    let (rad, z) = (1.3, 0.4);
    let slave_pts: Vec<[f64; 2]> = (0..=9)
        .map(|i| [rad * (i as f64 / 9.0).powf(0.8), z])
        .collect();
    // The slave (lower body, outward normal +z) runs from r = R to 0; the master (upper body,
    // outward normal -z) from 0 to R.
    let mut s = slave_pts.clone();
    s.reverse();
    let master_pts: Vec<[f64; 2]> = (0..=13).map(|i| [rad * (i as f64 / 13.0), z]).collect();
    let interface =
        Interface::new(polyline(&s, 1, false), polyline(&master_pts, 100, false)).unwrap();
    for dual in [false, true] {
        let c = assemble_coupling(&interface, &options(dual)).unwrap();
        let want = PI * rad * rad;
        assert!(
            (c.stats.area - want).abs() < 1e-13 * want,
            "dual {dual}: area {} vs pi R^2 = {want}",
            c.stats.area
        );
        let defect = constant_defect(&c);
        assert!(defect < 1e-12, "dual {dual}: |D 1 - M 1| = {defect:e}");
        if dual {
            assert!(d_is_diagonal(&c), "dual D not diagonal");
            assert!(
                c.stats.d_roundoff_largest < 1e-13,
                "largest dropped off-diagonal {:e}",
                c.stats.d_roundoff_largest
            );
            // Every slave node keeps a positive weight, the one on the axis too.
            let (d1, _) = row_sums(&c);
            assert!(d1.iter().all(|&v| v > 0.0), "{d1:?}");
        }
    }
    // The Cartesian dual basis is not biorthogonal in the weighted measure: with the
    // weighting applied to the integrals only, D is far from diagonal (so the weighted basis
    // above is what makes it diagonal). A space that does not override `basis_for` gets its
    // Cartesian basis...
    let mut o = CouplingOptions::default().axisymmetric();
    o.multipliers = Arc::new(UnweightedDual);
    let c = assemble_coupling(&interface, &o).unwrap();
    let largest =
        c.d.iter()
            .filter(|(_, (r, k))| r != k)
            .map(|(v, (r, _))| (v / c.d.get(r, r).unwrap()).abs())
            .fold(0.0, f64::max);
    println!("unweighted dual basis in the r-z measure: largest |D_jk / D_jj| = {largest:.3}");
    assert!(largest > 1e-2, "{largest}");
    // ... unless it claims a diagonal D, which the default refuses to fake.
    o.multipliers = Arc::new(ClaimsDiagonal);
    assert!(matches!(
        assemble_coupling(&interface, &o),
        Err(MortarError::MultiplierSpace {
            space: "claims diagonal",
            ..
        })
    ));
}

/// The Cartesian dual basis, without overriding `basis_for`.
#[derive(Debug)]
struct UnweightedDual;

impl MultiplierSpace for UnweightedDual {
    fn name(&self) -> &'static str {
        "unweighted dual"
    }

    fn basis(&self, face: &FaceGeometry, tol: &Tolerances) -> mortar::core::Result<LmBasis> {
        DualMultipliers.basis(face, tol)
    }
}

/// The same, claiming a diagonal D.
#[derive(Debug)]
struct ClaimsDiagonal;

impl MultiplierSpace for ClaimsDiagonal {
    fn name(&self) -> &'static str {
        "claims diagonal"
    }

    fn basis(&self, face: &FaceGeometry, tol: &Tolerances) -> mortar::core::Result<LmBasis> {
        DualMultipliers.basis(face, tol)
    }

    fn fast_paths(&self) -> Option<&dyn MultiplierFastPaths> {
        Some(self)
    }
}

impl MultiplierFastPaths for ClaimsDiagonal {
    fn diagonal_d(&self) -> bool {
        true
    }
}

/// The semicircular meridian of a sphere of radius R: `sum D` converges to `4 pi R^2` at the
/// second order of the polygonal approximation, within 1e-3 at 64 lines; `D 1 = M 1` on the
/// curved non-matching interface, and the dual D is diagonal.
#[test]
fn semicircular_meridian_converges_to_the_sphere_area() {
    let rad = 0.9;
    let arc = |n: usize, reverse: bool| -> Vec<[f64; 2]> {
        // From the north pole (0, R) to the south pole (0, -R) through r > 0: the normal
        // (t_y, -t_x) points to the centre (reversed: away from it).
        let mut p: Vec<[f64; 2]> = (0..=n)
            .map(|i| {
                let phi = PI * i as f64 / n as f64;
                [rad * phi.sin(), rad * phi.cos()]
            })
            .collect();
        // Exact zeros on the axis.
        p[0][0] = 0.0;
        p[n][0] = 0.0;
        if reverse {
            p.reverse();
        }
        p
    };
    let want = 4.0 * PI * rad * rad;
    let mut errors = Vec::new();
    for n in [16, 32, 64] {
        // The slave: the ball's surface (outward normal); the master: the inner surface of a
        // shell around it (normal towards the centre), subdivided otherwise.
        let slave = polyline(&arc(n, true), 1, false);
        let master = polyline(&arc(n + 5, false), 1000, false);
        let interface = Interface::new(slave, master).unwrap();
        for dual in [false, true] {
            let c = assemble_coupling(&interface, &options(dual)).unwrap();
            let defect = constant_defect(&c);
            assert!(
                defect < 1e-12,
                "n {n} dual {dual}: |D 1 - M 1| = {defect:e}"
            );
            if dual {
                assert!(d_is_diagonal(&c), "n {n}: dual D not diagonal");
            } else {
                errors.push(((c.stats.area - want) / want).abs());
            }
        }
    }
    println!("sphere area relative errors at n = 16, 32, 64: {errors:?}");
    assert!(errors[2] < 1e-3, "{errors:?}");
    for w in errors.windows(2) {
        let rate = (w[0] / w[1]).log2();
        assert!(rate > 1.9 && rate < 2.1, "rate {rate} ({errors:?})");
    }
}

/// The axisymmetric measure is refused for a 3D interface and for a node at a negative
/// radius, each with its typed error; a node on the axis is accepted.
#[test]
fn axisymmetric_coupling_refuses_bad_input() {
    use mortar::elements::TRI3;
    let tri = |z: f64, flip: bool, t0: u64| {
        let mut m = SurfaceMesh::new();
        for (i, p) in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]].iter().enumerate() {
            m.add_node(t0 + i as u64, [p[0], p[1], z]).unwrap();
        }
        let n = if flip {
            [t0, t0 + 2, t0 + 1]
        } else {
            [t0, t0 + 1, t0 + 2]
        };
        m.add_face(&TRI3, &n).unwrap();
        m
    };
    let i3 = Interface::new(tri(0.0, false, 1), tri(0.0, true, 10)).unwrap();
    assert!(matches!(
        assemble_coupling(&i3, &CouplingOptions::default().axisymmetric()),
        Err(MortarError::AxisymmetricNeeds2D { slave_faces: 1 })
    ));
    let s = polyline(&[[-0.5, 1.0], [-0.5, 0.0]], 1, false);
    let m = polyline(&[[-0.5, 0.0], [-0.5, 1.0]], 10, false);
    let i2 = Interface::new(s, m).unwrap();
    match assemble_coupling(&i2, &CouplingOptions::default().axisymmetric()) {
        Err(MortarError::NegativeRadius { side, node, radius }) => {
            assert_eq!((side, node, radius), (mortar::Side::Slave, 1, -0.5));
        }
        other => panic!("expected NegativeRadius, got {other:?}"),
    }
    assert_eq!(
        CouplingOptions::default().axisymmetric().geometry,
        ModelGeometry::Axisymmetric
    );
}
