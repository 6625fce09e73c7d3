//! Quadrature rules are exact to their stated degree for every monomial, and (sanity: the
//! check can fail) not exact beyond it where that is expected.

use mortar_core::element::ReferenceDomain;
use mortar_core::quadrature::{Quadrature, QuadratureRule};
use mortar_core::MortarError;

const DOMAINS: [ReferenceDomain; 3] = [
    ReferenceDomain::Line,
    ReferenceDomain::Triangle,
    ReferenceDomain::Quadrilateral,
];

fn factorial(n: u32) -> f64 {
    (1..=n).map(f64::from).product()
}

/// `int_{-1}^{1} x^a dx`.
fn line_moment(a: u32) -> f64 {
    if a.is_multiple_of(2) {
        2.0 / (a as f64 + 1.0)
    } else {
        0.0
    }
}

/// The exact integral of `x^a y^b` over the reference domain.
fn exact_moment(domain: ReferenceDomain, a: u32, b: u32) -> f64 {
    match domain {
        ReferenceDomain::Line => line_moment(a) * if b == 0 { 1.0 } else { 0.0 },
        // int over (0,0), (1,0), (0,1) of x^a y^b = a! b! / (a + b + 2)!
        ReferenceDomain::Triangle => factorial(a) * factorial(b) / factorial(a + b + 2),
        ReferenceDomain::Quadrilateral => line_moment(a) * line_moment(b),
    }
}

/// The monomials `x^a y^b` of total degree `degree` on a domain (lines: `y^0` only).
fn monomials(domain: ReferenceDomain, degree: u32) -> Vec<(u32, u32)> {
    match domain {
        ReferenceDomain::Line => vec![(degree, 0)],
        _ => (0..=degree).map(|a| (a, degree - a)).collect(),
    }
}

/// Whether the rule integrates `x^a y^b` exactly, to `1e-13` relative to the larger of the
/// exact value and `sum |w f|` (the size of the terms summed).
fn exact_for(rule: &QuadratureRule, a: u32, b: u32) -> bool {
    let domain = rule.domain();
    let mut sum = 0.0;
    let mut size = 0.0;
    for (p, w) in rule.points().iter().zip(rule.weights()) {
        let f = p.x.powi(a as i32) * p.y.powi(b as i32);
        sum += w * f;
        size += (w * f).abs();
    }
    let exact = exact_moment(domain, a, b);
    (sum - exact).abs() <= 1e-13 * exact.abs().max(size)
}

/// The highest degree `D` such that every monomial of degree at most `D` is integrated
/// exactly.
fn exactness(rule: &QuadratureRule) -> u32 {
    let mut d = 0;
    while monomials(rule.domain(), d + 1)
        .iter()
        .all(|&(a, b)| exact_for(rule, a, b))
    {
        d += 1;
        assert!(d < 60, "a rule exact to degree 60 is implausible");
    }
    d
}

#[test]
fn rules_are_exact_to_their_stated_degree() {
    for domain in DOMAINS {
        for requested in 0..=20 {
            let rule = QuadratureRule::for_domain(domain, requested).unwrap();
            assert!(rule.degree() >= requested.max(1), "{domain:?} {requested}");
            for d in 0..=rule.degree() {
                for (a, b) in monomials(domain, d) {
                    assert!(
                        exact_for(&rule, a, b),
                        "{domain:?} rule of degree {} ({} points) misses x^{a} y^{b}",
                        rule.degree(),
                        rule.len()
                    );
                }
            }
        }
    }
}

/// The exactness check is not vacuous: each rule fails one degree above its stated degree,
/// except where exactness one degree higher is expected — a symmetric quadrilateral rule of
/// even degree is exact for the odd degree above (every odd monomial integrates to zero by
/// symmetry), and the triangle rule asked for degree 3 is the 6-point rule of degree 4 (no
/// smaller symmetric positive rule of degree 3) — and then two degrees above.
#[test]
fn rules_are_not_exact_beyond_their_degree() {
    for domain in DOMAINS {
        for requested in 1..=20 {
            let rule = QuadratureRule::for_domain(domain, requested).unwrap();
            let stated = rule.degree();
            let expected = match domain {
                ReferenceDomain::Quadrilateral if stated.is_multiple_of(2) => stated + 1,
                ReferenceDomain::Triangle if stated == 3 => 4,
                _ => stated,
            };
            assert_eq!(
                exactness(&rule),
                expected,
                "{domain:?} rule stated degree {stated}, {} points",
                rule.len()
            );
        }
    }
}

#[test]
fn high_degree_line_rules_are_exact() {
    for degree in [41, 99, 199] {
        let rule = QuadratureRule::line(degree).unwrap();
        assert_eq!(rule.degree(), degree);
        // Every moment up to the degree. (One degree above, the Gauss error on x^(2n) is of
        // order 4^-n: below round-off here, so there is nothing to check beyond.)
        for a in 0..=degree {
            assert!(exact_for(&rule, a, 0), "degree {degree}: x^{a}");
        }
    }
}

#[test]
fn weights_are_positive_sum_to_the_measure_and_points_lie_inside() {
    for domain in DOMAINS {
        for degree in 1..=20 {
            let rule = QuadratureRule::for_domain(domain, degree).unwrap();
            assert_eq!(rule.points().len(), rule.weights().len());
            assert!(!rule.is_empty());
            let sum: f64 = rule.weights().iter().sum();
            assert!((sum - domain.measure()).abs() <= 1e-14 * domain.measure());
            for (p, w) in rule.points().iter().zip(rule.weights()) {
                assert!(*w > 0.0, "{domain:?} {degree}: weight {w}");
                assert!(
                    domain.contains(p, 1e-14),
                    "{domain:?} {degree}: point {p:?}"
                );
                if domain == ReferenceDomain::Line {
                    assert_eq!(p.y, 0.0);
                }
            }
        }
    }
}

#[test]
fn cached_rules_equal_fresh_ones() {
    for domain in DOMAINS {
        for degree in 0..=20 {
            let cached = QuadratureRule::cached(domain, degree).unwrap();
            let again = QuadratureRule::cached(domain, degree).unwrap();
            assert!(std::ptr::eq(cached, again));
            assert_eq!(*cached, QuadratureRule::for_domain(domain, degree).unwrap());
        }
    }
}

#[test]
fn degrees_out_of_range_are_invalid_options() {
    for result in [
        QuadratureRule::triangle(21),
        QuadratureRule::quadrilateral(21),
        QuadratureRule::line(200),
        QuadratureRule::cached(ReferenceDomain::Line, 21).cloned(),
    ] {
        assert!(
            matches!(
                result,
                Err(MortarError::InvalidOption {
                    option: "quadrature degree",
                    ..
                })
            ),
            "{result:?}"
        );
    }
}
