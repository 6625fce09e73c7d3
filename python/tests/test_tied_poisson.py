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
