//! A safeguarded scalar root finder: Newton inside a bracket, bisection when Newton leaves it.

/// Finds `x` in `[a, b]` with `f(x) = 0` for `f` of opposite signs (or zero) at the ends, where
/// `f` returns its value and derivative. Newton steps that stay inside the current bracket are
/// taken, bisection otherwise, so it converges for every continuous `f` with a sign change
/// (rtsafe, Numerical Recipes section 9.4). Stops when the bracket is narrower than `tol`
/// times `max(1, |x|)` or the value is exactly zero; at most `max_iterations` steps (each
/// halves the bracket at worst, so 60 reach the round-off of a unit interval).
///
/// Returns `None` if `f` does not change sign over `[a, b]` or is not finite at an end.
pub fn bracketed_root(
    mut f: impl FnMut(f64) -> (f64, f64),
    a: f64,
    b: f64,
    tol: f64,
    max_iterations: usize,
) -> Option<f64> {
    let (fa, _) = f(a);
    let (fb, _) = f(b);
    if !fa.is_finite() || !fb.is_finite() {
        return None;
    }
    if fa == 0.0 {
        return Some(a);
    }
    if fb == 0.0 {
        return Some(b);
    }
    if fa.signum() == fb.signum() {
        return None;
    }
    // `lo` is the end where f < 0.
    let (mut lo, mut hi) = if fa < 0.0 { (a, b) } else { (b, a) };
    let mut x = 0.5 * (a + b);
    for _ in 0..max_iterations.max(1) {
        let (fx, dfx) = f(x);
        if fx == 0.0 || !fx.is_finite() {
            return fx.is_finite().then_some(x);
        }
        if fx < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let newton = x - fx / dfx;
        let inside = newton.is_finite() && (newton - lo) * (newton - hi) < 0.0;
        let next = if inside { newton } else { 0.5 * (lo + hi) };
        let done =
            (next - x).abs() <= tol * x.abs().max(1.0) || (hi - lo).abs() <= tol * x.abs().max(1.0);
        x = next;
        if done {
            return Some(x);
        }
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_roots_newton_alone_misses() {
        // x^3 - 2x + 2 sends Newton from 0 into the cycle 0, 1, 0, ...; the bracket does not.
        let f = |x: f64| (x * x * x - 2.0 * x + 2.0, 3.0 * x * x - 2.0);
        let r = bracketed_root(f, -3.0, 0.0, 1e-15, 100).unwrap();
        assert!(f(r).0.abs() < 1e-13, "{r}");
        // A flat-then-steep function whose derivative vanishes at the start.
        let g = |x: f64| (x.powi(9) - 1e-9, 9.0 * x.powi(8));
        let r = bracketed_root(g, -1.0, 1.0, 1e-15, 200).unwrap();
        assert!((r - 0.1).abs() < 1e-12, "{r}");
    }

    #[test]
    fn no_sign_change_is_none() {
        assert_eq!(
            bracketed_root(|x| (x * x + 1.0, 2.0 * x), -1.0, 1.0, 1e-14, 50),
            None
        );
        assert_eq!(bracketed_root(|x| (x, 1.0), 0.0, 1.0, 1e-14, 50), Some(0.0));
        assert_eq!(
            bracketed_root(|_| (f64::NAN, 1.0), 0.0, 1.0, 1e-14, 50),
            None
        );
    }
}
