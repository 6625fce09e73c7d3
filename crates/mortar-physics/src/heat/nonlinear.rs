//! Heat conduction with a temperature-dependent conductivity `k(T)`: the internal heat flow
//! `f_a(T) = int k(T) grad T . grad N_a` of a body and its linearisations.

use mortar_core::linalg::{PartList, SparseMatrix, Triplets};
use mortar_fem::element::{CellValues, MAX_CELL_NODES};
use nalgebra::Vector3;
use rayon::prelude::*;

use super::assembly::{check, reinit_cell, HeatOptions, CELL_CHUNK};
use super::body::HeatBody;
use crate::error::PhysicsError;
use crate::field::cells;

/// A conductivity law `k(T)` (W/m/K, T in K).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Conductivity {
    /// A constant `k`.
    Constant(f64),
    /// `k(T) = 1 / (a + b T)` (the fuel pellet law of docs/models.md, section 3: `a` in m K/W, `b`
    /// in m/W). Temperatures below `-a / (2 b)` are taken as it, so that `k` stays positive
    /// and finite whatever the Newton iterate.
    InverseLinear {
        /// `a` (m K/W).
        a: f64,
        /// `b` (m/W).
        b: f64,
    },
}

impl Conductivity {
    /// `(k(T), dk/dT)`.
    pub fn at(&self, t: f64) -> (f64, f64) {
        match *self {
            Self::Constant(k) => (k, 0.0),
            Self::InverseLinear { a, b } => {
                let floor = if b > 0.0 { -a / (2.0 * b) } else { f64::MIN };
                if t < floor {
                    (1.0 / (a + b * floor), 0.0)
                } else {
                    let k = 1.0 / (a + b * t);
                    (k, -b * k * k)
                }
            }
        }
    }

    /// Checks the parameters.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a non-positive constant, `a <= 0` or `b < 0`, or
    /// a non-finite value.
    pub fn check(&self, body: &str) -> Result<(), PhysicsError> {
        let ok = match *self {
            Self::Constant(k) => k > 0.0 && k.is_finite(),
            Self::InverseLinear { a, b } => a > 0.0 && a.is_finite() && b >= 0.0 && b.is_finite(),
        };
        if ok {
            Ok(())
        } else {
            Err(PhysicsError::InvalidInput {
                body: body.into(),
                what: format!("conductivity law {self:?} out of range"),
            })
        }
    }
}

/// Which matrix [`assemble_conduction`] returns with the heat flow.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Linearization {
    /// The exact Jacobian `int k(T) grad N_b . grad N_a + int k'(T) N_b grad T . grad N_a`.
    Newton,
    /// The Picard (frozen-coefficient) matrix `int k(T) grad N_b . grad N_a`: symmetric, the
    /// usual approximate Jacobian of a preconditioner.
    Picard,
}

/// The internal heat flow `f_a = int k(T) grad T . grad N_a` of `body` at the nodal
/// temperatures `t` (by mesh node index) and, if asked, its linearisation (same sparsity
/// pattern whichever is asked, whatever `t`); every integral with the weight `2 pi r` in the
/// axisymmetric geometry ([`HeatOptions::geometry`]). Parallel over fixed chunks of cells merged in
/// order, so bit-for-bit the same for any thread count.
///
/// # Errors
/// [`PhysicsError::WrongLength`] if `t` is not one value per node, and the errors of
/// [`assemble_heat_matrices`](super::assemble_heat_matrices).
pub fn assemble_conduction(
    body: &HeatBody,
    conductivity: &Conductivity,
    t: &[f64],
    options: &HeatOptions,
    matrix: Option<Linearization>,
) -> Result<(Vec<f64>, Option<SparseMatrix>), PhysicsError> {
    check(body, options)?;
    conductivity.check(&body.name)?;
    let mesh = &body.mesh;
    if t.len() != mesh.node_count() {
        return Err(PhysicsError::WrongLength {
            what: format!("temperatures of body {:?}", body.name),
            expected: mesh.node_count(),
            got: t.len(),
        });
    }
    let cells = mesh.cell_count();
    type Chunk = (Vec<(u32, f64)>, PartList);
    let chunks: Vec<Result<Chunk, PhysicsError>> = (0..cells.div_ceil(CELL_CHUNK))
        .into_par_iter()
        .map(|ch| {
            let mut force = Vec::new();
            let mut trip = Triplets::default();
            let mut cv = CellValues::new();
            let mut x = [Vector3::zeros(); MAX_CELL_NODES];
            let mut fe = [0.0; MAX_CELL_NODES];
            let mut ke = [[0.0; MAX_CELL_NODES]; MAX_CELL_NODES];
            for c in ch * CELL_CHUNK..((ch + 1) * CELL_CHUNK).min(cells) {
                let cell = mesh.cell(c);
                let nn = reinit_cell(body, options, c, &mut cv, &mut x)?;
                fe[..nn].fill(0.0);
                for row in ke.iter_mut().take(nn) {
                    row[..nn].fill(0.0);
                }
                for q in 0..cv.len() {
                    let (g, n) = (cv.gradients(q), cv.shape(q));
                    let w = cells::weight(&cv, q, options.geometry);
                    let mut tq = 0.0;
                    let mut grad = Vector3::zeros();
                    for (a, &node) in cell.nodes.iter().enumerate() {
                        let ta = t[node as usize];
                        tq += n[a] * ta;
                        grad += g[a] * ta;
                    }
                    let (k, dk) = conductivity.at(tq);
                    for a in 0..nn {
                        let ga = g[a].dot(&grad);
                        fe[a] += k * ga * w;
                        if matrix.is_some() {
                            for b in 0..nn {
                                ke[a][b] += k * g[a].dot(&g[b]) * w;
                                if matrix == Some(Linearization::Newton) {
                                    ke[a][b] += dk * n[b] * ga * w;
                                }
                            }
                        }
                    }
                }
                force.extend(cell.nodes.iter().copied().zip(fe[..nn].iter().copied()));
                if matrix.is_some() {
                    for (a, &na) in cell.nodes.iter().enumerate() {
                        for (b, &nb) in cell.nodes.iter().enumerate() {
                            trip.push(na, nb, ke[a][b]);
                        }
                    }
                }
            }
            Ok((force, cells::compressed_chunk(ch, trip)))
        })
        .collect();
    let n = mesh.node_count();
    let mut f = vec![0.0; n];
    let mut parts = Vec::with_capacity(chunks.len());
    for ch in chunks {
        let (force, trip) = ch?;
        for (node, v) in force {
            f[node as usize] += v;
        }
        parts.push(trip);
    }
    let k = matrix.map(|_| cells::merged_csr(parts, n, n));
    Ok((f, k))
}
