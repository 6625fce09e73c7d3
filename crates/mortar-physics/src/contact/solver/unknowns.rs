//! The unknowns of the contact iteration: the two bodies' displacements, numbered among the
//! free ones (the Dirichlet ones held at their load step's values), and each slave
//! interface node's free components.

use mortar_fem::linalg::SparseMatrix;

use super::wrong_length;
use crate::contact::NormalGap;
use crate::error::PhysicsError;
use crate::field::free::{free_numbering, FIXED};

/// The displacement unknowns of both bodies (the slave body's, then the master body's) and
/// which of them are free: the numbering every Newton system is written in.
pub(super) struct Unknowns {
    /// The slave body's and the master body's unknown counts.
    pub n: [usize; 2],
    /// All unknowns, `n[0] + n[1]`.
    pub ndof: usize,
    /// Per unknown, its index among the free ones (increasing with the unknown), or
    /// [`FIXED`].
    pub free: Vec<u32>,
    /// The number of free unknowns.
    pub nfree: usize,
    /// Free indices below this are the slave body's (the numbering increases with the
    /// unknown).
    pub slave_free: usize,
    /// Per unknown, its full Dirichlet value (zero where free).
    pub fixed_value: Vec<f64>,
    /// Per row of the gap, the free indices of its slave node's displacement components.
    pub free_of_slave: Vec<Vec<u32>>,
}

impl Unknowns {
    /// Numbers the unknowns of the bodies of `stiffness` held by `dirichlet`, the gap's rows
    /// on the slave body's.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a Dirichlet unknown out of range,
    /// [`PhysicsError::WrongLength`] for a slave interface node beyond the slave stiffness.
    pub fn new(
        stiffness: [&SparseMatrix; 2],
        dirichlet: [(&[u32], &[f64]); 2],
        gap: &NormalGap,
    ) -> Result<Self, PhysicsError> {
        let n = [stiffness[0].rows(), stiffness[1].rows()];
        let ndof = n[0] + n[1];
        let mut fixed = Vec::new();
        let mut fixed_value = vec![0.0; ndof];
        for b in 0..2 {
            let offset = if b == 0 { 0 } else { n[0] };
            for (&d, &v) in dirichlet[b].0.iter().zip(dirichlet[b].1) {
                if d as usize >= n[b] {
                    return Err(PhysicsError::InvalidInput {
                        body: ["slave", "master"][b].into(),
                        what: format!("Dirichlet unknown {d} out of range ({})", n[b]),
                    });
                }
                fixed.push((offset + d as usize) as u32);
                fixed_value[offset + d as usize] = v;
            }
        }
        let (free, nfree) = free_numbering(ndof, &fixed);
        let slave_free = free[..n[0]].iter().filter(|&&f| f != FIXED).count();
        let (rows, dim) = (gap.weights.len(), gap.dim);
        if rows > 0
            && gap
                .slave_node
                .iter()
                .any(|&v| (v as usize + 1) * dim > n[0])
        {
            return Err(wrong_length(
                "slave stiffness (interface nodes beyond it)",
                ndof,
                n[0],
            ));
        }
        let free_of_slave = gap
            .slave_node
            .iter()
            .map(|&node| (0..dim).map(|k| free[node as usize * dim + k]).collect())
            .collect();
        Ok(Self {
            n,
            ndof,
            free,
            nfree,
            slave_free,
            fixed_value,
            free_of_slave,
        })
    }

    /// Sets the Dirichlet unknowns of `u` to the fraction `factor` of their values.
    pub fn impose(&self, factor: f64, u: &mut [f64]) {
        for g in 0..self.ndof {
            if self.free[g] == FIXED {
                u[g] = factor * self.fixed_value[g];
            }
        }
    }

    /// Adds the free increment `du` (free numbering) to the displacements `u`.
    pub fn add_free(&self, u: &mut [f64], du: &[f64]) {
        for g in 0..self.ndof {
            if self.free[g] != FIXED {
                u[g] += du[self.free[g] as usize];
            }
        }
    }

    /// Each row of the gap's matrix `N` on the free displacements, `(free index, value)`.
    pub fn free_rows(&self, gap: &NormalGap) -> Vec<Vec<(u32, f64)>> {
        gap.matrix
            .outer_iterator()
            .map(|row| {
                row.iter()
                    .filter(|(k, _)| self.free[*k] != FIXED)
                    .map(|(k, v)| (self.free[k], *v))
                    .collect()
            })
            .collect()
    }
}
