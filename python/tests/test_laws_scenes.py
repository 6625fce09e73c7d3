"""The constraint laws pointwise, and scenes run through the library's scene runner."""

import json
import math
import pathlib

import numpy as np
import pytest

import mortar
from mortar import laws

SCENES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "scenes"


def test_law_names():
    assert set(laws.names()) >= {
        "tying",
        "gap_conductance",
        "mechanical_gap_conductance",
        "exponential_pressure",
        "exponential_contact",
        "contact_complementarity",
    }


@pytest.mark.parametrize("lam, g", [(2.0, 1e-3), (2.0, -1e-3), (0.5, 1e-3)])
def test_complementarity_closed_form(lam, g):
    # C = lambda - max(0, lambda - c g).
    c = 1e3
    value, t = laws.evaluate("contact_complementarity", {"c": c}, gap=g, multiplier=lam)
    active = lam - c * g > 0
    assert value == pytest.approx(lam - max(0.0, lam - c * g), rel=1e-15)
    assert t["d_gap"] == pytest.approx(c if active else 0.0)
    assert t["d_multiplier"] == pytest.approx(0.0 if active else 1.0)
    assert set(t) == {
        "d_gap",
        "d_multiplier",
        "d_temperature",
        "d_normal_gap",
        "d_contact_pressure",
        "d_gas_pressure",
    }


def test_exponential_pressure_closed_form_and_tangent():
    # P_c = P_o exp(S (xi - g)^2) for g < xi; the residual is lambda - P_c.
    p = {"base_pressure": 2e6, "stiffness": 1e11, "onset": 5e-6}
    g, lam = 2e-6, 1e6
    value, t = laws.evaluate("exponential_pressure", p, gap=g, multiplier=lam)
    pc = 2e6 * math.exp(1e11 * (5e-6 - g) ** 2)
    assert abs(value) == pytest.approx(abs(lam - pc), rel=1e-12)
    for name, params, point in [
        ("exponential_pressure", p, dict(gap=g, multiplier=lam)),
        ("exponential_contact", {"stiffness": 1e12, "onset": 5e-6},
         dict(gap=3e-6, multiplier=1e7, temperature=900.0, normal_gap=3e-6,
              contact_pressure=1e7, gas_pressure=5e6)),
        ("gap_conductance", {"gap_width": 2e-5, "roughness_fuel": 1e-6,
                             "roughness_cladding": 1e-6, "jump_distance": 1e-6},
         dict(gap=50.0, multiplier=1e5, temperature=800.0)),
    ]:
        assert laws.check_tangent(name, params, **point) < 1e-6


def test_law_errors():
    with pytest.raises(mortar.LawError, match="no law named"):
        laws.evaluate("friction", {}, gap=0.0, multiplier=0.0)
    with pytest.raises(mortar.LawError, match='"c" is missing'):
        laws.evaluate("contact_complementarity", {}, gap=0.0, multiplier=0.0)
    with pytest.raises(mortar.InvalidInputError, match="NaN gap"):
        laws.evaluate("tying", {}, gap=float("nan"), multiplier=0.0)


def test_run_scene_file_and_dict(tmp_path):
    r = mortar.run_scene(SCENES / "tied_square.toml", out=tmp_path / "out")
    # The exact temperature is piecewise linear: 0 at x = 0, 2/3 at the cut, 1 at x = 1.
    bodies = {b["name"]: b for b in r["bodies"]}
    assert bodies["right"]["temperature_max"] == pytest.approx(1.0, abs=1e-12)
    assert bodies["left"]["temperature_max"] == pytest.approx(2 / 3, abs=1e-12)
    assert json.loads((tmp_path / "out" / "report.json").read_text()) == r
    # The same scene as a dict (mesh paths absolute), outputs not kept; standard
    # multipliers this time: the saddle point, the same temperatures.
    scene = {
        "kind": "tied_heat",
        "dimension": 2,
        "bodies": {
            "left": {
                "mesh": str(SCENES / "tied_square_left.msh"),
                "group": "left",
                "conductivity": 1.0,
                "dirichlet": [{"group": "left_end", "value": 0.0}],
            },
            "right": {
                "mesh": str(SCENES / "tied_square_right.msh"),
                "group": "right",
                "conductivity": 2.0,
                "neumann": [{"group": "right_end", "flux": 4.0 / 3.0}],
            },
        },
        "interface": {
            "slave": {"body": "right", "group": "right_cut"},
            "master": {"body": "left", "group": "left_cut"},
            "multipliers": "standard",
        },
        "solve": {"mode": "steady", "formulation": "auto"},
    }
    r2 = mortar.run_scene(scene)
    bodies = {b["name"]: b for b in r2["bodies"]}
    assert bodies["right"]["temperature_min"] == pytest.approx(2 / 3, abs=1e-12)
    assert r2["formulation"]["name"] != r["formulation"]["name"]


def test_run_scene_errors(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('kind = "tied_heat"\nunknown_key = 1\n')
    with pytest.raises(mortar.SceneError):
        mortar.run_scene(bad)
    with pytest.raises(mortar.SceneError, match="unknown scene kind"):
        mortar.run_scene({"kind": "plasma"})
    # A scene given as a dict is named as one, not as a file beside the current folder.
    with pytest.raises(mortar.SceneError, match=r"^run_scene\(dict\)[:,] ") as e:
        mortar.run_scene({"kind": "tied_heat", "bodies": {}, "unknown_key": 1})
    assert "scene.toml" not in str(e.value)
    with pytest.raises(mortar.SceneError, match=r"run_scene\(dict\)") as e:
        mortar.run_scene({"kind": "plasma"})
    assert "scene.toml" not in str(e.value)
