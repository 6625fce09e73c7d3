"""mortar: mortar coupling of non-matching surfaces, from Python.

Give it a slave and a master surface that touch but whose meshes do not match; it returns
the mortar coupling operators over their overlap::

    D[j, k] = integral of Phi_j N_k^s   (slave x slave)
    M[j, l] = integral of Phi_j N_l^m   (slave x master)

and the tying constraint is ``D u_s - M u_m = 0``.

Example::

    import numpy as np, mortar
    xs, ys = np.meshgrid(np.linspace(0, 1, 5), np.linspace(0, 1, 5))
    pts = np.c_[xs.ravel(), ys.ravel(), np.zeros(25)]
    quads = np.array([[i + 5 * j, i + 1 + 5 * j, i + 6 + 5 * j, i + 5 + 5 * j]
                      for j in range(4) for i in range(4)])
    c = mortar.couple((pts, quads, "quad"), (pts * [1, 1, 0], quads, "quad"))
    c.D.sum()                                 # 1.0: the interface area

Conventions:

- A surface is ``(points, cells, cell_type)``: ``points`` (n, 2) or (n, 3) float
  coordinates in any consistent length unit (2D problems: lines in the plane z = 0);
  ``cells`` (m, k) integer, each row the 0-based rows of ``points`` of one face in the
  element's node order; ``cell_type`` ``"line"``, ``"triangle"`` or ``"quad"`` (meshio's
  names; ``"Line2"``, ``"Tri3"``, ``"Quad4"`` too). Or a ``meshio.Mesh`` with a selection
  (see :func:`couple`).
- Rows of D and M are the slave nodes used by a face, columns of M the master nodes, each
  in ascending point index; :attr:`Coupling.slave_nodes` and :attr:`Coupling.master_nodes`
  map them back to rows of the points given.
- D and M carry the unit of the interface's measure: length squared in 3D, length in 2D.
- The master's normals must oppose the slave's; with ``orient=True`` (the default) each
  surface is made consistent and turned to face the other first, and what was turned is
  in ``stats["orientation"]``.
- Messages name faces and nodes by their 0-based rows in ``cells`` and ``points``.
"""

from __future__ import annotations

from . import laws
from ._couple import (
    Coupling,
    SlaveDirichletRows,
    Surface,
    couple,
    read_gmsh,
    redistribute_slave_dirichlet,
)
from ._mortar import __version__
from ._scene import run_scene
from .errors import (
    CoverageError,
    GeometryError,
    InvalidInputError,
    LawError,
    MeshFileError,
    MortarError,
    NoOverlapError,
    SceneError,
)

__all__ = [
    "Coupling",
    "CoverageError",
    "GeometryError",
    "InvalidInputError",
    "LawError",
    "MeshFileError",
    "MortarError",
    "NoOverlapError",
    "SceneError",
    "SlaveDirichletRows",
    "Surface",
    "__version__",
    "couple",
    "laws",
    "read_gmsh",
    "redistribute_slave_dirichlet",
    "run_scene",
]
