"""The shipped constraint laws, evaluated pointwise: ``C(g, lambda; T) = 0``.

Conventions (as the library's ``mortar::physics::laws``): for thermal laws ``gap`` is the
temperature jump ``T_s - T_m`` (K) and ``multiplier`` the heat flux leaving the slave body
(W/m^2); for mechanical laws ``gap`` is the normal gap (m, positive open) and
``multiplier`` the contact pressure (Pa, positive in compression). ``temperature`` is the
interface temperature (K); ``normal_gap`` (m), ``contact_pressure`` and ``gas_pressure``
(Pa) are what a thermomechanical law also sees at the point (zero where unused).

The tangent comes from forward automatic differentiation in the library (dual numbers), not
from finite differences; :func:`check_tangent` compares the two.

Example::

    >>> from mortar import laws
    >>> value, tangent = laws.evaluate("contact_complementarity", {"c": 1e3},
    ...                                gap=-1e-3, multiplier=0.0)
    >>> value, tangent["d_gap"]
    (-1.0, 1000.0)
"""

from __future__ import annotations

from typing import Dict, List, Mapping, Tuple

from . import _mortar

__all__ = ["names", "evaluate", "check_tangent"]


def names() -> List[str]:
    """The names of the shipped laws, sorted: ``contact_complementarity`` (parameter
    ``c``, Pa/m), ``exponential_contact`` (``stiffness`` 1/m^2, ``onset`` m),
    ``exponential_pressure`` (``base_pressure`` Pa, ``stiffness``, ``onset``),
    ``gap_conductance`` (``gap_width``, ``roughness_fuel``, ``roughness_cladding``,
    ``jump_distance`` m, optional ``gas_conductivity`` W/m/K, helium otherwise),
    ``mechanical_gap_conductance`` (the same less ``gap_width``, plus
    ``contact_conductance``), ``tying`` (none)."""
    return list(_mortar.law_names())


def evaluate(
    name: str,
    params: Mapping[str, float],
    *,
    gap: float,
    multiplier: float,
    temperature: float = 0.0,
    normal_gap: float = 0.0,
    contact_pressure: float = 0.0,
    gas_pressure: float = 0.0,
) -> Tuple[float, Dict[str, float]]:
    """The value and tangent of the law ``name`` at one point.

    Args:
        name: a law of :func:`names`.
        params: its parameters (SI units, see :func:`names`).
        gap, multiplier, temperature, normal_gap, contact_pressure, gas_pressure: the point
            (see the module's conventions).

    Returns:
        ``(value, tangent)``: ``C`` and a dict of its partial derivatives ``d_gap``,
        ``d_multiplier``, ``d_temperature``, ``d_normal_gap``, ``d_contact_pressure``,
        ``d_gas_pressure``.

    Raises:
        LawError: an unknown law, a missing or refused parameter, a value or derivative that
            is not finite at the point.
        InvalidInputError: a NaN argument.
    """
    t = _mortar.evaluate_law(
        name,
        {str(k): float(v) for k, v in params.items()},
        float(gap),
        float(multiplier),
        float(temperature),
        float(normal_gap),
        float(contact_pressure),
        float(gas_pressure),
    )
    value = t.pop("value")
    return value, t


def check_tangent(
    name: str,
    params: Mapping[str, float],
    *,
    gap: float,
    multiplier: float,
    temperature: float = 0.0,
    normal_gap: float = 0.0,
    contact_pressure: float = 0.0,
    gas_pressure: float = 0.0,
) -> float:
    """The largest relative difference between the law's tangent (dual numbers) and central
    finite differences of its value (step ``1e-6 |x|``, ``1e-9`` at zero), over the six
    arguments. About 1e-6 or less where the law is differentiable; arguments as
    :func:`evaluate`; raises as :func:`evaluate`."""
    c = _mortar.check_law_tangent(
        name,
        {str(k): float(v) for k, v in params.items()},
        float(gap),
        float(multiplier),
        float(temperature),
        float(normal_gap),
        float(contact_pressure),
        float(gas_pressure),
    )
    return float(c["max_relative_error"])
