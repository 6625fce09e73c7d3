//! A contact scene built in memory, written as a scene file and its meshes: what the built-in
//! contact scenes (`mortar run --scene hertz2d|hertz3d|shrink_fit`) run and write, so that a
//! user can open their results in ParaView and start from their files.
//!
//! The scene is solved from these files (read back from memory), not from the builder's own
//! bodies, so that the files written are the scene that ran.

use std::collections::{BTreeMap, HashSet};
use std::path::{Path, PathBuf};

use mortar_core::{CouplingOptions, SurfaceMesh};
use mortar_fem::mesh::{BoundaryFace, VolumeMesh};
use mortar_physics::contact::ContactOptions;
use mortar_physics::elastic::{ComponentSet, ElasticBody, ElasticMaterial};
use mortar_physics::PhysicsError;
use nalgebra::Vector3;

use super::contact::{
    Component, ComponentValue, ContactInterfaceSpec, ContactSolveSpec, ContactSpec,
    DisplacementSpec, ElasticBodySpec, LawSpec, SolvedContact,
};
use super::face_nodes;
use super::tied_heat::SideSpec;
use super::{FileScene, InMemory, SceneError};
use mortar::extend::Registries;
use mortar::io::{msh41_volume_bytes, CouplingSettings, Integration, MshFormat, Multipliers};

/// The name the scene file of [`ContactSceneFiles`] is written under.
pub const SCENE_FILE: &str = "scene.toml";

/// A body of a contact scene made in memory: its mesh, material, named groups of boundary
/// faces and prescribed displacements (on those groups).
#[derive(Debug, Clone)]
pub struct SceneBody {
    /// The body's name; its mesh file is `NAME.msh`, its cells the group `NAME`.
    pub name: String,
    /// The mesh.
    pub mesh: VolumeMesh,
    /// The material.
    pub material: ElasticMaterial,
    /// Named groups of boundary faces.
    pub groups: Vec<(String, Vec<BoundaryFace>)>,
    /// Prescribed displacements on those groups.
    pub dirichlet: Vec<DisplacementSpec>,
    /// The same, as group, component (`x`, `y` or `z`) and value.
    holds: Vec<(String, Component, f64)>,
}

impl SceneBody {
    /// A body without groups or conditions.
    pub fn new(name: &str, mesh: VolumeMesh, material: ElasticMaterial) -> Self {
        Self {
            name: name.to_string(),
            mesh,
            material,
            groups: Vec::new(),
            dirichlet: Vec::new(),
            holds: Vec::new(),
        }
    }

    /// Adds the group `NAME_suffix` of the boundary faces for which `select` is true.
    ///
    /// # Errors
    /// [`SceneError::Other`] if the mesh's boundary cannot be found or no face is selected.
    pub fn group(
        mut self,
        suffix: &str,
        select: impl Fn(&BoundaryFace) -> bool,
    ) -> Result<Self, SceneError> {
        let name = format!("{}_{suffix}", self.name);
        let faces: Vec<BoundaryFace> = self
            .mesh
            .boundary_faces()
            .map_err(|e| SceneError::Other(format!("{}: {e}", self.name)))?
            .into_iter()
            .filter(|f| select(f))
            .collect();
        if faces.is_empty() {
            return Err(SceneError::Other(format!(
                "group {name}: no boundary face selected"
            )));
        }
        self.groups.push((name, faces));
        Ok(self)
    }

    /// Prescribes `component` (`x`, `y` or `z`) to `value` on the group `NAME_suffix`.
    pub fn hold(mut self, suffix: &str, component: Component, value: f64) -> Self {
        self.holds
            .push((format!("{}_{suffix}", self.name), component, value));
        self.dirichlet.push(DisplacementSpec {
            group: format!("{}_{suffix}", self.name),
            component,
            value: ComponentValue::Number(value),
        });
        self
    }

    /// The faces of group `NAME_suffix`.
    fn faces(&self, group: &str) -> Result<&[BoundaryFace], PhysicsError> {
        self.groups
            .iter()
            .find(|(name, _)| name == group)
            .map(|(_, faces)| faces.as_slice())
            .ok_or_else(|| PhysicsError::InvalidInput {
                body: self.name.clone(),
                what: format!("no group {group}"),
            })
    }

    /// The body with its prescribed displacements, as the scene file states it, and the
    /// surface of its group `NAME_suffix` (its contact surface): the scene without its files.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a group it does not have; the errors of
    /// [`VolumeMesh::boundary_surface`].
    pub fn elastic(&self, suffix: &str) -> Result<(ElasticBody, SurfaceMesh), PhysicsError> {
        let mut body = ElasticBody::new(self.name.clone(), self.mesh.clone(), self.material);
        for (group, component, value) in &self.holds {
            let k = match component {
                Component::X => 0,
                Component::Y => 1,
                _ => 2,
            };
            let mut v = Vector3::zeros();
            v[k] = *value;
            body = body.with_dirichlet_nodes(
                face_nodes(self.faces(group)?),
                ComponentSet::One(k),
                move |_| v,
            );
        }
        let faces: HashSet<(u32, u8)> = self
            .faces(&format!("{}_{suffix}", self.name))?
            .iter()
            .map(|f| (f.cell, f.local_face))
            .collect();
        let surface = self
            .mesh
            .boundary_surface(|f| faces.contains(&(f.cell, f.local_face)))?;
        Ok((body, surface))
    }
}

/// A contact scene as its scene file and meshes (see the [module](self)).
#[derive(Debug, Clone)]
pub struct ContactSceneFiles {
    /// The scene.
    pub spec: ContactSpec,
    /// The scene file's text.
    pub toml: String,
    /// The mesh files, by file name (`NAME.msh` per body, ASCII Gmsh 4.1).
    pub meshes: Vec<(String, Vec<u8>)>,
}

/// The interface of [`contact_scene_files`]: the slave and master groups (by suffix, of the
/// slave and master body), the coupling, how far to search, the solve.
#[derive(Debug, Clone)]
pub struct SceneContact<'a> {
    /// The slave body's group suffix.
    pub slave: &'a str,
    /// The master body's group suffix.
    pub master: &'a str,
    /// The coupling (its multipliers and integration are written; see
    /// [`contact_scene_files`]).
    pub coupling: &'a CouplingOptions,
    /// The search radius (a distance), or `None` for the default search.
    pub search_radius: Option<f64>,
    /// Require full coverage of the slave surface.
    pub require_full_coverage: bool,
    /// The contact solve.
    pub solve: &'a ContactOptions,
}

/// The scene file and meshes of frictionless contact between `slave` and `master` with the
/// exact law.
///
/// # Errors
/// [`SceneError::Other`] for a coupling a scene file cannot state (a multiplier space or
/// integration other than the shipped ones at their defaults, a projector other than the
/// nodal normal field, the axisymmetric measure), or a mesh that cannot be written.
pub fn contact_scene_files(
    title: &str,
    [slave, master]: [SceneBody; 2],
    contact: &SceneContact<'_>,
) -> Result<ContactSceneFiles, SceneError> {
    let (multipliers, integration) = interface_keys(contact.coupling)?;
    let mut bodies = BTreeMap::new();
    let mut meshes = Vec::with_capacity(2);
    for body in [&slave, &master] {
        let file = format!("{}.msh", body.name);
        let groups: Vec<(&[BoundaryFace], &str)> = body
            .groups
            .iter()
            .map(|(name, faces)| (faces.as_slice(), name.as_str()))
            .collect();
        let bytes = msh41_volume_bytes((&body.mesh, &body.name), &groups, MshFormat::Ascii)
            .map_err(|e| SceneError::Other(format!("{file}: {e}")))?;
        meshes.push((file.clone(), bytes));
        bodies.insert(
            body.name.clone(),
            ElasticBodySpec {
                mesh: PathBuf::from(file),
                group: body.name.clone(),
                youngs_modulus: body.material.youngs_modulus,
                poisson_ratio: body.material.poisson_ratio,
                dirichlet: body.dirichlet.clone(),
                traction: Vec::new(),
            },
        );
    }
    let side = |body: &SceneBody, suffix: &str| SideSpec {
        body: body.name.clone(),
        group: format!("{}_{suffix}", body.name),
    };
    let spec = ContactSpec {
        kind: "contact".into(),
        title: Some(title.to_string()),
        solve: ContactSolveSpec {
            load_steps: contact.solve.load_steps,
            max_newton_steps: contact.solve.max_newton_steps,
            tolerance: contact.solve.tolerance,
            ..ContactSolveSpec::default()
        },
        bodies,
        contact: ContactInterfaceSpec {
            slave: side(&slave, contact.slave),
            master: side(&master, contact.master),
            law: LawSpec::Exact,
            named_law: None,
            base_pressure: None,
            stiffness: None,
            onset: None,
            multipliers,
            integration,
            degree: None,
            curved_tolerance: None,
            subdivision: None,
            quad_subdivision: None,
            search_radius: contact.search_radius,
            require_full_coverage: contact.require_full_coverage,
        },
    };
    let toml = spec.to_toml()?;
    Ok(ContactSceneFiles { spec, toml, meshes })
}

/// The `multipliers` and `integration` keys that state `options`: the pair whose options
/// describe themselves as `options` do (the curved-face dials and the degree at their
/// defaults).
fn interface_keys(options: &CouplingOptions) -> Result<(Multipliers, Integration), SceneError> {
    let wanted = options.describe();
    [
        Multipliers::Standard,
        Multipliers::Dual,
        Multipliers::Linear,
    ]
    .into_iter()
    .flat_map(|m| [(m, Integration::Segment), (m, Integration::Element)])
    .find(|&(multipliers, integration)| {
        let settings = CouplingSettings {
            multipliers,
            integration,
            ..CouplingSettings::default()
        };
        settings.options().is_ok_and(|o| o.describe() == wanted)
    })
    .ok_or_else(|| {
        SceneError::Other(format!(
            "a contact scene file cannot state the coupling {wanted}"
        ))
    })
}

impl ContactSceneFiles {
    /// Solves the scene from its files (held in memory, as if written into the current
    /// folder).
    ///
    /// # Errors
    /// The errors of [`ContactSpec::solve_with`].
    pub fn solve(&self) -> Result<SolvedContact, SceneError> {
        let base = Path::new("");
        let source = InMemory {
            files: self
                .meshes
                .iter()
                .map(|(name, bytes)| (base.join(name), bytes.clone()))
                .collect(),
        };
        self.spec.solve_with(
            &base.join(SCENE_FILE),
            base,
            &source,
            &Registries::default(),
        )
    }

    /// The files to write beside the results: the meshes and the scene file.
    pub fn files(&self) -> Vec<(String, Vec<u8>)> {
        let mut files = self.meshes.clone();
        files.push((SCENE_FILE.to_string(), self.toml.clone().into_bytes()));
        files
    }
}
