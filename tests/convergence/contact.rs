//! Frictionless contact: the contact patch test, Hertz (2D and 3D), and the Newton solve.
//!
//! The patch test. Source of the reference (closed form): two stacked blocks of the same material, the lower
//! held by symmetry conditions (`u_y = 0` at its bottom, `u_x = 0` on `x = 0`; in 3D also
//! `u_z = 0` on `z = 0` for both), the upper held laterally only (`u_x = 0` on `x = 0`), with a
//! uniform pressure `sigma` on top. The stress is uniaxial, `sigma_yy = -sigma`, everywhere, so
//! the displacement is linear: `u_y = -sigma (1 - nu^2) y / E`, `u_x = sigma nu (1 + nu) x / E`
//! in plane strain; `u_y = -sigma y / E`, `u_x = sigma nu x / E`, `u_z = sigma nu z / E` in 3D.
//! The contact pressure is `sigma` at every slave node. The contact faces do not match (the
//! slave and master meshes have other sizes and cell kinds).

use mortar::physics::contact::{automatic_complementarity, solve_contact, ContactOptions};
use mortar::physics::laws::ContactComplementarity;
use nalgebra::Vector3;

use super::blocks::{stacked_blocks, E, NU, SIGMA};

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

/// The solution of the patch on `b`, its largest pressure and displacement errors (relative).
fn patch_errors(
    b: &super::blocks::Blocks,
    dim: usize,
) -> (mortar::physics::contact::ContactSolution, f64, f64, f64) {
    let c = automatic_complementarity(&b.stiffness[0], &b.tie, &b.gap, dim);
    let law = ContactComplementarity::try_new(c).unwrap();
    let sol = solve_contact(
        [&b.stiffness[0], &b.stiffness[1]],
        [&b.load[0], &b.load[1]],
        [
            (&b.dirichlet[0].0, &b.dirichlet[0].1),
            (&b.dirichlet[1].0, &b.dirichlet[1].1),
        ],
        &b.gap,
        &law,
        &ContactOptions::default(),
    )
    .unwrap();
    let worst_p = sol
        .pressure
        .iter()
        .map(|p| (p - SIGMA).abs() / SIGMA)
        .fold(0.0f64, f64::max);
    let scale = exact(&Vector3::new(1.0, 2.0, 1.0), dim).amax();
    let mut worst_u = 0.0f64;
    for (k, body) in b.bodies.iter().enumerate() {
        for (node, x) in body.mesh.coords().iter().enumerate() {
            let e = exact(x, dim);
            for a in 0..dim {
                let u = sol.displacements[k][node * dim + a];
                worst_u = worst_u.max((u - e[a]).abs() / scale);
            }
        }
    }
    (sol, worst_p, worst_u, c)
}

fn patch(dim: usize) {
    let b = stacked_blocks(dim, 0.0, SIGMA);
    let (sol, worst_p, worst_u, c) = patch_errors(&b, dim);
    // Rounding level: measured 1.1e-14 and 1.2e-14 (pressure), 6.3e-15 and 5.6e-15
    // (displacement) in 2D and 3D; the bounds leave about two decades.
    let bound = crate::claims::claim("contact.patch").bound;
    assert!(
        worst_p < bound,
        "{dim}D: pressure off by {worst_p:e} (relative)"
    );
    assert!(
        worst_u < bound,
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

    // Element-based integration instead (the slave face's own quadrature, no segments):
    // not exact on non-matching faces, the patch is then lost, by how much is reported.
    let options = mortar::CouplingOptions::default()
        .dual()
        .element_based(None)
        .unwrap();
    let b = super::blocks::stacked_blocks_with(dim, 0.0, SIGMA, &options);
    let (_, p_elem, u_elem, _) = patch_errors(&b, dim);
    eprintln!(
        "contact patch {dim}D, element-based integration: pressure error {p_elem:.1e}, \
         displacement error {u_elem:.1e}"
    );
    assert!(
        p_elem.is_finite()
            && p_elem > worst_p
            && p_elem >= crate::claims::claim("contact.patch_element").bound
            && p_elem < 1.0,
        "{dim}D: element-based pressure error {p_elem:e}"
    );
}

#[test]
fn contact_patch_test_2d() {
    patch(2);
}

#[test]
fn contact_patch_test_3d() {
    patch(3);
}

/// The 2D Hertz contact (plane strain) at the default coarse mesh of
/// [`mortar_scenes::hertz`]: a quarter cylinder of radius `R = 1` (slave) pressed onto the
/// block `[0, 8R] x [-8R, 0]` (master) by moving its top down, both of steel-like
/// `E = 200 GPa`, `nu = 0.3`, frictionless, dual multipliers, segment-based integration, the
/// exact complementarity law with automatic `c`.
///
/// Source of the reference (closed form): K. L. Johnson, *Contact Mechanics*, Cambridge
/// University Press, 1985, sec. 4.3 (two cylinders in line contact, the pressure
/// `p(x) = p0 sqrt(1 - x^2 / a^2)`) and sec. 5.6: with `1 / E* = (1 - nu1^2) / E1 +
/// (1 - nu2^2) / E2` and the load `P` per unit length, `a = sqrt(4 P R / (pi E*))` and
/// `p0 = 2 P / (pi a)`. Compared at the computed `P` (twice the half model's vertical contact
/// force): the peak pressure within 2 %, the half-width within one slave element (the one at
/// the contact point), and equilibrium: the vertical contact force equals the reaction at the
/// block's bottom and the force on the cylinder's top to 1e-8.
#[test]
fn hertz_cylinder_on_block_2d() {
    use mortar_scenes::hertz::HertzScene;

    let run = HertzScene::default().run().unwrap();
    let a = run.a_exact;
    eprintln!(
        "Hertz 2D: P = {:.4e} N/m, a = {a:.5} (a_h = {:.5}, bracket [{:.5}, {:.5}], element \
         {:.5}), p0 = {:.4e} (p0_h off by {:+.2e}), {} of {} slave nodes in contact, \
         Newton steps {:?}, equilibrium {:.1e}, profile L2 error {:.2e}, {:.2} s",
        run.load,
        run.half_width.estimate,
        run.half_width.last_in_contact,
        run.half_width.first_open,
        run.contact_cell,
        run.p0_exact,
        run.peak_error(),
        run.active,
        run.slave_nodes,
        run.steps.iter().map(|s| s.newton_steps).collect::<Vec<_>>(),
        run.equilibrium_error(),
        run.profile_l2,
        run.seconds
    );
    hertz_2d_criteria(&run, "first order");
    assert!(
        run.profile_l2 <= crate::claims::claim("hertz2d.profile_24").bound,
        "profile L2 error {:e}",
        run.profile_l2
    );
    // The solver's force sum_j w_j p_j is the normal force, larger than the vertical one by
    // the tilt of the normals: about a^2 / (8 R^2) for the elliptical profile.
    let tilt = run.force / run.vertical_force() - 1.0;
    assert!(
        (tilt - a * a / 8.0).abs() < 0.2 * a * a / 8.0,
        "normal over vertical force - 1 = {tilt:e}"
    );
}

/// The same scene with 96 arc cells (23,654 unknowns): two bodies with a short contact zone
/// in 2D, whose Newton systems are factorised by body (the bodies side by side, the master
/// unknowns in contact last); the same criteria hold.
#[test]
fn hertz_2d_newton_systems_by_body() {
    use mortar_scenes::hertz::HertzScene;

    let run = HertzScene::new(96).run().unwrap();
    assert!(run.unknowns >= mortar::core::linalg::SUBSTRUCTURED_MIN);
    assert!(run.formulation.contains("by body"), "{}", run.formulation);
    hertz_2d_criteria(&run, "96 arc cells");
    eprintln!(
        "Hertz 2D, 96 arc cells: profile L2 error {:.2e}",
        run.profile_l2
    );
    assert!(
        run.profile_l2 <= crate::claims::claim("hertz2d.profile_96").bound,
        "96 arc cells: profile L2 error {:e}",
        run.profile_l2
    );
}

/// The default scene at 48 arc cells (the level between the default 24 and the 96 of
/// [`hertz_2d_newton_systems_by_body`]): the profile's L2 error against Johnson's ellipse
/// (1985, sec. 4.3) falls from the default mesh's and stays within its claim.
#[test]
fn hertz_2d_profile_falls_with_the_arc_cells() {
    use mortar_scenes::hertz::HertzScene;

    let coarse = HertzScene::default().run().unwrap();
    let run = HertzScene::new(48).run().unwrap();
    hertz_2d_criteria(&run, "48 arc cells");
    eprintln!(
        "Hertz 2D, 48 arc cells: profile L2 error {:.2e} (24: {:.2e})",
        run.profile_l2, coarse.profile_l2
    );
    assert!(run.profile_l2 < coarse.profile_l2);
    assert!(
        run.profile_l2 <= crate::claims::claim("hertz2d.profile_48").bound,
        "48 arc cells: profile L2 error {:e}",
        run.profile_l2
    );
}

/// The criteria of the 2D Hertz case (the doc of [`hertz_cylinder_on_block_2d`]): the scene
/// is the one intended (a about 0.1 R, a few slave nodes across it, contiguous), the peak
/// within 2 %, the half-width within one spacing of the nodes that carry the pressure and
/// bracketed, equilibrium to 1e-8, at most 10 Newton steps per load step.
fn hertz_2d_criteria(run: &mortar_scenes::hertz::HertzRun, what: &str) {
    let a = run.a_exact;
    assert!((a - 0.1).abs() < 0.005, "{what}: a = {a}");
    assert!(
        run.active >= 4 && run.half_width.contiguous,
        "{what}: {:?}",
        run.half_width
    );
    assert!(
        run.peak_error().abs() <= crate::claims::claim("hertz2d.peak").bound,
        "{what}: peak pressure {:.4e} against p0 = {:.4e}",
        run.peak,
        run.p0_exact
    );
    assert!(
        (run.half_width.estimate - a).abs() <= run.contact_cell,
        "{what}: half-width {} against a = {a} (spacing {})",
        run.half_width.estimate,
        run.contact_cell
    );
    assert!(
        run.half_width.brackets(a),
        "{what}: {:?} against {a}",
        run.half_width
    );
    assert!(
        run.equilibrium_error() <= 1e-8,
        "{what}: vertical contact force {:e}, reactions {:e} (bottom) and {:e} (top)",
        run.vertical_force(),
        run.reaction_bottom,
        run.reaction_top
    );
    assert!(
        run.steps.iter().all(|s| s.newton_steps <= 10),
        "{what}: {:?}",
        run.steps
    );
}

/// The 3D Hertz contact of [`mortar_scenes::hertz::sphere`] on a mesh a little coarser than
/// its default (for time): the lower octant of a sphere of radius `R = 1` (slave, 12 Hex8
/// cells per direction, `0.023 R = a / 4.3` at the pole, `0.041 R` where the contact zone
/// ends) pressed onto the block `[0, 8R]^2 x [-8R, 0]` (master, Hex8) by moving its
/// equator down by `d = 0.01 R`, both of steel-like `E = 200 GPa`, `nu = 0.3`, frictionless,
/// dual multipliers, segment-based integration, the exact complementarity law with automatic
/// `c`.
///
/// Source of the reference (closed form): K. L. Johnson, *Contact Mechanics*, Cambridge
/// University Press, 1985, sec. 4.2 (a sphere on a plane, the pressure
/// `p(r) = p0 sqrt(1 - r^2 / a^2)`): with `1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2` and
/// the approach `d`, `a = sqrt(R d)`, `p0 = 2 E* a / (pi R)`, `P = 4 E* a^3 / (3 R)`; for the
/// load `P`, `a = (3 P R / (4 E*))^(1/3)`, `p0 = 3 P / (2 pi a^2)`. The targets, at
/// the imposed `d`: the peak pressure within 3 % and the contact radius within one element
/// (the slave face along `y = 0` in which `a` ends). At the computed load `P` (four times the
/// quarter model's vertical contact force), which leaves out the bodies' compliance away
/// from the contact: the peak within 2 % and the contact radius within one element (the
/// estimate is the midpoint of the last slave node in contact and the next, by distance from
/// the axis; whether they bracket `a` is printed, not checked: in 3D they are much closer than
/// an element, and on some meshes the discrete contact zone reaches a quarter of an element
/// beyond `a`). Equilibrium: the vertical contact force equals the reactions at the block's bottom and at the sphere's
/// equator to 1e-8. At most 10 Newton steps per load step.
#[test]
fn hertz_sphere_on_block_3d() {
    use mortar_scenes::hertz::HertzSphereScene;

    let run = HertzSphereScene::new(12).run().unwrap();
    let (at_d, at_p) = (run.at_approach, run.at_load);
    eprintln!(
        "Hertz 3D: {} + {} nodes, {} unknowns; P = {:.4e} N ({:+.2e} off the closed form at d); \
         p0_h = {:.4e}: {:+.2e} off p0 at d, {:+.2e} at P; a_h = {:.5} (bracket [{:.5}, {:.5}], \
         along y = 0 [{:.5}, {:.5}], element {:.5}) against a = {:.5} at d, {:.5} at P; {} of {} \
         slave nodes in contact, Newton steps {:?} (settled after {:?}), equilibrium {:.1e}, \
         {:.2} s",
        run.sphere_nodes,
        run.block_nodes,
        run.unknowns,
        run.load,
        run.load_error_at_approach(),
        run.peak,
        run.peak_error_at_approach(),
        run.peak_error_at_load(),
        run.contact_radius.estimate,
        run.contact_radius.last_in_contact,
        run.contact_radius.first_open,
        run.contact_radius_axis.last_in_contact,
        run.contact_radius_axis.first_open,
        run.edge_cell,
        at_d.radius,
        at_p.radius,
        run.active,
        run.slave_nodes,
        run.steps.iter().map(|s| s.newton_steps).collect::<Vec<_>>(),
        run.steps.iter().map(|s| s.settled_at).collect::<Vec<_>>(),
        run.equilibrium_error(),
        run.seconds
    );
    // The scene is the one intended: a about 0.1 R, a few elements across the contact zone.
    assert!((at_d.radius - 0.1).abs() < 1e-12 && (at_p.radius - 0.1).abs() < 0.005);
    assert!(
        run.contact_cell < 0.25 * at_d.radius,
        "{}",
        run.contact_cell
    );
    assert!(
        run.active >= 10 && run.contact_radius.contiguous,
        "{:?}",
        run.contact_radius
    );
    assert!(
        run.peak_error_at_approach().abs() <= crate::claims::claim("hertz3d.peak_d").bound,
        "peak pressure {:.4e} against p0 = {:.4e} at d",
        run.peak,
        at_d.peak
    );
    assert!(
        run.peak_error_at_load().abs() <= crate::claims::claim("hertz3d.peak_p").bound,
        "peak pressure {:.4e} against p0 = {:.4e} at P",
        run.peak,
        at_p.peak
    );
    for (a, cell) in [
        (at_d.radius, run.edge_cell),
        (at_p.radius, run.edge_cell_at_load),
    ] {
        assert!(
            (run.contact_radius.estimate - a).abs() <= cell,
            "contact radius {} against a = {a} (element {cell})",
            run.contact_radius.estimate,
        );
    }
    assert!(
        run.equilibrium_error() <= 1e-8,
        "vertical contact force {:e}, reactions {:e} (bottom) and {:e} (top)",
        run.vertical_force(),
        run.reaction_bottom,
        run.reaction_top
    );
    // The normal force exceeds the vertical one by the tilt of the normals: about
    // a^2 / (5 R^2) for the ellipsoidal profile.
    let tilt = run.force / run.vertical_force() - 1.0;
    let expected = at_p.radius.powi(2) / 5.0;
    assert!(
        (tilt - expected).abs() < 0.2 * expected,
        "normal over vertical force - 1 = {tilt:e}"
    );
    assert!(run.max_newton_steps() <= 10, "{:?}", run.steps);
}

/// Regression: the contact Newton matrix with standard multipliers (nonsymmetric, its law rows
/// some 1e15 larger than its equilibrium rows) was factorised as its transpose (a CSR matrix
/// read as CSC), whose pivoting lost about 7 digits: each solve left an equilibrium residual
/// of 1e-2 to 1e-7 and Newton took extra steps after the active set had settled (9 steps,
/// settled after 7, at 48 arc cells). The problem being linear once the active set is right,
/// one step after it settles must reach the solution.
#[test]
fn the_newton_solve_is_exact_once_the_active_set_settles() {
    use mortar::CouplingOptions;
    use mortar_scenes::hertz::HertzScene;

    let mut scene = HertzScene::new(48);
    scene.coupling = CouplingOptions::default();
    let run = scene.run().unwrap();
    for step in &run.steps {
        let settled = step.settled_at.expect("the active set settles");
        assert_eq!(
            step.newton_steps,
            settled + 1,
            "standard multipliers: {step:?}"
        );
    }
}

/// The 2D Hertz contact of [`hertz_cylinder_on_block_2d`] with second-order bodies (Quad9
/// cells; the cylinder's Line3 arc faces with their middle nodes on the circle), the same
/// source and criteria: at the computed load the peak pressure within 2 %
/// (measured +5.8e-3; first order -2.5e-4), the half-width within one slave node spacing
/// (measured 3.4e-4 off, spacing 0.010) and bracketed, equilibrium to 1e-8. Linear
/// multipliers (on the arc's corner nodes only) meet them with the spacing of those nodes:
/// peak -1.26e-2, half-width 7.5e-3 off (spacing 0.020), bracketed.
#[test]
fn hertz_cylinder_on_block_2d_second_order() {
    use mortar::generate::SecondOrder;
    use mortar_scenes::hertz::HertzScene;

    for coupling in [
        HertzScene::default().coupling,
        mortar::CouplingOptions::default().linear(),
    ] {
        let name = coupling.multipliers.name();
        let scene = HertzScene {
            order: Some(SecondOrder::Complete),
            coupling,
            ..HertzScene::default()
        };
        let run = scene.run().unwrap();
        let a = run.a_exact;
        eprintln!(
            "Hertz 2D, second order, {name} multipliers: a = {a:.5} (a_h = {:.5}, spacing \
             {:.5}), p0_h off by {:+.2e}, {} of {} slave nodes in contact, equilibrium {:.1e}, \
             {:.2} s",
            run.half_width.estimate,
            run.contact_cell,
            run.peak_error(),
            run.active,
            run.slave_nodes,
            run.equilibrium_error(),
            run.seconds
        );
        hertz_2d_criteria(&run, &format!("second order, {name} multipliers"));
        let peak = crate::claims::claim("hertz2d.second_order_peak").bound;
        let half_width = crate::claims::claim("hertz2d.second_order_half_width").bound;
        assert!(
            run.peak_error().abs() <= peak,
            "{name}: {}",
            run.peak_error()
        );
        assert!(
            (run.half_width.estimate - a).abs() <= half_width,
            "{name}: half-width {} against {a}",
            run.half_width.estimate
        );
    }
}

/// The contact patch test (the module's closed form) with second-order blocks (Quad9 below,
/// Tri6 above in 2D; Hex27 below, Tet10 above in 3D, the upper mesh twisted in the plane of
/// the interface): the same criteria as first order, standard multipliers
/// in 2D, dual and linear ones in 2D and 3D. With standard multipliers a Tri6 slave's corner
/// functions integrate to zero, so its corner nodes have no contact area (row sum of D): the nodal
/// contact formulation refuses it with a typed error naming the node, checked here; the dual
/// basis (recombined, Popp, Gee and Wall 2012) gives every node a positive area. Linear
/// multipliers (on the corners only; the edge nodes' pressures interpolated from them) meet
/// the same criteria in 2D and 3D.
#[test]
fn contact_patch_test_second_order() {
    use mortar::generate::SecondOrder;
    let standard = std::panic::catch_unwind(|| {
        super::blocks::stacked_blocks_of_order(
            3,
            0.0,
            SIGMA,
            &mortar::CouplingOptions::default(),
            Some(SecondOrder::Complete),
        )
    });
    let message = standard
        .err()
        .and_then(|e| e.downcast_ref::<String>().cloned())
        .unwrap_or_default();
    assert!(
        message.contains("has no contact area")
            && message.contains("use dual or linear multipliers"),
        "{message}"
    );
    for dim in [2, 3] {
        let mut all = vec![
            mortar::CouplingOptions::default().dual(),
            mortar::CouplingOptions::default().linear(),
        ];
        if dim == 2 {
            all.push(mortar::CouplingOptions::default());
        }
        for options in all {
            let b = super::blocks::stacked_blocks_of_order(
                dim,
                0.0,
                SIGMA,
                &options,
                Some(SecondOrder::Complete),
            );
            let (sol, worst_p, worst_u, _) = patch_errors(&b, dim);
            eprintln!(
                "contact patch {dim}D second order, {}: pressure error {worst_p:.1e}, \
                 displacement error {worst_u:.1e}, {} of {} in contact",
                options.describe(),
                sol.steps[0].active,
                sol.pressure.len()
            );
            // Rounding level (measured at most 5.1e-14 and 2.8e-14 in 2D).
            let bound = crate::claims::claim("contact.patch_p2").bound;
            assert!(worst_p < bound, "{dim}D: pressure off by {worst_p:e}");
            assert!(worst_u < bound, "{dim}D: displacement off by {worst_u:e}");
            // Every node that carries a multiplier in contact (with linear multipliers the
            // corners; their edge nodes' pressures are interpolated, and checked above).
            let carrying = b.gap.carries.iter().filter(|c| **c).count();
            assert_eq!(sol.steps[0].active, carrying);
            assert_eq!(
                carrying < sol.pressure.len(),
                options.multipliers.name() == "linear"
            );
            assert!(
                (sol.force - SIGMA).abs() < 1e-12 * SIGMA,
                "force {}",
                sol.force
            );
        }
    }
}

/// The rigid motions of a disc in a ring (the pellet scene's meshes, frictionless contact on
/// the disc's circle): with the ring held on its outer circle and the disc held by nothing,
/// the disc's translations and its rotation are held by contact alone, and its rotation about
/// the centre moves no slave node along its (radial) normal, so it is free (closed form: a
/// rotation of a circle about its centre is tangential everywhere). The ring is held.
#[test]
fn a_disc_in_a_ring_is_free_to_spin() {
    use mortar::physics::contact::{rigid_motions, NormalGap};
    use mortar::physics::tied::Tie;
    use mortar_scenes::pellet::{annulus_mesh, pellet_mesh};
    let (a, c) = (1.0, 1.5);
    let disc = pellet_mesh(a, 8, 3).unwrap();
    let ring = annulus_mesh(a, c, 40, 2, 0.1).unwrap();
    let on_circle =
        |f: &mortar::core::mesh::BoundaryFace, r: f64| (f.centroid.norm() - r).abs() < 1e-2 * r;
    let surface = |mesh: &mortar::core::mesh::VolumeMesh, r: f64| {
        mesh.boundary_surface(|f| on_circle(f, r)).unwrap()
    };
    let tie = Tie::new(
        &disc,
        &ring,
        surface(&disc, a),
        surface(&ring, a),
        &mortar::CouplingOptions::default().dual(),
    )
    .unwrap();
    let gap = NormalGap::new(&tie, 2, disc.node_count(), ring.node_count()).unwrap();
    let outer: Vec<u32> = ring
        .boundary_nodes(|f| on_circle(f, c))
        .unwrap()
        .iter()
        .flat_map(|&n| [2 * n, 2 * n + 1])
        .collect();
    let [d, r] = rigid_motions([disc.coords(), ring.coords()], [&[], &outer], &gap);
    assert_eq!(d.by_contact_only.len(), 3, "{d:?}");
    assert_eq!(d.free.len(), 1, "{d:?}");
    let spin = &d.free[0];
    assert!(spin.translation.norm() < 1e-9, "{spin:?}");
    assert!(spin.describe().starts_with("rotation about z"), "{spin:?}");
    assert!(r.by_contact_only.is_empty() && r.free.is_empty(), "{r:?}");
}
