//! Assembly of a body's elasticity: the stiffness `K = int B^T C B`, the load (body force,
//! tractions, thermal strain) and the thermal load operator `G`, in parallel over fixed chunks
//! of cells merged in order (the same bits for any thread count).

use mortar_core::linalg::{PartList, SparseMatrix, Triplets};
use mortar_core::ModelGeometry;
use mortar_fem::element::{CellValues, MAX_CELL_NODES};
use nalgebra::Vector3;
use rayon::prelude::*;

use super::body::ElasticBody;
use crate::error::PhysicsError;
use crate::field::cells;

pub(crate) use crate::field::cells::CELL_CHUNK;

/// The largest number of unknowns of one cell (a 27-node cell in 3D).
const MAX_CELL_DOFS: usize = 3 * MAX_CELL_NODES;

/// Assembly settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ElasticOptions {
    /// The quadrature degree on the cells and traction faces; `None` uses `2 p` for each
    /// cell's (face's) shape functions of degree `p`: exact for the stiffness of affine cells
    /// (Tri3, Tet4, parallelogram Quad4, parallelepiped Hex8) and, for Quad4 and Hex8, more
    /// than the usual full (2 x 2, 2 x 2 x 2) Gauss integration.
    pub quadrature_degree: Option<u32>,
    /// What the mesh models ([`ModelGeometry`]): [`Cartesian`](ModelGeometry::Cartesian) (the
    /// default: a 3D body, or a 2D plane-strain slice of unit thickness) or
    /// [`Axisymmetric`](ModelGeometry::Axisymmetric): a 2D mesh in the plane `z = 0` is the
    /// r-z section of a body of revolution (`x = r >= 0`, `y = z`, torsionless), with the
    /// unknowns `(u_r, u_z)` as components `(x, y)`. The strains are
    /// `eps_rr = du_r/dr`, `eps_zz = du_z/dz`, the hoop strain `eps_tt = u_r / r` and
    /// `gamma_rz = du_r/dz + du_z/dr`, with the 4 x 4 isotropic `C`; the thermal strain
    /// `alpha (T - T_ref)` in all three normal components; every integral (stiffness, body
    /// force, thermal load, tractions) takes the weight `2 pi r` (forces over the full
    /// revolution, tractions per unit area of the revolved surface). Quadrature points lie
    /// inside the cells, so `1 / r` is finite; a node on the axis (`x = 0`, within
    /// [`ModelGeometry::axis_tolerance`]) must have `u_r = 0` prescribed (a condition on
    /// component x), or the assemblies refuse the body
    /// ([`PhysicsError::AxisNodeFree`](crate::PhysicsError::AxisNodeFree)).
    /// [`recover_stress`](super::recover_stress) puts the hoop stress `sigma_tt` in the `zz`
    /// slot of the Voigt order (r -> x, z -> y, theta -> z).
    pub geometry: ModelGeometry,
}

impl ElasticOptions {
    /// These options with the geometry `geometry`.
    pub fn with_geometry(mut self, geometry: ModelGeometry) -> Self {
        self.geometry = geometry;
        self
    }

    /// The degree for shape functions of degree `p`.
    pub(crate) fn degree(&self, p: u32) -> u32 {
        self.quadrature_degree.unwrap_or(2 * p)
    }
}

/// Assembles the stiffness matrix `K = int B^T C B` of a body (symmetric, bit for bit), with
/// `C` the isotropic elasticity matrix of the material: in index form
/// `K[(a,i),(b,j)] = int lambda dN_a/dx_i dN_b/dx_j + mu (dN_a/dx_j dN_b/dx_i
/// + delta_ij grad N_a . grad N_b)`. Rows and columns are numbered by the body's
/// [`layout`](ElasticBody::layout), `node * dim + component`. In 2D this is plane strain
/// (the out-of-plane strains are zero; `sigma_zz` is not an unknown).
///
/// Parallel over fixed chunks of cells merged in order: the matrix is the same bit for bit
/// whatever the thread count.
///
/// Fully integrated bilinear and trilinear cells (Quad4, Hex8, no reduced integration or
/// incompatible modes) represent linear displacement fields exactly (they pass the patch
/// test) but lock in bending (parasitic shear): a coarse mesh of them is much too stiff for a
/// slender part loaded in bending. The constant-strain Tri3 and Tet4 are stiffer still, and
/// every cell here locks volumetrically as nu approaches 0.5. Refine through the thickness.
///
/// In the axisymmetric geometry ([`ElasticOptions::geometry`]) the hoop strain adds, for the
/// radial components (`i = 0`, `h_a = N_a / r`), `lambda (dN_a/dx_i h_b + h_a dN_b/dx_j)
/// + (lambda + 2 mu) h_a h_b` to the integrand (the terms of `h` present only for a radial
/// component), and the measure is `2 pi r dr dz`.
///
/// # Errors
/// [`PhysicsError::InvalidInput`] for bad material data, a quadrature degree out of range or
/// an axisymmetric 3D mesh, [`PhysicsError::NegativeRadius`] and
/// [`PhysicsError::AxisNodeFree`] for an axisymmetric mesh with a node at `x < 0`, or on the
/// axis without a prescribed `u_r`, [`PhysicsError::InvertedCell`] for a cell with a
/// non-positive Jacobian determinant (the first in cell order); see also
/// [`ElasticBody::check`].
pub fn assemble_elastic_stiffness(
    body: &ElasticBody,
    options: &ElasticOptions,
) -> Result<SparseMatrix, PhysicsError> {
    check(body, options)?;
    let dim = body.layout().components;
    let (lambda, mu) = body.material.lame();
    let axi = options.geometry.is_axisymmetric();
    assemble_cell_matrix(body, options, dim, dim, |cv, nn, ke| {
        let m = nn * dim;
        for q in 0..cv.len() {
            let (g, w) = (cv.gradients(q), cells::weight(cv, q, options.geometry));
            let (n, inv_r) = (cv.shape(q), hoop_factor(cv, q, axi));
            for a in 0..nn {
                for b in 0..nn {
                    // Each product is formed symmetrically in (a, i) <-> (b, j), so that the
                    // element matrix is symmetric bit for bit.
                    let gab = mu * g[a].dot(&g[b]);
                    for i in 0..dim {
                        let row = (a * dim + i) * m + b * dim;
                        for j in 0..dim {
                            let mut v = lambda * (g[a][i] * g[b][j]) + mu * (g[a][j] * g[b][i]);
                            if i == j {
                                v += gab;
                            }
                            if axi {
                                // The hoop strains of (a, i) and (b, j).
                                let ha = if i == 0 { n[a] * inv_r } else { 0.0 };
                                let hb = if j == 0 { n[b] * inv_r } else { 0.0 };
                                v += lambda * (g[a][i] * hb + ha * g[b][j])
                                    + (lambda + 2.0 * mu) * (ha * hb);
                            }
                            ke[row + j] += v * w;
                        }
                    }
                }
            }
        }
    })
}

/// Assembles the load vector of a body (numbered by its [`layout`](ElasticBody::layout)):
///
/// - the body force, `f[(a,i)] += int b_i N_a`;
/// - the thermal strain `eps_th = alpha (T - T_ref) I` of the body's temperature field,
///   `f[(a,i)] += int (C eps_th) : (e_i grad N_a) = int 3 K alpha (T - T_ref) dN_a/dx_i`
///   (`3 K = E / (1 - 2 nu)`; in plane strain the constrained `eps_zz` makes the in-plane
///   free expansion `(1 + nu) alpha dT`; in the axisymmetric geometry the radial component
///   gains the hoop term, `int 3 K alpha (T - T_ref) (dN_a/dr + N_a / r)`);
/// - the body's eigenstrain `eps*` ([`ElasticBody::eigenstrain`]),
///   `f[(a,i)] += int (C eps*)_ij dN_a/dx_j` (in the axisymmetric geometry the radial
///   component gains `int (C eps*)_tt N_a / r`);
/// - the tractions, `f[(a,i)] += int_faces t_i N_a` (per unit length in 2D; per unit area of
///   the revolved surface, with the weight `2 pi r`, in the axisymmetric geometry).
///
/// Every cell integral takes the weight `2 pi r` in the axisymmetric geometry
/// ([`ElasticOptions::geometry`]).
///
/// The cell terms are computed in parallel over fixed chunks of cells and summed in order
/// (bit-for-bit the same for any thread count).
///
/// # Errors
/// As [`assemble_elastic_stiffness`].
pub fn assemble_elastic_load(
    body: &ElasticBody,
    options: &ElasticOptions,
) -> Result<Vec<f64>, PhysicsError> {
    check(body, options)?;
    let mut f = vec![0.0; body.layout().len()];
    let loads = CellLoads::new(body, options);
    if loads.any() {
        for ch in loads.chunks() {
            for (d, v) in ch? {
                f[d as usize] += v;
            }
        }
    }
    add_tractions(body, options, &mut f)?;
    Ok(f)
}

/// The cell terms of [`assemble_elastic_load`]: the body force, the thermal strain of the
/// body's temperature field (when it gives a stress) and the eigenstrain.
struct CellLoads<'a> {
    body: &'a ElasticBody,
    options: &'a ElasticOptions,
    /// `3 K alpha`.
    beta: f64,
    t_ref: f64,
    /// The temperature field, when it gives a thermal stress.
    thermal: Option<&'a [f64]>,
    /// The eigenstress `C eps*` as a tensor (the hoop component apart in r-z).
    eigen: Option<[[f64; 3]; 3]>,
}

impl<'a> CellLoads<'a> {
    fn new(body: &'a ElasticBody, options: &'a ElasticOptions) -> Self {
        let beta = body.material.thermal_stress_coefficient();
        Self {
            body,
            options,
            beta,
            t_ref: body.material.reference_temperature,
            thermal: body.temperature.as_deref().filter(|_| beta != 0.0),
            eigen: body
                .eigenstrain
                .map(|e| voigt_tensor(&body.material.stress(&e, 0.0))),
        }
    }

    /// Whether there is any cell term.
    fn any(&self) -> bool {
        self.body.body_force.is_some() || self.thermal.is_some() || self.eigen.is_some()
    }

    /// The cells' `(unknown, value)` terms, in parallel over fixed chunks of cells, in cell
    /// order.
    fn chunks(&self) -> Vec<Result<Vec<(u32, f64)>, PhysicsError>> {
        let (mesh, layout) = (&self.body.mesh, self.body.layout());
        let dim = layout.components;
        let cells = mesh.cell_count();
        (0..cells.div_ceil(CELL_CHUNK))
            .into_par_iter()
            .map(|ch| {
                let mut out = Vec::new();
                let mut cv = CellValues::new();
                let mut x = [Vector3::zeros(); MAX_CELL_NODES];
                let mut fe = [0.0; MAX_CELL_DOFS];
                let mut dt = [0.0; MAX_CELL_NODES];
                for c in ch * CELL_CHUNK..((ch + 1) * CELL_CHUNK).min(cells) {
                    let cell = mesh.cell(c);
                    let nn = reinit_cell(self.body, self.options, c, &mut cv, &mut x)?;
                    fe[..nn * dim].fill(0.0);
                    if let Some(t) = self.thermal {
                        for (d, &n) in dt.iter_mut().zip(cell.nodes) {
                            *d = t[n as usize] - self.t_ref;
                        }
                    }
                    for q in 0..cv.len() {
                        self.point(&cv, q, nn, &dt, &mut fe);
                    }
                    for (a, &na) in cell.nodes.iter().enumerate() {
                        for i in 0..dim {
                            out.push((layout.dof(na, i), fe[a * dim + i]));
                        }
                    }
                }
                Ok(out)
            })
            .collect()
    }

    /// Adds the terms of quadrature point `q` of a cell of `nn` nodes (`cv`, nodal
    /// temperature differences `dt`) to its load `fe`: body force, thermal strain,
    /// eigenstrain, in this order.
    fn point(&self, cv: &CellValues, q: usize, nn: usize, dt: &[f64], fe: &mut [f64]) {
        let dim = self.body.layout().components;
        let axi = self.options.geometry.is_axisymmetric();
        let (n, w) = (cv.shape(q), cells::weight(cv, q, self.options.geometry));
        if let Some(force) = &self.body.body_force {
            let b = force(&cv.point(q)) * w;
            for a in 0..nn {
                for i in 0..dim {
                    fe[a * dim + i] += b[i] * n[a];
                }
            }
        }
        if self.thermal.is_some() {
            let s = self.beta * cv.value(q, &dt[..nn]) * w;
            let g = cv.gradients(q);
            for a in 0..nn {
                for i in 0..dim {
                    fe[a * dim + i] += s * g[a][i];
                }
            }
            if axi {
                let inv_r = hoop_factor(cv, q, axi);
                for a in 0..nn {
                    fe[a * dim] += s * n[a] * inv_r;
                }
            }
        }
        if let Some(sigma) = &self.eigen {
            // int sigma*_ij dN_a/dx_j, and sigma*_tt N_a / r on the radial rows in r-z (the
            // hoop stress is in the zz slot there).
            let g = cv.gradients(q);
            for a in 0..nn {
                for i in 0..dim {
                    let mut v = 0.0;
                    for j in 0..dim {
                        v += sigma[i][j] * g[a][j];
                    }
                    fe[a * dim + i] += v * w;
                }
            }
            if axi {
                let inv_r = hoop_factor(cv, q, axi);
                for a in 0..nn {
                    fe[a * dim] += sigma[2][2] * n[a] * inv_r * w;
                }
            }
        }
    }
}

/// Adds the body's tractions to its load `f`, `int_faces t_i N_a`.
fn add_tractions(
    body: &ElasticBody,
    options: &ElasticOptions,
    f: &mut [f64],
) -> Result<(), PhysicsError> {
    let (mesh, layout) = (&body.mesh, body.layout());
    let dim = layout.components;
    for cond in &body.tractions {
        for face in &cond.faces {
            cells::for_each_face_point(
                mesh,
                face,
                |p| options.degree(p),
                |xp, w, jac, nodes, na| {
                    let t = (cond.traction)(xp) * (w * jac * options.geometry.weight(xp));
                    for (&n, a) in nodes.iter().zip(na) {
                        for i in 0..dim {
                            f[layout.dof(n, i) as usize] += t[i] * a;
                        }
                    }
                },
            )
            .map_err(|e| {
                body.invalid(format!(
                    "no {:?} face quadrature of degree {}: {e}",
                    face.element.domain(),
                    options.degree(face.element.shape_degree())
                ))
            })?;
        }
    }
    Ok(())
}

/// Assembles the matrix `G` of the thermal load, linear in the nodal temperatures:
/// `f_th = G (T - T_ref)` with `G[(a,i), b] = int 3 K alpha N_b dN_a/dx_i` (rows numbered by
/// the body's [`layout`](ElasticBody::layout), a column per mesh node; in the axisymmetric
/// geometry `int 3 K alpha N_b (dN_a/dr + N_a / r) 2 pi r` for the radial rows and
/// `int 3 K alpha N_b dN_a/dz 2 pi r` for the axial ones): the thermal term of
/// [`assemble_elastic_load`] as an operator, for problems in which the temperature is an
/// unknown (thermoelasticity: its Jacobian block is `-G`). The body's own temperature field
/// is not used. Parallel over fixed chunks of cells merged in order (bit for bit whatever
/// the thread count).
///
/// # Errors
/// As [`assemble_elastic_stiffness`].
pub fn assemble_thermal_load_matrix(
    body: &ElasticBody,
    options: &ElasticOptions,
) -> Result<SparseMatrix, PhysicsError> {
    check(body, options)?;
    let dim = body.layout().components;
    let beta = body.material.thermal_stress_coefficient();
    let axi = options.geometry.is_axisymmetric();
    assemble_cell_matrix(body, options, dim, 1, |cv, nn, ge| {
        for q in 0..cv.len() {
            let (n, g) = (cv.shape(q), cv.gradients(q));
            let w = beta * cells::weight(cv, q, options.geometry);
            let inv_r = hoop_factor(cv, q, axi);
            for a in 0..nn {
                for i in 0..dim {
                    let row = (a * dim + i) * nn;
                    // The divergence of the test function (a, i): with its hoop strain for a
                    // radial component in the axisymmetric geometry.
                    let div = if axi && i == 0 {
                        g[a][i] + n[a] * inv_r
                    } else {
                        g[a][i]
                    };
                    for b in 0..nn {
                        ge[row + b] += w * div * n[b];
                    }
                }
            }
        }
    })
}

/// Assembles a matrix cell by cell: rows `node * row_components + i`, columns
/// `node * col_components + j` (over the body's nodes). `local(cv, nn, m)` adds the cell's
/// integrals into the zeroed dense matrix `m` of `nn` nodes, row-major with rows
/// `a * row_components + i` and columns `b * col_components + j`. In parallel over fixed
/// chunks of cells merged in order: bit for bit the same whatever the thread count.
fn assemble_cell_matrix(
    body: &ElasticBody,
    options: &ElasticOptions,
    row_components: usize,
    col_components: usize,
    local: impl Fn(&CellValues, usize, &mut [f64]) + Sync,
) -> Result<SparseMatrix, PhysicsError> {
    let mesh = &body.mesh;
    let cells = mesh.cell_count();
    let (rc, cc) = (row_components, col_components);
    let chunks: Vec<Result<PartList, PhysicsError>> = (0..cells.div_ceil(CELL_CHUNK))
        .into_par_iter()
        .map(|ch| {
            let mut out = Triplets::default();
            let mut cv = CellValues::new();
            let mut x = [Vector3::zeros(); MAX_CELL_NODES];
            let mut ke = vec![0.0; rc * cc * MAX_CELL_NODES * MAX_CELL_NODES];
            for c in ch * CELL_CHUNK..((ch + 1) * CELL_CHUNK).min(cells) {
                let cell = mesh.cell(c);
                let nn = reinit_cell(body, options, c, &mut cv, &mut x)?;
                let cols = nn * cc;
                ke[..nn * rc * cols].fill(0.0);
                local(&cv, nn, &mut ke[..nn * rc * cols]);
                for (a, &na) in cell.nodes.iter().enumerate() {
                    for i in 0..rc {
                        let row = (a * rc + i) * cols;
                        let r = na * rc as u32 + i as u32;
                        for (b, &nb) in cell.nodes.iter().enumerate() {
                            for j in 0..cc {
                                out.push(r, nb * cc as u32 + j as u32, ke[row + b * cc + j]);
                            }
                        }
                    }
                }
            }
            Ok(cells::compressed_chunk(ch, out))
        })
        .collect();
    let mut parts = Vec::with_capacity(chunks.len());
    for ch in chunks {
        parts.push(ch?);
    }
    let n = mesh.node_count();
    Ok(cells::merged_csr(parts, n * rc, n * cc))
}

/// The symmetric tensor of a stress in Voigt order `[xx, yy, zz, yz, xz, xy]`.
pub(crate) fn voigt_tensor(s: &[f64; 6]) -> [[f64; 3]; 3] {
    [[s[0], s[5], s[4]], [s[5], s[1], s[3]], [s[4], s[3], s[2]]]
}

/// `1 / r` at point `q` of `cv` in the axisymmetric geometry (the factor of the hoop strain
/// `u_r / r`), zero otherwise. Gauss points lie inside the cells, so `r > 0` there.
#[inline]
pub(crate) fn hoop_factor(cv: &CellValues, q: usize, axisymmetric: bool) -> f64 {
    if axisymmetric {
        1.0 / cv.point(q).x
    } else {
        0.0
    }
}

/// Checks the body's data and that it fits the options' geometry: in the axisymmetric one, a
/// 2D mesh, no node at a negative radius, and `u_r` prescribed at every node on the axis.
///
/// # Errors
/// See [`assemble_elastic_stiffness`].
pub(crate) fn check(body: &ElasticBody, options: &ElasticOptions) -> Result<(), PhysicsError> {
    body.check()?;
    cells::check_geometry(&body.name, &body.mesh, options.geometry)?;
    if options.geometry.is_axisymmetric() {
        let coords = body.mesh.coords();
        let tol = ModelGeometry::axis_tolerance(coords);
        let mut radial_held = vec![false; coords.len()];
        for d in body.dirichlet.iter().filter(|d| d.components.contains(0)) {
            for &n in &d.nodes {
                radial_held[n as usize] = true;
            }
        }
        if let Some(i) = (0..coords.len()).find(|&i| coords[i].x <= tol && !radial_held[i]) {
            return Err(PhysicsError::AxisNodeFree {
                body: body.name.clone(),
                node: body.mesh.node_tags()[i],
            });
        }
    }
    Ok(())
}

/// Sets `cv` up on cell `c` of the body (see [`cells::reinit_cell`]).
pub(crate) fn reinit_cell(
    body: &ElasticBody,
    options: &ElasticOptions,
    c: usize,
    cv: &mut CellValues,
    x: &mut [Vector3<f64>; MAX_CELL_NODES],
) -> Result<usize, PhysicsError> {
    cells::reinit_cell(&body.name, &body.mesh, |p| options.degree(p), c, cv, x)
}
