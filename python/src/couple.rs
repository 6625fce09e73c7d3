//! `couple_arrays`: two surfaces given as numpy arrays in, D, M and the node maps out.

use std::time::Instant;

use mortar::core::element::ElementRef;
use mortar::core::mesh::orient::{face_each_other, OrientationReport};
use mortar::elements::{LINE2, LINE3, QUAD4, QUAD8, QUAD9, TRI3, TRI6};
use mortar::settings::{parse_or_default, CouplingSettings, Integration, Multipliers};
use mortar::{
    assemble_coupling, Coupling, CouplingOptions, Interface, MortarError, SpatialDim, SurfaceMesh,
    Tolerances,
};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{self, Kind};

/// How far the facing step looks across a gap, in slave face sizes (as `mortar couple`).
const FACING_REACH: f64 = 2.0;

/// What went wrong off the GIL, turned into a Python exception once it is held again.
pub(crate) enum Failure {
    /// An error of the library.
    Core(MortarError),
    /// Input the library never saw (shapes, indices, names), with the message.
    Input(String),
    /// A panic (a bug), with its message.
    Panic(String),
}

impl Failure {
    pub(crate) fn into_py(self) -> PyErr {
        match self {
            Failure::Core(e) => errors::core(&e),
            Failure::Input(m) => errors::raise(Kind::InvalidInput, m),
            Failure::Panic(m) => errors::raise(Kind::Base, m),
        }
    }
}

/// A surface element by its meshio name (`line`, `triangle`, `quad`, `line3`, `triangle6`,
/// `quad8`, `quad9`; the same node order as Gmsh's) or the library's (`Line2`, ..., `Quad9`).
fn element(name: &str) -> Option<ElementRef> {
    match name {
        "line" | "Line2" => Some(&LINE2),
        "triangle" | "Tri3" => Some(&TRI3),
        "quad" | "Quad4" => Some(&QUAD4),
        "line3" | "Line3" => Some(&LINE3),
        "triangle6" | "Tri6" => Some(&TRI6),
        "quad8" | "Quad8" => Some(&QUAD8),
        "quad9" | "Quad9" => Some(&QUAD9),
        _ => None,
    }
}

/// A block of cells of one type, borrowed from numpy (row-major, checked contiguous).
struct Block<'a> {
    cells: &'a [i64],
    k: usize,
    element: ElementRef,
}

/// One side's arrays, borrowed from numpy (row-major, checked contiguous).
pub(crate) struct SideArrays<'a> {
    side: &'static str,
    points: &'a [f64],
    n: usize,
    dim: usize,
    blocks: Vec<Block<'a>>,
    faces: usize,
}

/// Borrows one side's arrays and checks their shapes and the cell types.
pub(crate) fn side_arrays<'a>(
    side: &'static str,
    points: &'a PyReadonlyArray2<'_, f64>,
    blocks: &'a [(String, PyReadonlyArray2<'_, i64>)],
) -> Result<SideArrays<'a>, Failure> {
    let &[n, dim] = points.shape() else {
        return Err(Failure::Input(format!("{side} points: not a 2-D array")));
    };
    if dim != 2 && dim != 3 {
        return Err(Failure::Input(format!(
            "{side} points: shape ({n}, {dim}); points are (n, 2) or (n, 3) coordinates"
        )));
    }
    let points_slice = points
        .as_slice()
        .map_err(|_| Failure::Input(format!("{side} points: not a C-contiguous float64 array")))?;
    let mut out = Vec::with_capacity(blocks.len());
    let mut faces = 0;
    for (cell_type, cells) in blocks {
        let &[m, k] = cells.shape() else {
            return Err(Failure::Input(format!("{side} cells: not a 2-D array")));
        };
        let element = element(cell_type).ok_or_else(|| {
            Failure::Input(format!(
                "{side} cell type \"{cell_type}\": known types are \"line\" (Line2), \
                 \"triangle\" (Tri3) and \"quad\" (Quad4)"
            ))
        })?;
        if k != element.node_count() {
            return Err(Failure::Input(format!(
                "{side} cells: shape ({m}, {k}); a {cell_type} cell has {} nodes",
                element.node_count()
            )));
        }
        let cells_slice = cells
            .as_slice()
            .map_err(|_| Failure::Input(format!("{side} cells: not a C-contiguous int64 array")))?;
        faces += m;
        out.push(Block {
            cells: cells_slice,
            k,
            element,
        });
    }
    Ok(SideArrays {
        side,
        points: points_slice,
        n,
        dim,
        blocks: out,
        faces,
    })
}

/// The surface mesh of one side: the points used by a cell (tag = row of `points`) and the
/// cells (tag = row in the concatenation of the blocks).
pub(crate) fn surface(a: &SideArrays<'_>) -> Result<SurfaceMesh, Failure> {
    let mut used = vec![false; a.n];
    let mut j0 = 0;
    for b in &a.blocks {
        for (j, row) in b.cells.chunks_exact(b.k).enumerate() {
            for &i in row {
                match usize::try_from(i).ok().filter(|&i| i < a.n) {
                    Some(i) => used[i] = true,
                    None => {
                        return Err(Failure::Input(format!(
                            "{} cell {} refers to point {i}, but there are {} points (indices \
                             are 0-based rows of the points array)",
                            a.side,
                            j0 + j,
                            a.n
                        )))
                    }
                }
            }
        }
        j0 += b.cells.len() / b.k.max(1);
    }
    let nodes = used.iter().filter(|&&u| u).count();
    let mut mesh = SurfaceMesh::with_capacity(nodes, a.faces);
    let side_error = |e: MortarError| match e {
        // The library names the node by its tag, the row of `points`: say which side.
        MortarError::NonFiniteCoordinate { .. } | MortarError::DuplicateNode { .. } => {
            Failure::Input(format!("{} points: {e}", a.side))
        }
        e => Failure::Core(e),
    };
    for (i, x) in a.points.chunks_exact(a.dim).enumerate() {
        if used[i] {
            let z = if a.dim == 3 { x[2] } else { 0.0 };
            mesh.add_node(i as u64, [x[0], x[1], z])
                .map_err(side_error)?;
        }
    }
    let mut tags = [0u64; mortar::core::element::MAX_FACE_NODES];
    let mut tag = 0u64;
    for b in &a.blocks {
        for row in b.cells.chunks_exact(b.k) {
            for (t, &i) in tags.iter_mut().zip(row) {
                *t = i as u64;
            }
            mesh.add_face_with_tag(tag, b.element, &tags[..b.k])
                .map_err(side_error)?;
            tag += 1;
        }
    }
    Ok(mesh)
}

/// The dials of segment-based integration (`curved_tolerance`, `subdivision`,
/// `quad_subdivision`; see `mortar::core::integration::SegmentBased`).
#[derive(Debug, Clone, Copy, Default)]
struct SegmentDials {
    curved_tolerance: Option<f64>,
    subdivision: Option<u32>,
    quad_subdivision: Option<u32>,
}

/// The options and tolerances of the keywords, through the library's own
/// [`CouplingSettings`] (the settings of `mortar couple` and the scene files): the search
/// radius reaches the interface as `mortar couple --search-radius` makes it do, so that the
/// default is the library's.
#[allow(clippy::too_many_arguments)]
fn options(
    multipliers: Option<&str>,
    integration: Option<&str>,
    degree: Option<u32>,
    dials: SegmentDials,
    threads: Option<usize>,
    search_radius: Option<f64>,
    require_full_coverage: bool,
) -> Result<(CouplingOptions, Tolerances), Failure> {
    // Names as the scene files spell them; None is the vocabulary's default.
    let named = |what: &str, given: Option<&str>, e: String| {
        Failure::Input(format!("{what}={:?}: {e}", given.unwrap_or_default()))
    };
    let multipliers: Multipliers =
        parse_or_default(multipliers).map_err(|e| named("multipliers", multipliers, e))?;
    let integration: Integration =
        parse_or_default(integration).map_err(|e| named("integration", integration, e))?;
    if threads == Some(0) {
        return Err(Failure::Input(
            "threads=0: give at least one thread, or None for all cores".into(),
        ));
    }
    let settings = CouplingSettings {
        multipliers,
        integration,
        degree,
        threads,
        search_radius,
        require_full_coverage,
        curved_tolerance: dials.curved_tolerance,
        subdivision: dials.subdivision,
        quad_subdivision: dials.quad_subdivision,
    };
    let options = settings.options().map_err(Failure::Core)?;
    let tolerances = settings.tolerances().map_err(Failure::Core)?;
    Ok((options, tolerances))
}

/// What the work off the GIL returns.
struct Output {
    coupling: Coupling,
    orientation: Option<[OrientationReport; 2]>,
    dim: usize,
    seconds_meshes: f64,
    seconds_orientation: f64,
    seconds_interface: f64,
    seconds_total: f64,
}

/// Builds the meshes, orients them, validates the interface and assembles D and M.
fn work(
    slave: &SideArrays<'_>,
    master: &SideArrays<'_>,
    options: &CouplingOptions,
    tolerances: Tolerances,
    orient: bool,
) -> Result<Output, Failure> {
    let start = Instant::now();
    // The two meshes are built at once, unless one thread was asked for.
    let (s, m) = if options.threads == Some(1) {
        (surface(slave), surface(master))
    } else {
        std::thread::scope(|scope| {
            let master_mesh = scope.spawn(|| surface(master));
            let s = surface(slave);
            let m = master_mesh
                .join()
                .unwrap_or_else(|p| Err(Failure::Panic(errors::panic_message(&*p))));
            (s, m)
        })
    };
    let (mut s, mut m) = (s?, m?);
    let seconds_meshes = start.elapsed().as_secs_f64();
    let t = Instant::now();
    let orientation = if orient {
        Some(face_each_other(&mut s, &mut m, FACING_REACH, false, false).map_err(Failure::Core)?)
    } else {
        None
    };
    let seconds_orientation = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let interface = Interface::with_tolerances(s, m, tolerances).map_err(Failure::Core)?;
    let seconds_interface = t.elapsed().as_secs_f64();
    let coupling = assemble_coupling(&interface, options).map_err(Failure::Core)?;
    // Lines make a 2D problem whether their points came with two columns or three (z = 0).
    let dim = match interface.dim() {
        SpatialDim::Two => 2,
        SpatialDim::Three => 3,
    };
    // The meshes are dropped here, inside the timed span, as the caller's would be.
    drop(interface);
    Ok(Output {
        coupling,
        orientation,
        dim,
        seconds_meshes,
        seconds_orientation,
        seconds_interface,
        seconds_total: start.elapsed().as_secs_f64(),
    })
}

/// Index vectors as numpy arrays: int32 where every value fits (what scipy converts sparse
/// indices to anyway, so it keeps them without a copy), int64 otherwise (the allocation
/// reused: usize and i64 have the same size and alignment).
fn index_arrays(py: Python<'_>, fits_i32: bool, v: Vec<usize>) -> Bound<'_, PyAny> {
    if fits_i32 {
        let w: Vec<i32> = v.iter().map(|&x| x as i32).collect();
        PyArray1::from_vec(py, w).into_any()
    } else {
        let w: Vec<i64> = v.into_iter().map(|x| x as i64).collect();
        PyArray1::from_vec(py, w).into_any()
    }
}

/// A CSR matrix as a dict of its numpy arrays (indptr, indices, data, shape); the data vector
/// becomes its array without a copy.
pub(crate) fn csr<'py>(
    py: Python<'py>,
    a: mortar::core::linalg::SparseMatrix,
) -> PyResult<Bound<'py, PyDict>> {
    let shape = (a.rows(), a.cols());
    let largest = a.nnz().max(a.rows()).max(a.cols());
    let fits = i32::try_from(largest).is_ok();
    let (indptr, indices, data) = a.into_raw_storage();
    let d = PyDict::new(py);
    d.set_item("indptr", index_arrays(py, fits, indptr))?;
    d.set_item("indices", index_arrays(py, fits, indices))?;
    d.set_item("data", PyArray1::from_vec(py, data))?;
    d.set_item("shape", shape)?;
    Ok(d)
}

/// Couples two surfaces given as arrays (the compiled half of `mortar.couple`; see its
/// docstring). `*_points` are float64 (n, 2|3), C-contiguous; `*_blocks` lists of
/// `(cell_type, cells)` with `cells` int64 (m, k), C-contiguous, 0-based rows of the points.
/// Returns a dict of plain arrays.
#[pyfunction]
#[pyo3(signature = (
    slave_points, slave_blocks, master_points, master_blocks,
    *, multipliers = None, integration = None, degree = None, threads = None,
    orient = true, require_full_coverage = false, curved_tolerance = None, subdivision = None,
    quad_subdivision = None, search_radius = None
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn couple_arrays<'py>(
    py: Python<'py>,
    slave_points: PyReadonlyArray2<'py, f64>,
    slave_blocks: Vec<(String, PyReadonlyArray2<'py, i64>)>,
    master_points: PyReadonlyArray2<'py, f64>,
    master_blocks: Vec<(String, PyReadonlyArray2<'py, i64>)>,
    multipliers: Option<&str>,
    integration: Option<&str>,
    degree: Option<u32>,
    threads: Option<usize>,
    orient: bool,
    require_full_coverage: bool,
    curved_tolerance: Option<f64>,
    subdivision: Option<u32>,
    quad_subdivision: Option<u32>,
    search_radius: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let slave = side_arrays("slave", &slave_points, &slave_blocks).map_err(Failure::into_py)?;
    let master = side_arrays("master", &master_points, &master_blocks).map_err(Failure::into_py)?;
    let dials = SegmentDials {
        curved_tolerance,
        subdivision,
        quad_subdivision,
    };
    let (opts, tolerances) = options(
        multipliers,
        integration,
        degree,
        dials,
        threads,
        search_radius,
        require_full_coverage,
    )
    .map_err(Failure::into_py)?;
    // The GIL is released for the whole of the work: the arrays are only read (numpy's
    // borrow flags keep Rust from writing them; Python code must not write them meanwhile).
    let out = py
        .detach(|| {
            errors::no_panic(|| work(&slave, &master, &opts, tolerances, orient))
                .unwrap_or_else(|m| Err(Failure::Panic(m)))
        })
        .map_err(Failure::into_py)?;
    let stats = stats_dict(py, &out)?;
    let dim = out.dim;
    let c = out.coupling;
    let result = PyDict::new(py);
    let warnings: Vec<String> = c.warnings.iter().map(|w| w.to_string()).collect();
    let normals: Vec<f64> = c
        .slave_normals
        .iter()
        .flat_map(|n| n.iter().take(dim).copied().collect::<Vec<_>>())
        .collect();
    let rows = c.slave_normals.len();
    let to_index = |v: Vec<u64>| -> Vec<i64> { v.into_iter().map(|x| x as i64).collect() };
    result.set_item(
        "slave_nodes",
        PyArray1::from_vec(py, to_index(c.slave_nodes)),
    )?;
    result.set_item(
        "master_nodes",
        PyArray1::from_vec(py, to_index(c.master_nodes)),
    )?;
    result.set_item(
        "normals",
        PyArray1::from_vec(py, normals).reshape([rows, dim])?,
    )?;
    // D as `mortar couple` writes it: in the recombined slave basis where there is one (dual
    // multipliers on Tri6 or Quad8 faces), with T; the nodal D beside it.
    match c.recombined {
        Some(r) => {
            // The sum of D as given (T's columns sum to 1: the nodal D's, to round-off).
            stats.set_item("area", r.d.data().iter().sum::<f64>())?;
            stats.set_item("d_roundoff_dropped", r.d_roundoff_dropped)?;
            result.set_item("d", csr(py, r.d)?)?;
            result.set_item("t", csr(py, r.t)?)?;
            result.set_item("d_nodal", csr(py, c.d)?)?;
        }
        None => result.set_item("d", csr(py, c.d)?)?,
    }
    result.set_item("m", csr(py, c.m)?)?;
    result.set_item("formulation", c.formulation)?;
    result.set_item("warnings", warnings)?;
    result.set_item("stats", stats)?;
    result.set_item("dim", dim)?;
    Ok(result)
}

/// The `stats` entry of `couple_arrays`' result: the coupling's counts, areas and
/// formulation, the seconds by phase, and each side's orientation.
fn stats_dict<'py>(py: Python<'py>, out: &Output) -> PyResult<Bound<'py, PyDict>> {
    let c = &out.coupling;
    let stats = PyDict::new(py);
    let st = &c.stats;
    stats.set_item("pairs", st.pairs)?;
    stats.set_item("candidates", st.candidates)?;
    stats.set_item("segments", st.segments)?;
    stats.set_item("area", st.area)?;
    stats.set_item("back_facing", st.back_facing)?;
    stats.set_item("skipped_pairs", st.skipped_pairs)?;
    stats.set_item("uncovered_area", st.uncovered_area)?;
    stats.set_item("faces_without_partner", st.faces_without_partner)?;
    stats.set_item("faces_partly_covered", st.faces_partly_covered)?;
    stats.set_item("overlapped_area", st.overlapped_area)?;
    stats.set_item("faces_overlapped", st.faces_overlapped)?;
    stats.set_item("fused_line_faces", st.fused_line_faces)?;
    stats.set_item("straight_line_faces", st.straight_line_faces)?;
    stats.set_item("closed_form_faces", st.closed_form_faces)?;
    stats.set_item("slave_box_inflation", st.slave_box_inflation)?;
    stats.set_item("master_box_inflation", st.master_box_inflation)?;
    stats.set_item("d_roundoff_dropped", st.d_roundoff_dropped)?;
    stats.set_item("d_off_diagonal", st.d_off_diagonal)?;
    stats.set_item("d_off_diagonal_largest", st.d_off_diagonal_largest)?;
    stats.set_item("threads", st.threads)?;
    stats.set_item("degrees_used", c.degrees_used())?;
    stats.set_item("formulation", c.formulation.as_str())?;
    stats.set_item("seconds", out.seconds_total)?;
    let phases = PyDict::new(py);
    phases.set_item("meshes", out.seconds_meshes)?;
    phases.set_item("orientation", out.seconds_orientation)?;
    phases.set_item("interface", out.seconds_interface)?;
    phases.set_item("tree", st.seconds.tree)?;
    phases.set_item("faces", st.seconds.faces)?;
    phases.set_item("assembly", st.seconds.assembly)?;
    phases.set_item("coupling", st.seconds.total)?;
    stats.set_item("seconds_by_phase", phases)?;
    if let Some(o) = &out.orientation {
        let orientation = PyDict::new(py);
        for (name, r) in [("slave", &o[0]), ("master", &o[1])] {
            let side = PyDict::new(py);
            side.set_item("pieces", r.components)?;
            side.set_item("flipped", r.flipped)?;
            side.set_item("kept_as_given", r.kept_as_given)?;
            orientation.set_item(name, side)?;
        }
        stats.set_item("orientation", orientation)?;
    }
    Ok(stats)
}
