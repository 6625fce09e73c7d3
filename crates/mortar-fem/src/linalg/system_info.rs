//! What a caller knows of a linear system beyond its matrix ([`SystemInfo`]), for a backend
//! that can use it: an algebraic multigrid coarsens elasticity well only when it knows the
//! body's rigid motions (its near null space), which the matrix alone does not show once
//! prescribed unknowns are eliminated.

/// What a caller knows of a system beyond its matrix. A direct backend needs none of it; an
/// iterative one picks its method by it (a saddle point's multipliers) and gives its
/// preconditioner what it needs (a displacement field's rigid motions).
#[derive(Clone, Copy, Debug, Default)]
pub struct SystemInfo<'a> {
    /// For the system of a displacement field: where each unknown sits.
    pub displacements: Option<UnknownPlaces<'a>>,
    /// How many of the last unknowns are Lagrange multipliers, the matrix a saddle point
    /// `[A B^T; B C]` with them last (0: none).
    pub multipliers_last: usize,
}

/// Where the unknowns of a displacement field's system sit: per unknown (in the system's
/// numbering, whatever unknowns were eliminated from it), its node's position and its
/// component.
#[derive(Clone, Copy, Debug)]
pub struct UnknownPlaces<'a> {
    /// The space dimension: 2 or 3.
    pub dim: usize,
    /// Whether the field is axisymmetric (r-z, `x` the radius): then only the axial
    /// translation is a rigid motion.
    pub axisymmetric: bool,
    /// Per unknown, its node's coordinates (`z = 0` in 2D).
    pub points: &'a [[f64; 3]],
    /// Per unknown, its component (`0..dim`).
    pub components: &'a [u8],
}

impl UnknownPlaces<'_> {
    /// The rigid motions of the body restricted to these unknowns, one vector over the
    /// unknowns each: in 2D the translations along x and y and the rotation about z
    /// (`(-y, x)`); in 3D three translations and three rotations (`e_k x p`); in r-z the
    /// axial translation alone. Not normalised.
    ///
    /// ```
    /// use mortar_fem::linalg::UnknownPlaces;
    /// // One node at (1, 2), both components.
    /// let places = UnknownPlaces {
    ///     dim: 2,
    ///     axisymmetric: false,
    ///     points: &[[1.0, 2.0, 0.0], [1.0, 2.0, 0.0]],
    ///     components: &[0, 1],
    /// };
    /// let modes = places.rigid_body_modes();
    /// assert_eq!(modes, vec![vec![1.0, 0.0], vec![0.0, 1.0], vec![-2.0, 1.0]]);
    /// ```
    pub fn rigid_body_modes(&self) -> Vec<Vec<f64>> {
        let n = self.points.len().min(self.components.len());
        let translation = |k: u8| -> Vec<f64> {
            (0..n)
                .map(|i| f64::from(u8::from(self.components[i] == k)))
                .collect()
        };
        if self.axisymmetric {
            return vec![translation(1)];
        }
        // The rotation about axis `axis` moves a point p by e_axis x p.
        let rotation = |axis: usize| -> Vec<f64> {
            (0..n)
                .map(|i| {
                    let p = self.points[i];
                    // Row k: e_k x p.
                    let e = [[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]];
                    e[axis][self.components[i] as usize % 3]
                })
                .collect()
        };
        if self.dim == 2 {
            vec![translation(0), translation(1), rotation(2)]
        } else {
            let mut modes: Vec<Vec<f64>> = (0..3).map(translation).collect();
            modes.extend((0..3).map(rotation));
            modes
        }
    }
}
