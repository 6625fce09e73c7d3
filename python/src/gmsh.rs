//! `read_gmsh_arrays`: the faces of a Gmsh file (or of one physical group) as numpy arrays.

use mortar::core::element::MAX_FACE_NODES;
use mortar::elements::ElementRegistry;
use mortar::io::{read_gmsh_surface, IoError};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{self, Kind};

/// The meshio name of a surface element of the library.
fn meshio_name(name: &str) -> &str {
    match name {
        "Line2" => "line",
        "Tri3" => "triangle",
        "Quad4" => "quad",
        "Line3" => "line3",
        "Tri6" => "triangle6",
        "Quad8" => "quad8",
        "Quad9" => "quad9",
        other => other,
    }
}

/// Reads a Gmsh 4.1 file (ASCII or binary): the whole file's faces or the physical group
/// `group`, each face oriented outward from the one cell of the file it bounds where every
/// face bounds one. Returns a dict: `points` (n, 2) for lines at z = 0 (a 2D problem) or
/// (n, 3),
/// `cells` (m, k) int64 (0-based rows of `points`), `cell_type` (meshio name), `node_tags`,
/// `cell_tags` (the file's tags), `oriented_from_cells` (faces reversed, or None).
#[pyfunction]
#[pyo3(signature = (path, group = None))]
pub(crate) fn read_gmsh_arrays<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    group: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let registry = ElementRegistry::new();
    let read = py.detach(|| {
        errors::no_panic(|| {
            let mut s =
                read_gmsh_surface(&path, group.as_deref(), &registry).map_err(|e| io_error(&e))?;
            let flipped = s
                .orient_outward()
                .map_err(|e| (errors::core_kind(&e), e.to_string()))?;
            Ok((s, flipped))
        })
        .unwrap_or_else(|m| Err((Kind::Base, m)))
    });
    let (surface, flipped) = read.map_err(|(k, m)| errors::raise(k, m))?;
    let mesh = &surface.mesh;
    // Lines in the plane z = 0 (a 2D problem) come as (n, 2); lines off it keep their z, so
    // that coupling them says what is wrong instead of dropping it.
    let planar = mesh.coords().iter().all(|x| x.z == 0.0);
    let dim = if surface.dimension == 1 && planar {
        2
    } else {
        3
    };
    let mut element = None;
    for f in 0..mesh.face_count() {
        let e = mesh.face(f).element;
        match element {
            None => element = Some(e),
            Some(first) if first.name() != e.name() => {
                return Err(errors::raise(
                    Kind::InvalidInput,
                    format!(
                        "{}: the faces are of more than one type ({} and {}); read_gmsh returns \
                         one cell block, so select a group of one type",
                        surface.label(),
                        first.name(),
                        e.name()
                    ),
                ))
            }
            Some(_) => {}
        }
    }
    let Some(element) = element else {
        return Err(errors::raise(
            Kind::MeshFile,
            format!("{}: no faces", surface.label()),
        ));
    };
    let k = element.node_count().min(MAX_FACE_NODES);
    let mut points: Vec<f64> = Vec::with_capacity(mesh.node_count() * dim);
    for x in mesh.coords() {
        points.extend(x.iter().take(dim));
    }
    let mut cells = Vec::with_capacity(mesh.face_count() * k);
    let mut cell_tags = Vec::with_capacity(mesh.face_count());
    for f in 0..mesh.face_count() {
        let v = mesh.face(f);
        cells.extend(v.nodes.iter().map(|&i| i64::from(i)));
        cell_tags.push(v.tag);
    }
    let d = PyDict::new(py);
    d.set_item(
        "points",
        PyArray1::from_vec(py, points).reshape([mesh.node_count(), dim])?,
    )?;
    d.set_item(
        "cells",
        PyArray1::from_vec(py, cells).reshape([mesh.face_count(), k])?,
    )?;
    d.set_item("cell_type", meshio_name(element.name()))?;
    d.set_item("node_tags", PyArray1::from_slice(py, mesh.node_tags()))?;
    d.set_item("cell_tags", PyArray1::from_vec(py, cell_tags))?;
    d.set_item("oriented_from_cells", flipped)?;
    d.set_item("label", surface.label())?;
    Ok(d)
}

/// A reader's error as its exception class and message.
fn io_error(e: &IoError) -> (Kind, String) {
    match e {
        IoError::Mesh { source, .. } => (errors::core_kind(source), e.to_string()),
        _ => (Kind::MeshFile, e.to_string()),
    }
}
