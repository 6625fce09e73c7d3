//! A fill-reducing ordering by nested dissection (METIS, through `metis-sys`): the one module
//! of the toolkit that names METIS, and one of its two `unsafe` calls (the other is glibc's
//! `malloc_trim`, in `memory.rs`).
//!
//! For the stiffness matrices of 3D meshes, nested dissection leaves several times less fill
//! in a Cholesky factor than approximate minimum degree (faer's default), and the factor's
//! cost falls with it; for 2D and small matrices the two are close. Nodes of a vector field
//! share their pattern (`d` unknowns per node): the graph is compressed to one vertex per
//! group of consecutive unknowns with identical rows before METIS sees it, which makes the
//! ordering `d^2` times cheaper, and the groups stay together in the ordering.

use super::SparseMatrix;

/// The mean number of neighbours per node from which [`nested_dissection`] orders a graph:
/// the graphs of 3D meshes have 14 (Tet4) to 26 (Hex8), those of 2D meshes 6 (Tri3) to 8
/// (Quad4). Measured on the contact systems of `bench_contact` (faer's supernodal Cholesky):
/// a 3D system of 9.0e4 unknowns factorised in 6.5 s by nested dissection against 9.7 s by
/// minimum degree (fill 8.5e7 against 1.2e8 entries), a 2D one of 3.7e5 in 2.8 s against
/// 1.7 s (less fill, 3.6e7 against 4.1e7, but a slower factorisation and a 1 s longer
/// analysis).
pub const MIN_MEAN_DEGREE: f64 = 12.0;

/// The fill-reducing permutation of the symmetric pattern of `a` (square; both triangles or
/// one, the pattern is symmetrised), `perm[new] = old`, for a graph of 3D character (a mean
/// node degree of [`MIN_MEAN_DEGREE`] or more); `None` for a sparser graph, or when METIS
/// fails or the matrix is too large for its 32-bit indices (the caller then keeps its
/// default ordering).
pub fn nested_dissection(a: &SparseMatrix) -> Option<Vec<usize>> {
    let n = a.rows();
    if n != a.cols() || n == 0 {
        return None;
    }
    // Groups of consecutive unknowns with identical rows (the components of a node).
    // (Rows of a CSR matrix, columns of a CSC one: the same graph once symmetrised.)
    let (ptr, idx) = (a.proper_indptr(), a.indices());
    let row = |i: usize| &idx[ptr[i]..ptr[i + 1]];
    let mut group_start = vec![0usize];
    for i in 1..n {
        if row(i) != row(i - 1) {
            group_start.push(i);
        }
    }
    group_start.push(n);
    let groups = group_start.len() - 1;
    let mut group_of = vec![0u32; n];
    for g in 0..groups {
        group_of[group_start[g]..group_start[g + 1]].fill(g as u32);
    }
    // The graph of the groups, symmetrised: both directions of every stored entry, counted,
    // then placed, then sorted and deduplicated per vertex.
    let edges = |g: usize| {
        let first = group_start[g];
        row(first)
            .iter()
            .map(|&j| group_of[j] as usize)
            .filter(move |&h| h != g)
    };
    // A first look at the degree, from the stored entries alone (a one-triangle storage
    // shows half of them): a graph of 2D character is rejected before it is built.
    let stored: usize = (0..groups)
        .map(|g| {
            // Sorted columns: the entries of a neighbouring group are consecutive.
            let mut last = usize::MAX;
            edges(g)
                .filter(|&h| std::mem::replace(&mut last, h) != h)
                .count()
        })
        .sum();
    if (2 * stored) < (MIN_MEAN_DEGREE * groups as f64) as usize {
        return None;
    }
    let mut count = vec![0usize; groups + 1];
    for g in 0..groups {
        for h in edges(g) {
            count[g + 1] += 1;
            count[h + 1] += 1;
        }
    }
    for g in 0..groups {
        count[g + 1] += count[g];
    }
    let mut next = count.clone();
    let mut adj = vec![0u32; count[groups]];
    for g in 0..groups {
        for h in edges(g) {
            adj[next[g]] = h as u32;
            next[g] += 1;
            adj[next[h]] = g as u32;
            next[h] += 1;
        }
    }
    drop(next);
    let mut xadj: Vec<i32> = Vec::with_capacity(groups + 1);
    let mut adjncy: Vec<i32> = Vec::with_capacity(adj.len() / 2);
    xadj.push(0);
    for g in 0..groups {
        let list = &mut adj[count[g]..count[g + 1]];
        list.sort_unstable();
        let mut last = None;
        for &h in list.iter() {
            if last != Some(h) {
                adjncy.push(i32::try_from(h).ok()?);
                last = Some(h);
            }
        }
        xadj.push(i32::try_from(adjncy.len()).ok()?);
    }
    drop(adj);
    if (adjncy.len() as f64) < MIN_MEAN_DEGREE * groups as f64 {
        return None;
    }
    let group_perm = metis_node_nd(&mut xadj, &mut adjncy)?;
    let mut perm = Vec::with_capacity(n);
    for g in group_perm {
        perm.extend(group_start[g]..group_start[g + 1]);
    }
    Some(perm)
}

/// METIS_NodeND on the graph `(xadj, adjncy)` (no self loops, symmetric): the permutation of
/// its vertices, `perm[new] = old`.
#[allow(unsafe_code)]
fn metis_node_nd(xadj: &mut [i32], adjncy: &mut [i32]) -> Option<Vec<usize>> {
    let mut nvtxs = i32::try_from(xadj.len() - 1).ok()?;
    let len = xadj.len() - 1;
    let mut perm = vec![0i32; len];
    let mut iperm = vec![0i32; len];
    if len == 1 {
        return Some(vec![0]);
    }
    // SAFETY: `xadj` has `nvtxs + 1` entries, monotone from 0 to `adjncy.len()`, and every
    // entry of `adjncy` is a vertex in `0..nvtxs` (built so above); `perm` and `iperm` have
    // `nvtxs` entries; null `vwgt` and `options` ask for unit weights and METIS's defaults.
    // METIS reads the graph and writes only `perm` and `iperm`.
    let status = unsafe {
        metis_sys::METIS_NodeND(
            &mut nvtxs,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return None;
    }
    let perm: Vec<usize> = perm.into_iter().map(|p| p as usize).collect();
    // A permutation, or nothing.
    let mut seen = vec![false; len];
    for &p in &perm {
        if p >= len || std::mem::replace(&mut seen[p], true) {
            return None;
        }
    }
    Some(perm)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::Triplets;

    #[test]
    fn orders_grid_graphs_of_3d_character_with_grouped_components() {
        // The 2-component pattern of a 27-point stencil on an m^3 grid (that of Hex8
        // elasticity), stored whole or by its upper triangle: a permutation, and the two
        // components of a node stay next to each other. The 9-point stencil of a 2D grid
        // (Quad4) is left to minimum degree.
        let grid = |m: usize, dims: usize, upper: bool| {
            let nodes = m.pow(dims as u32);
            let coord = |p: usize| [p % m, (p / m) % m, p / (m * m)];
            let mut t = Triplets::default();
            for p in 0..nodes {
                for q in 0..nodes {
                    let (x, y) = (coord(p), coord(q));
                    if (0..3).all(|k| x[k].abs_diff(y[k]) <= 1) && (!upper || q >= p) {
                        for a in 0..2 {
                            for b in 0..2 {
                                if !upper || 2 * q + b >= 2 * p + a {
                                    let v = if p == q && a == b { 30.0 } else { -0.1 };
                                    t.push((2 * p + a) as u32, (2 * q + b) as u32, v);
                                }
                            }
                        }
                    }
                }
            }
            t.to_csr(2 * nodes, 2 * nodes)
        };
        for upper in [false, true] {
            let a = grid(8, 3, upper);
            let perm = nested_dissection(&a).expect("an ordering");
            let mut sorted = perm.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..a.rows()).collect::<Vec<_>>());
            if !upper {
                for pair in perm.chunks(2) {
                    assert_eq!(pair[0] % 2, 0);
                    assert_eq!(pair[1], pair[0] + 1);
                }
            }
        }
        assert_eq!(nested_dissection(&grid(20, 2, false)), None);
    }
}
