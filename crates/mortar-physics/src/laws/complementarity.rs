//! `ContactComplementarity`: exact frictionless contact as the complementarity function
//! `C = t - max(0, t - c g)`, solved by semi-smooth Newton.

use num_traits::Float;

use super::{cst, ConstraintLaw, LawError, LawPoint};

/// The contact complementarity function `C(g, t) = t - max(0, t - c g)`, zero exactly when
/// the Kuhn-Tucker conditions `g >= 0, t >= 0, t g = 0` hold (`t` the contact pressure,
/// positive in compression; `g` the gap, positive open). Its generalised derivative gives the
/// primal-dual active set method as a semi-smooth Newton: active (`t - c g > 0`):
/// `C = c g`; inactive: `C = t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactComplementarity {
    c: f64,
}

impl ContactComplementarity {
    /// The function with complementarity parameter `c` (Pa/m; any positive value gives the
    /// same solution; of the order of the stiffness over the element size it converges best).
    ///
    /// # Errors
    /// [`LawError::InvalidParameter`] unless `c` is positive and finite.
    pub fn try_new(c: f64) -> Result<Self, LawError> {
        if c > 0.0 && c.is_finite() {
            Ok(Self { c })
        } else {
            Err(LawError::InvalidParameter {
                law: "contact complementarity",
                what: format!("parameter c = {c} is not positive and finite"),
            })
        }
    }

    /// The parameter `c`.
    pub fn parameter(&self) -> f64 {
        self.c
    }
}

impl ConstraintLaw for ContactComplementarity {
    fn residual<S: Float>(&self, p: LawPoint<S>) -> S {
        let t = p.multiplier;
        t - (t - cst::<S>(self.c) * p.gap).max(S::zero())
    }
}
