//! The Hertz contact verifications: an elastic cylinder (2D, plane strain, [`cylinder`]) or
//! sphere (3D, [`sphere`]) pressed onto an elastic block by a prescribed approach, checked
//! against the closed forms of Johnson, *Contact Mechanics* (Cambridge University Press,
//! 1985), sec. 4.2 (sphere, [`HertzPoint`]) and sec. 4.3 and 5.6 (cylinder, [`HertzLine`]).
//!
//! Both scenes are symmetric parts (the half of a 2D section, the quarter of a 3D body, with
//! the body cut at its mid-plane) of two bodies refined towards the point of first contact,
//! frictionless mortar contact with dual multipliers, segment-based integration and the exact
//! complementarity law (semi-smooth Newton, [`solve_contact`](mortar_physics::contact::solve_contact)) with automatic `c`. What they
//! share lives here: the contact modulus, the assembled problem ([`HertzProblem`], built from
//! the two bodies and their surfaces by one function), the solve and its reactions, and the
//! extent of the computed contact zone ([`HalfWidth`]), bracketed by the slave nodes.

use mortar_core::interface::Interface;
use mortar_core::linalg::SparseMatrix;
use mortar_core::mesh::SurfaceMesh;
use mortar_core::{assemble_coupling, CouplingOptions, SearchRadius, Tolerances};
use mortar_fem::linalg::SparseSolver;
use mortar_physics::contact::{
    automatic_complementarity, solve_contact_on, ContactOptions, ContactSolution, NormalGap,
};
use mortar_physics::elastic::{
    assemble_elastic_load, assemble_elastic_stiffness, ElasticBody, ElasticMaterial, ElasticOptions,
};
use mortar_physics::laws::ContactComplementarity;
use mortar_physics::tied::Tie;
use mortar_physics::{LinearSolve, PhysicsError};
use nalgebra::Vector3;

use crate::file::contact::SolvedContact;
use crate::file::contact_files::{contact_scene_files, ContactSceneFiles, SceneBody, SceneContact};
use crate::file::SceneError;

/// A Hertz scene as its two bodies: what the cylinder and the sphere give, and the problem and
/// the scene file made of it the same way for both.
pub(crate) trait HertzBodies {
    /// The scene file's title.
    const TITLE: &'static str;
    /// 2 or 3.
    const DIMENSION: usize;

    /// The two bodies with their groups and conditions, slave (the curved body) first.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for bad geometry; the errors of mesh generation.
    fn bodies(&self) -> Result<[SceneBody; 2], PhysicsError>;

    /// How far the search looks (the contact zone, a distance), the coupling, the contact
    /// solver's options and the block's cells per direction.
    fn settings(&self) -> (f64, &CouplingOptions, &ContactOptions, usize);

    /// The two bodies, their stiffness matrices, loads and Dirichlet data, the tie and the
    /// normal gap of the scene, and the law with automatic `c`.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for bad geometry; the errors of mesh generation, of the
    /// coupling (with full coverage of the slave surface required) and of the assembly.
    fn problem(&self) -> Result<HertzProblem, PhysicsError> {
        let (zone, coupling, _, block_cells) = self.settings();
        HertzProblem::of_bodies(self.bodies()?, zone, coupling, Self::DIMENSION, block_cells)
    }

    /// The scene file of the bodies: the slave's group `contact` against the master's group
    /// `top` with the exact law, the slave's full coverage required, the search as far as the
    /// contact zone.
    ///
    /// # Errors
    /// [`SceneError::Other`] for bodies that could not be made (`bodies`' error) and for a
    /// coupling a scene file cannot state.
    fn files(&self) -> Result<ContactSceneFiles, SceneError> {
        let (zone, coupling, solve, _) = self.settings();
        contact_scene_files(
            Self::TITLE,
            self.bodies()
                .map_err(|e| SceneError::Other(e.to_string()))?,
            &SceneContact {
                slave: "contact",
                master: "top",
                coupling,
                search_radius: Some(zone),
                require_full_coverage: true,
                solve,
            },
        )
    }
}

/// Whether two coordinates are the same to `1e-12` of the radius `r`: how the scenes find the
/// faces of their groups and the nodes of their reactions.
pub(crate) fn near_to(r: f64) -> impl Fn(f64, f64) -> bool + Copy {
    let tol = 1e-12 * r;
    move |a: f64, b: f64| (a - b).abs() <= tol
}

/// The vertical force of the contact pressure on the slave nodes, of their `(weight, pressure,
/// vertical normal component)`: the sum of `-weight pressure normal`.
pub(crate) fn vertical_force(nodes: impl Iterator<Item = (f64, f64, f64)>) -> f64 {
    nodes.map(|(w, p, n)| -w * p * n).sum()
}

pub mod cylinder;
pub mod sphere;

pub use cylinder::{
    HertzLine, HertzRun, HertzScene, ProfileNode, DEFAULT_APPROACH, DEFAULT_ARC_CELLS,
};
pub use sphere::{
    HertzContact, HertzPoint, HertzSphereRun, HertzSphereScene, SphereNode,
    DEFAULT_SPHERE_APPROACH, DEFAULT_SPHERE_CELLS,
};

/// The contact modulus `E*` of two bodies: `1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2`
/// (Johnson 1985, eq. 4.22).
pub fn contact_modulus(a: &ElasticMaterial, b: &ElasticMaterial) -> f64 {
    let c = |m: &ElasticMaterial| (1.0 - m.poisson_ratio.powi(2)) / m.youngs_modulus;
    1.0 / (c(a) + c(b))
}

/// The size of the first cell of [`graded_points`](mortar::generate::graded_points) over
/// `length` with `cells` cells and the grading `grading`, to first order:
/// `length ln(g) / ((g - 1) cells)` (`length / cells` for `g = 1`).
pub(crate) fn first_cell(length: f64, cells: f64, grading: f64) -> f64 {
    let slope = if grading > 1.0 + 1e-12 {
        grading.ln() / (grading - 1.0)
    } else {
        1.0
    };
    length * slope / cells
}

/// The assembled scene (see [`HertzScene::build`] and [`HertzSphereScene::build`]): what
/// [`solve_contact`](mortar_physics::contact::solve_contact) takes.
#[derive(Debug, Clone)]
pub struct HertzProblem {
    /// The cylinder or sphere (slave) and the block (master).
    pub bodies: [ElasticBody; 2],
    /// Their stiffness matrices.
    pub stiffness: [SparseMatrix; 2],
    /// Their load vectors (zero: the load is the prescribed approach).
    pub load: [Vec<f64>; 2],
    /// Their Dirichlet unknowns and values.
    pub dirichlet: [(Vec<u32>, Vec<f64>); 2],
    /// The mortar coupling of the curved surface (slave) and the block's top (master).
    pub tie: Tie,
    /// The weighted normal gap.
    pub gap: NormalGap,
    /// The exact complementarity law with automatic `c`.
    pub law: ContactComplementarity,
    /// The block's cells per direction.
    pub block_cells: usize,
}

/// Two bodies' assembly: their stiffness matrices, load vectors and Dirichlet data.
type Assembly = ([SparseMatrix; 2], [Vec<f64>; 2], [(Vec<u32>, Vec<f64>); 2]);

/// Two elastic bodies in contact across the mortar tie of their surfaces (the interface under
/// `tolerances`, coupled as `coupling` says), assembled in `dim` dimensions: their assembly,
/// the tie, the normal gap and the exact law's automatic parameter `c`. The Hertz scenes and
/// the shrink fit share it.
///
/// # Errors
/// The errors of the interface, the coupling, the tie, the assembly and the gap.
pub(crate) fn exact_contact(
    [slave, master]: [&ElasticBody; 2],
    [slave_surface, master_surface]: [SurfaceMesh; 2],
    tolerances: Tolerances,
    coupling: &CouplingOptions,
    dim: usize,
) -> Result<(Assembly, Tie, NormalGap, f64), PhysicsError> {
    let interface = Interface::with_tolerances(slave_surface, master_surface, tolerances)?;
    let coupling = assemble_coupling(&interface, coupling)?;
    let tie = Tie::from_coupling(&slave.mesh, &master.mesh, interface, coupling)?;

    let options = ElasticOptions::default();
    let stiffness = [
        assemble_elastic_stiffness(slave, &options)?,
        assemble_elastic_stiffness(master, &options)?,
    ];
    let load = [
        assemble_elastic_load(slave, &options)?,
        assemble_elastic_load(master, &options)?,
    ];
    let dirichlet = [slave.dirichlet_dofs(), master.dirichlet_dofs()];
    let gap = NormalGap::new(&tie, dim, slave.mesh.node_count(), master.mesh.node_count())?;
    let c = automatic_complementarity(&stiffness[0], &tie, &gap, dim);
    Ok(((stiffness, load, dirichlet), tie, gap, c))
}

impl HertzProblem {
    /// The problem of a Hertz scene's bodies: the slave's group `contact` coupled to the
    /// master's group `top` (full coverage of the slave surface required, whatever `coupling`
    /// says; candidates searched within `search_distance`), both bodies assembled in `dim`
    /// dimensions, the normal gap and the exact law with automatic `c`.
    ///
    /// # Errors
    /// The errors of the bodies' groups, of the interface, the coupling, the tie and the
    /// assembly.
    pub(crate) fn of_bodies(
        [slave, master]: [SceneBody; 2],
        search_distance: f64,
        coupling: &CouplingOptions,
        dim: usize,
        block_cells: usize,
    ) -> Result<Self, PhysicsError> {
        let (slave, slave_surface) = slave.elastic("contact")?;
        let (master, master_surface) = master.elastic("top")?;
        let tolerances = Tolerances {
            search_radius: SearchRadius::Distance(search_distance),
            ..Tolerances::default()
        };
        let mut coupling_options = coupling.clone();
        coupling_options.require_full_coverage = true;
        let surfaces = [slave_surface, master_surface];
        let (assembly, tie, gap, c) = exact_contact(
            [&slave, &master],
            surfaces,
            tolerances,
            &coupling_options,
            dim,
        )?;
        Self::with_law([slave, master], assembly, tie, gap, c, block_cells)
    }

    /// The problem of its parts: the bodies, their assembly (stiffness matrices, loads,
    /// Dirichlet data), the tie and the normal gap, with the exact law of parameter `c`.
    ///
    /// # Errors
    /// The error of [`ContactComplementarity::try_new`] for a `c` it refuses.
    fn with_law(
        bodies: [ElasticBody; 2],
        (stiffness, load, dirichlet): Assembly,
        tie: Tie,
        gap: NormalGap,
        c: f64,
        block_cells: usize,
    ) -> Result<Self, PhysicsError> {
        Ok(Self {
            bodies,
            stiffness,
            load,
            dirichlet,
            tie,
            gap,
            law: ContactComplementarity::try_new(c)?,
            block_cells,
        })
    }

    /// The problem a Hertz scene's [scene file](HertzScene::scene_files) was solved as, and
    /// its solution: the bodies, matrices and tie the scene file's run built (the block's
    /// cells per direction `block_cells` given, as the run does not know them).
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] if the scene was not solved with the exact law.
    pub fn from_solved(
        solved: SolvedContact,
        block_cells: usize,
    ) -> Result<(Self, ContactSolution), PhysicsError> {
        let SolvedContact {
            bodies,
            tie,
            solution,
            stiffness,
            load,
            dirichlet,
            gap,
            complementarity,
            ..
        } = solved;
        let c = complementarity.ok_or_else(|| PhysicsError::InvalidInput {
            body: "hertz scene".into(),
            what: "solved with another law than the exact one".into(),
        })?;
        let problem = Self::with_law(
            bodies,
            (stiffness, load, dirichlet),
            tie,
            gap,
            c,
            block_cells,
        )?;
        Ok((problem, solution))
    }

    /// Solves the contact problem.
    ///
    /// # Errors
    /// The errors of [`solve_contact`](mortar_physics::contact::solve_contact).
    pub fn solve(&self, options: &ContactOptions) -> Result<ContactSolution, PhysicsError> {
        self.solve_on(options, None)
    }

    /// [`solve`](Self::solve) with the Newton systems solved by `backend` when given (PETSc's
    /// Krylov methods, say), told the bodies' node coordinates ([`solve_contact_on`]).
    ///
    /// # Errors
    /// The errors of [`solve_contact_on`].
    pub fn solve_on(
        &self,
        options: &ContactOptions,
        backend: Option<&dyn SparseSolver>,
    ) -> Result<ContactSolution, PhysicsError> {
        let (k, f, dir) = (&self.stiffness, &self.load, &self.dirichlet);
        let linear = backend.map_or_else(LinearSolve::default, |b| {
            LinearSolve::on(
                b,
                [self.bodies[0].mesh.coords(), self.bodies[1].mesh.coords()],
            )
        });
        solve_contact_on(
            [&k[0], &k[1]],
            [&f[0], &f[1]],
            [(&dir[0].0, &dir[0].1), (&dir[1].0, &dir[1].1)],
            &self.gap,
            &self.law,
            options,
            linear,
        )
    }

    /// The reaction `sum (K u - f)` over the Dirichlet unknowns of component `component` of
    /// body `body` (0 the slave, 1 the master) at the nodes for which `select` is true: the
    /// force the body exerts on its supports there, along the axis.
    pub fn reaction(
        &self,
        solution: &ContactSolution,
        body: usize,
        component: usize,
        select: impl Fn(&Vector3<f64>) -> bool,
    ) -> f64 {
        let dim = self.gap.dim;
        let (k, f, u) = (
            &self.stiffness[body],
            &self.load[body],
            &solution.displacements[body],
        );
        let coords = self.bodies[body].mesh.coords();
        self.dirichlet[body]
            .0
            .iter()
            .filter(|&&dof| dof as usize % dim == component && select(&coords[dof as usize / dim]))
            .map(|&dof| {
                let row = k
                    .outer_view(dof as usize)
                    .expect("row of a Dirichlet unknown");
                row.iter().map(|(j, v)| v * u[j]).sum::<f64>() - f[dof as usize]
            })
            .sum()
    }
}

/// The extent of the computed contact zone from the nodal pressures: the half-width (2D) or
/// the contact radius (3D). With the slave nodes ordered by their distance from the first
/// point of contact (the abscissa in 2D, the distance from the axis in 3D), the last node in
/// contact (positive pressure) and the next one (zero pressure) bracket it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HalfWidth {
    /// The estimate compared with `a`: the midpoint of the bracket, within half the edge's
    /// element of any half-width in the bracket; no assumption on the profile.
    pub estimate: f64,
    /// The distance of the last node with positive pressure.
    pub last_in_contact: f64,
    /// The distance of the next node, the first with zero pressure beyond every node in
    /// contact: the extent of the positive pressure of the piecewise linear interpolant (in
    /// 2D; in 3D along the rays of the nodes).
    pub first_open: f64,
    /// The zero of `p^2` extrapolated linearly in `x^2` through the last two nodes in
    /// contact at different distances, kept in the bracket: exact for the elliptical (2D) and ellipsoidal (3D)
    /// profiles, so it assumes them (reported, not the estimate).
    pub squared: f64,
    /// Whether the nodes in contact are the first ones, no open node among them (in 3D: no
    /// open node nearer the axis than a node in contact).
    pub contiguous: bool,
}

impl HalfWidth {
    /// The extent of the contact zone of the nodal profile `profile`: `(distance, pressure)`
    /// per slave node, ordered by distance (the first node at the point of first contact).
    ///
    /// # Panics
    /// If `profile` is empty.
    pub fn of_profile(profile: &[(f64, f64)]) -> Self {
        let k = profile.iter().rposition(|n| n.1 > 0.0).unwrap_or(0);
        let contiguous = profile[..=k].iter().all(|n| n.1 > 0.0);
        let lo = profile[k].0;
        let hi = profile.get(k + 1).map_or(lo, |n| n.0);
        // The previous node in contact nearer the first contact (in 3D, nodes symmetric
        // about the diagonal share their distance).
        let nearer = |n: &(f64, f64)| n.1 > 0.0 && n.0 < profile[k].0 * (1.0 - 1e-9);
        let squared = match profile[..k].iter().rposition(nearer) {
            None => 0.5 * (lo + hi),
            Some(i) => {
                let ((xa, pa), (xb, pb)) = (profile[i], profile[k]);
                let a2 = xb * xb + pb.powi(2) * (xb * xb - xa * xa) / (pa.powi(2) - pb.powi(2));
                if a2.is_finite() {
                    a2.max(0.0).sqrt().clamp(lo, hi)
                } else {
                    hi
                }
            }
        };
        Self {
            estimate: 0.5 * (lo + hi),
            last_in_contact: lo,
            first_open: hi,
            squared,
            contiguous,
        }
    }

    /// Whether `a` lies in the bracket.
    pub fn brackets(&self, a: f64) -> bool {
        self.last_in_contact <= a && a <= self.first_open
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bracket_holds_the_edge_of_the_positive_pressures() {
        // The elliptical profile of a = 0.35 at nodes 0, 0.1, ...: the last node in contact is
        // 0.3, the next 0.4; p^2 is linear in x^2, so the extrapolation is exact.
        let p = |x: f64| (1.0 - (x / 0.35f64).powi(2)).max(0.0).sqrt();
        let nodes: Vec<(f64, f64)> = (0..6)
            .map(|i| (0.1 * i as f64, p(0.1 * i as f64)))
            .collect();
        let h = HalfWidth::of_profile(&nodes);
        assert_eq!(
            (h.last_in_contact, h.first_open),
            (0.30000000000000004, 0.4)
        );
        assert!((h.estimate - 0.35).abs() < 1e-12 && h.contiguous && h.brackets(0.35));
        assert!((h.squared - 0.35).abs() < 1e-12, "{}", h.squared);
        // Nodes at the same distance (3D: symmetric about the diagonal) are passed over by the
        // extrapolation; an open node inside the zone breaks contiguity.
        let mut twins = nodes.clone();
        twins.insert(4, nodes[3]);
        twins[1].1 = 0.0;
        let t = HalfWidth::of_profile(&twins);
        assert!((t.squared - 0.35).abs() < 1e-12 && !t.contiguous, "{t:?}");
    }
}
