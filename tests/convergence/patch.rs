//! The patch test: a linear field `u = a + b . x` is reproduced to round-off with
//! segment-based integration, whatever the formulation, and the interface flux equals
//! `-k b . n_s` at every slave node that carries a multiplier.

use mortar::core::element::volume::VolumeElement;
use mortar::elements::volume::{QUAD4, TRI3};
use mortar::generate::{rectangle_mesh, CellShape};
use mortar::physics::heat::{error_norms, HeatBody, HeatMaterial, HeatOptions, TiedHeat};
use mortar::physics::tied::{Formulation, FormulationChoice, TiedOptions};
use mortar::CouplingOptions;
use mortar_scenes::tied_heat::{Exact, Geometry, TiedHeatScene};
use nalgebra::Vector3;

const LINEAR: Exact = Exact::Linear {
    a: 0.3,
    b: [1.0, -2.0, 0.5],
};

fn patch_error(
    dim: usize,
    coupling: CouplingOptions,
    formulation: FormulationChoice,
) -> (f64, f64) {
    let mut s = TiedHeatScene::new(dim, Geometry::Straight, 8);
    s.exact = LINEAR;
    s.conductivity = 2.5;
    s.coupling = coupling;
    s.tied = TiedOptions::default().with_formulation(formulation);
    let r = s.run().unwrap();
    (r.max_nodal, r.flux_error)
}

#[test]
fn linear_fields_are_reproduced_in_2d_and_3d() {
    for dim in [2, 3] {
        for (coupling, formulation) in [
            (CouplingOptions::default().dual(), FormulationChoice::Auto),
            (
                CouplingOptions::default().dual(),
                FormulationChoice::SaddlePoint,
            ),
            (CouplingOptions::default(), FormulationChoice::Auto),
        ] {
            let name = format!("{dim}D {} {formulation:?}", coupling.describe());
            let (err, flux) = patch_error(dim, coupling, formulation);
            let bound = crate::claims::claim("tied.patch").bound;
            assert!(err < bound, "{name}: max nodal error {err:e}");
            assert!(flux < bound, "{name}: flux error {flux:e}");
        }
    }
}

#[test]
fn element_based_integration_fails_the_patch_test() {
    // Element-based integration trades accuracy for speed: it is not exact on a
    // non-matching interface, so the linear field is only approximated.
    let coupling = CouplingOptions::default()
        .dual()
        .element_based(None)
        .unwrap();
    let (err, _) = patch_error(2, coupling, FormulationChoice::Auto);
    assert!(err > 1e-9, "element-based error {err:e}");
}

/// Two rectangles tied at x = 0.5 with Dirichlet data on the left and right sides only and
/// Neumann fluxes `k b . n` on the top and bottom: the interface ends on Neumann boundaries,
/// so no slave node is a Dirichlet node, and the linear field is still reproduced.
#[test]
fn neumann_data_and_an_interface_without_crosspoints() {
    let (k, a, b) = (0.7, 1.5, Vector3::new(-0.4, 2.0, 0.0));
    let u = move |x: &Vector3<f64>, _t: f64| a + b.dot(x);
    let flux_in = move |x: &Vector3<f64>, _t: f64| {
        // The outward normal of the top (y = 1) or bottom (y = 0) side.
        let ny = if x.y > 0.5 { 1.0 } else { -1.0 };
        k * b.y * ny
    };
    let body = |name: &str, x0: f64, x1: f64, n: [usize; 2], shape, side: f64| {
        let mesh = rectangle_mesh([x0, 0.0], [x1, 1.0], n, shape, 1).unwrap();
        HeatBody::new(name, mesh, HeatMaterial::new(k, 1.0))
            .with_dirichlet_where(move |f| (f.centroid.x - side).abs() < 1e-12, u)
            .unwrap()
            .with_neumann_where(
                |f| f.centroid.y < 1e-12 || f.centroid.y > 1.0 - 1e-12,
                flux_in,
            )
            .unwrap()
    };
    let master = body("left", 0.0, 0.5, [3, 5], CellShape::Tensor, 0.0);
    let slave = body("right", 0.5, 1.0, [4, 8], CellShape::Simplex, 1.0);
    assert_eq!(master.mesh.cell(0).element.name(), QUAD4.name());
    assert_eq!(slave.mesh.cell(0).element.name(), TRI3.name());
    let on = |f: &mortar::core::mesh::BoundaryFace| (f.centroid.x - 0.5).abs() < 1e-12;
    let ms = master.mesh.boundary_surface(on).unwrap();
    let ss = slave.mesh.boundary_surface(on).unwrap();
    let problem = TiedHeat::new(
        slave,
        master,
        ss,
        ms,
        &CouplingOptions::default().dual(),
        &HeatOptions::default(),
    )
    .unwrap();
    for choice in [FormulationChoice::Auto, FormulationChoice::SaddlePoint] {
        let sol = problem
            .solve_steady(&TiedOptions::default().with_formulation(choice), 0.0)
            .unwrap();
        assert_eq!(sol.formulation.redistributed, 0);
        if choice == FormulationChoice::Auto {
            assert_eq!(sol.formulation.formulation, Formulation::DualCondensed);
        }
        for (body, t) in problem.bodies().iter().zip(&sol.temperatures) {
            let e = error_norms(&body.mesh, t, &|x| u(x, 0.0), &|_| b, None).unwrap();
            assert!(
                e.max_nodal < 1e-12 && e.h1_seminorm < 1e-12,
                "{choice:?}: {e:?}"
            );
        }
        // lambda = -k grad u . n_s with n_s = -e_x.
        for l in &sol.flux {
            assert!((l - k * b.x).abs() < 1e-11, "{choice:?}: flux {l}");
        }
    }
}
