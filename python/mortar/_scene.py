"""run_scene(): a scene file (or dict) through the library's scene runners."""

from __future__ import annotations

import json
import os
import warnings
from typing import Any, Dict, Optional, Union

from . import _mortar

__all__ = ["run_scene"]

#: What messages and the report call a scene given as a dict.
DICT_NAME = "run_scene(dict)"


def run_scene(
    scene: Union[str, "os.PathLike[str]", Dict[str, Any]],
    out: Union[str, "os.PathLike[str]", None] = None,
) -> Dict[str, Any]:
    """Run a scene, as ``mortar run SCENE.toml --out DIR`` does, and return its report.

    Args:
        scene: the path of a scene file (TOML; ``kind = "tied_heat"``, ``"contact"`` or
            ``"pellet"``, keys as in docs/scenes.md), or the same scene as a dict (mesh paths
            in it relative to the current folder).
        out: a folder to write the scene's outputs into (VTU files, ``report.json``); None
            keeps none.

    Returns:
        The report (``report.json``) as a dict: SI units (m, K, W, Pa, s), as documented
        for the scene's kind in ``docs/models.md``.

    Raises:
        SceneError: an unknown kind or key, a value out of range, a missing mesh or group
            (the message names the key and the file; a scene given as a dict is named
            ``run_scene(dict)``).
        InvalidInputError: a dict that cannot be written as TOML (a None value, say).
        MortarError: any other failure of the run.

    Coupling warnings of the run (uncovered slave area, overlapping master faces, skipped
    pairs) are issued with ``warnings.warn``. The GIL is released while the scene runs.
    """
    out_s = None if out is None else os.fspath(out)
    if isinstance(scene, dict):
        text = json.dumps(scene)
        # Messages and the report name the dict, not a file; mesh paths are relative to the
        # current folder.
        report, warns = _mortar.run_scene_text(
            text, DICT_NAME, out_s, json=True, base=os.getcwd()
        )
    else:
        path = os.fspath(scene)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        report, warns = _mortar.run_scene_text(text, os.path.abspath(path), out_s)
    for w in warns:
        warnings.warn(f"mortar: {w}", RuntimeWarning, stacklevel=2)
    return json.loads(report)
