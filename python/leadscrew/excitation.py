"""Loads as functions of time, shared by every model.

A load argument accepts a :class:`Constant`, :class:`Sine` or :class:`Table`
(evaluated inside the C++ core), a plain number (a constant), or any Python
callable ``f(t) -> float`` (the slow, general fallback: the core calls back
into Python at every evaluation).

The parameters of a :class:`Constant`, :class:`Sine` or :class:`Table` are
read-only (a Table's arrays are not writeable): the core evaluates the values
given to the constructor, and a scene stores these loads as the dicts of
their parameters (see :mod:`leadscrew.scene`).
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from . import _core

__all__ = ["Excitation", "Constant", "Sine", "Table"]

Excitation = _core.Excitation


class Constant(_core.Excitation):
    """A constant load.

    Args:
        value: the load (N, N*m, ... as the parameter it is passed to).

    Raises:
        ValueError: value is not finite.
    """

    def __init__(self, value: float):
        super().__init__("constant", [float(value)])
        self._value = float(value)

    @property
    def value(self) -> float:
        """The load (read-only)."""
        return self._value

    def __repr__(self) -> str:
        return f"Constant({self.value!r})"

    def __reduce__(self):
        return (Constant, (self.value,))


class Sine(_core.Excitation):
    """``amplitude * sin(omega * t + phase) + offset``.

    Args:
        amplitude: amplitude (unit of the load).
        omega: angular frequency [rad/s].
        phase: phase [rad].
        offset: constant part (unit of the load).

    Raises:
        ValueError: a parameter is not finite.
    """

    def __init__(self, amplitude: float, omega: float, phase: float = 0.0, offset: float = 0.0):
        super().__init__("sine", [float(amplitude), float(omega), float(phase), float(offset)])
        self._parameters = (float(amplitude), float(omega), float(phase), float(offset))

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

    def __repr__(self) -> str:
        return (f"Sine(amplitude={self.amplitude!r}, omega={self.omega!r}, "
                f"phase={self.phase!r}, offset={self.offset!r})")

    def __reduce__(self):
        return (Sine, (self.amplitude, self.omega, self.phase, self.offset))


class Table(_core.Excitation):
    """Piecewise-linear load through the points (times[i], values[i]).

    Held constant before the first and after the last point. Integrators
    restart at the knots, where the slope jumps.

    Args:
        times: strictly increasing times [s].
        values: load values at those times.

    Raises:
        ValueError: lengths differ, a value is not finite, or times do not increase.
    """

    def __init__(self, times: Sequence[float], values: Sequence[float]):
        # Own copies, not writeable: the core holds the values given here.
        times = np.array(times, dtype=float).ravel()
        values = np.array(values, dtype=float).ravel()
        super().__init__("table", [], times.tolist(), values.tolist())
        times.flags.writeable = False
        values.flags.writeable = False
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

    def __repr__(self) -> str:
        return f"Table(times={self.times.tolist()!r}, values={self.values.tolist()!r})"

    def __reduce__(self):
        return (Table, (self.times, self.values))
