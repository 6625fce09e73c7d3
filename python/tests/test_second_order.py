"""Second-order faces from Python: the Gmsh-made meshes of tests/meshes (Mesh.ElementOrder =
2, made by tests/meshes/make_second_order_meshes.py) read with read_gmsh and coupled, and
meshio's names for them; the closed forms of a flat unit interface (sum(D) = 1, D 1 = M 1,
D x_s = M x_m), and dual multipliers on Tri6 and Quad8 faces in the recombined basis."""

import pathlib

import numpy as np
import pytest

import mortar

MESHES = pathlib.Path(__file__).resolve().parents[2] / "tests" / "meshes"


@pytest.mark.parametrize(
    "file, slave, master, types",
    [
        ("so_2d_quad8.msh", "right_x0", "left_x1", ("line3", "line3")),
        ("so_3d_hex20.msh", "top_bottom", "bottom_top", ("triangle6", "quad8")),
        ("so_3d_hex27.msh", "top_bottom", "bottom_top", ("quad9", "triangle6")),
    ],
)
@pytest.mark.parametrize("multipliers", ["standard", "dual", "linear"])
def test_second_order_interfaces_tie_linear_fields(file, slave, master, types, multipliers):
    s = mortar.read_gmsh(MESHES / file, slave)
    m = mortar.read_gmsh(MESHES / file, master)
    assert (s.cell_type, m.cell_type) == types
    c = mortar.couple(s, m, multipliers=multipliers)
    assert c.stats["area"] == pytest.approx(1.0, rel=1e-12)
    xs, xm = s.points[c.slave_nodes], m.points[c.master_nodes]
    pairs = [(np.ones(len(xs)), np.ones(len(xm)))]
    pairs += [(xs[:, d], xm[:, d]) for d in range(xs.shape[1])]
    for fs, fm in pairs:
        assert np.abs(c.D_nodal @ fs - c.M @ fm).max() < 1e-12
    recombined = multipliers == "dual" and s.cell_type in ("triangle6", "quad8")
    assert (c.T is not None) == recombined
    assert c.slave_basis == ("recombined" if recombined else "nodal")
    if recombined:
        # D as mortar couple writes it, D_nodal T^T (Popp, Gee and Wall 2012): diagonal, and
        # the slave values condense, u_s = T^T D^-1 M u_m, for constants and linear fields.
        assert c.D.nnz == len(c.slave_nodes)
        assert np.array_equal(c.D.indices, np.arange(len(c.slave_nodes)))
        assert abs(c.D - c.D_nodal @ c.T.T).max() < 1e-13
        for fs, fm in pairs:
            assert np.abs(c.T.T @ ((c.M @ fm) / c.D.diagonal()) - fs).max() < 1e-12
    elif multipliers == "dual":
        assert c.D_nodal is c.D
        assert c.D.nnz == len(c.slave_nodes)
    assert c.stats["d_off_diagonal"] == 0
    if multipliers == "linear":
        # Rows for the corner nodes only (the first columns of the cells).
        corners = {"line3": 2, "triangle6": 3, "quad8": 4, "quad9": 4}[s.cell_type]
        expected = np.isin(c.slave_nodes, np.unique(s.cells[:, :corners]))
        assert 0 < expected.sum() < len(expected)
        assert np.array_equal(np.diff(c.D.indptr) > 0, expected)
        assert np.array_equal(np.diff(c.M.indptr) > 0, expected)
        assert np.array_equal(c.multiplier_rows, np.flatnonzero(expected))
    else:
        assert np.array_equal(c.multiplier_rows, np.arange(len(c.slave_nodes)))


def test_second_order_cell_types_by_both_names():
    # One straight Line3 against two: meshio's and the library's names give the same D and M.
    pts = np.array([[0.0, 0.0], [1.0, 0.0], [0.5, 0.0]])
    mpts = np.array([[1.0, 0.0], [0.0, 0.0], [0.5, 0.0], [0.25, 0.0], [0.75, 0.0]])
    mcells = np.array([[2, 1, 3], [0, 2, 4]])  # running the other way: facing the slave
    a = mortar.couple((pts, np.array([[0, 1, 2]]), "line3"), (mpts, mcells, "line3"))
    b = mortar.couple((pts, np.array([[0, 1, 2]]), "Line3"), (mpts, mcells, "Line3"))
    assert (a.D != b.D).nnz == 0 and (a.M != b.M).nnz == 0
    assert a.stats["area"] == pytest.approx(1.0, rel=1e-14)
    with pytest.raises(mortar.InvalidInputError, match="triangle6"):
        mortar.couple((pts, np.array([[0, 1, 2]]), "line4"), (mpts, mcells, "line3"))
