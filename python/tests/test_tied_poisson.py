"""The scikit-fem client: Poisson on two non-matching meshes tied by mortar converges at the
L2 rate of P1 elements (2), with standard and dual multipliers (examples/tied_poisson.py)."""

import importlib.util
import pathlib

import numpy as np
import pytest

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "tied_poisson.py"


def load_example():
    spec = importlib.util.spec_from_file_location("tied_poisson", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("multipliers", ["standard", "dual"])
def test_l2_rate(multipliers):
    example = load_example()
    hs, errors, rates = example.study((4, 8, 16), multipliers)
    # Measured rate over the last two refinements, not error values.
    assert rates[-1] >= 1.9, (errors, rates)
    assert all(np.diff(errors) < 0)


def test_coupling_of_the_cut():
    # The cut x = 1/2 as the meshes' facets (unordered, as scikit-fem numbers them): the
    # coupling's length is the cut's, and a linear field is tied exactly.
    example = load_example()
    left, _, lcut, _ = example.body(0.0, 0.5, 8)
    right, _, rcut, _ = example.body(0.5, 1.0, 12)
    import mortar

    c = mortar.couple(
        (right.p.T, right.facets[:, rcut].T, "line"), (left.p.T, left.facets[:, lcut].T, "line")
    )
    assert c.stats["area"] == pytest.approx(1.0, rel=1e-13)
    y_s, y_m = right.p[1, c.slave_nodes], left.p[1, c.master_nodes]
    assert np.abs(c.D @ y_s - c.M @ y_m).max() < 1e-15


@pytest.mark.parametrize("multipliers", ["standard", "dual"])
def test_linear_patch_test_with_the_crosspoints_redistributed(multipliers):
    # u = 1 + 2x + 3y (f = 0) is in the P1 spaces of both bodies: a tie that passes the
    # patch test reproduces it to round-off. With the rows of the Dirichlet slave nodes
    # shared among their neighbours (mortar.redistribute_slave_dirichlet, the library's
    # SlaveDirichlet::Redistribute) it does. With them dropped, standard multipliers near the
    # crosspoints no longer hold the constant flux and it does not (8.4e-4 at n = 4; dual
    # multipliers happen to pass either way here, 1e-14).
    example = load_example()
    assert example.patch_test(4, multipliers, "redistribute") < 1e-12
    if multipliers == "standard":
        assert example.patch_test(4, multipliers, "drop") > 1e-4


@pytest.mark.parametrize("multipliers", ["standard", "dual"])
def test_redistribute_slave_dirichlet_rows(multipliers):
    # The cut x = 1/2 of the right body (slave, 13 nodes) with its two end nodes on the
    # Dirichlet boundary: their rows go to their neighbours, the other 11 stay; the rows
    # still sum to the master's (constants tied), and a dual D stays diagonal on the free
    # slave nodes.
    import mortar

    example = load_example()
    left, _, lcut, _ = example.body(0.0, 0.5, 4)
    right, _, rcut, rdir = example.body(0.5, 1.0, 6)
    c = mortar.couple(
        (right.p.T, right.facets[:, rcut].T, "line"),
        (left.p.T, left.facets[:, lcut].T, "line"),
        multipliers=multipliers,
    )
    ends = c.slave_nodes[np.isin(c.slave_nodes, rdir)]
    assert len(c.slave_nodes) == 13 and len(ends) == 2
    r = mortar.redistribute_slave_dirichlet(c, rdir)
    assert (r.redistributed, r.dropped) == (2, 0)
    assert np.array_equal(r.rows, np.flatnonzero(~np.isin(c.slave_nodes, rdir)))
    assert r.D.shape == (11, 13) and r.M.shape == (11, len(c.master_nodes))
    assert np.abs(r.D.sum(axis=1) - r.M.sum(axis=1)).max() < 1e-15
    assert r.S.sum() == pytest.approx(13.0, rel=1e-15)
    free = r.D[:, r.rows].toarray()
    if multipliers == "dual":
        assert np.count_nonzero(free - np.diag(np.diag(free))) == 0
    # Nothing to share: the rows as they are.
    same = mortar.redistribute_slave_dirichlet(c, [])
    assert (same.redistributed, same.dropped) == (0, 0)
    assert abs(same.D - c.D).max() == 0.0
    with pytest.raises(mortar.InvalidInputError, match="dirichlet"):
        mortar.redistribute_slave_dirichlet(c, [0.5])
