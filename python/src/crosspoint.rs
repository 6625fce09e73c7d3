//! `slave_dirichlet_shares_arrays`: the treatment of Dirichlet slave nodes of the library's
//! tied systems (`SlaveDirichlet::Redistribute`) for the rows of a coupling made in Python.

use mortar::physics::tied::slave_dirichlet_shares;
use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::couple::{csr, side_arrays, surface, Failure};
use crate::errors;

/// The shares `S` of the rows of a coupling whose slave surface is `slave_points` and
/// `slave_blocks` (as `couple_arrays` takes them) and whose row `r` is the point
/// `slave_nodes[r]`: `S D` and `S M` are the constraint rows once the rows of the Dirichlet
/// slave nodes (`dirichlet[r]`) that carry a multiplier (`carries[r]`) are shared among
/// their free neighbours. Returns a dict: `s` (CSR arrays), `rows` (the coupling row of each
/// row of `S`), `redistributed`, `dropped`.
#[pyfunction]
pub(crate) fn slave_dirichlet_shares_arrays<'py>(
    py: Python<'py>,
    slave_points: PyReadonlyArray2<'py, f64>,
    slave_blocks: Vec<(String, PyReadonlyArray2<'py, i64>)>,
    slave_nodes: PyReadonlyArray1<'py, i64>,
    carries: PyReadonlyArray1<'py, bool>,
    dirichlet: PyReadonlyArray1<'py, bool>,
) -> PyResult<Bound<'py, PyDict>> {
    let input = |m: &str| Failure::Input(m.to_string()).into_py();
    let side = side_arrays("slave", &slave_points, &slave_blocks).map_err(Failure::into_py)?;
    let nodes = slave_nodes
        .as_slice()
        .map_err(|_| input("slave_nodes: not a contiguous int64 array"))?;
    let carries = carries
        .as_slice()
        .map_err(|_| input("carries: not a contiguous bool array"))?;
    let dirichlet = dirichlet
        .as_slice()
        .map_err(|_| input("dirichlet: not a contiguous bool array"))?;
    let shares = py
        .detach(|| {
            errors::no_panic(|| {
                let mesh = surface(&side)?;
                let row_nodes = nodes
                    .iter()
                    .map(|&tag| {
                        u64::try_from(tag)
                            .ok()
                            .and_then(|t| mesh.node_index(t))
                            .ok_or_else(|| {
                                Failure::Input(format!(
                                    "slave node {tag}: not a point of a slave face"
                                ))
                            })
                    })
                    .collect::<Result<Vec<u32>, Failure>>()?;
                slave_dirichlet_shares(&mesh, &row_nodes, carries, dirichlet)
                    .map_err(|e| Failure::Input(e.to_string()))
            })
            .unwrap_or_else(|m| Err(Failure::Panic(m)))
        })
        .map_err(Failure::into_py)?;
    let out = PyDict::new(py);
    let rows: Vec<i64> = shares.rows.iter().map(|&r| r as i64).collect();
    out.set_item("s", csr(py, shares.s)?)?;
    out.set_item("rows", PyArray1::from_vec(py, rows))?;
    out.set_item("redistributed", shares.redistributed)?;
    out.set_item("dropped", shares.dropped)?;
    Ok(out)
}
