"""Helpers shared by the studies: argument checks, scene edits, frame metadata."""

from __future__ import annotations

import functools
import math
import numbers
import sys
import warnings
from typing import Any, Dict, Iterable, Optional, Tuple

import numpy as np
import pandas as pd

from ..errors import StudyWarning
from ..scene import Scene
from ..units import to_si

__all__ = [
    "as_scene",
    "in_unit",
    "check_finite",
    "check_positive",
    "check_count",
    "check_grid",
    "with_tolerances",
    "with_loads",
    "annotate",
    "raised_rows",
    "frame_of",
    "numeric_or_nan",
    "as_counts",
    "axes",
]


def as_scene(scene: Any, gear: bool = False) -> Scene:
    """A :class:`~leadscrew.Scene` from a Scene or a scene dict.

    Args:
        gear: the study's closed forms take an ideal gear stage (the rotor's
            torque and speed reflected through its ratio).

    Raises:
        ValueError: ``scene`` is neither, the dict is not a valid scene, or the
            scene has a gear stage and the study's closed forms have none.
    """
    if isinstance(scene, Scene):
        out = scene
    elif isinstance(scene, dict):
        out = Scene.from_dict(scene)
    else:
        raise ValueError(f"scene = {scene!r} is invalid: must be a leadscrew.Scene or a scene "
                         "dict")
    # The studies' closed forms are the bare drive's (the rotor turning the
    # screw or the nut directly): a gear stage would put them beside a
    # different train.
    stage = out.to_dict().get("gear")
    if stage is not None and not gear:
        raise ValueError(f"gear = {stage!r} is invalid for this study: must be absent (the "
                         "studies' closed forms are those of a rotor turning the screw or the "
                         "nut directly; simulate a geared drive with leadscrew.simulate)")
    return out


def constant_value(load: Any) -> Optional[float]:
    """The value of a scene's load (or motor voltage) entry where it is
    constant: a number, ``{"type": "constant", "value": ...}`` or a
    :class:`~leadscrew.Constant`; None for any other excitation."""
    from ..excitation import Constant

    if isinstance(load, numbers.Real) and not isinstance(load, bool):
        return float(load)
    if isinstance(load, dict) and load.get("type") == "constant":
        return float(load["value"])
    if isinstance(load, Constant):
        return float(load.value)
    return None


def gear_ratio(scene: Scene) -> float:
    """The ratio n of the scene's gear stage: the rotor turns n times per turn
    of the driven part (n < 0: reversing; 1 without a stage)."""
    return scene["gear"]["ratio"] if "gear" in scene else 1.0


def in_unit(name: str, value: Any, unit: Optional[str]) -> Any:
    """A study argument given as a string with a unit (``"20 N"``, ``"5 Hz"``)
    as a number in ``unit``, as a scene's field (:func:`leadscrew.units.to_si`);
    any other value, or any value where ``unit`` is None (a count, a flag),
    is returned as it is (for the checks that follow to name).

    Raises:
        ValueError: a string of another dimension, or no number with a unit,
            naming the argument: ``amplitude = "20 m" is invalid: "20 m" is
            not a force (N)``.
    """
    if unit is None or not isinstance(value, str):
        return value
    return to_si(name, value, unit)


def check_finite(name: str, value: Any, unit: Optional[str] = None) -> float:
    """``value`` as a float, a finite number (a string with a unit converted
    to ``unit``: :func:`in_unit`).

    Raises:
        ValueError: naming the parameter and the value.
    """
    value = in_unit(name, value, unit)
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value):
        raise ValueError(f"{name} = {value!r} is invalid: must be a finite number")
    return float(value)


def check_positive(name: str, value: Any, allow_zero: bool = False,
                   unit: Optional[str] = None) -> float:
    """``value`` as a float, finite and > 0 (>= 0 with ``allow_zero``; a
    string with a unit converted to ``unit``: :func:`in_unit`).

    Raises:
        ValueError: naming the parameter, the value and the valid range.
    """
    value = in_unit(name, value, unit)
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


def check_grid(name: str, values: Iterable[float], allow_zero: bool = False,
               unit: Optional[str] = None) -> np.ndarray:
    """A non-empty 1-D array of finite values > 0 (>= 0 with ``allow_zero``).

    With ``unit``, entries may be strings with units (``["5 Hz", "10 Hz"]``,
    or one string for one value), converted to ``unit`` (:func:`in_unit`).

    Raises:
        ValueError: naming the parameter, the offending value and the valid
            range; a string entry of another dimension naming its index
            (``frequencies[1] = "5 N" is invalid: ...``).
    """
    if unit is not None:
        if isinstance(values, str):
            values = [in_unit(name, values, unit)]
        elif (isinstance(values, (list, tuple)) or (isinstance(values, np.ndarray)
                                                    and values.dtype.kind in "UO"
                                                    and values.ndim == 1)) \
                and any(isinstance(v, str) for v in values):
            values = [in_unit(f"{name}[{i}]", v, unit) for i, v in enumerate(values)]
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


def check_window(window: Any, t_end: float, start_fraction: float) -> Tuple[float, float]:
    """A measurement window (start, end) [s] within the run.

    Args:
        window: (start, end), numbers [s] or strings with units; None: from
            ``start_fraction * t_end`` to ``t_end``.
        t_end: the run's end [s].
        start_fraction: where the default window starts, a fraction of t_end.

    Returns:
        (start, end) in s, 0 <= start < end <= t_end.

    Raises:
        ValueError: naming ``window``, its value and what is allowed.
    """
    if window is None:
        window = (start_fraction * t_end, t_end)
    # (start, end) may be strings with units, as the other arguments
    times = ([in_unit(f"window[{i}]", w, "s") for i, w in enumerate(window)]
             if isinstance(window, (list, tuple)) else window)
    try:
        start, end = (float(w) for w in times)
    except (TypeError, ValueError):
        raise ValueError(f"window = {window!r} is invalid: must be (start, end) in s") from None
    if not (0.0 <= start < end <= t_end):
        raise ValueError(f"window = {window!r} is invalid: must satisfy 0 <= start < end <= "
                         f"t_end = {t_end:g}")
    return start, end


def with_tolerances(options: Dict[str, Any], rtol: Any = None, atol: Any = None
                    ) -> Dict[str, Any]:
    """:func:`leadscrew.simulate`'s keywords ``options`` with the study's
    ``rtol`` and ``atol`` where given (None: the scene's [simulation] ones, else
    simulate's default, 1e-8 and 1e-10), so that simulate refuses them only where the user gave them
    (``integrator="moreau"`` takes neither)."""
    options = dict(options)
    for name, value in (("rtol", rtol), ("atol", atol)):
        if value is not None:
            options[name] = value
    return options


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
             summary_units: Optional[Dict[str, str]] = None, study: Optional[str] = None,
             **summary: Any):
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
        study: the name of a study whose rows are cases that may raise
            (their ``error`` column, work_precision's ``failure``, holds
            the message): the summary gets ``raised`` [1] and
            ``raised_reasons`` (:func:`raised_rows`), and where a row
            raised, a :class:`~leadscrew.StudyWarning` says so (as the
            command line does). None: a frame of one run, no such rows.
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
    if study is not None:
        count, reasons = raised_rows(frame)
        summary.update(raised=count, raised_reasons=reasons)
        summary_units = dict(summary_units or {}, raised="1")
        if count:
            warnings.warn(f"{study}: {count} of {len(frame)} rows raised and decide nothing "
                          f"(their error column says why): {reasons}", StudyWarning,
                          stacklevel=_caller_level())
    if summary:
        frame.attrs["summary"] = dict(summary)
        if summary_units:
            frame.attrs["summary_units"] = {key: summary_units[key] for key in summary
                                            if key in summary_units}
    return frame


#: The columns in which a study's row carries the message of a case that raised.
FAILURE_COLUMNS = ("error", "failure")


def _message(value: Any) -> str:
    """A failure cell as one line ("" where the case ran: None, NaN, "")."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return ""
    return " ".join(str(value).split())


def raised_rows(frame) -> Tuple[int, str]:
    """The rows of a study's frame whose case raised, and why.

    A row raised if its ``error`` (or work_precision's ``failure``) column
    holds a message, ``"ExceptionType: message"``.

    Args:
        frame: the study's DataFrame.

    Returns:
        ``(count, reasons)``: the number of such rows, and ``"none"`` or
        their exception types with counts, most frequent first, and the
        first message: ``"2 JammingError, 1 SimulationError; first:
        JammingError: ..."``.
    """
    messages = []
    for column in FAILURE_COLUMNS:
        if column in frame:
            messages.extend(m for m in map(_message, frame[column].tolist()) if m)
    if not messages:
        return 0, "none"
    kinds: Dict[str, int] = {}
    for message in messages:
        kind = message.split(":", 1)[0]
        kind = kind if ":" in message and kind.isidentifier() else "error"
        kinds[kind] = kinds.get(kind, 0) + 1
    counted = ", ".join(f"{n} {kind}" for kind, n in
                        sorted(kinds.items(), key=lambda item: (-item[1], item[0])))
    return len(messages), f"{counted}; first: {messages[0]}"


def _caller_level() -> int:
    """The stacklevel of warnings.warn that points at the first frame outside
    this package (the user's call of the study)."""
    level, frame = 2, sys._getframe(2)
    while frame is not None and frame.f_globals.get("__name__", "").startswith("leadscrew."):
        frame, level = frame.f_back, level + 1
    return level


def numeric_or_nan(value: Optional[float]) -> float:
    """A float for a frame cell of a failed case (NaN marks "no value"; the
    row's ``error`` column says why)."""
    return float("nan") if value is None else float(value)


#: The columns of a study's frame that count (steps, events, ...): integers.
COUNT_COLUMNS = ("steps", "events", "separations", "rhs_evaluations", "lcp_solves",
                 "nonlinear_iterations")


def as_counts(frame: pd.DataFrame) -> pd.DataFrame:
    """``frame`` with its count columns (:data:`COUNT_COLUMNS`, those it
    has) as integers: pandas' nullable ``Int64``, whose missing value
    (``<NA>``) marks a case that raised, as NaN does in a float column (a
    float column of step counts reads 1234.0)."""
    for name in COUNT_COLUMNS:
        if name in frame.columns:
            frame[name] = frame[name].astype("Int64")
    return frame


def axes(ax: Optional[Any] = None):
    """``ax``, or the Axes of a new matplotlib figure."""
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    return plt.subplots()[1]
