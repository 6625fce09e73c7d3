//! Whether a computed solution of a linear system has correct digits.

use super::SparseMatrix;

/// The condition number beyond which a solution is refused: `1e-3 / eps`, so that a
/// solution keeps about three correct digits.
pub const MAX_CONDITION: f64 = 1e-3 / f64::EPSILON;

/// The largest absolute entry of `x`.
pub fn inf_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// Whether the bound from below of the condition number of `a` that the solution `x` of
/// `a x = b` gives, `|a| |x| / |b|` (infinity norms, `b_norm = |b|`), is at most
/// [`MAX_CONDITION`]. Above it the solution has no correct digit, however the factorisation
/// went: a singular matrix whose round-off left a small positive pivot (a body held in some
/// direction by nothing) gives a solution of arbitrary size. Meaningful when the unknowns
/// share a unit (displacements, temperatures); in a saddle point of displacements and
/// pressures the bound mixes units.
///
/// ```
/// use mortar_fem::linalg::{well_conditioned, Triplets};
/// let mut t = Triplets::default();
/// t.push(0, 0, 2.0);
/// t.push(1, 1, 1e-20); // a round-off pivot
/// let a = t.to_csr(2, 2);
/// assert!(well_conditioned(&a, &[0.5, 0.0], 1.0));
/// assert!(!well_conditioned(&a, &[0.5, 1e20], 1.0));
/// ```
pub fn well_conditioned(a: &SparseMatrix, x: &[f64], b_norm: f64) -> bool {
    let a_norm = a
        .outer_iterator()
        .map(|row| row.iter().map(|(_, v)| v.abs()).sum::<f64>())
        .fold(0.0f64, f64::max);
    a_norm * inf_norm(x) <= MAX_CONDITION * b_norm
}
