"""``simulate``: run a model and get its time series, events and statistics."""

from __future__ import annotations

import inspect
import math
import numbers
from typing import NamedTuple, Optional, Sequence

import numpy as np

from . import _core
from .models import FrictionBlock
from .scene import Scene
from .units import channel_unit

__all__ = ["simulate", "Result", "Event"]


class Event(NamedTuple):
    """A mode change: time [s] and kind, e.g. ``"slip+->stick"``."""

    time: float
    kind: str


class Result:
    """Time series of a simulation.

    Attributes:
        t: output times [s] (at an event the time appears twice: the values
            just before and just after it, unless ``t_eval`` was given).
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
                 "_checks")

    def __init__(self, core_result):
        self._core = core_result
        self._t = self._channels = self._data = self._events = self._stats = self._names = None
        self._checks = None
        self._rows = {}  # channels converted one by one (before the whole matrix)

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


def _law(name: str) -> Optional[dict]:
    """The registry's entry of a friction law (None: no such law; the core
    names the laws)."""
    return next((law for law in _core.friction_laws() if law["name"] == name), None)


def _check_scene_friction(scene: Scene, friction: Optional[str], k_v=None) -> None:
    """A Scene carries its friction law and gain: ``friction`` and ``k_v``
    may only repeat them (another value would be ignored)."""
    if friction is not None and friction != scene["friction"]["law"]:
        raise ValueError(f"friction = {friction!r} is invalid for a Scene: set the "
                         f"scene's friction.law (it is {scene['friction']['law']!r})")
    if k_v is not None and k_v != scene["friction"]["k_v"]:
        raise ValueError(f"k_v = {k_v!r} is invalid for a Scene: set the scene's friction.k_v "
                         f"(it is {scene['friction']['k_v']!r})")


def _check_block_options(**options) -> None:
    """Options only a Scene's simulation takes must be None for a FrictionBlock
    (a value would be ignored)."""
    for name, value in options.items():
        if value is not None:
            raise ValueError(f"{name} = {value!r} is invalid for a FrictionBlock: only a "
                             "Scene's simulation takes it")


def _scalar(value):
    """A 0-d array as its number (``np.array(1.0)`` is a number here)."""
    return value.item() if isinstance(value, np.ndarray) and value.ndim == 0 else value


def _real(name: str, value) -> float:
    """``value`` as a float, if it is a real number (not a bool or a string:
    the core checks the range, this only the kind, naming the option)."""
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
    value = _scalar(value)
    whole = isinstance(value, numbers.Integral) or (
        isinstance(value, numbers.Real) and math.isfinite(value) and value == int(value))
    if isinstance(value, bool) or not whole:
        raise ValueError(f"{name} = {value!r} is invalid: must be an integer")
    if abs(int(value)) > limit:
        raise ValueError(f"{name} = {value!r} is invalid: must be an integer of at most "
                         f"{limit} in magnitude")
    return int(value)


class _progress_bar:
    """A tqdm bar over the simulated time [0, t_end] while a run lasts, or
    nothing (``show`` False); the context value is the core's progress
    callback of the simulated time (None without a bar)."""

    def __init__(self, show, t_end: float):
        self._bar = None
        if _flag("progress", show):
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
    return {"t_end": _real("t_end", t_end), "integrator": _name("integrator", integrator),
            "rtol": _real("rtol", rtol), "atol": _real("atol", atol),
            "dt": default_dt if dt is None else _real("dt", dt), "theta": _real("theta", theta),
            "t_eval": t_eval, "max_steps": _whole("max_steps", max_steps),
            "max_events": _whole("max_events", max_events),
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
    return arguments


def simulate(
    model,
    t_end: float,
    friction: Optional[str] = None,
    integrator: Optional[str] = None,
    rtol: float = 1e-8,
    atol: float = 1e-10,
    dt: Optional[float] = None,
    t_eval: Optional[Sequence[float]] = None,
    k_v: Optional[float] = None,
    theta: float = 0.5,
    max_steps: int = 1_000_000,
    max_events: int = 100_000,
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
            ``"moreau"``; for the regularized laws an ODE integrator:
            ``"cvode_bdf"`` (default), ``"cvode_adams"``, ``"dopri5"``, ...
            (a Scene with exact backlash and a regularized law: ``"event_driven"``).
        rtol, atol: integration tolerances (ODE and event-driven integrators).
        dt: fixed step [s] of ``"moreau"`` (default 1e-3 for a FrictionBlock,
            1e-4 for a Scene).
        t_eval: output times [s]; default: every step and event.
        k_v: for a FrictionBlock: regularization gain k_V of the arctan laws
            [s/m or s^2/m] (default 100). A Scene carries its own
            (``friction.k_v``): k_v may only repeat it.
        theta: theta of the Moreau-Jean scheme, in [0, 1].
        max_steps: bound on integrator steps; for ``"moreau"`` on its fixed
            steps (t_end / dt), refused before the run starts if too small.
        max_events: bound on events (Zeno or chattering raise instead of hanging).
        max_step, first_step: optional step-size controls [s].
        smooth_integrator: for a Scene only: the ODE integrator inside
            ``"event_driven"`` (default ``"rk_verner6"`` for the rigid
            concept, ``"cvode_bdf"`` for the flexible ones).
        bounce_threshold: for a Scene only: a flank impact slower than this
            [m/s] is plastic (exact backlash; default 1e-6).
        max_order: highest order of the CVODE methods (default: BDF 5,
            Adams 12; for the flexible drive models with a regularized
            friction law at rtol >= 1e-9, BDF 3: faster and robust with their
            lightly damped stiff modes and the law's stiffness near zero slip).
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
            them, with units and defaults). A Scene carries its own.

    Returns:
        A :class:`Result`.

    Raises:
        ValueError: bad input or an integrator that does not fit the friction law
            (the message lists those that do).
        SimulationError: the integrator or the LCP failed, or the result
            fails a check of its physics (time and reason).
        JammingError: the drive jams dynamically (a SimulationError).
    """
    t_eval_list = [] if t_eval is None else np.asarray(t_eval, dtype=float).ravel().tolist()
    if isinstance(model, _core.FrictionBlock):
        # The kinds are checked as for a Scene; the core validates the names
        # (listing the allowed ones) and the values.
        friction = "coulomb" if friction is None else _name("friction", friction,
                                                            "a friction law")
        arguments = _shared_arguments(1e-3, t_end, integrator, rtol, atol, dt, theta,
                                      t_eval_list, max_steps, max_events, max_step, first_step,
                                      max_order)
        if not arguments["integrator"]:  # None or "": the core lists those that fit, default first
            arguments["integrator"] = _core.block_integrators(friction)[0]
        _check_block_options(smooth_integrator=smooth_integrator,
                             bounce_threshold=bounce_threshold)
        law = {name: _real(name, value) for name, value in law_parameters.items()}
        takes = {p["key"] for p in _law(friction)["parameters"]} if _law(friction) else set()
        if k_v is not None:
            law["k_v"] = _real("k_v", k_v)
        elif "k_v" in takes:
            law["k_v"] = 100.0  # the block's default gain (the thesis's Table 3.1 range)
        with _progress_bar(progress, arguments["t_end"]) as report:
            return Result(_core.simulate_block(
                model, friction=friction, law=law, check=_flag("check", check),
                progress=report, **arguments))
    if isinstance(model, Scene):
        _check_scene_friction(model, friction, k_v)
        for name, value in law_parameters.items():
            raise ValueError(f"{name} = {value!r} is invalid for a Scene: set the scene's "
                             f"friction.{name}")
        # integrator None: the core takes the model's default
        arguments = _drive_arguments(
            t_end, integrator, smooth_integrator, rtol, atol, dt, theta, t_eval_list, max_steps,
            max_events, max_step, first_step, bounce_threshold, max_order, check)
        with _progress_bar(progress, arguments["t_end"]) as report:
            return Result(_core.simulate_drive(model.model(), progress=report, **arguments))
    raise ValueError(f"model = {model!r} is invalid: must be a FrictionBlock or a Scene")


# simulate's options: its parameters but the model and the times, which a
# study or a DriveBatch sets itself (the command line's study options and the
# batch's keywords are these).
# (progress is the display of one run: a study shows its own over its cases.)
_OPTIONS = {name: parameter for name, parameter in inspect.signature(simulate).parameters.items()
            if name not in ("model", "t_end", "t_eval", "progress")
            and parameter.kind is not inspect.Parameter.VAR_KEYWORD}
# Their defaults (what simulate takes for an option left out).
_OPTION_DEFAULTS = {name: parameter.default for name, parameter in _OPTIONS.items()}
