"""Type stub of the compiled module ``mortar._mortar`` (use the wrappers of ``mortar``)."""

from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

__version__: str

def couple_arrays(
    slave_points: npt.NDArray[np.float64],
    slave_blocks: Sequence[Tuple[str, npt.NDArray[np.int64]]],
    master_points: npt.NDArray[np.float64],
    master_blocks: Sequence[Tuple[str, npt.NDArray[np.int64]]],
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
) -> Dict[str, Any]:
    """The compiled half of :func:`mortar.couple`: C-contiguous float64 points (n, 2|3),
    blocks of (cell type, C-contiguous int64 cells (m, k)); returns a dict with ``d`` and
    ``m`` (each ``indptr``, ``indices``, ``data``, ``shape``), ``t`` and ``d_nodal`` (the
    same, where D is in the recombined slave basis), ``slave_nodes``, ``master_nodes``,
    ``normals``, ``formulation``, ``warnings``, ``stats``, ``dim``."""

def slave_dirichlet_shares_arrays(
    slave_points: npt.NDArray[np.float64],
    slave_blocks: Sequence[Tuple[str, npt.NDArray[np.int64]]],
    slave_nodes: npt.NDArray[np.int64],
    carries: npt.NDArray[np.bool_],
    dirichlet: npt.NDArray[np.bool_],
) -> Dict[str, Any]:
    """The compiled half of :func:`mortar.redistribute_slave_dirichlet`: a dict with ``s``
    (``indptr``, ``indices``, ``data``, ``shape``), ``rows``, ``redistributed``,
    ``dropped``."""

def read_gmsh_arrays(path: str, group: Optional[str] = None) -> Dict[str, Any]:
    """The compiled half of :func:`mortar.read_gmsh`: a dict with ``points``, ``cells``,
    ``cell_type``, ``node_tags``, ``cell_tags``, ``oriented_from_cells``, ``label``."""

def run_scene_text(
    text: str,
    path: str,
    out: Optional[str] = None,
    json: bool = False,
    base: Optional[str] = None,
) -> Tuple[str, List[str]]:
    """The compiled half of :func:`mortar.run_scene`: the scene named ``path`` in messages,
    its mesh paths relative to ``base`` (default: the folder of ``path``); the report as
    JSON text and the coupling warnings."""

def law_names() -> List[str]:
    """The names of the shipped constraint laws, sorted."""

def evaluate_law(
    name: str,
    params: Dict[str, float],
    gap: float,
    multiplier: float,
    temperature: float,
    normal_gap: float = 0.0,
    contact_pressure: float = 0.0,
    gas_pressure: float = 0.0,
) -> Dict[str, float]:
    """Value (``value``) and partial derivatives (``d_*``) of a law at a point."""

def check_law_tangent(
    name: str,
    params: Dict[str, float],
    gap: float,
    multiplier: float,
    temperature: float,
    normal_gap: float = 0.0,
    contact_pressure: float = 0.0,
    gas_pressure: float = 0.0,
) -> Dict[str, Any]:
    """``max_relative_error`` and ``rows`` of the tangent against finite differences."""
