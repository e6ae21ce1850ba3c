"""Loads given by samples: a random vibration from its PSD, a measured record.

Both are evaluated inside the C++ core (no call back into Python) by cubic
Hermite interpolation between knots, which is continuous with its first
derivative: the integrators need no restart at the knots
(``docs/vibration.md`` says why and what it costs).

- :class:`RandomVibration`: a stationary Gaussian signal with a one-sided
  power spectral density given at breakpoints (log-log interpolation between
  them), realised for a ``seed`` as a sum of sinusoids with random phases on
  the grid k / ``duration`` inside the breakpoints' band, periodic with
  period ``duration``.
- :class:`Measured`: a time series (an array, a CSV or Parquet file) with
  its unit, scaled, held at its end values or repeated periodically.

Their values take the units of the loads (:data:`leadscrew.excitation.LOAD_UNITS`):
a force, a torque, an angular velocity, a voltage, a velocity (m/s: a
transverse slip's), an acceleration (m/s^2) or an angular acceleration (rad/s^2).
"""

from __future__ import annotations

import math
import os
import re
from typing import Any, Optional, Sequence, Tuple

import numpy as np

from . import _core
from .excitation import LOAD_UNITS, Number, _table_column, frozen_arrays
from .units import _quoted, load_quantity, quantity, to_si

__all__ = ["RandomVibration", "Measured", "read_record"]


def _psd_values(items: Sequence[Any]) -> Tuple[list, str]:
    """PSD values in (unit)^2/Hz: numbers (SI) or strings with a unit such as
    ``"20 (m/s^2)^2/Hz"`` or ``"0.04 g0^2/Hz"``.

    Returns:
        ``(numbers, unit)``: the floats and the load unit whose square per
        hertz the strings are (``""`` for plain numbers).

    Raises:
        ValueError: naming ``psd[i]``, its value and what it takes.
    """
    out, unit = [], ""
    for i, item in enumerate(items):
        name = f"psd[{i}]"
        if not isinstance(item, str):
            out.append(quantity(name, item, ""))
            continue
        for candidate in LOAD_UNITS:
            try:
                number = to_si(name, item, f"({candidate})**2/Hz")
            except ValueError:
                continue
            if unit and candidate != unit:
                raise ValueError(f"{name} = {_quoted(item)} is invalid: ({candidate})^2/Hz, but "
                                 f"the PSD's earlier values are ({unit})^2/Hz")
            unit = candidate
            out.append(number)
            break
        else:
            raise ValueError(f"{name} = {_quoted(item)} is invalid: must be a PSD, the square "
                             "of a load's unit per hertz, e.g. \"20 (m/s^2)^2/Hz\"")
    return out, unit


class RandomVibration(_core.Excitation):
    """A stationary Gaussian random load with a one-sided PSD.

    Realised as x(t) = sum_k A_k cos(2 pi f_k t + phi_k) on the lines
    f_k = k / duration inside [frequencies[0], frequencies[-1]], with
    A_k = sqrt(2 S(f_k) df) (S log-log interpolated between the breakpoints,
    df the line's share of the band) and phases phi_k uniform in [0, 2 pi)
    from a 64-bit Mersenne Twister seeded with ``seed``: the same seed gives
    the same signal. Its mean square is the PSD's integral over the band to
    within the line spacing's quadrature error; it is periodic with period
    ``duration``.

    Args:
        frequencies: breakpoints [Hz], > 0, strictly increasing (strings
            with units: ``"10 Hz"``).
        psd: the PSD at the breakpoints [unit^2/Hz], > 0 (strings:
            ``"20 (m/s^2)^2/Hz"``; plain numbers SI).
        seed: an integer in [0, 2^53].
        duration: the realisation's period [s] (its frequency resolution
            is 1 / duration).

    Raises:
        ValueError: naming the argument (``psd[2]``), its value and its
            valid range; a duration whose grid has no line in the band.
    """

    def __init__(self, frequencies: Sequence[Number], psd: Sequence[Number], seed: int = 0,
                 duration: Number = 10.0):
        freqs = _table_column("frequencies", frequencies,
                              lambda name, v: quantity(name, v, "Hz"))
        items = _table_column("psd", psd, lambda name, v: v)
        values, self._unit = (items.tolist(), "") if isinstance(items, np.ndarray) else \
            _psd_values(items)
        if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
            raise ValueError(f"seed = {seed!r} is invalid: must be an integer in [0, 2^53]")
        duration = quantity("duration", duration, "s")
        freqs, values = frozen_arrays(freqs, values)
        super().__init__("random", [float(seed), duration], freqs.tolist(), values.tolist())
        self._frequencies, self._psd = freqs, values
        self._seed, self._duration = int(seed), duration

    @property
    def frequencies(self) -> np.ndarray:
        """The breakpoints [Hz] (read-only)."""
        return self._frequencies

    @property
    def psd(self) -> np.ndarray:
        """The PSD at the breakpoints [unit^2/Hz] (read-only)."""
        return self._psd

    @property
    def seed(self) -> int:
        """The seed of the phases."""
        return self._seed

    @property
    def duration(self) -> float:
        """The period of the realisation [s]."""
        return self._duration

    @property
    def unit(self) -> str:
        """The SI unit of the values if the PSD was given with a unit, else ``""``."""
        return self._unit

    @property
    def rms(self) -> float:
        """sqrt of the PSD's integral over its band (log-log segments in closed form)."""
        return self.target_rms

    def psd_at(self, f: Any) -> np.ndarray:
        """The target PSD at ``f`` [Hz], log-log interpolated; 0 outside the band."""
        f = np.asarray(f, dtype=float)
        inside = (f >= self._frequencies[0]) & (f <= self._frequencies[-1])
        logs = np.interp(np.log(np.where(inside, f, self._frequencies[0])),
                         np.log(self._frequencies), np.log(self._psd))
        return np.where(inside, np.exp(logs), 0.0)

    def replace(self, **changes) -> "RandomVibration":
        """A copy with some of its arguments changed (``seed=3``)."""
        arguments = dict(frequencies=self._frequencies, psd=self._psd, seed=self._seed,
                         duration=self._duration)
        arguments.update(changes)
        out = RandomVibration(**arguments)
        if "psd" not in changes:
            out._unit = self._unit
        return out

    def __repr__(self) -> str:
        return (f"RandomVibration(frequencies={self._frequencies.tolist()!r}, "
                f"psd={self._psd.tolist()!r}, seed={self._seed!r}, "
                f"duration={self._duration!r})" + (f"  # ({self.unit})^2/Hz" if self.unit
                                                   else ""))

    def __reduce__(self):
        return (_rebuilt_unit, (RandomVibration, dict(
            frequencies=self._frequencies, psd=self._psd, seed=self._seed,
            duration=self._duration), self._unit))


def _rebuilt_unit(cls, arguments: dict, unit: str):
    load = cls(**arguments)
    load._unit = unit
    return load


class Measured(_core.Excitation):
    """A measured record through (times[i], scale * values[i]).

    Interpolated by cubic Hermite segments with Catmull-Rom slopes (central
    differences of the neighbouring samples, one-sided at the ends): it
    passes through every sample and is continuous with its slope. Held at
    its end values outside the record (the integrators restart at both
    ends), or with ``repeat=True`` continued periodically with period
    ``times[-1] - times[0] + the mean spacing`` (the last sample runs into
    the first over one spacing).

    Args:
        times: strictly increasing times [s] (strings with units too).
        values: the samples, numbers in ``unit`` or strings with units.
        unit: the unit of numeric ``values`` (``"m/s^2"``, ``"g0"``,
            ``"mN"``): converted to the load's SI unit; ``""``: SI already.
        scale: a factor on the values (dimensionless).
        repeat: continue the record periodically.

    Raises:
        ValueError: naming the argument, its value and what it takes.
    """

    def __init__(self, times: Sequence[Number], values: Sequence[Number], unit: str = "",
                 scale: float = 1.0, repeat: bool = False):
        times = _table_column("times", times, lambda n, v: quantity(n, v, "s"))
        items = _table_column("values", values, lambda name, v: v)
        factor, self._unit = _unit_factor(unit)
        if isinstance(items, np.ndarray):
            numbers = items * factor
        else:
            numbers, given = [], self._unit
            for i, item in enumerate(items):
                number, found = load_quantity(f"values[{i}]", item, LOAD_UNITS)
                if found and given and found != given:
                    raise ValueError(f"values[{i}] = {item!r} is invalid: {found}, but the "
                                     f"record's unit is {given}")
                given = given or found
                numbers.append(number * (1.0 if found else factor))
            self._unit = given
        times, values = frozen_arrays(times, numbers)
        scale = quantity("scale", scale, "")
        if not isinstance(repeat, (bool, np.bool_)):
            raise ValueError(f"repeat = {repeat!r} is invalid: must be True or False")
        super().__init__("measured", [scale, 1.0 if repeat else 0.0], times.tolist(),
                         values.tolist())
        self._times, self._values, self._scale, self._repeat = times, values, scale, bool(repeat)

    @classmethod
    def from_file(cls, path: str, column: Optional[str] = None, unit: Optional[str] = None,
                  scale: float = 1.0, repeat: bool = False) -> "Measured":
        """A record from a CSV or Parquet file (:func:`read_record`).

        Args:
            path: the file (``.csv``, ``.parquet``).
            column: the values' column (None: the one column after the time).
            unit: the values' unit where the file gives none.
            scale, repeat: as the constructor's.

        Raises:
            ValueError: the file, its columns or units are invalid (named).
        """
        times, values, found = read_record(path, column)
        if unit and found and _unit_factor(unit) != _unit_factor(found):
            raise ValueError(f"unit = {unit!r} is invalid: the file gives {found!r} for its "
                             "column")
        return cls(times, values, unit=found or unit or "", scale=scale, repeat=repeat)

    @property
    def times(self) -> np.ndarray:
        """The sample times [s] (read-only)."""
        return self._times

    @property
    def values(self) -> np.ndarray:
        """The samples in SI, before the scale (read-only)."""
        return self._values

    @property
    def scale(self) -> float:
        """The factor on the values."""
        return self._scale

    @property
    def repeat(self) -> bool:
        """Whether the record repeats periodically."""
        return self._repeat

    @property
    def unit(self) -> str:
        """The SI unit of the values if given with a unit, else ``""``."""
        return self._unit

    def __repr__(self) -> str:
        return (f"Measured({len(self._times)} samples, {float(self._times[0])!r}.."
                f"{float(self._times[-1])!r} "
                f"s, unit={self._unit!r}, scale={self._scale!r}, repeat={self._repeat!r})")

    def __reduce__(self):
        return (_rebuilt_unit, (Measured, dict(times=self._times, values=self._values,
                                               scale=self._scale, repeat=self._repeat),
                                self._unit))


def _unit_factor(unit: str) -> Tuple[float, str]:
    """The factor from ``unit`` to the load unit of its dimension, and that unit.

    Raises:
        ValueError: ``unit`` is no unit of a load.
    """
    if not unit:
        return 1.0, ""
    try:
        return load_quantity("unit", f"1 {unit}", LOAD_UNITS)
    except ValueError as error:
        reason = str(error).split(" is invalid: ", 1)[-1]
        raise ValueError(f"unit = {unit!r} is invalid: {reason}") from None


_HEADER = re.compile(r"^\s*(.*?)\s*\[\s*(.*?)\s*\]\s*$")


def _split_header(name: str) -> Tuple[str, str]:
    """``"a [m/s^2]"`` -> ``("a", "m/s^2")``; a name without brackets has no unit."""
    match = _HEADER.match(str(name))
    return (match.group(1), match.group(2)) if match else (str(name).strip(), "")


def read_record(path: str, column: Optional[str] = None) -> Tuple[np.ndarray, np.ndarray, str]:
    """The time column (first) and a value column of a CSV or Parquet file.

    Units: from a header ``name [unit]`` (``t [s]``, ``a [m/s^2]``), from a
    row of units under the names (leadscrew's own CSV), or from a Parquet
    field's metadata ``unit``. A time column with a unit is converted to s.

    Args:
        path: a ``.csv`` or ``.parquet`` file.
        column: the values' column by name (without its unit); None: the
            file must have exactly two columns.

    Returns:
        ``(times [s], values, unit)``, ``unit`` ``""`` where the file gives none.

    Raises:
        ValueError: the file is missing or unreadable, a column is missing,
            a value is not a number (each named).
    """
    import pandas as pd

    if not os.path.isfile(path):
        raise ValueError(f"path = {path!r} is invalid: no such file")
    units = {}
    try:
        if str(path).lower().endswith(".parquet"):
            import pyarrow.parquet as pq

            table = pq.read_table(path)
            for field in table.schema:
                meta = field.metadata or {}
                units[field.name] = meta.get(b"unit", b"").decode()
            frame = table.to_pandas()
        else:
            frame = pd.read_csv(path)
            first = frame.iloc[0] if len(frame) else None
            if first is not None and not all(_is_number(x) for x in first):
                units = {name: ("" if pd.isna(u) else str(u)) for name, u in first.items()}
                frame = frame.iloc[1:].reset_index(drop=True)
    except Exception as error:  # pandas and pyarrow raise many types
        raise ValueError(f"path = {path!r} is invalid: not a readable table ({error})") from None
    names = {}
    for raw in frame.columns:
        name, unit = _split_header(raw)
        names[name] = (raw, unit or units.get(raw, ""))
    keys = list(names)
    if column is None:
        if len(keys) != 2:
            raise ValueError(f"column = None is invalid for {path!r}: it has {len(keys)} "
                             f"columns {keys}; name the values' column")
        column = keys[1]
    if column not in names or column == keys[0]:
        raise ValueError(f"column = {column!r} is invalid: must be one of {keys[1:]} (the "
                         f"first, {keys[0]!r}, is the time)")
    time_raw, time_unit = names[keys[0]]
    raw, unit = names[column]
    try:
        times = frame[time_raw].astype(float).to_numpy()
        values = frame[raw].astype(float).to_numpy()
    except ValueError as error:
        raise ValueError(f"path = {path!r} is invalid: a value is not a number ({error})") \
            from None
    if time_unit:
        times = times * quantity(f"{keys[0]} [{time_unit}]", f"1 {time_unit}", "s")
    return times, values, unit


def _is_number(x: Any) -> bool:
    try:
        return math.isfinite(float(x)) or True
    except (TypeError, ValueError):
        return False
