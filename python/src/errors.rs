//! Library errors as Python exceptions. The classes are defined in Python
//! (`mortar/errors.py`, so that they can subclass both `MortarError` and a builtin such as
//! `ValueError`); this module looks them up by name when it raises one.

use std::any::Any;

use mortar::MortarError;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyType;

/// The exception classes of `mortar.errors`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// `MortarError`: the base, for what fits no child.
    Base,
    /// `InvalidInputError` (also a `ValueError`): shapes, dtypes, NaN, options, ranges.
    InvalidInput,
    /// `GeometryError`: degenerate, inverted or folded faces, bad topology, failed projections.
    Geometry,
    /// `NoOverlapError`: no slave face overlaps a master face.
    NoOverlap,
    /// `CoverageError`: uncovered area, overlapping master faces or skipped pairs with full
    /// coverage required.
    Coverage,
    /// `MeshFileError`: a mesh file that cannot be read or has not what was asked.
    MeshFile,
    /// `SceneError`: a scene that cannot be run.
    Scene,
    /// `LawError`: a constraint law that cannot be made or evaluated.
    Law,
}

impl Kind {
    fn class_name(self) -> &'static str {
        match self {
            Kind::Base => "MortarError",
            Kind::InvalidInput => "InvalidInputError",
            Kind::Geometry => "GeometryError",
            Kind::NoOverlap => "NoOverlapError",
            Kind::Coverage => "CoverageError",
            Kind::MeshFile => "MeshFileError",
            Kind::Scene => "SceneError",
            Kind::Law => "LawError",
        }
    }
}

/// A Python exception of `kind` with `message`.
pub(crate) fn raise(kind: Kind, message: impl Into<String>) -> PyErr {
    let message = message.into();
    Python::attach(|py| {
        let class = py
            .import("mortar.errors")
            .and_then(|m| m.getattr(kind.class_name()))
            .and_then(|c| c.cast_into::<PyType>().map_err(PyErr::from));
        match class {
            Ok(class) => PyErr::from_type(class, (message,)),
            // The package is broken (its Python half missing): still an exception.
            Err(e) => PyRuntimeError::new_err(format!("{message} (mortar.errors: {e})")),
        }
    })
}

/// Which class a core error belongs to.
pub(crate) fn core_kind(e: &MortarError) -> Kind {
    match e {
        MortarError::NonFiniteCoordinate { .. }
        | MortarError::DuplicateNode { .. }
        | MortarError::UnknownNode { .. }
        | MortarError::WrongNodeCount { .. }
        | MortarError::CoordinateRange { .. }
        | MortarError::DimensionMismatch { .. }
        | MortarError::EmptySurface { .. }
        | MortarError::InvalidOption { .. }
        | MortarError::AxisymmetricNeeds2D { .. }
        | MortarError::NegativeRadius { .. } => Kind::InvalidInput,
        MortarError::DegenerateFace { .. }
        | MortarError::InvertedFace { .. }
        | MortarError::Topology { .. }
        | MortarError::ProjectionFailed { .. }
        | MortarError::MultiplierSpace { .. } => Kind::Geometry,
        MortarError::NoOverlap { .. } => Kind::NoOverlap,
        MortarError::IncompleteCoverage(_) => Kind::Coverage,
        _ => Kind::Base,
    }
}

/// A core error as its Python exception, with the library's message.
pub(crate) fn core(e: &MortarError) -> PyErr {
    raise(core_kind(e), e.to_string())
}

/// The message of a caught panic (a bug of the library: no input should reach one).
pub(crate) fn panic_message(payload: &(dyn Any + Send)) -> String {
    let what = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".to_string());
    format!("internal error (a bug of mortar, please report it with the input): {what}")
}

/// Runs `f`, turning a panic into an `Err` with its message, so that no panic unwinds into
/// Python (where PyO3 would raise `PanicException`, a `BaseException`).
pub(crate) fn no_panic<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).map_err(|p| panic_message(&*p))
}
