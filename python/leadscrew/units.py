"""Values with units in scenes: ``"1 mm"``, ``"210 GPa"``, ``"-40 N*mm"``, ``"2 Hz"``.

A scene field holds a plain number in its SI unit or a string with a unit,
which :func:`to_si` converts with `pint <https://pint.readthedocs.io>`_ to
that unit; a string of another dimension is rejected with the field's key path.

Angles and frequencies:

- Radians are dimensionless: an angle field (``rad``) takes ``"30 deg"``,
  ``"0.5 rad"`` or a plain number (radians); ``"1 turn"`` is 2 pi rad.
- ``Hz`` means cycles per second (1 Hz = 1 turn/s = 2 pi rad/s): an angular
  velocity or angular frequency field (``rad/s``, e.g. a sine's ``omega``)
  given ``"2 Hz"`` takes 2 * 2 pi = 12.566 rad/s, as ``"120 rpm"`` does;
  ``"2 rad/s"`` and ``"2 1/s"`` stay 2 rad/s. (Plain pint would read ``"2 Hz"``
  as 2 rad/s; this module's registry redefines ``hertz`` as ``turn / second``.)
- A dimensionless field (a friction coefficient, a ratio) takes plain numbers,
  numeric strings (``"0.3"``) and ``"30 %"``, but not angles.

The registry is built on first use (about 0.5 s), so scenes of plain numbers
never pay for it.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

__all__ = ["to_si", "parse_unit", "dimension_name"]

# Dimension names for the messages, by a reference unit of each dimension.
_DIMENSION_NAMES = (
    ("m", "a length"),
    ("kg", "a mass"),
    ("s", "a time"),
    ("m/s", "a velocity"),
    ("rad/s", "an angular velocity or frequency"),
    ("N", "a force"),
    ("Pa", "a pressure (stress, Young's modulus)"),
    ("N*m", "a torque"),
    ("N*m/rad", "a torsional stiffness"),
    ("kg*m^2", "a moment of inertia"),
    ("kg/m^3", "a density"),
    ("N/m", "a stiffness"),
    ("N*s/m", "a damping coefficient"),
    ("N*m*s/rad", "a torsional damping coefficient"),
    ("s/m", "an inverse velocity"),
    ("s^2/m", "an inverse acceleration"),
)


@lru_cache(maxsize=1)
def _registry():
    import pint

    registry = pint.UnitRegistry(on_redefinition="ignore")
    # Hz is a cycle per second here, so "2 Hz" in a rad/s field is 4 pi rad/s.
    registry.define("hertz = turn / second = Hz")
    return registry


@lru_cache(maxsize=None)
def parse_unit(unit: str):
    """The pint unit of a unit string such as ``"N*m/rad"`` ("" is dimensionless).

    Raises:
        ValueError: the string is not a unit pint knows.
    """
    try:
        return _registry().Unit(unit)
    except Exception as error:  # pint raises several unrelated types
        raise ValueError(f"unit {unit!r} does not parse: {error}") from None


def _radian_exponent(unit: str) -> float:
    root = _registry().Quantity(1.0, parse_unit(unit)).to_root_units().units
    return dict(root._units).get("radian", 0)


def _is_angle(unit: str) -> bool:
    return _radian_exponent(unit) != 0


def _signature(unit: str):
    """Dimensionality and power of radians: tells a torsional stiffness (N*m/rad)
    from a torque (N*m) for messages, though pint treats radians as 1."""
    return parse_unit(unit).dimensionality, _radian_exponent(unit)


def dimension_name(unit: str) -> str:
    """What a unit measures, for messages: ``"m"`` -> ``"a length"``."""
    if parse_unit(unit).dimensionless:
        return "an angle" if _is_angle(unit) else "a plain number"
    for reference, name in _DIMENSION_NAMES:
        if _signature(reference) == _signature(unit):
            return name
    return f"a quantity in {unit}"


def _quoted(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def to_si(path: str, value: Any, unit: str) -> Any:
    """Convert a string with a unit to a number in ``unit``; other values pass.

    Args:
        path: the key path for messages, e.g. ``"thread.pitch"``.
        value: a string such as ``"1 mm"`` (anything else is returned unchanged).
        unit: the field's SI unit, e.g. ``"m"``, ``"N*m/rad"``, ``""``.

    Returns:
        The value in ``unit`` (float), or ``value`` itself if it is not a string.

    Raises:
        ValueError: the string does not parse, or its dimension is not that of
            ``unit``, e.g. ``thread.pitch = "3 N" is invalid: "3 N" is not a
            length (m)``.
    """
    if not isinstance(value, str):
        return value
    prefix = f"{path} = {_quoted(value)} is invalid: "
    registry = _registry()
    try:
        quantity = registry.Quantity(value.strip())
    except Exception as error:  # pint raises several unrelated types
        raise ValueError(f"{prefix}not a number with a unit such as \"1 mm\" ({error})") from None
    if not isinstance(quantity, registry.Quantity):
        raise ValueError(f"{prefix}not a number with a unit such as \"1 mm\"")
    expected = f"{dimension_name(unit)} ({unit})" if unit else dimension_name(unit)
    if not unit and not quantity.unitless and _is_angle(str(quantity.units)):
        raise ValueError(f"{prefix}{_quoted(value)} is an angle, not {expected}")
    try:
        magnitude = quantity.to(parse_unit(unit)).magnitude
    except Exception:
        raise ValueError(f"{prefix}{_quoted(value)} is not {expected}") from None
    try:
        number = float(magnitude)
    except (TypeError, ValueError):
        raise ValueError(f"{prefix}not a single number") from None
    if not math.isfinite(number):
        raise ValueError(f"{prefix}not finite")
    return number
