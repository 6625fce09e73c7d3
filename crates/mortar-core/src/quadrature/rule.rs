//! Quadrature rules on the reference line, triangle and square (`QuadratureRule`), by degree,
//! with a cache of the rules already built.

use nalgebra::Vector2;

use crate::element::ReferenceDomain;
use crate::error::{MortarError, Result};

/// A quadrature rule on a reference domain.
pub trait Quadrature: Send + Sync {
    /// The domain the points live on.
    fn domain(&self) -> ReferenceDomain;
    /// The highest total polynomial degree integrated exactly.
    fn degree(&self) -> u32;
    /// The points (for lines the second coordinate is zero).
    fn points(&self) -> &[Vector2<f64>];
    /// The weights; they sum to the measure of the domain.
    fn weights(&self) -> &[f64];
}

/// A quadrature rule stored as points and weights.
#[derive(Debug, Clone, PartialEq)]
pub struct QuadratureRule {
    domain: ReferenceDomain,
    degree: u32,
    points: Vec<Vector2<f64>>,
    weights: Vec<f64>,
}

/// The highest degree for which a rule is provided on triangles and quadrilaterals.
const MAX_DEGREE_2D: u32 = 20;

impl QuadratureRule {
    /// The smallest rule on `domain` exact for polynomials of total degree `degree`.
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] if no rule of that degree is available (lines: any
    /// degree up to 199; triangles and quadrilaterals: up to 20).
    pub fn for_domain(domain: ReferenceDomain, degree: u32) -> Result<Self> {
        match domain {
            ReferenceDomain::Line => Self::line(degree),
            ReferenceDomain::Triangle => Self::triangle(degree),
            ReferenceDomain::Quadrilateral => Self::quadrilateral(degree),
        }
    }

    /// Gauss-Legendre on `[-1, 1]` exact to `degree` (`degree / 2 + 1` points).
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] for degrees above 199.
    pub fn line(degree: u32) -> Result<Self> {
        if degree > 199 {
            return Err(MortarError::InvalidOption {
                option: "quadrature degree",
                value: degree.to_string(),
                reason: "no line quadrature of that degree (at most 199)".into(),
            });
        }
        let n = degree as usize / 2 + 1;
        let (weights, points) = fenris_quadrature::univariate::gauss(n);
        Ok(Self {
            domain: ReferenceDomain::Line,
            degree: (2 * n - 1) as u32,
            points: points.iter().map(|p| Vector2::new(p[0], 0.0)).collect(),
            weights,
        })
    }

    /// A symmetric positive-weight rule on the triangle `(0,0), (1,0), (0,1)` exact to
    /// `degree`.
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] for degrees above 20.
    pub fn triangle(degree: u32) -> Result<Self> {
        let (weights, points) = Self::polyquad(degree, fenris_quadrature::polyquad::triangle)?;
        // fenris' triangle is (-1,-1), (1,-1), (-1,1): x = (X + 1) / 2, area ratio 1/4.
        Ok(Self {
            domain: ReferenceDomain::Triangle,
            degree: degree.max(1),
            points: points
                .iter()
                .map(|p| Vector2::new(0.5 * (p[0] + 1.0), 0.5 * (p[1] + 1.0)))
                .collect(),
            weights: weights.iter().map(|w| 0.25 * w).collect(),
        })
    }

    /// A symmetric positive-weight rule on `[-1, 1]^2` exact to total degree `degree`.
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] for degrees above 20.
    pub fn quadrilateral(degree: u32) -> Result<Self> {
        let (weights, points) = Self::polyquad(degree, fenris_quadrature::polyquad::quadrilateral)?;
        Ok(Self {
            domain: ReferenceDomain::Quadrilateral,
            degree: degree.max(1),
            points: points.iter().map(|p| Vector2::new(p[0], p[1])).collect(),
            weights,
        })
    }

    fn polyquad(
        degree: u32,
        rule: fn(usize) -> Result<fenris_quadrature::Rule<2>, fenris_quadrature::Error>,
    ) -> Result<fenris_quadrature::Rule<2>> {
        if degree > MAX_DEGREE_2D {
            return Err(MortarError::InvalidOption {
                option: "quadrature degree",
                value: degree.to_string(),
                reason: format!("no 2D quadrature of that degree (at most {MAX_DEGREE_2D})"),
            });
        }
        rule(degree.max(1) as usize).map_err(|e| MortarError::InvalidOption {
            option: "quadrature degree",
            value: degree.to_string(),
            reason: format!("no 2D quadrature of that degree: {e}"),
        })
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether the rule has no points (never, for the constructors above).
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
}

impl Quadrature for QuadratureRule {
    fn domain(&self) -> ReferenceDomain {
        self.domain
    }
    fn degree(&self) -> u32 {
        self.degree
    }
    fn points(&self) -> &[Vector2<f64>] {
        &self.points
    }
    fn weights(&self) -> &[f64] {
        &self.weights
    }
}

/// Rules cached per domain and degree, built once on first use and shared by all threads.
static CACHE: [[std::sync::OnceLock<QuadratureRule>; CACHED_DEGREES]; 3] =
    [const { [const { std::sync::OnceLock::new() }; CACHED_DEGREES] }; 3];

/// Degrees `0..CACHED_DEGREES` are cached.
const CACHED_DEGREES: usize = MAX_DEGREE_2D as usize + 1;

impl QuadratureRule {
    /// The rule of [`for_domain`](Self::for_domain), built once and shared (no allocation after
    /// the first call).
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] for degrees above 20.
    pub fn cached(domain: ReferenceDomain, degree: u32) -> Result<&'static QuadratureRule> {
        if degree as usize >= CACHED_DEGREES {
            return Err(MortarError::InvalidOption {
                option: "quadrature degree",
                value: degree.to_string(),
                reason: format!("no cached quadrature of that degree (at most {MAX_DEGREE_2D})"),
            });
        }
        let slot = &CACHE[domain as usize][degree as usize];
        if let Some(rule) = slot.get() {
            return Ok(rule);
        }
        let rule = Self::for_domain(domain, degree)?;
        Ok(slot.get_or_init(|| rule))
    }
}
