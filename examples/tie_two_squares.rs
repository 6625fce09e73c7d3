//! The README's library example: tie a triangle mesh to a non-matching quad mesh of the unit
//! square, with dual multipliers, and check the constant and linear patch tests.
//!
//! Run with `cargo run --release --example tie_two_squares`.

use mortar::generate::{square_quads, square_triangles, Diagonal};
use mortar::{assemble_coupling, CouplingOptions, Interface};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    run()
}

/// Runs the example (the test of the examples calls it).
pub fn run() -> Result<(), Box<dyn std::error::Error>> {
    let slave = square_triangles(8, Diagonal::Main, 0.0, false, 1)?; // normals +z
    let master = square_quads(11, 0.0, true, 1)?; // normals -z, 11 x 11 cells
    let interface = Interface::new(slave, master)?;
    let coupling = assemble_coupling(&interface, &CouplingOptions::default().dual())?;

    // A linear field f = 1 + 2x - 3y is tied exactly: D f_s = M f_m.
    let f =
        |x: &nalgebra::Vector3<f64>| nalgebra::Vector3::new(1.0 + 2.0 * x.x - 3.0 * x.y, 0.0, 0.0);
    let fs: Vec<_> = coupling.slave_positions(&interface).iter().map(f).collect();
    let fm: Vec<_> = coupling
        .master_positions(&interface)
        .iter()
        .map(f)
        .collect();
    let worst = coupling
        .weighted_gap(&fs, &fm)
        .iter()
        .map(|g| g.x.abs())
        .fold(0.0, f64::max);

    if worst > 1e-12 {
        return Err(format!("the linear field is not tied exactly: error {worst:e}").into());
    }
    println!("{}", coupling.formulation);
    println!(
        "D {}x{} ({} entries), M {}x{} ({} entries), area {:.15}, pairs {}, patch-test error {worst:.1e}",
        coupling.d.rows(), coupling.d.cols(), coupling.d.nnz(),
        coupling.m.rows(), coupling.m.cols(), coupling.m.nnz(),
        coupling.stats.area, coupling.stats.pairs,
    );
    Ok(())
}
