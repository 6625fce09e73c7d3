//! The 2D Hertz contact (plane strain): an elastic cylinder pressed onto an elastic block,
//! checked against the closed form of Johnson, *Contact Mechanics* (Cambridge University
//! Press, 1985), sec. 4.3 and 5.6 (see [`HertzLine`]).
//!
//! The symmetric half model: the lower-right quarter of the cylinder, radius `R`, centre
//! `(0, R)` ([`quarter_disc_mesh`], the slave body), touches the block `[0, W] x [-H, 0]`
//! ([`grid_rectangle_mesh`] on [`graded_points`], the master body) at the origin. Both are
//! refined towards the origin. Conditions: `u_x = 0` on `x = 0` for both bodies (the plane of
//! symmetry); the cylinder's flat top `y = R` is moved down by the approach `d`
//! (`u_y = -d`) and is free to slide (`u_x` free: the mid-plane of a cylinder squeezed between
//! two blocks, by symmetry); `u_y = 0` on the block's bottom `y = -H`. Frictionless mortar
//! contact with dual multipliers, segment-based integration and the exact complementarity
//! law (semi-smooth Newton, [`solve_contact`]) with automatic `c`, on the arc faces with
//! `x <= contact_zone R` (the slave surface) against the block's top (the master surface).
//!
//! The load per unit length `P` is twice the vertical contact force of the half model,
//! `F = -sum_j w_j p_j n_j . e_y` (`w_j` the row sums of D, `n_j` the slave's nodal normals),
//! which equilibrium makes equal to the reactions at the block's bottom and at the cylinder's
//! top (both measured, [`HertzRun::reaction_bottom`]). It differs from the solver's
//! `force = sum_j w_j p_j`, the normal force, by the tilt of the normals (about `a^2 / 8 R^2`,
//! 1.2e-3 at `a = 0.1 R`): Hertz's `P` is the load, the vertical resultant. The half-width,
//! the peak and the profile are compared with the closed form at the computed `P`.
//!
//! The closed form idealises both bodies as half-spaces and the cylinder as a parabola; at
//! `a = 0.1 R` the computed peak converges to 0.35 % above it (0.05 % at `a = 0.046 R`: an
//! `(a / R)^2` effect; unchanged with a block twice as large), which floors the profile's L2
//! error near 1e-2 from about 100 arc cells on (the default study stops at 96).

use std::time::Instant;

use mortar_core::CouplingOptions;
use mortar_fem::mesh::BoundaryFace;
use mortar_physics::contact::{ContactOptions, ContactSolution, ContactStep};
use mortar_physics::elastic::ElasticMaterial;
use mortar_physics::PhysicsError;

use super::{
    contact_modulus, first_cell, near_to, vertical_force, HalfWidth, HertzBodies, HertzProblem,
};
use crate::file::contact::Component;
use crate::file::contact_files::{ContactSceneFiles, SceneBody};
use crate::file::SceneError;
use mortar::generate::{
    graded_points, grid_rectangle_mesh, onto_sphere, quarter_disc_mesh, second_order_mesh,
    CellShape, SecondOrder,
};
#[cfg(doc)]
use mortar_physics::contact::solve_contact;

/// The closed form of the 2D Hertz contact (Johnson 1985, sec. 4.3 and 5.6): two cylinders
/// (here a cylinder of radius `R` and a plane) pressed together by a force `P` per unit length
/// touch over `|x| <= a` with the elliptical pressure `p(x) = p0 sqrt(1 - x^2 / a^2)`,
/// `a = sqrt(4 P R / (pi E*))`, `p0 = 2 P / (pi a)`, `1 / E* = (1 - nu1^2) / E1 +
/// (1 - nu2^2) / E2`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzLine {
    /// The radius `R` of the cylinder (m).
    pub radius: f64,
    /// The contact modulus `E*` (Pa).
    pub contact_modulus: f64,
}

impl HertzLine {
    /// The contact of a cylinder of radius `radius` and material `cylinder` with a flat body
    /// of material `block`.
    pub fn new(radius: f64, cylinder: &ElasticMaterial, block: &ElasticMaterial) -> Self {
        Self {
            radius,
            contact_modulus: contact_modulus(cylinder, block),
        }
    }

    /// The half-width `a = sqrt(4 P R / (pi E*))` for the load `load` (N/m).
    pub fn half_width(&self, load: f64) -> f64 {
        (4.0 * load * self.radius / (std::f64::consts::PI * self.contact_modulus)).sqrt()
    }

    /// The peak pressure `p0 = 2 P / (pi a)`.
    pub fn peak(&self, load: f64) -> f64 {
        2.0 * load / (std::f64::consts::PI * self.half_width(load))
    }

    /// The pressure `p0 sqrt(1 - x^2 / a^2)` at `x` (zero for `|x| >= a`).
    pub fn pressure(&self, load: f64, x: f64) -> f64 {
        let a = self.half_width(load);
        if x.abs() >= a {
            0.0
        } else {
            self.peak(load) * (1.0 - (x / a).powi(2)).sqrt()
        }
    }

    /// The load per unit length that gives the half-width `a`: `P = pi E* a^2 / (4 R)`.
    pub fn load_for_half_width(&self, a: f64) -> f64 {
        std::f64::consts::PI * self.contact_modulus * a * a / (4.0 * self.radius)
    }
}

/// A Hertz scene: geometry, materials, meshes and solver settings (see the
/// [module](self) documentation).
#[derive(Debug, Clone)]
pub struct HertzScene {
    /// The cylinder's radius `R` (m).
    pub radius: f64,
    /// The cylinder's material.
    pub cylinder: ElasticMaterial,
    /// The block's material.
    pub block: ElasticMaterial,
    /// The block's width and depth over the radius: `W = H = block_size R`.
    pub block_size: f64,
    /// The approach `d` (m): the cylinder's top moves by `-d` in `y`.
    pub approach: f64,
    /// Cells along the quarter disc's arc (see [`quarter_disc_mesh`]).
    pub arc_cells: usize,
    /// The quarter disc's grading (see [`quarter_disc_mesh`]).
    pub grading: f64,
    /// The block's grading, in `x` from `x = 0` and in `y` from `y = 0` (see
    /// [`graded_points`]).
    pub block_grading: f64,
    /// The block's first cell (at the origin) over the cylinder's first arc cell, about; the
    /// block's cell count per direction follows, proportional to `arc_cells` (see
    /// [`block_cell_count`](Self::block_cell_count)).
    pub block_cell_ratio: f64,
    /// The block's cells per direction, if given; otherwise from `block_cell_ratio`. A
    /// refinement study doubles it with `arc_cells`, so that the block's meshes are nested.
    pub block_cells: Option<usize>,
    /// The slave surface: the arc faces with `x <= contact_zone R`.
    pub contact_zone: f64,
    /// The mortar coupling (default: dual multipliers, segment-based integration); full
    /// coverage of the slave surface is required whatever this says.
    pub coupling: CouplingOptions,
    /// The contact solve.
    pub contact: ContactOptions,
    /// `None`: Quad4 cells, Line2 faces; a [`SecondOrder`] family: both bodies raised to
    /// second order, the disc's arc nodes on its circle (Line3 faces).
    pub order: Option<SecondOrder>,
}

impl Default for HertzScene {
    /// The scene at [`DEFAULT_ARC_CELLS`].
    fn default() -> Self {
        Self::new(DEFAULT_ARC_CELLS)
    }
}

impl HertzScene {
    /// The default scene at `arc_cells` cells along the arc: `R = 1`, both bodies
    /// `E = 200 GPa`, `nu = 0.3`, `W = H = 8 R`, the approach that makes `a` about `0.1 R`
    /// ([`DEFAULT_APPROACH`]), the disc graded by 8, the block by 100 with about the disc's
    /// cell at the origin, the slave surface out to `0.3 R`, one load step.
    pub fn new(arc_cells: usize) -> Self {
        Self {
            radius: 1.0,
            cylinder: ElasticMaterial::new(200e9, 0.3),
            block: ElasticMaterial::new(200e9, 0.3),
            block_size: 8.0,
            approach: DEFAULT_APPROACH,
            arc_cells,
            grading: 8.0,
            block_grading: 100.0,
            block_cell_ratio: 1.0,
            block_cells: None,
            contact_zone: 0.3,
            coupling: CouplingOptions::default().dual(),
            contact: ContactOptions::default(),
            order: None,
        }
    }

    /// The closed form for this scene's radius and materials.
    pub fn closed_form(&self) -> HertzLine {
        HertzLine::new(self.radius, &self.cylinder, &self.block)
    }

    /// The block's cells per direction: the field `block_cells` if given, otherwise
    /// such that its first cell `W f(1/n_b) ~ W ln(G) / ((G - 1) n_b)` is about
    /// `block_cell_ratio` times the disc's `(pi / 2) R ln(g) / ((g - 1) n)`.
    pub fn block_cell_count(&self) -> usize {
        if let Some(n) = self.block_cells {
            return n.max(1);
        }
        let w = self.block_size * self.radius;
        let disc = first_cell(std::f64::consts::FRAC_PI_2 * self.radius, 1.0, self.grading);
        let ratio = first_cell(w, 1.0, self.block_grading) / (self.block_cell_ratio * disc);
        ((ratio * self.arc_cells as f64).round() as usize).max(1)
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

    /// The scene as a scene file and its meshes (`cylinder.msh`, `block.msh`; groups
    /// `cylinder_axis`, `cylinder_top`, `cylinder_contact`, `block_axis`, `block_bottom`,
    /// `block_top`): what `mortar run --scene hertz2d` runs and writes.
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
    pub fn run(&self) -> Result<HertzRun, PhysicsError> {
        let t0 = Instant::now();
        let problem = self.build()?;
        let sol = problem.solve(&self.contact)?;
        Ok(self.evaluate(&problem, &sol, t0.elapsed().as_secs_f64()))
    }

    /// The comparison with the closed form of the solution `sol` of this scene's `problem`
    /// (built by [`build`](Self::build), or read back from its [scene
    /// file](Self::scene_files)); `seconds` is reported as the run's time.
    pub fn evaluate(
        &self,
        problem: &HertzProblem,
        sol: &ContactSolution,
        seconds: f64,
    ) -> HertzRun {
        let r = self.radius;
        let h = self.block_size * r;
        let near = near_to(r);
        let HertzProblem {
            bodies: [slave, master],
            tie,
            gap,
            law,
            block_cells: nb,
            ..
        } = problem;
        let (ns, nm) = (slave.mesh.node_count(), master.mesh.node_count());
        let c = law.parameter();

        // Reactions: K u - f on the Dirichlet rows of u_y at the block's bottom and at the
        // cylinder's top.
        let reaction_bottom = problem.reaction(sol, 1, 1, |x| near(x.y, -h));
        let reaction_top = -problem.reaction(sol, 0, 1, |x| near(x.y, r));

        // The profile, by x, over the nodes that carry a multiplier (with linear multipliers
        // on Line3 faces the corners: the pressure is linear between them).
        let cpl = tie.coupling();
        let coords = slave.mesh.coords();
        let mut nodes: Vec<ProfileNode> = (0..sol.pressure.len())
            .filter(|&j| gap.carries[j])
            .map(|j| ProfileNode {
                x: coords[tie.slave_nodes()[j] as usize].x,
                y: coords[tie.slave_nodes()[j] as usize].y,
                pressure: sol.pressure[j],
                weight: gap.weights[j],
                normal: [cpl.slave_normals[j].x, cpl.slave_normals[j].y],
            })
            .collect();
        nodes.sort_by(|a, b| a.x.total_cmp(&b.x));
        let vertical_force =
            vertical_force(nodes.iter().map(|n| (n.weight, n.pressure, n.normal[1])));
        let load = 2.0 * vertical_force;
        let hertz = self.closed_form();
        let a_exact = hertz.half_width(load);
        let p0_exact = hertz.peak(load);
        let half_width =
            HalfWidth::of_profile(&nodes.iter().map(|n| (n.x, n.pressure)).collect::<Vec<_>>());
        let length = |p: &ProfileNode, q: &ProfileNode| (q.x - p.x).hypot(q.y - p.y);
        let contact_cell = length(&nodes[0], &nodes[1]);
        let edge_cell = nodes
            .windows(2)
            .find(|w| w[1].x >= a_exact)
            .map_or(f64::NAN, |w| length(&w[0], &w[1]));
        let profile_l2 = profile_error(&nodes, &hertz, load);
        HertzRun {
            arc_cells: self.arc_cells,
            block_cells: *nb,
            unknowns: 2 * (ns + nm) + nodes.len(),
            slave_nodes: nodes.len(),
            active: nodes.iter().filter(|n| n.pressure > 0.0).count(),
            contact_cell,
            edge_cell,
            load,
            force: sol.force,
            reaction_bottom,
            reaction_top,
            half_width,
            a_exact,
            peak: nodes[0].pressure,
            p0_exact,
            profile_l2,
            complementarity: c,
            steps: sol.steps.clone(),
            formulation: sol.formulation.clone(),
            seconds,
            profile: nodes,
        }
    }
}

impl HertzBodies for HertzScene {
    const TITLE: &'static str =
        "2D Hertz contact: a cylinder on a block (plane strain, half model)";
    const DIMENSION: usize = 2;

    /// The two bodies with their groups and conditions (see the [module](self)).
    fn bodies(&self) -> Result<[SceneBody; 2], PhysicsError> {
        let invalid = |what: String| PhysicsError::InvalidInput {
            body: "hertz scene".into(),
            what,
        };
        let r = self.radius;
        if !(self.block_size > 1.0 && self.contact_zone > 0.0 && self.contact_zone < 1.0) {
            return Err(invalid(format!(
                "block size {} (over the radius, above 1) or contact zone {} (a fraction of \
                 the radius, in (0, 1))",
                self.block_size, self.contact_zone
            )));
        }
        let (w, h) = (self.block_size * r, self.block_size * r);
        let disc = quarter_disc_mesh(
            r,
            [0.0, r],
            self.arc_cells,
            self.grading,
            CellShape::Tensor,
            1,
        )?;
        let nb = self.block_cell_count();
        let xs = graded_points(0.0, w, nb, self.block_grading);
        let mut ys = graded_points(0.0, -h, nb, self.block_grading);
        ys.reverse();
        let block = grid_rectangle_mesh(&xs, &ys, CellShape::Tensor, 1_000_001)?;
        let (disc, block) = match self.order {
            None => (disc, block),
            Some(family) => (
                second_order_mesh(&disc, family, onto_sphere([0.0, r, 0.0], r))?,
                second_order_mesh(&block, family, |x, _| *x)?,
            ),
        };

        let near = near_to(r);
        // The slave surface: the arc faces near the contact. The gap grows to
        // r - sqrt(r^2 - zone^2) < zone at the zone's end: the search looks that far.
        let coords = disc.coords().to_vec();
        let zone = self.contact_zone * r;
        let on_arc = move |f: &BoundaryFace| {
            f.nodes.iter().all(|&n| {
                let x = coords[n as usize];
                (x.x.hypot(x.y - r) - r).abs() <= 1e-9 * r && x.x <= zone
            })
        };
        let scene = |e: SceneError| invalid(e.to_string());
        let slave = SceneBody::new("cylinder", disc, self.cylinder)
            .group("axis", |f| near(f.centroid.x, 0.0))
            .and_then(|b| b.group("top", |f| near(f.centroid.y, r)))
            .and_then(|b| b.group("contact", on_arc))
            .map_err(scene)?
            .hold("axis", Component::X, 0.0)
            .hold("top", Component::Y, -self.approach);
        let master = SceneBody::new("block", block, self.block)
            .group("axis", |f| near(f.centroid.x, 0.0))
            .and_then(|b| b.group("bottom", |f| near(f.centroid.y, -h)))
            .and_then(|b| b.group("top", |f| near(f.centroid.y, 0.0)))
            .map_err(scene)?
            .hold("axis", Component::X, 0.0)
            .hold("bottom", Component::Y, 0.0);
        Ok([slave, master])
    }

    fn settings(&self) -> (f64, &CouplingOptions, &ContactOptions, usize) {
        let zone = self.contact_zone * self.radius;
        (zone, &self.coupling, &self.contact, self.block_cell_count())
    }
}

/// The approach of [`HertzScene::new`] over the radius: `a = 0.0999 R` for its bodies at
/// the default mesh (`P = 8.6e8 N/m`), measured (the approach of a 2D contact depends on the
/// bodies' size, not only on `P`).
pub const DEFAULT_APPROACH: f64 = 0.021;

/// The default mesh: cells along the quarter disc's arc (first arc cell `0.020 R`, five slave
/// nodes in contact at the default approach).
pub const DEFAULT_ARC_CELLS: usize = 24;

/// One slave interface node of the solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileNode {
    /// Its abscissa (reference configuration).
    pub x: f64,
    /// Its ordinate (reference configuration).
    pub y: f64,
    /// The contact pressure (Pa).
    pub pressure: f64,
    /// Its weight `w_j`, the row sum of D (m, per unit length).
    pub weight: f64,
    /// Its averaged unit normal (outward from the cylinder).
    pub normal: [f64; 2],
}

/// `||p_h - p||_L2(0, X) / (p0 sqrt(a))` with `p_h` the piecewise linear interpolant of the
/// nodal pressures over the slave surface's segments (by `x`) and `p` the closed form at the
/// load `load`, over the segments up to the first that ends beyond both the exact and the
/// discrete contact zone. The segments are integrated by 8-point Gauss-Legendre rules, split
/// at `x = a`, the piece ending at `a` after the substitution `x = a - L s^2` (which makes
/// the square root smooth).
fn profile_error(nodes: &[ProfileNode], hertz: &HertzLine, load: f64) -> f64 {
    let a = hertz.half_width(load);
    let p0 = hertz.peak(load);
    let last = nodes.iter().rposition(|n| n.pressure > 0.0).unwrap_or(0);
    let mut sum = 0.0;
    for (i, w) in nodes.windows(2).enumerate() {
        let (x0, x1) = (w[0].x, w[1].x);
        if x0 >= a && i > last {
            break;
        }
        let ph = |x: f64| w[0].pressure + (w[1].pressure - w[0].pressure) * (x - x0) / (x1 - x0);
        let e2 = |x: f64| (ph(x) - hertz.pressure(load, x)).powi(2);
        if x0 < a && a < x1 {
            let l = a - x0;
            sum += gauss(0.0, 1.0, |s| e2(a - l * s * s) * 2.0 * l * s);
            sum += gauss(a, x1, e2);
        } else {
            sum += gauss(x0, x1, e2);
        }
    }
    sum.sqrt() / (p0 * a.sqrt())
}

/// The 8-point Gauss-Legendre rule on `[lo, hi]`.
fn gauss(lo: f64, hi: f64, f: impl Fn(f64) -> f64) -> f64 {
    const X: [f64; 4] = [
        0.183_434_642_495_649_8,
        0.525_532_409_916_329,
        0.796_666_477_413_626_7,
        0.960_289_856_497_536_3,
    ];
    const W: [f64; 4] = [
        0.362_683_783_378_362,
        0.313_706_645_877_887_3,
        0.222_381_034_453_374_5,
        0.101_228_536_290_376_3,
    ];
    let (m, h) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    X.iter()
        .zip(&W)
        .map(|(x, w)| w * (f(m - h * x) + f(m + h * x)))
        .sum::<f64>()
        * h
}

/// A solved Hertz scene and its comparison with the closed form.
#[derive(Debug, Clone)]
pub struct HertzRun {
    /// Cells along the arc.
    pub arc_cells: usize,
    /// The block's cells per direction.
    pub block_cells: usize,
    /// Unknowns of the saddle-point system before the Dirichlet values are eliminated: two
    /// displacements per node of both bodies and a pressure per slave interface node that
    /// carries a multiplier.
    pub unknowns: usize,
    /// Slave interface nodes that carry a multiplier (all of them, but for linear
    /// multipliers on Line3 faces: the corners).
    pub slave_nodes: usize,
    /// Of those, the nodes in contact (positive pressure).
    pub active: usize,
    /// The distance between the first two of those nodes at the contact point (`x = 0`):
    /// the resolution of the pressure profile.
    pub contact_cell: f64,
    /// The length of the slave face in which the exact contact zone ends.
    pub edge_cell: f64,
    /// `P`: twice the vertical contact force of the half model (N/m).
    pub load: f64,
    /// The solver's normal contact force of the half model, `sum_j w_j p_j` (N/m).
    pub force: f64,
    /// The reaction at the block's bottom (upwards, N/m): the vertical contact force.
    pub reaction_bottom: f64,
    /// The force the cylinder's top carries (downwards, N/m): the vertical contact force.
    pub reaction_top: f64,
    /// The computed half-width.
    pub half_width: HalfWidth,
    /// The closed form's half-width at `P`.
    pub a_exact: f64,
    /// The computed pressure at `x = 0`.
    pub peak: f64,
    /// The closed form's peak pressure at `P`.
    pub p0_exact: f64,
    /// The L2 error of the pressure profile relative to `p0 sqrt(a)` (see the module
    /// documentation).
    pub profile_l2: f64,
    /// The complementarity parameter `c` used (Pa/m).
    pub complementarity: f64,
    /// The load steps of the contact solve.
    pub steps: Vec<ContactStep>,
    /// How the Newton systems were solved (the contact solution's report).
    pub formulation: String,
    /// Wall-clock seconds of meshing, assembly and solve.
    pub seconds: f64,
    /// The slave interface nodes by `x`.
    pub profile: Vec<ProfileNode>,
}

impl HertzRun {
    /// `(p0_h - p0) / p0`.
    pub fn peak_error(&self) -> f64 {
        (self.peak - self.p0_exact) / self.p0_exact
    }

    /// `(a_h - a) / a`, with [`HalfWidth::estimate`].
    pub fn half_width_error(&self) -> f64 {
        (self.half_width.estimate - self.a_exact) / self.a_exact
    }

    /// The vertical force of the half model, `P / 2`.
    pub fn vertical_force(&self) -> f64 {
        0.5 * self.load
    }

    /// The largest relative difference between the vertical contact force and the two
    /// reactions (zero up to round-off: equilibrium).
    pub fn equilibrium_error(&self) -> f64 {
        let f = self.vertical_force();
        ((self.reaction_bottom - f).abs()).max((self.reaction_top - f).abs()) / f
    }
}
