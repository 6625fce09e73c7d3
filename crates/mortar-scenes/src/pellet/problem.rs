//! The coupled pellet's problem: the section's meshes (generated or a user's file), the
//! bodies with their conditions, the gap's options and plenum, and what a file or the model
//! adds (the gas on dishes and chamfers, a stack's lands, relocation).

use std::f64::consts::PI;
use std::sync::Arc;

use mortar_core::{CouplingOptions, ModelGeometry, SearchRadius, Tolerances};
use mortar_fem::mesh::{BoundaryFace, VolumeMesh};
use mortar_physics::elastic::{
    AxialForce, ComponentSet, ElasticBody, ElasticMaterial, ElasticOptions,
};
use mortar_physics::heat::{Conductivity, HeatBody, HeatMaterial, HeatOptions};
use mortar_physics::laws::{
    ConstraintLaw, ExponentialContact, GapConductance, GasConductivity, LawRegistry,
    MechanicalGapConductance, RelocationInput, RelocationModel,
};
use mortar_physics::thermomech::{
    GapThermoMechanics, GasPressure, Plenum, ThermoElasticBody, ThermoMechOptions,
};
use nalgebra::Vector3;

use super::file_mesh::{contains, FaceSet, FileGeometry};
use super::outputs::{mesh_area, nearest_node};
use super::{annulus_mesh, pellet_mesh, AxialModel, Geometry, PelletError, PelletScene};
use mortar::generate::{extrude_mesh, rectangle_mesh, CellShape};

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
pub(super) fn complementarity(scene: &PelletScene) -> f64 {
    let p = &scene.pellet;
    p.youngs_modulus / (p.radius * (1.0 + p.poisson_ratio) * (1.0 - 2.0 * p.poisson_ratio))
}

/// Builds the coupled problem of `scene` with the contact law `law` and the scene's thermal
/// law ([`thermal_law`]) (see [`run_coupled`](super::run_coupled)).
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
/// mesh file's geometry if it has one: the section's meshes, the bodies with their
/// conditions, the gap's options, the problem, and what the file or the model adds (the gas
/// on dishes and chamfers, a stack's lands, relocation).
pub(super) fn problem_of<TL: ConstraintLaw + Clone, ML: ConstraintLaw + Clone>(
    scene: &PelletScene,
    file: Option<&FileGeometry>,
    thermal: TL,
    contact: ML,
    relocation: &Arc<dyn RelocationModel>,
) -> Result<GapThermoMechanics<TL, ML>, PelletError> {
    let meshes = section_meshes(scene, file)?;
    let section = Section::new(scene, file);
    let (pellet_heat, pellet_elastic) = pellet_bodies(&section, &meshes)?;
    let (cladding_heat, cladding_elastic) = cladding_bodies(&section, &meshes)?;
    let slave_surface = pellet_heat
        .mesh
        .boundary_surface(|f| section.slave_face(f))?;
    let master_surface = cladding_heat
        .mesh
        .boundary_surface(|f| section.master_face(f))?;
    let (options, tolerances) = gap_options(&section, meshes.area)?;
    let coupling = CouplingOptions::default()
        .dual()
        .with_geometry(options.heat.geometry);
    let laws = (thermal.clone(), contact.clone());
    let (p, c) = (&scene.pellet, &scene.cladding);
    let problem = GapThermoMechanics::new(
        ThermoElasticBody {
            heat: pellet_heat,
            conductivity: Conductivity::InverseLinear {
                a: p.conductivity_a,
                b: p.conductivity_b,
            },
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

/// The section's meshes: the pellet's and the cladding's, the pellet's cross-section area
/// (the heat source is `q'(t) / area`) and the axial component (held on the end planes in 3D
/// and r-z; `usize::MAX` in 2D, where there is none).
struct SectionMeshes {
    pellet: VolumeMesh,
    cladding: VolumeMesh,
    area: f64,
    axial: usize,
}

/// The meshes of `scene`: the file's, or the generated section's (see [`SectionMeshes`]).
fn section_meshes(
    scene: &PelletScene,
    file: Option<&FileGeometry>,
) -> Result<SectionMeshes, PelletError> {
    let (p, c) = (&scene.pellet, &scene.cladding);
    let r = scene.mesh.refinement;
    let geometry = scene.model.geometry;
    let height = scene.model.segment_height;
    let (a, b) = (p.radius, c.inner_radius);
    let meshes = |pellet, cladding, area, axial| SectionMeshes {
        pellet,
        cladding,
        area,
        axial,
    };
    Ok(match (geometry, file) {
        (Geometry::Plane | Geometry::PlaneStrain, Some(f)) => meshes(
            f.pellet.clone(),
            f.cladding.clone(),
            f.pellet_volume,
            usize::MAX,
        ),
        // The user's section: the heat source is q'(t) over the mean cross-section
        // V_pellet / H, so that the segment produces q' H whatever its dishes.
        (Geometry::Axisymmetric, Some(f)) => meshes(
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
                meshes(
                    extrude_mesh(&pm, &levels, 1)?,
                    extrude_mesh(&cm, &levels, 1)?,
                    area,
                    2,
                )
            } else {
                meshes(pm, cm, area, usize::MAX)
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
            meshes(pm, cm, PI * a * a, 1)
        }
    })
}

/// Where a point or a face of the section lies: its end planes, its radius, the surfaces
/// (the file's groups, or the generated section's faces by position).
struct Section<'a> {
    scene: &'a PelletScene,
    file: Option<&'a FileGeometry>,
    geometry: Geometry,
    height: f64,
    /// The tolerance of a coordinate (m).
    tol: f64,
}

impl<'a> Section<'a> {
    fn new(scene: &'a PelletScene, file: Option<&'a FileGeometry>) -> Self {
        Self {
            scene,
            file,
            geometry: scene.model.geometry,
            height: scene.model.segment_height,
            tol: 1e-9 * scene.cladding.outer_radius,
        }
    }

    /// The axial coordinate, in r-z and 3D.
    fn end_coordinate(&self, x: &Vector3<f64>) -> Option<f64> {
        match self.geometry {
            Geometry::ThreeD => Some(x.z),
            Geometry::Axisymmetric => Some(x.y),
            Geometry::Plane | Geometry::PlaneStrain => None,
        }
    }

    /// A face not on an end plane.
    fn lateral(&self, f: &BoundaryFace) -> bool {
        self.end_coordinate(&f.centroid)
            .is_none_or(|z| z > self.tol && z < self.height - self.tol)
    }

    /// The distance from the axis: in the xy plane, or x in r-z.
    fn radius(geometry: Geometry, x: &Vector3<f64>) -> f64 {
        match geometry {
            Geometry::Axisymmetric => x.x,
            _ => x.xy().norm(),
        }
    }

    /// The middle of the cladding's wall.
    fn mid(&self) -> f64 {
        0.5 * (self.scene.cladding.inner_radius + self.scene.cladding.outer_radius)
    }

    /// The cladding's outer surface (the coolant's).
    fn coolant(&self, f: &BoundaryFace) -> bool {
        match self.file {
            Some(g) => contains(&g.cladding_outer, f),
            None => Self::radius(self.geometry, &f.centroid) > self.mid() && self.lateral(f),
        }
    }

    /// The pellet's lateral surface (the gap's slave side).
    fn slave_face(&self, f: &BoundaryFace) -> bool {
        match self.file {
            Some(g) => contains(&g.pellet_outer, f),
            None => {
                Self::radius(self.geometry, &f.centroid) > 0.5 * self.scene.pellet.radius
                    && self.lateral(f)
            }
        }
    }

    /// The cladding's inner surface (the gap's master side).
    fn master_face(&self, f: &BoundaryFace) -> bool {
        match self.file {
            Some(g) => contains(&g.cladding_inner, f),
            None => Self::radius(self.geometry, &f.centroid) < self.mid() && self.lateral(f),
        }
    }

    /// The nodes on the line through (x, y) along z (the one node there in 2D).
    fn at(&self, mesh: &VolumeMesh, x: [f64; 2]) -> Vec<u32> {
        let xy = nalgebra::Vector2::new(x[0], x[1]);
        (0..mesh.node_count() as u32)
            .filter(|&i| (mesh.coords()[i as usize].xy() - xy).norm() < self.tol)
            .collect()
    }

    /// In 3D and r-z: no axial displacement on the bottom plane (symmetry), nor on the top
    /// one in plane strain (free axial expansion: the top is the axial unknown's).
    fn ends(&self, body: ElasticBody, axial: usize) -> Result<ElasticBody, PelletError> {
        if axial == usize::MAX {
            return Ok(body);
        }
        let free_ends = self.scene.model.axial() == AxialModel::Generalized;
        let held = |f: &BoundaryFace| {
            self.end_coordinate(&f.centroid)
                .is_some_and(|z| z <= self.tol || (!free_ends && z >= self.height - self.tol))
        };
        Ok(body.with_dirichlet_where(held, ComponentSet::One(axial), zero)?)
    }
}

/// The zero displacement of a held node.
fn zero(_: &Vector3<f64>) -> Vector3<f64> {
    Vector3::zeros()
}

/// The pellet's heat body (its source `q'(t) / area`) and elastic body (held on its axis in
/// r-z, against rigid motion in 2D and 3D, and at its ends as [`Section::ends`] says).
fn pellet_bodies(
    section: &Section,
    meshes: &SectionMeshes,
) -> Result<(HeatBody, ElasticBody), PelletError> {
    let (scene, file, tol) = (section.scene, section.file, section.tol);
    let (p, mesh) = (&scene.pellet, &meshes.pellet);
    let k_pellet = Conductivity::InverseLinear {
        a: p.conductivity_a,
        b: p.conductivity_b,
    };
    let power = scene.power;
    let area = meshes.area;
    let heat = HeatBody::new(
        "pellet",
        mesh.clone(),
        HeatMaterial::new(
            k_pellet.at(scene.cladding.outer_temperature).0,
            p.heat_capacity,
        ),
    )
    .with_source(move |_x, t| power.at(t) / area);
    let elastic = ElasticBody::new(
        "pellet",
        mesh.clone(),
        ElasticMaterial::new(p.youngs_modulus, p.poisson_ratio)
            .with_expansion(p.thermal_expansion, scene.model.reference_temperature),
    );
    let elastic = if section.geometry == Geometry::Axisymmetric {
        // u_r = 0 on the axis.
        let axis = (0..mesh.node_count() as u32)
            .filter(|&i| mesh.coords()[i as usize].x.abs() < tol)
            .collect();
        elastic.with_dirichlet_nodes(axis, ComponentSet::One(0), zero)
    } else {
        // Rigid motions: the axis held in x and y, the line through (a, 0) held in y; the
        // exact field is radial, so none of them loads the body. A file's pellet: the node
        // nearest the axis and the lateral surface's node furthest along x.
        let (centre, east) = match file {
            Some(f) => (
                vec![nearest_node(mesh, Vector3::zeros()) as u32],
                vec![extreme_node(mesh, &f.pellet_outer, |x| x.x)?],
            ),
            None => (
                section.at(mesh, [0.0, 0.0]),
                section.at(mesh, [p.radius, 0.0]),
            ),
        };
        elastic
            .with_dirichlet_nodes(centre.clone(), ComponentSet::One(0), zero)
            .with_dirichlet_nodes(centre, ComponentSet::One(1), zero)
            .with_dirichlet_nodes(east, ComponentSet::One(1), zero)
    };
    Ok((heat, section.ends(elastic, meshes.axial)?))
}

/// The cladding's heat body (its outer temperature prescribed) and elastic body (the coolant
/// pressing on its outside; held against rigid motion in 2D and 3D, and at its ends as
/// [`Section::ends`] says).
fn cladding_bodies(
    section: &Section,
    meshes: &SectionMeshes,
) -> Result<(HeatBody, ElasticBody), PelletError> {
    let (scene, file, geometry) = (section.scene, section.file, section.geometry);
    let (c, mesh) = (&scene.cladding, &meshes.cladding);
    let t_co = c.outer_temperature;
    let heat = HeatBody::new(
        "cladding",
        mesh.clone(),
        HeatMaterial::new(c.conductivity, c.heat_capacity),
    )
    .with_dirichlet_where(|f| section.coolant(f), move |_x, _t| t_co)?;
    let p_cool = c.coolant_pressure;
    let elastic = ElasticBody::new(
        "cladding",
        mesh.clone(),
        ElasticMaterial::new(c.youngs_modulus, c.poisson_ratio)
            .with_expansion(c.thermal_expansion, scene.model.reference_temperature),
    )
    .with_traction_where(
        |f| section.coolant(f),
        move |x| {
            // The coolant presses along the inward radius.
            let r = Section::radius(geometry, x);
            match geometry {
                Geometry::Axisymmetric => Vector3::new(-p_cool, 0.0, 0.0),
                _ => Vector3::new(-p_cool * x.x / r, -p_cool * x.y / r, 0.0),
            }
        },
    )?;
    let elastic = if geometry == Geometry::Axisymmetric {
        elastic
    } else {
        // Rigid motions: the inner lines on the axes held in their tangential direction (a
        // file's: the inner surface's nodes furthest along +x, -x and +y).
        let b = c.inner_radius;
        let (e, w, n) = match file {
            Some(f) => {
                let extreme = |along: fn(&Vector3<f64>) -> f64| {
                    extreme_node(mesh, &f.cladding_inner, along).map(|n| vec![n])
                };
                (extreme(|x| x.x)?, extreme(|x| -x.x)?, extreme(|x| x.y)?)
            }
            None => (
                section.at(mesh, [b, 0.0]),
                section.at(mesh, [-b, 0.0]),
                section.at(mesh, [0.0, b]),
            ),
        };
        elastic
            .with_dirichlet_nodes([e, w].concat(), ComponentSet::One(1), zero)
            .with_dirichlet_nodes(n, ComponentSet::One(0), zero)
    };
    Ok((heat, section.ends(elastic, meshes.axial)?))
}

/// The gap's options (the r-z measure where it applies, the design gap of a generated
/// section, the plenum, the units, the axial forces of free axial expansion) and the search
/// tolerances (twice the widest gap).
fn gap_options(
    section: &Section,
    area: f64,
) -> Result<(ThermoMechOptions, Tolerances), PelletError> {
    let (scene, file) = (section.scene, section.file);
    let (p, c) = (&scene.pellet, &scene.cladding);
    let gap = c.inner_radius - p.radius;
    let widest = file.map_or(gap, |f| f.widest_gap.max(gap));
    let tolerances = Tolerances {
        search_radius: SearchRadius::Distance(2.0 * widest),
        ..Tolerances::default()
    };
    let pl = &scene.plenum;
    // Per unit length in 2D; the segment's share of the plenum in 3D and r-z.
    let length = if section.geometry.is_plane() {
        1.0
    } else {
        section.height
    };
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
    let model = if section.geometry == Geometry::Axisymmetric {
        ModelGeometry::Axisymmetric
    } else {
        ModelGeometry::Cartesian
    };
    let free_ends = scene.model.axial() == AxialModel::Generalized;
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
    Ok((options, tolerances))
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
