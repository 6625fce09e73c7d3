//! The shrink fit (plane strain): a disc of radius `b + delta` pressed into a ring of inner
//! radius `b` and outer radius `c`, same material, frictionless mortar contact, checked
//! against Lamé's closed form (S. P. Timoshenko and J. N. Goodier, *Theory of Elasticity*,
//! 3rd ed., McGraw-Hill, 1970, sec. 33, the thick cylinder; see [`ShrinkFit::pressure`]).
//!
//! The quarter model: the lower-right quarter of both bodies (`x >= 0`, `y <= 0`, centred at
//! the origin), `u_x = 0` on `x = 0` and `u_y = 0` on `y = 0` for both. The disc is
//! [`quarter_disc_mesh`] (uniform, grading 1), its arc the slave surface; the ring is
//! [`quarter_annulus_mesh`], its inner arc the master surface. The arcs have `slave_cells`
//! and `master_cells` cells (non-matching for a ratio other than 1, e.g. 3:2). Dual
//! multipliers, segment-based integration, the exact complementarity law with automatic `c`.
//! No load: the overlap `delta` (a negative initial gap) is the only source.
//!
//! Both circles are faceted: the nodes lie on them, the faces are chords, inside the circle by
//! up to `R dtheta^2 / 8` (on average `R dtheta^2 / 12` along a chord). The initial gap is
//! therefore `-delta` only to `O(h^2)`: the mean interference of the polygons is about
//! `delta + b dtheta_m^2 / 12 - (b + delta) dtheta_s^2 / 12` (slave `s`, master `m`), which
//! the mesh-dependent reference [`ShrinkFitRun::faceted_pressure`] uses; and where the two
//! arcs' cells do not match, the gap seen by neighbouring slave nodes differs by a fraction
//! of `b dtheta_m^2 / 8`, which the contact stiffness (about `E / h`) turns into a pressure
//! varying from node to node by `O(E dtheta)`, i.e. `O(h / delta)` relative to `p`: with the
//! disc's arc (the finer, 3:2) as the slave, by more than `p` up to 192/128 arc cells (nodes
//! lift off); with the coarser ring as the slave, by `0.18 p` at 96/64, halving with `h`.
//! With the same angular nodes on both arcs the sagittas cancel and the pressure is uniform
//! up to `O(delta / b)` effects of the linearisation about the overlapping reference
//! configuration: the slave's pressure acts on its own radius (`b + delta` for the disc: a
//! `delta / b` lower pressure for the same force), and the end nodes on the symmetry lines
//! (their normals the end chords', the disc's end faces' slivers of `delta dtheta / 2` not
//! covered by the ring) sit `2.6e-4` (ring slave) to `6.3e-4` (disc slave) above the rest at
//! `delta = 1e-3`, `O(h^2)` plus a part proportional to `delta`.

use std::time::Instant;

use mortar_core::{CouplingOptions, SearchRadius, Tolerances};
use mortar_fem::mesh::BoundaryFace;
use mortar_physics::contact::{
    solve_contact, ContactOptions, ContactSolution, ContactStep, NormalGap,
};
use mortar_physics::elastic::{ElasticBody, ElasticMaterial};
use mortar_physics::laws::ContactComplementarity;
use mortar_physics::tied::Tie;
use mortar_physics::PhysicsError;
use nalgebra::Vector3;

use crate::file::contact::Component;
use crate::file::contact_files::{contact_scene_files, ContactSceneFiles, SceneBody, SceneContact};
use crate::file::SceneError;
use crate::hertz::exact_contact;
use mortar::generate::{
    quarter_annulus_mesh, quarter_disc_mesh, second_order_mesh, CellShape, SecondOrder,
};

/// The closed form: Lamé's thick cylinder in plane strain (Timoshenko and Goodier, sec. 33).
/// A disc and a ring of the same material (`E`, `nu`), interference `delta` on the radius at
/// the interface radius `b`, ring outer radius `c`: the contact pressure is
/// `p = E delta (c^2 - b^2) / (2 b c^2 (1 - nu^2))`, uniform.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShrinkFit {
    /// The interface radius `b` (the ring's inner radius), m.
    pub inner: f64,
    /// The ring's outer radius `c`, m.
    pub outer: f64,
    /// The radial interference `delta` (the disc's radius is `b + delta`), m.
    pub interference: f64,
    /// The material of both bodies.
    pub material: ElasticMaterial,
}

impl ShrinkFit {
    /// The closed-form contact pressure (Pa) for the interference `delta`.
    pub fn pressure_for(&self, delta: f64) -> f64 {
        let (b, c) = (self.inner, self.outer);
        let (e, nu) = (self.material.youngs_modulus, self.material.poisson_ratio);
        e * delta * (c * c - b * b) / (2.0 * b * c * c * (1.0 - nu * nu))
    }

    /// The closed-form contact pressure (Pa).
    pub fn pressure(&self) -> f64 {
        self.pressure_for(self.interference)
    }
}

/// A shrink-fit scene (see the [module](self) documentation).
#[derive(Debug, Clone)]
pub struct ShrinkFitScene {
    /// The geometry and material.
    pub fit: ShrinkFit,
    /// Cells along the disc's arc (the slave surface).
    pub slave_cells: usize,
    /// Cells along the ring's arcs (the master surface).
    pub master_cells: usize,
    /// Swap the sides: the ring's inner arc the slave surface, the disc's arc the master
    /// (`slave_cells` and `master_cells` still count the disc's and the ring's cells). Off by
    /// default.
    pub ring_is_slave: bool,
    /// Cells across the ring; `None`: about square cells at the inner arc.
    pub ring_radial_cells: Option<usize>,
    /// The search radius; `None`: `SearchRadius::Distance(max(4 delta, h_s))`, `h_s` the
    /// slave's arc cell.
    pub search_radius: Option<SearchRadius>,
    /// The mortar coupling (default: dual multipliers, segment-based integration).
    pub coupling: CouplingOptions,
    /// The contact solve.
    pub contact: ContactOptions,
    /// `None`: Quad4 cells, Line2 faces; a [`SecondOrder`] family: both bodies raised to
    /// second order, the new nodes of the arcs on their circles (Line3 faces).
    pub order: Option<SecondOrder>,
}

impl ShrinkFitScene {
    /// `b = 1`, `c = 2`, `delta = 1e-3`, `E = 200 GPa`, `nu = 0.3`, the given arc cells.
    pub fn new(slave_cells: usize, master_cells: usize) -> Self {
        Self {
            fit: ShrinkFit {
                inner: 1.0,
                outer: 2.0,
                interference: 1e-3,
                material: ElasticMaterial::new(200e9, 0.3),
            },
            slave_cells,
            master_cells,
            ring_radial_cells: None,
            ring_is_slave: false,
            search_radius: None,
            coupling: CouplingOptions::default().dual(),
            contact: ContactOptions::default(),
            order: None,
        }
    }

    /// The two bodies with their groups and conditions, slave first (the disc, groups
    /// `disc_x0`, `disc_y0`, `disc_rim`; the ring, groups `ring_x0`, `ring_y0`, `ring_inner`;
    /// swapped with `ring_is_slave`), the slave and master group suffixes and the search
    /// radius.
    fn bodies(&self) -> Result<ShrinkFitBodies, PhysicsError> {
        let ShrinkFit {
            inner: b,
            outer: c,
            interference: delta,
            material,
        } = self.fit;
        let rs = b + delta;
        let dts = std::f64::consts::FRAC_PI_2 / self.slave_cells as f64;
        let nr = self.ring_radial_cell_count();
        let disc = quarter_disc_mesh(rs, [0.0, 0.0], self.slave_cells, 1.0, CellShape::Tensor, 1)?;
        let ring = quarter_annulus_mesh(b, c, [self.master_cells, nr], CellShape::Tensor, 1)?;
        let (disc, ring) = match self.order {
            None => (disc, ring),
            Some(family) => {
                // New nodes between nodes of one of the circles (radii rs, b, c) go onto it.
                let place = |x: &Vector3<f64>, parents: &[Vector3<f64>]| {
                    let r0 = parents[0].x.hypot(parents[0].y);
                    let on = |p: &Vector3<f64>| (p.x.hypot(p.y) - r0).abs() <= 1e-12 * c;
                    let circle = [rs, b, c].iter().any(|r| (r - r0).abs() <= 1e-12 * c);
                    if circle && parents.iter().all(on) {
                        x * (r0 / x.x.hypot(x.y))
                    } else {
                        *x
                    }
                };
                (
                    second_order_mesh(&disc, family, place)?,
                    second_order_mesh(&ring, family, place)?,
                )
            }
        };

        let tol = 1e-12 * c;
        let near = move |a: f64, v: f64| (a - v).abs() <= tol;
        let on_circle = |coords: &[Vector3<f64>], r: f64| {
            let coords = coords.to_vec();
            move |f: &BoundaryFace| {
                f.nodes.iter().all(|&n| {
                    let x = coords[n as usize];
                    (x.x.hypot(x.y) - r).abs() <= 1e-9 * r
                })
            }
        };
        let held = |body: SceneBody, arc: &str, r: f64| -> Result<SceneBody, SceneError> {
            let on_arc = on_circle(body.mesh.coords(), r);
            Ok(body
                .group("x0", |f| near(f.centroid.x, 0.0))?
                .group("y0", |f| near(f.centroid.y, 0.0))?
                .group(arc, on_arc)?
                .hold("x0", Component::X, 0.0)
                .hold("y0", Component::Y, 0.0))
        };
        let scene = |e: SceneError| PhysicsError::InvalidInput {
            body: "shrink fit".into(),
            what: e.to_string(),
        };
        let disc = held(SceneBody::new("disc", disc, material), "rim", rs).map_err(scene)?;
        let ring = held(SceneBody::new("ring", ring, material), "inner", b).map_err(scene)?;
        let search = self
            .search_radius
            .unwrap_or(SearchRadius::Distance((4.0 * delta).max(rs * dts)));
        Ok(if self.ring_is_slave {
            ShrinkFitBodies {
                bodies: [ring, disc],
                groups: ["inner", "rim"],
                search,
            }
        } else {
            ShrinkFitBodies {
                bodies: [disc, ring],
                groups: ["rim", "inner"],
                search,
            }
        })
    }

    /// The scene as a scene file and its meshes (`disc.msh`, `ring.msh`, see
    /// [`run`](Self::run) for the groups): what `mortar run --scene shrink_fit` runs and
    /// writes.
    ///
    /// # Errors
    /// The errors of the meshing, and [`SceneError::Other`] for a coupling or a search
    /// radius a scene file cannot state.
    pub fn scene_files(&self) -> Result<ContactSceneFiles, SceneError> {
        let parts = self
            .bodies()
            .map_err(|e| SceneError::Other(e.to_string()))?;
        let search_radius = match parts.search {
            SearchRadius::Distance(d) => Some(d),
            s if s == SearchRadius::DEFAULT => None,
            s => {
                return Err(SceneError::Other(format!(
                    "a contact scene file cannot state the search radius {s:?}"
                )))
            }
        };
        contact_scene_files(
            "shrink fit: a disc in a ring (plane strain, quarter model)",
            parts.bodies,
            &SceneContact {
                slave: parts.groups[0],
                master: parts.groups[1],
                coupling: &self.coupling,
                search_radius,
                require_full_coverage: self.coupling.require_full_coverage,
                solve: &self.contact,
            },
        )
    }

    /// Builds and solves the scene: the disc (groups `disc_x0`, `disc_y0` held in x and y,
    /// `disc_rim` its arc) and the ring (`ring_x0`, `ring_y0`, `ring_inner`).
    ///
    /// # Errors
    /// The errors of mesh generation, of the coupling, of the assembly and of
    /// [`solve_contact`].
    pub fn run(&self) -> Result<ShrinkFitRun, PhysicsError> {
        let t0 = Instant::now();
        let parts = self.bodies()?;
        let [slave, master] = &parts.bodies;
        let (slave, slave_surface) = slave.elastic(parts.groups[0])?;
        let (master, master_surface) = master.elastic(parts.groups[1])?;
        let tolerances = Tolerances {
            search_radius: parts.search,
            ..Tolerances::default()
        };
        let surfaces = [slave_surface, master_surface];
        let ((k, f, dir), tie, gap, cpar) =
            exact_contact([&slave, &master], surfaces, tolerances, &self.coupling, 2)?;
        let nm = master.mesh.node_count();
        let law = ContactComplementarity::try_new(cpar)?;
        let sol = solve_contact(
            [&k[0], &k[1]],
            [&f[0], &f[1]],
            [(&dir[0].0, &dir[0].1), (&dir[1].0, &dir[1].1)],
            &gap,
            &law,
            &self.contact,
        )?;
        let seconds = t0.elapsed().as_secs_f64();
        Ok(self.evaluate(
            ShrinkFitSolved {
                slave: &slave,
                master_nodes: nm,
                tie: &tie,
                gap: &gap,
                complementarity: cpar,
            },
            sol,
            seconds,
        ))
    }

    /// The comparison with the closed form of the solution `sol` of this scene (built in
    /// memory by [`run`](Self::run), or read back from its [scene
    /// file](Self::scene_files)); `seconds` is reported as the run's time.
    pub fn evaluate(
        &self,
        solved: ShrinkFitSolved<'_>,
        sol: ContactSolution,
        seconds: f64,
    ) -> ShrinkFitRun {
        let ShrinkFitSolved {
            slave,
            master_nodes,
            tie,
            gap,
            complementarity: cpar,
        } = solved;
        let nr = self.ring_radial_cell_count();
        let ShrinkFit {
            inner: b,
            interference: delta,
            ..
        } = self.fit;
        let rs = b + delta;
        let dts = std::f64::consts::FRAC_PI_2 / self.slave_cells as f64;
        let dtm = std::f64::consts::FRAC_PI_2 / self.master_cells as f64;
        let warnings: Vec<String> = tie
            .coupling()
            .warnings
            .iter()
            .map(|w| w.to_string())
            .collect();
        let (ns, nm) = (slave.mesh.node_count(), master_nodes);
        let coords = slave.mesh.coords();
        let mut nodes: Vec<(f64, f64, f64)> = (0..sol.pressure.len())
            .map(|j| {
                let x = coords[tie.slave_nodes()[j] as usize];
                (
                    x.x.atan2(-x.y),
                    sol.pressure[j],
                    gap.initial[j] / gap.weights[j],
                )
            })
            .collect();
        nodes.sort_by(|a, b| a.0.total_cmp(&b.0));
        let weight: f64 = gap.weights.iter().sum();
        let mean = gap
            .weights
            .iter()
            .zip(&sol.pressure)
            .map(|(w, p)| w * p)
            .sum::<f64>()
            / weight;
        let min = sol.pressure.iter().copied().fold(f64::INFINITY, f64::min);
        let max = sol
            .pressure
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        let faceted_delta = delta + b * dtm * dtm / 12.0 - rs * dts * dts / 12.0;
        ShrinkFitRun {
            slave_cells: self.slave_cells,
            master_cells: self.master_cells,
            ring_is_slave: self.ring_is_slave,
            ring_radial_cells: nr,
            unknowns: 2 * (ns + nm) + nodes.len(),
            exact: self.fit.pressure(),
            faceted_pressure: self.fit.pressure_for(faceted_delta),
            mean,
            min,
            max,
            active: sol.steps.last().map_or(0, |s| s.active),
            angle: nodes.iter().map(|n| n.0).collect(),
            pressure: nodes.iter().map(|n| n.1).collect(),
            initial_gap: nodes.iter().map(|n| n.2).collect(),
            complementarity: cpar,
            steps: sol.steps,
            warnings,
            seconds,
        }
    }

    /// Cells across the ring: `ring_radial_cells`, or about square cells at the inner arc.
    pub fn ring_radial_cell_count(&self) -> usize {
        let dtm = std::f64::consts::FRAC_PI_2 / self.master_cells as f64;
        let (b, c) = (self.fit.inner, self.fit.outer);
        self.ring_radial_cells
            .unwrap_or_else(|| ((c - b) / (b * dtm)).round().max(1.0) as usize)
    }
}

/// The parts of a solved [`ShrinkFitScene`] its comparison with the closed form reads (see
/// [`ShrinkFitScene::evaluate`]).
#[derive(Debug, Clone, Copy)]
pub struct ShrinkFitSolved<'a> {
    /// The slave body.
    pub slave: &'a ElasticBody,
    /// The master body's node count.
    pub master_nodes: usize,
    /// The tie of the contact surfaces.
    pub tie: &'a Tie,
    /// Its normal gap.
    pub gap: &'a NormalGap,
    /// The exact law's `c` (Pa/m).
    pub complementarity: f64,
}

/// [`ShrinkFitScene::bodies`]'s parts.
struct ShrinkFitBodies {
    /// Slave first.
    bodies: [SceneBody; 2],
    /// The slave's and the master's contact group suffixes.
    groups: [&'static str; 2],
    /// The search radius.
    search: SearchRadius,
}

/// The result of [`ShrinkFitScene::run`].
#[derive(Debug, Clone)]
pub struct ShrinkFitRun {
    /// Cells along the disc's arc (slave, unless swapped).
    pub slave_cells: usize,
    /// Cells along the ring's inner arc (master, unless swapped).
    pub master_cells: usize,
    /// Whether the ring's inner arc was the slave surface.
    pub ring_is_slave: bool,
    /// Cells across the ring.
    pub ring_radial_cells: usize,
    /// Displacement unknowns of both bodies plus the pressures.
    pub unknowns: usize,
    /// The closed-form pressure `p` (Pa).
    pub exact: f64,
    /// The closed form at the faceted circles' mean interference
    /// `delta + b dtheta_m^2 / 12 - (b + delta) dtheta_s^2 / 12` (Pa): what the polygons
    /// would give if the fit were still Lamé's.
    pub faceted_pressure: f64,
    /// The mean pressure `sum w_j p_j / sum w_j` (Pa), on the slave's radius.
    pub mean: f64,
    /// The smallest nodal pressure (Pa).
    pub min: f64,
    /// The largest nodal pressure (Pa).
    pub max: f64,
    /// Slave nodes in contact.
    pub active: usize,
    /// The slave nodes' angles from the downward vertical, ascending.
    pub angle: Vec<f64>,
    /// Their pressures (Pa), on the slave's radius (`b + delta` for the disc, `b` for the
    /// ring).
    pub pressure: Vec<f64>,
    /// Their initial nodal gaps `g~_0 / w` (m; about `-delta`).
    pub initial_gap: Vec<f64>,
    /// The complementarity parameter used.
    pub complementarity: f64,
    /// The load steps of the solve.
    pub steps: Vec<ContactStep>,
    /// The coupling's warnings.
    pub warnings: Vec<String>,
    /// Wall time of build and solve (s).
    pub seconds: f64,
}

impl ShrinkFitRun {
    /// The worst nodal pressure's error relative to `p`.
    pub fn worst_error(&self) -> f64 {
        self.pressure
            .iter()
            .map(|q| (q - self.exact).abs() / self.exact)
            .fold(0.0, f64::max)
    }

    /// The mean pressure's error relative to `p`.
    pub fn mean_error(&self) -> f64 {
        (self.mean - self.exact) / self.exact
    }

    /// `(max - min) / p`.
    pub fn uniformity(&self) -> f64 {
        (self.max - self.min) / self.exact
    }
}
