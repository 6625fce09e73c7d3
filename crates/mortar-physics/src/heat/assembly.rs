//! Assembly of one body's heat conduction matrices (stiffness, capacity) and loads (source,
//! Neumann flux), with `HeatOptions` for the quadrature degree and the model geometry.

use mortar_core::linalg::{PartList, SparseMatrix, Triplets};
use mortar_core::ModelGeometry;
use mortar_fem::element::{CellValues, MAX_CELL_NODES};
use nalgebra::Vector3;
use rayon::prelude::*;

use super::body::HeatBody;
use crate::error::PhysicsError;
use crate::field::cells;

pub(crate) use crate::field::cells::CELL_CHUNK;

/// Assembly settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct HeatOptions {
    /// The quadrature degree on the cells and Neumann faces; `None` uses `2 p + 1` for each
    /// cell's (face's) shape functions of degree `p` (exact for the stiffness and capacity of
    /// affine cells, and one more for the source; with the axisymmetric weight `r` the
    /// stiffness of affine cells is exact too, the capacity of degree `2 p + 1` also).
    pub quadrature_degree: Option<u32>,
    /// What the mesh models ([`ModelGeometry`]): [`Cartesian`](ModelGeometry::Cartesian) (the
    /// default: a 3D body, or a 2D slice of unit thickness, heat flows in W/m) or
    /// [`Axisymmetric`](ModelGeometry::Axisymmetric): a 2D mesh in the plane `z = 0` is the
    /// r-z section of a body of revolution (`x = r >= 0`, `y = z`), and every integral
    /// (conduction, also the `k(T)` one of [`assemble_conduction`](super::assemble_conduction),
    /// capacity, source, Neumann faces) takes the weight `2 pi r`: heat flows in W over the
    /// full revolution, sources stay W/m^3 and Neumann fluxes W/m^2. Give a coupling the same
    /// ([`CouplingOptions::geometry`](mortar_core::CouplingOptions::geometry));
    /// [`TiedHeat`](super::TiedHeat) and [`GapHeat`](super::GapHeat) refuse a mismatch. Nodes
    /// on the axis need no condition (the symmetry makes `dT/dr = 0` there naturally).
    pub geometry: ModelGeometry,
}

impl HeatOptions {
    /// These options with the geometry `geometry`.
    pub fn with_geometry(mut self, geometry: ModelGeometry) -> Self {
        self.geometry = geometry;
        self
    }

    /// The degree for shape functions of degree `p`.
    pub(crate) fn degree(&self, p: u32) -> u32 {
        self.quadrature_degree.unwrap_or(2 * p + 1)
    }
}

/// The matrices of one body: `K[a][b] = int k grad N_a . grad N_b` and
/// `C[a][b] = int rho c_p N_a N_b` (both symmetric; rows and columns follow the mesh's node
/// indices).
#[derive(Debug, Clone)]
pub struct HeatMatrices {
    /// The conductivity (stiffness) matrix K.
    pub stiffness: SparseMatrix,
    /// The capacity (mass) matrix C.
    pub capacity: SparseMatrix,
}

impl HeatMatrices {
    /// The backward Euler matrix `K + C / dt`, with the sparsity pattern of K (and C: they
    /// share it), whatever `dt`, so that its factorisation can be reused.
    pub fn backward_euler(&self, dt: f64) -> SparseMatrix {
        let (k, c) = (&self.stiffness, &self.capacity);
        if k.indptr() == c.indptr() && k.indices() == c.indices() && k.is_csr() && c.is_csr() {
            let data = k
                .data()
                .iter()
                .zip(c.data())
                .map(|(a, b)| a + b / dt)
                .collect();
            SparseMatrix::new(
                k.shape(),
                k.proper_indptr().into_owned(),
                k.indices().to_vec(),
                data,
            )
        } else {
            k + &c.map(|v| v / dt)
        }
    }
}

/// One chunk's triplets.
#[derive(Default)]
struct ChunkMatrices {
    k: Triplets,
    c: Triplets,
}

/// One chunk's entries, compressed ([`cells::compressed_chunk`]).
struct ChunkParts {
    k: PartList,
    c: PartList,
}

/// Assembles the stiffness K and capacity C of a body, in parallel over fixed chunks of cells
/// merged in order (bit-for-bit the same for any thread count). With the axisymmetric
/// geometry the integrals take the weight `2 pi r` ([`HeatOptions::geometry`]).
///
/// # Errors
/// [`PhysicsError::InvalidInput`] for bad material data, a quadrature degree out of range or
/// an axisymmetric 3D mesh, [`PhysicsError::NegativeRadius`] for an axisymmetric mesh with a
/// node at `x < 0`, [`PhysicsError::InvertedCell`] for a cell with a non-positive Jacobian
/// determinant (the first in cell order).
pub fn assemble_heat_matrices(
    body: &HeatBody,
    options: &HeatOptions,
) -> Result<HeatMatrices, PhysicsError> {
    let (stiffness, capacity) = assemble(body, options, true)?;
    Ok(HeatMatrices {
        stiffness,
        capacity,
    })
}

/// Assembles the stiffness K of a body alone, as [`assemble_heat_matrices`] does, for a steady
/// problem, which needs no capacity: half the triplets, and the same bits of K.
///
/// # Errors
/// As [`assemble_heat_matrices`].
pub fn assemble_heat_stiffness(
    body: &HeatBody,
    options: &HeatOptions,
) -> Result<SparseMatrix, PhysicsError> {
    Ok(assemble(body, options, false)?.0)
}

/// K, and C if `with_capacity` (else C without entries).
fn assemble(
    body: &HeatBody,
    options: &HeatOptions,
    with_capacity: bool,
) -> Result<(SparseMatrix, SparseMatrix), PhysicsError> {
    check(body, options)?;
    let mesh = &body.mesh;
    let (k, rho_cp) = (body.material.conductivity, body.material.capacity);
    let cells = mesh.cell_count();
    let chunks: Vec<Result<ChunkParts, PhysicsError>> = (0..cells.div_ceil(CELL_CHUNK))
        .into_par_iter()
        .map(|ch| {
            let mut out = ChunkMatrices::default();
            let mut cv = CellValues::new();
            let mut x = [Vector3::zeros(); MAX_CELL_NODES];
            let mut ke = [[0.0; MAX_CELL_NODES]; MAX_CELL_NODES];
            let mut ce = [[0.0; MAX_CELL_NODES]; MAX_CELL_NODES];
            for c in ch * CELL_CHUNK..((ch + 1) * CELL_CHUNK).min(cells) {
                let cell = mesh.cell(c);
                let nn = reinit_cell(body, options, c, &mut cv, &mut x)?;
                for a in 0..nn {
                    ke[a][..nn].fill(0.0);
                    ce[a][..nn].fill(0.0);
                }
                for q in 0..cv.len() {
                    let (g, n) = (cv.gradients(q), cv.shape(q));
                    let w = cells::weight(&cv, q, options.geometry);
                    for a in 0..nn {
                        for b in 0..nn {
                            ke[a][b] += k * g[a].dot(&g[b]) * w;
                        }
                    }
                    if with_capacity {
                        for a in 0..nn {
                            for b in 0..nn {
                                ce[a][b] += rho_cp * n[a] * n[b] * w;
                            }
                        }
                    }
                }
                for (a, &na) in cell.nodes.iter().enumerate() {
                    for (b, &nb) in cell.nodes.iter().enumerate() {
                        out.k.push(na, nb, ke[a][b]);
                        if with_capacity {
                            out.c.push(na, nb, ce[a][b]);
                        }
                    }
                }
            }
            Ok(ChunkParts {
                k: cells::compressed_chunk(ch, out.k),
                c: cells::compressed_chunk(ch, out.c),
            })
        })
        .collect();
    let mut ks = Vec::with_capacity(chunks.len());
    let mut cs = Vec::with_capacity(chunks.len());
    for ch in chunks {
        let ch = ch?;
        ks.push(ch.k);
        cs.push(ch.c);
    }
    let n = mesh.node_count();
    Ok((cells::merged_csr(ks, n, n), cells::merged_csr(cs, n, n)))
}

/// Assembles the load vector of a body at time `t`: the source, `int Q(x, t) N_a`, plus the
/// Neumann fluxes, `int_faces q(x, t) N_a` (each with the weight `2 pi r` in the
/// axisymmetric geometry). Parallel over fixed chunks of cells, summed in order (bit-for-bit
/// the same for any thread count).
///
/// # Errors
/// As [`assemble_heat_matrices`].
pub fn assemble_heat_load(
    body: &HeatBody,
    t: f64,
    options: &HeatOptions,
) -> Result<Vec<f64>, PhysicsError> {
    check(body, options)?;
    let mesh = &body.mesh;
    let mut f = vec![0.0; mesh.node_count()];
    if let Some(source) = &body.source {
        let cells = mesh.cell_count();
        let chunks: Vec<Result<Vec<(u32, f64)>, PhysicsError>> = (0..cells.div_ceil(CELL_CHUNK))
            .into_par_iter()
            .map(|ch| {
                let mut out = Vec::new();
                let mut cv = CellValues::new();
                let mut x = [Vector3::zeros(); MAX_CELL_NODES];
                let mut fe = [0.0; MAX_CELL_NODES];
                for c in ch * CELL_CHUNK..((ch + 1) * CELL_CHUNK).min(cells) {
                    let cell = mesh.cell(c);
                    let nn = reinit_cell(body, options, c, &mut cv, &mut x)?;
                    fe[..nn].fill(0.0);
                    for q in 0..cv.len() {
                        let s = source(&cv.point(q), t) * cells::weight(&cv, q, options.geometry);
                        for (fa, na) in fe.iter_mut().zip(cv.shape(q)) {
                            *fa += s * na;
                        }
                    }
                    out.extend(cell.nodes.iter().copied().zip(fe[..nn].iter().copied()));
                }
                Ok(out)
            })
            .collect();
        for ch in chunks {
            for (n, v) in ch? {
                f[n as usize] += v;
            }
        }
    }
    for cond in &body.neumann {
        for face in &cond.faces {
            cells::for_each_face_point(
                mesh,
                face,
                |p| options.degree(p),
                |xp, w, jac, nodes, na| {
                    let s = (cond.flux)(xp, t) * w * jac * options.geometry.weight(xp);
                    for (&n, a) in nodes.iter().zip(na) {
                        f[n as usize] += s * a;
                    }
                },
            )?;
        }
    }
    Ok(f)
}

/// Checks the body's data and that its mesh fits the options' geometry.
pub(crate) fn check(body: &HeatBody, options: &HeatOptions) -> Result<(), PhysicsError> {
    body.check()?;
    cells::check_geometry(&body.name, &body.mesh, options.geometry)
}

/// Sets `cv` up on cell `c` of the body (see [`cells::reinit_cell`]).
pub(crate) fn reinit_cell(
    body: &HeatBody,
    options: &HeatOptions,
    c: usize,
    cv: &mut CellValues,
    x: &mut [Vector3<f64>; MAX_CELL_NODES],
) -> Result<usize, PhysicsError> {
    cells::reinit_cell(&body.name, &body.mesh, |p| options.degree(p), c, cv, x)
}
