//! Row sums of D equal the slave nodal areas, and D 1 = M 1 (constants are reproduced), on
//! covered interfaces.

use mortar::testing::{
    covered_pair, covered_pair_2d, covered_pair_3d_with, CellKind, MeshPair, PairConfig,
};
use mortar::CouplingOptions;
use proptest::prelude::*;

use super::common::{config, couple, max_abs, nodal_areas, row_sums, segment_options};

/// `sum_k D[j,k] == int N_j` over the slave surface, for every slave node `j`, to `1e-12`
/// relative to the largest nodal area. Holds for standard multipliers (`sum_k N_k = 1`) and
/// dual ones (`int Phi_j = int N_j` by biorthogonality) alike.
fn check_row_sums(pair: &MeshPair, options: &CouplingOptions) -> Result<(), TestCaseError> {
    let (_, coupling) = couple(pair, options)?;
    let areas = nodal_areas(&pair.slave);
    let sums = row_sums(&coupling.d);
    let scale = areas.values().fold(0.0f64, |m, a| m.max(a.abs()));
    prop_assert_eq!(areas.len(), sums.len());
    for (tag, sum) in coupling.slave_nodes.iter().zip(&sums) {
        let area = areas[tag];
        prop_assert!(
            (sum - area).abs() <= crate::claims::claim("coupling.conservation").bound * scale,
            "{}: row of node {tag}: sum {sum} but nodal area {area} (relative error {:e})",
            coupling.formulation,
            (sum - area).abs() / scale
        );
    }
    Ok(())
}

/// `D 1 == M 1` row by row, to `1e-12` relative to the largest row sum.
fn check_constants(pair: &MeshPair, options: &CouplingOptions) -> Result<(), TestCaseError> {
    let (_, coupling) = couple(pair, options)?;
    let d1 = row_sums(&coupling.d);
    let m1 = row_sums(&coupling.m);
    let scale = max_abs(&d1);
    for (j, (a, b)) in d1.iter().zip(&m1).enumerate() {
        prop_assert!(
            (a - b).abs() <= crate::claims::claim("coupling.conservation").bound * scale,
            "{}: row {j} (node {}): D 1 = {a}, M 1 = {b}",
            coupling.formulation,
            coupling.slave_nodes[j]
        );
    }
    Ok(())
}

/// Slave meshes of triangles only (affine faces), any master.
fn affine_slave_3d() -> impl Strategy<Value = MeshPair> {
    covered_pair_3d_with(PairConfig {
        slave_kinds: vec![CellKind::Triangles],
        ..PairConfig::default()
    })
}

/// Slave meshes with (jittered, hence non-affine) Quad4 faces, any master.
fn quad_slave_3d() -> impl Strategy<Value = MeshPair> {
    covered_pair_3d_with(PairConfig {
        slave_kinds: vec![CellKind::Quads, CellKind::Mixed],
        ..PairConfig::default()
    })
}

proptest! {
    #![proptest_config(config(48))]

    #[test]
    fn d_row_sums_are_slave_nodal_areas_2d(pair in covered_pair_2d(), dual in any::<bool>()) {
        check_row_sums(&pair, &segment_options(dual))?;
    }

    #[test]
    fn d_row_sums_are_slave_nodal_areas_3d_triangle_slave(
        pair in affine_slave_3d(),
        dual in any::<bool>(),
    ) {
        check_row_sums(&pair, &segment_options(dual))?;
    }

    /// The same with Quad4 slave faces. With node jitter a Quad4 is not affine, so
    /// `N_j(xi(x))` is not a polynomial on the clip triangles; the default degree must still
    /// give the nodal areas to round-off, as it does for triangles.
    #[test]
    fn d_row_sums_are_slave_nodal_areas_3d_quad_slave(
        pair in quad_slave_3d(),
        dual in any::<bool>(),
    ) {
        check_row_sums(&pair, &segment_options(dual))?;
    }

    #[test]
    fn constants_are_reproduced_segment_based(pair in covered_pair(), dual in any::<bool>()) {
        check_constants(&pair, &segment_options(dual))?;
    }

    #[test]
    fn constants_are_reproduced_at_any_segment_degree(
        pair in covered_pair(),
        dual in any::<bool>(),
        degree in 1..=12u32,
    ) {
        check_constants(&pair, &segment_options(dual).segment_based(Some(degree)).unwrap())?;
    }
}
