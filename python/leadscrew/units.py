"""Values with units in scenes: ``"1 mm"``, ``"210 GPa"``, ``"-40 N*mm"``, ``"2 Hz"``.

A scene field holds a plain number in its SI unit or a string with a unit,
which :func:`to_si` converts with `pint <https://pint.readthedocs.io>`_ to
that unit; a string of another dimension is rejected with the field's key path.

A string is exactly one number (``"1.5"``, ``"-2e-3"``, ``".5"``) followed by
an optional unit expression (``"mm"``, ``"N*m/deg"``, ``"N/m^1.5"``, ``"1/s"``).
Numbers inside the unit other than exponents and a leading ``1/`` are
rejected (``"1 mm 2"``, ``"2 3"``: pint would multiply them), and so is a
decimal comma (``"1,5 mm"``: pint would read 15 mm).

Angles and frequencies:

- Radians are dimensionless to pint, but not here: the power of the angle in
  the given unit must be that of the field's unit. A torque field (``N*m``)
  rejects ``"5 N*m/deg"``, a torsional stiffness (``N*m/rad``) rejects
  ``"100 N*m"`` and takes ``"11.3 N*m/deg"``, a time field rejects ``"0.5 1/Hz"``.
- An angle field (``rad``) takes ``"30 deg"``, ``"0.5 rad"``, ``"1 turn"`` (2 pi
  rad) or a plain number (radians, also as a string such as ``"0.5"``), but not
  ``"30 %"``.
- ``Hz`` means cycles per second (1 Hz = 1 turn/s = 2 pi rad/s): an angular
  velocity or angular frequency field (``rad/s``, e.g. a sine's ``omega``)
  given ``"2 Hz"`` takes 2 * 2 pi = 12.566 rad/s, as ``"120 rpm"`` does;
  ``"2 rad/s"`` and ``"2 1/s"`` stay 2 rad/s (``1/s`` is the one unit without
  an angle such a field takes; ``"3000 1/min"`` is rejected, as it often
  means rpm: write ``"3000 rpm"`` or ``"3000 rad/min"``). (Plain pint would
  read ``"2 Hz"`` as 2 rad/s; this module's registry redefines ``hertz`` as
  ``turn / second``.)
- A dimensionless field (a friction coefficient, a ratio) takes plain numbers,
  numeric strings (``"0.3"``) and ``"30 %"``, but not angles.

Units as people type them: ``"2 Ohm"`` is an ohm (an alias; pint knows
``"ohm"`` and ``"Ω"``). Pint reads ``"Nm"`` as a "number meter", not a newton
metre: where a torque is expected the message says to write ``"N*m"``. A unit
pint does not know whose other case it knows (``"12 v"``, ``"3 mv"``) is
refused with that unit in the message (units are case-sensitive).

The registry is built on first use (about 0.5 s), so scenes of plain numbers
never pay for it.

:func:`channel_unit` gives the SI unit of a result channel from its name (the
core's, as the drive's elements declare each channel with its unit; this
module's for the time and the friction block's own channels:
:meth:`leadscrew.Result.to_frame`, the command line's CSV and Parquet files
use it).
"""

from __future__ import annotations

import math
import numbers
import re
from functools import lru_cache
from typing import Any, Optional, Sequence, Tuple

__all__ = ["to_si", "parse_unit", "dimension_name", "quantity", "load_quantity",
           "channel_unit"]

# Dimension names for the messages, by a reference unit of each dimension.
_DIMENSION_NAMES = (
    ("m", "a length"),
    ("kg", "a mass"),
    ("s", "a time"),
    ("m/s", "a velocity"),
    ("m/s^2", "an acceleration"),
    ("rad/s^2", "an angular acceleration"),
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
    ("1/m", "an inverse length (a stiffness per unit force)"),
    ("V", "a voltage"),
    ("A", "a current"),
    ("ohm", "a resistance"),
    ("H", "an inductance"),
    ("N*m/A", "a torque constant"),
    ("V*s/rad", "a back-EMF constant"),
)


@lru_cache(maxsize=1)
def _registry():
    import pint

    registry = pint.UnitRegistry(on_redefinition="ignore")
    # Hz is a cycle per second here, so "2 Hz" in a rad/s field is 4 pi rad/s.
    registry.define("hertz = turn / second = Hz")
    # "2 Ohm" as written in data sheets (pint knows only "ohm" and "Ω").
    registry.define("@alias ohm = Ohm")
    # pint caches the root units of its definitions when it builds the
    # registry: without a rebuild "Hz" would keep 1/s as its root units and
    # lose the angle that the checks below compare.
    registry._build_cache()
    hertz = registry.Quantity(1.0, "Hz").to_root_units()
    if dict(hertz.units._units).get("radian", 0) != 1:  # pragma: no cover - a pint change
        raise RuntimeError("leadscrew.units: pint did not take Hz = turn / second")
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
        raise ValueError(f"unit {unit!r} does not parse: {error}{_case_hint(error)}") from None


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


# One number, then an optional unit expression (parsed by pint on its own).
_NUMBER = re.compile(r"\s*([+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf(?:inity)?|nan))"
                     r"\s*(.*?)\s*$", re.IGNORECASE | re.DOTALL)
# Numbers a unit expression may hold: exponents ("m^2", "m**-1", "m^(1.5)")
# and the 1 of "1/s".
_EXPONENT = re.compile(r"(?:\^|\*\*)\s*\(?\s*[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\s*\)?")
_ONE_OVER = re.compile(r"(?<![\w.])1\s*/")
_STRAY_NUMBER = re.compile(r"(?<![\w.])(?:\d+\.?\d*|\.\d+)")


def _split_number(prefix: str, value: str):
    """Split ``value`` into its one number and its unit text.

    Args:
        prefix: the start of messages (key path and value).
        value: the string, e.g. ``"1.5 mm"``.

    Returns:
        ``(number, unit)``: a float and the unit text (``""``: no unit).

    Raises:
        ValueError: a comma, no leading number, or a further number in the unit.
    """
    example = 'such as "1.5 mm"'
    if "," in value:
        raise ValueError(f'{prefix}a comma is not a decimal point here: use a decimal point '
                         f'and no thousands separators ({example})')
    match = _NUMBER.fullmatch(value)
    if match is None:
        raise ValueError(f"{prefix}not one number followed by a unit {example}")
    number, unit = match.group(1), match.group(2)
    if unit:
        stray = _STRAY_NUMBER.search(_ONE_OVER.sub("/", _EXPONENT.sub("", unit)))
        if stray is not None:
            raise ValueError(f"{prefix}not one number followed by a unit {example}: the unit "
                             f"{_quoted(unit)} holds the further number {stray.group(0)!r}")
    return float(number), unit


# "Nm", "mNm", "kNm" meant as newton metres (pint reads a "number meter").
_NEWTON_METRE = re.compile(r"(?<![\w.])[a-zA-Zµ]?Nm(?!\w)")


def _torque_hint(given_unit: str, units: Sequence[str]) -> str:
    """A hint for a unit such as ``"Nm/A"`` given where one of ``units``
    holds a torque (``N*m``): pint does not read ``Nm`` as N*m."""
    match = _NEWTON_METRE.search(given_unit or "")
    if match is None or not any("N*m" in unit for unit in units):
        return ""
    try:
        read = f"{parse_unit(match.group(0))}"
    except ValueError:  # pragma: no cover - pint reads all of them
        read = "another unit"
    return (f' ("{match.group(0)}" is {read} to pint, not a newton metre: write '
            f'"{match.group(0)[:-2]}N*m")')


def _case_hint(error: Exception) -> str:
    """A hint for a unit pint does not know whose other case it does
    (``"12 v"``: ``"V"``); units are case-sensitive."""
    names = getattr(error, "unit_names", None) or getattr(error, "args", ())
    for name in names if isinstance(names, (tuple, list)) else (names,):
        if not isinstance(name, str):
            continue
        # "mv" is mV rather than MV: a prefix and a symbol first
        variants = (name[:-1] + name[-1:].upper(), name.lower(), name.upper(), name.capitalize())
        for other in dict.fromkeys(variants):
            if other == name:
                continue
            try:  # (not parse_unit, whose own failure comes here)
                known = _registry().Unit(other)
            except Exception:  # pint raises several unrelated types
                continue
            return f'; units are case-sensitive: write "{other}" for {known}'
    return ""


def _angle_text(exponent: float) -> str:
    return "no angle" if exponent == 0 else f"rad^{exponent:g}"


def to_si(path: str, value: Any, unit: str, name: Optional[str] = None) -> Any:
    """Convert a string with a unit to a number in ``unit``; other values pass.

    Args:
        path: the key path for messages, e.g. ``"thread.pitch"``.
        value: a string such as ``"1 mm"`` (anything else is returned unchanged).
        unit: the field's SI unit, e.g. ``"m"``, ``"N*m/rad"``, ``""``.
        name: what the field measures, for messages (e.g. ``"a 'bistop'
            contact stiffness"``); None: :func:`dimension_name` of ``unit``.

    Returns:
        The value in ``unit`` (float), or ``value`` itself if it is not a string.

    Raises:
        ValueError: the string is not one number with an optional unit (a
            decimal comma, a second number), the unit does not parse, or its
            dimension (with the power of the angle, see the module doc) is not
            that of ``unit``, e.g. ``thread.pitch = "3 N" is invalid: "3 N" is
            not a length (m)``; the number is not finite.
    """
    if not isinstance(value, str):
        return value
    prefix = f"{path} = {_quoted(value)} is invalid: "
    number, given_unit = _split_number(prefix, value)
    registry = _registry()
    try:
        quantity = registry.Quantity(number, given_unit) if given_unit else \
            registry.Quantity(number)
    except Exception as error:  # pint raises several unrelated types
        raise ValueError(f"{prefix}not a number with a unit such as \"1 mm\" ({error})"
                         f"{_case_hint(error)}") from None
    if name is None:
        name = dimension_name(unit)
    expected = name if not unit or name.startswith("a quantity in") else f"{name} ({unit})"
    given_angle = _radian_exponent(given_unit) if given_unit else 0
    if not unit and given_angle != 0:
        raise ValueError(f"{prefix}{_quoted(value)} is an angle, not {expected}")
    try:
        magnitude = quantity.to(parse_unit(unit)).magnitude
    except Exception:
        raise ValueError(f"{prefix}{_quoted(value)} is not {expected}"
                         f"{_torque_hint(given_unit, (unit,))}") from None
    field_angle = _radian_exponent(unit)
    if given_unit and given_angle != field_angle:
        _check_angle_free_rate(prefix, value, given_unit, unit, expected, given_angle,
                               field_angle)
    try:
        number = float(magnitude)
    except (TypeError, ValueError):
        raise ValueError(f"{prefix}not a single number") from None
    if not math.isfinite(number):
        raise ValueError(f"{prefix}not finite")
    return number


def _check_angle_free_rate(prefix: str, value: str, given_unit: str, unit: str, expected: str,
                           given_angle: float, field_angle: float) -> None:
    """Accept a unit whose angle power differs from the field's only as the
    documented ``1/s`` in an angular velocity field; otherwise raise."""
    registry = _registry()
    rate = _signature(unit) == _signature("rad/s")
    if rate and given_angle == 0:
        factor = registry.Quantity(1.0, given_unit).to("1/s").magnitude
        if factor == 1.0:
            return  # "2 1/s" is 2 rad/s
        raise ValueError(f"{prefix}{_quoted(value)} is not {expected}: a rate without an "
                         "angle is ambiguous except as 1/s (= rad/s); write the turns as rpm or "
                         "Hz, or the radians as rad/min, rad/s")
    if rate:
        hint = "give it in rad/s, Hz (turns per second), rpm or 1/s (= rad/s)"
    elif parse_unit(unit).dimensionless:
        hint = "give it in deg, rad or turn, or as a plain number of radians"
    else:
        hint = (f"its angle part ({_angle_text(given_angle)}) differs from that of {unit} "
                f"({_angle_text(field_angle)})")
    raise ValueError(f"{prefix}{_quoted(value)} is not {expected}: {hint}")


# --- parameters of Python objects -----------------------------------------------

# Examples of strings with a unit, for messages.
_UNIT_EXAMPLES = {"m": '"2 mm"', "N": '"-10 N"', "N*m": '"40 N*mm"', "rad/s": '"2 Hz"',
                  "rad": '"90 deg"', "s": '"250 ms"', "kg": '"2 kg"', "m/s": '"5 mm/s"',
                  "m/s^2": '"9.81 m/s^2"'}


def what_it_takes(unit: str, number: str = "a number") -> str:
    """What a numeric value in ``unit`` may be, for messages: ``a number [m] or
    a string with a unit such as "2 mm"`` (``number`` alone without a unit)."""
    if not unit:
        return number
    return (f"{number} [{unit}] or a string with a unit such as "
            f"{_UNIT_EXAMPLES.get(unit, _quoted('1 ' + unit))}")


def quantity(name: str, value: Any, unit: str) -> float:
    """A numeric parameter of a Python object (a Thread, a load, a
    FrictionBlock, a closed-form function) as a float in ``unit``.

    The range is left to the core, which checks it and names the parameter.

    Args:
        name: the parameter's name for messages, e.g. ``"pitch"``.
        value: a real number (in ``unit``) or a string with a unit, converted
            by :func:`to_si`.
        unit: the parameter's SI unit (``""``: a plain number).

    Returns:
        The value in ``unit`` (NaN and infinities pass: the core refuses them
        naming the parameter).

    Raises:
        ValueError: a string of another dimension (as :func:`to_si`), a bool,
            or a value that is no real number, e.g. ``pitch = None is invalid:
            must be a number [m] or a string with a unit such as "2 mm"``.
    """
    if value.__class__ is float:
        return value
    number = to_si(name, value, unit)
    if isinstance(number, bool) or not isinstance(number, numbers.Real):
        raise ValueError(f"{name} = {value!r} is invalid: must be {what_it_takes(unit)}")
    try:
        return float(number)
    except OverflowError:  # an int beyond a float
        raise ValueError(f"{name} = {value!r} is invalid: must be a finite number") from None


def load_quantity(name: str, value: Any, units: Sequence[str]) -> Tuple[float, str]:
    """A value of a load (a Sine's amplitude, a Table's value) whose unit is
    that of the parameter it will drive: a number, or a string in one of
    ``units``.

    Args:
        name: the parameter's name for messages (``"amplitude"``, ``"values[2]"``).
        value: a real number or a string with a unit.
        units: the units a load may have (``"N"``, ``"N*m"``, ``"rad/s"``).

    Returns:
        ``(number, unit)``: the value in the first of ``units`` whose dimension
        the string has (``""`` for a plain number).

    Raises:
        ValueError: as :func:`quantity`; a string of none of these dimensions.
    """
    if not isinstance(value, str):
        return quantity(name, value, ""), ""
    for unit in units:
        try:
            return to_si(name, value, unit), unit
        except ValueError:
            continue
    # Not one of them: the message of a string that does not parse at all,
    # or the list of what a load takes.
    prefix = f"{name} = {_quoted(value)} is invalid: "
    number, given_unit = _split_number(prefix, value)
    try:
        parse_unit(given_unit)
    except ValueError as error:
        raise ValueError(f"{prefix}{error}") from None
    if not math.isfinite(number):
        raise ValueError(f"{prefix}not finite")
    names = [f"{dimension_name(unit)} ({unit})" for unit in units]
    raise ValueError(f"{prefix}{_quoted(value)} is not {', '.join(names[:-1])} or {names[-1]} "
                     f"(the loads' units){_torque_hint(given_unit, units)}")


# --- units of result channels -------------------------------------------------

# The units of the channels the core does not declare, by unit: the time and
# the friction block's own (cpp/src/model/block/block_common.cpp). Every
# drive channel's unit is the core's (_core.drive_channel_units: its
# elements declare each channel with its unit, cpp/src/model/drive/
# declaration.hpp); the block's channels of the same name share it.
_CHANNELS_BY_UNIT = {
    "s": ("t",),
    "m": ("u",),
    "m/s": ("v",),
    "m/s^2": ("acceleration",),
    "N": ("force", "spring_force"),
    "J": ("work_force",),
}
_OWN_UNITS = {name: unit for unit, names in _CHANNELS_BY_UNIT.items() for name in names}
# A body's coordinate and velocity channels, <prefix>_<body>: u_nut, omega_drive.
_COORDINATE_UNITS = {"u": "m", "v": "m/s", "phi": "rad", "omega": "rad/s"}
_BODIES = ("rotor", "drive", "screw", "nut", "load")


@lru_cache(maxsize=1)
def _channel_units() -> dict:
    """Every named channel's unit: the core's declarations, then this module's."""
    from . import _core

    units = dict(_core.drive_channel_units())
    for name, unit in _OWN_UNITS.items():
        units.setdefault(name, unit)
    return units


def channel_unit(name: str) -> str:
    """The SI unit of a result channel (or of the time ``"t"``), from its name.

    Args:
        name: a channel name of :class:`leadscrew.Result` (``"u_load"``,
            ``"omega_screw"``, ``"friction_loss"``, ...) or ``"t"``.

    Returns:
        The unit as text: ``"s"``, ``"m"``, ``"m/s"``, ``"m/s^2"``, ``"rad"``,
        ``"rad/s"``, ``"N"``, ``"N*m"``, ``"J"``, or ``""`` for a flag
        (``stick``: 1 while the flank sticks).

    Raises:
        KeyError: a name no model writes (a new drive channel declares its
            unit in the core, cpp/src/model/drive/declaration.hpp).
    """
    units = _channel_units()
    unit = units.get(name)
    if unit is not None:
        return unit
    prefix, _, body = name.partition("_")
    if body in _BODIES and prefix in _COORDINATE_UNITS:
        return _COORDINATE_UNITS[prefix]
    raise KeyError(f"channel {name!r} has no unit: leadscrew.units.channel_unit knows "
                   f"{', '.join(units)} and <u|v|phi|omega>_<{'|'.join(_BODIES)}>")
