//! The steps that the two-body scene files ([`tied_heat`](super::tied_heat) and
//! [`contact`](super::contact)) share, so that both say the same thing the same way: a body's
//! name and the search radius checked, a body's mesh read, the mortar interface of the two
//! sides made, the coupling's warnings worded and the report written.

use std::collections::BTreeMap;
use std::path::Path;

use mortar::extend::{Registries, VolumeRegistry};
use mortar::io::{parse_gmsh_volume, CouplingSettings, GmshVolume};
use mortar_core::{CouplingOptions, CouplingWarning, Interface, SurfaceMesh};

use super::error::Errors;
use super::tied_heat::SideSpec;
use super::{coupling_of, widen_hint, SceneError, SceneSource};

/// Checks that body `name` can name its VTU file: letters, digits, `_` and `-`, at least one.
///
/// # Errors
/// [`SceneError::Invalid`] (key `bodies.NAME`) otherwise.
pub(super) fn check_body_name(errors: &Errors, name: &str) -> Result<(), SceneError> {
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        return Err(errors.invalid(
            format!("bodies.{name}"),
            "a body name is made of letters, digits, '_' and '-' (it names the VTU file)".into(),
        ));
    }
    Ok(())
}

/// Checks the `search_radius` of `section` (`interface` or `contact`): positive and finite
/// when given.
///
/// # Errors
/// [`SceneError::Invalid`] (key `SECTION.search_radius`) otherwise.
pub(super) fn check_search_radius(
    errors: &Errors,
    section: &str,
    radius: Option<f64>,
) -> Result<(), SceneError> {
    if let Some(r) = radius {
        if !(r > 0.0 && r.is_finite()) {
            return Err(errors.invalid(
                format!("{section}.search_radius"),
                format!("{r} is not positive and finite"),
            ));
        }
    }
    Ok(())
}

/// Checks that the scene file's `kind` is `expected`.
///
/// # Errors
/// [`SceneError::Invalid`] (key `kind`) otherwise.
pub(super) fn check_kind(errors: &Errors, kind: &str, expected: &str) -> Result<(), SceneError> {
    if kind != expected {
        return Err(errors.invalid("kind".into(), format!("\"{kind}\" is not \"{expected}\"")));
    }
    Ok(())
}

/// Checks that the `slave` and `master` sides of `section` (`interface` or `contact`) name
/// bodies of the scene; a message lists the bodies after `listed` (the kinds word it apart).
///
/// # Errors
/// [`SceneError::Invalid`] (key `SECTION.slave.body` or `SECTION.master.body`) for the first
/// side that names no body of the scene.
pub(super) fn check_side_bodies<B>(
    errors: &Errors,
    section: &str,
    [slave, master]: [&SideSpec; 2],
    bodies: &BTreeMap<String, B>,
    listed: &str,
) -> Result<(), SceneError> {
    for (which, side) in [("slave", slave), ("master", master)] {
        if !bodies.contains_key(&side.body) {
            return Err(errors.invalid(
                format!("{section}.{which}.body"),
                format!(
                    "no body named \"{}\" ({listed}{})",
                    side.body,
                    body_names(bodies)
                ),
            ));
        }
    }
    Ok(())
}

/// The `(name, mesh file, physical group)` of the bodies that the `slave` and `master` sides
/// name, slave first, with `mesh_of` a body's mesh file and group. The sides are checked
/// ([`check_side_bodies`]) to name bodies of the scene.
pub(super) fn mesh_sides<'a, B>(
    [slave, master]: [&'a SideSpec; 2],
    bodies: &'a BTreeMap<String, B>,
    mesh_of: impl Fn(&'a B) -> (&'a Path, &'a str),
) -> [(&'a str, &'a Path, &'a str); 2] {
    [slave, master].map(|side| {
        let (mesh, group) = mesh_of(&bodies[&side.body]);
        (side.body.as_str(), mesh, group)
    })
}

/// The names of a scene's bodies joined by `", "`, for a message that lists them.
pub(super) fn body_names<B>(bodies: &BTreeMap<String, B>) -> String {
    bodies.keys().cloned().collect::<Vec<_>>().join(", ")
}

/// Where a scene's meshes come from: the scene file's folder (mesh paths are relative to it),
/// the files, and the cells a mesh may hold.
#[derive(Clone, Copy)]
pub(super) struct MeshSource<'a> {
    /// The scene file's folder.
    pub(super) base: &'a Path,
    /// The files.
    pub(super) source: &'a dyn SceneSource,
    /// The cells (the shipped ones and a program's own).
    pub(super) registry: &'a VolumeRegistry,
}

impl<'a> MeshSource<'a> {
    /// The meshes of a scene file in the folder `base`, read through `source`, of the cells of
    /// `registries`.
    pub(super) fn new(
        base: &'a Path,
        source: &'a dyn SceneSource,
        registries: &'a Registries,
    ) -> Self {
        MeshSource {
            base,
            source,
            registry: &registries.cells,
        }
    }

    /// Body `name`'s cells: the physical group `group` of the Gmsh file `mesh`.
    ///
    /// # Errors
    /// [`SceneError::Mesh`] naming `bodies.NAME.mesh` for a file that cannot be read,
    /// `bodies.NAME.group` for a group that cannot be selected.
    pub(super) fn read(
        &self,
        errors: &Errors,
        name: &str,
        mesh: &Path,
        group: &str,
    ) -> Result<GmshVolume, SceneError> {
        let file = self.base.join(mesh);
        let bytes = self
            .source
            .read(&file)
            .map_err(|e| errors.mesh(format!("bodies.{name}.mesh"), e))?;
        parse_gmsh_volume(bytes, &file, group, self.registry)
            .map_err(|e| errors.mesh(format!("bodies.{name}.group"), e))
    }

    /// The two bodies' cells, slave first, each `(name, mesh, group)` read as
    /// [`read`](Self::read) does, with its name.
    ///
    /// # Errors
    /// As [`read`](Self::read), for the first body that fails; [`SceneError::Invalid`] (key
    /// `bodies`) for two bodies of different dimensions.
    pub(super) fn read_sides(
        &self,
        errors: &Errors,
        [slave, master]: [(&str, &Path, &str); 2],
    ) -> Result<[(String, GmshVolume); 2], SceneError> {
        let read = |(name, mesh, group): (&str, &Path, &str)| {
            Ok::<_, SceneError>((name.to_string(), self.read(errors, name, mesh, group)?))
        };
        let volumes = [read(slave)?, read(master)?];
        let dims = [volumes[0].1.dimension, volumes[1].1.dimension];
        if dims[0] != dims[1] {
            return Err(errors.invalid(
                "bodies".into(),
                format!(
                    "body \"{}\" ({}) is {}D but body \"{}\" ({}) is {}D",
                    volumes[0].0,
                    volumes[0].1.label(),
                    dims[0],
                    volumes[1].0,
                    volumes[1].1.label(),
                    dims[1]
                ),
            ));
        }
        Ok(volumes)
    }
}

/// The coupling options of `settings` (the keys of `section`, `interface` or `contact`) and
/// the mortar interface of the `slave` and `master` surfaces under their tolerances.
///
/// # Errors
/// [`SceneError::Invalid`] naming the key for a setting the core refuses
/// ([`coupling_of`]); [`SceneError::Physics`] for surfaces that make no interface.
pub(super) fn interface_of(
    errors: &Errors,
    settings: &CouplingSettings,
    section: &str,
    slave: SurfaceMesh,
    master: SurfaceMesh,
) -> Result<(CouplingOptions, Interface), SceneError> {
    let (coupling, tolerances) = coupling_of(settings, section, errors.path)?;
    let interface = Interface::with_tolerances(slave, master, tolerances)
        .map_err(|e| errors.physics(e.into()))?;
    Ok((coupling, interface))
}

/// The coupling's `warnings` as the report and the terminal word them: an uncovered slave
/// area says which key of `section` widens the search (`radius`, the scene's, if given).
pub(super) fn warning_texts(
    warnings: &[CouplingWarning],
    section: &str,
    radius: Option<f64>,
) -> Vec<String> {
    warnings
        .iter()
        .map(|w| mortar::io::warning_text(w, &widen_hint(section, radius)))
        .collect()
}

/// `report`'s text as `report.json` holds it: pretty-printed, with a final newline.
///
/// # Errors
/// serde_json's, for a value it cannot write.
pub(super) fn report_bytes(report: &serde_json::Value) -> Result<Vec<u8>, serde_json::Error> {
    let mut json = serde_json::to_string_pretty(report)?;
    json.push('\n');
    Ok(json.into_bytes())
}
