//! A displacement field's system embedded in whole node blocks ([`Blocks`]): smoothed
//! aggregation coarsens a vector problem by nodes only when the matrix has a block size, and
//! a system from which prescribed or condensed unknowns were eliminated has none. Each node
//! gets its `dim` slots back; a slot without an unknown is a decoupled row `c x = 0` (`c` the
//! mean diagonal, so that it neither helps nor hurts the conditioning), and the nodes'
//! coordinates give GAMG the rigid body modes.

use std::collections::HashMap;

use mortar_core::linalg::SparseMatrix;
use mortar_fem::linalg::UnknownPlaces;

/// Where each unknown of a system goes in the blocked system of its nodes.
#[derive(Debug, Clone)]
pub(crate) struct Blocks {
    /// Components per node.
    pub dim: usize,
    /// Per unknown, its slot `node * dim + component`.
    slot: Vec<usize>,
    /// Slots: `nodes * dim`.
    pub size: usize,
    /// The nodes' coordinates, `dim` per node.
    pub coordinates: Vec<f64>,
}

impl Blocks {
    /// The blocks of the unknowns at `places` (nodes found by their coordinates), or
    /// `None` for an axisymmetric field (whose rigid motion is the axial one alone, which
    /// PETSc's rigid body modes do not describe) or a component out of range. Unknowns of one
    /// component at one point (two bodies' nodes where they touch) go to separate nodes.
    pub fn of(places: &UnknownPlaces<'_>) -> Option<Self> {
        let dim = places.dim;
        if places.axisymmetric || !(dim == 2 || dim == 3) {
            return None;
        }
        // The nodes at each point (two bodies touching have nodes at the same points), and
        // per node which slots are taken.
        let mut nodes_at: HashMap<[u64; 3], Vec<usize>> = HashMap::new();
        let mut taken: Vec<bool> = Vec::new();
        let mut coordinates = Vec::new();
        let mut slot = Vec::with_capacity(places.points.len());
        for (p, &c) in places.points.iter().zip(places.components) {
            let c = c as usize;
            if c >= dim {
                return None;
            }
            let at = nodes_at.entry(p.map(f64::to_bits)).or_default();
            let node = match at.iter().find(|&&n| !taken[n * dim + c]) {
                Some(&n) => n,
                None => {
                    let n = taken.len() / dim;
                    taken.resize(taken.len() + dim, false);
                    coordinates.extend_from_slice(&p[..dim]);
                    at.push(n);
                    n
                }
            };
            taken[node * dim + c] = true;
            slot.push(node * dim + c);
        }
        let size = taken.len();
        Some(Self {
            dim,
            slot,
            size,
            coordinates,
        })
    }

    /// The number of the caller's unknowns.
    pub fn unknowns(&self) -> usize {
        self.slot.len()
    }

    /// `b` in the blocked numbering (zero in the empty slots).
    #[cfg_attr(not(feature = "petsc"), allow(dead_code))]
    pub fn scatter(&self, b: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.size];
        for (&s, &v) in self.slot.iter().zip(b) {
            out[s] = v;
        }
        out
    }

    /// The unknowns' values of the blocked `x`.
    #[cfg_attr(not(feature = "petsc"), allow(dead_code))]
    pub fn gather(&self, x: &[f64], out: &mut [f64]) {
        for (o, &s) in out.iter_mut().zip(&self.slot) {
            *o = x[s];
        }
    }
}

/// The matrix PETSc solves for `a`: all of `a`, or (`upper`: a symmetric matrix given by its
/// upper triangle, which is all the solver interface reads of it) its upper triangle mirrored;
/// with `blocks`, its rows and columns moved to their slots, each empty slot's diagonal the
/// mean of `a`'s. Built in compressed form in two passes (counts, then entries, each row
/// sorted), no triplets: one copy of the matrix at a time.
pub(crate) fn petsc_matrix(a: &SparseMatrix, upper: bool, blocks: Option<&Blocks>) -> SparseMatrix {
    let n = blocks.map_or(a.rows(), |b| b.size);
    let at = |i: usize| blocks.map_or(i, |b| b.slot[i]);
    // Visits every entry of the result that comes from `a`, as (row, column, value).
    let visit = |f: &mut dyn FnMut(usize, usize, f64)| {
        for (&v, (i, j)) in a.iter() {
            if upper && i > j {
                continue;
            }
            f(at(i), at(j), v);
            if upper && i < j {
                f(at(j), at(i), v);
            }
        }
    };
    let mut used = vec![blocks.is_none(); n];
    if let Some(b) = blocks {
        for &s in &b.slot {
            used[s] = true;
        }
    }
    let mut count = vec![0usize; n + 1];
    let (mut diagonal, mut diagonals) = (0.0, 0usize);
    visit(&mut |r, c, v| {
        count[r + 1] += 1;
        if r == c {
            diagonal += v.abs();
            diagonals += 1;
        }
    });
    for (s, _) in used.iter().enumerate().filter(|(_, &u)| !u) {
        count[s + 1] += 1;
    }
    for r in 0..n {
        count[r + 1] += count[r];
    }
    let nnz = count[n];
    let mut indices = vec![0usize; nnz];
    let mut values = vec![0.0; nnz];
    let mut next = count.clone();
    visit(&mut |r, c, v| {
        indices[next[r]] = c;
        values[next[r]] = v;
        next[r] += 1;
    });
    let fill = if diagonals > 0 && diagonal > 0.0 {
        diagonal / diagonals as f64
    } else {
        1.0
    };
    for (s, _) in used.iter().enumerate().filter(|(_, &u)| !u) {
        indices[next[s]] = s;
        values[next[s]] = fill;
    }
    let mut row: Vec<(usize, f64)> = Vec::new();
    for r in 0..n {
        let range = count[r]..count[r + 1];
        row.clear();
        row.extend(
            indices[range.clone()]
                .iter()
                .copied()
                .zip(values[range.clone()].iter().copied()),
        );
        row.sort_unstable_by_key(|e| e.0);
        for (k, (c, v)) in range.zip(&row) {
            indices[k] = *c;
            values[k] = *v;
        }
    }
    SparseMatrix::new((n, n), count, indices, values)
}

#[cfg(test)]
mod tests {
    use mortar_core::linalg::Triplets;

    use super::*;

    /// Three unknowns of two nodes in 2D (node B's x held): B's x slot is empty, decoupled
    /// with the mean diagonal; scatter and gather are inverse on the unknowns.
    #[test]
    fn unknowns_go_to_their_nodes_slots() {
        let points = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let places = UnknownPlaces {
            dim: 2,
            axisymmetric: false,
            points: &points,
            components: &[0, 1, 1],
        };
        let blocks = Blocks::of(&places).unwrap();
        assert_eq!(blocks.size, 4);
        assert_eq!(blocks.coordinates, vec![0.0, 0.0, 1.0, 0.0]);
        let mut t = Triplets::default();
        for (i, v) in [2.0, 4.0, 6.0].into_iter().enumerate() {
            t.push(i as u32, i as u32, v);
        }
        t.push(0, 2, 1.0);
        t.push(2, 0, 1.0);
        let a = t.to_csr(3, 3);
        let e = petsc_matrix(&a, false, Some(&blocks));
        assert_eq!(
            petsc_matrix(&a, true, Some(&blocks)),
            e,
            "the upper triangle mirrored"
        );
        assert_eq!(petsc_matrix(&a, false, None), a);
        assert_eq!(
            e.get(2, 2),
            Some(&4.0),
            "the empty slot holds the mean diagonal"
        );
        assert_eq!(e.get(0, 3), Some(&1.0));
        assert_eq!(e.get(3, 3), Some(&6.0));
        let b = [1.0, 2.0, 3.0];
        let mut back = [0.0; 3];
        blocks.gather(&blocks.scatter(&b), &mut back);
        assert_eq!(back, b);
        let axi = UnknownPlaces {
            axisymmetric: true,
            ..places
        };
        assert!(Blocks::of(&axi).is_none());
    }
}
