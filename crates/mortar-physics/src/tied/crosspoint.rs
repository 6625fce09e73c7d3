//! The rows of Dirichlet slave nodes shared among their free neighbours
//! ([`SlaveDirichlet::Redistribute`](super::SlaveDirichlet::Redistribute)): the crosspoint
//! modification of Wohlmuth's mortar methods, on the assembled rows of D and M, for a tied
//! system and for a program that assembles its own ([`slave_dirichlet_shares`]).

use mortar_core::linalg::{SparseMatrix, Triplets};
use mortar_core::SurfaceMesh;
use nalgebra::Vector3;

use crate::error::PhysicsError;

/// Where the constraint rows go once the rows of Dirichlet slave nodes are shared among
/// their free neighbours: `S` such that `S D` and `S M` are the constraint's rows (see
/// [`slave_dirichlet_shares`]).
#[derive(Debug, Clone)]
pub struct SlaveDirichletShares {
    /// `S` (kept rows x coupling rows, CSR): for each kept row, 1 on its own coupling row and
    /// the shares of the Dirichlet rows it takes.
    pub s: SparseMatrix,
    /// For each kept row, its coupling row: the rows that carry a multiplier and are not of
    /// a Dirichlet node, ascending.
    pub rows: Vec<usize>,
    /// Dirichlet rows shared among free rows.
    pub redistributed: usize,
    /// Dirichlet rows with no free row in reach, dropped without a share.
    pub dropped: usize,
}

/// The treatment of Dirichlet slave nodes of
/// [`SlaveDirichlet::Redistribute`](super::SlaveDirichlet::Redistribute) for the rows of a
/// coupling of `slave` whose row `r` is the slave node of index `row_nodes[r]` (as
/// [`Interface::slave_nodes`](mortar_core::Interface::slave_nodes) gives them): each row
/// `r` with `dirichlet[r]` that carries a multiplier (`carries[r]`: its row of D not empty;
/// all but those of the edge and centre nodes of linear multipliers on second-order faces,
/// and of nodes no master face covers) is removed
/// and its multiplier's basis function shared among the nearest free rows (those of the
/// nodes of its slave faces, or one face further where all of those are Dirichlet nodes;
/// on second-order faces with the weights that keep linear functions, else equally). The
/// constraint rows are then `S D` and `S M`: they still reproduce constants, so the patch
/// test still passes, and a diagonal D stays diagonal on the free slave nodes.
///
/// # Errors
/// [`PhysicsError::InvalidInput`] when `row_nodes`, `carries` and `dirichlet` do not have
/// one entry per coupling row, or a node index is not one of `slave`'s.
pub fn slave_dirichlet_shares(
    slave: &SurfaceMesh,
    row_nodes: &[u32],
    carries: &[bool],
    dirichlet: &[bool],
) -> Result<SlaveDirichletShares, PhysicsError> {
    let n = row_nodes.len();
    let invalid = |what: String| PhysicsError::InvalidInput {
        body: "slave".into(),
        what,
    };
    if carries.len() != n || dirichlet.len() != n {
        return Err(invalid(format!(
            "{n} coupling rows, but {} flags of rows that carry a multiplier and {} \
             Dirichlet flags",
            carries.len(),
            dirichlet.len()
        )));
    }
    let nodes = slave.node_count();
    let mut row_of = vec![None; nodes];
    for (r, &node) in row_nodes.iter().enumerate() {
        match row_of.get_mut(node as usize) {
            Some(slot) => *slot = Some(r as u32),
            None => {
                return Err(invalid(format!(
                    "coupling row {r}: node index {node}, but the slave surface has {nodes} nodes"
                )))
            }
        }
    }
    let fixed: Vec<bool> = (0..n).map(|r| carries[r] && dirichlet[r]).collect();
    let shares = shares(
        slave,
        row_nodes,
        |node| row_of[node as usize],
        1,
        carries,
        &fixed,
    );
    let mut new_of = vec![u32::MAX; n];
    let mut rows = Vec::new();
    for r in (0..n).filter(|&r| carries[r] && !fixed[r]) {
        new_of[r] = rows.len() as u32;
        rows.push(r);
    }
    let (mut redistributed, mut dropped) = (0, 0);
    let mut t = Triplets::default();
    for r in (0..n).filter(|&r| carries[r]) {
        if fixed[r] {
            if shares[r].is_empty() {
                dropped += 1;
            } else {
                redistributed += 1;
            }
            for &(k, w) in &shares[r] {
                t.push(new_of[k as usize], r as u32, w);
            }
        } else {
            t.push(new_of[r], r as u32, 1.0);
        }
    }
    Ok(SlaveDirichletShares {
        s: t.to_csr(rows.len(), n),
        rows,
        redistributed,
        dropped,
    })
}

/// For each constraint row (`comps` per slave row: row `r` is component `r % comps` of the
/// node `row_nodes[r / comps]` of `slave`; `row_of` the slave row of a node) that is
/// `fixed` (a Dirichlet row carrying a multiplier), the free rows of the same component it
/// is shared among and their weights: the nearest in the graph of slave faces (its face
/// neighbours, or failing those, at a corner of the interface, the free rows one face
/// further); on second-order faces, the least-norm weights that keep linear functions
/// (gathering up to three rings for them), else equal shares. Empty for the other rows, and
/// for a fixed row with no free row in reach.
pub(crate) fn shares(
    slave: &SurfaceMesh,
    row_nodes: &[u32],
    row_of: impl Fn(u32) -> Option<u32>,
    comps: usize,
    carries: &[bool],
    fixed: &[bool],
) -> Vec<Vec<(u32, f64)>> {
    let ns = carries.len();
    let mut out = vec![Vec::new(); ns];
    if !fixed.iter().any(|f| *f) {
        return out;
    }
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); ns];
    // Rows of nodes on second-order faces: their redistribution must keep linear multipliers.
    let mut second_order = vec![false; ns];
    let mut adjacent: Vec<Vec<u32>> = vec![Vec::new(); ns];
    for f in 0..slave.face_count() {
        let face = slave.face(f);
        let rows: Vec<u32> = face.nodes.iter().filter_map(|&n| row_of(n)).collect();
        if face.element.node_count() > face.element.corner_count() {
            for &a in &rows {
                for k in 0..comps {
                    second_order[a as usize * comps + k] = true;
                }
            }
        }
        for k in 0..comps as u32 {
            for &a in &rows {
                let a = (a * comps as u32 + k) as usize;
                adjacent[a].extend(
                    rows.iter()
                        .map(|&b| b * comps as u32 + k)
                        .filter(|&b| b as usize != a),
                );
            }
        }
    }
    for list in &mut adjacent {
        list.sort_unstable();
        list.dedup();
    }
    let coords = slave.coords();
    let position = |row: usize| coords[row_nodes[row / comps] as usize];
    let mut seen = vec![false; ns];
    for c in (0..ns).filter(|&r| fixed[r]) {
        let mut front = vec![c as u32];
        let mut visited = vec![c as u32];
        seen[c] = true;
        // Second-order rows gather rings until their free neighbours can reproduce a
        // linear function at the node (at most three rings).
        let mut rings = 0;
        while !front.is_empty()
            && (neighbours[c].is_empty()
                || (second_order[c]
                    && rings < 3
                    && linear_weights(&position, c, &neighbours[c]).is_none()))
        {
            rings += 1;
            let mut next: Vec<u32> = front
                .iter()
                .flat_map(|&r| adjacent[r as usize].iter().copied())
                .filter(|&r| !seen[r as usize])
                .collect();
            next.sort_unstable();
            next.dedup();
            for &r in &next {
                seen[r as usize] = true;
                visited.push(r);
            }
            neighbours[c].extend(
                next.iter()
                    .copied()
                    .filter(|&r| carries[r as usize] && !fixed[r as usize]),
            );
            front = next;
        }
        for r in visited {
            seen[r as usize] = false;
        }
        let nb = &neighbours[c];
        let weights = if second_order[c] {
            linear_weights(&position, c, nb)
        } else {
            None
        };
        let w = 1.0 / nb.len().max(1) as f64;
        out[c] = match weights {
            Some(ws) => nb.iter().copied().zip(ws).collect(),
            None => nb.iter().map(|&k| (k, w)).collect(),
        };
    }
    out
}

/// The weights with which the row of a Dirichlet slave node `r` is shared among its free
/// neighbours `nb` so that the modified multipliers still represent linear functions (as a
/// second-order multiplier space must, for the flux of a quadratic field): the least-norm
/// affine combination `sum w_k = 1`, `sum w_k x_k = x_r` of the neighbours' positions; on a
/// Line3 end, `2` on the middle node and `-1` on the far end. `None` when no such combination
/// exists (the node off the neighbours' affine hull), leaving the equal shares.
fn linear_weights(x: &impl Fn(usize) -> Vector3<f64>, r: usize, nb: &[u32]) -> Option<Vec<f64>> {
    let xr = x(r);
    let scale = nb
        .iter()
        .map(|&k| (x(k as usize) - xr).norm())
        .fold(0.0, f64::max);
    if nb.len() < 2 || scale <= 0.0 {
        return None;
    }
    let a = nalgebra::DMatrix::from_fn(4, nb.len(), |i, j| {
        if i == 0 {
            1.0
        } else {
            (x(nb[j] as usize) - xr)[i - 1] / scale
        }
    });
    let pinv = a.clone().pseudo_inverse(1e-12).ok()?;
    let w = pinv.column(0).into_owned();
    let residual = &a * &w - nalgebra::DVector::from_fn(4, |i, _| if i == 0 { 1.0 } else { 0.0 });
    (residual.amax() <= 1e-10).then(|| w.iter().copied().collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use mortar_core::element::ElementRef;
    use mortar_elements::{LINE2, LINE3};

    /// A straight slave line along x from 0 to 1 in `faces` faces of `element`, nodes tagged
    /// by position (the middle nodes of Line3 at the centres).
    fn line(element: ElementRef, faces: u64) -> SurfaceMesh {
        let k = element.node_count() as u64 - 1;
        let n = faces * k;
        let mut mesh = SurfaceMesh::new();
        for i in 0..=n {
            mesh.add_node(i, [i as f64 / n as f64, 0.0, 0.0]).unwrap();
        }
        for f in 0..faces {
            let a = f * k;
            let nodes: Vec<u64> = if k == 1 {
                vec![a, a + 1]
            } else {
                vec![a, a + 2, a + 1]
            };
            mesh.add_face(element, &nodes).unwrap();
        }
        mesh
    }

    /// The rows of the shares matrix as dense vectors.
    fn dense(s: &SparseMatrix) -> Vec<Vec<f64>> {
        (0..s.rows())
            .map(|r| {
                (0..s.cols())
                    .map(|c| s.get(r, c).copied().unwrap_or(0.0))
                    .collect()
            })
            .collect()
    }

    /// Both ends of a line of Line2 are Dirichlet nodes: each end's row goes whole to its one
    /// free neighbour (the rows still sum to the identity's: constants are kept); of Line3,
    /// with the weights that keep linear functions, 2 on the middle node and -1 on the far
    /// end (the end's position is `2 x_mid - x_far`).
    #[test]
    fn end_rows_are_shared_with_their_neighbours() {
        let mesh = line(&LINE2, 4);
        let nodes: Vec<u32> = (0..5).collect();
        let dirichlet = [true, false, false, false, true];
        let s = slave_dirichlet_shares(&mesh, &nodes, &[true; 5], &dirichlet).unwrap();
        assert_eq!(s.rows, [1, 2, 3]);
        assert_eq!((s.redistributed, s.dropped), (2, 0));
        assert_eq!(
            dense(&s.s),
            [
                [1.0, 1.0, 0.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 0.0, 1.0, 1.0]
            ]
        );
        let mesh = line(&LINE3, 2);
        let nodes: Vec<u32> = (0..5).collect();
        let s = slave_dirichlet_shares(&mesh, &nodes, &[true; 5], &dirichlet).unwrap();
        let d = dense(&s.s);
        assert_eq!(s.rows, [1, 2, 3]);
        assert!(
            (d[0][0] - 2.0).abs() < 1e-12 && (d[1][0] + 1.0).abs() < 1e-12,
            "{d:?}"
        );
        assert!(
            (d[2][4] - 2.0).abs() < 1e-12 && (d[1][4] + 1.0).abs() < 1e-12,
            "{d:?}"
        );
        // A row of a node without a multiplier is neither kept nor shared.
        let s =
            slave_dirichlet_shares(&mesh, &nodes, &[true, false, true, true, true], &[false; 5])
                .unwrap();
        assert_eq!(s.rows, [0, 2, 3, 4]);
        assert!(slave_dirichlet_shares(&mesh, &nodes[..4], &[true; 5], &dirichlet).is_err());
        assert!(slave_dirichlet_shares(&mesh, &[0, 1, 2, 3, 9], &[true; 5], &dirichlet).is_err());
    }
}
