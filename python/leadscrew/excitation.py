"""Loads as functions of time, shared by every model.

A load argument accepts a :class:`Constant`, :class:`Sine` or :class:`Table`
(evaluated inside the C++ core; so are
:class:`~leadscrew.excitation_sampled.RandomVibration` and
:class:`~leadscrew.excitation_sampled.Measured`), a plain number (a constant), or any Python
callable ``f(t) -> float`` (the slow, general fallback: the core calls back
into Python at every evaluation).

The parameters of a :class:`Constant`, :class:`Sine` or :class:`Table` are
read-only (a Table's arrays are not writeable): the core evaluates the values
given to the constructor, and a scene stores these loads as the dicts of
their parameters (see :mod:`leadscrew.scene`).

Their parameters may be strings with units, as in a scene: ``Sine("50 N",
"15 Hz")``, ``Table(["0 s", "250 ms"], ["0 N*mm", "40 N*mm"])``. The values
of a load (value, amplitude, offset, a table's values) take a force (N), a
torque (N*m), an angular velocity (rad/s), an acceleration (m/s^2, rad/s^2: a
base excitation) or a voltage (V, a DC motor's
``motor.voltage``), all in the same one: the load
keeps it as :attr:`unit` (``""`` when they are plain numbers), and a scene
or a FrictionBlock refuses a load whose unit is not that of the parameter it
drives (a torque as an axial force). Plain numbers are SI in the unit of
that parameter.
"""

from __future__ import annotations

import functools
import numbers
from typing import Any, Callable, Dict, List, Sequence, Tuple, Union

import numpy as np

from . import _core
from .units import _quoted, dimension_name, load_quantity, quantity

__all__ = ["Excitation", "Constant", "Sine", "Table"]

Excitation = _core.Excitation

Number = Union[float, str]

#: The units a load's values may have: those of the loads it drives (the
#: velocity: a transverse slip's, ``loads.transverse_slip_velocity`` and
#: ``FrictionBlock(transverse_velocity=...)``; the accelerations: a base
#: excitation's, ``loads.base_acceleration`` and
#: ``loads.base_angular_acceleration``). The key a load drives checks its unit.
LOAD_UNITS = ("N", "N*m", "rad/s", "V", "m/s", "m/s^2", "rad/s^2")


def _load_values(named: Sequence[Tuple[str, Any]]) -> Tuple[List[float], str]:
    """The values of one load in SI and their common unit.

    Args:
        named: ``(name, value)`` pairs, a value a number or a string with a
            unit in :data:`LOAD_UNITS`.

    Returns:
        ``(numbers, unit)``: the floats and the unit of the strings (``""``
        if there are none).

    Raises:
        ValueError: naming the value that is no number, is of another
            dimension, or has another unit than an earlier one.
    """
    values = [value for _, value in named]
    if all(value.__class__ is float for value in values):  # SI floats: nothing to convert
        return values, ""
    values, unit, first = [], "", ""
    for name, value in named:
        number, given = load_quantity(name, value, LOAD_UNITS)
        if given and unit and given != unit:
            shown = _quoted(value) if isinstance(value, str) else repr(value)
            raise ValueError(f"{name} = {shown} is invalid: {dimension_name(given)} "
                             f"({given}), but {first} is {dimension_name(unit)} ({unit}): the "
                             "values of one load share their unit")
        if given and not unit:
            unit, first = given, name
        values.append(number)
    return values, unit


def _with_unit(value: float, unit: str) -> Union[float, str]:
    """A value for a repr: the float, or a string with its unit."""
    return f"{value!r} {unit}" if unit else value


def _rebuilt(cls, arguments: tuple, unit: str):
    """A load from its SI parameters and unit (for pickle)."""
    load = cls(*arguments)
    load._unit = unit
    return load


def check_load_unit(name: str, load: Any, unit: str) -> None:
    """Refuse a Constant, Sine, Table, RandomVibration or Measured given with a
    unit other than that of
    the parameter it drives.

    Args:
        name: the parameter (``"force"``, ``"loads.axial_force"``).
        load: the load (anything else passes).
        unit: the parameter's unit.

    Raises:
        ValueError: e.g. ``loads.axial_force = Sine(amplitude='50.0 N*m', ...)
        is invalid: its values are a torque (N*m), not a force (N)``.
    """
    given = getattr(load, "unit", "") if isinstance(load, _core.Excitation) else ""
    if given and given != unit:
        raise ValueError(f"{name} = {load!r} is invalid: its values are "
                         f"{dimension_name(given)} ({given}), not {dimension_name(unit)} "
                         f"({unit})")


def checked_callable(name: str, function: Callable[[float], float], unit: str = ""):
    """A Python load ``f(t)`` as the core calls it: a value that is no number
    (a string, None, a bool, an array) raises ``ValueError`` naming the load,
    the value and the time, instead of the core's cast error. The repr
    names the load too (the core's message for a NaN shows it).

    Overhead: one Python call and a class check per evaluation, 50-60 ns
    against about 135 ns for a call of ``lambda t: 4.0 * math.sin(3.0 * t)``
    itself (timeit); 60-160 ns per evaluation in a FrictionBlock run of 1520
    evaluations (0.58 -> 0.71 ms, medians of 30, noisy machine).
    """
    @functools.wraps(function, assigned=(), updated=())
    def load(t):
        value = function(t)
        if value.__class__ is float:
            return value
        return _checked_value(name, function, unit, t, value)

    load.__qualname__ = (f"{getattr(function, '__qualname__', type(function).__qualname__)} "
                         f"({name})")
    load.__wrapped__ = function
    return load


def _checked_value(name: str, function, unit: str, t: float, value: Any) -> float:
    if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)):
        try:
            return float(value)
        except OverflowError:  # an int beyond a float: infinite, as the core refuses NaN
            return float("inf") if value > 0 else float("-inf")
    unit_text = f" [{unit}]" if unit else ""
    raise ValueError(f"{name} = {function!r} is invalid: at t = {t:.4g} s it returned {value!r}, "
                     f"not a number{unit_text} (a load function returns a float)")


class Constant(_core.Excitation):
    """A constant load.

    Args:
        value: the load (N, N*m, rad/s or V as the parameter it is passed
            to), or a string with a unit (``"-10 N"``, ``"12 V"``).

    Raises:
        ValueError: value is not finite, not a number or of another
            dimension than a load.
    """

    def __init__(self, value: Number):
        if value.__class__ is float:  # SI: nothing to convert (the core checks it)
            number, self._unit = value, ""
        else:
            (number,), self._unit = _load_values([("value", value)])
        super().__init__("constant", [number])
        self._value = number

    @property
    def value(self) -> float:
        """The load in SI (read-only)."""
        return self._value

    @property
    def unit(self) -> str:
        """The SI unit of the values given with a unit, ``""`` for plain numbers."""
        return self._unit

    def __repr__(self) -> str:
        return f"Constant({_with_unit(self.value, self.unit)!r})"

    def __reduce__(self):
        return (_rebuilt, (Constant, (self.value,), self.unit))


class Sine(_core.Excitation):
    """``amplitude * sin(omega * t + phase) + offset``.

    Args:
        amplitude: amplitude (unit of the load).
        omega: angular frequency [rad/s] (``"15 Hz"`` is 15 turns per second).
        phase: phase [rad].
        offset: constant part (unit of the load).

    Each may be a string with a unit: ``Sine("50 N", "15 Hz", "90 deg")``.

    Raises:
        ValueError: a parameter is not finite, not a number or of the wrong
            dimension (the message names it).
    """

    def __init__(self, amplitude: Number, omega: Number, phase: Number = 0.0,
                 offset: Number = 0.0):
        parameters = (amplitude, omega, phase, offset)
        if all(value.__class__ is float for value in parameters):  # SI: nothing to convert
            self._unit = ""
        else:
            (amplitude, offset), self._unit = _load_values([("amplitude", amplitude),
                                                            ("offset", offset)])
            parameters = (amplitude, quantity("omega", omega, "rad/s"),
                          quantity("phase", phase, "rad"), offset)
        super().__init__("sine", list(parameters))
        self._parameters = parameters

    @property
    def amplitude(self) -> float:
        """Amplitude (read-only)."""
        return self._parameters[0]

    @property
    def omega(self) -> float:
        """Angular frequency [rad/s] (read-only)."""
        return self._parameters[1]

    @property
    def phase(self) -> float:
        """Phase [rad] (read-only)."""
        return self._parameters[2]

    @property
    def offset(self) -> float:
        """Constant part (read-only)."""
        return self._parameters[3]

    @property
    def unit(self) -> str:
        """The SI unit of amplitude and offset if given with a unit, else ``""``."""
        return self._unit

    def __repr__(self) -> str:
        return (f"Sine(amplitude={_with_unit(self.amplitude, self.unit)!r}, "
                f"omega={self.omega!r}, phase={self.phase!r}, "
                f"offset={_with_unit(self.offset, self.unit)!r})")

    def __reduce__(self):
        return (_rebuilt, (Sine, self._parameters, self.unit))


class Table(_core.Excitation):
    """Piecewise-linear load through the points (times[i], values[i]).

    Held constant before the first and after the last point. Integrators
    restart at the knots, where the slope jumps.

    Args:
        times: strictly increasing times [s].
        values: load values at those times.

    Either may hold strings with units: ``Table(["0 s", "250 ms"], ["0 N",
    "40 N"])``.

    Raises:
        ValueError: lengths differ, a value is not finite or not a number
            (or of the wrong dimension), or times do not increase.
    """

    def __init__(self, times: Sequence[Number], values: Sequence[Number]):
        # Own copies, not writeable: the core holds the values given here.
        times = _table_column("times", times, lambda name, v: quantity(name, v, "s"))
        values = _table_column("values", values, None)
        values, self._unit = (values, "") if isinstance(values, np.ndarray) else \
            _load_values([(f"values[{i}]", v) for i, v in enumerate(values)])
        times, values = frozen_arrays(times, values)
        super().__init__("table", [], times.tolist(), values.tolist())
        self._times = times
        self._values = values

    @property
    def times(self) -> np.ndarray:
        """The times [s] (a read-only array)."""
        return self._times

    @property
    def values(self) -> np.ndarray:
        """The load values (a read-only array)."""
        return self._values

    @property
    def unit(self) -> str:
        """The SI unit of the values if given with a unit, else ``""``."""
        return self._unit

    def __repr__(self) -> str:
        values = [_with_unit(v, self.unit) for v in self.values.tolist()]
        return f"Table(times={self.times.tolist()!r}, values={values!r})"

    def __reduce__(self):
        return (_rebuilt, (Table, (self.times, self.values), self.unit))


def frozen_arrays(*columns) -> Tuple[np.ndarray, ...]:
    """Own flat float copies of ``columns``, not writeable: the core holds
    the values given to a load's constructor."""
    arrays = tuple(np.array(column, dtype=float).ravel() for column in columns)
    for array in arrays:
        array.flags.writeable = False
    return arrays


def _table_column(name: str, items: Any, convert) -> Union[np.ndarray, list]:
    """A column of a Table: a float array if it holds numbers only, else
    (strings with units) its items converted one by one with
    ``convert(name[i], item)`` (None: the items as given, for the values).

    Raises:
        ValueError: ``items`` is no sequence, or an item no number (naming it).
    """
    if isinstance(items, (str, bytes, dict)) or not hasattr(items, "__len__"):
        raise ValueError(f"{name} = {items!r} is invalid: must be a sequence of numbers")
    try:
        array = np.asarray(items)
    except ValueError:  # ragged
        array = None
    if array is not None and array.dtype.kind in "fiu":
        return array.astype(float).ravel()
    # Strings with units, or items that are no numbers (None is no NaN here):
    # one by one, each named.
    items = list(items)
    if convert is None:
        return items
    return [convert(f"{name}[{i}]", item) for i, item in enumerate(items)]
