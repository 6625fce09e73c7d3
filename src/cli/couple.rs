//! `mortar couple`: two Gmsh surfaces in, D, M and a summary out.

use mortar::elements::ElementRegistry;
use mortar::io::{parse_interface_arg, read_gmsh_surface, write_coupling, CouplingSummary};
use mortar::{assemble_coupling, Interface};

use super::report::{core_error, print_summary};
use super::CoupleArgs;

/// Runs the command; the error is the message for the user.
pub(super) fn run(args: &CoupleArgs, json: bool) -> Result<(), String> {
    let slave_arg = parse_interface_arg(&args.slave).map_err(|e| format!("--slave: {e}"))?;
    let master_arg = parse_interface_arg(&args.master).map_err(|e| format!("--master: {e}"))?;
    let settings = args.settings();
    let options = settings.options().map_err(|e| e.to_string())?;

    let registry = ElementRegistry::new();
    let mut slave = read_gmsh_surface(&slave_arg.path, slave_arg.group.as_deref(), &registry)
        .map_err(|e| format!("slave mesh: {e}"))?;
    let mut master = read_gmsh_surface(&master_arg.path, master_arg.group.as_deref(), &registry)
        .map_err(|e| format!("master mesh: {e}"))?;

    let interface = Interface::new(
        std::mem::take(&mut slave.mesh),
        std::mem::take(&mut master.mesh),
    )
    .map_err(|e| core_error(&e, Some((&slave, &master))))?;
    let coupling = assemble_coupling(&interface, &options)
        .map_err(|e| core_error(&e, Some((&slave, &master))))?;

    let mut summary = CouplingSummary::new(&interface, &coupling, &settings);
    summary.slave = Some(slave.label());
    summary.master = Some(master.label());
    write_coupling(&args.out, &coupling, &summary).map_err(|e| e.to_string())?;
    print_summary(&summary, json);
    if !json {
        println!(
            "{:<9}{} (D.mtx, M.mtx, summary.json)",
            "output",
            args.out.display()
        );
    }
    Ok(())
}
