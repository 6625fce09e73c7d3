"""Exceptions of mortar: every error the library reports is a :class:`MortarError`.

The message is the library's own: it names what went wrong and where (the side, the face
by its 0-based row in ``cells``, the node by its 0-based row in ``points``, the file and
line). Catch a child to act on a kind of failure, or :class:`MortarError` for all.
"""

__all__ = [
    "MortarError",
    "InvalidInputError",
    "GeometryError",
    "NoOverlapError",
    "CoverageError",
    "MeshFileError",
    "SceneError",
    "LawError",
]


class MortarError(Exception):
    """Base class of every error mortar raises; its message is the library's, naming what
    went wrong and where."""


class InvalidInputError(MortarError, ValueError):
    """Input refused before any geometry: wrong shapes or dtypes, indices out of range,
    NaN or infinite coordinates, coordinates out of the supported range, an unknown cell
    type or option, an empty surface, lines mixed with faces."""


class GeometryError(MortarError):
    """A face that cannot be used: degenerate (zero length or area, a repeated node),
    inverted or folded, surfaces that are not manifolds, or a point that cannot be projected
    onto a face."""


class NoOverlapError(MortarError):
    """No slave face overlaps a master face (the message says how many candidate pairs the
    search found and whether the master faced the wrong way)."""


class CoverageError(MortarError):
    """Part of the slave surface is not covered by the master, or pairs were skipped, and
    ``require_full_coverage=True`` was asked."""


class MeshFileError(MortarError, OSError):
    """A mesh file that cannot be read, is malformed, or has not the group asked for."""


class SceneError(MortarError):
    """A scene that cannot be run: a bad key or value, a missing mesh or group."""


class LawError(MortarError):
    """A constraint law that cannot be made (unknown name, missing or refused parameter) or
    is not finite at the point asked."""
