"""The drive jammed at its end stop (issue 19, item 5): ``end_stop_jam``.

The scene's motor (a constant drive torque M, or a DC motor at a constant
voltage U) drives the load into the scene's penalty end stop for
``t_drive`` (without one: until the clamp settles); the thread clamps, and a
self-locking thread keeps the clamp force F after the drive lets go. Then
the drive reverses: at ``t_drive`` the torque steps to -x (the voltage to
-x) and is held. The smallest constant reverse x that frees the load (the
stop releases it; on the rigid drive without play also a thread that slips
away from the stop, the clamp falling as it goes) is found by bisection over
runs of the whole sequence, a bounded number of them; each run is judged
until it is decided, freed or held at rest (_end_stop_runs.py), so the
answer does not depend on the window. A flexible drive rings after the step
and may creep off the stop by stick-slip below the quasi-static form
(docs/physics/end_stops.md, "After a step of reverse drive").

Beside it the quasi-static closed form (docs/physics/end_stops.md): the
clamp is an axial load F that the thread holds (the stop's force and the
scene's axial force on the load, at rest); the torque that moves it
back (lowers it) with the static coefficient is

    breakaway torque T_b = F r_m tan(rho_s' - alpha),  rho_s' = atan(mu_static'),

(:func:`leadscrew.lower_torque` with ``mu_static``). Only a self-locking
thread (tan(alpha) < mu_static') jams; the study refuses another, where the
stop pushes the drive back as soon as it lets go. With a DC motor at rest the torque
is k_t U / R (the current limit caps it), so the breakaway voltage is
U_b = R T_b / k_t (infinite where T_b > k_t i_max).

Behind an ideal gear stage of ratio n (section ``gear``) the drive's torque
and the DC motor act on the rotor: the breakaway torque on the driven part
T_b takes T_b / |n| on the rotor, U_b = R T_b / (|n| k_t). The study reports
``breakaway_torque`` on the driven part either way.

Through the train's friction stages (a lossy or worm stage, the motor's
friction T_c: the rigid drive without play, docs/physics/gear.md, "End
stops through the stages") the breakaway is the static stick test's edge:
at rest the thread holds any torque tau on the driven part between -T_b and
T_r = F r_m tan(alpha + rho_s') (its lowering and raising torques with
mu_static), the stage passes x = k tau with k between eta_b,static and
1 / eta_static, and the motor moves the clamp back beyond the largest
|k| |tau| of them, plus T_c: T_b / (|n| eta_static) + T_c where the thread
is self-locking and the motor drives it back, or |eta_b,static| T_r / |n| +
T_c where a self-locking stage is locked by the thread holding at its
raising edge (the torque a drive into the stop leaves in the train), the
larger. Then U_b = R T_motor / k_t. ``breakaway_torque`` is that split's
torque on the driven part (T_b, or T_r); ``breakaway_motor_torque`` the
motor's.
"""

from __future__ import annotations

import math
from typing import Any, Dict, Optional, Tuple

import numpy as np
import pandas as pd

from .. import _core
from ..errors import NutOffScrewError, SimulationError
from ..simulation import simulate
from . import _end_stop_runs as runs_module
from .._progress import shown
from ._common import (annotate, as_scene, axes, check_count, check_positive, constant_value,
                      frame_of, gear_ratio, with_tolerances)
from ._sweep import _progress_bar
from .motor import has_dc_motor

__all__ = ["end_stop_jam", "plot_end_stop_jam"]

UNITS = {"reverse_torque": "N*m", "reverse_voltage": "V", "broke_free": "",
         "stop_force_end": "N", "window": "s", "t_free": "s", "error": ""}
_SUMMARY_UNITS = {"clamp_force": "N", "thread_force": "N", "peak_clamp_force": "N",
                  "peak_current": "A",
                  **{f"breakaway_{name}{form}": unit
                     for name, unit in (("torque", "N*m"), ("motor_torque", "N*m"),
                                        ("voltage", "V"))
                     for form in ("", "_closed_form", "_kinetic", "_held_clamp")},
                  "thread_force_held": "N",
                  "t_free": "s", "slips_to_free": "1", "t_drive": "s", "t_reverse": "s",
                  "t_reverse_max": "s", "runs": "1"}


def _drive(scene) -> Tuple[str, float]:
    """("torque", M [N*m]) or ("voltage", U [V]): the scene's constant drive.

    Raises:
        ValueError: no penalty end stops, a speed-controlled drive, or a drive
            that is not constant or is zero.
    """
    if "end_stops" not in scene:
        raise ValueError("scene has no end stops: end_stop_jam needs end_stops = "
                         "{lower or upper, contact = \"penalty\", stiffness, damping}")
    if scene["end_stops"]["contact"] != "penalty":
        raise ValueError(f"end_stops.contact = {scene['end_stops']['contact']!r} is invalid "
                         "for end_stop_jam: must be 'penalty' (the clamp force of a rigid "
                         "stop depends on compliance the exact stop does not have)")
    if has_dc_motor(scene):
        kind, key, value = "voltage", "motor.voltage", scene["motor"]["voltage"]
    else:
        loads = scene["loads"]
        if "drive_speed" in loads:
            raise ValueError("loads.drive_speed is invalid for end_stop_jam: a prescribed "
                             "speed drives through any stop; give loads.drive_torque or a "
                             "DC motor")
        kind, key, value = "torque", "loads.drive_torque", loads.get("drive_torque", 0.0)
    constant = constant_value(value)
    if constant is None or constant == 0.0:
        raise ValueError(f"{key} = {value!r} is invalid for end_stop_jam: must be a nonzero "
                         "constant (it drives the load into the stop)")
    return kind, constant


def _train(scene) -> Dict[str, float]:
    """The train's friction stages' sliding and static efficiencies and the
    motor's friction T_c [N*m] (an ideal stage or none: 1 and 0)."""
    train = scene.model().train_friction
    names = ("efficiency", "efficiency_backdrive", "efficiency_static",
             "efficiency_backdrive_static")
    if not train:
        return {**{name: 1.0 for name in names}, "motor_friction_torque": 0.0}
    return {name: train[name] for name in names + ("motor_friction_torque",)}


def _breakaway_split(scene, clamp: float, static: bool = True) -> Tuple[float, float]:
    """(the torque on the driven part [N*m], |k|) at the breakaway of a clamp
    F [N]: the static stick test's edge (docs/physics/gear.md, "End stops
    through the stages"). At rest the thread holds the torques tau in
    [-T_b, T_r] (T_b = F r_m tan(rho_s' - alpha), T_r = F r_m tan(alpha +
    rho_s'): its lowering and raising torques with mu_static) and the stage
    passes x = k tau with k between eta_b,static and 1 / eta_static; the
    motor moves the clamp back where its torque on the stage's input exceeds
    the largest -x of them all, |k| |tau| (an ideal stage or none: T_b).
    ``static=False``: the same edge with the sliding coefficients (mu and
    the stage's sliding efficiencies), the torque that keeps a slip going
    (docs/physics/end_stops.md, "After a step of reverse drive")."""
    friction = scene["friction"]
    mu = friction.get("mu_static", friction["mu"]) if static else friction["mu"]
    train = _train(scene)
    suffix = "_static" if static else ""
    low = -float(_core.lower_torque(scene.thread, mu, clamp))
    high = float(_core.raise_torque(scene.thread, mu, clamp))
    forward = 1.0 / train["efficiency" + suffix]
    backward = train["efficiency_backdrive" + suffix]
    k, tau = min(((backward, low), (backward, high), (forward, low), (forward, high)),
                 key=lambda split: split[0] * split[1])
    return abs(tau), abs(k)


def _require_self_locking(scene) -> None:
    """A thread that holds a clamp by itself, tan(alpha) < mu_static', or a
    self-locking stage of the train (eta_b,static <= 0) that holds it.

    Raises:
        ValueError: the train back-drives (nothing jams: the stop pushes the
            drive back once the drive lets go).
    """
    friction = scene["friction"]
    mu_static = friction.get("mu_static", friction["mu"])
    if _train(scene)["efficiency_backdrive_static"] <= 0.0:
        return
    if not _core.lower_torque(scene.thread, mu_static, 1.0) > 0.0:
        raise ValueError(f"friction.mu_static = {mu_static!r} is invalid for end_stop_jam: the "
                         "thread is not self-locking (tan(alpha) >= mu_static') and no "
                         "self-locking gear stage holds it, so nothing jams: the stop pushes "
                         "the drive back as soon as the drive lets go")


def _closed_form(scene, kind: str, clamp: float, static: bool = True) -> Dict[str, float]:
    """The breakaway's torque on the driven part T (T_b = F r_m tan(rho_s' -
    alpha) without friction stages: _breakaway_split), the motor's torque
    |k| T / |n| + T_c (``breakaway_motor_torque_closed_form``) and, with a DC
    motor, U_b = R (|k| T + |n| T_c) / (|n| k_t). ``static=False``: the same
    with the sliding coefficients (the keys ``..._kinetic``; 0 where the
    sliding thread back-drives behind a stage that does too)."""
    torque, k = _breakaway_split(scene, clamp, static)
    if not static and not (_core.lower_torque(scene.thread, scene["friction"]["mu"], 1.0) > 0.0
                           or _train(scene)["efficiency_backdrive"] <= 0.0):
        torque = 0.0
    n, friction_torque = abs(gear_ratio(scene)), _train(scene)["motor_friction_torque"]
    suffix = "_closed_form" if static else "_kinetic"
    out = {"breakaway_torque" + suffix: torque, "breakaway_voltage" + suffix: math.nan,
           "breakaway_motor_torque" + suffix: k * torque / n + friction_torque}
    if kind == "voltage":
        motor = scene["motor"]
        limit = motor.get("current_limit", math.inf)
        current = (k * torque + n * friction_torque) / (n * motor["torque_constant"])
        out["breakaway_voltage" + suffix] = (math.inf if current > limit
                                             else motor["resistance"] * current)
    return out


class _Reversals:
    """The reversing runs of one study: each judged in a window of
    t_reverse, doubled while the run is undecided (_end_stop_runs_module.judge) up
    to t_reverse_max; the rows and the figure's histories they leave."""

    def __init__(self, running, kind, forward, t_drive, clamp, clamping, windows, options,
                 bar):
        self.running, self.kind, self.forward, self.t_drive = running, kind, forward, t_drive
        self.clamp, self.clamping, self.windows, self.options = clamp, clamping, windows, options
        self.bar, self.rows, self.histories = bar, [], {}
        self.verdicts: Dict[float, runs_module.Verdict] = {}
        # (On a flexible drive, or in play, a slip at the end may be the springs'
        # or the play's motion, not the clamp's release: there the stop must let go.)
        self.slipping_frees = (running["concept"] == "rigid" and "backlash" not in running)

    def frees(self, x: float) -> Optional[bool]:
        """One reversing run, -sign x after t_drive: True if it freed, False if
        it was held at rest, None if it raised or stayed undecided in the
        longest window (it decides nothing: its row carries the reason)."""
        self.bar.update()
        sign = math.copysign(1.0, self.forward)
        row = {"reverse": x, "broke_free": False, "stop_force_end": math.nan, "error": None,
               "window": math.nan, "t_free": math.nan, "thread_force_end": math.nan}
        self.rows.append(row)
        for window in self.windows:
            t_end = self.t_drive + window
            scene = runs_module.with_drive(self.running, self.kind, self.forward, -sign * x,
                                           self.t_drive, t_end)
            row["window"] = window
            try:
                result = simulate(scene, t_end,
                                  t_eval=runs_module.output_times(self.t_drive, t_end),
                                  **self.options)
            except SimulationError as error:
                # Only a load that left the stop runs the nut to the screw's end.
                free = error.time > self.t_drive and isinstance(error, NutOffScrewError)
                row.update(broke_free=free, error=None if free else f"{type(error).__name__}: "
                                                                   f"{error}")
                return True if free else None
            except (ValueError, ArithmeticError, RuntimeError) as error:
                row["error"] = f"{type(error).__name__}: {error}"
                return None
            verdict = runs_module.judge(result, self.t_drive, window, self.clamping,
                                        self.clamp, self.slipping_frees)
            if verdict.free is not None:
                break
        row.update(stop_force_end=float(result["stop_force"][-1]), t_free=verdict.t_free,
                   broke_free=bool(verdict.free),
                   thread_force_end=abs(float(result["stop_force"][-1])
                                        + float(result["axial_force"][-1])))
        if verdict.free is None:
            row["error"] = (f"undecided: neither freed nor held at rest after "
                            f"{self.windows[-1]:.6g} s reversed (a longer t_reverse_max)")
            return None
        self.verdicts[x] = verdict
        self.histories["freeing" if verdict.free else "held"] = (
            x, (result.t - self.t_drive).tolist(), result["stop_force"].tolist(),
            verdict.t_free)
        return verdict.free


def _bisect(frees, low: float, high: float, probe: float, ceiling: float, runs_left,
            resolution: float) -> Tuple[float, float, bool, list]:
    """The bracket [last held, first freeing] of the reverse x: high doubled
    until a run frees (not beyond ``ceiling``), then the probes ``probe``
    (the sliding closed form) and 0 (the drive switched off) where they lie
    inside, and bisection down to ``resolution`` of high, while
    ``runs_left()``. A run that decides nothing (None) is listed; the
    doubling goes on past it with low where it was, the bisection stops at
    it. Returns (low, high, found, undecided)."""
    undecided, found = [], False
    while runs_left():
        outcome = frees(high)
        if outcome:
            found = True
            break
        if outcome is None:
            undecided.append(high)
        if high > ceiling:
            break
        if outcome is not None:
            low = high
        high = 2.0 * high
    for x in (probe, 0.0):
        if found and low < x < high and runs_left():
            outcome = frees(x)
            if outcome is None:
                return low, high, found, undecided + [x]
            low, high = (low, x) if outcome else (x, high)
    while found and runs_left() and high - low > resolution * abs(high):
        middle = 0.5 * (low + high)
        outcome = frees(middle)
        if outcome is None:
            undecided.append(middle)
            break
        if outcome:
            high = middle
        else:
            low = middle
    return low, high, found, undecided


def end_stop_jam(
    scene: Any,
    t_drive: Optional[float] = None,
    t_reverse: float = 0.2,
    runs: int = 30,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    progress: bool = True,
    t_reverse_max: Optional[float] = None,
    resolution: float = 1e-3,
    **simulate_options: Any,
) -> pd.DataFrame:
    """Drive into the end stop under the scene's motor, then reverse with a
    step to a constant reverse torque (or voltage): the peak clamp force, the
    peak current and the smallest constant reverse that frees the load, the
    time it takes, beside the quasi-static closed form and its sliding
    (kinetic) counterpart (docs/physics/end_stops.md, "The study
    end_stop_jam").

    Args:
        scene: a :class:`~leadscrew.Scene` (or dict) with penalty
            ``end_stops`` and a constant ``loads.drive_torque`` or a DC motor
            (``motor``) at a constant voltage, which drive the load into a
            stop; a gear stage of any type (a lossy or worm stage and the
            motor's friction on the rigid concept without play).
        t_drive: the time the drive pushes [s], > 0, within which the clamp
            must settle (the thread sticks, or the stop's force and a DC
            motor's current change by less than 1e-3 over its last tenth).
            Default: chosen from the run itself, 0.25 s doubled until the
            clamp settles (at most 64 s).
        t_reverse: the first window in which a reversing run is judged [s],
            > 0. A run is decided where the clamping stop lets go of the
            load (freed) or where the thread has stuck over the window's
            whole second half (held at rest); a run still moving (a
            stick-slip creep off the stop) is run again with the window
            doubled, up to ``t_reverse_max``. The answer does not depend on
            it; a window near the runs' time scales only saves doublings.
        runs: the largest number of reversing runs (bracket and bisection),
            at least 4.
        rtol, atol: integration tolerances (default simulate's).
        progress: show a tqdm progress bar over the runs (they follow each
            other: a bisection).
        t_reverse_max: the longest window [s], >= t_reverse (default 32
            t_reverse): a run undecided then decides nothing.
        resolution: the bisection stops where the bracket is narrower than
            this fraction of its upper end, > 0 (default 1e-3).
        **simulate_options: passed on to :func:`leadscrew.simulate` (all
            but ``t_eval``).

    Returns:
        DataFrame with one row per reversing run, in the order run:
        ``reverse_torque`` [N*m] (a torque-driven scene: the torque on the
        rotor after the reversal is -sign(M) reverse_torque) or
        ``reverse_voltage`` [V] (a DC motor), ``broke_free`` (the clamping
        stop released the load after the reversal, whatever it met then: the
        other stop, or the screw's end, which ends the run; on the rigid
        drive without play also a thread slipping away from the stop at the
        window's end), ``stop_force_end`` [N] (NaN where the run raised),
        ``window`` [s] (the window the run was decided in), ``t_free`` [s]
        (the release's time after the reversal; NaN: none in the window),
        ``error`` (why the run decides nothing). With a DC motor and a
        current limit the bracket stops doubling beyond R i_max volts (no
        more torque).
        ``attrs["summary"]``: ``drive`` ("torque" or "voltage"),
        ``clamp_force`` [N] (|stop_force| held at the reversal),
        ``thread_force`` [N] (the axial load the thread holds then:
        |stop_force + axial_force|, the closed form's F),
        ``peak_clamp_force`` [N], ``peak_current`` [A] (NaN without a DC
        motor), ``breakaway_torque`` [N*m] (on the driven part, |n| times
        the rotor's behind a gear stage; with a DC motor |n| k_t times the
        current at rest, min(U_b / R, i_max)),
        ``breakaway_torque_closed_form`` [N*m] (the static stick test's edge;
        through the train's friction stages: the thread's torque the
        motor's gives through the stage's static efficiency, less its
        friction), ``breakaway_torque_kinetic`` [N*m] (the same with the
        sliding coefficients: below it no constant reverse keeps the thread
        slipping back from the clamp), ``breakaway_motor_torque``,
        ``breakaway_motor_torque_closed_form`` and
        ``breakaway_motor_torque_kinetic`` [N*m] (the motor's torque on the
        rotor: k_t i, or the reverse torque; k T / |n| + T_c),
        ``breakaway_voltage``, ``breakaway_voltage_closed_form`` and
        ``breakaway_voltage_kinetic`` [V] (NaN without a DC motor; inf where
        the current limit cannot reach the torque), ``thread_force_held``
        [N] (the thread's force at rest in the last held run: the step's
        ringing slips relax the clamp; NaN where no run held) and
        ``breakaway_torque_held_clamp``, ``breakaway_motor_torque_held_clamp``,
        ``breakaway_voltage_held_clamp`` (the static closed form at that
        clamp: the breakaway where mu_static = mu), ``t_free`` [s] (the
        first freeing run at the breakaway: the time from the reversal to
        the stop's release; NaN where it freed by slipping away),
        ``slips_to_free`` [1] (that run's breakaways of the thread, stick to
        slip, before the release: 1, a single slip; many, a stick-slip
        creep off the stop), ``bracket`` (the last held and the first
        freeing reverse [N*m or V]; inf: none freed), ``t_drive``,
        ``t_reverse`` and ``t_reverse_max`` [s], ``runs``, ``undecided``
        (the reverses whose runs raised or stayed undecided [N*m or V]: they
        decide nothing, the bisection stops at the first such one, so the
        breakaway is then only known to lie in ``bracket``; their rows carry
        the reason).
        ``attrs["histories"]``: ``t`` [s] (after the reversal), ``stop_force``
        [N], ``reverse`` and ``t_free`` of the last held and the first
        freeing run (lists, for the figure).

    Raises:
        ValueError: no penalty end stops, a drive that is not a nonzero
            constant, a thread that is not self-locking behind a stage that
            is not either, invalid times, runs or resolution (naming the
            argument), or the load does not rest clamped against a stop at
            ``t_drive`` (or, without one, within 64 s).
    """
    progress = shown(progress)
    scene = as_scene(scene, gear=True)
    kind, forward = _drive(scene)
    _require_self_locking(scene)
    if t_drive is not None:
        t_drive = check_positive("t_drive", t_drive, unit="s")
    t_reverse = check_positive("t_reverse", t_reverse, unit="s")
    t_reverse_max = (32.0 * t_reverse if t_reverse_max is None
                     else check_positive("t_reverse_max", t_reverse_max, unit="s"))
    if t_reverse_max < t_reverse:
        raise ValueError(f"t_reverse_max = {t_reverse_max!r} is invalid for end_stop_jam: "
                         f"must be at least t_reverse = {t_reverse!r} s")
    runs = check_count("runs", runs, 4)
    resolution = check_positive("resolution", resolution)
    options = with_tolerances(dict(simulate_options), rtol, atol)
    running = scene.replace(initial={"rotor_speed": 0.0, "state": "relaxed"})
    pushing, t_drive = runs_module.push(running, kind, forward, t_drive, options)
    return _reverse(scene, running, kind, forward, pushing, t_drive, t_reverse, t_reverse_max,
                    runs, resolution, options, progress)


def _reverse(scene, running, kind, forward, pushing, t_drive, t_reverse, t_reverse_max, runs,
             resolution, options, progress) -> pd.DataFrame:
    """The reversing runs' bisection after the drive's run ``pushing``, and
    the study's frame."""
    clamp = abs(float(pushing["stop_force"][-1]))
    # The stop that clamps (its force pushes the load along +x: the lower one).
    clamping = "lower end stop" if float(pushing["stop_force"][-1]) > 0.0 else "upper end stop"
    windows = [t_reverse]
    while 2.0 * windows[-1] <= t_reverse_max * (1.0 + 1e-12):
        windows.append(2.0 * windows[-1])
    bar = _progress_bar(runs, "end_stop_jam", progress)
    reversals = _Reversals(running, kind, forward, t_drive, clamp, clamping, windows, options,
                           bar)
    # The thread holds the load against the stop's force and the axial load
    # together (the load at rest): the clamp the thread carries.
    thread_force = abs(float(pushing["stop_force"][-1]) + float(pushing["axial_force"][-1]))
    closed = {**_closed_form(scene, kind, thread_force),
              **_closed_form(scene, kind, thread_force, static=False)}
    # (in the units of the reverse drive: the rotor's torque, or the voltage)
    unit = "voltage" if kind == "voltage" else "motor_torque"
    estimate, kinetic = closed[f"breakaway_{unit}_closed_form"], closed[f"breakaway_{unit}_kinetic"]
    # The bracket: the forward drive itself holds (the run's state at
    # t_drive); the reverse starts just above the closed form (or at the
    # forward drive's size) and is doubled until it frees. With a DC motor
    # the torque at rest is k_t min(U / R, i_max): beyond R i_max volts a
    # larger reverse voltage adds nothing.
    high = 1.01 * estimate if math.isfinite(estimate) and estimate > 0.0 else abs(forward)
    ceiling = math.inf
    if kind == "voltage" and "current_limit" in scene["motor"]:
        ceiling = scene["motor"]["resistance"] * scene["motor"]["current_limit"]
    low, high, found, undecided = _bisect(
        reversals.frees, -abs(forward), high, kinetic if math.isfinite(kinetic) else math.nan,
        ceiling, lambda: len(reversals.rows) < runs, resolution)
    bar.close()
    breakaway = high if found else math.inf
    verdict = reversals.verdicts.get(high) if found else None
    summary = {"drive": kind, "clamp_force": clamp, "thread_force": thread_force,
               "peak_clamp_force": float(np.max(np.abs(pushing["stop_force"]))),
               "peak_current": (float(np.max(np.abs(pushing["motor_current"])))
                                if kind == "voltage" else math.nan),
               **closed, "bracket": (low, breakaway),
               "t_free": verdict.t_free if verdict else math.nan,
               "slips_to_free": verdict.slips if verdict else 0,
               "t_drive": t_drive, "t_reverse": t_reverse, "t_reverse_max": t_reverse_max,
               "runs": len(reversals.rows), "undecided": undecided}
    summary.update(_breakaway_torques(scene, kind, breakaway, found, thread_force))
    summary.update(_held_clamp(scene, kind, reversals.rows, low))
    column = "reverse_voltage" if kind == "voltage" else "reverse_torque"
    rows = reversals.rows
    frame = frame_of({column: [row["reverse"] for row in rows],
                      **{name: [row[name] for row in rows]
                         for name in ("broke_free", "stop_force_end", "window", "t_free",
                                      "error")}})
    frame.attrs["histories"] = {name: {"reverse": x, "t": t, "stop_force": f, "t_free": t_free}
                                for name, (x, t, f, t_free) in reversals.histories.items()}
    return annotate(frame, UNITS, study="end_stop_jam",
                    summary_units={**_SUMMARY_UNITS, "bracket": UNITS[column],
                                   "undecided": UNITS[column]}, **summary)


def _held_clamp(scene, kind: str, rows, low: float) -> Dict[str, float]:
    """``thread_force_held`` [N], the thread's force at rest in the last run
    that held (the bracket's low end; NaN where that is the forward drive,
    not a run): the step's ringing slips the thread a few times before it
    sticks, and each slip relaxes the clamp; and the static closed form at
    that clamp (``..._held_clamp``), the breakaway where the sliding and the
    static coefficients agree (docs/physics/end_stops.md, "After a step of
    reverse drive")."""
    held = [row["thread_force_end"] for row in rows
            if row["reverse"] == low and row["error"] is None and not row["broke_free"]]
    force = held[-1] if held else math.nan
    forms = _closed_form(scene, kind, force if held else 0.0)
    out = {"thread_force_held": force}
    for name in ("torque", "motor_torque", "voltage"):
        value = forms[f"breakaway_{name}_closed_form"]
        out[f"breakaway_{name}_held_clamp"] = value if held else math.nan
    return out


def _breakaway_torques(scene, kind: str, breakaway: float, found: bool,
                       thread_force: float) -> Dict[str, float]:
    """The motor's torque at the breakaway and the driven part's through the
    train's branch (an ideal stage or none: n times the motor's)."""
    k = _breakaway_split(scene, thread_force)[1]
    n = abs(gear_ratio(scene))
    friction_torque = _train(scene)["motor_friction_torque"]
    if kind == "voltage":
        motor = scene["motor"]
        current = min(breakaway / motor["resistance"], motor.get("current_limit", math.inf))
        motor_torque = motor["torque_constant"] * current if found else math.inf
        return {"breakaway_voltage": breakaway, "breakaway_motor_torque": motor_torque,
                "breakaway_torque": (n * (motor_torque - friction_torque) / k if found
                                     else math.inf)}
    return {"breakaway_voltage": math.nan, "breakaway_motor_torque": breakaway,
            "breakaway_torque": n * (breakaway - friction_torque) / k}


def _distinct_labels(values: Dict[str, float], unit: str) -> Dict[str, str]:
    """Each value with as many significant digits as it takes (4 to 12) for
    the labels to differ: the bisection leaves the last held and the first
    freeing reverse a resolution apart."""
    texts: Dict[str, str] = {}
    for digits in range(4, 13):
        texts = {name: f"{value:.{digits}g} {unit}" for name, value in values.items()}
        if len(set(texts.values())) == len(texts):
            break
    return texts


def plot_end_stop_jam(frame: pd.DataFrame, ax: Optional[Any] = None):
    """Draw the stop's force over the time after the reversal in the last run
    that held (it comes to rest clamped) and the first that broke free (down
    to its release, marked), with the clamp force and the breakaway
    (simulated, the static closed form and its sliding counterpart) in the
    legend.

    Args:
        frame: what :func:`end_stop_jam` returned (its ``attrs["histories"]``
            and summary are drawn).
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes, the stop's force [N] over the time after the reversal [s].
    """
    ax = axes(ax)
    summary = frame.attrs.get("summary", {})
    unit = "V" if summary.get("drive") == "voltage" else "N*m"
    histories = {name: history for name, history in frame.attrs.get("histories", {}).items()
                 if history}
    labels = _distinct_labels({name: h["reverse"] for name, h in histories.items()}, unit)
    span = max((h["t"][-1] for h in histories.values()), default=1.0)
    styles = {"held": dict(color="C0", linestyle="-", linewidth=1.6),
              "freeing": dict(color="C3", linestyle="--", linewidth=1.2)}
    for name in ("held", "freeing"):
        if name not in histories:
            continue
        t, force = np.asarray(histories[name]["t"]), np.abs(histories[name]["stop_force"])
        shown = t >= -0.05 * span  # the reversal, not the whole run into the stop
        text = {"held": "held at rest", "freeing": "freed"}[name]
        ax.plot(t[shown], force[shown], label=f"{text}: reverse {labels[name]}",
                **styles[name])
        t_free = histories[name].get("t_free", math.nan)
        if name == "freeing" and math.isfinite(t_free):
            ax.axvline(t_free, color="C3", linestyle=":", linewidth=0.8,
                       label=f"released after {t_free:.3g} s")
    clamp = summary.get("clamp_force")
    if clamp is not None:
        ax.axhline(clamp, color="k", linestyle=":", label=f"clamp force {clamp:.4g} N")
    key = "breakaway_voltage" if unit == "V" else "breakaway_motor_torque"
    simulated, closed = summary.get(key), summary.get(f"{key}_closed_form")
    if simulated is not None and closed is not None:
        kinetic = summary.get(f"{key}_kinetic", math.nan)
        ax.plot([], [], " ", label=f"breakaway {simulated:.4g} {unit} (closed forms: static "
                                   f"{closed:.4g}, sliding {kinetic:.4g} {unit})")
    ax.axvline(0.0, color="0.6", linewidth=0.8)
    ax.set_xlabel("time after the reversal [s]")
    ax.set_ylabel("|stop force| [N]")
    ax.legend(loc="best", fontsize="small")
    return ax
