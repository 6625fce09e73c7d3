//! The thermomechanical pellet: expansion, contact across the gap, gap conductance on the
//! mechanical gap, plenum pressure (docs/models.md, section 3a).

use std::f64::consts::PI;
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use mortar_core::{CouplingOptions, ModelGeometry, SearchRadius, Tolerances};
use mortar_fem::mesh::{BoundaryFace, VolumeMesh};
use mortar_physics::elastic::{
    AxialForce, ComponentSet, ElasticBody, ElasticMaterial, ElasticOptions,
};
use mortar_physics::heat::{
    assemble_conduction, Conductivity, HeatBody, HeatMaterial, HeatOptions,
};
use mortar_physics::laws::{
    ConstraintLaw, ContactComplementarity, DynLaw, ExponentialContact, GapConductance,
    GasConductivity, LawRegistry, MechanicalGapConductance, RelocationInput, RelocationModel,
};
use mortar_physics::nonlinear::NewtonOptions;
use mortar_physics::thermomech::{
    GapThermoMechanics, GasPressure, Plenum, ThermoElasticBody, ThermoMechOptions,
    ThermoMechSolver, ThermoMechSolverState, ThermoMechStats,
};
use mortar_physics::PhysicsError;
use nalgebra::Vector3;
use serde_json::{json, Value};

use super::file_mesh::{contains, FaceSet, FileGeometry};
use super::limits::{extremes, LimitWatch, When};
use super::run::{mesh_area, nearest_node, progress_bar, pvd, write_scene_outputs};
use super::{
    annulus_mesh, pellet_mesh, AxialModel, ContactLawName, Geometry, PelletError, PelletScene,
    SolverChoice, SolverMethod,
};
#[cfg(feature = "plots")]
use crate::plot::{line_chart_png, Chart, Curve};
use mortar::generate::{extrude_mesh, rectangle_mesh, CellShape};
use mortar::io::vtu::{surface_vtu_string, vtu_string_with_vectors, VtuPiece};

/// The most times a failing time step is halved before the run stops.
pub const MAX_STEP_CUTS: usize = 4;

/// The thermal law of the coupled scene: Ross-Stoute on the mechanical gap plus the contact
/// conductance.
///
/// # Errors
/// [`PelletError::Law`] for parameters out of range.
pub fn thermal_law(scene: &PelletScene) -> Result<MechanicalGapConductance, PelletError> {
    let gas = match scene.gap.gas_conductivity {
        Some(k) => GasConductivity::Constant(k),
        None => GasConductivity::HELIUM,
    };
    Ok(MechanicalGapConductance::try_new(
        scene.gap.roughness_pellet,
        scene.gap.roughness_cladding,
        scene.gap.jump_distance,
        gas,
        scene.gap.contact_conductance,
    )?)
}

/// The scene's exponential contact law (`[contact]` stiffness exponent and onset gap).
///
/// # Errors
/// [`PelletError::Law`] for parameters out of range.
pub fn exponential_contact_law(scene: &PelletScene) -> Result<ExponentialContact, PelletError> {
    Ok(ExponentialContact::try_new(
        scene.contact.stiffness_exponent,
        scene.contact.onset_gap,
    )?)
}

/// The complementarity parameter `c` (Pa/m) of the exact law: the pellet's radial stiffness
/// `E / (a (1 + nu)(1 - 2 nu))` (any positive value gives the same solution).
fn complementarity(scene: &PelletScene) -> f64 {
    let p = &scene.pellet;
    p.youngs_modulus / (p.radius * (1.0 + p.poisson_ratio) * (1.0 - 2.0 * p.poisson_ratio))
}

/// Builds the coupled problem of `scene` with the contact law `law` and the scene's thermal
/// law ([`thermal_law`]) (see [`run_coupled`]).
///
/// # Errors
/// [`PelletError::Mesh`] / [`PelletError::Physics`] for meshes or a problem that cannot be
/// built.
pub fn coupled_problem<ML: ConstraintLaw + Clone>(
    scene: &PelletScene,
    law: ML,
) -> Result<GapThermoMechanics<MechanicalGapConductance, ML>, PelletError> {
    coupled_problem_with(scene, thermal_law(scene)?, law)
}

/// Builds the coupled problem of `scene` with any thermal law `thermal` (heat flux against
/// temperature jump; it sees the mechanical gap, contact and gas pressures of each point) and
/// contact law `contact` (contact pressure in excess of the gas pressure against the gap);
/// the relocation model `[model] relocation` is a shipped one
/// ([`LawRegistry::with_shipped`]).
///
/// # Errors
/// As [`coupled_problem`]; [`PelletError::Law`] for an unknown relocation model.
pub fn coupled_problem_with<TL: ConstraintLaw + Clone, ML: ConstraintLaw + Clone>(
    scene: &PelletScene,
    thermal: TL,
    contact: ML,
) -> Result<GapThermoMechanics<TL, ML>, PelletError> {
    let relocation = LawRegistry::with_shipped().relocation(&scene.model.relocation)?;
    let (scene, file) = scene.resolved()?;
    problem_of(&scene, file.as_ref(), thermal, contact, &relocation)
}

/// An eigenstrain that follows time: its unit and its factor at a time.
type RelocationLoad = ([f64; 6], Box<dyn Fn(f64) -> f64 + Send + Sync>);

/// The relocation of `scene` as the pellet's eigenstrain that follows time: `unit` across
/// the axis (`[1, 1, 0, ...]` in 2D and 3D, `eps_rr = eps_tt` in r-z) times `model`'s strain
/// at the largest linear power reached by `t` (the ramp never falls, so `q'(t)`), the scene's
/// burnup and its cold gap `b - a`; `None` for the model `none`.
fn relocation_load(
    scene: &PelletScene,
    model: &Arc<dyn RelocationModel>,
) -> Option<RelocationLoad> {
    if model.name() == "none" {
        return None;
    }
    let unit = match scene.model.geometry {
        Geometry::Axisymmetric => [1.0, 0.0, 1.0, 0.0, 0.0, 0.0],
        _ => [1.0, 1.0, 0.0, 0.0, 0.0, 0.0],
    };
    let (power, model) = (scene.power, Arc::clone(model));
    let rod = RelocationInput {
        linear_power: 0.0,
        burnup: scene.model.burnup,
        cold_gap: scene.cladding.inner_radius - scene.pellet.radius,
        pellet_radius: scene.pellet.radius,
    };
    Some((
        unit,
        Box::new(move |t| {
            model.strain(&RelocationInput {
                linear_power: power.at(t),
                ..rod
            })
        }),
    ))
}

/// [`coupled_problem_with`] of a scene already [`resolved`](PelletScene::resolved), with its
/// mesh file's geometry if it has one.
fn problem_of<TL: ConstraintLaw + Clone, ML: ConstraintLaw + Clone>(
    scene: &PelletScene,
    file: Option<&FileGeometry>,
    thermal: TL,
    contact: ML,
    relocation: &Arc<dyn RelocationModel>,
) -> Result<GapThermoMechanics<TL, ML>, PelletError> {
    let (p, c) = (&scene.pellet, &scene.cladding);
    let r = scene.mesh.refinement;
    let geometry = scene.model.geometry;
    let height = scene.model.segment_height;
    let (a, b) = (p.radius, c.inner_radius);
    let tol = 1e-9 * c.outer_radius;
    // Meshes, the pellet's cross-section area (the heat source is q'(t) / area), and the
    // axial component (held on the end planes in 3D and r-z: plane strain).
    let (pellet_mesh, cladding_mesh, area, axial) = match (geometry, file) {
        (Geometry::Plane | Geometry::PlaneStrain, Some(f)) => (
            f.pellet.clone(),
            f.cladding.clone(),
            f.pellet_volume,
            usize::MAX,
        ),
        // The user's section: the heat source is q'(t) over the mean cross-section
        // V_pellet / H, so that the segment produces q' H whatever its dishes.
        (Geometry::Axisymmetric, Some(f)) => (
            f.pellet.clone(),
            f.cladding.clone(),
            f.pellet_volume / f.height,
            1,
        ),
        (Geometry::Plane | Geometry::PlaneStrain | Geometry::ThreeD, _) => {
            // The pellet's circle has 16 r edges, the cladding's 20 r: the interface does not
            // match (they share the four nodes on the axes, which hold the rigid motions). In
            // 3D both cross-sections are swept along z through `axial_layers` layers of Hex8.
            let pm = pellet_mesh(a, 4 * r, 2 * r)?;
            let cm = annulus_mesh(b, c.outer_radius, 20 * r, 2 * r, 0.0)?;
            let area = mesh_area(&pm);
            if geometry == Geometry::ThreeD {
                let layers = scene.mesh.axial_layers;
                let levels: Vec<f64> = (0..=layers)
                    .map(|k| height * k as f64 / layers as f64)
                    .collect();
                (
                    extrude_mesh(&pm, &levels, 1)?,
                    extrude_mesh(&cm, &levels, 1)?,
                    area,
                    2,
                )
            } else {
                (pm, cm, area, usize::MAX)
            }
        }
        (Geometry::Axisymmetric, None) => {
            // The r-z section (x = r, y = z) of a pellet segment: 8 r x 2 cells in the pellet,
            // 2 r x 3 in the cladding, so that the interface r = a does not match; the revolved
            // pellet is exactly pi a^2 H.
            let layers = scene.mesh.axial_layers;
            let pm = rectangle_mesh(
                [0.0, 0.0],
                [a, height],
                [8 * r, layers],
                CellShape::Tensor,
                1,
            )?;
            let cm = rectangle_mesh(
                [b, 0.0],
                [c.outer_radius, height],
                [2 * r, layers + 1],
                CellShape::Tensor,
                1,
            )?;
            (pm, cm, PI * a * a, 1)
        }
    };
    let end_coordinate = move |x: &Vector3<f64>| match geometry {
        Geometry::ThreeD => Some(x.z),
        Geometry::Axisymmetric => Some(x.y),
        Geometry::Plane | Geometry::PlaneStrain => None,
    };
    // Faces: lateral unless on an end plane; the radius: in the xy plane, or x in r-z.
    let lateral = move |f: &BoundaryFace| {
        end_coordinate(&f.centroid).is_none_or(|z| z > tol && z < height - tol)
    };
    let radius = move |x: &Vector3<f64>| match geometry {
        Geometry::Axisymmetric => x.x,
        _ => x.xy().norm(),
    };
    let mid = 0.5 * (c.inner_radius + c.outer_radius);
    // The surfaces: the file's groups, or the generated section's faces by position.
    let coolant = |f: &BoundaryFace| match file {
        Some(g) => contains(&g.cladding_outer, f),
        None => radius(&f.centroid) > mid && lateral(f),
    };
    let slave_face = |f: &BoundaryFace| match file {
        Some(g) => contains(&g.pellet_outer, f),
        None => radius(&f.centroid) > 0.5 * a && lateral(f),
    };
    let master_face = |f: &BoundaryFace| match file {
        Some(g) => contains(&g.cladding_inner, f),
        None => radius(&f.centroid) < mid && lateral(f),
    };
    let power = scene.power;
    let power = move |t: f64| power.at(t);
    let k_pellet = Conductivity::InverseLinear {
        a: p.conductivity_a,
        b: p.conductivity_b,
    };
    let t_co = c.outer_temperature;
    let t_ref = scene.model.reference_temperature;
    let zero = |_: &Vector3<f64>| Vector3::zeros();
    // The nodes on the line through (x, y) along z (the one node there in 2D).
    let at = |mesh: &VolumeMesh, x: [f64; 2]| -> Vec<u32> {
        let xy = nalgebra::Vector2::new(x[0], x[1]);
        (0..mesh.node_count() as u32)
            .filter(|&i| (mesh.coords()[i as usize].xy() - xy).norm() < tol)
            .collect()
    };
    // In 3D and r-z: no axial displacement on the bottom plane (symmetry), nor on the top
    // one in plane strain (free axial expansion: the top is the axial unknown's).
    let free_ends = scene.model.axial() == AxialModel::Generalized;
    let held = move |f: &BoundaryFace| {
        end_coordinate(&f.centroid).is_some_and(|z| z <= tol || (!free_ends && z >= height - tol))
    };
    let ends = move |body: ElasticBody| -> Result<ElasticBody, PelletError> {
        if axial == usize::MAX {
            Ok(body)
        } else {
            Ok(body.with_dirichlet_where(held, ComponentSet::One(axial), zero)?)
        }
    };

    let pellet_heat = HeatBody::new(
        "pellet",
        pellet_mesh.clone(),
        HeatMaterial::new(k_pellet.at(t_co).0, p.heat_capacity),
    )
    .with_source(move |_x, t| power(t) / area);
    let pellet_elastic = ElasticBody::new(
        "pellet",
        pellet_mesh.clone(),
        ElasticMaterial::new(p.youngs_modulus, p.poisson_ratio)
            .with_expansion(p.thermal_expansion, t_ref),
    );
    let pellet_elastic = ends(if geometry == Geometry::Axisymmetric {
        // u_r = 0 on the axis.
        let axis = (0..pellet_mesh.node_count() as u32)
            .filter(|&i| pellet_mesh.coords()[i as usize].x.abs() < tol)
            .collect();
        pellet_elastic.with_dirichlet_nodes(axis, ComponentSet::One(0), zero)
    } else {
        // Rigid motions: the axis held in x and y, the line through (a, 0) held in y; the
        // exact field is radial, so none of them loads the body. A file's pellet: the node
        // nearest the axis and the lateral surface's node furthest along x.
        let (centre, east) = match file {
            Some(f) => (
                vec![nearest_node(&pellet_mesh, Vector3::zeros()) as u32],
                vec![extreme_node(&pellet_mesh, &f.pellet_outer, |x| x.x)?],
            ),
            None => (at(&pellet_mesh, [0.0, 0.0]), at(&pellet_mesh, [a, 0.0])),
        };
        pellet_elastic
            .with_dirichlet_nodes(centre.clone(), ComponentSet::One(0), zero)
            .with_dirichlet_nodes(centre, ComponentSet::One(1), zero)
            .with_dirichlet_nodes(east, ComponentSet::One(1), zero)
    })?;

    let cladding_heat = HeatBody::new(
        "cladding",
        cladding_mesh.clone(),
        HeatMaterial::new(c.conductivity, c.heat_capacity),
    )
    .with_dirichlet_where(coolant, move |_x, _t| t_co)?;
    let p_cool = c.coolant_pressure;
    let cladding_elastic = ElasticBody::new(
        "cladding",
        cladding_mesh.clone(),
        ElasticMaterial::new(c.youngs_modulus, c.poisson_ratio)
            .with_expansion(c.thermal_expansion, t_ref),
    )
    .with_traction_where(coolant, move |x| {
        // The coolant presses along the inward radius.
        let r = radius(x);
        match geometry {
            Geometry::Axisymmetric => Vector3::new(-p_cool, 0.0, 0.0),
            _ => Vector3::new(-p_cool * x.x / r, -p_cool * x.y / r, 0.0),
        }
    })?;
    let cladding_elastic = ends(if geometry == Geometry::Axisymmetric {
        cladding_elastic
    } else {
        // Rigid motions: the inner lines on the axes held in their tangential direction (a
        // file's: the inner surface's nodes furthest along +x, -x and +y).
        let (e, w, n) = match file {
            Some(f) => {
                let extreme = |along: fn(&Vector3<f64>) -> f64| {
                    extreme_node(&cladding_mesh, &f.cladding_inner, along).map(|n| vec![n])
                };
                (extreme(|x| x.x)?, extreme(|x| -x.x)?, extreme(|x| x.y)?)
            }
            None => (
                at(&cladding_mesh, [b, 0.0]),
                at(&cladding_mesh, [-b, 0.0]),
                at(&cladding_mesh, [0.0, b]),
            ),
        };
        cladding_elastic
            .with_dirichlet_nodes([e, w].concat(), ComponentSet::One(1), zero)
            .with_dirichlet_nodes(n, ComponentSet::One(0), zero)
    })?;

    let slave_surface = pellet_heat.mesh.boundary_surface(slave_face)?;
    let master_surface = cladding_heat.mesh.boundary_surface(master_face)?;
    let gap = c.inner_radius - p.radius;
    let widest = file.map_or(gap, |f| f.widest_gap.max(gap));
    let tolerances = Tolerances {
        search_radius: SearchRadius::Distance(2.0 * widest),
        ..Tolerances::default()
    };
    let pl = &scene.plenum;
    // Per unit length in 2D; the segment's share of the plenum in 3D and r-z.
    let length = if geometry.is_plane() { 1.0 } else { height };
    // The file's dishes and chamfers hold gas at the plenum's pressure: a volume of the
    // plenum's (held at its as-built size).
    let end_voids = file.map_or(0.0, |f| f.end_voids());
    let plenum = Plenum::from_fill(
        pl.volume * length + end_voids,
        file.map_or(
            PI * (c.inner_radius.powi(2) - p.radius.powi(2)) * length,
            |f| f.gap_volume(),
        ),
        pl.fill_pressure,
        pl.fill_temperature,
    )?;
    let model = if geometry == Geometry::Axisymmetric {
        ModelGeometry::Axisymmetric
    } else {
        ModelGeometry::Cartesian
    };
    let options = ThermoMechOptions {
        heat: HeatOptions::default().with_geometry(model),
        elastic: ElasticOptions::default().with_geometry(model),
        // A file's gap is its meshes' (an eccentric pellet's varies around it).
        nominal_gap: file.is_none().then_some(gap),
        gas: GasPressure::Plenum(plenum),
        flux_unit: 1.0 / GapConductance::DEFAULT_REFERENCE_RESISTANCE,
        axial: if free_ends {
            // The next pellet bears on the file's land only: the gas presses on the rest
            // of the end (dish and chamfer) as a surface load.
            axial_forces(scene, file, area)
        } else {
            [None, None]
        },
        ..ThermoMechOptions::default()
    };
    let coupling = CouplingOptions::default().dual().with_geometry(model);
    let laws = (thermal.clone(), contact.clone());
    let problem = GapThermoMechanics::new(
        ThermoElasticBody {
            heat: pellet_heat,
            conductivity: k_pellet,
            elastic: pellet_elastic,
        },
        ThermoElasticBody {
            heat: cladding_heat,
            conductivity: Conductivity::Constant(c.conductivity),
            elastic: cladding_elastic,
        },
        slave_surface,
        master_surface,
        &coupling,
        tolerances,
        thermal,
        contact,
        &options,
    )?;
    let problem = match file {
        Some(f) if !f.pellet_free.is_empty() => {
            let free = f
                .pellet
                .boundary_surface(|face| contains(&f.pellet_free, face))?;
            problem.with_gas_on(0, &free)?
        }
        _ => problem,
    };
    // A stack's pellets bear on each other at their lands: a contact pair of the pellet
    // body with itself, under the gap's laws.
    let problem = match file.and_then(|f| f.lands.as_ref().map(|l| (f, l))) {
        Some((f, [lower, upper])) => {
            let lower = f.pellet.boundary_surface(|face| contains(lower, face))?;
            let upper = f.pellet.boundary_surface(|face| contains(upper, face))?;
            let (thermal, contact) = laws;
            problem.with_contact_pair(
                lower,
                upper,
                [0, 0],
                &coupling,
                tolerances,
                thermal,
                contact,
            )?
        }
        None => problem,
    };
    Ok(match relocation_load(scene, relocation) {
        Some((unit, strain)) => problem.with_eigenstrain(0, unit, strain)?,
        None => problem,
    })
}

/// The axial forces `[pellet, cladding]` of free axial expansion: the plenum pressure on the
/// pellet's ends over its cross-section, `-P_o A_pellet`; on the cladding's closed ends over
/// the area its inner surface encloses, less the coolant's over the area its outer surface
/// encloses, `P_o A_inner - P_coolant A_outer`. The areas are those of the model's own
/// surfaces (the polygons of `20 r` edges of the cladding's circles in 2D and 3D, exact
/// circles in r-z), so that a uniform axial stress balances them exactly; `pellet_area` is
/// the pellet mesh's.
fn axial_forces(
    scene: &PelletScene,
    file: Option<&FileGeometry>,
    pellet_area: f64,
) -> [Option<AxialForce>; 2] {
    let c = &scene.cladding;
    // The area of a circle of radius 1 as the model sees it.
    let unit = if scene.model.geometry == Geometry::Axisymmetric {
        PI
    } else {
        let n = (20 * scene.mesh.refinement) as f64;
        0.5 * n * (2.0 * PI / n).sin()
    };
    // The coolant's force on the closed ends, `-P_coolant A_outer`.
    let coolant = -c.coolant_pressure;
    let (pellet, inner, outer_force) = match file {
        // In r-z the next pellet bears on the file's land only (the gas presses on the rest
        // of the end, dish and chamfer, as a surface load); in 2D the areas are the file's.
        Some(f) if f.axisymmetric => (
            f.land_area,
            unit * c.inner_radius.powi(2),
            coolant * unit * c.outer_radius.powi(2),
        ),
        Some(f) => (
            f.pellet_volume,
            f.enclosed_areas[0],
            coolant * f.enclosed_areas[1],
        ),
        None => (
            pellet_area,
            unit * c.inner_radius.powi(2),
            coolant * unit * c.outer_radius.powi(2),
        ),
    };
    [
        Some(AxialForce {
            force: 0.0,
            per_gas_pressure: -pellet,
        }),
        Some(AxialForce {
            force: outer_force,
            per_gas_pressure: inner,
        }),
    ]
}

/// The node of the faces `set` of `mesh` furthest along `along`.
fn extreme_node(
    mesh: &VolumeMesh,
    set: &FaceSet,
    along: impl Fn(&Vector3<f64>) -> f64,
) -> Result<u32, PelletError> {
    let x = mesh.coords();
    let mut best: Option<(f64, u32)> = None;
    for f in mesh.boundary_faces()?.iter().filter(|f| contains(set, f)) {
        for &n in &f.nodes {
            let v = along(&x[n as usize]);
            if best.is_none_or(|(b, m)| v > b || (v == b && n < m)) {
                best = Some((v, n));
            }
        }
    }
    best.map(|(_, n)| n)
        .ok_or_else(|| PelletError::Invalid("a surface group without faces".into()))
}

/// Runs the coupled scene (see [`run`](super::run)).
///
/// # Errors
/// As [`run`](super::run).
pub fn run_coupled(scene: &PelletScene, out: &Path, progress: bool) -> Result<Value, PelletError> {
    run_coupled_in(scene, &LawRegistry::with_shipped(), out, progress)
}

/// [`run_coupled`] with the laws and relocation models of `registry`: the laws the scene's
/// `[laws]` tables name ([`run_with_registry`]), else the scene's built-in ones under their
/// descriptive names, as [`run_coupled`] reports them.
///
/// # Errors
/// As [`run_with_registry`].
pub fn run_coupled_in(
    scene: &PelletScene,
    registry: &LawRegistry,
    out: &Path,
    progress: bool,
) -> Result<Value, PelletError> {
    if scene.laws.thermal.is_some() || scene.laws.contact.is_some() {
        return run_with_registry(scene, registry, out, progress);
    }
    let relocation = registry.relocation(&scene.model.relocation)?;
    match scene.contact.law {
        ContactLawName::Exponential => {
            let law = exponential_contact_law(scene)?;
            let onset = law.onset();
            let names = (
                "Ross-Stoute on the mechanical gap, plus h_contact p_contact",
                "exponential",
            );
            run_with(
                scene,
                (thermal_law(scene)?, law),
                names,
                Some(onset),
                &relocation,
                out,
                progress,
            )
        }
        ContactLawName::Exact => {
            let law = ContactComplementarity::try_new(complementarity(scene))?;
            let names = (
                "Ross-Stoute on the mechanical gap, plus h_contact p_contact",
                "exact",
            );
            run_with(
                scene,
                (thermal_law(scene)?, law),
                names,
                None,
                &relocation,
                out,
                progress,
            )
        }
    }
}

/// Runs the coupled scene with the laws of its `[laws]` tables made by `registry` (the shipped
/// laws and a program's own; see [`LawsData`](super::LawsData)); a law not named there is the
/// scene's built-in one, made by name too (`mechanical_gap_conductance` from `[gap]`,
/// `exponential_contact` or `contact_complementarity` from `[contact]`).
///
/// # Errors
/// [`PelletError::Law`] for an unknown name (listing the known ones), a missing parameter or
/// a value the law refuses; otherwise as [`run`](super::run).
pub fn run_with_registry(
    scene: &PelletScene,
    registry: &LawRegistry,
    out: &Path,
    progress: bool,
) -> Result<Value, PelletError> {
    // A law the scene does not name is its built-in one, under its registry name.
    let thermal = match &scene.laws.thermal {
        Some(spec) => spec.make(registry)?,
        None => DynLaw::new("mechanical_gap_conductance", thermal_law(scene)?),
    };
    let (contact, onset) = match &scene.laws.contact {
        Some(spec) => {
            let law = spec.make(registry)?;
            let onset = (spec.name == "exponential_contact")
                .then(|| spec.parameters.get("onset").copied())
                .flatten();
            (law, onset)
        }
        None => {
            let ct = &scene.contact;
            match ct.law {
                ContactLawName::Exponential => (
                    DynLaw::new("exponential_contact", exponential_contact_law(scene)?),
                    Some(ct.onset_gap),
                ),
                ContactLawName::Exact => (
                    DynLaw::new(
                        "contact_complementarity",
                        ContactComplementarity::try_new(complementarity(scene))?,
                    ),
                    None,
                ),
            }
        }
    };
    let names = (thermal.name().to_string(), contact.name().to_string());
    let relocation = registry.relocation(&scene.model.relocation)?;
    run_with(
        scene,
        (thermal, contact),
        (&names.0, &names.1),
        onset,
        &relocation,
        out,
        progress,
    )
}

/// Runs the coupled scene with a program's own interface laws in place of the scene's
/// (`[gap]` and `[contact]` then serve only the gap's search radius): everything else, the
/// solver, the report, the VTU and plots, as [`run_coupled`]. The report names the laws by
/// their Rust types; contact counts as engaged once the mean contact pressure exceeds a
/// millionth of the gas pressure.
///
/// # Errors
/// As [`run`](super::run).
pub fn run_coupled_with<TL: ConstraintLaw + Clone, ML: ConstraintLaw + Clone>(
    scene: &PelletScene,
    thermal: TL,
    contact: ML,
    out: &Path,
    progress: bool,
) -> Result<Value, PelletError> {
    let names = (std::any::type_name::<TL>(), std::any::type_name::<ML>());
    let relocation = LawRegistry::with_shipped().relocation(&scene.model.relocation)?;
    run_with(
        scene,
        (thermal, contact),
        names,
        None,
        &relocation,
        out,
        progress,
    )
}

/// The quantities of one state, for the history.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Summary {
    center: f64,
    pellet_surface: f64,
    cladding_inner: f64,
    gap: f64,
    min_gap: f64,
    interface_pressure: f64,
    peak_pressure: f64,
    contact_pressure: f64,
    plenum: f64,
    displacement: f64,
    /// A stack's lands (its contact pairs): the smallest gap and the largest contact
    /// pressure (NaN without).
    land_min_gap: f64,
    land_peak_pressure: f64,
}

fn summary<TL: ConstraintLaw, ML: ConstraintLaw>(
    problem: &GapThermoMechanics<TL, ML>,
    x: &[f64],
    centre: usize,
) -> Summary {
    let f = problem.fields(x);
    let tie = problem.heat().tie();
    let w = &problem.normal_gap().weights;
    let length: f64 = w.iter().sum();
    let mean = |v: &[f64]| v.iter().zip(w).map(|(a, b)| a * b).sum::<f64>() / length;
    let (ts, tm) = (f.temperature[0], f.temperature[1]);
    let node_mean = |nodes: &[u32], t: &[f64]| {
        nodes.iter().map(|&n| t[n as usize]).sum::<f64>() / nodes.len() as f64
    };
    let gaps = problem.gaps(x);
    let p = f.contact_pressure();
    let u = f.displacement(0);
    let coords = problem.heat().bodies()[0].mesh.coords();
    let sn = tie.slave_nodes();
    let dim = problem.elastic_bodies()[0].components();
    let rz = problem.options().elastic.geometry.is_axisymmetric();
    let radial: f64 = sn
        .iter()
        .map(|&n| {
            let (n, x) = (n as usize, coords[n as usize]);
            if rz {
                u[dim * n]
            } else {
                (u[dim * n] * x.x + u[dim * n + 1] * x.y) / x.xy().norm()
            }
        })
        .sum::<f64>()
        / sn.len() as f64;
    Summary {
        center: ts[centre],
        pellet_surface: node_mean(sn, ts),
        cladding_inner: node_mean(tie.master_nodes(), tm),
        gap: mean(&gaps),
        min_gap: gaps.iter().copied().fold(f64::INFINITY, f64::min),
        interface_pressure: f.gas_pressure + mean(&p),
        peak_pressure: f.gas_pressure + p.iter().copied().fold(0.0, f64::max),
        contact_pressure: mean(&p),
        plenum: f.gas_pressure,
        displacement: radial,
        land_min_gap: (0..problem.contact_pairs())
            .flat_map(|k| problem.pair_gaps(k, x))
            .reduce(f64::min)
            .unwrap_or(f64::NAN),
        land_peak_pressure: (0..problem.contact_pairs())
            .flat_map(|k| problem.pair_contact_pressures(k, x))
            .reduce(f64::max)
            .unwrap_or(f64::NAN),
    }
}

/// The time stepping, reports and outputs of the coupled scene with contact law `law`
/// (`onset`: the exponential law's `xi`, for the time contact engages): the initial state,
/// the backward Euler steps and the steady state at full power ([`March`]), then the
/// report and the outputs.
fn run_with<TL: ConstraintLaw + Clone, ML: ConstraintLaw + Clone>(
    scene: &PelletScene,
    laws: (TL, ML),
    names: (&str, &str),
    onset: Option<f64>,
    relocation: &Arc<dyn RelocationModel>,
    out: &Path,
    progress: bool,
) -> Result<Value, PelletError> {
    let start = Instant::now();
    // A mesh file's radii and height replace the scene's everywhere below.
    let (scene, file) = scene.resolved()?;
    let scene = &scene;
    let problem = problem_of(scene, file.as_ref(), laws.0, laws.1, relocation)?;
    let setup_seconds = start.elapsed().as_secs_f64();
    let choice = scene
        .solver
        .choose(true, scene.model.geometry.is_plane(), problem.dimension());
    let steps = scene.time.steps();
    let bar = progress_bar(progress, steps as u64 + 1);
    let mut march = March::new(scene, &problem, &choice, out);
    march.initial()?;
    for k in 1..=steps {
        if let Err(e) = march.step(k) {
            bar.finish_and_clear();
            return Err(e);
        }
        let s = march.rows.last().expect("the step's row").1;
        bar.set_message(format!(
            "t = {:.1} s, T0 = {:.0} K, gap = {:.2} um",
            march.time,
            s.center,
            s.gap * 1e6
        ));
        bar.inc(1);
    }
    let transient_stats = march.solver.stats;
    let steady = march.steady();
    bar.inc(1);
    bar.finish_and_clear();
    let t_steady = steady?;
    let report = CoupledReport {
        scene,
        file: file.as_ref(),
        names,
        onset,
        relocation,
        choice: &choice,
        transient_stats,
        t_steady,
        seconds: (setup_seconds, start),
    }
    .json(&march)?;
    let March {
        mut outputs, rows, ..
    } = march;
    outputs.extend(history_plots(&rows)?);
    let text = serde_json::to_string_pretty(&report).expect("JSON values serialise");
    outputs.push(("report.json".to_string(), text.into_bytes()));
    write_scene_outputs(out, outputs)?;
    Ok(report)
}

/// A row of the history: time, summary, Newton and linear iterations, step cuts.
type Row = (f64, Summary, usize, usize, usize);

/// The coupled run as it goes: the problem and its solver (with the fallback of a picked
/// JFNK to Newton), the state, the history, the snapshots and the outputs, the model
/// ranges watched. Each solve that fails ends the run through [`fail`](Self::fail), which
/// writes what was computed with `"status": "failed"`.
struct March<'a, TL: ConstraintLaw, ML: ConstraintLaw> {
    scene: &'a PelletScene,
    problem: &'a GapThermoMechanics<TL, ML>,
    choice: &'a SolverChoice,
    out: &'a Path,
    newton: NewtonOptions,
    solver: ThermoMechSolverState,
    /// A picked JFNK whose solve failed hands the solve, and the rest of the run, to Newton:
    /// when and why.
    fallback: Option<Value>,
    x: Vec<f64>,
    /// The pellet's centre node (its temperature is the history's).
    centre: usize,
    time: f64,
    cuts_total: usize,
    rows: Vec<Row>,
    files: Vec<(String, f64)>,
    outputs: Vec<(String, Vec<u8>)>,
    watch: LimitWatch,
}

impl<'a, TL: ConstraintLaw, ML: ConstraintLaw> March<'a, TL, ML> {
    /// The run of `problem` (of `scene`) by the method of `choice`, from the uniform outer
    /// temperature, writing into `out`.
    fn new(
        scene: &'a PelletScene,
        problem: &'a GapThermoMechanics<TL, ML>,
        choice: &'a SolverChoice,
        out: &'a Path,
    ) -> Self {
        let method = match choice.method {
            SolverMethod::Jfnk => ThermoMechSolver::Jfnk(scene.solver.jfnk_options()),
            _ => ThermoMechSolver::Newton,
        };
        let bodies = problem.heat().bodies();
        let t_co = scene.cladding.outer_temperature;
        let t0 = vec![t_co; bodies[0].mesh.node_count()];
        let t1 = vec![t_co; bodies[1].mesh.node_count()];
        Self {
            scene,
            problem,
            choice,
            out,
            newton: scene.solver.newton_options(scene.power.linear_power),
            solver: ThermoMechSolverState::new(method),
            fallback: None,
            x: problem.state([&t0, &t1]),
            centre: nearest_node(&bodies[0].mesh, Vector3::zeros()),
            time: 0.0,
            cuts_total: 0,
            rows: Vec::new(),
            files: Vec::new(),
            outputs: Vec::new(),
            watch: LimitWatch::default(),
        }
    }

    /// Solves the state at `t` (steady for `transient = None`) from `self.x`; a picked JFNK
    /// that fails is handed to Newton, from the same start.
    fn solve(&mut self, t: f64, transient: Option<(&[f64], f64)>) -> Result<(), PhysicsError> {
        // The start of the solve, kept only while a fallback can use it.
        let start = (self.choice.picked && matches!(self.solver.method, ThermoMechSolver::Jfnk(_)))
            .then(|| self.x.clone());
        let problem = self.problem;
        match (
            problem.solve(&mut self.x, t, transient, &mut self.solver, &self.newton),
            start,
        ) {
            (Ok(_), _) => Ok(()),
            (Err(e), Some(start)) => {
                self.fallback = Some(json!({ "time": t, "cause": e.to_string() }));
                self.solver.method = ThermoMechSolver::Newton;
                self.x.copy_from_slice(&start);
                problem
                    .solve(&mut self.x, t, transient, &mut self.solver, &self.newton)
                    .map(|_| ())
            }
            (Err(e), None) => Err(e),
        }
    }

    /// The model ranges at the state, at `time`, for the step named `step`.
    fn observe(&mut self, time: f64, step: Value) -> Result<(), PelletError> {
        let extremes = extremes(self.problem, &self.x, time)?;
        self.watch.observe(&When { time, step }, &extremes);
        Ok(())
    }

    /// The initial state: mechanical equilibrium at the uniform temperature, no power; its
    /// row and snapshot.
    fn initial(&mut self) -> Result<(), PelletError> {
        if let Err(e) = self.solve(0.0, None) {
            let what = "the initial state".to_string();
            let e = located(self.problem, e, what, Some(0), 0.0, &self.x, None);
            return Err(self.fail(e));
        }
        self.observe(0.0, json!("initial"))?;
        let rep0 = self.solver.stats;
        self.rows.push((
            0.0,
            summary(self.problem, &self.x, self.centre),
            rep0.newton_iterations,
            rep0.linear_iterations,
            0,
        ));
        write_snapshot(
            self.out,
            self.problem,
            &self.x,
            self.time,
            &mut self.files,
            &mut self.outputs,
        )
    }

    /// Time step `k`: backward Euler from the time reached to `k dt` (the end at most),
    /// halving the step on a failure up to [`MAX_STEP_CUTS`] times; its row, and its
    /// snapshot when one is due. An interruption asked for stops the run here.
    fn step(&mut self, k: usize) -> Result<(), PelletError> {
        let (scene, steps) = (self.scene, self.scene.time.steps());
        if crate::interrupt::requested() {
            let e = PelletError::Interrupted {
                time: self.time,
                steps: k - 1,
            };
            return Err(self.fail(e));
        }
        let target = (k as f64 * scene.time.step).min(scene.time.end);
        let before = self.solver.stats;
        let mut cuts = 0;
        while self.time < target {
            let time = self.time;
            let dt = (target - time).min(scene.time.step / f64::powi(2.0, cuts as i32));
            let old = self.x.clone();
            match self.solve(time + dt, Some((&old, dt))) {
                Ok(_) => self.time += dt,
                Err(e) => {
                    cuts += 1;
                    if cuts > MAX_STEP_CUTS {
                        let what = format!(
                            "time step {k} of {steps} (from t = {time} s, dt = {dt} s after \
                             {MAX_STEP_CUTS} halvings)"
                        );
                        let transient = Some((old.as_slice(), dt));
                        let e = located(
                            self.problem,
                            e,
                            what,
                            Some(k),
                            time + dt,
                            &self.x,
                            transient,
                        );
                        return Err(self.fail(e));
                    }
                    self.x = old;
                }
            }
        }
        self.time = target;
        self.cuts_total += cuts;
        let s = summary(self.problem, &self.x, self.centre);
        self.observe(self.time, json!(k))?;
        self.rows.push((
            self.time,
            s,
            self.solver.stats.newton_iterations - before.newton_iterations,
            self.solver.stats.linear_iterations - before.linear_iterations,
            cuts,
        ));
        if k.is_multiple_of(scene.time.snapshot_every()) || k == steps {
            write_snapshot(
                self.out,
                self.problem,
                &self.x,
                self.time,
                &mut self.files,
                &mut self.outputs,
            )?;
        }
        Ok(())
    }

    /// The steady state at full power (at the end, or the ramp's end if later); its time.
    fn steady(&mut self) -> Result<f64, PelletError> {
        let t_steady = self.time.max(self.scene.power.ramp_time);
        if let Err(e) = self.solve(t_steady, None) {
            let what = "the steady state at full power".to_string();
            let e = located(self.problem, e, what, None, t_steady, &self.x, None);
            return Err(self.fail(e));
        }
        self.observe(t_steady, json!("steady"))?;
        self.outputs
            .push(("pellet.pvd".to_string(), pvd(&self.files).into_bytes()));
        self.outputs.push((
            "interface.pvd".to_string(),
            pvd(&interface_files(&self.files)).into_bytes(),
        ));
        Ok(t_steady)
    }

    /// Ends the run on the error `e`: writes what was computed (the snapshots, the history,
    /// the located failure, `"status": "failed"` or `"interrupted"`) and returns `e` (or,
    /// when those outputs cannot be written, an error saying so too).
    fn fail(&mut self, e: PelletError) -> PelletError {
        let physics = match &e {
            PelletError::Physics(p) => Some(p),
            PelletError::SolveFailed { source, .. } => Some(source.as_ref()),
            _ => None,
        };
        let newton = match physics {
            Some(PhysicsError::Newton(f)) => Some(f),
            _ => None,
        };
        let history = newton.map_or(Vec::new(), |f| f.residual_history.clone());
        let located = match &e {
            PelletError::SolveFailed {
                solve,
                step,
                time,
                block,
                blocks,
                source,
            } => json!({
                "solve": solve,
                "step": step,
                "time": time,
                "reason": newton.map_or_else(|| source.to_string(), |f| format!("{:?}", f.reason)),
                "block": block,
                "blocks": blocks.iter().map(|(n, v)| (n.to_string(), json!(v))).collect::<serde_json::Map<_, _>>(),
            }),
            _ => Value::Null,
        };
        let status = if matches!(e, PelletError::Interrupted { .. }) {
            "interrupted"
        } else {
            "failed"
        };
        let files = &self.files;
        let report = json!({
            "scene": "pellet",
            "status": status,
            "error": e.to_string(),
            "failure": located,
            "residual_history": history,
            "warnings": self.watch.to_json(),
            "valid_steps": self.rows.len(),
            "history": history_json(self.scene, &self.rows),
            "vtu": files.iter().map(|(f, _)| f.clone()).collect::<Vec<_>>(),
            "scene_data": self.scene,
        });
        let mut outputs = std::mem::take(&mut self.outputs);
        outputs.push(("pellet.pvd".to_string(), pvd(files).into_bytes()));
        outputs.push((
            "interface.pvd".to_string(),
            pvd(&interface_files(files)).into_bytes(),
        ));
        outputs.push((
            "report.json".to_string(),
            serde_json::to_string_pretty(&report)
                .expect("JSON values serialise")
                .into_bytes(),
        ));
        match write_scene_outputs(self.out, outputs) {
            Ok(()) => e,
            Err(w) => PelletError::Invalid(format!("{e}; and the outputs of the failure: {w}")),
        }
    }
}

/// What the coupled run's report says besides the march's own state.
struct CoupledReport<'a> {
    scene: &'a PelletScene,
    file: Option<&'a FileGeometry>,
    /// The thermal and contact laws' names.
    names: (&'a str, &'a str),
    /// The exponential law's onset gap.
    onset: Option<f64>,
    relocation: &'a Arc<dyn RelocationModel>,
    choice: &'a SolverChoice,
    /// The solver's counts before the steady solve.
    transient_stats: ThermoMechStats,
    t_steady: f64,
    /// The set-up's seconds, and the run's start.
    seconds: (f64, Instant),
}

impl CoupledReport<'_> {
    /// The report of a march that reached its steady state.
    ///
    /// # Errors
    /// [`PelletError::Physics`] where the heat flow or the eigenstrain cannot be evaluated.
    fn json<TL: ConstraintLaw, ML: ConstraintLaw>(
        &self,
        march: &March<'_, TL, ML>,
    ) -> Result<Value, PelletError> {
        let (scene, problem, rows) = (self.scene, march.problem, &march.rows);
        let (onset, t_steady, x) = (self.onset, self.t_steady, &march.x);
        let bodies = problem.heat().bodies();
        let steady = summary(problem, x, march.centre);
        let heat_out = outer_heat_flow(problem, x)?;
        // Per unit length in 2D, over the segment in 3D.
        let length = if scene.model.geometry.is_plane() {
            1.0
        } else {
            scene.model.segment_height
        };
        let power_in = scene.power.at(t_steady) * length;
        let closure = contact_engaged(rows, onset);
        let last = rows.last().expect("the initial row").1;
        let peak = rows.iter().map(|r| r.1.peak_pressure).fold(0.0, f64::max);
        let stats = march.solver.stats;
        let mesh = |b: usize| {
            json!({
                "nodes": bodies[b].mesh.node_count(),
                "cells": bodies[b].mesh.cell_count(),
            })
        };
        Ok(json!({
            "scene": "pellet",
            "status": if march.watch.is_empty() { "ok" } else { "warnings" },
            // The model ranges the run left, each once (docs/models.md, section 3b).
            "warnings": march.watch.to_json(),
            "models": {
                "heat": true,
                "mechanics": true,
                "geometry": scene.model.geometry,
                "axial": scene.model.axial(),
                "contact_law": self.names.1,
                "gap_conductance": self.names.0,
                "plenum": "ideal gas, fixed moles",
                // The pellet's relocation model, and the burnup it sees (MWd/kgU).
                "relocation": self.relocation.name(),
                "burnup": scene.model.burnup,
                "contact_engaged": closure.is_some(),
                // The exponential law's onset gap xi (m), below which its pressure rises.
                "contact_onset_gap": onset,
            },
            "method": match march.solver.method { ThermoMechSolver::Newton => "newton", ThermoMechSolver::Jfnk(_) => "jfnk" },
            "solver_choice": {
                "asked": scene.solver.method.name(),
                "picked": self.choice.method.name(),
                "why": self.choice.reason,
                "fallback_to_newton": march.fallback,
            },
            "center_temperature": last.center,
            "gap": last.gap,
            // When contact engaged (the mean gap fell below xi, or the exact law's pressure
            // became positive); the key's name is kept for the scripts that read it.
            "gap_closure_time": closure,
            "peak_interface_pressure": peak,
            "plenum_pressure": last.plenum,
            "interface_pressure": last.interface_pressure,
            "history": history_json(scene, rows),
            // Uncovered slave area or skipped pairs of the coupling, named (none on these meshes).
            "coupling_warnings": problem.heat().tie()
                .coupling()
                .warnings
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>(),
            "steady": {
                "time": t_steady,
                "center_temperature": steady.center,
                "pellet_surface_temperature": steady.pellet_surface,
                "cladding_inner_temperature": steady.cladding_inner,
                "gap": steady.gap,
                "interface_pressure": steady.interface_pressure,
                "plenum_pressure": steady.plenum,
                "pellet_surface_displacement": steady.displacement,
                // The pellet's relocation strain across its axis (0 without relocation).
                "relocation_strain": problem.eigenstrain_at(0, t_steady)?.map_or(0.0, |e| e[0]),
                // The bodies' axial strains (null where the axial direction is held).
                "axial_strain": {
                    "pellet": problem.fields(x).axial_strain[0],
                    "cladding": problem.fields(x).axial_strain[1],
                },
                "power_in": power_in,
                "heat_out": heat_out,
                "relative_imbalance": (heat_out - power_in).abs() / power_in.max(f64::MIN_POSITIVE),
            },
            "solver": {
                "newton_iterations": stats.newton_iterations,
                "linear_iterations": stats.linear_iterations,
                "factorizations": stats.factorizations,
                "symbolic_analyses": stats.symbolic_analyses,
                "reused_preconditioners": stats.reused_preconditioners,
                "transient_newton_iterations": self.transient_stats.newton_iterations,
                "step_cuts": march.cuts_total,
                "seconds": {
                    "newton_total": stats.total_seconds,
                    "assembly": stats.assembly_seconds,
                    "linear": stats.linear_seconds,
                },
            },
            "mesh": {
                "file": self.file.map(|f| json!({
                    "path": scene.mesh.file.as_ref().map(|p| p.display().to_string()),
                    "pellet_radius": f.pellet_radius,
                    "cladding_inner_radius": f.inner_radius,
                    "cladding_outer_radius": f.outer_radius,
                    "height": f.height,
                    "pellet_volume": f.pellet_volume,
                    "land_area": f.land_area,
                    "end_voids": f.end_voids(),
                })),
                "refinement": scene.mesh.refinement,
                "pellet": mesh(0),
                "cladding": mesh(1),
                "interface_slave_nodes": problem.normal_gap().weights.len(),
                "unknowns": problem.dimension(),
            },
            "vtu": march.files.iter().map(|(f, _)| f.clone()).collect::<Vec<_>>(),
            "seconds": { "setup": self.seconds.0, "total": self.seconds.1.elapsed().as_secs_f64() },
            "scene_data": scene,
        }))
    }
}

/// When contact engaged, from the history: the exponential law's pressure rises where the
/// gap falls below `xi` (the smallest gap, not zero: the gap is not closed; an off-centre
/// pellet engages on its near side first); the exact law's (`onset` `None`) mean contact
/// pressure is positive (above a millionth of the gas pressure: the round-off of an inactive
/// node's pressure is far below it). From the initial state (an off-centre pellet touching
/// at once), or between two rows (interpolated in the exponential law's smallest gap).
fn contact_engaged(rows: &[Row], onset: Option<f64>) -> Option<f64> {
    let touches = |s: &Summary| match onset {
        Some(xi) => s.min_gap <= xi,
        None => s.contact_pressure > 1e-6 * s.plenum,
    };
    rows.iter().position(|r| touches(&r.1)).map(|i| {
        if i == 0 {
            return rows[0].0;
        }
        let (t0, s0, t1, s1) = (rows[i - 1].0, rows[i - 1].1, rows[i].0, rows[i].1);
        match onset {
            Some(xi) if s0.min_gap > s1.min_gap => {
                t0 + (t1 - t0) * (s0.min_gap - xi) / (s0.min_gap - s1.min_gap)
            }
            _ => t1,
        }
    })
}

/// The error of the failed solve `solve` (`step`, to time `time`; `transient` as
/// [`GapThermoMechanics::solve`]), with the block of equations holding the largest residual
/// at its last iterate `x`.
fn located<TL: ConstraintLaw, ML: ConstraintLaw>(
    problem: &GapThermoMechanics<TL, ML>,
    e: PhysicsError,
    solve: String,
    step: Option<usize>,
    time: f64,
    x: &[f64],
    transient: Option<(&[f64], f64)>,
) -> PelletError {
    // A block whose residual is not finite is the one named; else the largest.
    let blocks = problem.residual_blocks(x, time, transient).ok();
    let block = blocks.and_then(|b| {
        b.iter()
            .find(|(_, v)| !v.is_finite())
            .or_else(|| b.iter().max_by(|p, q| p.1.total_cmp(&q.1)))
            .map(|b| b.0)
    });
    PelletError::SolveFailed {
        solve,
        step,
        time,
        block,
        blocks: blocks.map_or(Vec::new(), |b| b.to_vec()),
        source: Box::new(e),
    }
}

/// The heat leaving through the cladding's outer surface (W/m): the reaction of its
/// prescribed temperatures, `sum over them of int k grad T . grad N_a` (the conduction rows
/// of the prescribed nodes, which the residual replaces by their conditions).
fn outer_heat_flow<TL: ConstraintLaw, ML: ConstraintLaw>(
    problem: &GapThermoMechanics<TL, ML>,
    x: &[f64],
) -> Result<f64, PelletError> {
    let cladding = &problem.heat().bodies()[1];
    let t = problem.fields(x).temperature[1];
    let k = Conductivity::Constant(cladding.material.conductivity);
    let (f, _) = assemble_conduction(cladding, &k, t, &problem.options().heat, None)?;
    let (nodes, _) = cladding.dirichlet_nodes();
    Ok(nodes.iter().map(|&n| -f[n as usize]).sum())
}

/// PNG plots of the history: temperatures, gap, pressures (none without the feature
/// `plots`).
#[cfg(not(feature = "plots"))]
fn history_plots(
    _: &[(f64, Summary, usize, usize, usize)],
) -> Result<Vec<(String, Vec<u8>)>, PelletError> {
    Ok(Vec::new())
}

/// PNG plots of the history: temperatures, gap, pressures.
#[cfg(feature = "plots")]
fn history_plots(
    rows: &[(f64, Summary, usize, usize, usize)],
) -> Result<Vec<(String, Vec<u8>)>, PelletError> {
    let curve = |name: &'static str, scale: f64, f: fn(&Summary) -> f64| Curve {
        name,
        points: rows.iter().map(|r| (r.0, scale * f(&r.1))).collect(),
    };
    let charts = [
        (
            "temperatures.png",
            Chart {
                title: "Pellet temperatures",
                x_label: "time (s)",
                y_label: "temperature (K)",
                curves: vec![
                    curve("centre", 1.0, |s| s.center),
                    curve("pellet surface", 1.0, |s| s.pellet_surface),
                    curve("cladding inner surface", 1.0, |s| s.cladding_inner),
                ],
            },
        ),
        (
            "gap.png",
            Chart {
                title: "Pellet-cladding gap",
                x_label: "time (s)",
                y_label: "gap (um)",
                curves: vec![
                    curve("mean gap", 1e6, |s| s.gap),
                    curve("smallest gap", 1e6, |s| s.min_gap),
                ],
            },
        ),
        (
            "pressures.png",
            Chart {
                title: "Pressures",
                x_label: "time (s)",
                y_label: "pressure (MPa)",
                curves: vec![
                    curve("interface pressure P_c (mean)", 1e-6, |s| {
                        s.interface_pressure
                    }),
                    curve("interface pressure (peak)", 1e-6, |s| s.peak_pressure),
                    curve("plenum pressure P_o", 1e-6, |s| s.plenum),
                ],
            },
        ),
    ];
    let mut out = Vec::new();
    for (name, chart) in charts {
        out.push((name.to_string(), line_chart_png(&chart)?));
    }
    Ok(out)
}

/// The interface files beside the bodies' `pellet_NNNN.vtu` files.
fn interface_files(files: &[(String, f64)]) -> Vec<(String, f64)> {
    files
        .iter()
        .map(|(n, t)| (n.replacen("pellet_", "interface_", 1), *t))
        .collect()
}

/// The history as arrays over the time steps.
fn history_json(scene: &PelletScene, rows: &[Row]) -> Value {
    let col = |f: &dyn Fn(&Summary) -> f64| rows.iter().map(|r| f(&r.1)).collect::<Vec<_>>();
    let mut history = json!({
        "time": rows.iter().map(|r| r.0).collect::<Vec<_>>(),
        "linear_power": rows.iter().map(|r| scene.power.at(r.0)).collect::<Vec<_>>(),
        "center_temperature": col(&|s| s.center),
        "pellet_surface_temperature": col(&|s| s.pellet_surface),
        "cladding_inner_temperature": col(&|s| s.cladding_inner),
        "gap": col(&|s| s.gap),
        "min_gap": col(&|s| s.min_gap),
        "interface_pressure": col(&|s| s.interface_pressure),
        "peak_interface_pressure": col(&|s| s.peak_pressure),
        "plenum_pressure": col(&|s| s.plenum),
        "pellet_surface_displacement": col(&|s| s.displacement),
        "newton_iterations": rows.iter().map(|r| r.2).collect::<Vec<_>>(),
        "linear_iterations": rows.iter().map(|r| r.3).collect::<Vec<_>>(),
        "step_cuts": rows.iter().map(|r| r.4).collect::<Vec<_>>(),
    });
    // A stack's lands, where it has them.
    if rows.first().is_some_and(|r| !r.1.land_min_gap.is_nan()) {
        history["land_min_gap"] = json!(col(&|s| s.land_min_gap));
        history["land_peak_contact_pressure"] = json!(col(&|s| s.land_peak_pressure));
    }
    history
}

/// The VTU files of the state `x` at `time`: the bodies (temperature, displacement vector,
/// von Mises stress) in `pellet_NNNN.vtu`, the interface (the pellet's surface: gap, heat
/// flux, contact and interface pressure) in `interface_NNNN.vtu`.
fn write_snapshot<TL: ConstraintLaw, ML: ConstraintLaw>(
    out: &Path,
    problem: &GapThermoMechanics<TL, ML>,
    x: &[f64],
    time: f64,
    files: &mut Vec<(String, f64)>,
    outputs: &mut Vec<(String, Vec<u8>)>,
) -> Result<(), PelletError> {
    let f = problem.fields(x);
    let elastic = problem.elastic_bodies();
    let mut von_mises = Vec::new();
    let mut displacement = Vec::new();
    for b in 0..2 {
        let u = f.displacement(b);
        let dim = elastic[b].components();
        von_mises.push(super::stress::stress_field(problem, &f, b, time)?.von_mises);
        displacement.push(
            u.chunks(dim)
                .flat_map(|c| [c[0], c[1], if dim == 3 { c[2] } else { 0.0 }])
                .collect::<Vec<f64>>(),
        );
    }
    let k = files.len();
    let name = format!("pellet_{k:04}.vtu");
    let pieces: Vec<VtuPiece> = (0..2)
        .map(|b| VtuPiece {
            mesh: &elastic[b].mesh,
            point_data: vec![
                ("temperature", f.temperature[b]),
                ("von_mises", &von_mises[b]),
            ],
        })
        .collect();
    let vectors = [(
        "displacement",
        displacement.iter().map(Vec::as_slice).collect::<Vec<_>>(),
    )];
    let text = vtu_string_with_vectors(&out.join(&name), &pieces, &vectors)?;
    outputs.push((name.clone(), text.into_bytes()));

    // The interface, one value per slave surface node (NaN off the coupling's rows).
    let surface = problem.heat().tie().interface().slave();
    let row_of = |node: usize| {
        problem
            .heat()
            .tie()
            .coupling()
            .slave_nodes
            .binary_search(&surface.node_tags()[node])
            .ok()
    };
    let gaps = problem.gaps(x);
    let (flux, pressure) = (f.flux(), f.contact_pressure());
    let per_node = |v: &dyn Fn(usize) -> f64| -> Vec<f64> {
        (0..surface.node_count())
            .map(|i| row_of(i).map_or(f64::NAN, v))
            .collect()
    };
    let fields = [
        ("gap", per_node(&|j| gaps[j])),
        ("heat_flux", per_node(&|j| flux[j])),
        ("contact_pressure", per_node(&|j| pressure[j])),
        (
            "interface_pressure",
            per_node(&|j| pressure[j] + f.gas_pressure),
        ),
    ];
    let cells: Vec<_> = (0..surface.face_count())
        .map(|i| {
            let face = surface.face(i);
            (face.element, face.nodes.to_vec())
        })
        .collect();
    let data: Vec<(&str, &[f64])> = fields.iter().map(|(n, v)| (*n, v.as_slice())).collect();
    let iname = format!("interface_{k:04}.vtu");
    let text = surface_vtu_string(&out.join(&iname), surface.coords(), &cells, &data)?;
    outputs.push((iname, text.into_bytes()));
    files.push((name, time));
    Ok(())
}
