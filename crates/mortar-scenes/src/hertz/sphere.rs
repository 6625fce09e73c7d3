//! The 3D Hertz contact: an elastic sphere pressed onto an elastic block, checked against the
//! closed form of Johnson, *Contact Mechanics* (Cambridge University Press, 1985), sec. 4.2
//! (see [`HertzPoint`]).
//!
//! The symmetric quarter model: the lower octant of the sphere, radius `R`, centre `(0, 0, R)`
//! ([`ball_octant_mesh`], the slave body), touches the block `[0, W] x [0, W] x [-H, 0]`
//! ([`grid_box_mesh`] on [`graded_points`], the master body) at the origin. Both are Hex8,
//! refined towards the origin. Conditions: `u_x = 0` on `x = 0` and `u_y = 0` on `y = 0` for
//! both bodies (the planes of symmetry); the sphere's flat equator `z = R` is moved down by the
//! approach `d` (`u_z = -d`) and is free to slide (the mid-plane of a sphere squeezed between
//! two blocks, by symmetry); `u_z = 0` on the block's bottom `z = -H`. Frictionless mortar
//! contact with dual multipliers, segment-based integration and the exact complementarity law
//! (semi-smooth Newton, [`solve_contact`]) with automatic `c`, on the sphere's faces within
//! `contact_zone R` of the axis (the slave surface) against the block's top (the master
//! surface).
//!
//! The load `P` is four times the vertical contact force of the quarter model,
//! `F = -sum_j w_j p_j n_j . e_z`, which equilibrium makes equal to the reactions at the
//! block's bottom and at the sphere's equator (both measured, [`HertzSphereRun::reaction_bottom`]);
//! the solver's normal force `sum_j w_j p_j` exceeds it by the tilt of the normals, about
//! `a^2 / 5 R^2` for the ellipsoidal pressure.
//!
//! Two comparisons. At the imposed approach `d` ([`HertzSphereRun::at_approach`]):
//! `a = sqrt(R d)`, `p0 = 2 E* a / (pi R)`, `P = 4 E* a^3 / (3 R)`; Hertz's `d` is the approach
//! of points far from the contact in two half-spaces, while here it is the approach of the
//! sphere's equator and the block's bottom, so the bodies' finite size enters: their own
//! compliance away from the contact (the sphere narrows towards its pole; the block is held
//! at a finite depth) changes `P` for a given `d` at first order in `a / R`. At the measured
//! load `P` ([`HertzSphereRun::at_load`]): `a = (3 P R / (4 E*))^(1/3)`,
//! `p0 = 3 P / (2 pi a^2)`, which sees the contact zone only, as the 2D scene's comparison does.
//!
//! Measured at `d = 0.01 R` (`a = 0.1 R`), steel on steel: at the default mesh (14 cells per
//! direction, `a / 5` at the pole) the peak pressure is 1.8 % above `p0` at `d` and 1.0 %
//! above it at `P`, the contact radius a quarter of an element off `a` (both), in 3 Newton
//! steps; `P` is 2.3 % above the closed form's at `d`. Over 10, 12, 14, 16, 20 and 24 cells
//! the peak is 1.8, 1.2, 1.8, 1.4, 1.4, 1.4 % above `p0` at `d` and 1.4, -0.3, 1.0, 0.4, 0.4,
//! 0.5 % at `P` (the 2D scene's peak converges to 0.35 % above at this `a / R`), while `P` is
//! 1.3, 4.6, 2.3, 3.3, 3.1, 2.9 % above the closed form's at `d`: the edge of the discrete
//! contact zone (elements of `0.2 a` to `0.45 a` there) shifts `P` from mesh to mesh, and `P`
//! settles near 3 % above, the stiffness of the finite bodies (and of Hex8) at the approach.
//! The block's size enters it: at 14 cells, `W = 4 R`, `8 R`, `16 R` give 4.1, 2.3, 1.9 %
//! (and the peak at `d` 2.2, 1.8, 1.6 %). The node in contact farthest from the axis and the
//! next one are closer together than an element in 3D, and the discrete contact zone reaches
//! up to a quarter of an element beyond `a`: they do not always bracket `a`
//! ([`HertzSphereRun::contact_radius`]), while their midpoint stays within an element of it.

use std::time::Instant;

use mortar_core::CouplingOptions;
use mortar_fem::mesh::BoundaryFace;
use mortar_physics::contact::{ContactOptions, ContactSolution, ContactStep};
use mortar_physics::elastic::ElasticMaterial;
use mortar_physics::PhysicsError;
use nalgebra::Vector3;

use super::{
    contact_modulus, first_cell, near_to, vertical_force, HalfWidth, HertzBodies, HertzProblem,
};
use crate::file::contact::Component;
use crate::file::contact_files::{ContactSceneFiles, SceneBody};
use crate::file::SceneError;
use mortar::generate::{ball_octant_mesh, graded_points, grid_box_mesh, CellShape};
#[cfg(doc)]
use mortar_physics::contact::solve_contact;

/// The closed form of the 3D Hertz contact (Johnson 1985, sec. 4.2): a sphere of radius `R`
/// and a plane (or two spheres, `1 / R = 1 / R1 + 1 / R2`) pressed together touch over the
/// disc `r <= a` with the pressure `p(r) = p0 sqrt(1 - r^2 / a^2)`, where for the approach `d`
/// of distant points `a = sqrt(R d)`, `p0 = 2 E* a / (pi R)` and the load
/// `P = 4 E* a^3 / (3 R)`; equivalently, for the load `P`, `a = (3 P R / (4 E*))^(1/3)`,
/// `p0 = 3 P / (2 pi a^2)` and `d = a^2 / R`. `1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzPoint {
    /// The radius `R` of the sphere (m).
    pub radius: f64,
    /// The contact modulus `E*` (Pa).
    pub contact_modulus: f64,
}

/// The closed-form contact of [`HertzPoint`] at one load: the four related values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzContact {
    /// The contact radius `a` (m).
    pub radius: f64,
    /// The peak pressure `p0` (Pa), at the centre.
    pub peak: f64,
    /// The load `P` (N).
    pub load: f64,
    /// The approach `d` of distant points (m).
    pub approach: f64,
}

impl HertzContact {
    /// The pressure `p0 sqrt(1 - r^2 / a^2)` at the distance `r` from the centre (zero for
    /// `r >= a`).
    pub fn pressure(&self, r: f64) -> f64 {
        if r.abs() >= self.radius {
            0.0
        } else {
            self.peak * (1.0 - (r / self.radius).powi(2)).sqrt()
        }
    }
}

impl HertzPoint {
    /// The contact of a sphere of radius `radius` and material `sphere` with a flat body of
    /// material `block`.
    pub fn new(radius: f64, sphere: &ElasticMaterial, block: &ElasticMaterial) -> Self {
        Self {
            radius,
            contact_modulus: contact_modulus(sphere, block),
        }
    }

    /// The contact of contact radius `a`.
    fn with_radius(&self, a: f64) -> HertzContact {
        let (r, e) = (self.radius, self.contact_modulus);
        HertzContact {
            radius: a,
            peak: 2.0 * e * a / (std::f64::consts::PI * r),
            load: 4.0 * e * a.powi(3) / (3.0 * r),
            approach: a * a / r,
        }
    }

    /// The contact at the approach `d` (m): `a = sqrt(R d)`, `p0 = 2 E* a / (pi R)`,
    /// `P = 4 E* a^3 / (3 R)`.
    pub fn at_approach(&self, d: f64) -> HertzContact {
        self.with_radius((self.radius * d).sqrt())
    }

    /// The contact at the load `P` (N): `a = (3 P R / (4 E*))^(1/3)`, `p0 = 3 P / (2 pi a^2)`,
    /// `d = a^2 / R`.
    pub fn at_load(&self, load: f64) -> HertzContact {
        self.with_radius((3.0 * load * self.radius / (4.0 * self.contact_modulus)).cbrt())
    }
}

/// A 3D Hertz scene: geometry, materials, meshes and solver settings (see the
/// [module](self) documentation).
#[derive(Debug, Clone)]
pub struct HertzSphereScene {
    /// The sphere's radius `R` (m).
    pub radius: f64,
    /// The sphere's material.
    pub sphere: ElasticMaterial,
    /// The block's material.
    pub block: ElasticMaterial,
    /// The block's width and depth over the radius: `W = H = block_size R`.
    pub block_size: f64,
    /// The approach `d` (m): the sphere's equator moves by `-d` in `z`.
    pub approach: f64,
    /// The sphere octant's cells per direction (see [`ball_octant_mesh`]).
    pub cells: usize,
    /// The sphere octant's grading (see [`ball_octant_mesh`]).
    pub grading: f64,
    /// The block's grading, in `x` and `y` from `0` and in `z` from `z = 0` (see
    /// [`graded_points`]).
    pub block_grading: f64,
    /// The block's first cell (at the origin) over the sphere's first cell at the pole,
    /// about; the block's cell count per direction follows, proportional to `cells` (see
    /// [`block_cell_count`](Self::block_cell_count)).
    pub block_cell_ratio: f64,
    /// The block's cells per direction, if given; otherwise from `block_cell_ratio`.
    pub block_cells: Option<usize>,
    /// The slave surface: the sphere's faces with every node within `contact_zone R` of the
    /// axis.
    pub contact_zone: f64,
    /// The mortar coupling (default: dual multipliers, segment-based integration); full
    /// coverage of the slave surface is required whatever this says.
    pub coupling: CouplingOptions,
    /// The contact solve.
    pub contact: ContactOptions,
}

impl Default for HertzSphereScene {
    /// The scene at [`DEFAULT_SPHERE_CELLS`].
    fn default() -> Self {
        Self::new(DEFAULT_SPHERE_CELLS)
    }
}

/// The approach of [`HertzSphereScene::new`] over the radius: the closed form's
/// `a = sqrt(R d) = 0.1 R`.
pub const DEFAULT_SPHERE_APPROACH: f64 = 0.01;

/// The default mesh: the sphere octant's cells per direction (first cell at the pole
/// `0.020 R`, `a / 5`; `0.032 R` where the contact zone ends).
pub const DEFAULT_SPHERE_CELLS: usize = 14;

impl HertzSphereScene {
    /// The default scene at `cells` cells per direction of the sphere octant: `R = 1`, both
    /// bodies `E = 200 GPa`, `nu = 0.3`, `W = H = 8 R`, the approach
    /// [`DEFAULT_SPHERE_APPROACH`] (`a = 0.1 R` by the closed form), the octant graded by 10,
    /// the block by 100 with about the octant's cell at the origin, the slave surface out to
    /// `0.3 R`, one load step.
    pub fn new(cells: usize) -> Self {
        Self {
            radius: 1.0,
            sphere: ElasticMaterial::new(200e9, 0.3),
            block: ElasticMaterial::new(200e9, 0.3),
            block_size: 8.0,
            approach: DEFAULT_SPHERE_APPROACH,
            cells,
            grading: 10.0,
            block_grading: 100.0,
            block_cell_ratio: 1.0,
            block_cells: None,
            contact_zone: 0.3,
            coupling: CouplingOptions::default().dual(),
            contact: ContactOptions::default(),
        }
    }

    /// The closed form for this scene's radius and materials.
    pub fn closed_form(&self) -> HertzPoint {
        HertzPoint::new(self.radius, &self.sphere, &self.block)
    }

    /// The sphere's first cell at the pole, `R f(1 / n)` (see [`ball_octant_mesh`]), about
    /// `R ln(g) / ((g - 1) n)`.
    ///
    /// # Panics
    /// If `cells` is zero or `grading` is not finite and at least 1.
    pub fn pole_cell(&self) -> f64 {
        graded_points(0.0, self.radius, self.cells, self.grading)[1]
    }

    /// The block's cells per direction: the field `block_cells` if given, otherwise such
    /// that its first cell `W ln(G) / ((G - 1) n_b)` is about `block_cell_ratio` times the
    /// sphere's `R ln(g) / ((g - 1) n)` (to first order in `1 / n`, as the 2D scene's).
    pub fn block_cell_count(&self) -> usize {
        if let Some(n) = self.block_cells {
            return n.max(1);
        }
        let w = self.block_size * self.radius;
        let pole = first_cell(self.radius, self.cells as f64, self.grading);
        let n = first_cell(w, 1.0, self.block_grading) / (self.block_cell_ratio * pole);
        (n.round() as usize).max(1)
    }

    /// The two bodies, their stiffness matrices, loads and Dirichlet data, the tie and the
    /// normal gap of the scene, and the law with automatic `c`.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for bad geometry; the errors of mesh generation, of the
    /// coupling (with full coverage of the slave surface required) and of the assembly.
    pub fn build(&self) -> Result<HertzProblem, PhysicsError> {
        self.problem()
    }

    /// The scene as a scene file and its meshes (`sphere.msh`, `block.msh`; groups
    /// `sphere_x0`, `sphere_y0`, `sphere_top`, `sphere_contact`, `block_x0`, `block_y0`,
    /// `block_bottom`, `block_top`): what `mortar run --scene hertz3d` runs and writes.
    ///
    /// # Errors
    /// The errors of [`build`](Self::build)'s meshing, and [`SceneError::Other`] for a
    /// coupling a scene file cannot state.
    pub fn scene_files(&self) -> Result<ContactSceneFiles, SceneError> {
        self.files()
    }

    /// Builds and solves the scene and compares it with the closed form.
    ///
    /// # Errors
    /// The errors of [`build`](Self::build) and of [`solve_contact`].
    pub fn run(&self) -> Result<HertzSphereRun, PhysicsError> {
        self.run_on(None)
    }

    /// [`run`](Self::run) with the Newton systems solved by `backend` when given (see
    /// [`HertzProblem::solve_on`]).
    ///
    /// # Errors
    /// As [`run`](Self::run).
    pub fn run_on(
        &self,
        backend: Option<&dyn mortar_fem::linalg::SparseSolver>,
    ) -> Result<HertzSphereRun, PhysicsError> {
        let t0 = Instant::now();
        let problem = self.build()?;
        let seconds_build = t0.elapsed().as_secs_f64();
        let sol = problem.solve_on(&self.contact, backend)?;
        Ok(self.evaluate(&problem, &sol, [seconds_build, t0.elapsed().as_secs_f64()]))
    }

    /// The comparison with the closed form of the solution `sol` of this scene's `problem`
    /// (built by [`build`](Self::build), or read back from its [scene
    /// file](Self::scene_files)); `seconds` are reported as the build's and the run's time.
    pub fn evaluate(
        &self,
        problem: &HertzProblem,
        sol: &ContactSolution,
        [seconds_build, seconds]: [f64; 2],
    ) -> HertzSphereRun {
        let r = self.radius;
        let h = self.block_size * r;
        let near = near_to(r);
        let [slave, master] = &problem.bodies;
        let (tie, gap) = (&problem.tie, &problem.gap);

        let reaction_bottom = problem.reaction(sol, 1, 2, |x| near(x.z, -h));
        let reaction_top = -problem.reaction(sol, 0, 2, |x| near(x.z, r));

        // The profile, by the distance from the axis.
        let cpl = tie.coupling();
        let coords = slave.mesh.coords();
        let mut nodes: Vec<SphereNode> = (0..sol.pressure.len())
            .map(|j| {
                let x = coords[tie.slave_nodes()[j] as usize];
                let n = cpl.slave_normals[j];
                SphereNode {
                    position: [x.x, x.y, x.z],
                    r: x.x.hypot(x.y),
                    pressure: sol.pressure[j],
                    weight: gap.weights[j],
                    normal: [n.x, n.y, n.z],
                }
            })
            .collect();
        nodes.sort_by(|a, b| {
            a.r.total_cmp(&b.r)
                .then(a.position[0].total_cmp(&b.position[0]))
        });
        let vertical_force =
            vertical_force(nodes.iter().map(|n| (n.weight, n.pressure, n.normal[2])));
        let load = 4.0 * vertical_force;
        let hertz = self.closed_form();
        let at_approach = hertz.at_approach(self.approach);
        let at_load = hertz.at_load(load);
        let profile: Vec<(f64, f64)> = nodes.iter().map(|n| (n.r, n.pressure)).collect();
        let contact_radius = HalfWidth::of_profile(&profile);
        // Along the symmetry line y = 0 (the nodes of one row of faces, by x).
        let axis: Vec<(f64, f64)> = nodes
            .iter()
            .filter(|n| n.position[1] == 0.0)
            .map(|n| (n.r, n.pressure))
            .collect();
        let contact_radius_axis = HalfWidth::of_profile(&axis);
        let spacing_at = |a: f64| {
            axis.windows(2)
                .find(|w| w[1].0 >= a)
                .map_or(f64::NAN, |w| w[1].0 - w[0].0)
        };
        let pole = nodes[0];
        let contact_cell = axis.get(1).map_or(f64::NAN, |n| n.0);
        let profile_l2 = (nodes
            .iter()
            .map(|n| n.weight * (n.pressure - at_load.pressure(n.r)).powi(2))
            .sum::<f64>()
            / (std::f64::consts::PI / 8.0))
            .sqrt()
            / (at_load.peak * at_load.radius);
        HertzSphereRun {
            cells: self.cells,
            block_cells: problem.block_cells,
            sphere_nodes: slave.mesh.node_count(),
            block_nodes: master.mesh.node_count(),
            unknowns: 3 * (slave.mesh.node_count() + master.mesh.node_count()) + nodes.len(),
            slave_nodes: nodes.len(),
            active: nodes.iter().filter(|n| n.pressure > 0.0).count(),
            contact_cell,
            edge_cell: spacing_at(at_approach.radius),
            edge_cell_at_load: spacing_at(at_load.radius),
            load,
            force: sol.force,
            reaction_bottom,
            reaction_top,
            contact_radius,
            contact_radius_axis,
            peak: pole.pressure,
            at_approach,
            at_load,
            profile_l2,
            complementarity: problem.law.parameter(),
            steps: sol.steps.clone(),
            seconds_build,
            seconds,
            profile: nodes,
        }
    }
}

impl HertzBodies for HertzSphereScene {
    const TITLE: &'static str = "3D Hertz contact: a sphere on a block (quarter model, Hex8)";
    const DIMENSION: usize = 3;

    /// The two bodies with their groups and conditions (see the [module](self)).
    fn bodies(&self) -> Result<[SceneBody; 2], PhysicsError> {
        let r = self.radius;
        if !(self.block_size > 1.0 && self.contact_zone > 0.0 && self.contact_zone < 0.7) {
            return Err(PhysicsError::InvalidInput {
                body: "hertz sphere scene".into(),
                what: format!(
                    "block size {} (over the radius, above 1) or contact zone {} (a fraction \
                     of the radius, in (0, 0.7): the octant's cap around the pole)",
                    self.block_size, self.contact_zone
                ),
            });
        }
        let (w, h) = (self.block_size * r, self.block_size * r);
        let ball = ball_octant_mesh(r, [0.0, 0.0, r], self.cells, self.grading, 1)?;
        let nb = self.block_cell_count();
        let xs = graded_points(0.0, w, nb, self.block_grading);
        let mut zs = graded_points(0.0, -h, nb, self.block_grading);
        zs.reverse();
        let block = grid_box_mesh(&xs, &xs, &zs, CellShape::Tensor, 1_000_001)?;

        let near = near_to(r);
        // The slave surface: the sphere's faces near the pole. The gap grows to
        // r - sqrt(r^2 - zone^2) < zone at the zone's end: the search looks that far.
        let coords = ball.coords().to_vec();
        let zone = self.contact_zone * r;
        let centre = Vector3::new(0.0, 0.0, r);
        let on_cap = move |f: &BoundaryFace| {
            f.nodes.iter().all(|&n| {
                let x = coords[n as usize];
                ((x - centre).norm() - r).abs() <= 1e-9 * r && x.x.hypot(x.y) <= zone
            })
        };
        let symmetric = |body: SceneBody| -> Result<SceneBody, SceneError> {
            Ok(body
                .group("x0", |f| near(f.centroid.x, 0.0))?
                .group("y0", |f| near(f.centroid.y, 0.0))?
                .hold("x0", Component::X, 0.0)
                .hold("y0", Component::Y, 0.0))
        };
        let scene = |e: SceneError| PhysicsError::InvalidInput {
            body: "hertz sphere scene".into(),
            what: e.to_string(),
        };
        let slave = symmetric(SceneBody::new("sphere", ball, self.sphere))
            .and_then(|b| b.group("top", |f| near(f.centroid.z, r)))
            .and_then(|b| b.group("contact", on_cap))
            .map_err(scene)?
            .hold("top", Component::Z, -self.approach);
        let master = symmetric(SceneBody::new("block", block, self.block))
            .and_then(|b| b.group("bottom", |f| near(f.centroid.z, -h)))
            .and_then(|b| b.group("top", |f| near(f.centroid.z, 0.0)))
            .map_err(scene)?
            .hold("bottom", Component::Z, 0.0);
        Ok([slave, master])
    }

    fn settings(&self) -> (f64, &CouplingOptions, &ContactOptions, usize) {
        let zone = self.contact_zone * self.radius;
        (zone, &self.coupling, &self.contact, self.block_cell_count())
    }
}

/// One slave interface node of the 3D solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereNode {
    /// Its position (reference configuration).
    pub position: [f64; 3],
    /// Its distance from the axis `x = y = 0`.
    pub r: f64,
    /// The contact pressure (Pa).
    pub pressure: f64,
    /// Its weight `w_j`, the row sum of D (m^2).
    pub weight: f64,
    /// Its averaged unit normal (outward from the sphere).
    pub normal: [f64; 3],
}

/// A solved 3D Hertz scene and its comparison with the closed form.
#[derive(Debug, Clone)]
pub struct HertzSphereRun {
    /// The sphere octant's cells per direction.
    pub cells: usize,
    /// The block's cells per direction.
    pub block_cells: usize,
    /// The sphere octant's nodes.
    pub sphere_nodes: usize,
    /// The block's nodes.
    pub block_nodes: usize,
    /// Unknowns of the saddle-point system before the Dirichlet values are eliminated: three
    /// displacements per node of both bodies and a pressure per slave interface node.
    pub unknowns: usize,
    /// Slave interface nodes.
    pub slave_nodes: usize,
    /// Slave interface nodes in contact (positive pressure).
    pub active: usize,
    /// The length of the slave face edge at the pole, along `y = 0`.
    pub contact_cell: f64,
    /// The length, in `r`, of the slave face edge along `y = 0` in which the closed form's
    /// contact radius at the approach ends: the element the contact radius is compared with.
    pub edge_cell: f64,
    /// The same at the closed form's contact radius at the computed load.
    pub edge_cell_at_load: f64,
    /// `P`: four times the vertical contact force of the quarter model (N).
    pub load: f64,
    /// The solver's normal contact force of the quarter model, `sum_j w_j p_j` (N).
    pub force: f64,
    /// The reaction at the block's bottom (upwards, N): the vertical contact force.
    pub reaction_bottom: f64,
    /// The force the sphere's equator carries (downwards, N): the vertical contact force.
    pub reaction_top: f64,
    /// The computed contact radius, over all slave nodes by their distance from the axis.
    pub contact_radius: HalfWidth,
    /// The computed contact radius along the symmetry line `y = 0` (the slave nodes on it,
    /// by `x`): the bracket of two neighbouring nodes, one element wide.
    pub contact_radius_axis: HalfWidth,
    /// The computed pressure at the pole.
    pub peak: f64,
    /// The closed form at the imposed approach `d`.
    pub at_approach: HertzContact,
    /// The closed form at the computed load `P`.
    pub at_load: HertzContact,
    /// The relative L2 error of the nodal pressures at the load `P`:
    /// `sqrt(sum_j w_j (p_j - p(r_j))^2) / ||p||`, `||p|| = p0 a sqrt(pi / 8)` the closed
    /// form's norm over the quarter of the contact disc.
    pub profile_l2: f64,
    /// The complementarity parameter `c` used (Pa/m).
    pub complementarity: f64,
    /// The load steps of the contact solve.
    pub steps: Vec<ContactStep>,
    /// Wall-clock seconds of meshing and assembly.
    pub seconds_build: f64,
    /// Wall-clock seconds of meshing, assembly and solve.
    pub seconds: f64,
    /// The slave interface nodes by their distance from the axis.
    pub profile: Vec<SphereNode>,
}

impl HertzSphereRun {
    /// `(p0_h - p0) / p0` against the closed form at the approach.
    pub fn peak_error_at_approach(&self) -> f64 {
        (self.peak - self.at_approach.peak) / self.at_approach.peak
    }

    /// `(p0_h - p0) / p0` against the closed form at the computed load.
    pub fn peak_error_at_load(&self) -> f64 {
        (self.peak - self.at_load.peak) / self.at_load.peak
    }

    /// `(P_h - P) / P` against the closed form's load at the approach.
    pub fn load_error_at_approach(&self) -> f64 {
        (self.load - self.at_approach.load) / self.at_approach.load
    }

    /// `(a_h - a) / a` with [`HalfWidth::estimate`] over all slave nodes, against the closed
    /// form at the approach.
    pub fn radius_error_at_approach(&self) -> f64 {
        (self.contact_radius.estimate - self.at_approach.radius) / self.at_approach.radius
    }

    /// `(a_h - a) / a` with [`HalfWidth::estimate`] over all slave nodes, against the closed
    /// form at the computed load.
    pub fn radius_error_at_load(&self) -> f64 {
        (self.contact_radius.estimate - self.at_load.radius) / self.at_load.radius
    }

    /// The vertical force of the quarter model, `P / 4`.
    pub fn vertical_force(&self) -> f64 {
        0.25 * self.load
    }

    /// The largest relative difference between the vertical contact force and the two
    /// reactions (zero up to round-off: equilibrium).
    pub fn equilibrium_error(&self) -> f64 {
        let f = self.vertical_force();
        ((self.reaction_bottom - f).abs()).max((self.reaction_top - f).abs()) / f
    }

    /// The most Newton steps of a load step.
    pub fn max_newton_steps(&self) -> usize {
        self.steps.iter().map(|s| s.newton_steps).max().unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_closed_form_at_the_approach_and_at_the_load_agree() {
        let steel = ElasticMaterial::new(200e9, 0.3);
        let hertz = HertzPoint::new(0.5, &steel, &steel);
        assert!((hertz.contact_modulus - 200e9 / (2.0 * 0.91)).abs() < 1e-3);
        let at_d = hertz.at_approach(4e-3);
        assert!((at_d.radius - (0.5f64 * 4e-3).sqrt()).abs() < 1e-15);
        let at_p = hertz.at_load(at_d.load);
        for (a, b) in [
            (at_d.radius, at_p.radius),
            (at_d.peak, at_p.peak),
            (at_d.approach, at_p.approach),
        ] {
            assert!((a - b).abs() <= 1e-12 * a.abs(), "{a} {b}");
        }
        // P = integral of the pressure over the disc: 2 pi p0 a^2 / 3.
        let total = 2.0 * std::f64::consts::PI * at_d.peak * at_d.radius.powi(2) / 3.0;
        assert!((total - at_d.load).abs() < 1e-12 * total);
        assert_eq!(at_d.pressure(at_d.radius), 0.0);
        assert_eq!(at_d.pressure(0.0), at_d.peak);
    }
}
