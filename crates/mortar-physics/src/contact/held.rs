//! Which rigid motions of two bodies in contact their displacement conditions and the contact
//! leave free.
//!
//! A body's rigid motions (translations and rotations; 3 in plane strain, 6 in 3D) cost no
//! strain energy: only its Dirichlet conditions and the contact hold them. Frictionless
//! contact pushes along the slave's normals only, so a motion that moves no slave interface
//! node along its normal (a block on a flat base sliding sideways, a disc spinning in a ring)
//! is held by nothing but the Dirichlet conditions. Left free, the Newton system is singular
//! in that direction and a direct solver returns one solution out of a line of them: an
//! arbitrary rigid shift. [`rigid_motions`] finds such motions before the solve, so that a
//! scene can refuse them naming the body and the motion.
//!
//! The test is linear algebra on the rigid modes `r_k` of each body (translations along the
//! axes; rotations about the axes through the body's centroid, scaled by the size `L` of its
//! bounding box so that every mode moves the body's nodes by about one unit): a combination
//! `r = sum c_k r_k` is held by the Dirichlet conditions when it moves a prescribed unknown,
//! `|R_D c| > 0`, and may be held by contact when it changes a weighted gap, `|N R c| > 0`
//! (`N` the [`NormalGap`]'s matrix). The motions held by neither are the null space of
//! `[R_D; N R]`, found from the eigenvectors of the small Gram matrices (3 x 3 or 6 x 6) whose
//! eigenvalues are below [`FREE_MOTION_TOLERANCE`] of the largest scale they can take.

use nalgebra::{DMatrix, SymmetricEigen, Vector3};

use super::NormalGap;

/// A combination of rigid modes counts as unheld when its Gram eigenvalue is below this
/// fraction of the scale it would have if every row held it (the number of prescribed
/// unknowns for the Dirichlet conditions; the sum of the squared nodal weights for the
/// contact). Two fixed points a millionth of the body's size apart still hold a rotation
/// (eigenvalue 1e-12 of the scale); a single fixed point does not (rounding, 1e-30).
pub const FREE_MOTION_TOLERANCE: f64 = 1e-14;

/// A rigid motion of one body, in terms of its translation and rotation.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidMotion {
    /// The translation (unit length when the motion is a translation only).
    pub translation: Vector3<f64>,
    /// The rotation vector (radians per unit of the modes' scale; zero for a translation).
    pub rotation: Vector3<f64>,
    /// The point the rotation is about (the body's centroid).
    pub centre: Vector3<f64>,
    /// The dimension of the body (2 or 3).
    pub dim: usize,
}

impl RigidMotion {
    /// A phrase for a person: `"translation along x"`, `"translation along (0.71, 0.71)"`,
    /// `"rotation about z through (0.5, 1.5)"`, or a rotation with a translation.
    pub fn describe(&self) -> String {
        let d = self.dim;
        let t = self.translation;
        let w = self.rotation;
        let scale = t.norm().max(w.norm());
        let small = |v: f64| v.abs() <= 1e-9 * scale;
        let vector = |v: &Vector3<f64>| {
            let n = v.norm();
            let axes = ["x", "y", "z"];
            for (k, axis) in axes.iter().enumerate().take(d) {
                if (0..d).all(|i| i == k || small(v[i] / n * scale)) {
                    return axis.to_string();
                }
            }
            let parts: Vec<String> = (0..d).map(|i| format!("{:.3}", v[i] / n)).collect();
            format!("({})", parts.join(", "))
        };
        let point = |p: &Vector3<f64>| {
            let parts: Vec<String> = (0..d).map(|i| format!("{:.6e}", p[i])).collect();
            format!("({})", parts.join(", "))
        };
        let rotates = w.norm() > 1e-9 * scale;
        let translates = t.norm() > 1e-9 * scale;
        match (translates, rotates) {
            (true, false) => format!("translation along {}", vector(&t)),
            (false, true) if d == 2 => format!("rotation about z through {}", point(&self.centre)),
            (false, true) => format!(
                "rotation about the axis {} through {}",
                vector(&w),
                point(&self.centre)
            ),
            _ if d == 2 => {
                // u = w e_z x (x - c) + t is a rotation about c + e_z x t / w.
                let c = self.centre + Vector3::new(-t.y, t.x, 0.0) / w.z;
                format!("rotation about z through {}", point(&c))
            }
            _ => format!(
                "rotation about the axis {} through {} with a translation along {}",
                vector(&w),
                point(&self.centre),
                vector(&t)
            ),
        }
    }
}

/// What holds one body's rigid motions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct HeldMotions {
    /// Motions the Dirichlet conditions leave free but the contact may hold (once it closes
    /// and presses): the body rests on the contact there, and pulling it off leaves it free.
    pub by_contact_only: Vec<RigidMotion>,
    /// Motions held neither by the Dirichlet conditions nor by the contact.
    pub free: Vec<RigidMotion>,
}

/// For each of the two bodies of a contact problem (slave first), the rigid motions their
/// Dirichlet conditions leave free, and those the contact does not hold either (a body held
/// by contact alone in some direction is sound only while the contact is active). `coords` are the bodies' node coordinates (index order),
/// `dirichlet` their prescribed unknowns (`node * dim + k`), `gap` the contact's normal gap
/// (columns: the slave body's unknowns, then the master body's). Cartesian bodies (plane
/// strain in 2D, or 3D); an axisymmetric body's only rigid motion is along its axis.
pub fn rigid_motions(
    coords: [&[Vector3<f64>]; 2],
    dirichlet: [&[u32]; 2],
    gap: &NormalGap,
) -> [HeldMotions; 2] {
    let dim = gap.dim;
    let offset = [0, coords[0].len() * dim];
    std::array::from_fn(|b| body_motions(coords[b], dirichlet[b], gap, offset[b], dim))
}

/// [`rigid_motions`] of one body whose unknowns start at column `offset` of the gap.
fn body_motions(
    coords: &[Vector3<f64>],
    dirichlet: &[u32],
    gap: &NormalGap,
    offset: usize,
    dim: usize,
) -> HeldMotions {
    let n = coords.len();
    if n == 0 {
        return HeldMotions::default();
    }
    let rigid = Modes::new(coords, dim);
    let modes = rigid.count;
    let mode = |k: usize, node: usize, a: usize| rigid.value(k, node, a);
    // Dirichlet: the Gram matrix of the modes over the prescribed unknowns.
    let rows_d: Vec<Vec<f64>> = dirichlet
        .iter()
        .map(|&u| {
            let (node, a) = (u as usize / dim, u as usize % dim);
            (0..modes).map(|k| mode(k, node, a)).collect()
        })
        .collect();
    let free_d = null_space(&gram(&rows_d, modes), dirichlet.len() as f64);
    if free_d.ncols() == 0 {
        return HeldMotions::default();
    }
    // Contact: the change of each weighted gap under each mode left free.
    let mut rows_c = Vec::with_capacity(gap.matrix.rows());
    for row in gap.matrix.outer_iterator() {
        let mut r = vec![0.0; modes];
        for (col, v) in row.iter() {
            if col < offset || col >= offset + n * dim {
                continue;
            }
            let (node, a) = ((col - offset) / dim, (col - offset) % dim);
            for (k, rk) in r.iter_mut().enumerate() {
                *rk += v * mode(k, node, a);
            }
        }
        let along: Vec<f64> = (0..free_d.ncols())
            .map(|f| (0..modes).map(|k| r[k] * free_d[(k, f)]).sum())
            .collect();
        rows_c.push(along);
    }
    let scale: f64 = gap.weights.iter().map(|w| w * w).sum();
    let free_c = null_space(&gram(&rows_c, free_d.ncols()), scale);
    let motion = |c: &[f64]| rigid.motion(c);
    let in_modes = |combination: &[f64]| -> Vec<f64> {
        (0..modes)
            .map(|k| {
                (0..free_d.ncols())
                    .map(|f| free_d[(k, f)] * combination[f])
                    .sum()
            })
            .collect()
    };
    let free: Vec<RigidMotion> = (0..free_c.ncols())
        .map(|j| motion(&in_modes(free_c.column(j).as_slice())))
        .collect();
    let by_contact_only = (0..free_d.ncols())
        .map(|f| motion(free_d.column(f).as_slice()))
        .collect();
    HeldMotions {
        by_contact_only,
        free,
    }
}

/// The rigid modes of a body: the translations along the axes, then the rotations about
/// its centre (about z in 2D, about x, y, z in 3D) scaled by its size, so that all are of
/// the order of one.
struct Modes<'a> {
    coords: &'a [Vector3<f64>],
    centre: Vector3<f64>,
    size: f64,
    dim: usize,
    /// Their number: 3 in 2D, 6 in 3D.
    count: usize,
}

impl<'a> Modes<'a> {
    /// The modes of the body of nodes `coords` (not empty), `dim` components.
    fn new(coords: &'a [Vector3<f64>], dim: usize) -> Self {
        let (lo, hi) = coords
            .iter()
            .fold((coords[0], coords[0]), |(lo, hi), x| (lo.inf(x), hi.sup(x)));
        let centre = coords.iter().sum::<Vector3<f64>>() / coords.len() as f64;
        let size = (hi - lo).norm().max(f64::MIN_POSITIVE);
        Self {
            coords,
            centre,
            size,
            dim,
            count: if dim == 2 { 3 } else { 6 },
        }
    }

    /// The value of mode `k` at unknown `node * dim + a`.
    fn value(&self, k: usize, node: usize, a: usize) -> f64 {
        let dim = self.dim;
        if k < dim {
            return f64::from(u8::from(k == a));
        }
        let x = (self.coords[node] - self.centre) / self.size;
        let w = if dim == 2 {
            Vector3::z()
        } else {
            Vector3::ith(k - dim, 1.0)
        };
        w.cross(&x)[a]
    }

    /// The motion of the combination `c` of the modes.
    fn motion(&self, c: &[f64]) -> RigidMotion {
        let dim = self.dim;
        let mut translation = Vector3::zeros();
        let mut rotation = Vector3::zeros();
        for k in 0..dim {
            translation[k] = c[k];
        }
        if dim == 2 {
            rotation.z = c[2] / self.size;
        } else {
            for k in 0..3 {
                rotation[k] = c[3 + k] / self.size;
            }
        }
        RigidMotion {
            translation,
            rotation,
            centre: self.centre,
            dim,
        }
    }
}

/// `A^T A` of the rows `rows` (each of length `m`).
fn gram(rows: &[Vec<f64>], m: usize) -> DMatrix<f64> {
    let mut g = DMatrix::zeros(m, m);
    for r in rows {
        for i in 0..m {
            for j in 0..m {
                g[(i, j)] += r[i] * r[j];
            }
        }
    }
    g
}

/// The eigenvectors (as columns) of the symmetric `g` whose eigenvalues are at most
/// [`FREE_MOTION_TOLERANCE`] times `scale`, in a fixed order (ascending eigenvalue), each
/// with its largest component positive.
fn null_space(g: &DMatrix<f64>, scale: f64) -> DMatrix<f64> {
    let m = g.nrows();
    if m == 0 {
        return DMatrix::zeros(0, 0);
    }
    let eigen = SymmetricEigen::new(g.clone());
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]));
    let kept: Vec<usize> = order
        .into_iter()
        .filter(|&i| eigen.eigenvalues[i] <= FREE_MOTION_TOLERANCE * scale)
        .collect();
    let mut out = DMatrix::zeros(m, kept.len());
    for (j, &i) in kept.iter().enumerate() {
        let mut v = eigen.eigenvectors.column(i).into_owned();
        let largest = v
            .iter()
            .copied()
            .fold(0.0f64, |a, x| if x.abs() > a.abs() { x } else { a });
        if largest < 0.0 {
            v = -v;
        }
        out.set_column(j, &v);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn motion(t: [f64; 3], w: [f64; 3], dim: usize) -> RigidMotion {
        RigidMotion {
            translation: Vector3::from(t),
            rotation: Vector3::from(w),
            centre: Vector3::new(0.5, 1.5, 0.0),
            dim,
        }
    }

    #[test]
    fn motions_are_described_by_axis_and_point() {
        assert_eq!(
            motion([1.0, 0.0, 0.0], [0.0; 3], 2).describe(),
            "translation along x"
        );
        assert_eq!(
            motion([0.6, 0.8, 0.0], [0.0; 3], 2).describe(),
            "translation along (0.600, 0.800)"
        );
        assert!(motion([0.0; 3], [0.0, 0.0, 1.0], 2)
            .describe()
            .starts_with("rotation about z through (5.000000e-1, 1.500000e0)"));
        // u = e_z x (x - c) + (0, 1): a rotation about c + (-1, 0).
        assert!(motion([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], 2)
            .describe()
            .starts_with("rotation about z through (-5.000000e-1, 1.500000e0)"));
        assert!(motion([0.0; 3], [0.0, 1.0, 0.0], 3)
            .describe()
            .starts_with("rotation about the axis y"));
    }
}
