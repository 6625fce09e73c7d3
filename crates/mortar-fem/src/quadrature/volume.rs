//! Quadrature rules on the reference domains of volume elements.

use nalgebra::Vector3;

use mortar_core::element::ReferenceDomain;
use mortar_core::quadrature::{Quadrature, QuadratureRule};
use mortar_core::{MortarError, Result};

use crate::element::VolumeDomain;

/// A quadrature rule on a volume element's reference domain (see
/// [`VolumeDomain`]): triangle and quadrilateral rules are those of [`QuadratureRule`] with a
/// zero third coordinate; tetrahedron and hexahedron rules are the symmetric positive-weight
/// Witherden-Vincent rules of `fenris-quadrature`, the tetrahedron mapped from fenris'
/// `(-1,-1,-1), (1,-1,-1), (-1,1,-1), (-1,-1,1)` onto `(0,0,0), (1,0,0), (0,1,0), (0,0,1)`
/// (`x = (X + 1) / 2`, weights times 1/8).
#[derive(Debug, Clone, PartialEq)]
pub struct VolumeQuadratureRule {
    domain: VolumeDomain,
    degree: u32,
    points: Vec<Vector3<f64>>,
    weights: Vec<f64>,
}

/// The highest degree provided on each domain: triangles and quadrilaterals 20, tetrahedra
/// 10, hexahedra 11.
pub const fn max_volume_degree(domain: VolumeDomain) -> u32 {
    match domain {
        VolumeDomain::Triangle | VolumeDomain::Quadrilateral => 20,
        VolumeDomain::Tetrahedron => 10,
        VolumeDomain::Hexahedron => 20,
    }
}

/// The highest degree of the symmetric (polyquad) hexahedron rules; above it, tensor
/// Gauss-Legendre rules.
const MAX_POLYQUAD_HEXAHEDRON: u32 = 11;

impl VolumeQuadratureRule {
    /// The smallest rule on `domain` exact for polynomials of total degree `degree`.
    ///
    /// # Errors
    /// [`MortarError::InvalidOption`] above the domain's highest degree (see
    /// [`max_volume_degree`]).
    pub fn for_domain(domain: VolumeDomain, degree: u32) -> Result<Self> {
        if degree > max_volume_degree(domain) {
            return Err(too_high(domain, degree));
        }
        let planar = |d: ReferenceDomain| -> Result<Self> {
            let rule = QuadratureRule::for_domain(d, degree)?;
            Ok(Self {
                domain,
                degree: rule.degree(),
                points: rule
                    .points()
                    .iter()
                    .map(|p| Vector3::new(p.x, p.y, 0.0))
                    .collect(),
                weights: rule.weights().to_vec(),
            })
        };
        let fail = |e: fenris_quadrature::Error| MortarError::InvalidOption {
            option: "quadrature degree",
            value: degree.to_string(),
            reason: format!("no {domain:?} quadrature of that degree: {e:?}"),
        };
        match domain {
            VolumeDomain::Triangle => planar(ReferenceDomain::Triangle),
            VolumeDomain::Quadrilateral => planar(ReferenceDomain::Quadrilateral),
            VolumeDomain::Tetrahedron => {
                let (w, p) = fenris_quadrature::polyquad::tetrahedron(degree.max(1) as usize)
                    .map_err(fail)?;
                Ok(Self {
                    domain,
                    degree: degree.max(1),
                    points: p
                        .iter()
                        .map(|x| Vector3::new(x[0] + 1.0, x[1] + 1.0, x[2] + 1.0) * 0.5)
                        .collect(),
                    weights: w.iter().map(|w| w * 0.125).collect(),
                })
            }
            VolumeDomain::Hexahedron if degree > MAX_POLYQUAD_HEXAHEDRON => {
                // The tensor product of Gauss-Legendre lines exact to `degree` in each
                // coordinate, hence for total degree `degree` (the second-order hexahedra's
                // integrands: Hex27 has shape degree 6).
                let line = QuadratureRule::line(degree)?;
                let (lp, lw) = (line.points(), line.weights());
                let mut points = Vec::with_capacity(lp.len().pow(3));
                let mut weights = Vec::with_capacity(lp.len().pow(3));
                for (a, wa) in lp.iter().zip(lw) {
                    for (b, wb) in lp.iter().zip(lw) {
                        for (c, wc) in lp.iter().zip(lw) {
                            points.push(Vector3::new(a.x, b.x, c.x));
                            weights.push(wa * wb * wc);
                        }
                    }
                }
                Ok(Self {
                    domain,
                    degree,
                    points,
                    weights,
                })
            }
            VolumeDomain::Hexahedron => {
                let (w, p) = fenris_quadrature::polyquad::hexahedron(degree.max(1) as usize)
                    .map_err(fail)?;
                Ok(Self {
                    domain,
                    degree: degree.max(1),
                    points: p.iter().map(|x| Vector3::new(x[0], x[1], x[2])).collect(),
                    weights: w,
                })
            }
        }
    }

    /// The rule of [`for_domain`](Self::for_domain), built once and shared by all threads.
    ///
    /// # Errors
    /// As [`for_domain`](Self::for_domain).
    pub fn cached(domain: VolumeDomain, degree: u32) -> Result<&'static VolumeQuadratureRule> {
        if degree > max_volume_degree(domain) {
            return Err(too_high(domain, degree));
        }
        let slot = &CACHE[domain as usize][degree as usize];
        if let Some(rule) = slot.get() {
            return Ok(rule);
        }
        let rule = Self::for_domain(domain, degree)?;
        Ok(slot.get_or_init(|| rule))
    }

    /// The domain the points live on.
    pub fn domain(&self) -> VolumeDomain {
        self.domain
    }

    /// The highest total polynomial degree integrated exactly.
    pub fn degree(&self) -> u32 {
        self.degree
    }

    /// The points (third coordinate zero in 2D).
    pub fn points(&self) -> &[Vector3<f64>] {
        &self.points
    }

    /// The weights; they sum to the measure of the domain.
    pub fn weights(&self) -> &[f64] {
        &self.weights
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

fn too_high(domain: VolumeDomain, degree: u32) -> MortarError {
    MortarError::InvalidOption {
        option: "quadrature degree",
        value: degree.to_string(),
        reason: format!(
            "no {domain:?} quadrature of that degree (at most {})",
            max_volume_degree(domain)
        ),
    }
}

/// Rules cached per domain and degree (degrees 0 to 20).
static CACHE: [[std::sync::OnceLock<VolumeQuadratureRule>; 21]; 4] =
    [const { [const { std::sync::OnceLock::new() }; 21] }; 4];
