//! `mortar couple`: two Gmsh surfaces in, D, M and a summary out.

use mortar::core::mesh::orient::face_each_other;
use mortar::core::mesh::SurfaceMesh;
use mortar::extend::Registries;
use mortar::io::{
    parse_interface_arg, read_gmsh_surface, write_coupling, write_operators, CouplingSummary,
    GmshSurface, OrientationMethod, OrientationSummary, SideOrientation,
};
use mortar::{assemble_coupling, CouplingOptions, Interface, Tolerances};
use mortar_mpi::{couple_distributed, gather, DistributedOptions, Exchange, World};

use super::report::{core_error, print_summary, print_warnings};
use super::CoupleArgs;

/// Runs the command with the surface elements of `registries`; the error is the message for
/// the user.
pub(super) fn run(args: &CoupleArgs, json: bool, registries: &Registries) -> Result<(), String> {
    // Under `mpirun` on several ranks, MPI first (before anything else could start it).
    let world = World::start().map_err(|e| e.to_string())?;
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

    if let Some(world) = &world {
        let parts = (&slave, &master);
        return run_on_ranks(world, args, json, registries, parts, options, tolerances);
    }

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

/// Rank `rank`'s share of `mesh` among `ranks`: its faces in `ranks` contiguous blocks of the
/// file's order, this rank's block with its nodes.
fn block_of(mesh: &SurfaceMesh, rank: usize, ranks: usize) -> Result<SurfaceMesh, String> {
    let n = mesh.face_count();
    mesh.part(n * rank / ranks..n * (rank + 1) / ranks)
        .map_err(|e| e.to_string())
}

/// `mortar couple` on the ranks of `world`: each rank reads both files, takes its block of
/// each surface's faces and couples it ([`couple_distributed`]); rank 0 gathers the rows and
/// writes `D.mtx`, `M.mtx` (as one process writes them, to round-off) and a `summary.json`
/// with every rank's counts. `gap.mtx` and `normals.mtx` are one process's only.
fn run_on_ranks(
    world: &World,
    args: &CoupleArgs,
    json: bool,
    registries: &Registries,
    (slave, master): (&GmshSurface, &GmshSurface),
    coupling: CouplingOptions,
    tolerances: Tolerances,
) -> Result<(), String> {
    let (rank, ranks) = (world.rank(), world.size());
    let my_slave = block_of(&slave.mesh, rank, ranks)?;
    let my_master = block_of(&master.mesh, rank, ranks)?;
    let options = DistributedOptions {
        coupling,
        tolerances,
        elements: registries.elements.clone(),
    };
    let rows =
        couple_distributed(world, &my_slave, &my_master, &options).map_err(|e| e.to_string())?;
    // Each rank's warnings (a face next to a part's boundary may be reported by two ranks).
    print_warnings(&rows.warnings, &args.settings().widen_search_hint());
    if !rows.uncoupled_faces.is_empty() {
        let first: Vec<String> = rows
            .uncoupled_faces
            .iter()
            .take(5)
            .map(u64::to_string)
            .collect();
        let line = format!(
            "warning: rank {rank}: none of its {} slave faces meets a master face within the search's reach (faces {}{}): their rows of D and M are zero\n",
            rows.uncoupled_faces.len(),
            first.join(", "),
            if rows.uncoupled_faces.len() > 5 { ", ..." } else { "" }
        );
        // One write, so that the ranks' lines do not interleave.
        std::io::Write::write_all(&mut std::io::stderr(), line.as_bytes()).ok();
    }
    let Some(all) = gather(world, &rows, 0).map_err(|e| e.to_string())? else {
        return Ok(());
    };
    let per_rank: Vec<serde_json::Value> = all
        .counts
        .iter()
        .map(|c| {
            let fields = c
                .named()
                .map(|(k, v)| (k.to_string(), serde_json::Value::from(v)));
            serde_json::Value::Object(fields.into_iter().collect())
        })
        .collect();
    let summary = serde_json::json!({
        "ranks": ranks,
        "distribution": "each surface's faces in contiguous blocks of the file's order, one per rank",
        "slave": slave.label(),
        "master": master.label(),
        "slave_faces": slave.mesh.face_count(),
        "master_faces": master.mesh.face_count(),
        "slave_nodes": all.slave_nodes,
        "master_nodes": all.master_nodes,
        "per_rank": per_rank,
        "written": ["D.mtx", "M.mtx", "summary.json"],
    });
    let text = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
    write_operators(&args.out, &all.d, &all.m, &text).map_err(|e| e.to_string())?;
    if json {
        println!("{text}");
    } else {
        say!(
            "{:<9}{} slave and {} master faces on {ranks} ranks: D {} x {}, M {} x {}",
            "coupled",
            slave.mesh.face_count(),
            master.mesh.face_count(),
            all.d.rows(),
            all.d.cols(),
            all.m.rows(),
            all.m.cols()
        );
        say!(
            "{:<9}{} (D.mtx, M.mtx, summary.json)",
            "output",
            args.out.display()
        );
    }
    Ok(())
}
