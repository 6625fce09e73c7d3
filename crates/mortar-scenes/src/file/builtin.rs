//! Built-in scenes: a scene file and its meshes, generated in memory (`mortar run --scene
//! NAME`), and the meshes of `examples/scenes/tied_square.toml`.

use std::collections::BTreeMap;
use std::path::PathBuf;

use mortar_fem::mesh::{BoundaryFace, VolumeMesh};

use super::tied_heat::{
    BodySpec, DirichletSpec, InterfaceSpec, NeumannSpec, SideSpec, SolveSpec, TiedHeatSpec,
};
use super::{FileScene, SceneError};
use mortar::io::{msh41_volume_bytes, Integration, MshFormat, Multipliers};

/// The names of the built-in scenes (`mortar run --scene NAME`): `tied_heat` (this module),
/// `pellet` (`crate::pellet`, run by its own driver), and the
/// [`BUILTIN_CONTACT_SCENES`].
pub const BUILTIN_SCENES: &[&str] = &["tied_heat", "pellet", "hertz2d", "hertz3d", "shrink_fit"];

/// The built-in contact scenes, run from memory by
/// [`run_builtin_contact`](super::run_builtin_contact): `hertz2d`, `hertz3d` and
/// `shrink_fit`.
pub const BUILTIN_CONTACT_SCENES: &[&str] = &["hertz2d", "hertz3d", "shrink_fit"];

/// A built-in scene: its scene file and the mesh files it names.
#[derive(Debug, Clone)]
pub struct BuiltinScene {
    /// The scene.
    pub spec: TiedHeatSpec,
    /// The scene file's text.
    pub toml: String,
    /// The mesh files, by file name.
    pub meshes: Vec<(String, Vec<u8>)>,
}

/// The built-in scene `name`: `tied_heat` is [`tied_block`] in 2D with `n = 8`, ASCII meshes.
///
/// # Errors
/// [`SceneError::Other`] for an unknown name (listing the known ones), and for `pellet`,
/// which is not a tied-heat scene (its driver is `crate::pellet`).
pub fn builtin_scene(name: &str) -> Result<BuiltinScene, SceneError> {
    match name {
        "tied_heat" => tied_block(2, 8, MshFormat::Ascii),
        "pellet" => Err(SceneError::Other(
            "the built-in scene \"pellet\" is not a tied-heat scene: run it with \
             `mortar run --scene pellet` (or mortar_scenes::pellet)"
                .into(),
        )),
        name if BUILTIN_CONTACT_SCENES.contains(&name) => Err(SceneError::Other(format!(
            "the built-in scene \"{name}\" is a contact scene run from memory: run it with \
             `mortar run --scene {name}` (or mortar_scenes::file::run_builtin_contact)"
        ))),
        _ => Err(SceneError::Other(format!(
            "no built-in scene named \"{name}\" (built-in scenes: {})",
            BUILTIN_SCENES.join(", ")
        ))),
    }
}

/// The exact temperature of [`tied_block`]: piecewise linear in `x`, `4x/3` in the left body
/// (k = 1) and `2/3 + 2(x - 1/2)/3` in the right one (k = 2).
pub fn tied_block_exact(x: f64) -> f64 {
    if x <= 0.5 {
        4.0 * x / 3.0
    } else {
        2.0 / 3.0 + 2.0 * (x - 0.5) / 3.0
    }
}

/// A square (cube) `[0, 1]^dim` cut at `x = 1/2` into two bodies meshed independently with a
/// 2:3 size ratio: `left` (master; `n/2 x n (x n)` Quad4 or Hex8, conductivity 1, `T = 0` on
/// `x = 0`) and `right` (slave; `3n/4 x 3n/2 (x 3n/2)` cells cut into Tri3 or Tet4,
/// conductivity 2, entering flux 4/3 on `x = 1`), insulated elsewhere. Its solution
/// [`tied_block_exact`] is piecewise linear, so the mortar solution reproduces it to
/// round-off (the patch test).
///
/// Mesh files `left.msh` and `right.msh`, each with the body's group (`left`, `right`) and
/// three face groups: `*_end` (on `x = 0` or `x = 1`), `*_cut` (on `x = 1/2`) and `*_sides`.
///
/// # Errors
/// [`SceneError::Other`] for a `dim` other than 2 or 3 or an `n` not a positive multiple of 4.
pub fn tied_block(dim: usize, n: usize, format: MshFormat) -> Result<BuiltinScene, SceneError> {
    if !(dim == 2 || dim == 3) || n == 0 || !n.is_multiple_of(4) {
        return Err(SceneError::Other(format!(
            "tied_block: dimension {dim} (2 or 3) and n = {n} (a positive multiple of 4)"
        )));
    }
    let other = |e: &dyn std::fmt::Display| SceneError::Other(e.to_string());
    let (left, right) = crate::tied_heat::straight_blocks(dim, n, 1).map_err(|e| other(&e))?;
    let meshes = vec![
        (
            "left.msh".to_string(),
            body_file(&left, "left", 0.0, format)?,
        ),
        (
            "right.msh".to_string(),
            body_file(&right, "right", 1.0, format)?,
        ),
    ];
    let body = |name: &str, k: f64| BodySpec {
        mesh: PathBuf::from(format!("{name}.msh")),
        group: name.to_string(),
        conductivity: k,
        rho_cp: None,
        source: 0.0,
        initial: 0.0,
        dirichlet: Vec::new(),
        neumann: Vec::new(),
    };
    let mut l = body("left", 1.0);
    l.dirichlet.push(DirichletSpec {
        group: "left_end".into(),
        value: 0.0,
    });
    let mut r = body("right", 2.0);
    r.neumann.push(NeumannSpec {
        group: "right_end".into(),
        flux: 4.0 / 3.0,
    });
    let spec = TiedHeatSpec {
        kind: "tied_heat".into(),
        title: Some(format!(
            "{dim}D block cut at x = 1/2, non-matching meshes (2:3), piecewise linear solution"
        )),
        dimension: Some(dim as u8),
        solve: SolveSpec::default(),
        bodies: BTreeMap::from([("left".to_string(), l), ("right".to_string(), r)]),
        interface: InterfaceSpec {
            slave: SideSpec {
                body: "right".into(),
                group: "right_cut".into(),
            },
            master: SideSpec {
                body: "left".into(),
                group: "left_cut".into(),
            },
            multipliers: Multipliers::Dual,
            integration: Integration::Segment,
            degree: None,
            curved_tolerance: None,
            subdivision: None,
            quad_subdivision: None,
            search_radius: None,
            require_full_coverage: false,
        },
    };
    let toml = spec.to_toml()?;
    Ok(BuiltinScene { spec, toml, meshes })
}

/// A body's Gmsh file with its `*_end` face group on `x = end`, `*_cut` on `x = 1/2` and
/// `*_sides` elsewhere.
fn body_file(
    mesh: &VolumeMesh,
    name: &str,
    end: f64,
    format: MshFormat,
) -> Result<Vec<u8>, SceneError> {
    let faces = mesh
        .boundary_faces()
        .map_err(|e| SceneError::Other(e.to_string()))?;
    let on = |f: &BoundaryFace, x: f64| (f.centroid.x - x).abs() < 1e-9;
    let ends: Vec<BoundaryFace> = faces.iter().filter(|f| on(f, end)).cloned().collect();
    let cut: Vec<BoundaryFace> = faces.iter().filter(|f| on(f, 0.5)).cloned().collect();
    let sides: Vec<BoundaryFace> = faces
        .iter()
        .filter(|f| !on(f, end) && !on(f, 0.5))
        .cloned()
        .collect();
    msh41_volume_bytes(
        (mesh, name),
        &[
            (&ends, &format!("{name}_end")),
            (&cut, &format!("{name}_cut")),
            (&sides, &format!("{name}_sides")),
        ],
        format,
    )
    .map_err(|e| SceneError::Other(e.to_string()))
}
