//! Euclidean norms that neither overflow nor underflow: a face's scaled normal is a product of
//! two lengths, and its squared norm a product of four, which leaves double precision for
//! meshes at 1e-100 or 1e100 while the norm itself is representable.

use nalgebra::SVector;

/// The smallest squared norm computed directly: below it the squares lose precision
/// (subnormal) or vanish.
const SAFE_SQUARED_MIN: f64 = f64::MIN_POSITIVE / f64::EPSILON;

/// The Euclidean norm of `v`, exact to rounding whatever the magnitude of its components (a
/// finite result whenever the norm is representable). Components whose squares stay in the
/// normal range take the direct path, bit for bit the same as `v.norm()`; others are scaled
/// by the largest component first.
#[inline]
pub fn stable_norm<const D: usize>(v: &SVector<f64, D>) -> f64 {
    let squared = v.norm_squared();
    if squared.is_finite() && squared >= SAFE_SQUARED_MIN {
        return squared.sqrt();
    }
    let largest = v.amax();
    if largest == 0.0 || !largest.is_finite() {
        return largest;
    }
    largest * (v / largest).norm()
}

/// `v` divided by its [`stable_norm`], or `None` when it is zero or not finite.
#[inline]
pub fn stable_normalize<const D: usize>(v: &SVector<f64, D>) -> Option<SVector<f64, D>> {
    let len = stable_norm(v);
    (len > 0.0 && len.is_finite()).then(|| v / len)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn norms_at_any_scale() {
        let v = Vector3::new(3.0, -4.0, 12.0);
        for s in [
            1e-300, 1e-200, 1e-160, 1e-100, 1.0, 1e100, 1e160, 1e200, 1e300,
        ] {
            let n = stable_norm(&(v * s));
            assert!(
                (n / (13.0 * s) - 1.0).abs() <= 2.0 * f64::EPSILON,
                "{s:e}: {n:e}"
            );
            let u = stable_normalize(&(v * s)).unwrap();
            assert!((u - v / 13.0).amax() <= 2.0 * f64::EPSILON, "{s:e}: {u:?}");
        }
        assert_eq!(stable_norm(&Vector3::zeros()), 0.0);
        assert!(stable_normalize(&Vector3::<f64>::zeros()).is_none());
        // The direct path is the plain norm.
        assert_eq!(stable_norm(&v), v.norm());
    }
}
