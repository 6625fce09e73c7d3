//! The built-in default scene: tying two non-matching meshes of the unit square.

use mortar::generate::{square_quads, square_triangles, Diagonal};
use mortar::io::{CouplingSettings, CouplingSummary};
use mortar::{assemble_coupling, Interface};

use super::report::{core_error, print_summary};

/// Slave: 24 x 24 cells cut into triangles; master: 35 x 35 quadrilaterals facing it.
const SLAVE_CELLS: usize = 24;
const MASTER_CELLS: usize = 35;

/// Couples the scene and prints its summary.
pub(super) fn run(json: bool) -> Result<(), String> {
    let slave =
        square_triangles(SLAVE_CELLS, Diagonal::Main, 0.0, false, 1).map_err(|e| e.to_string())?;
    let master = square_quads(MASTER_CELLS, 0.0, true, 1).map_err(|e| e.to_string())?;
    let interface = Interface::new(slave, master).map_err(|e| core_error(&e, None))?;
    let settings = CouplingSettings::default();
    let options = settings.options().map_err(|e| e.to_string())?;
    let coupling = assemble_coupling(&interface, &options).map_err(|e| core_error(&e, None))?;

    let mut summary = CouplingSummary::new(&interface, &coupling, &settings);
    summary.slave = Some(format!(
        "built-in unit square, {SLAVE_CELLS} x {SLAVE_CELLS} cells cut into Tri3, normal +z"
    ));
    summary.master = Some(format!(
        "built-in unit square, {MASTER_CELLS} x {MASTER_CELLS} Quad4, normal -z"
    ));
    if !json {
        say!("mortar: default scene, tying two non-matching meshes of the unit square");
        say!("(couple your own Gmsh meshes with `mortar couple --help`)\n");
    }
    print_summary(&summary, json);
    Ok(())
}
