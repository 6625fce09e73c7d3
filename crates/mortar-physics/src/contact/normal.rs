//! The linearised weighted normal gap `g~ = g~_0 - N u` of a tie.

use mortar_core::linalg::{SparseMatrix, Triplets};

use crate::error::PhysicsError;
use crate::tied::{Interpolated, Tie};

/// The weighted normal gap of a tie, linear in the displacements: `g~ = g~_0 - N u`, with
/// `u` the slave body's displacements followed by the master body's (`node * dim + k`).
#[derive(Debug, Clone)]
pub struct NormalGap {
    /// `N`: a row per slave interface node (coupling row), a column per displacement unknown
    /// of both bodies.
    pub matrix: SparseMatrix,
    /// `g~_0`, the weighted gap of the reference configuration.
    pub initial: Vec<f64>,
    /// `w_j`, the row sums of D: the nodal gap is `g~_j / w_j`.
    pub weights: Vec<f64>,
    /// The round-off of a nodal gap: 8 ulps of the largest interface coordinate. Nodal gaps
    /// within it of zero are zero (surfaces that touch in the reference configuration are
    /// closed, not open by the rounding of their coordinates).
    pub roundoff: f64,
    /// Per row, the slave body's node of the row.
    pub slave_node: Vec<u32>,
    /// Displacement components per node (2 or 3).
    pub dim: usize,
    /// Whether D is diagonal (dual multipliers on a covered interface, off-diagonal entries
    /// at most 1e-10 of the diagonal): each row's slave part then holds its own node only,
    /// and the pressure can be condensed out of the Newton system.
    pub diagonal: bool,
    /// Per row, whether its slave node carries a multiplier: `false` for the edge and centre
    /// nodes of linear multipliers on second-order faces, whose rows of D are empty. Such a
    /// row has no weight and no pressure of its own (the solver holds it at zero); its
    /// reported pressure and gap are interpolated from its face's corners
    /// ([`interpolate_rows_without_multiplier`](Self::interpolate_rows_without_multiplier)).
    pub carries: Vec<bool>,
    /// For each row without multiplier: the rows of its face's corners and the first-order
    /// shape functions of those corners at its node.
    interpolation: Vec<Interpolated>,
}

impl NormalGap {
    /// The gap of `tie` (a tie of scalar node numbering: [`Tie::components`] must be 1; the
    /// displacement has `dim` components per node) between bodies of `slave_nodes` and
    /// `master_nodes` nodes.
    ///
    /// # Errors
    /// [`PhysicsError::InvalidInput`] for a tie of more than one component, a dimension not
    /// 2 or 3, a slave row with a non-positive weight (a slave node the master does not
    /// cover at all), or a slave node without multiplier whose face's corners do not all
    /// carry one.
    pub fn new(
        tie: &Tie,
        dim: usize,
        slave_nodes: usize,
        master_nodes: usize,
    ) -> Result<Self, PhysicsError> {
        let offsets = [0, slave_nodes * dim];
        Self::with_offsets(tie, dim, offsets, (slave_nodes + master_nodes) * dim)
    }

    /// [`new`](Self::new) with the columns of the slave body's displacements starting at
    /// `offsets[0]` and the master body's at `offsets[1]` in a vector of `columns`
    /// displacement unknowns: both sides in one body (the lands of two pellets of one
    /// body, say) take the same offset.
    ///
    /// # Errors
    /// As [`new`](Self::new), and [`PhysicsError::InvalidInput`] for a node whose columns
    /// would lie beyond `columns`.
    pub fn with_offsets(
        tie: &Tie,
        dim: usize,
        offsets: [usize; 2],
        columns: usize,
    ) -> Result<Self, PhysicsError> {
        let invalid = |what: String| PhysicsError::InvalidInput {
            body: "contact".into(),
            what,
        };
        if tie.components() != 1 {
            return Err(invalid(
                "the normal gap is built from a tie of one component per node".into(),
            ));
        }
        if !(dim == 2 || dim == 3) {
            return Err(invalid(format!("dimension {dim} is not 2 or 3")));
        }
        let c = tie.coupling();
        let interface = tie.interface();
        let x_s = c.slave_positions(interface);
        let x_m = c.master_positions(interface);
        let initial = c.normal_gaps(&x_s, &x_m);
        let roundoff =
            8.0 * f64::EPSILON * x_s.iter().chain(&x_m).fold(0.0f64, |a, x| a.max(x.amax()));
        let rows = c.d.rows();
        let carries = tie.rows_with_multiplier();
        let interpolation = tie.rows_without_multiplier()?;
        let mut weights = vec![0.0; rows];
        let mut diagonal = true;
        let mut t = Triplets::default();
        let beyond = |nodes: &[u32], offset: usize| {
            nodes
                .iter()
                .any(|&n| offset + (n as usize + 1) * dim > columns)
        };
        if beyond(tie.slave_nodes(), offsets[0]) || beyond(tie.master_nodes(), offsets[1]) {
            return Err(invalid(format!(
                "a node's displacement lies beyond the {columns} columns of the gap"
            )));
        }
        let offset = offsets[1];
        for (j, w) in weights.iter_mut().enumerate() {
            let n = c.slave_normals[j];
            if !carries[j] {
                continue;
            }
            if let Some(d) = c.d.outer_view(j) {
                let djj = d.get(j).copied().unwrap_or(0.0);
                for (k, v) in d.iter() {
                    if k != j && v.abs() > 1e-10 * djj.abs() {
                        diagonal = false;
                    }
                    *w += v;
                    let node = tie.slave_nodes()[k] as usize;
                    for a in 0..dim {
                        t.push(j as u32, (offsets[0] + node * dim + a) as u32, v * n[a]);
                    }
                }
            }
            if let Some(m) = c.m.outer_view(j) {
                for (l, v) in m.iter() {
                    let node = tie.master_nodes()[l] as usize;
                    for a in 0..dim {
                        t.push(j as u32, (offset + node * dim + a) as u32, -v * n[a]);
                    }
                }
            }
            if w.is_nan() || *w <= 0.0 {
                return Err(invalid(format!(
                    "slave node {} has no contact area (row sum of D {w:e}): the master \
                     surface does not cover it, or (with standard multipliers on Tri6 or Quad8 \
                     slave faces, whose corner functions integrate to zero or less) the \
                     multipliers give it none: use dual or linear multipliers",
                    c.slave_nodes[j]
                )));
            }
        }
        Ok(Self {
            matrix: t.to_csr(rows, columns),
            initial,
            weights,
            roundoff,
            slave_node: tie.slave_nodes().to_vec(),
            dim,
            diagonal,
            carries,
            interpolation,
        })
    }

    /// Overwrites the values of the rows without multiplier (see [`carries`](Self::carries))
    /// with the first-order interpolation of their face's corners' values: the pressure
    /// field the linear multipliers stand for, or the gap there.
    pub fn interpolate_rows_without_multiplier(&self, values: &mut [f64]) {
        for (row, from) in &self.interpolation {
            values[*row as usize] = from.iter().map(|&(r, w)| w * values[r as usize]).sum();
        }
    }

    /// The nodal gaps `g_j = (g~_0 - N u)_j / w_j` for displacements `u` (both bodies),
    /// those within [`roundoff`](Self::roundoff) of zero set to zero.
    ///
    /// Rows without multiplier get the interpolation of their face's corners' gaps.
    pub fn nodal(&self, u: &[f64]) -> Vec<f64> {
        let mut gaps: Vec<f64> = self
            .matrix
            .outer_iterator()
            .enumerate()
            .map(|(j, row)| {
                if !self.carries[j] {
                    return 0.0;
                }
                let nu: f64 = row.iter().map(|(k, v)| v * u[k]).sum();
                let g = (self.initial[j] - nu) / self.weights[j];
                if g.abs() <= self.roundoff {
                    0.0
                } else {
                    g
                }
            })
            .collect();
        self.interpolate_rows_without_multiplier(&mut gaps);
        gaps
    }

    /// The rounding error of each nodal gap [`nodal`](Self::nodal) computes at `u`: 8 ulps of
    /// the magnitudes it sums, `(|g~_0j| + sum_k |N_jk u_k|) / w_j`. A law residual that
    /// changes by less than its gap derivative times this is at round-off.
    pub fn nodal_rounding(&self, u: &[f64]) -> Vec<f64> {
        self.matrix
            .outer_iterator()
            .enumerate()
            .map(|(j, row)| {
                if !self.carries[j] {
                    return 0.0;
                }
                let nu: f64 = row.iter().map(|(k, v)| (v * u[k]).abs()).sum();
                8.0 * f64::EPSILON * (self.initial[j].abs() + nu) / self.weights[j].abs()
            })
            .collect()
    }
}
