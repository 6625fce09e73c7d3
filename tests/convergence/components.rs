//! Tying of vector fields: `D (x) I_c u_s - M (x) I_c u_m = 0` per component.
//!
//! Source of the reference: the patch test (closed form). Each component of a field linear in
//! space, `u_k(x) = a_k . x + b_k`, is harmonic, so the component-wise Laplacian
//! `K (x) I_c` of two non-matching bodies tied by mortar reproduces it to round-off, by both
//! solution paths (dual-condensed SPD and saddle point), with the Dirichlet data on every outer
//! boundary node (the interface's end nodes included: their rows are redistributed).

use mortar::physics::tied::{
    kron_identity, Formulation, FormulationChoice, TiedOptions, TiedSystem,
};
use mortar_scenes::tied_heat::{Geometry, TiedHeatScene};
use nalgebra::Vector3;

/// The exact field: component `k` is `a_k . x + b_k`.
fn exact(x: &Vector3<f64>, k: usize) -> f64 {
    let a = [
        Vector3::new(0.7, -1.3, 0.4),
        Vector3::new(-0.2, 0.9, 1.1),
        Vector3::new(1.5, 0.3, -0.6),
    ];
    a[k].dot(x) + [0.25, -0.5, 2.0][k]
}

#[test]
fn linear_vector_fields_are_reproduced_by_both_paths() {
    // (2, 48): 7,852 unknowns, factorised by body on the condensed path.
    for (dim, n) in [(2, 8), (2, 48), (3, 4)] {
        let problem = TiedHeatScene::new(dim, Geometry::Straight, n)
            .build()
            .unwrap();
        let c = dim;
        let tie = problem.tie().clone().with_components(c).unwrap();
        assert_eq!(tie.d().rows(), problem.tie().coupling().d.rows() * c);
        let k: Vec<_> = problem
            .matrices()
            .iter()
            .map(|m| kron_identity(&m.stiffness, c))
            .collect();
        // Dirichlet data on the outer boundary (faces off the interface x = 1/2).
        let mut dofs = [Vec::new(), Vec::new()];
        let mut values = [Vec::new(), Vec::new()];
        for (b, body) in problem.bodies().iter().enumerate() {
            let nodes = body
                .mesh
                .boundary_nodes(|f| (f.centroid.x - 0.5).abs() > 1e-9)
                .unwrap();
            for &node in &nodes {
                let x = body.mesh.coords()[node as usize];
                for comp in 0..c {
                    dofs[b].push(node * c as u32 + comp as u32);
                    values[b].push(exact(&x, comp));
                }
            }
        }
        for choice in [FormulationChoice::Auto, FormulationChoice::SaddlePoint] {
            let options = TiedOptions::default().with_formulation(choice);
            let system =
                TiedSystem::new([&k[0], &k[1]], &tie, [&dofs[0], &dofs[1]], &options).unwrap();
            let expected = if choice == FormulationChoice::Auto {
                Formulation::DualCondensed
            } else {
                Formulation::SaddlePoint
            };
            assert_eq!(system.report().formulation, expected, "{dim}D");
            let by_body = system.report().factorisation.contains("by body");
            assert_eq!(
                by_body,
                n == 48 && choice == FormulationChoice::Auto,
                "{dim}D {n}"
            );
            let zero = [vec![0.0; k[0].rows()], vec![0.0; k[1].rows()]];
            let sol = system
                .solve([&zero[0], &zero[1]], [&values[0], &values[1]])
                .unwrap();
            let mut worst = 0.0f64;
            for (b, body) in problem.bodies().iter().enumerate() {
                for (node, x) in body.mesh.coords().iter().enumerate() {
                    for comp in 0..c {
                        let u = sol.fields[b][node * c + comp];
                        worst = worst.max((u - exact(x, comp)).abs());
                    }
                }
            }
            assert!(
                worst < crate::claims::claim("tied.components").bound,
                "{dim}D {choice:?}: error {worst:e}"
            );
            // A linear field carries no flux across the (insulated-free) interface other than
            // its constant normal derivative: the multipliers are finite on free rows.
            assert_eq!(sol.multipliers.len(), tie.d().rows());
        }
    }
}
