"""``simulate``: run a model and get its time series, events and statistics."""

from __future__ import annotations

import functools
import inspect
import math
import numbers
import operator
from typing import Any, Callable, Dict, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from . import _core
from ._hints import did_you_mean
from ._progress import shown
from .models import FrictionBlock
from .scene import SCHEMA, Scene, _friction_law_entry, _friction_registry
from .units import channel_unit
# (the option rules, re-exported: the command line, the studies and the
# Scene import them from here)
from ._option_rules import (ADAPTIVE_OPTIONS, MOREAU_OPTIONS, SCENE_OPTIONS,  # noqa: F401
                            _choose_integrator, _play_of, _scalar, _shown,
                            _stored_option_errors, check_integrator_name,
                            integrator_taking, option_conflict,
                            scene_options, takes_option, unused_option)

__all__ = ["simulate", "Result", "Event"]


class Event(NamedTuple):
    """A mode change: time [s] and kind, e.g. ``"slip+->stick"``."""

    time: float
    kind: str


class Result:
    """Time series of a simulation.

    Attributes:
        t: output times [s] (at an event the time appears twice: the values
            just before and just after it, unless ``t_eval`` gave the times;
            by default a long run's steps are sampled: ``simulate``'s
            ``t_eval``).
        events: list of :class:`Event`.
        stats: dict with ``steps``, ``rhs_evaluations``, ``events``,
            ``lcp_solves``, ``restarts``, ``nonlinear_iterations`` and
            ``wall_time`` [s, measured inside C++].
        integrator, friction: what ran.

    ``result[name]`` gives a channel as a numpy array (``result["t"]`` the
    times, as every channel; ``"t" in result`` holds, though ``t`` is the
    time axis and not in ``result.channels``, which lists the names);
    :meth:`units` gives their SI units; :meth:`to_frame` gives a pandas
    DataFrame.

    Every attribute is converted from the core's result on first use and
    kept: a caller that reads ``t`` and one channel pays for those alone
    (a short simulation costs a few microseconds, the conversions would
    double it). A pickled Result carries the converted values.
    """

    __slots__ = ("_core", "_t", "_channels", "_data", "_events", "_stats", "_names", "_rows",
                 "_checks", "_sampled")

    def __init__(self, core_result):
        self._core = core_result
        self._t = self._channels = self._data = self._events = self._stats = self._names = None
        self._checks = None
        self._rows = {}  # channels converted one by one (before the whole matrix)
        self._sampled = False  # the steps sampled down (simulate's default output)

    def __reduce__(self):
        state = (self.t, self.channels, self._matrix(), self.events, self.stats,
                 self.integrator, self.friction, self.checks)
        return (_restore_result, state)

    @property
    def t(self) -> np.ndarray:
        if self._t is None:
            self._t = self._core.time
        return self._t

    @property
    def channels(self) -> list:
        if self._channels is None:
            self._channels = self._core.channel_names
        return self._channels

    @property
    def events(self) -> list:
        if self._events is None:
            self._events = [Event(time, kind) for time, kind in self._core.events]
        return self._events

    @property
    def checks(self) -> dict:
        """The invariants the run was checked for: name -> dict with
        ``what``, ``applies``, ``passed``, ``value`` (the worst seen),
        ``bound``, ``margin`` (bound - value), ``time`` [s] where the worst
        was seen and ``unit`` (docs/physics/result_checks.md)."""
        if self._checks is None:
            self._checks = self._core.checks
        return self._checks

    @property
    def stats(self) -> dict:
        if self._stats is None:
            self._stats = self._core.stats
        return self._stats

    def _what_ran(self) -> tuple:
        if self._names is None:
            self._names = (self._core.integrator, self._core.friction)
        return self._names

    @property
    def integrator(self) -> str:
        return self._what_ran()[0]

    @property
    def friction(self) -> str:
        return self._what_ran()[1]

    def _matrix(self) -> np.ndarray:
        if self._data is None:
            self._data = self._core.channels
        return self._data

    def __getitem__(self, name: str) -> np.ndarray:
        if self._data is None and self._core is not None:
            # One channel without converting the others (or their names).
            row = self._rows.get(name) if isinstance(name, str) else None
            if row is None and isinstance(name, str):
                row = self._core.channel(name)
                if row is not None:
                    self._rows[name] = row
            if row is not None:
                return row
        elif name in self.channels:
            return self._matrix()[self.channels.index(name)]
        if name == "t":
            return self.t
        raise KeyError(f"no channel {name!r}; channels are {['t'] + list(self.channels)}")

    def __contains__(self, name: str) -> bool:
        return name == "t" or name in self.channels

    def keys(self):
        return list(self.channels)

    def units(self) -> dict:
        """The SI unit of ``t`` and of every channel, in the frame's order.

        Returns:
            dict name -> unit text (``"s"``, ``"m"``, ``"rad/s"``, ``"N*m"``,
            ``"J"``, ...; ``""`` for the flag ``stick``), see
            :func:`leadscrew.units.channel_unit`.
        """
        return {name: channel_unit(name) for name in ["t", *self.channels]}

    def to_frame(self):
        """The time series as a pandas DataFrame with a column ``t``.

        ``frame.attrs["units"]`` holds the SI unit of every column (as
        :meth:`units`).
        """
        import pandas as pd

        frame = pd.DataFrame(self._matrix().T, columns=self.channels)
        frame.insert(0, "t", self.t)
        frame.attrs["units"] = self.units()
        return frame

    def plot(self, kind: str = "time_series", title: Optional[str] = None):
        """Draw the result (:func:`leadscrew.plotting.plot_result`).

        Args:
            kind: ``"time_series"`` (position, speed, forces, torque, a DC
                motor's current over time) or ``"energy"`` (the energy
                account and its residual).
            title: the figure's title (default none).

        Returns:
            A :class:`matplotlib.figure.Figure` (``.savefig(path)`` writes it).

        Raises:
            ValueError: an unknown ``kind``, or a FrictionBlock's result.
        """
        from .plotting import plot_result

        return plot_result(self, kind, title)

    def __repr__(self) -> str:
        return (f"<Result {self.friction}/{self.integrator}: {len(self.t)} points, "
                f"{len(self.events)} events, {self.stats['wall_time'] * 1e6:.0f} us>")


def _restore_result(t, channels, data, events, stats, integrator, friction,
                    checks=None) -> Result:
    result = Result(None)
    result._t, result._channels, result._data = t, channels, data
    result._events, result._stats, result._names = events, stats, (integrator, friction)
    result._checks = checks
    return result


@functools.lru_cache(maxsize=None)
def _block_integrators(friction: str) -> Tuple[str, ...]:
    """The integrators that run a FrictionBlock with the law ``friction``,
    the default first (the core's list, fixed per law: looked up once)."""
    return tuple(_core.block_integrators(friction))


@functools.lru_cache(maxsize=None)
def _law_parameter_keys(friction: str) -> Tuple[str, ...]:
    """The keys of the law's parameters (a law of the registry)."""
    return tuple(p["key"] for p in _law(friction)["parameters"])


@functools.lru_cache(maxsize=None)
def _law(name: str) -> Optional[dict]:
    """The registry's entry of a friction law (None: no such law; the core
    names the laws); looked up once per name (a scan of the registry took
    microseconds a call)."""
    return _friction_law_entry(name)


def _check_scene_friction(scene: Scene, friction: Optional[str], k_v=None) -> None:
    """A Scene carries its friction law and gain: ``friction`` and ``k_v``
    may only repeat them (another value would be ignored)."""
    if friction is not None and friction != scene["friction"]["law"]:
        raise ValueError(f"friction = {friction!r} is invalid for a Scene: set the "
                         f"scene's friction.law (it is {scene['friction']['law']!r})")
    if k_v is not None and k_v != scene["friction"]["k_v"]:
        raise ValueError(f"k_v = {k_v!r} is invalid for a Scene: set the scene's friction.k_v "
                         f"(it is {scene['friction']['k_v']!r})")


def _unknown_scene_option(name: str, value) -> ValueError:
    """The error of a keyword simulate() does not take for a Scene: a
    friction law's parameter (a FrictionBlock's keyword; a Scene carries its
    law's in its friction section) or an unknown option (with a close match
    and the list)."""
    laws = [law["name"] for law in _friction_registry()
            if any(p["key"] == name for p in law["parameters"])]
    if laws or name in _SCENE_FRICTION_KEYS:
        taken = (f" (a parameter of the friction law{'s' if len(laws) > 1 else ''} "
                 f"{', '.join(map(repr, laws))})" if laws else "")
        return ValueError(f"{name} = {_shown(value)} is invalid for a Scene: set the scene's "
                          f"friction.{name}{taken}")
    options = [option for option in _SIGNATURE if option not in ("model", "t_end")]
    hint = did_you_mean(name, options)
    return ValueError(f"{name} = {_shown(value)} is invalid: simulate() has no option {name!r}"
                      f"{hint}; for a Scene it takes {', '.join(options)}")


def _law_keys() -> set:
    """The keys of every friction law's parameters."""
    return {p["key"] for law in _friction_registry() for p in law["parameters"]}


def _unknown_block_option(name: str, value, friction: str, takes: Sequence[str]) -> ValueError:
    """The error of a keyword that is neither simulate()'s nor a parameter of
    the block's friction law (with a close match and both lists)."""
    options = [option for option in _SIGNATURE if option not in ("model", "t_end")]
    hint = did_you_mean(name, [*options, *takes])
    return ValueError(f"{name} = {_shown(value)} is invalid: simulate() has no option {name!r} and "
                      f"the friction law {friction!r} no parameter {name!r}{hint}; simulate "
                      f"takes {', '.join(options)}, the law {', '.join(takes)}")


def _check_block_options(**options) -> None:
    """Options only a Scene's simulation takes must be None for a FrictionBlock
    (a value would be ignored)."""
    for name, value in options.items():
        if value is not None:
            raise ValueError(f"{name} = {value!r} is invalid for a FrictionBlock: only a "
                             "Scene's simulation takes it")


def _real(name: str, value) -> float:
    """``value`` as a float, if it is a real number (not a bool or a string:
    the core checks the range, this only the kind, naming the option)."""
    if type(value) is float:  # the common case, without the abstract-class checks
        return value
    value = _scalar(value)
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name} = {value!r} is invalid: must be a number")
    try:
        return float(value)
    except OverflowError:  # an int beyond a float
        raise ValueError(f"{name} = {value!r} is invalid: must be a finite number") from None


def _whole(name: str, value, limit: int = 2 ** 63 - 1) -> int:
    """``value`` as an int, if it is a whole number (``1e6`` is; 1.5 is not)
    of at most ``limit`` in magnitude (the core's integer)."""
    if type(value) is int and -limit <= value <= limit:  # the common case
        return value
    value = _scalar(value)
    whole = isinstance(value, numbers.Integral) or (
        isinstance(value, numbers.Real) and math.isfinite(value) and value == int(value))
    if isinstance(value, bool) or not whole:
        raise ValueError(f"{name} = {value!r} is invalid: must be an integer")
    if abs(int(value)) > limit:
        raise ValueError(f"{name} = {value!r} is invalid: must be an integer of at most "
                         f"{limit} in magnitude")
    return int(value)


#: The rows a run keeps by default (``t_eval`` None), besides its events'
#: rows and its two ends: a long run's integrator steps are sampled down to
#: about this many (a 2 s seat adjuster's run takes 116,242 steps).
DEFAULT_ROWS = 2000


def _sampled(result: Result) -> Result:
    """``result`` with at most about :data:`DEFAULT_ROWS` of its integrator
    steps: the first step at or after each of that many evenly spaced
    times, every row at an event (before and after it) and the first and
    last rows. The rows kept are the integrator's own (nothing
    interpolated); a result with fewer rows is returned as it is."""
    # (the row count read without converting the times: the block's and
    # the rigid drive's short runs are returned as they are, at no cost)
    count = result._core.point_count if result._core is not None else len(result.t)
    if count <= DEFAULT_ROWS:
        return result
    t = result.t
    keep = np.zeros(len(t), dtype=bool)
    grid = np.linspace(t[0], t[-1], DEFAULT_ROWS)
    keep[np.minimum(np.searchsorted(t, grid, side="left"), len(t) - 1)] = True
    keep[[0, -1]] = True
    events = np.array([event.time for event in result.events], dtype=float)
    if events.size:
        keep[np.minimum(np.searchsorted(t, events, side="left"), len(t) - 1)] = True
        keep[np.maximum(np.searchsorted(t, events, side="right") - 1, 0)] = True
    rows = np.flatnonzero(keep)
    sampled = _restore_result(t[rows], result.channels, result._matrix()[:, rows], result.events,
                              result.stats, result.integrator, result.friction, result.checks)
    sampled._sampled = True
    return sampled


def _t_eval_list(t_eval) -> list:
    """``t_eval`` as a list of floats ([] for None and ``"steps"``: every
    step and event; simulate samples None's afterwards).

    Raises:
        ValueError: ``t_eval`` is no sequence of numbers, or holds no time
            (an empty list would silently give the default output).
    """
    if t_eval is None or (isinstance(t_eval, str) and t_eval == "steps"):
        return []
    try:
        times = np.asarray(t_eval, dtype=float).ravel().tolist()
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"t_eval = {t_eval!r} is invalid: must be a sequence of times [s] in "
                         "[0, t_end], or \"steps\" (every step and event), or None (the steps "
                         "sampled)") from None
    if not times:
        raise ValueError(f"t_eval = {t_eval!r} is invalid: t_eval must hold at least one time "
                         "in [0, t_end] ('steps': every step and event)")
    return times


class _progress_bar:
    """A tqdm bar over the simulated time [0, t_end] while a run lasts, or
    nothing (``show`` False); the context value is the core's progress
    callback of the simulated time (None without a bar)."""

    def __init__(self, show, t_end: float):
        self._bar = None
        if shown(show):
            from tqdm.auto import tqdm

            self._bar = tqdm(total=t_end, unit="s", desc="simulate", leave=False,
                             bar_format="{desc}: {percentage:3.0f}%|{bar}| t = {n:.4g} s of "
                                        "{total:.4g} s [{elapsed}<{remaining}]")

    def _report(self, t: float) -> None:
        self._bar.update(t - self._bar.n)

    def __enter__(self):
        return self._report if self._bar is not None else None

    def __exit__(self, *exc) -> None:
        if self._bar is not None:
            self._bar.close()


def _run_core(simulate_core: Callable, call: Callable, arguments: dict, progress) -> Result:
    """The core's simulation ``simulate_core(*call(arguments))`` as a
    Result, under a progress bar where ``progress`` asks for one (without
    one, the common case, no bar is set up or closed)."""
    if progress is False:
        arguments["progress"] = None
        return Result(simulate_core(*call(arguments)))
    with _progress_bar(progress, arguments["t_end"]) as report:
        arguments["progress"] = report
        return Result(simulate_core(*call(arguments)))


def _flag(name: str, value) -> bool:
    """``value`` if it is a bool (or numpy's), naming the option otherwise."""
    value = _scalar(value)
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} = {value!r} is invalid: must be True or False")
    return bool(value)


def _name(name: str, value, what: str = "an integrator") -> str:
    """``value`` if it is a string (the core checks the name); None as ``""``."""
    if value is not None and not isinstance(value, str):
        raise ValueError(f"{name} = {value!r} is invalid: must be the name of {what} or None")
    return value or ""


#: simulate's defaults of the options it takes as None when left out (so that
#: it can tell an option given from one left out: :func:`_unused_option`).
DEFAULT_RTOL, DEFAULT_ATOL, DEFAULT_THETA = 1e-8, 1e-10, 0.5
#: simulate's default bound on a run's events.
DEFAULT_MAX_EVENTS = 100_000

#: The default step budget: this many integrator steps per simulated second,
#: at least this many in all (max_steps None: :func:`default_max_steps`).
STEPS_PER_SECOND = 1_000_000


def default_max_steps(t_end) -> int:
    """simulate's default ``max_steps`` for a run to ``t_end`` [s]: 1e6 steps
    per simulated second, at least 1e6 (a budget fixed at 1e6 ended the
    shipped position_holding scene with its former arctan law, 0.64 million
    steps per second, at 1.56 s of 2). Beyond the core's integer it stays there; a t_end the core refuses
    gets the floor."""
    steps = STEPS_PER_SECOND * t_end
    # (one chained comparison: NaN, inf and runs up to 1 s take the floor)
    if not STEPS_PER_SECOND < steps < math.inf:
        return STEPS_PER_SECOND
    return min(math.ceil(steps), 2 ** 62)


def _shared_arguments(default_dt: float, t_end, integrator, rtol, atol, dt, theta, t_eval,
                      max_steps, max_events, max_step, first_step, max_order) -> dict:
    """The keywords the core's block and drive simulations share, from
    :func:`simulate`'s (None: the default; ``dt`` None: ``default_dt``, which
    differs between the models; ``integrator`` None: ``""``; ``t_eval`` a
    list of floats).

    Raises:
        ValueError: a value of the wrong kind (a string for a number, 1.5
            steps), naming the option; the core checks the ranges.
    """
    t_end = _real("t_end", t_end)
    return {"t_end": t_end,
            "integrator": check_integrator_name(_name("integrator", integrator)),
            "rtol": DEFAULT_RTOL if rtol is None else _real("rtol", rtol),
            "atol": DEFAULT_ATOL if atol is None else _real("atol", atol),
            "dt": default_dt if dt is None else _real("dt", dt),
            "theta": DEFAULT_THETA if theta is None else _real("theta", theta),
            "t_eval": t_eval,
            "max_steps": ((STEPS_PER_SECOND if t_end <= 1.0 else default_max_steps(t_end))
                          if max_steps is None else _whole("max_steps", max_steps)),
            "max_events": (DEFAULT_MAX_EVENTS if max_events is None
                           else _whole("max_events", max_events)),
            "max_step": 0.0 if max_step is None else _real("max_step", max_step),
            "first_step": 0.0 if first_step is None else _real("first_step", first_step),
            "max_order": 0 if max_order is None else _whole("max_order", max_order, 2 ** 31 - 1)}


def _drive_arguments(t_end, integrator, smooth_integrator, rtol, atol, dt, theta, t_eval,
                     max_steps, max_events, max_step, first_step, bounce_threshold,
                     max_order, check=True) -> dict:
    """The core's drive-simulation keywords from :func:`simulate`'s (None:
    the default; ``integrator`` None or ``""``: the core's default per model;
    ``t_eval`` a list of floats). Shared with
    :class:`leadscrew.studies._batch.DriveBatch`.

    Raises:
        ValueError: a value of the wrong kind (a string for a number, 1.5
            steps), naming the option; the core checks the ranges.
    """
    arguments = _shared_arguments(1e-4, t_end, integrator, rtol, atol, dt, theta, t_eval,
                                  max_steps, max_events, max_step, first_step, max_order)
    arguments["smooth_integrator"] = _name("smooth_integrator", smooth_integrator)
    arguments["bounce_threshold"] = (1e-6 if bounce_threshold is None
                                     else _real("bounce_threshold", bounce_threshold))
    arguments["check"] = _flag("check", check)
    # (dt left out: the core shortens its default where a drive's stiffness
    # needs a shorter Moreau-Jean step, instead of refusing it)
    arguments["dt_given"] = dt is not None
    return arguments


def _run_options(integrator=None, smooth_integrator=None, rtol=None, atol=None,
                 max_steps=1_000_000, max_events=100_000, max_step=None, first_step=None,
                 bounce_threshold=None, max_order=None) -> dict:
    """The options of a drive's run without its length or output, with
    :func:`simulate`'s defaults: the keywords of ``_core.DriveStepper`` and
    ``_core.write_core_spec`` (a core spec carries them).

    Raises:
        ValueError: a value of the wrong kind, naming the option.
    """
    arguments = _drive_arguments(1.0, integrator, smooth_integrator, rtol, atol, None, None,
                                 [], max_steps, max_events, max_step, first_step,
                                 bounce_threshold, max_order)
    for unused in ("t_end", "dt", "dt_given", "theta", "t_eval", "check"):
        del arguments[unused]
    return arguments


def simulate(
    model,
    t_end: float,
    friction: Optional[str] = None,
    integrator: Optional[str] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    dt: Optional[float] = None,
    t_eval: Optional[Sequence[float]] = None,
    k_v: Optional[float] = None,
    theta: Optional[float] = None,
    max_steps: Optional[int] = None,
    max_events: Optional[int] = None,
    max_step: Optional[float] = None,
    first_step: Optional[float] = None,
    smooth_integrator: Optional[str] = None,
    bounce_threshold: Optional[float] = None,
    max_order: Optional[int] = None,
    check: bool = True,
    progress: bool = False,
    **law_parameters,
) -> Result:
    """Simulate a model from t = 0 to ``t_end``.

    Args:
        model: a :class:`~leadscrew.FrictionBlock` or a :class:`~leadscrew.Scene`.
        t_end: end time [s], > 0.
        friction: for a FrictionBlock: a law of the registry
            (:func:`leadscrew.friction_laws`): ``"coulomb"`` (exact,
            default; with the block's ``mu_static``), ``"stribeck"``,
            ``"lugre"``, ``"arctan_velocity"`` (eq. 3.16) or
            ``"arctan_acceleration"`` (eq. 3.15). A Scene carries its
            friction law (``friction.law``).
        integrator: for ``"coulomb"``: ``"event_driven"`` (default) or
            ``"moreau"`` (a Scene without play, with exact flanks or with
            penalty flanks, ``backlash.contact`` ``"bistop"`` or
            ``"cubic"``); for the regularized laws an ODE integrator:
            ``"cvode_bdf"`` (default), ``"cvode_adams"``, ``"dopri5"``, ...
            (a Scene with exact backlash and a regularized law: ``"event_driven"``),
            and ``"moreau"`` for ``"arctan_velocity"`` and ``"lugre"`` (their
            friction implicit in the step; not ``"arctan_acceleration"``).
            Where only ``"moreau"`` fits a Scene, it is the default: the
            train's friction stages (``motor.friction_torque``, ``gear.type``
            ``"lossy"`` or ``"worm"``) anywhere but on the rigid concept
            without play with plain Coulomb friction (no ``mu_static``) and a
            torque or DC motor: on the flexible concepts, with exact or
            penalty play, another thread law or ``loads.drive_speed``.
        rtol, atol: integration tolerances of the ODE and event-driven
            integrators (default 1e-8 and 1e-10, or the Scene's own; refused
            with ``"moreau"``; given without ``integrator`` where the default
            is ``"moreau"``, the first adaptive integrator that fits runs).
            A Scene whose law runs velocity-regularized refuses an atol
            whose slip velocity spans 1/20 of its stick band 1 / k_v
            (docs/physics/result_checks.md, "Options refused before a run").
        dt: fixed step [s] of ``"moreau"`` (given without ``integrator``, it
            runs ``"moreau"`` where that fits; default 1e-3 for a FrictionBlock,
            1e-4 for a Scene, there shortened to half the longest step that
            resolves the drive's stiffness where 1e-4 does not; a dt you
            give is used as it is, or refused; refused with the other
            integrators).
        t_eval: output times [s], at least one, in [0, t_end]; ``"steps"``:
            every integrator step and event; default (None): the
            integrator's steps sampled down to about :data:`DEFAULT_ROWS`
            (2,000) evenly spaced in time, with every event's rows and the
            last time (a run with fewer steps keeps them all).
        k_v: for a FrictionBlock: regularization gain k_V of the arctan laws
            [s/m or s^2/m] (default 100). A Scene carries its own
            (``friction.k_v``): k_v may only repeat it.
        theta: theta of the Moreau-Jean scheme, in [0, 1] (default 0.5;
            given without ``integrator``, it runs ``"moreau"`` where that
            fits; refused with the other integrators).
        max_steps: bound on integrator steps; for ``"moreau"`` on its fixed
            steps (t_end / dt), refused before the run starts if too small.
            Default (None): 1e6 per simulated second, at least 1e6
            (:func:`default_max_steps`), so that a run's budget grows with
            its length.
        max_events: bound on events (Zeno or chattering raise instead of
            hanging; default None: 100,000).
        max_step, first_step: optional step-size controls [s] (not with
            ``"moreau"``).
        smooth_integrator: for a Scene only: the ODE integrator inside
            ``"event_driven"`` (default ``"rk_verner6"`` for the rigid
            concept, ``"cvode_bdf"`` for the flexible ones).
        bounce_threshold: for a Scene only: a flank impact slower than this
            [m/s] is plastic (default 1e-6; refused for a scene without an
            exact backlash, ``backlash.contact = "exact"``, and with
            ``"moreau"``).
        max_order: highest order of the CVODE methods (default: BDF 5,
            Adams 12; for the flexible drive models with a regularized
            friction law at rtol >= 1e-9, BDF 3: faster and robust with their
            lightly damped stiff modes and the law's stiffness near zero slip;
            not with ``"moreau"``).
        check: check the result's physics before returning it (every
            channel finite, events within the run, friction never doing
            positive work, Coulomb's cone, the energy account within the
            integration tolerances; docs/physics/result_checks.md) and raise
            SimulationError naming the invariant that fails. ``False``
            returns the result unchecked (``Result.checks`` still reports).
        progress: show a progress bar over the simulated time (tqdm; it
            updates about every 0.1 s of wall time). Whether or not it is
            shown, Ctrl-C interrupts a run within that time with
            ``KeyboardInterrupt``, the process left usable.
        **law_parameters: for a FrictionBlock: the friction law's other
            parameters by their keys (``sigma0``, ``sigma1``, ``viscous``,
            ``stribeck_velocity``, ``stribeck_exponent``, ...; the law lists
            them, with units and defaults). A Scene carries its own; for a
            Scene any other keyword is refused, naming the options it takes.

    A Scene may store its run's options (its ``[simulation]`` section:
    ``integrator``, ``smooth_integrator``, ``rtol``, ``atol``, ``dt``,
    ``theta``, ``max_steps``, ``max_events``, ``max_step``, ``first_step``,
    ``bounce_threshold``, ``max_order``): each one left out here (None)
    takes the scene's, each one given overrides it; where ``integrator`` is
    given, the scene's options that integrator does not take are left out
    (the scene's ``rtol`` under ``integrator="moreau"``). An error about a
    stored option names its key path (``simulation.rtol``).

    An option names its scheme where ``integrator`` is left out: ``dt`` or
    ``theta`` (Moreau-Jean's) runs ``"moreau"`` where it fits the model,
    ``rtol``, ``atol``, ``max_order``, ``max_step`` or ``first_step`` on a
    Moreau-Jean default the first adaptive integrator that fits
    (``Result.integrator`` names the one that ran). An option the integrator
    that runs would ignore (no integrator that fits takes it, or the
    ``integrator`` given does not: ``dt`` and ``theta`` without ``"moreau"``; ``rtol``, ``atol``, ``max_order``, ``max_step``,
    ``first_step`` with it; ``bounce_threshold`` without an exact backlash)
    is refused, not ignored: only options given count (None, the default,
    is never refused).

    Returns:
        A :class:`Result`.

    Raises:
        ValueError: bad input, an unknown keyword, an option the integrator
            would ignore, or an integrator that does not fit the friction law
            (the message lists those that do).
        SimulationError: the integrator or the LCP failed, or the result
            fails a check of its physics (time and reason).
        JammingError: the drive jams dynamically (a SimulationError).
    """
    t_eval_list = _t_eval_list(t_eval)
    # The options only some integrators (or scenes) take, as given (None:
    # left out; their defaults are filled in later).
    given = {"rtol": rtol, "atol": atol, "dt": dt, "theta": theta, "max_order": max_order,
             "max_step": max_step, "first_step": first_step}
    if isinstance(model, _core.FrictionBlock):
        # The kinds are checked as for a Scene; the core validates the names
        # (listing the allowed ones) and the values.
        friction = "coulomb" if friction is None else _name("friction", friction,
                                                            "a friction law")
        arguments = _shared_arguments(1e-3, t_end, integrator, rtol, atol, dt, theta,
                                      t_eval_list, max_steps, max_events, max_step, first_step,
                                      max_order)
        _check_block_options(smooth_integrator=smooth_integrator,
                             bounce_threshold=bounce_threshold)
        entry = _law(friction)
        if entry is not None:  # else the core names the laws
            integrators = functools.partial(_block_integrators, friction)
            arguments["integrator"] = _choose_integrator(arguments["integrator"], integrators,
                                                         given)
            if not arguments["integrator"]:  # None or "": the first of those that fit
                arguments["integrator"] = integrators()[0]
        takes = _law_parameter_keys(friction) if entry is not None else ()
        for name, value in law_parameters.items():  # no law's parameter (a law's: the core)
            if name in _BLOCK_COEFFICIENTS:
                # (given here they would override the block's own silently)
                raise ValueError(f"{name} = {value!r} is invalid as a keyword of simulate for a "
                                 f"FrictionBlock: the block carries its {name} "
                                 "(ls.FrictionBlock(mass, mu, ..., mu_static=...)); build the "
                                 "block with it")
            if takes and name not in _law_keys():
                raise _unknown_block_option(name, value, friction, takes)
        law = {name: _real(name, value) for name, value in law_parameters.items()}
        if k_v is not None:
            law["k_v"] = _real("k_v", k_v)
        elif "k_v" in takes:
            law["k_v"] = 100.0  # the block's default gain (the thesis's Table 3.1 range)
        arguments.update(block=model, friction=friction, law=law,
                         check=check if check is True else _flag("check", check))
        result = _run_core(_core.simulate_block, _block_call, arguments, progress)
        # (the row count read inline: a short run costs one attribute read)
        return (_sampled(result) if t_eval is None and result._core.point_count > DEFAULT_ROWS
                else result)
    if isinstance(model, Scene):
        _check_scene_friction(model, friction, k_v)
        for name, value in law_parameters.items():
            raise _unknown_scene_option(name, value)
        options = dict(given, integrator=integrator, smooth_integrator=smooth_integrator,
                       max_steps=max_steps, max_events=max_events,
                       bounce_threshold=bounce_threshold)
        if not model._data.get("simulation"):  # (the common case: nothing stored)
            return _simulate_scene(model, t_end, t_eval, t_eval_list, options, check, progress)
        options, stored = scene_options(model, options)
        with _stored_option_errors(stored):
            return _simulate_scene(model, t_end, t_eval, t_eval_list, options, check, progress)
    raise ValueError(f"model = {model!r} is invalid: must be a FrictionBlock or a Scene")


def _simulate_scene(scene: Scene, t_end, t_eval, t_eval_list: list, options: Dict[str, Any],
                    check, progress) -> Result:
    """:func:`simulate` of a Scene with its options (name -> value, None:
    simulate's default; the scene's stored ones merged in already)."""
    o = options
    # integrator None: the core takes the model's default
    arguments = _drive_arguments(
        t_end, o["integrator"], o["smooth_integrator"], o["rtol"], o["atol"], o["dt"],
        o["theta"], t_eval_list, o["max_steps"], o["max_events"], o["max_step"],
        o["first_step"], o["bounce_threshold"], o["max_order"], check)
    drive = scene.model()
    arguments["integrator"] = _choose_integrator(
        arguments["integrator"], functools.partial(_core.drive_integrators, drive.parameters),
        {name: o[name] for name in (*ADAPTIVE_OPTIONS, *MOREAU_OPTIONS, "bounce_threshold")},
        scene)
    arguments["drive"] = drive
    result = _run_core(_core.simulate_drive, _drive_call, arguments, progress)
    return (_sampled(result) if t_eval is None and result._core.point_count > DEFAULT_ROWS
            else result)


# The friction coefficients a FrictionBlock carries itself (not keywords of
# simulate, as the law's other parameters are).
_BLOCK_COEFFICIENTS = ("mu", "mu_static")

# The core's simulate_block's and simulate_drive's parameters, in their
# order (bind_model.cpp, bind_drive.cpp), and their arguments picked from a
# dict in that order: simulate passes them by position, as pybind11 interns
# each keyword's name per call (12k of the block's 530k instructions per
# call; issue 17's benchmark).
_BLOCK_CALL = ("block", "t_end", "friction", "integrator", "law", "rtol", "atol", "dt", "theta",
               "t_eval", "max_steps", "max_events", "max_step", "first_step", "max_order",
               "check", "progress")
_DRIVE_CALL = ("drive", "t_end", "integrator", "smooth_integrator", "rtol", "atol", "dt", "theta",
               "t_eval", "max_steps", "max_events", "max_step", "first_step", "bounce_threshold",
               "max_order", "check", "dt_given", "progress")
_block_call = operator.itemgetter(*_BLOCK_CALL)
_drive_call = operator.itemgetter(*_DRIVE_CALL)

# simulate's parameters by name (its **law_parameters left out) and the keys
# of a Scene's friction section (what a Scene takes of a law's parameters).
_SIGNATURE = [name for name, parameter in inspect.signature(simulate).parameters.items()
              if parameter.kind is not inspect.Parameter.VAR_KEYWORD]
_SCENE_FRICTION_KEYS = tuple(SCHEMA["friction"])

# simulate's options: its parameters but the model and the times, which a
# study or a DriveBatch sets itself (the command line's study options and the
# batch's keywords are these).
# (progress is the display of one run: a study shows its own over its cases.)
_OPTIONS = {name: parameter for name, parameter in inspect.signature(simulate).parameters.items()
            if name not in ("model", "t_end", "t_eval", "progress")
            and parameter.kind is not inspect.Parameter.VAR_KEYWORD}
# Their defaults (what simulate takes for an option left out).
_OPTION_DEFAULTS = {name: parameter.default for name, parameter in _OPTIONS.items()}
