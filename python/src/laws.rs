//! The shipped constraint laws, pointwise: value and tangent by name and parameters.

use std::collections::BTreeMap;

use mortar::physics::laws::{
    check_tangent, evaluate, LawError, LawParameters, LawPoint, LawRegistry, LawTangent,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{self, Kind};

/// A law error as its exception: `InvalidInputError` for NaN input, `LawError` otherwise.
fn law_error(e: &LawError) -> PyErr {
    let kind = match e {
        LawError::NanInput { .. } => Kind::InvalidInput,
        _ => Kind::Law,
    };
    errors::raise(kind, e.to_string())
}

/// The point of the keywords.
fn point(
    gap: f64,
    multiplier: f64,
    temperature: f64,
    normal_gap: f64,
    contact_pressure: f64,
    gas_pressure: f64,
) -> LawPoint<f64> {
    LawPoint::new(gap, multiplier, temperature).with_mechanics(
        normal_gap,
        contact_pressure,
        gas_pressure,
    )
}

/// The law `name` of the shipped registry made from `params`.
fn make(name: &str, params: BTreeMap<String, f64>) -> PyResult<mortar::physics::laws::DynLaw> {
    let params: LawParameters = params;
    errors::no_panic(|| LawRegistry::with_shipped().make(name, &params))
        .map_err(|m| errors::raise(Kind::Base, m))?
        .map_err(|e| law_error(&e))
}

/// The names of the shipped laws, sorted.
#[pyfunction]
pub(crate) fn law_names() -> Vec<String> {
    LawRegistry::with_shipped()
        .names()
        .into_iter()
        .map(str::to_string)
        .collect()
}

/// The value and partial derivatives of law `name` (made from `params`) at a point; a dict
/// with `value` and `d_gap`, `d_multiplier`, `d_temperature`, `d_normal_gap`,
/// `d_contact_pressure`, `d_gas_pressure`.
#[pyfunction]
#[pyo3(signature = (
    name, params, gap, multiplier, temperature,
    normal_gap = 0.0, contact_pressure = 0.0, gas_pressure = 0.0
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn evaluate_law<'py>(
    py: Python<'py>,
    name: &str,
    params: BTreeMap<String, f64>,
    gap: f64,
    multiplier: f64,
    temperature: f64,
    normal_gap: f64,
    contact_pressure: f64,
    gas_pressure: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let law = make(name, params)?;
    let p = point(
        gap,
        multiplier,
        temperature,
        normal_gap,
        contact_pressure,
        gas_pressure,
    );
    let t: LawTangent = errors::no_panic(|| evaluate(&law, p))
        .map_err(|m| errors::raise(Kind::Base, m))?
        .map_err(|e| law_error(&e))?;
    let d = PyDict::new(py);
    d.set_item("value", t.value)?;
    d.set_item("d_gap", t.d_gap)?;
    d.set_item("d_multiplier", t.d_multiplier)?;
    d.set_item("d_temperature", t.d_temperature)?;
    d.set_item("d_normal_gap", t.d_normal_gap)?;
    d.set_item("d_contact_pressure", t.d_contact_pressure)?;
    d.set_item("d_gas_pressure", t.d_gas_pressure)?;
    Ok(d)
}

/// The tangent of law `name` at a point against central finite differences: a dict with
/// `max_relative_error` and `rows` (argument, dual-number derivative, finite difference, step).
#[pyfunction]
#[pyo3(signature = (
    name, params, gap, multiplier, temperature,
    normal_gap = 0.0, contact_pressure = 0.0, gas_pressure = 0.0
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn check_law_tangent<'py>(
    py: Python<'py>,
    name: &str,
    params: BTreeMap<String, f64>,
    gap: f64,
    multiplier: f64,
    temperature: f64,
    normal_gap: f64,
    contact_pressure: f64,
    gas_pressure: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let law = make(name, params)?;
    let p = point(
        gap,
        multiplier,
        temperature,
        normal_gap,
        contact_pressure,
        gas_pressure,
    );
    let c = errors::no_panic(|| check_tangent(&law, p))
        .map_err(|m| errors::raise(Kind::Base, m))?
        .map_err(|e| law_error(&e))?;
    let d = PyDict::new(py);
    d.set_item("max_relative_error", c.max_relative_error)?;
    d.set_item("rows", c.rows)?;
    Ok(d)
}
