"""couple(), read_gmsh() and the Coupling they return."""

from __future__ import annotations

import os
import time
import warnings
from typing import Any, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np
import scipy.sparse

from . import _mortar
from .errors import InvalidInputError

__all__ = [
    "Coupling",
    "SlaveDirichletRows",
    "Surface",
    "couple",
    "read_gmsh",
    "redistribute_slave_dirichlet",
]

#: Cell types a surface may have, meshio's names with the library's beside them.
CELL_TYPES = {
    "line": "line",
    "Line2": "line",
    "triangle": "triangle",
    "Tri3": "triangle",
    "quad": "quad",
    "Quad4": "quad",
    "line3": "line3",
    "Line3": "line3",
    "triangle6": "triangle6",
    "Tri6": "triangle6",
    "quad8": "quad8",
    "Quad8": "quad8",
    "quad9": "quad9",
    "Quad9": "quad9",
}

_INT64_MAX = np.iinfo(np.int64).max


class _SurfaceFields(NamedTuple):
    points: np.ndarray
    cells: np.ndarray
    cell_type: str


class Surface(_SurfaceFields):
    """A surface as three arrays, usable wherever :func:`couple` takes a surface.

    Unpacks as ``points, cells, cell_type``: ``points`` (n, 2) for lines (a 2D problem) or
    (n, 3) float64, ``cells`` (m, k) int64 with 0-based rows of ``points``, ``cell_type``
    meshio's name (``"line"``, ``"triangle"`` or ``"quad"``). :func:`read_gmsh` also sets
    ``node_tags`` (the file's tag of each point) and ``cell_tags`` (of each cell).
    """

    node_tags: Optional[np.ndarray] = None
    cell_tags: Optional[np.ndarray] = None


class Coupling:
    """The mortar coupling of a slave and a master surface (returned by :func:`couple`).

    Attributes:
        D: ``scipy.sparse.csr_array`` (slave nodes x slave nodes), ``D[j, k] = int Phi_j
            N_k^s``: in length^2 (3D) or length (2D). Diagonal for dual multipliers: on
            Tri6 and Quad8 slave faces in the recombined basis ``D T^T`` (see ``T``), as
            ``mortar couple`` writes it.
        T: ``None``, or with dual multipliers on Tri6 or Quad8 slave faces the recombination
            ``N~ = T N`` of the slave shape functions (Popp, Gee and Wall 2012; slave nodes x
            slave nodes, ``csr_array``): then ``D`` is ``D_nodal @ T.T`` and the constraint
            reads ``D @ u~_s - M @ u_m = 0`` in the slave unknowns ``u~_s`` with ``u_s = T.T
            @ u~_s``, so that ``u_s = T.T @ ((M @ u_m) / D.diagonal())``.
        D_nodal: D in the slave nodes' own basis (``D`` itself when ``T`` is None).
        slave_basis: ``"recombined"`` when ``T`` is given, else ``"nodal"``.
        M: ``scipy.sparse.csr_array`` (slave nodes x master nodes), ``M[j, l] = int Phi_j
            N_l^m``, same unit.
        slave_nodes: int64 (rows,): the row of the slave ``points`` of each row of D and M
            (ascending; only points used by a face).
        master_nodes: int64 (cols,): the row of the master ``points`` of each column of M.
        normals: float64 (rows, dim): unit averaged normals of the slave nodes (out of the
            slave body, towards the master), in row order; dim is 2 for a 2D problem.
        formulation: what was computed, e.g. ``"standard multipliers, segment-based, degree
            auto, nodal-normal-field projection"``.
        stats: dict: ``pairs`` (overlapping face pairs), ``segments`` (integration cells),
            ``area`` (sum of D: the overlap's area, or length in 2D), ``degrees_used``
            (quadrature degrees), ``seconds`` (wall time in the library: meshes, orientation,
            validation, assembly), ``seconds_by_phase``, ``seconds_call`` (the whole Python
            call, conversions included), ``uncovered_area``, ``faces_without_partner``,
            ``faces_partly_covered``, ``overlapped_area`` and ``faces_overlapped`` (slave
            area covered by more than one master face, and its faces), ``skipped_pairs``,
            ``fused_line_faces`` (slave faces done by the fused kernel for straight 2D
            lines), ``straight_line_faces`` (slave faces done by the sorted merge of a
            straight 2D interface), ``closed_form_faces`` (3D slave faces whose clip polygons
            were integrated in closed form), ``d_roundoff_dropped`` (off-diagonal round-off
            of a dual D lumped into its diagonal), ``d_off_diagonal`` and
            ``d_off_diagonal_largest`` (off-diagonal entries a dual D keeps, and the largest
            relative to its diagonal: none on an interface covered everywhere, unless the
            warning ``dual D not diagonal`` says why), ``slave_box_inflation`` and
            ``master_box_inflation`` (the search boxes' inflation, a fraction of a face's
            diameter: 0 where the nodes bound the faces), ``threads``, ``formulation``, and
            ``orientation`` (faces flipped per side) when ``orient=True``.
        warnings: list of str: uncovered slave area, overlapping master faces, skipped pairs,
            a dual D not diagonal (each also warned of with ``warnings.warn`` by
            :func:`couple`).
        dim: 2 or 3.

    The tying constraint of fields ``u_s`` (slave nodes, row order) and ``u_m`` (master
    nodes, column order) is ``D_nodal @ u_s - M @ u_m = 0`` (``D @ u_s - M @ u_m = 0`` but
    in the recombined basis, see ``T``); for a field given on all points,
    ``u_s = u[slave_nodes]``, ``u_m = u[master_nodes]``. With ``multipliers="linear"`` the
    rows of the edge and centre nodes of second-order faces are empty (no multiplier there):
    take ``D[c.multiplier_rows]`` and ``M[c.multiplier_rows]`` as the constraint, or its
    saddle point is singular.
    """

    def __init__(self, raw: dict, slave: Any = None):
        self.D = _csr(raw["d"])
        self.M = _csr(raw["m"])
        self.T: Optional[scipy.sparse.csr_array] = _csr(raw["t"]) if "t" in raw else None
        self.D_nodal = _csr(raw["d_nodal"]) if "d_nodal" in raw else self.D
        self.slave_basis: str = "nodal" if self.T is None else "recombined"
        # The slave surface as passed to the library (points, blocks), for
        # redistribute_slave_dirichlet.
        self._slave = slave
        self.slave_nodes: np.ndarray = raw["slave_nodes"]
        self.master_nodes: np.ndarray = raw["master_nodes"]
        self.normals: np.ndarray = raw["normals"]
        self.formulation: str = raw["formulation"]
        self.stats: dict = raw["stats"]
        self.warnings: list = raw["warnings"]
        self.dim: int = raw["dim"]

    @property
    def multiplier_rows(self) -> np.ndarray:
        """int64: the rows of D and M that carry a multiplier, ascending: every row but the
        empty ones (the edge and centre nodes of second-order faces with
        ``multipliers="linear"``, and slave nodes no master face covers)."""
        return np.flatnonzero(np.diff(self.D.indptr) > 0).astype(np.int64)

    def weighted_gap(self, x_s: np.ndarray, x_m: np.ndarray) -> np.ndarray:
        """The weighted gap vectors ``G = D x_s - M x_m``, one row per slave node.

        Args:
            x_s: (rows, dim) slave node positions in row order, e.g.
                ``points_s[c.slave_nodes]`` (current positions, in the unit of the points).
            x_m: (cols, dim) master node positions in column order,
                ``points_m[c.master_nodes]``.

        Returns:
            (rows, dim) float64, in length^3 (3D) or length^2 (2D): zero on a tied
            interface, and ``-normals[j] . G[j]`` is the weighted normal gap of node j
            (positive where the surfaces are apart).

        Raises:
            InvalidInputError: shapes that do not match the node counts, or NaN.
        """
        xs = _positions(x_s, len(self.slave_nodes), "x_s", "slave")
        xm = _positions(x_m, len(self.master_nodes), "x_m", "master")
        if xs.shape[1] != xm.shape[1]:
            raise InvalidInputError(
                f"x_s has {xs.shape[1]} columns and x_m {xm.shape[1]}: give both in the "
                "same dimension"
            )
        return self.D_nodal @ xs - self.M @ xm

    def normal_gaps(self, x_s: np.ndarray, x_m: np.ndarray) -> np.ndarray:
        """The weighted normal gaps ``g_j = -n_j . G_j`` (positive where the surfaces are
        apart), one per slave node; arguments as :meth:`weighted_gap`."""
        g = self.weighted_gap(x_s, x_m)
        n = self.normals[:, : g.shape[1]]
        return -np.einsum("ij,ij->i", n, g)

    def __repr__(self) -> str:
        s = self.stats
        return (
            f"<mortar.Coupling {self.dim}D: D {self.D.shape}, M {self.M.shape}, "
            f"{s['pairs']} pairs, area {s['area']:.6g}; {self.formulation}>"
        )


def _csr(raw: dict) -> scipy.sparse.csr_array:
    # The library's data array becomes the matrix's without a copy; the index arrays come
    # as int32 where they fit (what scipy would convert them to) or int64.
    return scipy.sparse.csr_array(
        (raw["data"], raw["indices"], raw["indptr"]), shape=raw["shape"], copy=False
    )


def _positions(x: Any, n: int, name: str, side: str) -> np.ndarray:
    a = np.asarray(x)
    if a.dtype.kind not in "fiu":
        raise InvalidInputError(f"{name}: dtype {a.dtype}; give float coordinates")
    if a.ndim != 2 or a.shape[0] != n or a.shape[1] not in (2, 3):
        raise InvalidInputError(
            f"{name}: shape {a.shape}; give ({n}, 2) or ({n}, 3): one row per {side} node, "
            f"in the order of {side}_nodes"
        )
    a = a.astype(np.float64, copy=False)
    if not np.all(np.isfinite(a)):
        raise InvalidInputError(f"{name}: NaN or infinite coordinates")
    return a


def _points(points: Any, side: str) -> np.ndarray:
    a = np.asarray(points)
    if a.dtype.kind not in "fiu":
        raise InvalidInputError(f"{side} points: dtype {a.dtype}; give float coordinates")
    if a.ndim != 2 or a.shape[1] not in (2, 3):
        raise InvalidInputError(
            f"{side} points: shape {a.shape}; points are (n, 2) or (n, 3) coordinates"
        )
    # No copy for float64 C-contiguous points (the library reads them in place).
    return np.ascontiguousarray(a, dtype=np.float64)


def _cells(cells: Any, side: str) -> np.ndarray:
    a = np.asarray(cells)
    if a.dtype.kind not in "iu":
        raise InvalidInputError(
            f"{side} cells: dtype {a.dtype}; give integer rows of the points array"
        )
    if a.ndim != 2:
        raise InvalidInputError(f"{side} cells: shape {a.shape}; cells are (m, k) integers")
    if a.dtype.kind == "u" and a.size and a.max() > _INT64_MAX:
        raise InvalidInputError(f"{side} cells: index {a.max()} out of range")
    # No copy for int64 C-contiguous cells; other integer types are converted once.
    return np.ascontiguousarray(a, dtype=np.int64)


def _cell_type(name: Any, side: str) -> str:
    if not isinstance(name, str) or name not in CELL_TYPES:
        raise InvalidInputError(
            f"{side} cell type {name!r}: known types are 'line' (Line2), 'triangle' (Tri3), "
            "'quad' (Quad4), 'line3' (Line3), 'triangle6' (Tri6), 'quad8' (Quad8) and "
            "'quad9' (Quad9)"
        )
    return CELL_TYPES[name]


def _is_meshio(x: Any) -> bool:
    return hasattr(x, "points") and hasattr(x, "cells") and hasattr(x, "cell_sets")


#: Reference dimension of each cell type.
_CELL_DIM = {
    "line": 1,
    "triangle": 2,
    "quad": 2,
    "line3": 1,
    "triangle6": 2,
    "quad8": 2,
    "quad9": 2,
}


def _meshio_blocks(mesh: Any, selection: Union[str, int, None], side: str):
    """The (cell_type, cells) blocks of a meshio.Mesh: a cell set, a Gmsh physical group (by
    name or tag), or, without a selection, every face block (every line block if there are
    no faces)."""
    blocks = [(b.type, np.asarray(b.data)) for b in mesh.cells]
    usable = [(i, t, c) for i, (t, c) in enumerate(blocks) if t in _CELL_DIM]
    if selection is None:
        top = max((_CELL_DIM[t] for _, t, _ in usable), default=None)
        out = [(t, c) for _, t, c in usable if _CELL_DIM[t] == top]
    elif isinstance(selection, str) and any(
        s is not None and len(s) for s in mesh.cell_sets.get(selection, [])
    ):
        sets = mesh.cell_sets[selection]
        out = [
            (t, c[np.asarray(sets[i], dtype=np.int64)])
            for i, t, c in usable
            if i < len(sets) and sets[i] is not None and len(sets[i])
        ]
    else:
        physical = mesh.cell_data.get("gmsh:physical")
        tag = dim = None
        if isinstance(selection, str) and selection in mesh.field_data:
            tag, dim = (int(v) for v in mesh.field_data[selection][:2])
        elif isinstance(selection, (int, np.integer)):
            tag = int(selection)
        if tag is None or physical is None:
            names = sorted(set(mesh.cell_sets) | set(getattr(mesh, "field_data", {})))
            raise InvalidInputError(
                f"{side} mesh: no cell set or physical group {selection!r} (the mesh has: "
                f"{', '.join(map(repr, names)) or 'none'})"
            )
        out = []
        for i, t, c in usable:
            if dim is not None and _CELL_DIM[t] != dim:
                continue
            mask = np.asarray(physical[i]) == tag
            if mask.any():
                out.append((t, c[mask]))
    out = [(t, c) for t, c in out if len(c)]
    if not out:
        raise InvalidInputError(
            f"{side} mesh: no line, triangle or quad cells"
            + (f" in {selection!r}" if selection is not None else "")
        )
    faces = [t for t, _ in out if _CELL_DIM[t] == 2]
    if faces:
        out = [(t, c) for t, c in out if _CELL_DIM[t] == 2]
    return out


SurfaceLike = Union[Surface, Tuple[Any, Any, str], Tuple[Any, Union[str, int]], Any]


def _surface(s: Any, side: str):
    """points (float64, C order) and [(cell_type, int64 cells)] of any accepted form."""
    if _is_meshio(s):
        return _points(s.points, side), _blocks(_meshio_blocks(s, None, side), side)
    if isinstance(s, (tuple, list)) and len(s) == 2 and _is_meshio(s[0]):
        return _points(s[0].points, side), _blocks(_meshio_blocks(s[0], s[1], side), side)
    if isinstance(s, (tuple, list)) and len(s) == 3:
        points, cells, cell_type = s
        return _points(points, side), [(_cell_type(cell_type, side), _cells(cells, side))]
    if isinstance(s, (tuple, list)) and len(s) == 2:
        points, blocks = s
        pairs = [(b.type, b.data) if hasattr(b, "type") else tuple(b) for b in blocks]
        return _points(points, side), _blocks(pairs, side)
    raise InvalidInputError(
        f"{side}: give (points, cells, cell_type), (points, [(cell_type, cells), ...]), a "
        f"meshio.Mesh, or (meshio.Mesh, selection); got {type(s).__name__}"
    )


def _blocks(pairs: Sequence, side: str):
    return [(_cell_type(t, side), _cells(c, side)) for t, c in pairs]


def couple(
    slave: SurfaceLike,
    master: SurfaceLike,
    *,
    multipliers: Optional[str] = None,
    integration: Optional[str] = None,
    degree: Optional[int] = None,
    threads: Optional[int] = None,
    orient: bool = True,
    require_full_coverage: bool = False,
    curved_tolerance: Optional[float] = None,
    subdivision: Optional[int] = None,
    quad_subdivision: Optional[int] = None,
    search_radius: Optional[float] = None,
) -> Coupling:
    """Assemble the mortar operators D and M between two non-matching surfaces.

    ``D[j, k] = int Phi_j N_k^s`` and ``M[j, l] = int Phi_j N_l^m`` over the overlap of the
    slave (non-mortar, carries the multipliers Phi) and the master surface; the tying
    constraint is ``D u_s - M u_m = 0``.

    Args:
        slave, master: each a surface, one of
            - ``(points, cells, cell_type)``: ``points`` (n, 2) or (n, 3) coordinates (any
              consistent length unit; a 2D problem has lines in the plane z = 0),
              ``cells`` (m, k) integers, each row the 0-based rows of ``points`` of one
              face in the element's node order, ``cell_type`` ``"line"``, ``"triangle"``
              or ``"quad"`` (or ``"Line2"``, ``"Tri3"``, ``"Quad4"``);
            - ``(points, [(cell_type, cells), ...])`` for mixed triangles and quads (faces
              numbered through the blocks in order);
            - a ``meshio.Mesh`` (its triangle and quad blocks, or its line blocks if it has
              no faces), or ``(mesh, selection)`` with a cell set name, a Gmsh physical
              group name (``mesh.field_data``) or a physical tag;
            - a :class:`Surface` from :func:`read_gmsh`.
            Points no face uses are ignored.
        multipliers: ``"standard"`` (Phi = N), ``"dual"`` (biorthogonal: D diagonal) or
            ``"linear"`` (second-order faces: first-order functions on the corner nodes
            only, the rows of the other nodes empty; standard on first-order faces); None:
            the default of ``mortar couple`` and the scene files, ``"dual"``.
        integration: ``"segment"`` (clipped overlaps: exact on affine faces; the default
            for None) or ``"element"`` (slave quadrature points projected: cheaper,
            inexact where master edges cross a slave face).
        degree: quadrature degree; None picks the lowest exact one (in ``stats``).
        threads: worker threads; None uses all cores (or ``RAYON_NUM_THREADS``). D and M
            are bit-for-bit the same for any count.
        orient: make each surface consistently oriented and turned to face the other (the
            master's normals opposing the slave's) before coupling; False trusts the node
            order given (then a master facing the wrong way is an error that says so).
        require_full_coverage: make uncovered slave area, overlapping master faces or
            skipped pairs an error (:class:`CoverageError`) instead of a warning.
        curved_tolerance: segment-based, curved second-order faces in 3D: the bend left per
            flat sub-triangle, relative to the face size (None: 1e-2); smaller is finer.
        subdivision: segment-based, curved second-order faces in 3D: a fixed subdivision
            level (1 to 16) instead of the tolerance's.
        quad_subdivision: segment-based, slave quads that are not parallelograms: cut each
            clip triangle into m^2 (1 to 16; None: 1) so that M follows the master edges'
            curved images in the quad's coordinates (error about m^-4, cost m^2 on such
            faces).
        search_radius: how far along the slave normals (both ways) to look for master
            faces, a distance in the points' unit (``mortar couple --search-radius``); None:
            the library's default (as far as the nearest master surface, within a quarter
            of the interface's size). Master faces beyond it are not coupled.

    Returns:
        A :class:`Coupling`: ``D``, ``M`` (``scipy.sparse.csr_array``), ``T`` (dual
        multipliers on Tri6 or Quad8 faces: D in the recombined basis), ``slave_nodes``,
        ``master_nodes`` (rows of the points given), ``normals``, ``stats``,
        ``formulation``, ``weighted_gap(x_s, x_m)``.

    Raises:
        InvalidInputError: wrong shapes or dtypes, indices out of range, NaN or infinite
            coordinates, an unknown cell type or option (also a ``ValueError``).
        GeometryError: a degenerate or inverted face, a surface that is not a manifold.
        NoOverlapError: no slave face overlaps a master face.
        CoverageError: with ``require_full_coverage``, uncovered area, overlapping master
            faces or skipped pairs.

    Copies: float64 C-contiguous points and int64 C-contiguous cells are read in place (other
    dtypes or layouts are converted once); the library builds its own meshes from them. The
    data arrays of D and M are handed over without a copy; their index arrays are converted
    once to int32 where they fit (as scipy would). The GIL is released while the library
    works.
    """
    start = time.perf_counter()
    sp, sb = _surface(slave, "slave")
    mp, mb = _surface(master, "master")
    if degree is not None and (
        not isinstance(degree, (int, np.integer)) or not 0 <= degree < 2**31
    ):
        raise InvalidInputError(f"degree={degree!r}: give a non-negative integer or None")
    if threads is not None and (
        not isinstance(threads, (int, np.integer)) or not 1 <= threads < 2**31
    ):
        raise InvalidInputError(f"threads={threads!r}: give a positive integer or None")
    if search_radius is not None and (
        isinstance(search_radius, bool)
        or not isinstance(search_radius, (int, float, np.integer, np.floating))
    ):
        raise InvalidInputError(
            f"search_radius={search_radius!r}: give a distance (a non-negative number) or None"
        )
    raw = _mortar.couple_arrays(
        sp,
        sb,
        mp,
        mb,
        multipliers=multipliers,
        integration=integration,
        degree=None if degree is None else int(degree),
        threads=None if threads is None else int(threads),
        orient=bool(orient),
        require_full_coverage=bool(require_full_coverage),
        curved_tolerance=None if curved_tolerance is None else float(curved_tolerance),
        subdivision=None if subdivision is None else int(subdivision),
        quad_subdivision=None if quad_subdivision is None else int(quad_subdivision),
        search_radius=None if search_radius is None else float(search_radius),
    )
    c = Coupling(raw, (sp, sb))
    for w in c.warnings:
        warnings.warn(f"mortar: {w}", RuntimeWarning, stacklevel=2)
    c.stats["seconds_call"] = time.perf_counter() - start
    return c


class SlaveDirichletRows(NamedTuple):
    """The constraint rows of a coupling with the rows of its Dirichlet slave nodes shared
    among their free neighbours (returned by :func:`redistribute_slave_dirichlet`)."""

    #: ``S @ coupling.D``: the constraint's slave operator (kept rows x slave nodes).
    D: scipy.sparse.csr_array
    #: ``S @ coupling.M``: the constraint's master operator (kept rows x master nodes).
    M: scipy.sparse.csr_array
    #: int64: for each kept row, its row of the coupling (a free slave node with a multiplier).
    rows: np.ndarray
    #: ``S`` (kept rows x coupling rows): 1 on each kept row's own row and the shares of the
    #: Dirichlet rows it takes.
    S: scipy.sparse.csr_array
    #: Dirichlet rows shared among free rows.
    redistributed: int
    #: Dirichlet rows with no free row in reach, dropped without a share.
    dropped: int


def redistribute_slave_dirichlet(coupling: Coupling, dirichlet: Any) -> SlaveDirichletRows:
    """The constraint rows of ``coupling`` when some slave nodes carry Dirichlet conditions.

    A Dirichlet slave node (where the interface meets a Dirichlet boundary: a crosspoint)
    cannot keep its multiplier: its constraint row would over-constrain the master side.
    Dropping the row loses the constant in the multiplier space, and with it the patch test
    (a linear field is then not reproduced near the crosspoint). This function is the
    library's treatment (``SlaveDirichlet::Redistribute`` of its tied systems, Wohlmuth's
    crosspoint modification): each such row is removed and its multiplier shared among the
    nearest free slave nodes (those of its slave faces, or one face further where all of
    those are Dirichlet nodes; on second-order faces with the weights that keep linear
    functions, else equally). The rows still reproduce constants, so the patch test passes,
    and a diagonal D stays diagonal on the free slave nodes.

    Args:
        coupling: a :class:`Coupling` from :func:`couple`.
        dirichlet: the slave points with Dirichlet conditions, as integer rows of the slave
            ``points`` given to :func:`couple` (the numbering of ``slave_nodes``); points
            not on the interface are ignored.

    Returns:
        :class:`SlaveDirichletRows`: the constraint ``D @ u_s - M @ u_m = 0`` (in the basis
        of ``coupling.D``: see ``coupling.T``), the coupling row of each of its rows, ``S``,
        and the counts.

    Raises:
        InvalidInputError: ``dirichlet`` not integers; a coupling not made by :func:`couple`.
    """
    if not isinstance(coupling, Coupling) or coupling._slave is None:
        raise InvalidInputError("coupling: give a Coupling returned by mortar.couple")
    nodes = np.asarray(dirichlet)
    if nodes.size and nodes.dtype.kind not in "iu":
        raise InvalidInputError(
            f"dirichlet: dtype {nodes.dtype}; give integer rows of the slave points"
        )
    fixed = np.isin(coupling.slave_nodes, nodes.ravel())
    carries = np.diff(coupling.D.indptr) > 0
    points, blocks = coupling._slave
    raw = _mortar.slave_dirichlet_shares_arrays(
        points,
        blocks,
        np.ascontiguousarray(coupling.slave_nodes, dtype=np.int64),
        np.ascontiguousarray(carries),
        np.ascontiguousarray(fixed),
    )
    S = _csr(raw["s"])
    return SlaveDirichletRows(
        D=scipy.sparse.csr_array(S @ coupling.D),
        M=scipy.sparse.csr_array(S @ coupling.M),
        rows=raw["rows"],
        S=S,
        redistributed=int(raw["redistributed"]),
        dropped=int(raw["dropped"]),
    )


def read_gmsh(path: Union[str, "os.PathLike[str]"], group: Union[str, int, None] = None) -> Surface:
    """Read the faces of a Gmsh 4.1 file (ASCII or binary) as a :class:`Surface`.

    Args:
        path: the ``.msh`` file.
        group: a physical group's name (or its tag) to read only its faces; None reads the
            whole file's faces (its surfaces, or its lines if it has no surfaces; a file with
            volume cells needs a group).

    Returns:
        ``Surface(points, cells, cell_type)``: ``points`` (n, 2) for lines at z = 0 (a 2D
        problem) or (n, 3), in the file's unit; ``cells`` (m, k) 0-based rows of ``points``;
        ``cell_type`` ``"line"``, ``"triangle"`` or ``"quad"``; with ``node_tags`` and
        ``cell_tags``, the file's tags. Only the points the faces use are returned. Where
        every face bounds one cell of the file, faces are oriented out of that cell (as
        ``mortar couple`` does).

    Raises:
        MeshFileError: a missing or malformed file, an unknown group (the message lists the
            file's groups), a group with no faces (also an ``OSError``).
        InvalidInputError: faces of more than one type in the selection (select a group of
            one type, or read the file with meshio and pass the mesh to :func:`couple`).
    """
    raw = _mortar.read_gmsh_arrays(os.fspath(path), None if group is None else str(group))
    s = Surface(raw["points"], raw["cells"], raw["cell_type"])
    s.node_tags = raw["node_tags"]
    s.cell_tags = raw["cell_tags"]
    return s
