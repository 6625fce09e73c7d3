//! The Python module `mortar._mortar`: the compiled half of the `mortar` Python package
//! (`python/mortar/` is the other half, which re-exports these functions with Python
//! conveniences: scipy matrices, meshio input, the `Coupling` class).
//!
//! PyO3 stays behind this crate: the library crates know nothing of Python. Every function
//! here takes plain numpy arrays or Python scalars, returns plain dicts of numpy arrays, and
//! turns every library error into an exception of `mortar.errors` (`MortarError` and its
//! children) carrying the library's message. Work on user input never panics; a panic of the
//! library (a bug) is still caught at the boundary and raised as `MortarError`, never as
//! PyO3's `PanicException`.
//!
//! Conventions (see the package's docstrings): node `i` is row `i` of the `points` given,
//! face `j` row `j` of `cells` (both 0-based, as messages name them); coordinates in any
//! consistent length unit, D and M in that unit squared (3D) or the unit (2D).

mod couple;
mod crosspoint;
mod errors;
mod gmsh;
mod laws;
mod scene;

use pyo3::prelude::*;

/// The module.
#[pymodule]
fn _mortar(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(couple::couple_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(
        crosspoint::slave_dirichlet_shares_arrays,
        m
    )?)?;
    m.add_function(wrap_pyfunction!(gmsh::read_gmsh_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(scene::run_scene_text, m)?)?;
    m.add_function(wrap_pyfunction!(laws::law_names, m)?)?;
    m.add_function(wrap_pyfunction!(laws::evaluate_law, m)?)?;
    m.add_function(wrap_pyfunction!(laws::check_law_tangent, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
