//! Mesh tying: `D u_s - M u_m = 0`.

use mortar_core::linalg::{SparseMatrix, Triplets};
use mortar_core::Coupling;

/// Why a tying operator could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TyingError {
    /// D has an off-diagonal entry too large for the dual condensation.
    #[error("D is not diagonal: entry ({row}, {col}) = {value:e} against diagonal {diagonal:e}; use dual multipliers on a fully covered interface, or the saddle-point form")]
    NotDiagonal {
        /// Row (slave node, row order).
        row: usize,
        /// Column.
        col: usize,
        /// The entry.
        value: f64,
        /// The row's diagonal entry.
        diagonal: f64,
    },
    /// A slave node has a zero (or negative) diagonal entry in D: it lies outside the overlap.
    #[error("slave node {tag} (row {row}) has D[{row},{row}] = {value:e}: it is not covered by the master surface")]
    Uncovered {
        /// Row.
        row: usize,
        /// The node tag.
        tag: u64,
        /// The diagonal entry.
        value: f64,
    },
}

/// The tying constraint matrix `B = [D, -M]`: rows follow the slave nodes, the first columns
/// the slave nodes, the remaining ones the master nodes (each in the coupling's order).
pub fn constraint_matrix(coupling: &Coupling) -> SparseMatrix {
    let ns = coupling.slave_nodes.len();
    let nm = coupling.master_nodes.len();
    let mut t = Triplets::default();
    for (v, (r, c)) in coupling.d.iter() {
        t.push(r as u32, c as u32, *v);
    }
    for (v, (r, c)) in coupling.m.iter() {
        t.push(r as u32, (ns + c) as u32, -*v);
    }
    t.to_csr(ns, ns + nm)
}

/// The condensation operator `P = D^-1 M` (slave x master), so that the tied slave values are
/// `u_s = P u_m`. Needs D diagonal: off-diagonal entries at most `rel_tol` times their row's
/// diagonal entry (dual multipliers on a covered interface give round-off).
///
/// # Errors
/// [`TyingError::NotDiagonal`] or [`TyingError::Uncovered`].
pub fn dual_condensation(coupling: &Coupling, rel_tol: f64) -> Result<SparseMatrix, TyingError> {
    let ns = coupling.slave_nodes.len();
    let mut diag = vec![0.0; ns];
    for (v, (r, c)) in coupling.d.iter() {
        if r == c {
            diag[r] = *v;
        }
    }
    for (v, (r, c)) in coupling.d.iter() {
        if r != c && v.abs() > rel_tol * diag[r].abs() {
            return Err(TyingError::NotDiagonal {
                row: r,
                col: c,
                value: *v,
                diagonal: diag[r],
            });
        }
    }
    if let Some((row, &value)) = diag.iter().enumerate().find(|(_, d)| **d <= 0.0) {
        return Err(TyingError::Uncovered {
            row,
            tag: coupling.slave_nodes[row],
            value,
        });
    }
    let mut t = Triplets::default();
    for (v, (r, c)) in coupling.m.iter() {
        t.push(r as u32, c as u32, *v / diag[r]);
    }
    Ok(t.to_csr(ns, coupling.master_nodes.len()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use mortar_core::mesh::SurfaceMesh;
    use mortar_core::{assemble_coupling, CouplingOptions, Interface};
    use mortar_elements::LINE2;

    fn line(n: usize, flip: bool) -> SurfaceMesh {
        let mut m = SurfaceMesh::new();
        for i in 0..=n {
            m.add_node(i as u64 + 1, [i as f64 / n as f64, 0.0, 0.0])
                .unwrap();
        }
        for i in 0..n {
            let (a, b) = (i as u64 + 1, i as u64 + 2);
            let f = if flip { [b, a] } else { [a, b] };
            m.add_face(&LINE2, &f).unwrap();
        }
        m
    }

    #[test]
    fn dual_condensation_interpolates_linear_fields() {
        let i = Interface::new(line(5, false), line(8, true)).unwrap();
        let c = assemble_coupling(&i, &CouplingOptions::default().dual()).unwrap();
        let p = dual_condensation(&c, 1e-12).unwrap();
        let xm = c.master_positions(&i);
        let xs = c.slave_positions(&i);
        let f = |x: f64| 0.3 + 2.0 * x;
        for (r, row) in p.outer_iterator().enumerate() {
            let us: f64 = row.iter().map(|(k, v)| v * f(xm[k].x)).sum();
            assert!(
                (us - f(xs[r].x)).abs() < 1e-13,
                "row {r}: {us} vs {}",
                f(xs[r].x)
            );
        }
    }

    #[test]
    fn standard_multipliers_are_refused_by_the_condensation() {
        let i = Interface::new(line(5, false), line(8, true)).unwrap();
        let c = assemble_coupling(&i, &CouplingOptions::default()).unwrap();
        assert!(matches!(
            dual_condensation(&c, 1e-12),
            Err(TyingError::NotDiagonal { .. })
        ));
        let b = constraint_matrix(&c);
        assert_eq!(b.shape(), (6, 15));
        // B [1, 1] = D 1 - M 1 = 0 on a covered interface.
        for row in b.outer_iterator() {
            let s: f64 = row.iter().map(|(_, v)| v).sum();
            assert!(s.abs() < 1e-14);
        }
    }
}
