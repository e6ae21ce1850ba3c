"""The loads of a scene and its initial-state rules.

A load (``loads.drive_torque``, ``loads.drive_speed``, ``loads.axial_force``,
``loads.base_acceleration``, ``loads.base_angular_acceleration``,
``motor.voltage``) is a number, a ``{type = "constant" | "sine" | "table" |
"random" | "measured", ...}`` dict (a random vibration: ``frequencies``,
``psd``, ``seed``, ``duration``, or ``profile`` and ``seed``, ``duration``;
a record: ``times`` and ``values``, or ``file`` (CSV or Parquet) with
``column`` and ``unit``, and ``scale``, ``repeat``), an :class:`~leadscrew.Excitation` or a callable: ``_check_load``
checks and converts one (units included), ``_make_excitation`` builds what
the core takes from it. The defaults the model applies where a scene gives
no drive torque or initial rotor speed, and the rule that a speed-controlled
drive starts at drive_speed(0), are here as well.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable
from typing import Any, Dict, Optional

from . import _core
from .excitation import Constant, Sine, Table, check_load_unit, checked_callable
from .excitation_sampled import Measured, RandomVibration
from .scene_schema import SCHEMA, _Converted, _fail
from .units import to_si, what_it_takes

__all__: list = []  # the scene's internals: leadscrew.Scene is the public face


_LOAD_TYPES = {"constant": ("value",), "sine": ("amplitude", "omega", "phase", "offset"),
               "table": ("times", "values"),
               "random": ("frequencies", "psd", "seed", "duration"),
               "measured": ("times", "values", "scale", "repeat")}
# What a dict of these types may give instead of some of its keys: a
# profile's name (leadscrew.profiles) for the breakpoints, a file for the samples.
_LOAD_ALTERNATIVES = {"random": ("profile",), "measured": ("file", "column", "unit")}
# The defaults of the entries that have one.
_LOAD_DEFAULTS = {"phase": 0.0, "offset": 0.0, "seed": 0, "duration": 10.0, "scale": 1.0,
                  "repeat": False}
# Units of the entries of a load table; None: the unit of the load itself,
# "psd": its square per hertz, "": a plain number (or a flag).
_LOAD_ENTRY_UNITS = {"value": None, "amplitude": None, "offset": None, "values": None,
                     "omega": "rad/s", "phase": "rad", "times": "s", "frequencies": "Hz",
                     "psd": "psd", "seed": "", "duration": "s", "scale": "", "repeat": ""}


def load_entry_unit(key: str, unit: str) -> str:
    """The unit of a load table's entry ``key`` in a load of ``unit``."""
    entry_unit = _LOAD_ENTRY_UNITS[key]
    if entry_unit == "psd":
        return f"({unit})**2/Hz" if unit else ""
    return unit if entry_unit is None else entry_unit


def _load_entry_to_si(path: str, key: str, entry: Any, unit: str):
    """An entry of a load table as float(s) in its unit: a number or a list of
    numbers, each a real number (not a bool) or a string with a unit.

    Raises:
        ValueError: naming ``path.key`` (or ``path.key[i]``), the value and
            what is allowed.
    """
    entry_unit = load_entry_unit(key, unit)
    if key == "repeat":
        if not isinstance(entry, bool):
            _fail(f"{path}.{key}", entry, "true or false")
        return entry
    if key == "seed":
        if isinstance(entry, bool) or not isinstance(entry, numbers.Integral) or entry < 0:
            _fail(f"{path}.{key}", entry, "an integer in [0, 2^53]")
        return int(entry)
    if key in ("times", "values", "frequencies", "psd"):
        items = entry.tolist() if hasattr(entry, "tolist") else entry
        if isinstance(items, (str, bytes, dict, set, frozenset)) or not isinstance(
                items, Iterable):
            _fail(f"{path}.{key}", entry, "a list of numbers" + (f" [{entry_unit}]" if entry_unit
                                                                  else ""))
        return [_load_number(f"{path}.{key}[{i}]", x, entry_unit) for i, x in enumerate(items)]
    return _load_number(f"{path}.{key}", entry, entry_unit)


def _load_number(path: str, value: Any, unit: str) -> float:
    """One number of a load table: a finite real number (numpy scalars too,
    not a bool) or a string with a unit, as float in ``unit``."""
    number = to_si(path, value, unit)
    finite = None if isinstance(number, bool) else _finite_float(number)
    if finite is None:
        shown = _Converted(value, number, unit) if isinstance(value, str) else value
        _fail(path, shown, what_it_takes(unit, "a finite number"))
    return finite


def _finite_float(value: Any) -> Optional[float]:
    """A real number as a finite float; None for anything else (NaN, inf, an
    int beyond the float range, no real number)."""
    if not isinstance(value, numbers.Real):
        return None
    try:
        number = float(value)
    except OverflowError:
        return None
    return number if math.isfinite(number) else None


def _excitation_spec(value: Any) -> Optional[Dict[str, Any]]:
    """The ``{type = ...}`` dict of a Constant, Sine or Table (None for
    anything else): a scene stores these loads as dicts, which compare equal
    by value and round-trip through TOML."""
    if isinstance(value, Constant):
        return {"type": "constant", "value": value.value}
    if isinstance(value, Sine):
        return {"type": "sine", "amplitude": value.amplitude, "omega": value.omega,
                "phase": value.phase, "offset": value.offset}
    if isinstance(value, Table):
        return {"type": "table", "times": value.times.tolist(), "values": value.values.tolist()}
    if isinstance(value, RandomVibration):
        return {"type": "random", "frequencies": value.frequencies.tolist(),
                "psd": value.psd.tolist(), "seed": value.seed, "duration": value.duration}
    if isinstance(value, Measured):
        return {"type": "measured", "times": value.times.tolist(),
                "values": value.values.tolist(), "scale": value.scale, "repeat": value.repeat}
    return None


def _check_load(path: str, value: Any, unit: str = ""):
    spec = _excitation_spec(value)
    if spec is not None:  # the core checked the object as it was built
        check_load_unit(path, value, unit)
        return spec
    if isinstance(value, _core.Excitation) or (callable(value) and not isinstance(value, dict)):
        return value
    value = to_si(path, value, unit)
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        number = _finite_float(value)
        if number is None:
            _fail(path, value, "finite")
        return number
    if isinstance(value, dict):
        kind = value.get("type")
        if not isinstance(kind, str) or kind not in _LOAD_TYPES:
            _fail(f"{path}.type", kind, "one of " + ", ".join(repr(k) for k in _LOAD_TYPES))
        allowed = _LOAD_TYPES[kind]
        alternatives = _LOAD_ALTERNATIVES.get(kind, ())
        for key in value:
            if key != "type" and key not in allowed and key not in alternatives:
                _fail(f"{path}.{key}", value[key],
                      f"absent: {kind!r} loads take {', '.join(allowed + alternatives)}")
        value = _resolved(path, kind, value, unit)
        out = {"type": kind}
        for key in allowed:
            if key in value:
                out[key] = _load_entry_to_si(path, key, value[key], unit)
            elif key in _LOAD_DEFAULTS and kind != "table":
                out[key] = _LOAD_DEFAULTS[key]
            else:
                raise ValueError(f"{path}.{key} is missing: a {kind!r} load needs "
                                 f"{', '.join(allowed)}")
        try:
            _make_excitation(out)
        except ValueError as error:
            raise ValueError(f"{path}: {error}") from None
        return out
    _fail(path, value, "a number, a dict with 'type' in constant/sine/table/random/measured, "
          "an Excitation or a callable f(t)")


def _resolved(path: str, kind: str, value: Dict[str, Any], unit: str) -> Dict[str, Any]:
    """A random load's ``profile`` as its breakpoints, a record's ``file`` as
    its samples in ``unit`` (the other keys as given).

    Raises:
        ValueError: naming ``path.profile`` or ``path.file``, the value and
            what it takes (a profile in m/s^2 where the load is not one).
    """
    from . import profiles

    value = dict(value)
    if kind == "random" and "profile" in value:
        if "frequencies" in value or "psd" in value:
            _fail(f"{path}.profile", value["profile"], "absent where frequencies and psd are "
                  "given")
        name = value.pop("profile")
        if not isinstance(name, str) or name not in profiles.names():
            _fail(f"{path}.profile", name, "one of " + ", ".join(map(repr, profiles.names())))
        if unit != "m/s^2":
            _fail(f"{path}.profile", name, f"absent: a profile is an acceleration (m/s^2), "
                  f"{path} is in {unit}")
        profile = profiles.checked(name)
        value["frequencies"], value["psd"] = list(profile.frequencies), list(profile.psd)
    if kind == "measured" and "file" in value:
        if "times" in value or "values" in value:
            _fail(f"{path}.file", value["file"], "absent where times and values are given")
        file = value.pop("file")
        if not isinstance(file, str):
            _fail(f"{path}.file", file, "the path of a CSV or Parquet file")
        try:
            record = Measured.from_file(file, value.pop("column", None), value.pop("unit", None))
        except ValueError as error:  # (from_file's argument `path` is the key `file` here)
            text = str(error)
            text = "file" + text[len("path"):] if text.startswith("path = ") else text
            raise ValueError(f"{path}.{text}") from None
        check_load_unit(path, record, unit)
        value["times"], value["values"] = record.times.tolist(), record.values.tolist()
    elif kind == "measured" and ("column" in value or "unit" in value):
        key = "column" if "column" in value else "unit"
        _fail(f"{path}.{key}", value[key], "absent without file")
    return value


def _make_excitation(spec, key: str = ""):
    """An Excitation (or number, or checked callable) from a validated load
    value; ``key`` (of ``loads``) names a Python callable's load in its errors."""
    if isinstance(spec, dict):
        kind = spec["type"]
        if kind == "constant":
            return Constant(spec["value"])
        if kind == "sine":
            return Sine(spec["amplitude"], spec["omega"], spec["phase"], spec["offset"])
        if kind == "random":
            return RandomVibration(spec["frequencies"], spec["psd"], seed=spec["seed"],
                                   duration=spec["duration"])
        if kind == "measured":
            return Measured(spec["times"], spec["values"], scale=spec["scale"],
                            repeat=spec["repeat"])
        return Table(spec["times"], spec["values"])
    if spec.__class__ is not float and callable(spec) and not isinstance(spec, _core.Excitation):
        return checked_callable(f"loads.{key}", spec, SCHEMA["loads"][key].unit)
    return spec


# The drive torque of a scene that gives neither drive_torque nor drive_speed.
_DEFAULT_DRIVE_TORQUE = 0.0
# The initial rotor speed of a torque-driven scene that gives none.
_DEFAULT_ROTOR_SPEED = 0.0


def _effective(data: Dict[str, Any]) -> Dict[str, Any]:
    """The scene data with the defaults the model applies filled in (for
    comparing): the drive torque, and the initial rotor speed (that of a
    speed-controlled drive is drive_speed(0), whether given or not)."""
    loads, initial = data["loads"], data["initial"]
    if "drive_speed" in loads:
        initial = {k: v for k, v in initial.items() if k != "rotor_speed"}
    else:
        initial = {"rotor_speed": _DEFAULT_ROTOR_SPEED, **initial}
    if not ("drive_torque" in loads or "drive_speed" in loads):
        loads = {**loads, "drive_torque": _DEFAULT_DRIVE_TORQUE}
    return {**data, "loads": loads, "initial": initial}


def _check_rotor_speed(data: Dict[str, Any]) -> None:
    """A rotor speed given for a speed-controlled drive must be the speed the
    drive prescribes at t = 0 (the run starts there: another value would be
    overridden silently).

    Raises:
        ValueError: naming initial.rotor_speed, its value and drive_speed(0).
    """
    speed = data["initial"].get("rotor_speed")
    if speed is None or "drive_speed" not in data["loads"]:
        return
    load = _make_excitation(data["loads"]["drive_speed"], "drive_speed")
    prescribed = float(load if isinstance(load, numbers.Real) else load(0.0))
    # Round-off of the load's evaluation (a sine's offset + amplitude sin(phase)).
    if not math.isclose(speed, prescribed, rel_tol=1e-12, abs_tol=1e-12):
        _fail("initial.rotor_speed", speed,
              f"{prescribed!r} rad/s or absent: loads.drive_speed prescribes {prescribed!r} "
              "rad/s at t = 0, where a speed-controlled drive starts")
