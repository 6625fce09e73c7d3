//! A curved interface: the lateral surface of a cylinder, slave Quad4 outside against master
//! Tri3 of another resolution. Projected along the slave's nodal normals (radial), every slave
//! point finds the master, so the coupled area is the slave's polygonal area and constants
//! are reproduced.

use std::f64::consts::PI;

use mortar::generate::cylinder_surface;
use mortar::testing::log_uniform;
use mortar::{assemble_coupling, CouplingOptions, Interface};
use proptest::prelude::*;

use super::common::{config, max_abs, ok, row_sums, segment_options};

proptest! {
    #![proptest_config(config(32))]

    #[test]
    fn cylinder_quads_against_triangles(
        radius in log_uniform(0.1, 10.0),
        (around_s, around_m) in (8..=32usize, 8..=32usize).prop_filter("non-matching", |(a, b)| a != b),
        along_s in 1..=4usize,
        along_m in 1..=5usize,
        dual in any::<bool>(),
    ) {
        let slave = ok(cylinder_surface(radius, around_s, along_s, false, false, 1))?;
        let master = ok(cylinder_surface(radius, around_m, along_m, true, true, 1))?;
        let interface = ok(Interface::new(slave, master))?;
        let options: CouplingOptions = segment_options(dual);
        let coupling = ok(assemble_coupling(&interface, &options))?;
        let d1 = row_sums(&coupling.d);
        let m1 = row_sums(&coupling.m);
        let scale = max_abs(&d1);
        for (j, (a, b)) in d1.iter().zip(&m1).enumerate() {
            prop_assert!((a - b).abs() <= 1e-12 * scale, "row {j}: D 1 = {a}, M 1 = {b}");
        }
        // The slave faces are flat rectangles of width 2 r sin(pi / around) and height 1/along.
        let polygonal = around_s as f64 * 2.0 * radius * (PI / around_s as f64).sin();
        let area = coupling.stats.area;
        prop_assert!(
            (area - polygonal).abs() <= 1e-10 * polygonal,
            "area {area}, polygonal {polygonal} (relative {:e})",
            area / polygonal - 1.0
        );
    }
}
