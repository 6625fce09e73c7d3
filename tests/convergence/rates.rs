//! Measured convergence rates over two refinements (h halved), never hard-coded errors:
//! linear elements must give L2 error O(h^2) and H1 error O(h).

use mortar::CouplingOptions;
use mortar_scenes::tied_heat::{rate, Geometry, TiedHeatRun, TiedHeatScene};

fn rates(scene: impl Fn(usize) -> TiedHeatScene, levels: [usize; 2]) -> (f64, f64, f64) {
    let runs: Vec<TiedHeatRun> = levels
        .iter()
        .map(|&n| scene(n).run().expect("the scene solves"))
        .collect();
    let (a, b) = (&runs[0], &runs[1]);
    assert!(b.l2 < a.l2 && b.h1 < a.h1);
    (
        rate(a.h, a.l2, b.h, b.l2),
        rate(a.h, a.h1, b.h, b.h1),
        rate(a.h, a.flux_error, b.h, b.flux_error),
    )
}

fn check(dim: usize, geometry: Geometry, levels: [usize; 2]) {
    let (l2, h1, flux) = rates(|n| TiedHeatScene::new(dim, geometry, n), levels);
    assert!(
        l2 >= crate::claims::claim("tied.rate_l2").bound
            && h1 >= crate::claims::claim("tied.rate_h1").bound,
        "{dim}D {geometry:?} {levels:?}: L2 rate {l2:.3}, H1 rate {h1:.3}"
    );
    // The interface flux (the multiplier) converges too.
    assert!(flux >= 0.9, "{dim}D {geometry:?}: flux rate {flux:.3}");
}

#[test]
fn straight_interface_2d() {
    check(2, Geometry::Straight, [16, 32]);
}

#[test]
fn straight_interface_3d() {
    check(3, Geometry::Straight, [8, 16]);
}

#[test]
fn curved_interface_2d() {
    check(2, Geometry::Curved, [16, 32]);
}

#[test]
fn curved_interface_3d() {
    check(3, Geometry::Curved, [8, 16]);
}

#[test]
fn standard_multipliers_converge_at_the_same_rates() {
    let (l2, h1, _) = rates(
        |n| {
            let mut s = TiedHeatScene::new(2, Geometry::Straight, n);
            s.coupling = CouplingOptions::default();
            s
        },
        [16, 32],
    );
    assert!(l2 >= 1.9 && h1 >= 0.95, "L2 rate {l2:.3}, H1 rate {h1:.3}");
}
