"""Work-precision study: error against run time for every friction formulation
and integrator (thesis section 3.2.6 and Table 3.1, with the error column the
thesis leaves out).

Each *configuration* is one call of :func:`leadscrew.simulate`: a friction
formulation, an integrator and its accuracy knob (``rtol`` for the adaptive
integrators, ``dt`` for Moreau-Jean), plus ``k_v`` for the arctan laws. The
study runs each configuration once as a warm-up (that run also gives the
error), then ``repeats`` more times for the timing, and reports medians.
"""

from __future__ import annotations

import math
import numbers
import statistics
import sys
import time
from typing import Callable, Dict, Iterable, List, Optional, Sequence, Union

import numpy as np

from .. import _core
from .._progress import shown
from ..errors import SimulationError
from ..models import FrictionBlock
from ..scene import Scene
from ..simulation import Result, _real, _whole, simulate
from ..units import channel_unit
from ._common import annotate, as_counts, check_count, in_unit, numeric_or_nan

__all__ = [
    "work_precision",
    "plot_work_precision",
    "default_configurations",
    "exact_reference",
    "CONFIGURATION_KEYS",
    "COLUMNS",
    "REFERENCE_OPTIONS",
    "ATOL_PER_RTOL",
]

#: Keys a configuration dict may hold (all are arguments of ``simulate``).
CONFIGURATION_KEYS = ("friction", "integrator", "rtol", "atol", "dt", "theta", "k_v",
                      "max_steps", "max_events", "max_step", "first_step", "smooth_integrator")

#: Columns of the frame returned by :func:`work_precision`, in order.
COLUMNS = ("label", "friction", "integrator", "k_v", "rtol", "atol", "dt", "theta",
           "error_max", "error_final", "wall_time", "wall_time_python", "steps",
           "rhs_evaluations", "events", "lcp_solves", "nonlinear_iterations", "failure")

#: The default reference: exact Coulomb friction, event-driven, near round-off.
#: (tests/test_work_precision.py checks it against the closed form to 1e-12 m.)
REFERENCE_OPTIONS = {"integrator": "event_driven", "rtol": 1e-13, "atol": 1e-15}

#: A configuration with ``rtol`` but no ``atol`` gets ``atol = ATOL_PER_RTOL * rtol``.
ATOL_PER_RTOL = 1e-2

_FIXED_STEP = ("moreau",)
_ADAPTIVE_KEYS = ("rtol", "atol", "max_step", "first_step")
_FIXED_STEP_KEYS = ("dt", "theta")
_REGULARIZED = ("arctan_velocity", "arctan_acceleration")


def default_configurations(model) -> List[Dict[str, object]]:
    """The default sweep for a model.

    For a :class:`~leadscrew.FrictionBlock` (the thesis's benchmark):

    * exact Coulomb, ``event_driven`` at rtol 1e-4 ... 1e-12;
    * exact Coulomb, ``moreau`` at dt = 2e-3 / 2^k, k = 0..4 (first order);
    * ``arctan_velocity`` (eq. 3.16) with k_V in (1, 10, 100, 1e3, 1e4) times
      the integrators ``cvode_bdf``, ``dopri5`` and ``rk_verner6`` at rtol
      1e-4, 1e-7 and 1e-10;
    * ``arctan_acceleration`` (eq. 3.15) with k_V in (1, 10, 100) and
      ``cvode_bdf`` at the same three rtol.

    For a :class:`~leadscrew.Scene`, its own friction law (a regularized
    law's gain stays the scene's: it depends on the drive) on each of the
    first three integrators that fit it (its default first): an
    error-controlled one at rtol 1e-4, 1e-6 and 1e-8, ``moreau`` at
    dt = 1e-4, 5e-5 and 2.5e-5 s.

    Args:
        model: a FrictionBlock or a Scene.

    Returns:
        A list of configuration dicts (keys from :data:`CONFIGURATION_KEYS`).

    Raises:
        ValueError: the model is neither (naming it), or a Scene whose model
            cannot be built.
    """
    if isinstance(model, Scene):
        return _scene_configurations(model)
    if not isinstance(model, _core.FrictionBlock):
        raise ValueError(f"model = {model!r} has no default configurations: they exist for a "
                         "FrictionBlock and a Scene")
    configurations: List[Dict[str, object]] = []
    for rtol in (1e-4, 1e-6, 1e-8, 1e-10, 1e-12):
        configurations.append({"friction": "coulomb", "integrator": "event_driven",
                               "rtol": rtol})
    for k in range(5):
        configurations.append({"friction": "coulomb", "integrator": "moreau",
                               "dt": 2e-3 / 2.0**k})
    tolerances = (1e-4, 1e-7, 1e-10)
    for integrator in ("cvode_bdf", "dopri5", "rk_verner6"):
        for k_v in (1.0, 10.0, 100.0, 1e3, 1e4):
            for rtol in tolerances:
                configurations.append({"friction": "arctan_velocity", "integrator": integrator,
                                       "k_v": k_v, "rtol": rtol})
    for k_v in (1.0, 10.0, 100.0):
        for rtol in tolerances:
            configurations.append({"friction": "arctan_acceleration", "integrator": "cvode_bdf",
                                   "k_v": k_v, "rtol": rtol})
    return configurations


def _scene_configurations(scene) -> List[Dict[str, object]]:
    """:func:`default_configurations` of a Scene."""
    law = scene["friction"]["law"]
    configurations: List[Dict[str, object]] = []
    for integrator in list(_core.drive_integrators(scene.model().parameters))[:3]:
        if integrator == "moreau":
            configurations += [{"friction": law, "integrator": "moreau", "dt": 1e-4 / 2.0**k}
                               for k in range(3)]
        else:
            configurations += [{"friction": law, "integrator": integrator, "rtol": rtol}
                               for rtol in (1e-4, 1e-6, 1e-8)]
    return configurations


def _quantity_for(model, quantity: Optional[str]) -> str:
    if quantity is not None:
        if not isinstance(quantity, str):
            raise ValueError(f"quantity = {quantity!r} is invalid: must be a channel name")
        return quantity
    return "u_load" if isinstance(model, Scene) else "u"


def _with_friction(model, friction: Optional[str], k_v: Optional[float]):
    """The model and the ``simulate`` friction arguments of one configuration:
    a FrictionBlock takes them as arguments, a Scene carries them in its
    friction section."""
    if isinstance(model, Scene):
        changes = {}
        if friction is not None and friction != model["friction"]["law"]:
            changes["law"] = friction
        if k_v is not None and k_v != model["friction"]["k_v"]:
            changes["k_v"] = k_v
        return (model.replace(friction=changes) if changes else model), {}
    arguments = {}
    if friction is not None:
        arguments["friction"] = friction
    if k_v is not None:
        arguments["k_v"] = k_v
    return model, arguments


def exact_reference(model, t_end: float, quantity: Optional[str] = None) -> Callable:
    """The default reference: exact Coulomb friction, event-driven at
    :data:`REFERENCE_OPTIONS` (rtol 1e-13), as a callable ``t -> quantity``.

    Each call runs the reference with ``t_eval`` at the requested times
    (sorted and made unique internally), so it is exact to the reference's
    tolerance at any time, not interpolated from a fixed grid.

    Args:
        model: a FrictionBlock or a Scene (its friction law replaced by
            ``"coulomb"``).
        t_end: end time [s], > 0.
        quantity: channel to return (default ``"u"``, ``"u_load"`` for a Scene).

    Returns:
        ``reference(t)``: the channel at the times ``t`` [s] (array, any shape
        of ``t``, each time in [0, t_end]).
    """
    quantity = _quantity_for(model, quantity)
    coulomb_model, arguments = _with_friction(model, "coulomb", None)

    def reference(t):
        t = np.asarray(t, dtype=float)
        times, inverse = np.unique(t.ravel(), return_inverse=True)
        result = simulate(coulomb_model, t_end, t_eval=times, **arguments, **REFERENCE_OPTIONS)
        return np.asarray(result[quantity])[inverse].reshape(t.shape)

    reference.description = (f"exact Coulomb, event_driven rtol={REFERENCE_OPTIONS['rtol']:g} "
                             f"atol={REFERENCE_OPTIONS['atol']:g}")
    return reference


def _column_units(frictions: Iterable[str], quantity: str) -> Dict[str, str]:
    """The unit of each of :data:`COLUMNS` (``"1"`` counts and ratios, ``""``
    labels): the errors in the quantity's, ``k_v`` in those of the laws in
    ``frictions`` that take it (``"s/m or s^2/m"`` for both arctan laws; ""
    for none), ``atol`` in SI (it bounds every coordinate in its own unit).
    """
    try:
        error = channel_unit(quantity)
    except KeyError:
        error = ""
    laws = set(frictions)
    k_v = sorted({p["unit"] for law in _core.friction_laws() if law["name"] in laws
                  for p in law["parameters"] if p["key"] == "k_v"})
    counts = ("steps", "rhs_evaluations", "events", "lcp_solves", "nonlinear_iterations")
    return {"label": "", "friction": "", "integrator": "", "k_v": " or ".join(k_v),
            "rtol": "1", "atol": "SI", "dt": "s", "theta": "1", "error_max": error,
            "error_final": error, "wall_time": "s", "wall_time_python": "s",
            **{name: "1" for name in counts}, "failure": ""}


def _check_t_end(t_end) -> float:
    t_end = in_unit("t_end", t_end, "s")
    if isinstance(t_end, bool) or not isinstance(t_end, numbers.Real) or \
            not (math.isfinite(float(t_end)) and float(t_end) > 0.0):
        raise ValueError(f"t_end = {t_end!r} is invalid: must be a finite time > 0 s")
    return float(t_end)


def _check_t_eval(t_eval, t_end: float) -> Optional[np.ndarray]:
    if t_eval is None:
        return None
    try:
        times = np.asarray(t_eval, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"t_eval = {t_eval!r} is invalid: must be a 1-D array of times") from None
    if times.ndim != 1 or times.size == 0:
        raise ValueError(f"t_eval has shape {times.shape} is invalid: must be a non-empty 1-D "
                         "array of times")
    if not np.all(np.isfinite(times)) or times[0] < 0.0 or times[-1] > t_end:
        raise ValueError(f"t_eval is invalid: its times must be finite and lie in "
                         f"[0, t_end = {t_end:g}] s")
    if np.any(np.diff(times) <= 0.0):
        raise ValueError("t_eval is invalid: its times must be strictly increasing")
    if times[-1] < t_end:  # the final-time error needs t_end
        times = np.append(times, t_end)
    return times


# The kind of each configuration value (simulate checks the ranges).
_NAME_KEYS = ("friction", "integrator", "smooth_integrator")
_WHOLE_KEYS = ("max_steps", "max_events")
_OPTIONAL_KEYS = ("dt", "max_step", "first_step")  # None: simulate's default


def _check_kinds(index: int, entry: Dict[str, object]) -> None:
    """Each value of configurations[index] is of its key's kind: a name (or
    None), a whole number or a real number (simulate's own kind checks), so
    that labels and the frame can show it; numbers are stored as int and
    float. ValueError naming the entry."""
    for key, value in entry.items():
        name = f"configurations[{index}]: {key}"
        if key in _NAME_KEYS:
            if value is not None and not isinstance(value, str):
                raise ValueError(f"{name} = {value!r} is invalid: must be a name (a string) "
                                 "or None")
        elif key in _WHOLE_KEYS:
            entry[key] = _whole(name, value)
        elif not (key in _OPTIONAL_KEYS and value is None):
            entry[key] = _real(name, value)


def _check_configurations(model, configurations) -> List[Dict[str, object]]:
    if configurations is None:
        configurations = default_configurations(model)
    if isinstance(configurations, (dict, str)) or not isinstance(configurations, Iterable):
        raise ValueError(f"configurations = {configurations!r} is invalid: must be a list of "
                         "dicts of simulate arguments")
    checked = []
    for i, configuration in enumerate(configurations):
        if not isinstance(configuration, dict):
            raise ValueError(f"configurations[{i}] = {configuration!r} is invalid: must be a dict")
        unknown = sorted(set(configuration) - set(CONFIGURATION_KEYS))
        if unknown:
            raise ValueError(f"configurations[{i}] has the unknown key {unknown[0]!r}; allowed "
                             f"keys are {', '.join(CONFIGURATION_KEYS)}")
        entry = dict(configuration)
        _check_kinds(i, entry)
        friction = entry.get("friction")
        if friction is None:
            friction = model["friction"]["law"] if isinstance(model, Scene) else "coulomb"
            entry["friction"] = friction
        integrator = entry.get("integrator")
        if integrator in _FIXED_STEP:
            misplaced = [key for key in _ADAPTIVE_KEYS if key in entry]
            if misplaced:
                raise ValueError(f"configurations[{i}]: {misplaced[0]} = {entry[misplaced[0]]!r} "
                                 f"is invalid with integrator {integrator!r}, which takes dt "
                                 "and theta")
        else:
            misplaced = [key for key in _FIXED_STEP_KEYS if key in entry]
            if misplaced:
                raise ValueError(f"configurations[{i}]: {misplaced[0]} = {entry[misplaced[0]]!r} "
                                 f"is invalid with integrator {integrator!r}: only 'moreau' "
                                 "takes dt and theta")
            if "rtol" in entry and "atol" not in entry:  # (a float: _check_kinds)
                entry["atol"] = ATOL_PER_RTOL * entry["rtol"]
        if "k_v" in entry and friction not in _REGULARIZED:
            raise ValueError(f"configurations[{i}]: k_v = {entry['k_v']!r} is invalid with "
                             f"friction {friction!r}: only {', '.join(_REGULARIZED)} take k_v")
        checked.append(entry)
    if not checked:
        raise ValueError("configurations is invalid: it is empty")
    return checked


def _check_reference(reference, model, t_end, quantity):
    """(callable t -> values, fixed times or None, description)."""
    if reference is None:
        function = exact_reference(model, t_end, quantity)
        return function, None, function.description
    if isinstance(reference, Result):
        if quantity not in reference:
            raise ValueError(f"reference is invalid: the Result has no channel {quantity!r} "
                             f"(it has {', '.join(reference.channels)})")
        times = np.asarray(reference.t, dtype=float)
        values = np.asarray(reference[quantity], dtype=float)
        # An event appears twice (values before and after); the position is
        # continuous, so keep the first of each time.
        times, first = np.unique(times, return_index=True)
        values = values[first]
        if times[-1] != t_end:
            raise ValueError(f"reference is invalid: the Result ends at {times[-1]:g} s, "
                             f"not at t_end = {t_end:g} s")

        def lookup(t):
            t = np.asarray(t, dtype=float)
            index = np.searchsorted(times, t)
            index = np.clip(index, 0, times.size - 1)
            if np.any(times[index] != t):
                missing = float(t[times[index] != t].ravel()[0])
                raise ValueError(f"reference is invalid: the Result has no output at t = "
                                 f"{missing!r} s; run it with t_eval equal to the study's "
                                 "t_eval, or pass a callable")
            return values[index]

        return lookup, times, f"Result ({reference.friction}/{reference.integrator})"
    if callable(reference):
        return reference, None, getattr(reference, "description", "callable")
    raise ValueError(f"reference = {reference!r} is invalid: must be None, a callable t -> "
                     f"{quantity} or a leadscrew Result")


def _label(entry: Dict[str, object]) -> str:
    friction = entry["friction"]
    integrator = entry.get("integrator") or "default"
    gain = f" k_V={entry['k_v']:g}" if "k_v" in entry else ""
    knob = f"dt={entry['dt']:g}" if entry.get("dt") is not None else (
        f"rtol={entry['rtol']:g}" if "rtol" in entry else "defaults")
    return f"{friction}{gain} {integrator} {knob}"


def work_precision(
    model,
    t_end: float,
    configurations: Optional[Sequence[Dict[str, object]]] = None,
    reference: Union[None, Callable, Result] = None,
    t_eval: Optional[Sequence[float]] = None,
    repeats: int = 5,
    quantity: Optional[str] = None,
    on_failure: str = "record",
    progress: bool = False,
    ax=None,
):
    """Error against run time for a set of simulate configurations.

    For each configuration the model is simulated once (warm-up; this run
    also gives the error) and then ``repeats`` times for the timing.

    Args:
        model: a :class:`~leadscrew.FrictionBlock` or a :class:`~leadscrew.Scene`
            (a configuration's ``friction`` and ``k_v`` then replace the scene's
            friction law and gain).
        t_end: end time [s], > 0.
        configurations: list of dicts of :func:`~leadscrew.simulate` arguments
            (keys in :data:`CONFIGURATION_KEYS`: ``friction``, ``integrator``,
            ``rtol``, ``atol``, ``dt``, ``theta``, ``k_v``, ...). A missing
            ``atol`` is ``ATOL_PER_RTOL * rtol``. Default:
            :func:`default_configurations` (a FrictionBlock's or a Scene's).
        reference: what the errors are measured against:
            ``None`` (default): exact Coulomb friction, event-driven at rtol
            1e-13 (:func:`exact_reference`; for the thesis block it matches
            the closed-form solution to 1e-13 m, tested); a callable
            ``t -> values`` (e.g. a closed form, vectorised over an array of
            times [s]); or a :class:`~leadscrew.Result` whose output times
            contain every compared time (``t_eval`` then defaults to its
            times; at a time listed twice, an event, the first value is used,
            so compare continuous channels such as u).
        t_eval: times [s] (strictly increasing, in [0, t_end]; t_end is
            appended if missing) at which the runs report and the errors are
            taken. Default None: every run reports at its own steps and
            events, its natural cost, and is compared there. Note that with
            ``t_eval`` the integrators stop at every output time, which adds
            steps.
        repeats: timed runs per configuration (>= 1); times are medians.
        quantity: the compared channel (default ``"u"``; ``"u_load"`` for a Scene).
        on_failure: ``"record"`` (default): a configuration whose run raises
            :class:`~leadscrew.SimulationError` gets a row with NaN errors and
            times and the message in ``failure``, and the summary counts
            them (one :class:`~leadscrew.StudyWarning` names them);
            ``"raise"``: the error propagates.
        progress: print one line per configuration to stderr (where it is a
            terminal: :func:`leadscrew._progress.shown`).
        ax: a matplotlib Axes to draw the diagram on (see :func:`plot_work_precision`).

    Returns:
        pandas.DataFrame with one row per configuration and the columns
        :data:`COLUMNS`: ``label``; ``friction``, ``integrator``, ``k_v``,
        ``rtol``, ``atol``, ``dt``, ``theta`` (NaN where they do not apply);
        ``error_max`` = max |q - q_ref| over the compared times and
        ``error_final`` = |q(t_end) - q_ref(t_end)| [unit of the quantity,
        m for u]; ``wall_time`` (median, measured inside C++) and
        ``wall_time_python`` (median around the ``simulate`` call) [s];
        ``steps``, ``rhs_evaluations``, ``events``, ``lcp_solves``,
        ``nonlinear_iterations``; ``failure`` (empty string, or
        ``"ExceptionType: message"``). ``frame.attrs`` holds ``reference``,
        ``quantity``, ``t_end``, ``repeats``, ``units`` (each column's,
        :func:`_column_units`) and the ``summary``: ``raised`` [1] and
        ``raised_reasons`` (the configurations that raised: their count, and
        their exception types with the first message, or ``"none"``).

    Raises:
        ValueError: a bad argument (the message names it), including a bad
            configuration (``configurations[i]: ...``).
        SimulationError: a run failed and ``on_failure="raise"``.
    """
    progress = shown(progress)
    import pandas as pd

    if not isinstance(model, (_core.FrictionBlock, Scene)):
        raise ValueError(f"model = {model!r} is invalid: must be a FrictionBlock or a Scene")
    t_end = _check_t_end(t_end)
    repeats = check_count("repeats", repeats, 1)
    if on_failure not in ("record", "raise"):
        raise ValueError(f"on_failure = {on_failure!r} is invalid: must be \"record\" or \"raise\"")
    quantity = _quantity_for(model, quantity)
    entries = _check_configurations(model, configurations)
    times = _check_t_eval(t_eval, t_end)
    reference_function, reference_times, description = _check_reference(
        reference, model, t_end, quantity)
    if times is None and reference_times is not None:
        times = reference_times

    rows = []
    for i, entry in enumerate(entries):
        friction = entry["friction"]
        run_model, friction_arguments = _with_friction(model, friction, entry.get("k_v"))
        arguments = {key: value for key, value in entry.items() if key not in ("friction", "k_v")}
        arguments.update(friction_arguments)
        arguments["t_eval"] = times if times is not None else "steps"
        row = {
            "label": _label(entry),
            "friction": friction,
            "integrator": entry.get("integrator"),
            "k_v": numeric_or_nan(entry.get("k_v")),
            "rtol": numeric_or_nan(entry.get("rtol")),
            "atol": numeric_or_nan(entry.get("atol")),
            "dt": numeric_or_nan(entry.get("dt")),
            "theta": numeric_or_nan(entry.get("theta")),
            "failure": "",
        }
        try:
            try:
                result = simulate(run_model, t_end, **arguments)
            except ValueError as error:
                raise ValueError(f"configurations[{i}]: {error}") from None
            core_times, python_times = [], []
            for _ in range(repeats):
                start = time.perf_counter()
                timed = simulate(run_model, t_end, **arguments)
                python_times.append(time.perf_counter() - start)
                core_times.append(timed.stats["wall_time"])
        except SimulationError as error:
            if on_failure == "raise":
                raise
            row.update(error_max=math.nan, error_final=math.nan, wall_time=math.nan,
                       wall_time_python=math.nan, steps=0, rhs_evaluations=0, events=0,
                       lcp_solves=0, nonlinear_iterations=0,
                       failure=f"{type(error).__name__}: {error}")
            rows.append(row)
            if progress:
                print(f"[{i + 1}/{len(entries)}] {row['label']}: FAILED {error}", file=sys.stderr)
            continue
        if quantity not in result:
            raise ValueError(f"quantity = {quantity!r} is invalid: the result has the channels "
                             f"{', '.join(result.channels)}")
        result_times = np.asarray(result.t, dtype=float)
        values = np.asarray(result[quantity], dtype=float)
        expected = np.asarray(reference_function(result_times), dtype=float)
        if expected.shape != result_times.shape:
            raise ValueError(f"reference is invalid: it returned shape {expected.shape} for "
                             f"{result_times.shape} times")
        difference = np.abs(values - expected)
        if not np.all(np.isfinite(difference)):
            raise ValueError(f"reference is invalid: it returned non-finite values for "
                             f"{row['label']}")
        stats = result.stats
        row.update(
            error_max=float(np.max(difference)),
            error_final=float(difference[-1]),
            wall_time=statistics.median(core_times),
            wall_time_python=statistics.median(python_times),
            steps=int(stats["steps"]),
            rhs_evaluations=int(stats["rhs_evaluations"]),
            events=int(stats["events"]),
            lcp_solves=int(stats["lcp_solves"]),
            nonlinear_iterations=int(stats["nonlinear_iterations"]),
        )
        rows.append(row)
        if progress:
            print(f"[{i + 1}/{len(entries)}] {row['label']}: error {row['error_max']:.2e}, "
                  f"{row['wall_time'] * 1e6:.0f} us", file=sys.stderr)

    frame = as_counts(pd.DataFrame(rows, columns=list(COLUMNS)))
    frame.attrs.update(reference=description, quantity=quantity, t_end=t_end, repeats=repeats)
    # The units of every column; the configurations that raised: counted in
    # the summary, and a StudyWarning.
    annotate(frame, _column_units(frame["friction"], quantity), errors_checked=True,
             study="work_precision")
    if ax is not None:
        plot_work_precision(frame, ax=ax)
    return frame


_LINE_STYLES = ("-", "--", ":", "-.")
_MARKERS = ("o", "^", "s", "D", "v", "P", "X", "*")
_EXACT_COLORS = ("black", "dimgray", "darkgray")
_GAIN_COLORMAPS = {"arctan_velocity": "viridis", "arctan_acceleration": "autumn"}


def plot_work_precision(frame, ax=None, time: str = "wall_time", error: str = "error_max"):
    """Draw the work-precision diagram: error against run time, log-log.

    One line per (friction, integrator, k_V), its points ordered from the
    loosest to the tightest tolerance (or the largest to the smallest dt).
    Exact Coulomb friction is drawn in black/gray; each regularized law has a
    colormap over log k_V; the integrator sets marker and line style.
    Failed configurations (NaN) are left out.

    Args:
        frame: the DataFrame of :func:`work_precision`.
        ax: matplotlib Axes (default: a new figure's).
        time: the time column, ``"wall_time"`` (inside C++) or
            ``"wall_time_python"``.
        error: the error column, ``"error_max"`` or ``"error_final"``.

    Returns:
        The Axes.

    Raises:
        ValueError: a column is missing or not a time/error column.
    """
    import matplotlib

    if time not in ("wall_time", "wall_time_python"):
        raise ValueError(f"time = {time!r} is invalid: must be \"wall_time\" or "
                         "\"wall_time_python\"")
    if error not in ("error_max", "error_final"):
        raise ValueError(f"error = {error!r} is invalid: must be \"error_max\" or \"error_final\"")
    missing = [c for c in ("friction", "integrator", "k_v", "rtol", "dt", time, error)
               if c not in getattr(frame, "columns", ())]
    if missing:
        raise ValueError(f"frame is invalid: it lacks the column {missing[0]!r} (pass the "
                         "frame of work_precision)")
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(9, 5.5))
    usable = frame[np.isfinite(frame[time]) & np.isfinite(frame[error]) & (frame[error] > 0)]
    integrators = list(dict.fromkeys(usable["integrator"].fillna("default")))
    gains = usable["k_v"].dropna()
    low, high = (np.log10(gains.min()), np.log10(gains.max())) if len(gains) else (0.0, 1.0)
    exact_index = 0
    keys = ["friction", "integrator", "k_v"]
    grouped = usable.assign(k_v=usable["k_v"].fillna(-1.0),
                            integrator=usable["integrator"].fillna("default"))
    for (friction, integrator, k_v), group in grouped.groupby(keys, sort=False):
        # Loosest first: descending dt, then descending rtol.
        order = group.sort_values(["dt", "rtol"], ascending=False, na_position="last")
        style = integrators.index(integrator)
        if k_v > 0:
            colormap = matplotlib.colormaps[_GAIN_COLORMAPS.get(friction, "plasma")]
            position = 0.5 if high == low else (np.log10(k_v) - low) / (high - low)
            color = colormap(0.85 * position)
            label = f"{friction} $k_V$={k_v:g} / {integrator}"
        else:
            color = _EXACT_COLORS[exact_index % len(_EXACT_COLORS)]
            exact_index += 1
            label = f"{friction} / {integrator}"
        ax.loglog(order[time], order[error], color=color,
                  marker=_MARKERS[style % len(_MARKERS)],
                  linestyle=_LINE_STYLES[style % len(_LINE_STYLES)],
                  markersize=4, linewidth=1, label=label)
    ax.set_xlabel("run time [s] (median, " +
                  ("inside C++)" if time == "wall_time" else "through Python)"))
    ax.set_ylabel(("max" if error == "error_max" else "final-time") + " error of "
                  + str(frame.attrs.get("quantity", "u")))
    ax.grid(True, which="both", linewidth=0.3)
    if len(usable):
        ax.legend(fontsize="x-small", loc="upper left", bbox_to_anchor=(1.01, 1.0),
                  borderaxespad=0.0)
    else:  # every configuration failed or was exact: nothing to draw on log axes
        ax.text(0.5, 0.5, "no configuration with a finite error > 0", ha="center",
                va="center", transform=ax.transAxes)
    ax.set_title("work-precision: error against run time")
    return ax
