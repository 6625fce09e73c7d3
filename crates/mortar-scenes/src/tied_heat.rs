//! The tied heat scene: heat conduction in two bodies meshed independently and
//! tied by mortar, with a manufactured solution, for convergence studies and patch tests.
//!
//! Geometries (the domain is the unit square or cube; `n` is the coarse body's number of
//! cells per unit length and the fine body has `3n/2`, a 2:3 size ratio):
//!
//! - [`Geometry::Straight`]: the square (cube) cut at `x = 0.5`. The left body (master) has
//!   `n/2 x n (x n)` Quad4 (Hex8) cells, the right body (slave) `3n/4 x 3n/2 (x 3n/2)` cells
//!   cut into Tri3 (Tet4). Dirichlet data on the whole outer boundary, so the interface's end
//!   nodes are Dirichlet nodes on both sides (see
//!   [`SlaveDirichlet`](mortar_physics::tied::SlaveDirichlet)).
//! - [`Geometry::Curved`]: a disc (ball) of radius 0.3 at the centre, the master body, an
//!   O-grid of Quad4 (Hex8) with `n/2` cells along each of its `2 dim` blocks, inside the rest
//!   of the square (cube), the slave body, an O-grid with `3n/4` cells along each block (cut
//!   into Tri3 in 2D; Hex8 in 3D). Both circles (spheres) are polygons (polyhedra) inscribed
//!   in the exact one with different nodes, so the interface is curved and non-matching.
//!   Dirichlet data on the outer boundary; the inclusion is held by the interface alone.
//!
//! `n` must be a multiple of 4.

use std::time::Instant;

use mortar_core::CouplingOptions;
use mortar_fem::mesh::VolumeMeshError;
use mortar_fem::VolumeMesh;
use mortar_physics::heat::{
    error_norms, ErrorNorms, HeatBody, HeatMaterial, HeatOptions, TiedHeat, TiedHeatSolution,
};
use mortar_physics::tied::TiedOptions;
use mortar_physics::{LinearSolve, PhysicsError};
use nalgebra::Vector3;

use mortar::generate::{
    ball_mesh, box_mesh, box_with_hole_mesh, onto_sphere, rectangle_mesh, second_order_mesh,
    CellShape, Inclusion, SecondOrder,
};

/// The two blocks of the straight tied geometry (`n` cells across on the left, `m = 3 n / 2` on
/// the right): `[0, 0.5] x [0, 1]^(dim - 1)` of `n / 2 x n (x n)` tensor cells, node tags from
/// 1, and `[0.5, 1] x [0, 1]^(dim - 1)` of `m / 2 x m (x m)` simplices, node tags from
/// `right_tag`; the left block is made first.
///
/// # Errors
/// The generators' error for a cell count of zero.
pub fn straight_blocks(
    dim: usize,
    n: usize,
    right_tag: u64,
) -> Result<(VolumeMesh, VolumeMesh), VolumeMeshError> {
    let m = 3 * n / 2;
    Ok(if dim == 2 {
        (
            rectangle_mesh([0.0, 0.0], [0.5, 1.0], [n / 2, n], CellShape::Tensor, 1)?,
            rectangle_mesh(
                [0.5, 0.0],
                [1.0, 1.0],
                [m / 2, m],
                CellShape::Simplex,
                right_tag,
            )?,
        )
    } else {
        (
            box_mesh(
                [0.0; 3],
                [0.5, 1.0, 1.0],
                [n / 2, n, n],
                CellShape::Tensor,
                1,
            )?,
            box_mesh(
                [0.5, 0.0, 0.0],
                [1.0; 3],
                [m / 2, m, m],
                CellShape::Simplex,
                right_tag,
            )?,
        )
    })
}

/// The interface of a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Geometry {
    /// A plane cut at `x = 0.5`.
    Straight,
    /// A circular (spherical) inclusion of radius 0.3 at the centre.
    Curved,
}

/// The radius of the inclusion of [`Geometry::Curved`].
pub const INCLUSION_RADIUS: f64 = 0.3;

/// A manufactured exact solution (the same in both bodies, of equal conductivity).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Exact {
    /// `u = prod_d sin(pi x_d)` (zero on the boundary of the unit square or cube), with the
    /// source `Q = dim pi^2 k u`.
    Sine,
    /// `u = a + b . x` without source: reproduced exactly by linear elements and a consistent
    /// mortar coupling (the patch test).
    Linear {
        /// The constant.
        a: f64,
        /// The gradient.
        b: [f64; 3],
    },
    /// `u = sum_d a_d x_d^2 + c x y` with the source `Q = -2 k sum_d a_d`: reproduced exactly
    /// by second-order elements and a consistent mortar coupling on a flat interface.
    Quadratic {
        /// The coefficients of `x_d^2`.
        a: [f64; 3],
        /// The coefficient of `x y`.
        c: f64,
    },
}

impl Exact {
    /// `u(x)` in dimension `dim`.
    pub fn value(&self, dim: usize, x: &Vector3<f64>) -> f64 {
        match self {
            Exact::Sine => (0..dim)
                .map(|d| (std::f64::consts::PI * x[d]).sin())
                .product(),
            Exact::Linear { a, b } => a + (0..dim).map(|d| b[d] * x[d]).sum::<f64>(),
            Exact::Quadratic { a, c } => {
                (0..dim).map(|d| a[d] * x[d] * x[d]).sum::<f64>() + c * x.x * x.y
            }
        }
    }

    /// `grad u(x)` (zero third component in 2D).
    pub fn gradient(&self, dim: usize, x: &Vector3<f64>) -> Vector3<f64> {
        let mut g = Vector3::zeros();
        match self {
            Exact::Sine => {
                let pi = std::f64::consts::PI;
                for d in 0..dim {
                    g[d] = (0..dim)
                        .map(|e| {
                            if e == d {
                                pi * (pi * x[e]).cos()
                            } else {
                                (pi * x[e]).sin()
                            }
                        })
                        .product();
                }
            }
            Exact::Linear { b, .. } => {
                for d in 0..dim {
                    g[d] = b[d];
                }
            }
            Exact::Quadratic { a, c } => {
                for d in 0..dim {
                    g[d] = 2.0 * a[d] * x[d];
                }
                g.x += c * x.y;
                g.y += c * x.x;
            }
        }
        g
    }

    /// The source `Q = -k lap u`.
    pub fn source(&self, dim: usize, k: f64, x: &Vector3<f64>) -> f64 {
        match self {
            Exact::Sine => dim as f64 * std::f64::consts::PI.powi(2) * k * self.value(dim, x),
            Exact::Linear { .. } => 0.0,
            Exact::Quadratic { a, .. } => -2.0 * k * a[..dim].iter().sum::<f64>(),
        }
    }
}

/// A tied heat scene: geometry, resolution, exact solution and solver settings.
#[derive(Debug, Clone)]
pub struct TiedHeatScene {
    /// 2 or 3.
    pub dim: usize,
    /// The interface.
    pub geometry: Geometry,
    /// Cells per unit length of the coarse (master) body; a multiple of 4.
    pub n: usize,
    /// The exact solution.
    pub exact: Exact,
    /// The conductivity of both bodies.
    pub conductivity: f64,
    /// The mortar coupling (default: dual multipliers, segment-based integration).
    pub coupling: CouplingOptions,
    /// The tied solve (default: automatic formulation).
    pub tied: TiedOptions,
    /// `None` for first-order cells (Quad4/Tri3, Hex8/Tet4); a [`SecondOrder`] family to
    /// raise both bodies to second order ([`second_order_mesh`]), the new nodes of the
    /// curved interface placed on its circle (sphere).
    pub order: Option<SecondOrder>,
}

impl TiedHeatScene {
    /// The sine solution with unit conductivity, dual multipliers and the automatic
    /// formulation.
    pub fn new(dim: usize, geometry: Geometry, n: usize) -> Self {
        Self {
            dim,
            geometry,
            n,
            exact: Exact::Sine,
            conductivity: 1.0,
            coupling: CouplingOptions::default().dual(),
            tied: TiedOptions::default(),
            order: None,
        }
    }

    /// The mesh size parameter `1 / n` of the coarse body.
    pub fn h(&self) -> f64 {
        1.0 / self.n as f64
    }

    /// The two bodies, the interface surfaces and the tied problem.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a dimension other than 2 or 3 or an `n` that is
    /// not a positive multiple of 4; the errors of mesh generation and of [`TiedHeat::new`].
    pub fn build(&self) -> Result<TiedHeat, PhysicsError> {
        let invalid = |what: String| PhysicsError::InvalidInput {
            body: "scene".into(),
            what,
        };
        if self.dim != 2 && self.dim != 3 {
            return Err(invalid(format!("dimension {} (2 or 3)", self.dim)));
        }
        if self.n == 0 || !self.n.is_multiple_of(4) {
            return Err(invalid(format!(
                "n = {} is not a positive multiple of 4",
                self.n
            )));
        }
        let (dim, n) = (self.dim, self.n);
        let (master, slave, on_interface): (VolumeMesh, VolumeMesh, InterfaceTest) =
            match self.geometry {
                Geometry::Straight => {
                    let (master, slave) = straight_blocks(dim, n, 1_000_001)?;
                    (
                        master,
                        slave,
                        Box::new(|x: &Vector3<f64>| (x.x - 0.5).abs() < 1e-9),
                    )
                }
                Geometry::Curved => {
                    let g = Inclusion::unit(dim, INCLUSION_RADIUS);
                    let (nb, mb) = (n / 2, 3 * n / 4);
                    let master = ball_mesh(&g, nb, (nb / 2).max(1), 1)?;
                    let slave =
                        box_with_hole_mesh(&g, mb, (mb / 2).max(1), CellShape::Simplex, 1_000_001)?;
                    let c = Vector3::from(g.centre);
                    let cut = 0.5 * (g.radius + g.half_width);
                    (
                        master,
                        slave,
                        Box::new(move |x: &Vector3<f64>| (x - c).norm() < cut),
                    )
                }
            };
        let (master, slave) = match self.order {
            None => (master, slave),
            Some(family) => match self.geometry {
                Geometry::Straight => (
                    second_order_mesh(&master, family, |x, _| *x)?,
                    second_order_mesh(&slave, family, |x, _| *x)?,
                ),
                Geometry::Curved => {
                    let g = Inclusion::unit(dim, INCLUSION_RADIUS);
                    (
                        second_order_mesh(&master, family, onto_sphere(g.centre, g.radius))?,
                        second_order_mesh(&slave, family, onto_sphere(g.centre, g.radius))?,
                    )
                }
            },
        };
        let k = self.conductivity;
        let exact = self.exact;
        let body = |name: &str, mesh: VolumeMesh| -> Result<HeatBody, PhysicsError> {
            let b = HeatBody::new(name, mesh, HeatMaterial::new(k, 1.0))
                .with_source(move |x, _| exact.source(dim, k, x));
            // Dirichlet data on every boundary face off the interface, if there is one.
            let outer = b.mesh.boundary_nodes(|f| !on_interface(&f.centroid))?;
            Ok(if outer.is_empty() {
                b
            } else {
                b.with_dirichlet_nodes(outer, move |x, _| exact.value(dim, x))
            })
        };
        let master = body("master", master)?;
        let slave = body("slave", slave)?;
        let master_surface = master
            .mesh
            .boundary_surface(|f| on_interface(&f.centroid))?;
        let slave_surface = slave.mesh.boundary_surface(|f| on_interface(&f.centroid))?;
        TiedHeat::new(
            slave,
            master,
            slave_surface,
            master_surface,
            &self.coupling,
            &HeatOptions::default(),
        )
    }

    /// Builds and solves the scene, and measures its errors.
    ///
    /// # Errors
    /// The errors of [`build`](Self::build) and of the solve.
    pub fn run(&self) -> Result<TiedHeatRun, PhysicsError> {
        self.run_on(&LinearSolve::default())
    }

    /// [`run`](Self::run), the tied system solved by `linear`'s backend when it names one
    /// (PETSc's Krylov methods, say).
    ///
    /// # Errors
    /// As [`run`](Self::run).
    pub fn run_on(&self, linear: &LinearSolve<'_>) -> Result<TiedHeatRun, PhysicsError> {
        let t0 = Instant::now();
        let problem = self.build()?;
        let solution = problem.solve_steady_on(&self.tied, 0.0, linear)?;
        let seconds = t0.elapsed().as_secs_f64();
        let (dim, exact) = (self.dim, self.exact);
        let u = move |x: &Vector3<f64>| exact.value(dim, x);
        let g = move |x: &Vector3<f64>| exact.gradient(dim, x);
        let mut norms = [ErrorNorms::default(); 2];
        for (b, body) in problem.bodies().iter().enumerate() {
            norms[b] = error_norms(&body.mesh, &solution.temperatures[b], &u, &g, None)?;
        }
        let flux_error = flux_error(self, &problem, &solution);
        Ok(TiedHeatRun {
            h: self.h(),
            dofs: problem.bodies().iter().map(|b| b.mesh.node_count()).sum(),
            l2: norms[0].l2.hypot(norms[1].l2),
            h1: norms[0].h1_seminorm.hypot(norms[1].h1_seminorm),
            max_nodal: norms[0].max_nodal.max(norms[1].max_nodal),
            flux_error,
            seconds,
            problem,
            solution,
        })
    }
}

type InterfaceTest = Box<dyn Fn(&Vector3<f64>) -> bool + Send + Sync>;

/// The discrete L2 error of the interface flux, `sqrt(sum_j d_j (lambda_j - lambda(x_j))^2)`
/// with `d_j` the row sums of D and `lambda = -k grad u . n_s` at the slave nodes (averaged
/// nodal normals), over the rows that carry a multiplier.
fn flux_error(scene: &TiedHeatScene, problem: &TiedHeat, solution: &TiedHeatSolution) -> f64 {
    let c = problem.tie().coupling();
    let coords = problem.bodies()[0].mesh.coords();
    let mut sum = 0.0;
    for (j, (&node, lambda)) in problem
        .tie()
        .slave_nodes()
        .iter()
        .zip(&solution.flux)
        .enumerate()
    {
        if !lambda.is_finite() {
            continue;
        }
        let x = coords[node as usize];
        let exact =
            -scene.conductivity * scene.exact.gradient(scene.dim, &x).dot(&c.slave_normals[j]);
        let d: f64 =
            c.d.outer_view(j)
                .map(|r| r.data().iter().sum())
                .unwrap_or(0.0);
        sum += d * (lambda - exact).powi(2);
    }
    sum.sqrt()
}

/// One solved scene and its errors.
#[derive(Debug, Clone)]
pub struct TiedHeatRun {
    /// The mesh size parameter `1 / n`.
    pub h: f64,
    /// Temperature unknowns: the nodes of both bodies.
    pub dofs: usize,
    /// `||T_h - u||_L2` over both bodies.
    pub l2: f64,
    /// The H1-seminorm error over both bodies.
    pub h1: f64,
    /// The largest nodal error.
    pub max_nodal: f64,
    /// The discrete L2 error of the interface flux (see the module documentation).
    pub flux_error: f64,
    /// Wall-clock seconds of build and solve.
    pub seconds: f64,
    /// The problem.
    pub problem: TiedHeat,
    /// The solution.
    pub solution: TiedHeatSolution,
}

/// The convergence rate `log(e1 / e2) / log(h1 / h2)` between two levels.
pub fn rate(h1: f64, e1: f64, h2: f64, e2: f64) -> f64 {
    (e1 / e2).ln() / (h1 / h2).ln()
}
