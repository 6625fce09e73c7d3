//! Forward-mode dual numbers `a + sum_i b_i eps_i` (`eps_i eps_j = 0`) with `N` derivative
//! directions, implementing [`num_traits::Float`] so that a law written once over a generic
//! `S: Float` yields its value and all `N` partial derivatives in one evaluation.
//!
//! Why our own type rather than the `num-dual` crate: `num-dual` (0.15) implements its own
//! `DualNum` trait and `num_traits::{Num, Signed, FloatConst}`, but not `num_traits::Float`,
//! the bound of [`ConstraintLaw`](super::ConstraintLaw); this type is small, has no
//! dependency, and carries the three partials (gap, multiplier, temperature) at once.
//!
//! Comparisons (`<`, `max`, `min`, `is_nan`, ...) look at the real part only: a law with a
//! kink (`max(0, x)`) gets the derivative of the branch taken, the usual generalised
//! (semi-smooth) derivative.

use std::cmp::Ordering;
use std::num::FpCategory;
use std::ops::{Add, Div, Mul, Neg, Rem, Sub};

use num_traits::{Float, Num, NumCast, One, ToPrimitive, Zero};

/// A dual number with `N` derivative directions: value `re`, partials `eps`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dual<const N: usize> {
    /// The value.
    pub re: f64,
    /// The partial derivatives.
    pub eps: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// A constant (all partials zero).
    pub fn constant(re: f64) -> Self {
        Self { re, eps: [0.0; N] }
    }

    /// The `i`-th independent variable at value `re` (partial `i` is one).
    ///
    /// # Panics
    /// If `i >= N`.
    pub fn variable(re: f64, i: usize) -> Self {
        let mut eps = [0.0; N];
        eps[i] = 1.0;
        Self { re, eps }
    }

    /// `f(re)` with derivative `df = f'(re)` (the chain rule).
    #[inline]
    fn chain(self, f: f64, df: f64) -> Self {
        let mut eps = self.eps;
        for e in &mut eps {
            *e *= df;
        }
        Self { re: f, eps }
    }
}

impl<const N: usize> PartialOrd for Dual<N> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        self.re.partial_cmp(&other.re)
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    fn add(mut self, o: Self) -> Self {
        self.re += o.re;
        for (a, b) in self.eps.iter_mut().zip(o.eps) {
            *a += b;
        }
        self
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    fn sub(mut self, o: Self) -> Self {
        self.re -= o.re;
        for (a, b) in self.eps.iter_mut().zip(o.eps) {
            *a -= b;
        }
        self
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let mut eps = [0.0; N];
        for i in 0..N {
            eps[i] = self.eps[i] * o.re + self.re * o.eps[i];
        }
        Self {
            re: self.re * o.re,
            eps,
        }
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.re;
        let re = self.re * inv;
        let mut eps = [0.0; N];
        for i in 0..N {
            eps[i] = (self.eps[i] - re * o.eps[i]) * inv;
        }
        Self { re, eps }
    }
}

impl<const N: usize> Rem for Dual<N> {
    type Output = Self;
    /// `a % b = a - trunc(a / b) b`, differentiated piecewise.
    fn rem(self, o: Self) -> Self {
        self - (self / o).trunc() * o
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    fn neg(self) -> Self {
        self.chain(-self.re, -1.0)
    }
}

impl<const N: usize> Zero for Dual<N> {
    fn zero() -> Self {
        Self::constant(0.0)
    }
    fn is_zero(&self) -> bool {
        self.re == 0.0
    }
}

impl<const N: usize> One for Dual<N> {
    fn one() -> Self {
        Self::constant(1.0)
    }
}

impl<const N: usize> Num for Dual<N> {
    type FromStrRadixErr = <f64 as Num>::FromStrRadixErr;
    fn from_str_radix(s: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
        f64::from_str_radix(s, radix).map(Self::constant)
    }
}

impl<const N: usize> ToPrimitive for Dual<N> {
    fn to_i64(&self) -> Option<i64> {
        self.re.to_i64()
    }
    fn to_u64(&self) -> Option<u64> {
        self.re.to_u64()
    }
    fn to_f64(&self) -> Option<f64> {
        Some(self.re)
    }
}

impl<const N: usize> NumCast for Dual<N> {
    fn from<T: ToPrimitive>(n: T) -> Option<Self> {
        n.to_f64().map(Self::constant)
    }
}

impl<const N: usize> Float for Dual<N> {
    fn nan() -> Self {
        Self::constant(f64::NAN)
    }
    fn infinity() -> Self {
        Self::constant(f64::INFINITY)
    }
    fn neg_infinity() -> Self {
        Self::constant(f64::NEG_INFINITY)
    }
    fn neg_zero() -> Self {
        Self::constant(-0.0)
    }
    fn min_value() -> Self {
        Self::constant(f64::MIN)
    }
    fn min_positive_value() -> Self {
        Self::constant(f64::MIN_POSITIVE)
    }
    fn epsilon() -> Self {
        Self::constant(f64::EPSILON)
    }
    fn max_value() -> Self {
        Self::constant(f64::MAX)
    }
    fn is_nan(self) -> bool {
        self.re.is_nan()
    }
    fn is_infinite(self) -> bool {
        self.re.is_infinite()
    }
    fn is_finite(self) -> bool {
        self.re.is_finite()
    }
    fn is_normal(self) -> bool {
        self.re.is_normal()
    }
    fn classify(self) -> FpCategory {
        self.re.classify()
    }
    fn floor(self) -> Self {
        self.chain(self.re.floor(), 0.0)
    }
    fn ceil(self) -> Self {
        self.chain(self.re.ceil(), 0.0)
    }
    fn round(self) -> Self {
        self.chain(self.re.round(), 0.0)
    }
    fn trunc(self) -> Self {
        self.chain(self.re.trunc(), 0.0)
    }
    fn fract(self) -> Self {
        self.chain(self.re.fract(), 1.0)
    }
    fn abs(self) -> Self {
        let s = if self.re < 0.0 { -1.0 } else { 1.0 };
        self.chain(self.re.abs(), s)
    }
    fn signum(self) -> Self {
        self.chain(self.re.signum(), 0.0)
    }
    fn is_sign_positive(self) -> bool {
        self.re.is_sign_positive()
    }
    fn is_sign_negative(self) -> bool {
        self.re.is_sign_negative()
    }
    fn mul_add(self, a: Self, b: Self) -> Self {
        self * a + b
    }
    fn recip(self) -> Self {
        let r = 1.0 / self.re;
        self.chain(r, -r * r)
    }
    fn powi(self, n: i32) -> Self {
        let d = if n == 0 {
            0.0
        } else {
            n as f64 * self.re.powi(n - 1)
        };
        self.chain(self.re.powi(n), d)
    }
    fn powf(self, n: Self) -> Self {
        if n.eps.iter().all(|&e| e == 0.0) {
            // A constant exponent: defined for negative bases too.
            let p = n.re;
            let d = if p == 0.0 {
                0.0
            } else {
                p * self.re.powf(p - 1.0)
            };
            self.chain(self.re.powf(p), d)
        } else {
            (self.ln() * n).exp()
        }
    }
    fn sqrt(self) -> Self {
        let s = self.re.sqrt();
        self.chain(s, 0.5 / s)
    }
    fn exp(self) -> Self {
        let e = self.re.exp();
        self.chain(e, e)
    }
    fn exp2(self) -> Self {
        let e = self.re.exp2();
        self.chain(e, e * std::f64::consts::LN_2)
    }
    fn ln(self) -> Self {
        self.chain(self.re.ln(), 1.0 / self.re)
    }
    fn log(self, base: Self) -> Self {
        self.ln() / base.ln()
    }
    fn log2(self) -> Self {
        self.chain(self.re.log2(), 1.0 / (self.re * std::f64::consts::LN_2))
    }
    fn log10(self) -> Self {
        self.chain(self.re.log10(), 1.0 / (self.re * std::f64::consts::LN_10))
    }
    fn max(self, o: Self) -> Self {
        if self.re.is_nan() || o.re > self.re {
            o
        } else {
            self
        }
    }
    fn min(self, o: Self) -> Self {
        if self.re.is_nan() || o.re < self.re {
            o
        } else {
            self
        }
    }
    fn abs_sub(self, o: Self) -> Self {
        if self.re <= o.re {
            Self::zero()
        } else {
            self - o
        }
    }
    fn cbrt(self) -> Self {
        let c = self.re.cbrt();
        self.chain(c, 1.0 / (3.0 * c * c))
    }
    fn hypot(self, o: Self) -> Self {
        (self * self + o * o).sqrt()
    }
    fn sin(self) -> Self {
        self.chain(self.re.sin(), self.re.cos())
    }
    fn cos(self) -> Self {
        self.chain(self.re.cos(), -self.re.sin())
    }
    fn tan(self) -> Self {
        let t = self.re.tan();
        self.chain(t, 1.0 + t * t)
    }
    fn asin(self) -> Self {
        self.chain(self.re.asin(), 1.0 / (1.0 - self.re * self.re).sqrt())
    }
    fn acos(self) -> Self {
        self.chain(self.re.acos(), -1.0 / (1.0 - self.re * self.re).sqrt())
    }
    fn atan(self) -> Self {
        self.chain(self.re.atan(), 1.0 / (1.0 + self.re * self.re))
    }
    fn atan2(self, o: Self) -> Self {
        let d = self.re * self.re + o.re * o.re;
        let mut eps = [0.0; N];
        for i in 0..N {
            eps[i] = (o.re * self.eps[i] - self.re * o.eps[i]) / d;
        }
        Self {
            re: self.re.atan2(o.re),
            eps,
        }
    }
    fn sin_cos(self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    fn exp_m1(self) -> Self {
        self.chain(self.re.exp_m1(), self.re.exp())
    }
    fn ln_1p(self) -> Self {
        self.chain(self.re.ln_1p(), 1.0 / (1.0 + self.re))
    }
    fn sinh(self) -> Self {
        self.chain(self.re.sinh(), self.re.cosh())
    }
    fn cosh(self) -> Self {
        self.chain(self.re.cosh(), self.re.sinh())
    }
    fn tanh(self) -> Self {
        let t = self.re.tanh();
        self.chain(t, 1.0 - t * t)
    }
    fn asinh(self) -> Self {
        self.chain(self.re.asinh(), 1.0 / (self.re * self.re + 1.0).sqrt())
    }
    fn acosh(self) -> Self {
        self.chain(self.re.acosh(), 1.0 / (self.re * self.re - 1.0).sqrt())
    }
    fn atanh(self) -> Self {
        self.chain(self.re.atanh(), 1.0 / (1.0 - self.re * self.re))
    }
    fn integer_decode(self) -> (u64, i16, i8) {
        self.re.integer_decode()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn product_quotient_and_functions() {
        let x = Dual::<2>::variable(2.0, 0);
        let y = Dual::<2>::variable(3.0, 1);
        let f = x * y / (x + y) + x.exp() * y.ln() - x.powf(Dual::constant(1.5));
        let df_dx = (y.re * (x.re + y.re) - x.re * y.re) / (x.re + y.re).powi(2)
            + x.re.exp() * y.re.ln()
            - 1.5 * x.re.sqrt();
        let df_dy =
            (x.re * (x.re + y.re) - x.re * y.re) / (x.re + y.re).powi(2) + x.re.exp() / y.re;
        assert!((f.eps[0] - df_dx).abs() < 1e-12);
        assert!((f.eps[1] - df_dy).abs() < 1e-12);
        let m = Float::max(Dual::<2>::constant(0.0), x - y);
        assert_eq!(m.eps, [0.0, 0.0]);
    }
}
