//! Conductivity contrast (issue 14, item 2): two rectangles tied at x = 0.5 along a
//! non-matching interface, conductivities `k_left`, `k_right`, `T = 0` at x = 0 and `T = 1` at
//! x = 1, insulated top and bottom. The exact solution is piecewise linear with the flux
//! continuous: `q = 1 / (0.5 / k_left + 0.5 / k_right)`, `T = q x / k_left` on the left and
//! `T = 1 - q (1 - x) / k_right` on the right; bilinear and linear elements reproduce it, so
//! the nodal error measures only the round-off of the tied solve.

use mortar::generate::{box_mesh, rectangle_mesh, CellShape};
use mortar::physics::heat::{
    HeatBody, HeatMaterial, HeatOptions, TiedHeat, MAX_CONDUCTIVITY_CONTRAST,
    MAX_STIFFER_SLAVE_CONTRAST,
};
use mortar::physics::tied::{Formulation, FormulationChoice, TiedOptions};
use mortar::physics::PhysicsError;
use mortar::CouplingOptions;
use nalgebra::Vector3;

/// The scene: two rectangles (2D, Quad4 against Tri3) or two boxes (3D, Hex8 against Tet4)
/// meeting at x = 0.5; Dirichlet data at x = 0 and x = 1 only (the interface ends on
/// insulated sides), or the exact field on every outer side (the interface's ends are then
/// Dirichlet slave nodes, whose multipliers are redistributed).
#[derive(Debug, Clone, Copy)]
struct Case {
    dim: usize,
    dirichlet_everywhere: bool,
}

const CASES: [Case; 3] = [
    Case {
        dim: 2,
        dirichlet_everywhere: false,
    },
    Case {
        dim: 2,
        dirichlet_everywhere: true,
    },
    Case {
        dim: 3,
        dirichlet_everywhere: false,
    },
];

/// The exact temperature.
fn exact(kl: f64, kr: f64) -> impl Fn(&Vector3<f64>) -> f64 + Copy + Send + Sync + 'static {
    let q = 1.0 / (0.5 / kl + 0.5 / kr);
    move |x: &Vector3<f64>| {
        if x.x <= 0.5 {
            q * x.x / kl
        } else {
            1.0 - q * (1.0 - x.x) / kr
        }
    }
}

/// The problem with the left body of conductivity `kl` and the right body of `kr`; the slave
/// side is the right body when `right_is_slave`.
fn problem(case: Case, kl: f64, kr: f64, right_is_slave: bool) -> Result<TiedHeat, PhysicsError> {
    let u = exact(kl, kr);
    let body = |name: &str, x0: f64, x1: f64, n: usize, shape, k: f64, side: f64| {
        let mesh = if case.dim == 2 {
            rectangle_mesh([x0, 0.0], [x1, 1.0], [n, n + 2], shape, 1).unwrap()
        } else {
            box_mesh([x0, 0.0, 0.0], [x1, 1.0, 1.0], [n, n, n], shape, 1).unwrap()
        };
        let everywhere = case.dirichlet_everywhere;
        HeatBody::new(name, mesh, HeatMaterial::new(k, 1.0))
            .with_dirichlet_where(
                move |f| {
                    (f.centroid.x - side).abs() < 1e-12
                        || (everywhere && (f.centroid.x - 0.5).abs() > 1e-12)
                },
                move |x, _| u(x),
            )
            .unwrap()
    };
    let left = body("left", 0.0, 0.5, 3, CellShape::Tensor, kl, 0.0);
    let right = body("right", 0.5, 1.0, 4, CellShape::Simplex, kr, 1.0);
    let on = |f: &mortar::core::mesh::BoundaryFace| (f.centroid.x - 0.5).abs() < 1e-12;
    let ls = left.mesh.boundary_surface(on).unwrap();
    let rs = right.mesh.boundary_surface(on).unwrap();
    let (slave, master, ss, ms) = if right_is_slave {
        (right, left, rs, ls)
    } else {
        (left, right, ls, rs)
    };
    TiedHeat::new(
        slave,
        master,
        ss,
        ms,
        &CouplingOptions::default().dual(),
        &HeatOptions::default(),
    )
}

/// The largest nodal error relative to the temperature span (1), the formulation used, and
/// the largest relative error of the interface flux.
fn contrast_error(
    case: Case,
    kl: f64,
    kr: f64,
    right_is_slave: bool,
    choice: FormulationChoice,
) -> Result<(f64, f64, Formulation), PhysicsError> {
    let p = problem(case, kl, kr, right_is_slave)?;
    let sol = p.solve_steady(&TiedOptions::default().with_formulation(choice), 0.0)?;
    let q = 1.0 / (0.5 / kl + 0.5 / kr);
    let exact = exact(kl, kr);
    let mut err = 0.0f64;
    for (body, t) in p.bodies().iter().zip(&sol.temperatures) {
        for (ti, x) in t.iter().zip(body.mesh.coords()) {
            err = err.max((ti - exact(x)).abs());
        }
    }
    // The multiplier is the flux leaving the slave body: +q when the slave is the right body
    // (heat flows from right to left), -q otherwise.
    let sign = if right_is_slave { 1.0 } else { -1.0 };
    let flux = sol
        .flux
        .iter()
        .filter(|l| !l.is_nan())
        .map(|l| (l - sign * q).abs() / q)
        .fold(0.0f64, f64::max);
    Ok((err, flux, sol.formulation.formulation))
}

/// Contrasts 1 to 1e12, as `(1, c)`, `(c, 1)` and `(1/sqrt(c), sqrt(c))`, either body the
/// slave, each [`Case`], both formulations: the nodal error relative to the span stays below
/// 1e-8 (measured: 2e-14), and so does the interface flux when the slave is the softer body
/// (measured: 1e-13). When the slave is the stiffer body, its multipliers come from its own
/// stiff rows, whose residual `b - A T` cancels to a flux `contrast` times smaller than its
/// terms: their error is bounded by `100 eps contrast` (eps = 2.2e-16).
///
/// Measured (largest over the splits, the cases and both slave sides; nodal error relative to
/// the span, flux error relative to the exact flux):
///
/// | contrast | saddle point nodal | flux, softer slave | flux, stiffer slave | dual condensed nodal | flux, softer slave | flux, stiffer slave |
/// |---------:|---------:|---------:|--------:|---------:|--------:|--------:|
/// | 1        | 7.8e-15  | 1.0e-13  | -       | 2.2e-15  | 8.3e-15 | -       |
/// | 1e3      | 9.0e-15  |          | 1.6e-11 | 6.0e-15  |         | 7.5e-12 |
/// | 1e6      | 1.0e-14  | 1.2e-14  | 1.1e-8  | 6.2e-15  | 8.0e-15 | 8.2e-9  |
/// | 1e9      | 1.9e-14  |          | 1.5e-5  | 1.1e-14  |         | 6.2e-6  |
/// | 1e12     | 6.2e-15  | 8.8e-15  | 1.3e-2  | 5.6e-15  | 5.3e-15 | 7.2e-3  |
/// | 1e15     | 1.1e-14  | 9.3e-15  | 9.5     | 7.0e-15  | 7.1e-15 | 7.7     |
///
/// (1e15 measured before [`MAX_STIFFER_SLAVE_CONTRAST`] refused a stiffer slave there; the
/// empty cells were not split by slave side.) The nodal field was this exact before the
/// scaling of the saddle point too (issue 14, item 2, reported 4.7e-3 "relative" at 1e-6 and
/// 1e6: that is the size of this flux error, not of the temperatures); what the scaling
/// changed is the saddle point at extreme magnitudes (both conductivities 1e300: nodal error
/// 8.5e-12 before, 4.4e-16 after; 1e-200 and 1e-190 with the softer slave: flux 9.0e-6
/// before, 2.9e-15 after; see the next test).
#[test]
fn contrasts_up_to_1e12_reproduce_the_piecewise_linear_field() {
    let mut failures = Vec::new();
    for c in [1.0, 1e3, 1e6, 1e9, 1e12] {
        for choice in [
            FormulationChoice::SaddlePoint,
            FormulationChoice::DualCondensed,
        ] {
            let mut worst = (0.0f64, 0.0f64);
            for (kl, kr) in [(1.0, c), (c, 1.0), (1.0 / f64::sqrt(c), f64::sqrt(c))] {
                for (case, right_is_slave) in CASES.iter().flat_map(|&c| [(c, true), (c, false)]) {
                    let (err, flux, formulation) =
                        contrast_error(case, kl, kr, right_is_slave, choice).unwrap();
                    let expected = match choice {
                        FormulationChoice::SaddlePoint => Formulation::SaddlePoint,
                        _ => Formulation::DualCondensed,
                    };
                    assert_eq!(formulation, expected);
                    let ks = if right_is_slave { kr } else { kl };
                    let stiffer = ks / (kl * kr / ks);
                    let flux_bound = 1e-8f64.max(100.0 * f64::EPSILON * stiffer);
                    worst = (worst.0.max(err), worst.1.max(flux));
                    if err > 1e-8 || flux > flux_bound {
                        failures.push(format!(
                            "{case:?}, k = ({kl:e}, {kr:e}), right slave {right_is_slave}, \
                             {choice:?}: nodal {err:.1e}, flux {flux:.1e} (bound {flux_bound:.1e})"
                        ));
                    }
                }
            }
            eprintln!(
                "contrast {c:e} {choice:?}: nodal {:.1e}, flux {:.1e}",
                worst.0, worst.1
            );
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Extreme magnitudes at a small contrast are solved as well as ordinary ones (the saddle
/// point is scaled per body): nodal error and flux within 1e-13.
#[test]
fn extreme_conductivities_at_small_contrast() {
    for (kl, kr) in [
        (1e-300, 1e-300),
        (1e300, 1e300),
        (1e-200, 1e-195),
        (1e290, 1e295),
    ] {
        for choice in [
            FormulationChoice::SaddlePoint,
            FormulationChoice::DualCondensed,
        ] {
            // The softer body is the slave (see the test above).
            let (err, flux, _) = contrast_error(CASES[0], kl, kr, false, choice).unwrap();
            assert!(
                err < 1e-13 && flux < 1e-13,
                "k = ({kl:e}, {kr:e}) {choice:?}: nodal {err:e}, flux {flux:e}"
            );
        }
    }
}

/// Contrasts beyond what double precision carries (the stiffer body's drop below one unit in
/// the last place of the span), and a slave body stiffer than its master beyond
/// [`MAX_STIFFER_SLAVE_CONTRAST`], are refused with an error naming both conductivities; the
/// limits themselves are accepted.
#[test]
fn contrasts_beyond_double_precision_are_refused_by_name() {
    for (kl, kr, right_is_slave) in [
        (1.0, 1e16, false),
        (1e-300, 1.0, true),
        (1.0, 1e300, false),
        (1e-6, 1e10, false),
        (1.0, 1e13, true),
        (1e13, 1.0, false),
    ] {
        let e = problem(CASES[0], kl, kr, right_is_slave).unwrap_err();
        let text = e.to_string();
        assert!(
            matches!(e, PhysicsError::InvalidInput { .. })
                && text.contains(&format!("{kl:e}"))
                && text.contains(&format!("{kr:e}"))
                && text.contains("contrast")
                && !text.contains("positive definite"),
            "{text}"
        );
    }
    for (kl, kr, right_is_slave) in [
        (1.0, MAX_CONDUCTIVITY_CONTRAST, false),
        (MAX_CONDUCTIVITY_CONTRAST, 1.0, true),
        (1.0, MAX_STIFFER_SLAVE_CONTRAST, true),
    ] {
        let (err, _, _) =
            contrast_error(CASES[0], kl, kr, right_is_slave, FormulationChoice::Auto).unwrap();
        assert!(err < 1e-8, "k = ({kl:e}, {kr:e}): {err:e}");
    }
}
