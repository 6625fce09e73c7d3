//! The ranges in which the coupled pellet's models hold, and the named warnings of a run that
//! leaves them (docs/models.md, section 3b). A warning is raised once per run, with the first
//! state past its bound and the run's extreme value.

use mortar_physics::laws::ConstraintLaw;
use mortar_physics::thermomech::GapThermoMechanics;
use nalgebra::{Matrix3, Vector3};
use serde_json::{json, Value};

use super::PelletError;

/// The melting point of UO2 (K): 3120 +- 30 K (J.K. Fink, "Thermophysical properties of
/// uranium dioxide", J. Nucl. Mater. 279 (2000) 1-18).
pub const UO2_MELTING_POINT: f64 = 3120.0;

/// The temperatures (K) in which the pellet's `k = 1 / (A + B T)` is taken to hold. The
/// default `A`, `B` are the lattice (phonon) term of the correlation of J.H. Harding and
/// D.G. Martin, "A recommendation for the thermal conductivity of UO2", J. Nucl. Mater. 166
/// (1989) 223-226, whose full form adds `4.715e9 / T^2 exp(-16361 / T)` W/m/K; that term,
/// which the scene leaves out, passes 5% of the lattice term at 1730 K, the upper end. The
/// lower end, 300 K, is room temperature, below any temperature the default scene reaches.
pub const CONDUCTIVITY_RANGE: (f64, f64) = (300.0, 1730.0);

/// The yield stress (Pa) of unirradiated, annealed Zircaloy-4 at 600 K, 145 MPa: MATPRO's
/// strength coefficient, strain-hardening and strain-rate exponents (subroutines CKMN and
/// CMLIMT of NUREG/CR-6150, as coded in FRAPCON) with no cold work and no fluence, at a
/// strain rate of 1e-5 /s (157 MPa at 1e-3 /s), and MATPRO's modulus `1.088e11 - 5.475e7 T`
/// Pa. A constant, taken at the cladding's temperature in the default scene (580-650 K).
pub const CLADDING_YIELD_STRESS: f64 = 145e6;

/// The fracture strength (Pa) of UO2 in tension, about 130 MPa (D.R. Olander, *Fundamental
/// Aspects of Nuclear Reactor Fuel Elements*, TID-26711-P1, 1976).
pub const UO2_FRACTURE_STRENGTH: f64 = 130e6;

/// One model range: its warning's name, what leaving it means, its bound and its source.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limit {
    /// The warning's name.
    pub name: &'static str,
    /// What a value past the bound means.
    pub what: &'static str,
    /// The quantity compared with the bound, and its unit.
    pub quantity: &'static str,
    /// The unit of the value and bound.
    pub unit: &'static str,
    /// The bound: the value must stay below `bound.1` (and, when given, above `bound.0`).
    pub bound: (Option<f64>, f64),
    /// Where the bound comes from.
    pub source: &'static str,
}

/// The limits the coupled pellet scene checks at every converged state.
pub const LIMITS: [Limit; 5] = [
    Limit {
        name: "fuel_melting",
        what: "the pellet's temperature is above UO2's melting point: the solid model no longer applies",
        quantity: "largest pellet temperature",
        unit: "K",
        bound: (None, UO2_MELTING_POINT),
        source: "J.K. Fink, Thermophysical properties of uranium dioxide, J. Nucl. Mater. 279 (2000) 1-18: 3120 +- 30 K",
    },
    Limit {
        name: "conductivity_range",
        what: "a pellet temperature is outside the range where k = 1/(A + B T) is taken to hold",
        quantity: "pellet temperature furthest outside the range",
        unit: "K",
        bound: (Some(CONDUCTIVITY_RANGE.0), CONDUCTIVITY_RANGE.1),
        source: "A, B: the lattice term of J.H. Harding and D.G. Martin, J. Nucl. Mater. 166 (1989) 223-226; above 1730 K the electronic term that it leaves out exceeds 5% of it; 300 K: room temperature (docs/models.md, section 3b)",
    },
    Limit {
        name: "cladding_beyond_elastic",
        what: "the cladding's von Mises stress is above the yield stress of Zircaloy-4: it would deform plastically, which the elastic model does not",
        quantity: "largest cladding von Mises stress",
        unit: "Pa",
        bound: (None, CLADDING_YIELD_STRESS),
        source: "MATPRO (NUREG/CR-6150) CKMN/CMLIMT as coded in FRAPCON: unirradiated annealed Zircaloy-4 at 600 K, strain rate 1e-5 /s",
    },
    Limit {
        name: "pellet_cracking",
        what: "the pellet's largest tensile principal stress is above UO2's fracture strength: the pellet would crack, which the model does not",
        quantity: "largest tensile principal stress in the pellet",
        unit: "Pa",
        bound: (None, UO2_FRACTURE_STRENGTH),
        source: "D.R. Olander, Fundamental Aspects of Nuclear Reactor Fuel Elements, TID-26711-P1 (1976): about 130 MPa",
    },
    Limit {
        name: "contact_pressure_beyond_elastic",
        what: "the interface pressure (contact plus gas) is above the cladding's yield stress: the contact would deform it plastically",
        quantity: "largest interface pressure",
        unit: "Pa",
        bound: (None, CLADDING_YIELD_STRESS),
        source: "as cladding_beyond_elastic",
    },
];

/// A point of a body: its name and position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct At {
    body: &'static str,
    position: Vector3<f64>,
    /// The distance from the rod's axis: `x` in r-z, `|(x, y)|` otherwise.
    radius: f64,
}

/// A state's values of the limits' quantities (in [`LIMITS`] order), each with its place.
pub(super) type Extremes = [(f64, At); 5];

/// When a state was reached: its time and the solve (the step number, or "initial" or
/// "steady").
#[derive(Debug, Clone, PartialEq)]
pub(super) struct When {
    pub time: f64,
    pub step: Value,
}

/// One warning of a run: the limit, the first state past it, the extreme value and its state
/// and place.
#[derive(Debug, Clone, PartialEq)]
struct Warning {
    limit: Limit,
    first: When,
    first_value: f64,
    extreme: When,
    value: f64,
    at: At,
}

/// The warnings raised so far in a run.
#[derive(Debug, Clone, Default)]
pub(super) struct LimitWatch {
    warnings: Vec<Warning>,
}

/// How far `v` is past the limit's bound (positive past it).
fn excess(limit: &Limit, v: f64) -> f64 {
    let above = v - limit.bound.1;
    match limit.bound.0 {
        Some(lo) => above.max(lo - v),
        None => above,
    }
}

impl LimitWatch {
    /// Records the state `when` with its `extremes`.
    pub fn observe(&mut self, when: &When, extremes: &Extremes) {
        for (limit, &(value, at)) in LIMITS.iter().zip(extremes) {
            if value.is_nan() || excess(limit, value) <= 0.0 {
                continue;
            }
            match self
                .warnings
                .iter_mut()
                .find(|w| w.limit.name == limit.name)
            {
                Some(w) => {
                    if excess(limit, value) > excess(limit, w.value) {
                        (w.value, w.at, w.extreme) = (value, at, when.clone());
                    }
                }
                None => self.warnings.push(Warning {
                    limit: *limit,
                    first: when.clone(),
                    first_value: value,
                    extreme: when.clone(),
                    value,
                    at,
                }),
            }
        }
    }

    /// Whether no limit was passed.
    pub fn is_empty(&self) -> bool {
        self.warnings.is_empty()
    }

    /// The warnings as JSON, in the order they were first raised.
    pub fn to_json(&self) -> Value {
        Value::Array(
            self.warnings
                .iter()
                .map(|w| {
                    let l = &w.limit;
                    let bound = match l.bound.0 {
                        Some(lo) => json!([lo, l.bound.1]),
                        None => json!(l.bound.1),
                    };
                    let p = w.at.position;
                    json!({
                        "name": l.name,
                        "what": l.what,
                        "quantity": l.quantity,
                        "value": w.value,
                        "bound": bound,
                        "unit": l.unit,
                        "where": {
                            "body": w.at.body,
                            "position": [p.x, p.y, p.z],
                            "radius": w.at.radius,
                        },
                        "when": {
                            "first": { "time": w.first.time, "step": w.first.step, "value": w.first_value },
                            "extreme": { "time": w.extreme.time, "step": w.extreme.step },
                        },
                        "source": l.source,
                    })
                })
                .collect(),
        )
    }
}

/// One line per warning of a report's `"warnings"` array.
pub fn summary_lines(warnings: &Value) -> Vec<String> {
    let f = |v: &Value| v.as_f64().unwrap_or(f64::NAN);
    let scaled = |v: f64, unit: &str| match unit {
        "Pa" => format!("{:.1} MPa", v * 1e-6),
        _ => format!("{v:.1} {unit}"),
    };
    warnings
        .as_array()
        .into_iter()
        .flatten()
        .map(|w| {
            let unit = w["unit"].as_str().unwrap_or("");
            let bound = match w["bound"].as_array() {
                Some(b) => format!(
                    "outside {}..{}",
                    scaled(f(&b[0]), unit),
                    scaled(f(&b[1]), unit)
                ),
                None => format!("above {}", scaled(f(&w["bound"]), unit)),
            };
            // The solve: a step number, "initial" or "steady".
            let step = |v: &Value| match v {
                Value::String(s) => s.clone(),
                v => format!("step {v}"),
            };
            let (first, extreme) = (&w["when"]["first"], &w["when"]["extreme"]);
            format!(
                "{}: {} {} {bound} (first: {}, t = {:.2} s; extreme: {}, t = {:.2} s, {} r = {:.3} mm): {}",
                w["name"].as_str().unwrap_or("?"),
                w["quantity"].as_str().unwrap_or("?"),
                scaled(f(&w["value"]), unit),
                step(&first["step"]),
                f(&first["time"]),
                step(&extreme["step"]),
                f(&extreme["time"]),
                w["where"]["body"].as_str().unwrap_or("?"),
                1e3 * f(&w["where"]["radius"]),
                w["what"].as_str().unwrap_or(""),
            )
        })
        .collect()
}

/// The largest eigenvalue of the symmetric stress in Voigt order `[xx, yy, zz, yz, xz, xy]`.
fn largest_principal(s: &[f64; 6]) -> f64 {
    let m = Matrix3::new(s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2]);
    m.symmetric_eigenvalues().max()
}

/// The limits' quantities at the state `x` of time `time` (in [`LIMITS`] order): the pellet's largest
/// temperature, the pellet temperature furthest outside [`CONDUCTIVITY_RANGE`], the
/// cladding's largest von Mises stress and the pellet's largest principal stress (of the
/// nodal stresses, averaged from the cells), and the largest interface pressure (contact plus
/// gas, at the slave interface nodes).
///
/// # Errors
/// [`PelletError::Physics`] if the stresses cannot be recovered.
pub(super) fn extremes<TL: ConstraintLaw, ML: ConstraintLaw>(
    problem: &GapThermoMechanics<TL, ML>,
    x: &[f64],
    time: f64,
) -> Result<Extremes, PelletError> {
    let f = problem.fields(x);
    let elastic = problem.elastic_bodies();
    let coords = |b: usize| elastic[b].mesh.coords();
    let axisymmetric = problem.options().elastic.geometry.is_axisymmetric();
    let at = |body, position: Vector3<f64>| At {
        body,
        position,
        radius: if axisymmetric {
            position.x
        } else {
            position.xy().norm()
        },
    };
    let largest = |values: &mut dyn Iterator<Item = (usize, f64)>, b: usize, body| {
        let (i, v) =
            values
                .filter(|(_, v)| !v.is_nan())
                .fold(
                    (0, f64::NEG_INFINITY),
                    |m, (i, v)| if v > m.1 { (i, v) } else { m },
                );
        (v, at(body, coords(b)[i]))
    };
    let t = f.temperature[0];
    let hottest = largest(&mut t.iter().copied().enumerate(), 0, "pellet");
    let (lo, hi) = CONDUCTIVITY_RANGE;
    let coldest = largest(&mut t.iter().map(|&v| -v).enumerate(), 0, "pellet");
    let coldest = (-coldest.0, coldest.1);
    let outside = if hottest.0 - hi >= lo - coldest.0 {
        hottest
    } else {
        coldest
    };
    let stress = |b: usize| super::stress::stress_field(problem, &f, b, time);
    let cladding = stress(1)?;
    let von_mises = largest(
        &mut cladding.von_mises.iter().copied().enumerate(),
        1,
        "cladding",
    );
    let pellet = stress(0)?;
    let tension = largest(
        &mut pellet.nodal.iter().map(largest_principal).enumerate(),
        0,
        "pellet",
    );
    // The interface pressure at each slave interface node (a row of D).
    let tie = problem.heat().tie();
    let pressure = f.contact_pressure();
    let (j, p) =
        pressure.iter().enumerate().fold(
            (0, f64::NEG_INFINITY),
            |m, (j, &p)| if p > m.1 { (j, p) } else { m },
        );
    let node = tie.coupling().slave_nodes.get(j).copied().unwrap_or(0) as usize;
    let slave = tie.interface().slave();
    let position = slave
        .node_tags()
        .iter()
        .position(|&tag| tag as usize == node)
        .map_or(Vector3::zeros(), |i| slave.coords()[i]);
    let interface = (p + f.gas_pressure, at("interface", position));
    Ok([hottest, outside, von_mises, tension, interface])
}
