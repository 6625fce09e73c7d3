//! `mortar couple`: two Gmsh surfaces in, D, M and a summary out.

use mortar::core::mesh::orient::face_each_other;
use mortar::extend::Registries;
use mortar::io::{
    parse_interface_arg, read_gmsh_surface, write_coupling, CouplingSummary, GmshSurface,
    OrientationMethod, OrientationSummary, SideOrientation,
};
use mortar::{assemble_coupling, Interface};

use super::report::{core_error, print_summary, print_warnings};
use super::CoupleArgs;

/// Runs the command with the surface elements of `registries`; the error is the message for
/// the user.
pub(super) fn run(args: &CoupleArgs, json: bool, registries: &Registries) -> Result<(), String> {
    let slave_arg = parse_interface_arg(&args.slave).map_err(|e| format!("--slave: {e}"))?;
    let master_arg = parse_interface_arg(&args.master).map_err(|e| format!("--master: {e}"))?;
    let settings = args.settings();
    let options = settings.options().map_err(|e| e.to_string())?;
    let tolerances = settings.tolerances().map_err(|e| e.to_string())?;

    let registry = &registries.elements;
    let mut slave = read_gmsh_surface(&slave_arg.path, slave_arg.group.as_deref(), registry)
        .map_err(|e| format!("slave mesh: {e}"))?;
    let mut master = read_gmsh_surface(&master_arg.path, master_arg.group.as_deref(), registry)
        .map_err(|e| format!("master mesh: {e}"))?;
    let orientation = if args.keep_orientation {
        None
    } else {
        Some(orient(&mut slave, &mut master)?)
    };

    let interface = Interface::with_tolerances(
        std::mem::take(&mut slave.mesh),
        std::mem::take(&mut master.mesh),
        tolerances,
    )
    .map_err(|e| core_error(&e, Some((&slave, &master))))?;
    let coupling = assemble_coupling(&interface, &options)
        .map_err(|e| core_error(&e, Some((&slave, &master))))?;

    let mut summary = CouplingSummary::new(&interface, &coupling, &settings);
    summary.slave = Some(slave.label());
    summary.master = Some(master.label());
    summary.orientation = orientation;
    write_coupling(&args.out, &interface, &coupling, &summary).map_err(|e| e.to_string())?;
    print_warnings(&coupling.warnings, &settings.widen_search_hint());
    print_summary(&summary, json);
    if !json {
        let t = if coupling.recombined.is_some() {
            ", T.mtx"
        } else {
            ""
        };
        say!(
            "{:<9}{} (D.mtx, M.mtx{t}, gap.mtx, normals.mtx, summary.json)",
            "output",
            args.out.display()
        );
    }
    Ok(())
}

/// Orients both surfaces: outward from the cells of their files where every face bounds one
/// cell, otherwise consistent piece by piece and turned to face each other.
fn orient(slave: &mut GmshSurface, master: &mut GmshSurface) -> Result<OrientationSummary, String> {
    let flip_error = |e: mortar::MortarError| e.to_string();
    let s = slave.orient_outward().map_err(flip_error)?;
    let m = master.orient_outward().map_err(flip_error)?;
    if let (Some(fs), Some(fm)) = (s, m) {
        let side = |flipped| SideOrientation {
            method: OrientationMethod::Cells,
            components: None,
            flipped,
        };
        return Ok(OrientationSummary {
            slave: side(fs),
            master: side(fm),
        });
    }
    // The facing step decides each piece's sense from the other surface; a side oriented
    // from its cells keeps the sense its cells gave it.
    let [rs, rm] = face_each_other(
        &mut slave.mesh,
        &mut master.mesh,
        2.0,
        s.is_some(),
        m.is_some(),
    )
    .map_err(|e| core_error(&e, Some((slave, master))))?;
    let side = |from_cells: Option<usize>, r: &mortar::core::mesh::orient::OrientationReport| {
        SideOrientation {
            method: if from_cells.is_some() {
                OrientationMethod::Cells
            } else if r.kept_as_given == r.components {
                OrientationMethod::Consistent
            } else {
                OrientationMethod::Facing
            },
            components: Some(r.components),
            flipped: from_cells.unwrap_or(0) + r.flipped,
        }
    };
    Ok(OrientationSummary {
        slave: side(s, &rs),
        master: side(m, &rm),
    })
}
