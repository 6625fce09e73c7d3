//! Test systems built in code, and the measures the tests compare.

use mortar_core::linalg::SparseMatrix;
use sprs::TriMat;

/// The 5-point Laplacian on the `m x m` interior nodes of the unit square, Dirichlet
/// boundary eliminated, scaled by h^2 (4 on the diagonal, -1 to each neighbour): SPD,
/// condition number growing as m^2.
pub fn poisson_2d(m: usize) -> SparseMatrix {
    let n = m * m;
    let mut t = TriMat::new((n, n));
    let id = |i: usize, j: usize| i * m + j;
    for i in 0..m {
        for j in 0..m {
            let r = id(i, j);
            t.add_triplet(r, r, 4.0);
            if i > 0 {
                t.add_triplet(r, id(i - 1, j), -1.0);
            }
            if i + 1 < m {
                t.add_triplet(r, id(i + 1, j), -1.0);
            }
            if j > 0 {
                t.add_triplet(r, id(i, j - 1), -1.0);
            }
            if j + 1 < m {
                t.add_triplet(r, id(i, j + 1), -1.0);
            }
        }
    }
    t.to_csr()
}

/// A smooth right-hand side of `n` entries (not an eigenvector of anything here).
pub fn rhs(n: usize) -> Vec<f64> {
    (0..n).map(|i| 1.0 + ((i as f64) * 0.37).sin()).collect()
}

/// `|x - y| / |y|` in the Euclidean norm.
pub fn relative_error(x: &[f64], y: &[f64]) -> f64 {
    let d: f64 = x.iter().zip(y).map(|(a, b)| (a - b) * (a - b)).sum();
    let n: f64 = y.iter().map(|b| b * b).sum();
    (d / n).sqrt()
}

/// `|b - A x| / |b|`.
pub fn relative_residual(a: &SparseMatrix, x: &[f64], b: &[f64]) -> f64 {
    let mut r = b.to_vec();
    for (row, vec) in a.outer_iterator().enumerate() {
        for (col, &v) in vec.iter() {
            r[row] -= v * x[col];
        }
    }
    let norm = |v: &[f64]| v.iter().map(|t| t * t).sum::<f64>().sqrt();
    norm(&r) / norm(b)
}

/// Plane-strain linear elasticity (E = 1, nu = 0.3) on the unit square, `m x m` bilinear
/// quadrilaterals (2 x 2 Gauss points), clamped on the left edge (x = 0, its unknowns
/// removed): the stiffness matrix, unknowns node by node with (u_x, u_y) interleaved, and
/// the free nodes' coordinates (x, y per node).
pub fn elasticity_2d(m: usize) -> (SparseMatrix, Vec<f64>) {
    let (e, nu) = (1.0, 0.3);
    let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let d = [
        [c * (1.0 - nu), c * nu, 0.0],
        [c * nu, c * (1.0 - nu), 0.0],
        [0.0, 0.0, c * (1.0 - 2.0 * nu) / 2.0],
    ];
    let h = 1.0 / m as f64;
    // The element stiffness of a square of side h (the same for every element).
    let g = 1.0 / 3f64.sqrt();
    let mut ke = [[0.0; 8]; 8];
    for (xi, eta) in [(-g, -g), (g, -g), (g, g), (-g, g)] {
        // Corners (-1,-1), (1,-1), (1,1), (-1,1); d/dx = (2/h) d/dxi.
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        let mut bmat = [[0.0; 8]; 3];
        for (a, (xa, ya)) in corners.iter().enumerate() {
            let dx = 0.25 * xa * (1.0 + ya * eta) * 2.0 / h;
            let dy = 0.25 * ya * (1.0 + xa * xi) * 2.0 / h;
            bmat[0][2 * a] = dx;
            bmat[1][2 * a + 1] = dy;
            bmat[2][2 * a] = dy;
            bmat[2][2 * a + 1] = dx;
        }
        let w = h * h / 4.0; // weight 1, det J = h^2 / 4
        for i in 0..8 {
            for j in 0..8 {
                let mut s = 0.0;
                for p in 0..3 {
                    for q in 0..3 {
                        s += bmat[p][i] * d[p][q] * bmat[q][j];
                    }
                }
                ke[i][j] += w * s;
            }
        }
    }
    // Nodes (i, j) at (i h, j h); those with i = 0 are clamped.
    let free = |i: usize, j: usize| (i > 0).then(|| (i - 1) * (m + 1) + j);
    let nodes = m * (m + 1);
    let mut t = TriMat::new((2 * nodes, 2 * nodes));
    for ei in 0..m {
        for ej in 0..m {
            let corner_nodes = [(ei, ej), (ei + 1, ej), (ei + 1, ej + 1), (ei, ej + 1)];
            for (a, &(ia, ja)) in corner_nodes.iter().enumerate() {
                let Some(na) = free(ia, ja) else { continue };
                for (b, &(ib, jb)) in corner_nodes.iter().enumerate() {
                    let Some(nb) = free(ib, jb) else { continue };
                    for ca in 0..2 {
                        for cb in 0..2 {
                            t.add_triplet(2 * na + ca, 2 * nb + cb, ke[2 * a + ca][2 * b + cb]);
                        }
                    }
                }
            }
        }
    }
    let mut coords = Vec::with_capacity(2 * nodes);
    for i in 1..=m {
        for j in 0..=m {
            coords.extend([i as f64 * h, j as f64 * h]);
        }
    }
    (t.to_csr(), coords)
}

/// The saddle point `[A B^T; B 0]` of the Poisson matrix on `m x m` nodes tied by `B`: each
/// node of column j = m/2 - 1 tied to its neighbour in column m/2 (`u_a - u_b = 0`), as a
/// mesh tying would; returns the matrix and the number of primal unknowns.
pub fn tied_poisson(m: usize) -> (SparseMatrix, usize) {
    let a = poisson_2d(m);
    let n = m * m;
    let k = m;
    let mut t = TriMat::new((n + k, n + k));
    for (row, vec) in a.outer_iterator().enumerate() {
        for (col, &v) in vec.iter() {
            t.add_triplet(row, col, v);
        }
    }
    for i in 0..m {
        let (p, q) = (i * m + m / 2 - 1, i * m + m / 2);
        for (col, v) in [(p, 1.0), (q, -1.0)] {
            t.add_triplet(n + i, col, v);
            t.add_triplet(col, n + i, v);
        }
    }
    (t.to_csr(), n)
}

/// The vector Laplacian (3 uncoupled components, each the 7-point Laplacian) on the `m^3`
/// interior nodes of the unit cube, unknowns node by node with the components interleaved,
/// and the nodes' coordinates (x, y, z per node): an SPD system with block size 3 whose
/// near null space contains the rigid body modes' translations.
pub fn vector_laplacian_3d(m: usize) -> (SparseMatrix, Vec<f64>) {
    let nodes = m * m * m;
    let id = |i: usize, j: usize, k: usize| (i * m + j) * m + k;
    let mut t = TriMat::new((3 * nodes, 3 * nodes));
    let mut coords = Vec::with_capacity(3 * nodes);
    let h = 1.0 / (m + 1) as f64;
    for i in 0..m {
        for j in 0..m {
            for k in 0..m {
                let r = id(i, j, k);
                coords.extend([(i + 1) as f64 * h, (j + 1) as f64 * h, (k + 1) as f64 * h]);
                let mut neighbours = Vec::new();
                if i > 0 {
                    neighbours.push(id(i - 1, j, k));
                }
                if i + 1 < m {
                    neighbours.push(id(i + 1, j, k));
                }
                if j > 0 {
                    neighbours.push(id(i, j - 1, k));
                }
                if j + 1 < m {
                    neighbours.push(id(i, j + 1, k));
                }
                if k > 0 {
                    neighbours.push(id(i, j, k - 1));
                }
                if k + 1 < m {
                    neighbours.push(id(i, j, k + 1));
                }
                for c in 0..3 {
                    t.add_triplet(3 * r + c, 3 * r + c, 6.0);
                    for &q in &neighbours {
                        t.add_triplet(3 * r + c, 3 * q + c, -1.0);
                    }
                }
            }
        }
    }
    (t.to_csr(), coords)
}
