//! All output files or none: everything is rendered in memory first, written under temporary
//! names inside the output directory, and renamed at the end.

use std::path::{Path, PathBuf};

use mortar_core::linalg::SparseMatrix;
use mortar_core::{Coupling, Interface, SpatialDim};

use super::error::IoError;
use super::matrix_market;
use super::summary::{CouplingSummary, RECOMBINATION_FILE};

/// Writes `D.mtx`, `M.mtx`, `gap.mtx`, `normals.mtx` and `summary.json` into `dir` (created
/// if missing), all or none; for a coupling in the recombined slave basis
/// ([`Coupling::recombined`]: dual multipliers on Tri6 or Quad8 slave faces), `D.mtx` holds
/// its diagonal `D T^T` and `T.mtx` the recombination `T` (`summary.slave_basis`,
/// `summary.recombination`), so that the slave unknowns condense: `u_s = T^T D~^-1 M u_m`.
///
/// Rows of D and M are the slave nodes, columns the slave (D, T) or master (M) nodes, each in
/// ascending node tag order: `summary.slave_nodes` and `summary.master_nodes`. `gap.mtx` is
/// the weighted gap `G = D x_s - M x_m` of the surfaces of `interface` (the positions of
/// their nodes; D the nodal one, whatever basis `D.mtx` is written in: `D~ x~_s` is the same
/// vector), and `normals.mtx` the slave's averaged unit nodal normals: dense Matrix Market
/// arrays, one row per slave node (the rows of D), one column per coordinate (2 for lines in
/// the plane `z = 0`, 3 for faces). The nodal normal gap is `g_j = -n_j . G_j` (positive
/// where the surfaces are apart).
///
/// # Errors
/// As [`write_outputs`].
pub fn write_coupling(
    dir: impl AsRef<Path>,
    interface: &Interface,
    coupling: &Coupling,
    summary: &CouplingSummary,
) -> Result<(), IoError> {
    let dim = match interface.dim() {
        SpatialDim::Two => 2,
        SpatialDim::Three => 3,
    };
    let gap = coupling.weighted_gap(
        &coupling.slave_positions(interface),
        &coupling.master_positions(interface),
    );
    let gap = matrix_market::dense_to_string(
        &gap.iter().map(|g| g.as_slice()[..dim].to_vec()).collect::<Vec<_>>(),
        dim,
        &[
            "G = D x_s - M x_m (weighted gap, one row per slave node as the rows of D; normal gap g_j = -n_j . G_j)",
        ],
    );
    let normals = matrix_market::dense_to_string(
        &coupling
            .slave_normals
            .iter()
            .map(|n| n.as_slice()[..dim].to_vec())
            .collect::<Vec<_>>(),
        dim,
        &["n_j: averaged unit normal of each slave node (rows of D), pointing out of the slave side"],
    );
    let d = match &coupling.recombined {
        Some(r) => matrix_market::to_string(
            &r.d,
            &[
                "D~[j,k] = int Phi_j N~_k^s = (D T^T)[j,k] (mortar, recombined slave basis: N~ = T N, u = T^T u~)",
                SLAVE_ROWS,
            ],
        ),
        None => d_file(&coupling.d),
    };
    let m = m_file(&coupling.m);
    let mut json = summary.to_json();
    json.push('\n');
    let mut files = vec![
        ("D.mtx", d.into_bytes()),
        ("M.mtx", m.into_bytes()),
        ("gap.mtx", gap.into_bytes()),
        ("normals.mtx", normals.into_bytes()),
    ];
    if let Some(r) = &coupling.recombined {
        let t = matrix_market::to_string(
            &r.t,
            &[
                "T[j,k]: N~_j = sum_k T[j,k] N_k (recombined slave shape functions, Popp, Gee and Wall 2012); u_s = T^T u~_s",
                SLAVE_ROWS,
            ],
        );
        files.push((RECOMBINATION_FILE, t.into_bytes()));
    }
    files.push(("summary.json", json.into_bytes()));
    let dir = dir.as_ref();
    write_outputs(dir, &files)?;
    // A T.mtx of an earlier run into the same folder would pass for this run's.
    let written: Vec<&str> = files.iter().map(|(n, _)| *n).collect();
    remove_stale_outputs(dir, &written, |n| n == RECOMBINATION_FILE)?;
    Ok(())
}

/// The comment of the rows and columns of D (and T).
const SLAVE_ROWS: &str =
    "rows: slave nodes, columns: slave nodes, both by ascending node tag (summary.json: slave_nodes)";

/// `D.mtx`'s text.
fn d_file(d: &SparseMatrix) -> String {
    matrix_market::to_string(d, &["D[j,k] = int Phi_j N_k^s (mortar)", SLAVE_ROWS])
}

/// `M.mtx`'s text.
fn m_file(m: &SparseMatrix) -> String {
    matrix_market::to_string(
        m,
        &[
            "M[j,l] = int Phi_j N_l^m (mortar)",
            "rows: slave nodes, columns: master nodes, both by ascending node tag (summary.json: slave_nodes, master_nodes)",
        ],
    )
}

/// Writes `D.mtx` and `M.mtx` as [`write_coupling`] does, and `summary.json` from
/// `summary_json`, into `dir`, all or none: the operators of a coupling computed elsewhere
/// (gathered from MPI ranks, say), without the interface that `gap.mtx` and `normals.mtx`
/// need. A `gap.mtx`, `normals.mtx` or `T.mtx` of an earlier run in `dir` is removed, so that
/// it does not pass for this run's.
///
/// # Errors
/// As [`write_outputs`].
pub fn write_operators(
    dir: impl AsRef<Path>,
    d: &SparseMatrix,
    m: &SparseMatrix,
    summary_json: &str,
) -> Result<(), IoError> {
    let mut json = summary_json.to_string();
    json.push('\n');
    let files = [
        ("D.mtx", d_file(d).into_bytes()),
        ("M.mtx", m_file(m).into_bytes()),
        ("summary.json", json.into_bytes()),
    ];
    let dir = dir.as_ref();
    write_outputs(dir, &files)?;
    remove_stale_outputs(dir, &["D.mtx", "M.mtx", "summary.json"], |n| {
        ["gap.mtx", "normals.mtx", RECOMBINATION_FILE].contains(&n)
    })?;
    Ok(())
}

/// Writes `files` (name, contents) into `dir`, all or none: `dir` is created if missing (with
/// its missing parents), each file is written as `.NAME.tmp-PID` and, once all are written,
/// renamed to `NAME`. On failure the temporary files, any file already renamed, and the
/// directories this call created are removed.
///
/// # Errors
/// [`IoError::Write`] naming the directory or file that could not be created, written or
/// renamed.
pub fn write_outputs(dir: impl AsRef<Path>, files: &[(&str, Vec<u8>)]) -> Result<(), IoError> {
    let dir = dir.as_ref();
    let created = create_dirs(dir)?;
    let result = write_all(dir, files);
    if result.is_err() {
        for d in created.iter().rev() {
            let _ = std::fs::remove_dir(d);
        }
    }
    result
}

/// Creates `dir` and its missing parents; returns those created, outermost first.
fn create_dirs(dir: &Path) -> Result<Vec<PathBuf>, IoError> {
    let mut missing = Vec::new();
    let mut p = Some(dir);
    while let Some(d) = p {
        if d.as_os_str().is_empty() || d.exists() {
            break;
        }
        missing.push(d.to_path_buf());
        p = d.parent();
    }
    missing.reverse();
    for (i, d) in missing.iter().enumerate() {
        if let Err(source) = std::fs::create_dir(d) {
            if !d.is_dir() {
                for made in missing[..i].iter().rev() {
                    let _ = std::fs::remove_dir(made);
                }
                return Err(IoError::Write {
                    path: d.clone(),
                    source,
                });
            }
        }
    }
    if !dir.is_dir() {
        return Err(IoError::Write {
            path: dir.to_path_buf(),
            source: std::io::Error::other("exists and is not a directory"),
        });
    }
    Ok(missing)
}

fn write_all(dir: &Path, files: &[(&str, Vec<u8>)]) -> Result<(), IoError> {
    let pid = std::process::id();
    let temps: Vec<PathBuf> = files
        .iter()
        .map(|(name, _)| dir.join(format!(".{name}.tmp-{pid}")))
        .collect();
    let cleanup = |upto: usize| {
        for t in &temps[..upto] {
            let _ = std::fs::remove_file(t);
        }
    };
    for (i, ((_, contents), temp)) in files.iter().zip(&temps).enumerate() {
        if let Err(source) = std::fs::write(temp, contents) {
            cleanup(i + 1);
            return Err(IoError::Write {
                path: temp.clone(),
                source,
            });
        }
    }
    for (i, ((name, _), temp)) in files.iter().zip(&temps).enumerate() {
        let target = dir.join(name);
        if let Err(source) = std::fs::rename(temp, &target) {
            for (done, _) in &files[..i] {
                let _ = std::fs::remove_file(dir.join(done));
            }
            for t in &temps[i..] {
                let _ = std::fs::remove_file(t);
            }
            return Err(IoError::Write {
                path: target,
                source,
            });
        }
    }
    Ok(())
}

/// Removes from `dir` the files that an earlier run of the same scene wrote and this one did
/// not: those whose name `ours` recognises (the scene's own output patterns) and that are not
/// in `written`. Other files are left alone. Returns the names removed.
///
/// A run of 4 snapshots after a run of 30 would otherwise leave `pellet_0005.vtu` and on,
/// which a ParaView user would take for this run's.
///
/// # Errors
/// [`IoError::Write`] naming a file that could not be removed, or the directory that could not
/// be listed.
pub fn remove_stale_outputs(
    dir: impl AsRef<Path>,
    written: &[&str],
    ours: impl Fn(&str) -> bool,
) -> Result<Vec<String>, IoError> {
    let dir = dir.as_ref();
    let entries = std::fs::read_dir(dir).map_err(|source| IoError::Write {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut removed = Vec::new();
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if ours(&name) && !written.contains(&name.as_str()) && entry.path().is_file() {
            std::fs::remove_file(entry.path()).map_err(|source| IoError::Write {
                path: entry.path(),
                source,
            })?;
            removed.push(name);
        }
    }
    removed.sort();
    Ok(removed)
}
