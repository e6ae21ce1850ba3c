"""Helpers shared by the studies: argument checks, scene edits, frame metadata."""

from __future__ import annotations

import functools
import math
import numbers
from typing import Any, Dict, Iterable, Optional

import numpy as np
import pandas as pd

from ..scene import Scene

__all__ = [
    "as_scene",
    "check_finite",
    "check_positive",
    "check_count",
    "check_grid",
    "with_loads",
    "annotate",
    "frame_of",
    "numeric_or_nan",
    "axes",
]


def as_scene(scene: Any) -> Scene:
    """A :class:`~leadscrew.Scene` from a Scene or a scene dict.

    Raises:
        ValueError: ``scene`` is neither, or the dict is not a valid scene.
    """
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, dict):
        return Scene.from_dict(scene)
    raise ValueError(f"scene = {scene!r} is invalid: must be a leadscrew.Scene or a scene dict")


def check_finite(name: str, value: Any) -> float:
    """``value`` as a float, a finite number.

    Raises:
        ValueError: naming the parameter and the value.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value):
        raise ValueError(f"{name} = {value!r} is invalid: must be a finite number")
    return float(value)


def check_positive(name: str, value: Any, allow_zero: bool = False) -> float:
    """``value`` as a float, finite and > 0 (>= 0 with ``allow_zero``).

    Raises:
        ValueError: naming the parameter, the value and the valid range.
    """
    bound = ">= 0" if allow_zero else "> 0"
    try:
        value = check_finite(name, value)
    except ValueError:
        raise ValueError(f"{name} = {value!r} is invalid: must be a finite number {bound}") \
            from None
    if value < 0 or (value == 0 and not allow_zero):
        raise ValueError(f"{name} = {value!r} is invalid: must be a finite number {bound}")
    return value


def check_count(name: str, value: Any, low: int) -> int:
    """``value`` as an int >= ``low``.

    Raises:
        ValueError: naming the parameter, the value and the valid range.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < low:
        raise ValueError(f"{name} = {value!r} is invalid: must be an integer >= {low}")
    return int(value)


def check_grid(name: str, values: Iterable[float], allow_zero: bool = False) -> np.ndarray:
    """A non-empty 1-D array of finite values > 0 (>= 0 with ``allow_zero``).

    Raises:
        ValueError: naming the parameter, the offending value and the valid range.
    """
    try:
        array = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {values!r} is invalid: must be a sequence of numbers") from None
    if array.ndim != 1 or array.size == 0:
        raise ValueError(f"{name} = {values!r} is invalid: must be a non-empty 1-D sequence")
    valid = np.isfinite(array) & ((array >= 0) if allow_zero else (array > 0))
    if not valid.all():  # the message names the first offending entry
        check_positive(f"{name} entry", float(array[np.argmin(valid)]), allow_zero)
    return array


def with_loads(scene: Scene, **loads: Any) -> Scene:
    """The scene with some of its ``loads`` replaced (``None`` removes one:
    ``drive_torque=None, drive_speed=10.0`` switches to a speed-controlled drive).

    Raises:
        ValueError: the loads are invalid (as :meth:`Scene.from_dict`).
    """
    return scene.replace(loads=loads)


def frame_of(columns: Dict[str, Any]):
    """A DataFrame of 1-D columns of one length, made by pandas' public
    constructor (object columns passed as object Series, so that pandas does
    not turn None and messages into a string dtype).

    Args:
        columns: column name -> 1-D array (or sequence) of values, all of one
            length, in the order of the frame's columns. Numeric and bool
            arrays keep their dtype; object arrays and arrays of strings
            become object columns. The frame may share memory with the
            arrays: pass arrays nothing else writes to.

    Returns:
        The DataFrame, with a RangeIndex and plain (object) column labels.

    Raises:
        ValueError: a column is not 1-D, or the lengths differ.
    """
    arrays = [np.asarray(values) for values in columns.values()]
    arrays = [a.astype(object) if a.dtype.kind in "US" else a for a in arrays]
    length = len(arrays[0]) if arrays else 0
    if any(a.ndim != 1 or len(a) != length for a in arrays):
        raise ValueError("frame columns must be 1-D arrays of one length: got shapes "
                         f"{[a.shape for a in arrays]}")
    # A view: each frame gets its own Index object (its name is the frame's
    # to set), on the cached labels.
    names = _labels(tuple(columns)).view()
    frame = pd.DataFrame(
        {name: pd.Series(a, dtype=object, copy=False) if a.dtype == object else a
         for name, a in zip(names, arrays)}, copy=False)
    frame.columns = names
    return frame


@functools.lru_cache(maxsize=64)
def _labels(names: tuple):
    """An object Index of column names, one per set of names (frame_of hands
    out views of it)."""
    return pd.Index(list(names), dtype=object)


# What an error column holds when it needs no conversion.
_ERROR_TYPES = {type(None), str}


def annotate(frame, units: Dict[str, str], errors_checked: bool = False,
             summary_units: Optional[Dict[str, str]] = None, **summary: Any):
    """Attach units and a summary to a study's frame.

    Args:
        frame: the DataFrame (changed in place).
        units: column -> SI unit (``"1"`` for ratios, ``""`` for labels),
            stored as ``attrs["units"]`` for the frame's columns.
        errors_checked: True if the caller built the ``error`` column itself
            as an object column of None and messages only; otherwise it is
            converted here so that it is (NaN from a frame built of rows
            becomes None).
        summary_units: summary key -> SI unit, stored as
            ``attrs["summary_units"]`` for the keys of ``summary`` (the
            command line prints them next to the values).
        **summary: scalars stored as ``attrs["summary"]``.

    Returns:
        The frame, with plain (object) column labels.
    """
    # Plain labels: pandas 3 makes the labels an Arrow-backed index, whose
    # first lookup costs ~0.1 ms (what a sweep of microsecond simulations
    # notices); an object index of the same names costs a few microseconds.
    names = frame.columns.tolist()
    if frame.columns.dtype != object:
        frame.columns = pd.Index(names, dtype=object)
    if not errors_checked and "error" in frame:
        errors = frame["error"]
        # Only a column that holds something besides None and messages (NaN
        # from a frame built of rows) needs the conversion.
        if errors.dtype != object or not set(map(type, errors.to_numpy())) <= _ERROR_TYPES:
            frame["error"] = errors.astype(object).where(errors.notna(), None)
    frame.attrs["units"] = {column: units[column] for column in names if column in units}
    if summary:
        frame.attrs["summary"] = dict(summary)
        if summary_units:
            frame.attrs["summary_units"] = {key: summary_units[key] for key in summary
                                            if key in summary_units}
    return frame


def numeric_or_nan(value: Optional[float]) -> float:
    """A float for a frame cell of a failed case (NaN marks "no value"; the
    row's ``error`` column says why)."""
    return float("nan") if value is None else float(value)


def axes(ax: Optional[Any] = None):
    """``ax``, or the Axes of a new matplotlib figure."""
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    return plt.subplots()[1]
