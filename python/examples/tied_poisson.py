"""Poisson's equation on two non-matching scikit-fem meshes tied by mortar.

    -laplace(u) = f  on [0, 1] x [0, 1],  u = 0 on the boundary,
    u = sin(pi x) sin(pi y) exp(x)  (manufactured: f from it)

The square is cut at x = 1/2 into two bodies meshed independently with P1 triangles, the
right one 1.5 times finer than the left. mortar couples the cut: the right body's edge is the
slave (it carries the multipliers), the left's the master; the tying constraint
D u_s - M u_m = 0 enters a saddle point

    [ K   B^T ] [ u      ]   [ f ]
    [ B   0   ] [ lambda ] = [ 0 ],   B = [ -M  D ] on (left, right) unknowns,

solved by scipy.sparse.linalg.spsolve. The slave nodes at the ends of the cut lie on the
Dirichlet boundary (crosspoints): their multipliers cannot stay (B would lose full rank), and
mortar.redistribute_slave_dirichlet shares their rows among the neighbouring free slave
nodes, the library's treatment, which keeps constants in the multiplier space. Dropping
those rows instead (crosspoints="drop") loses the linear patch test with standard
multipliers: u = 1 + 2x + 3y is reproduced to 9e-15 at the nodes with the rows shared and
only to 8.4e-4 with them dropped (n = 4).

Run: python examples/tied_poisson.py [levels]   (prints the L2 error and its rate, and the
patch test)
"""

from __future__ import annotations

import sys

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve
from skfem import Basis, BilinearForm, ElementTriP1, Functional, LinearForm, MeshTri
from skfem.helpers import dot, grad

import mortar

CUT = 0.5


def exact(x, y):
    return np.sin(np.pi * x) * np.sin(np.pi * y) * np.exp(x)


def source(x, y):
    # -laplace(u) for u = sin(pi x) sin(pi y) e^x.
    s, c = np.sin(np.pi * x), np.cos(np.pi * x)
    return -np.exp(x) * np.sin(np.pi * y) * (s + 2 * np.pi * c - 2 * np.pi**2 * s)


@BilinearForm
def laplace(u, v, w):
    return dot(grad(u), grad(v))


def linear(x, y):
    # The patch test's field: harmonic, so f = 0, and P1 elements represent it exactly.
    return 1.0 + 2.0 * x + 3.0 * y


@LinearForm
def load(v, w):
    return w["f"] * v


@Functional
def l2_error_squared(w):
    return (w["uh"] - w["ue"]) ** 2


def body(x0, x1, nx):
    """A P1 body over [x0, x1] x [0, 1] with nx x 2 nx cells cut into triangles."""
    mesh = MeshTri.init_tensor(np.linspace(x0, x1, nx + 1), np.linspace(0.0, 1.0, 2 * nx + 1))
    basis = Basis(mesh, ElementTriP1())
    cut_facets = mesh.facets_satisfying(lambda x: np.isclose(x[0], CUT))
    outer = mesh.boundary_facets()
    midpoints = mesh.p[:, mesh.facets[:, outer]].mean(axis=1)
    boundary = basis.get_dofs(facets=outer[~np.isclose(midpoints[0], CUT)]).all()
    return mesh, basis, cut_facets, boundary


def solve(n: int, multipliers: str = "standard", crosspoints: str = "redistribute", field=exact):
    """Solves with the left body n x 2n cells, the right 1.5 n x 3 n, for the exact solution
    ``field`` (``exact``, or ``linear`` with f = 0: the patch test), its values on the outer
    boundary; the rows of the slave nodes on it shared among their neighbours
    (``crosspoints="redistribute"``) or dropped (``"drop"``). Returns the mesh size of the
    left body, the L2 error over both bodies, the largest nodal error, and the coupling."""
    left, lb, lcut, ldir = body(0.0, CUT, n)
    right, rb, rcut, rdir = body(CUT, 1.0, (3 * n) // 2)
    # The cut's edges as (points, cells, cell_type): the meshes' own points (n, 2), so that
    # slave_nodes and master_nodes are node numbers of the meshes.
    c = mortar.couple(
        (right.p.T, right.facets[:, rcut].T, "line"),
        (left.p.T, left.facets[:, lcut].T, "line"),
        multipliers=multipliers,
    )
    nl, nr = lb.N, rb.N
    f_of = source if field is exact else (lambda x, y: 0.0 * x)
    K = sp.block_diag([laplace.assemble(lb), laplace.assemble(rb)], format="csr")
    f = np.concatenate(
        [
            load.assemble(lb, f=f_of(*lb.global_coordinates().value)),
            load.assemble(rb, f=f_of(*rb.global_coordinates().value)),
        ]
    )
    # The constraint rows: the slave nodes on the Dirichlet boundary (rdir) keep no row of
    # their own; their rows are shared among their neighbours, or dropped.
    if crosspoints == "redistribute":
        tied = mortar.redistribute_slave_dirichlet(c, rdir)
        D, M = tied.D, tied.M
    elif crosspoints == "drop":
        rows = np.flatnonzero(~np.isin(c.slave_nodes, rdir))
        D, M = c.D[rows], c.M[rows]
    else:
        raise ValueError(f"crosspoints={crosspoints!r}: give 'redistribute' or 'drop'")

    # B = [-M D] on all unknowns (slave_nodes, master_nodes are the meshes' node numbers).
    def columns(nodes, n):  # the (len(nodes), n) matrix picking those nodes
        return sp.csr_array((np.ones(len(nodes)), (np.arange(len(nodes)), nodes)), shape=(len(nodes), n))

    B = sp.hstack([-M @ columns(c.master_nodes, nl), D @ columns(c.slave_nodes, nr)], format="csr")
    points = np.hstack([left.p, right.p])
    u_exact = field(points[0], points[1])
    fixed = np.concatenate([ldir, nl + rdir])
    free = np.setdiff1d(np.arange(nl + nr), fixed)
    g = u_exact[fixed]
    Kf = K[free][:, free]
    Bf = B[:, free]
    A = sp.block_array([[Kf, Bf.T], [Bf, None]], format="csc")
    rhs = np.concatenate([f[free] - K[free][:, fixed] @ g, -B[:, fixed] @ g])
    sol = spsolve(A, rhs)
    u = np.zeros(nl + nr)
    u[fixed] = g
    u[free] = sol[: len(free)]
    err2 = l2_error_squared.assemble(
        lb, uh=lb.interpolate(u[:nl]), ue=field(*lb.global_coordinates().value)
    ) + l2_error_squared.assemble(rb, uh=rb.interpolate(u[nl:]), ue=field(*rb.global_coordinates().value))
    return CUT / n, float(np.sqrt(err2)), float(np.abs(u - u_exact).max()), c


def patch_test(n: int = 4, multipliers: str = "standard", crosspoints: str = "redistribute"):
    """The largest nodal error for u = 1 + 2x + 3y (f = 0): round-off when the tie passes
    the linear patch test."""
    return solve(n, multipliers, crosspoints, field=linear)[2]


def study(levels=(4, 8, 16, 32), multipliers="standard"):
    """The L2 errors over the refinements and the rates between successive ones."""
    hs, errors = [], []
    for n in levels:
        h, e, _, _ = solve(n, multipliers)
        hs.append(h)
        errors.append(e)
    rates = [np.log(errors[i - 1] / errors[i]) / np.log(hs[i - 1] / hs[i]) for i in range(1, len(hs))]
    return hs, errors, rates


def main(argv):
    levels = tuple(int(a) for a in argv[1:]) or (4, 8, 16, 32)
    for multipliers in ("standard", "dual"):
        hs, errors, rates = study(levels, multipliers)
        print(f"{multipliers} multipliers")
        print(f"{'h':>10} {'L2 error':>12} {'rate':>6}")
        for i, (h, e) in enumerate(zip(hs, errors)):
            rate = f"{rates[i - 1]:6.3f}" if i else ""
            print(f"{h:10.5f} {e:12.4e} {rate:>6}")
        for crosspoints in ("redistribute", "drop"):
            print(f"patch test, crosspoint rows {crosspoints}: {patch_test(4, multipliers, crosspoints):.2e}")


if __name__ == "__main__":
    main(sys.argv)
