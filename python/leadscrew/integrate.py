"""The core's ODE integrators with a Python right-hand side.

``solve_ode`` runs any integrator of the C++ core (SUNDIALS CVODE BDF/Adams,
ARKODE explicit Runge-Kutta pairs, ...) on y' = fun(t, y), with root finding
for event functions. It is meant for testing the integrators and for quick
experiments: every evaluation of ``fun`` is a Python call, so it is slow
compared with a model written in C++ (the simulations of the package run
their models inside C++ through the same integrators).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Optional, Sequence

import numpy as np

from . import _core
from .errors import SimulationError

__all__ = ["solve_ode", "OdeResult", "METHODS"]

#: Names of the available integrators.
METHODS: tuple = tuple(_core.integrate.integrator_names())


@dataclass
class OdeResult:
    """Solution of :func:`solve_ode`.

    Attributes:
        t: output times, shape (k,).
        y: states at the output times, shape (n, k).
        t_events: per event function, the times of its recorded roots.
        y_events: per event function, the states at those roots, shape (m_i, n).
        direction_events: per event function, +1 (rising) / -1 (falling) per root.
        terminated: True when a terminal event stopped the integration.
        stats: integrator counters (steps, rhs_evaluations, ...).
        method: the integrator's name.
    """

    t: np.ndarray
    y: np.ndarray
    t_events: list = field(default_factory=list)
    y_events: list = field(default_factory=list)
    direction_events: list = field(default_factory=list)
    terminated: bool = False
    stats: dict = field(default_factory=dict)
    method: str = ""


def _event_list(events) -> list:
    if events is None:
        return []
    if callable(events):
        return [events]
    events = list(events)
    for i, e in enumerate(events):
        if not callable(e):
            raise ValueError(f"events[{i}] = {e!r} is invalid: must be a callable g(t, y)")
    return events


def _simulation_error(time: float, reason: str, hint: str) -> SimulationError:
    error = SimulationError(f"at t = {time:.4g} s: {reason} (hint: {hint})")
    error.time = time
    error.reason = reason
    return error


def solve_ode(
    fun: Callable,
    t_span: Sequence[float],
    y0,
    method: str = "cvode_bdf",
    rtol: float = 1e-8,
    atol: float = 1e-10,
    t_eval=None,
    events=None,
    max_step: Optional[float] = None,
    fixed_step: Optional[float] = None,
    max_order: Optional[int] = None,
    first_step: Optional[float] = None,
    max_steps: Optional[int] = None,
) -> OdeResult:
    """Integrate y' = fun(t, y) from t_span[0] to t_span[1].

    Args:
        fun: right-hand side f(t, y) -> array of n values (y is an array of n).
        t_span: (t0, t_end) with t_end > t0 [s].
        y0: initial state, n values.
        method: one of :data:`METHODS`: "cvode_bdf" (SUNDIALS CVODE BDF,
            stiff problems), "cvode_adams" (CVODE Adams, non-stiff), "dopri5"
            and "verner6" (SUNDIALS ARKODE Dormand-Prince 5(4), as ode45, and
            Verner 6(5)), "rk_dopri5" and "rk_verner6" (the same pairs in the
            core's own allocation-free engine: far less overhead per step and
            restart, event times from the exact step continuation).
        rtol: relative tolerance, in (0, 1).
        atol: absolute tolerance, > 0.
        t_eval: increasing output times within t_span; None: every internal
            step (and t0).
        events: an event function g(t, y) -> float, or a list of them. Roots
            are located by the integrator; a function with attribute
            ``terminal = True`` stops the integration at its first root, one
            with ``direction = +1`` (-1) records only rising (falling)
            crossings (as scipy's solve_ivp).
        max_step: largest internal step [s], None: unbounded. Roots are
            found from sign changes between step ends: when an event function
            depends on t (forcing) while f is (nearly) zero, limit the step
            to a fraction of the forcing period or a double crossing within
            one step goes unseen.
        fixed_step: fixed step size [s] for the explicit Runge-Kutta methods.
        max_order: highest order of cvode_bdf (1..5) or cvode_adams (1..12).
        first_step: initial step size [s], None: chosen by the integrator.
        max_steps: total internal steps allowed, None: the core's default.

    Returns:
        An :class:`OdeResult`.

    Raises:
        ValueError: an invalid argument or option (the message names it and
            the allowed values).
        leadscrew.SimulationError: the integrator failed (the message names the
            solver flag, e.g. CV_TOO_MUCH_WORK, the time and a hint).
    """
    t0, t_end = (float(v) for v in t_span)
    if not (np.isfinite(t0) and np.isfinite(t_end) and t_end > t0):
        raise ValueError(
            f"t_span = ({t0!r}, {t_end!r}) is invalid: must be finite with t_span[1] > t_span[0]"
        )
    y0 = np.array(y0, dtype=float).reshape(-1)
    n = y0.size
    if n < 1:
        raise ValueError("y0 is invalid: must have at least one component")
    if t_eval is not None:
        t_eval = np.array(t_eval, dtype=float).reshape(-1)
        if t_eval.size and (
            not np.all(np.isfinite(t_eval))
            or np.any(np.diff(t_eval) <= 0)
            or t_eval[0] < t0
            or t_eval[-1] > t_end
        ):
            raise ValueError(
                "t_eval is invalid: must be strictly increasing and within t_span "
                f"[{t0!r}, {t_end!r}]"
            )
    event_functions = _event_list(events)
    m = len(event_functions)
    terminal = [bool(getattr(e, "terminal", False)) for e in event_functions]
    wanted = [float(getattr(e, "direction", 0.0)) for e in event_functions]

    options = {}
    for name, value in (
        ("max_step", max_step),
        ("fixed_step", fixed_step),
        ("first_step", first_step),
    ):
        if value is not None:
            options[name] = float(value)
    if max_order is not None:
        options["max_order"] = int(max_order)
    if max_steps is not None:
        options["max_steps"] = int(max_steps)
    integrator = _core.integrate.make_integrator(method, rtol=rtol, atol=atol, **options)

    def g(t, y):
        return np.array([e(t, y) for e in event_functions], dtype=float)

    system = _core.integrate.PythonOdeSystem(fun, n, g if m else None, m)
    integrator.initialize(system, t0, y0)

    ts, ys = [], []
    if t_eval is None:
        ts.append(t0)
        ys.append(y0.copy())
        targets = np.array([t_end])
    else:
        targets = t_eval
        if targets.size and targets[0] == t0:
            ts.append(t0)
            ys.append(y0.copy())
            targets = targets[1:]
    t_events = [[] for _ in range(m)]
    y_events = [[] for _ in range(m)]
    d_events = [[] for _ in range(m)]
    terminated = False

    # Each call of advance either takes at least one internal step or returns
    # at a root inside the last step; the core bounds the steps (max_steps),
    # so this loop is bounded by that budget plus the roots and outputs.
    budget = 2 * (max_steps if max_steps is not None else 1_000_000) + 2 * len(targets) + 16
    t = t0
    index = 0
    for _ in range(budget):
        if index >= len(targets) or terminated:
            break
        target = float(targets[index])
        t, root_found, y = integrator.advance(target, one_step=t_eval is None)
        if root_found:
            for i, direction in enumerate(integrator.root_info):
                if direction == 0 or (wanted[i] and np.sign(wanted[i]) != direction):
                    continue
                t_events[i].append(t)
                y_events[i].append(y.copy())
                d_events[i].append(direction)
                if terminal[i]:
                    terminated = True
            if terminated and t_eval is None:
                ts.append(t)
                ys.append(y)
            continue
        if t_eval is None or t == target:
            ts.append(t)
            ys.append(y)
        if t == target:
            index += 1
    else:
        raise _simulation_error(t, "solve_ode made no progress", "report this as a bug")

    return OdeResult(
        t=np.array(ts),
        y=np.array(ys).T.reshape(n, len(ts)),
        t_events=[np.array(v) for v in t_events],
        y_events=[np.array(v).reshape(-1, n) for v in y_events],
        direction_events=[np.array(v, dtype=int) for v in d_events],
        terminated=terminated,
        stats=integrator.stats,
        method=integrator.name,
    )
