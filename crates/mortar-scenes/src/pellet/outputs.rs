//! What the pellet's runs share, thermal and thermomechanical: their output files (which
//! names are theirs, written all or none, stale ones removed), the ParaView collection of
//! their snapshots, the progress display, and two measures of a mesh (its area, the node
//! nearest a point).

use std::path::Path;

use mortar::io::{remove_stale_outputs, write_outputs};
use mortar_fem::mesh::VolumeMesh;

use super::PelletError;

/// The area of a 2D mesh (shoelace formula per cell; Gmsh node order is cyclic for Tri3 and
/// Quad4).
pub(super) fn mesh_area(mesh: &VolumeMesh) -> f64 {
    (0..mesh.cell_count())
        .map(|c| {
            let nodes = mesh.cell(c).nodes;
            let x = mesh.coords();
            let mut a = 0.0;
            for i in 0..nodes.len() {
                let (p, q) = (
                    x[nodes[i] as usize],
                    x[nodes[(i + 1) % nodes.len()] as usize],
                );
                a += p.x * q.y - q.x * p.y;
            }
            0.5 * a
        })
        .sum()
}

/// Whether `name` is one of the pellet scenes' own output files.
pub fn is_output(name: &str) -> bool {
    let numbered = |prefix: &str| {
        name.strip_prefix(prefix)
            .and_then(|rest| rest.strip_suffix(".vtu"))
            .is_some_and(|n| n.len() == 4 && n.bytes().all(|b| b.is_ascii_digit()))
    };
    numbered("pellet_")
        || numbered("interface_")
        || [
            "pellet_steady.vtu",
            "pellet.pvd",
            "interface.pvd",
            "temperatures.png",
            "gap.png",
            "pressures.png",
            "report.json",
        ]
        .contains(&name)
}

/// Writes a pellet run's `outputs` into `out`, all or none, then removes the pellet outputs of
/// an earlier run that this one did not write (so that the folder holds one run).
pub(super) fn write_scene_outputs(
    out: &Path,
    outputs: Vec<(String, Vec<u8>)>,
) -> Result<(), PelletError> {
    let (names, bytes): (Vec<String>, Vec<Vec<u8>>) = outputs.into_iter().unzip();
    let files: Vec<(&str, Vec<u8>)> = names.iter().map(String::as_str).zip(bytes).collect();
    write_outputs(out, &files)?;
    let written: Vec<&str> = names.iter().map(String::as_str).collect();
    remove_stale_outputs(out, &written, is_output)?;
    Ok(())
}

/// The run's progress display: the caller's ([`crate::progress::set_display`]) when asked.
pub(super) fn progress_bar(progress: bool, len: u64) -> Box<dyn crate::progress::Progress> {
    crate::progress::display(progress, len, "pellet")
}

/// The node nearest to `point`.
pub(super) fn nearest_node(mesh: &VolumeMesh, point: nalgebra::Vector3<f64>) -> usize {
    let mut best = (f64::INFINITY, 0);
    for (i, x) in mesh.coords().iter().enumerate() {
        let d = (x - point).norm();
        if d < best.0 {
            best = (d, i);
        }
    }
    best.1
}

/// A ParaView collection of the transient snapshots (the steady one at the last time + 1).
pub(super) fn pvd(files: &[(String, f64)]) -> String {
    let last = files
        .iter()
        .map(|f| f.1)
        .filter(|t| t.is_finite())
        .fold(0.0, f64::max);
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n",
    );
    for (name, t) in files {
        let t = if t.is_finite() { *t } else { last + 1.0 };
        s.push_str(&format!(
            "    <DataSet timestep=\"{t}\" part=\"0\" file=\"{name}\"/>\n"
        ));
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    s
}
