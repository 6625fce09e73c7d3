//! The traits a user implements to extend the toolkit, in one place, each with an example
//! that compiles and runs. Every piece of the coupling and of the physics is one of
//! them, and the library's own implementations go through the same doors:
//!
//! | trait | what it adds | where it plugs in |
//! | --- | --- | --- |
//! | [`ReferenceElement`], [`SurfaceElement`] | an interface face type | [`SurfaceMesh::add_face`](crate::SurfaceMesh::add_face), the Gmsh reader through an [`ElementRegistry`] |
//! | [`VolumeElement`] | a cell type of a body | [`VolumeMesh::add_cell`](crate::VolumeMesh::add_cell) |
//! | [`MultiplierSpace`] | a Lagrange multiplier basis | [`CouplingOptions::multipliers`] |
//! | [`IntegrationStrategy`] | how a slave face is integrated against its partners | [`CouplingOptions::integration`] |
//! | [`Projector`] | the projection direction field | [`CouplingOptions::projector`] |
//! | [`ConstraintLaw`] | a pointwise interface law (tying, gap conductance, contact) | the heat, contact and thermomechanical problems; [`DynLaw`] and [`LawRegistry`] for run-time choice and scene files |
//! | [`RelocationModel`] | a fuel pellet's relocation strain | the pellet scene's `[model] relocation`, through [`LawRegistry::register_relocation`] |
//! | [`NewtonProblem`] | a nonlinear problem for [`newton`](crate::physics::nonlinear::newton) | the solvers (Newton, JFNK) |
//! | [`Preconditioner`], [`LinearOperator`] | a preconditioner or operator for GMRES | [`gmres`](crate::core::linalg::gmres), JFNK |
//!
//! A multiplier space, a projector or an integration strategy of one's own implements its
//! mathematical methods only (the basis on a face, the direction at a point, the paired rule
//! of a face), as below, and gets the D and M of the shipped one it imitates, to round-off.
//! The coupling's fast paths are the library's business: it recognises
//! [`SegmentBased`](crate::core::integration::SegmentBased) by its type for its fused
//! kernels, and reads the few facts it cannot find itself (a diagonal D, an affine or uniform
//! direction, candidates that may be split) from each trait's one optional method,
//! `fast_paths`, whose default `None` claims nothing and is always correct. A plug-in that
//! knows such facts may state them there ([`MultiplierFastPaths`], [`ProjectorFastPaths`],
//! [`IntegrationFastPaths`]); the shipped ones do.
//!
//! **A multiplier space of one's own**: here a dual basis under another name (a real one
//! would build its own coefficients in [`MultiplierSpace::basis`]). It gives the shipped dual
//! space's D and M; only the shipped one states that D is diagonal
//! ([`MultiplierFastPaths::diagonal_d`]), so that its coupling also folds D's round-off off
//! the diagonal into it:
//!
//! ```
//! use std::sync::Arc;
//! use mortar::core::interface::FaceGeometry;
//! use mortar::core::multiplier::{DualMultipliers, LmBasis};
//! use mortar::extend::MultiplierSpace;
//! use mortar::generate::{square_quads, square_triangles, Diagonal};
//! use mortar::{assemble_coupling, CouplingOptions, Interface, Tolerances};
//!
//! #[derive(Debug)]
//! struct MyDual;
//! impl MultiplierSpace for MyDual {
//!     fn name(&self) -> &'static str {
//!         "my dual"
//!     }
//!     fn basis(&self, face: &FaceGeometry, tol: &Tolerances) -> mortar::core::Result<LmBasis> {
//!         DualMultipliers.basis(face, tol)
//!     }
//! }
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let slave = square_triangles(4, Diagonal::Main, 0.0, false, 1)?;
//! let master = square_quads(5, 0.0, true, 1)?;
//! let interface = Interface::new(slave, master)?;
//! let options = CouplingOptions { multipliers: Arc::new(MyDual), ..Default::default() };
//! let c = assemble_coupling(&interface, &options)?;
//! assert!((c.stats.area - 1.0).abs() < 1e-12);
//! // Dual: D is diagonal, to round-off.
//! for (j, row) in c.d.outer_iterator().enumerate() {
//!     let diagonal = row.get(j).copied().unwrap_or(0.0);
//!     assert!(row.iter().all(|(k, v)| k == j || v.abs() < 1e-12 * diagonal));
//! }
//! // The shipped dual space's D and M, to round-off.
//! let shipped = assemble_coupling(&interface, &CouplingOptions::default().dual())?;
//! let (d, m) = (&c.d - &shipped.d, &c.m - &shipped.m);
//! assert!(d.data().iter().chain(m.data()).all(|v| v.abs() < 1e-15));
//! # Ok(()) }
//! ```
//!
//! **A projector of one's own**: project along the fixed direction `+z` (for flat interfaces
//! in the plane `z = const`, the exact normal). It states no facts of its field, so the
//! search inflates its slave faces' boxes by `Tolerances::search_inflation` as a margin (a
//! projector whose directions are always convex combinations of a face's nodal normals may
//! say so, [`ProjectorFastPaths::within_nodal_normals`], for exact boxes):
//!
//! ```
//! use std::sync::Arc;
//! use mortar::core::interface::FaceGeometry;
//! use mortar::extend::Projector;
//! use mortar::generate::{square_quads, square_triangles, Diagonal};
//! use mortar::{assemble_coupling, CouplingOptions, Interface};
//! use nalgebra::{Vector2, Vector3};
//!
//! #[derive(Debug)]
//! struct AlongZ;
//! impl Projector for AlongZ {
//!     fn name(&self) -> &'static str {
//!         "along z"
//!     }
//!     fn direction(&self, _: &FaceGeometry, _: &Vector2<f64>) -> (Vector3<f64>, [Vector3<f64>; 2]) {
//!         (Vector3::z(), [Vector3::zeros(), Vector3::zeros()])
//!     }
//! }
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let slave = square_triangles(3, Diagonal::Main, 0.0, false, 1)?;
//! let master = square_quads(4, 0.0, true, 1)?;
//! let options = CouplingOptions { projector: Arc::new(AlongZ), ..Default::default() };
//! let c = assemble_coupling(&Interface::new(slave, master)?, &options)?;
//! assert!((c.stats.area - 1.0).abs() < 1e-12);
//! assert!(c.stats.slave_box_inflation > 0.0);
//! # Ok(()) }
//! ```
//!
//! **An integration strategy of one's own**: here the shipped segmentation behind a count of
//! the slave faces it integrates. The coupling hands it every face (its fused kernels are for
//! [`SegmentBased`](crate::core::integration::SegmentBased) itself), and it gives the same D
//! and M, to round-off:
//!
//! ```
//! use std::sync::atomic::{AtomicUsize, Ordering};
//! use std::sync::Arc;
//! use mortar::core::integration::{PairedRule, SegmentBased, SegmentContext};
//! use mortar::core::interface::FaceGeometry;
//! use mortar::extend::IntegrationStrategy;
//! use mortar::generate::half_circle_mesh;
//! use mortar::{assemble_coupling, CouplingOptions, Interface};
//!
//! #[derive(Debug, Default)]
//! struct Counted(AtomicUsize);
//! impl IntegrationStrategy for Counted {
//!     fn name(&self) -> String {
//!         "segment-based, counted".into()
//!     }
//!     fn paired_rule_into(
//!         &self,
//!         ctx: &SegmentContext<'_>,
//!         slave: &FaceGeometry,
//!         candidates: &[u32],
//!         out: &mut PairedRule,
//!     ) -> mortar::core::Result<()> {
//!         self.0.fetch_add(1, Ordering::Relaxed);
//!         SegmentBased::default().paired_rule_into(ctx, slave, candidates, out)
//!     }
//! }
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let (slave, master) = (half_circle_mesh(40, false, 1)?, half_circle_mesh(61, true, 1)?);
//! let interface = Interface::new(slave, master)?;
//! let counted = Arc::new(Counted::default());
//! let options = CouplingOptions { integration: counted.clone(), ..Default::default() };
//! let c = assemble_coupling(&interface, &options)?;
//! assert_eq!(counted.0.load(Ordering::Relaxed), 40);
//! let shipped = assemble_coupling(&interface, &CouplingOptions::default())?;
//! assert_eq!(shipped.stats.fused_line_faces, 40);
//! let (d, m) = (&c.d - &shipped.d, &c.m - &shipped.m);
//! assert!(d.data().iter().chain(m.data()).all(|v| v.abs() < 1e-15));
//! # Ok(()) }
//! ```
//!
//! **A constraint law of one's own**, its tangent for free (dual numbers) and checked, then
//! chosen at run time by name:
//!
//! ```
//! use mortar::extend::{check_tangent, ConstraintLaw, DynLaw, Float, LawPoint, LawRegistry};
//!
//! /// A linear spring across the gap: pressure = k (xi - g) below xi.
//! struct Spring { k: f64, xi: f64 }
//! impl ConstraintLaw for Spring {
//!     fn residual<S: Float>(&self, p: LawPoint<S>) -> S {
//!         let (k, xi) = (S::from(self.k).unwrap(), S::from(self.xi).unwrap());
//!         p.multiplier - k * (xi - p.gap).max(S::zero())
//!     }
//! }
//!
//! let check = check_tangent(&Spring { k: 1e12, xi: 5e-6 }, LawPoint::new(2e-6, 1e6, 600.0)).unwrap();
//! assert!(check.max_relative_error < 1e-6);
//! let mut registry = LawRegistry::with_shipped();
//! registry.register("spring", |p| {
//!     Ok(DynLaw::new("spring", Spring { k: p["k"], xi: p["xi"] }))
//! });
//! let params = [("k".to_string(), 1e12), ("xi".to_string(), 5e-6)].into();
//! assert_eq!(registry.make("spring", &params).unwrap().name(), "spring");
//! ```
//!
//! **A nonlinear problem of one's own** for the library's Newton (with its line search and
//! convergence test): `x^3 = 8`.
//!
//! ```
//! use mortar::extend::NewtonProblem;
//! use mortar::physics::nonlinear::{newton, NewtonOptions};
//! use mortar::physics::PhysicsError;
//!
//! struct Cube;
//! impl NewtonProblem for Cube {
//!     fn residual(&self, x: &[f64], r: &mut [f64]) -> Result<(), PhysicsError> {
//!         r[0] = x[0].powi(3) - 8.0;
//!         Ok(())
//!     }
//!     fn solve_linearized(&mut self, x: &[f64], r: &[f64], dx: &mut [f64], _: f64) -> Result<usize, PhysicsError> {
//!         dx[0] = r[0] / (3.0 * x[0] * x[0]);
//!         Ok(1)
//!     }
//! }
//! let mut x = [1.0];
//! newton(&mut Cube, &mut x, &NewtonOptions::default()).unwrap();
//! assert!((x[0] - 2.0).abs() < 1e-12);
//! ```
//!
//! **Elements and laws of one's own everywhere**: a [`Registries`] gathers the surface
//! elements, the cells and the laws a program knows; the scene files (`mortar-scenes`:
//! `TiedHeatSpec::run_with`, `ContactSpec::run_with`, the pellet's `run_from_toml_with`) and
//! the whole command line (`mortar-app`: `cli::main_with`, `couple` and `run`) take it, so a
//! program's own `main` is `mortar_app::cli::main_with(registries)` (see
//! `examples/extend_element.rs`).
//!
//! The property-test helpers for one's own elements and laws are in `mortar::testing`
//! (feature `proptest-support`; documented on docs.rs).

pub use mortar_core::element::{ReferenceElement, SurfaceElement};
pub use mortar_core::integration::{IntegrationFastPaths, IntegrationStrategy};
pub use mortar_core::multiplier::{MultiplierFastPaths, MultiplierSpace};
pub use mortar_core::projector::{Projector, ProjectorFastPaths};
pub use mortar_core::CouplingOptions;
pub use mortar_elements::volume::VolumeRegistry;
pub use mortar_elements::ElementRegistry;
pub use mortar_fem::element::VolumeElement;
pub use mortar_fem::linalg::{LinearOperator, Preconditioner};
pub use mortar_physics::laws::{
    check_tangent, ConstraintLaw, DynLaw, Float, LawPoint, LawRegistry, ObjectLaw, RelocationInput,
    RelocationModel,
};
pub use mortar_physics::nonlinear::NewtonProblem;

/// The element types and laws a program knows, by Gmsh type and by name: what the Gmsh
/// readers, the scene files and the command line (`mortar_app::cli::main_with`) look elements and
/// laws up in. [`Registries::default`] holds the shipped ones; add a program's own with the
/// registries' `register`.
///
/// ```
/// use mortar::extend::Registries;
///
/// let registries = Registries::default();
/// assert!(registries.elements.by_gmsh_type(2).is_some()); // Tri3 faces
/// assert!(registries.cells.by_gmsh_type(4, 3).is_some()); // Tet4 cells
/// assert!(registries.laws.names().contains(&"exponential_contact"));
/// ```
#[derive(Debug, Clone)]
pub struct Registries {
    /// Surface (interface) elements, for [`read_gmsh_surface`](crate::io::read_gmsh_surface)
    /// and `mortar couple`.
    pub elements: ElementRegistry,
    /// Cells of the bodies, for [`read_gmsh_volume`](crate::io::read_gmsh_volume) and the scene
    /// files; a cell's boundary faces are the surface elements its
    /// [`face_element`](VolumeElement::face_element) names.
    pub cells: VolumeRegistry,
    /// Interface laws, for the scene files' `[laws]` and `named_law` tables.
    pub laws: LawRegistry,
}

impl Default for Registries {
    /// The shipped elements (Line2, Tri3, Quad4), cells (Tri3, Quad4, Tet4, Hex8) and laws
    /// ([`LawRegistry::with_shipped`]).
    fn default() -> Self {
        Self {
            elements: ElementRegistry::new(),
            cells: VolumeRegistry::new(),
            laws: LawRegistry::with_shipped(),
        }
    }
}
