"""Loads as functions of time, shared by every model.

A load argument accepts a :class:`Constant`, :class:`Sine` or :class:`Table`
(evaluated inside the C++ core), a plain number (a constant), or any Python
callable ``f(t) -> float`` (the slow, general fallback: the core calls back
into Python at every evaluation).
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
        self.value = float(value)

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
        self.amplitude = float(amplitude)
        self.omega = float(omega)
        self.phase = float(phase)
        self.offset = float(offset)

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
        times = np.asarray(times, dtype=float).ravel()
        values = np.asarray(values, dtype=float).ravel()
        super().__init__("table", [], times.tolist(), values.tolist())
        self.times = times
        self.values = values

    def __repr__(self) -> str:
        return f"Table(times={self.times.tolist()!r}, values={self.values.tolist()!r})"

    def __reduce__(self):
        return (Table, (self.times, self.values))
