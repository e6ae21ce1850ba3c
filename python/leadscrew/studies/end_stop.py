"""The drive jammed at its end stop (issue 19, item 5): ``end_stop_jam``.

The scene's motor (a constant drive torque M, or a DC motor at a constant
voltage U) drives the load into the scene's penalty end stop for
``t_drive``; the thread clamps, and a self-locking thread keeps the clamp
force F after the drive lets go. Then the drive reverses: at ``t_drive``
the torque steps to -x (the voltage to -x), held for ``t_reverse``. The
smallest reverse x that breaks the thread free (the stop releases the
load; on the rigid drive without play also a thread that slips away from
the stop at the run's end, the clamp falling as it goes) is found by
bisection over runs of the whole sequence, a bounded number of them.

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
from .._progress import shown
from ._common import (annotate, as_scene, axes, check_count, check_positive, constant_value,
                      frame_of, gear_ratio)
from ._sweep import _progress_bar

__all__ = ["end_stop_jam", "plot_end_stop_jam"]

UNITS = {"reverse_torque": "N*m", "reverse_voltage": "V", "broke_free": "",
         "stop_force_end": "N", "error": ""}
_SUMMARY_UNITS = {"clamp_force": "N", "thread_force": "N", "peak_clamp_force": "N",
                  "peak_current": "A",
                  "breakaway_torque": "N*m", "breakaway_torque_closed_form": "N*m",
                  "breakaway_motor_torque": "N*m", "breakaway_motor_torque_closed_form": "N*m",
                  "breakaway_voltage": "V", "breakaway_voltage_closed_form": "V",
                  "t_drive": "s", "t_reverse": "s", "runs": "1"}


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
    if "motor" in scene:
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


def _with_drive(scene, kind: str, forward: float, reverse: Optional[float], t_drive: float,
                t_end: float):
    """The scene with its drive held at ``forward`` up to t_drive, then
    stepped to ``reverse`` (None: held)."""
    if reverse is None:
        value: Any = forward
    else:
        step = 1e-9 * t_end
        value = {"type": "table", "times": [0.0, t_drive, t_drive + step, t_end],
                 "values": [forward, forward, reverse, reverse]}
    if kind == "voltage":
        return scene.replace(motor={"voltage": value})
    return scene.replace(loads={"drive_torque": value})


def _train(scene) -> Dict[str, float]:
    """The train's friction stages' static efficiencies and the motor's
    friction T_c [N*m] (an ideal stage or none: 1, 1, 0)."""
    train = scene.model().train_friction
    if not train:
        return {"efficiency_static": 1.0, "efficiency_backdrive_static": 1.0,
                "motor_friction_torque": 0.0}
    return {name: train[name] for name in ("efficiency_static", "efficiency_backdrive_static",
                                           "motor_friction_torque")}


def _breakaway_split(scene, clamp: float) -> Tuple[float, float]:
    """(the torque on the driven part [N*m], |k|) at the breakaway of a clamp
    F [N]: the static stick test's edge (docs/physics/gear.md, "End stops
    through the stages"). At rest the thread holds the torques tau in
    [-T_b, T_r] (T_b = F r_m tan(rho_s' - alpha), T_r = F r_m tan(alpha +
    rho_s'): its lowering and raising torques with mu_static) and the stage
    passes x = k tau with k between eta_b,static and 1 / eta_static; the
    motor moves the clamp back where its torque on the stage's input exceeds
    the largest -x of them all, |k| |tau| (an ideal stage or none: T_b)."""
    friction = scene["friction"]
    mu_static = friction.get("mu_static", friction["mu"])
    train = _train(scene)
    low = -float(_core.lower_torque(scene.thread, mu_static, clamp))
    high = float(_core.raise_torque(scene.thread, mu_static, clamp))
    forward, backward = 1.0 / train["efficiency_static"], train["efficiency_backdrive_static"]
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


def _closed_form(scene, kind: str, clamp: float) -> Dict[str, float]:
    """The breakaway's torque on the driven part T (T_b = F r_m tan(rho_s' -
    alpha) without friction stages: _breakaway_split), the motor's torque
    |k| T / |n| + T_c (``breakaway_motor_torque_closed_form``) and, with a DC
    motor, U_b = R (|k| T + |n| T_c) / (|n| k_t)."""
    torque, k = _breakaway_split(scene, clamp)
    n, friction_torque = abs(gear_ratio(scene)), _train(scene)["motor_friction_torque"]
    out = {"breakaway_torque_closed_form": torque, "breakaway_voltage_closed_form": math.nan,
           "breakaway_motor_torque_closed_form": k * torque / n + friction_torque}
    if kind == "voltage":
        motor = scene["motor"]
        limit = motor.get("current_limit", math.inf)
        current = (k * torque + n * friction_torque) / (n * motor["torque_constant"])
        out["breakaway_voltage_closed_form"] = (math.inf if current > limit
                                                else motor["resistance"] * current)
    return out


def end_stop_jam(
    scene: Any,
    t_drive: float = 0.5,
    t_reverse: float = 0.2,
    runs: int = 30,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    progress: bool = True,
    **simulate_options: Any,
) -> pd.DataFrame:
    """Drive into the end stop under the scene's motor, then reverse: the peak
    clamp force, the peak current and the smallest reverse torque (or voltage)
    that breaks the thread free, beside the quasi-static closed form.

    Args:
        scene: a :class:`~leadscrew.Scene` (or dict) with penalty
            ``end_stops`` and a constant ``loads.drive_torque`` or a DC motor
            (``motor``) at a constant voltage, which drive the load into a
            stop within ``t_drive``; a gear stage of any type (a lossy or
            worm stage and the motor's friction on the rigid concept
            without play).
        t_drive: the time the drive pushes [s], > 0: the load reaches the
            stop and the clamp settles.
        t_reverse: the time the reverse torque or voltage is held [s], > 0.
        runs: the largest number of reversing runs (bracket and bisection),
            at least 4; the breakaway is resolved to the bracket's width
            over 2^(runs - bracketing runs).
        rtol, atol: integration tolerances (default simulate's).
        progress: show a tqdm progress bar over the runs (they follow each
            other: a bisection).
        **simulate_options: passed on to :func:`leadscrew.simulate` (all
            but ``t_eval``).

    Returns:
        DataFrame with one row per reversing run, in the order run:
        ``reverse_torque`` [N*m] (a torque-driven scene: the torque on the rotor after
        the reversal is -sign(M) reverse_torque) or ``reverse_voltage`` [V]
        (a DC motor), ``broke_free`` (the clamping stop released the load
        after the reversal, whatever it met then: the other stop, or the
        screw's end, which ends the run), ``stop_force_end`` [N] (NaN where
        the run ended at the screw's end), ``error``. With a DC motor and a
        current limit the bracket stops doubling beyond R i_max volts (no more
        torque).
        ``attrs["summary"]``: ``drive`` ("torque" or "voltage"),
        ``clamp_force`` [N] (|stop_force| held at the reversal),
        ``thread_force`` [N] (the axial load the thread holds then: |stop_force
        + axial_force|, the closed form's F),
        ``peak_clamp_force`` [N], ``peak_current`` [A] (NaN without a DC
        motor), ``breakaway_torque`` [N*m] (on the driven part, |n| times the rotor's behind a gear stage; with a DC
        motor |n| k_t times the current at rest, min(U_b / R, i_max)),
        ``breakaway_torque_closed_form`` [N*m] (through the train's
        friction stages: the thread's torque the motor's gives through the
        stage's static efficiency, less its friction),
        ``breakaway_motor_torque`` and ``breakaway_motor_torque_closed_form``
        [N*m] (the motor's torque on the rotor: k_t i, or the reverse
        torque; k T_b / |n| + T_c), ``breakaway_voltage`` and
        ``breakaway_voltage_closed_form`` [V] (NaN without a DC motor; inf
        where the current limit cannot reach the torque), ``bracket`` (the
        last held and the first freeing reverse [N*m or V]; inf: none freed),
        ``t_drive`` and ``t_reverse`` [s], ``runs``, ``undecided`` (the
        reverses whose runs raised [N*m or V]: they decide nothing, the
        bisection stops at the first such one, so the breakaway is then
        only known to lie in ``bracket``; their rows carry the message).
        ``attrs["histories"]``: ``t`` [s] and ``stop_force`` [N] of the
        last held and the first freeing run (lists, for the figure).

    Raises:
        ValueError: no penalty end stops, a drive that is not a nonzero
            constant, a thread that is not self-locking behind a stage that
            is not either, invalid times or
            runs (naming the argument), or the load does not rest clamped
            against a stop at ``t_drive``.
    """
    progress = shown(progress)
    scene = as_scene(scene, gear=True)
    kind, forward = _drive(scene)
    _require_self_locking(scene)
    t_drive = check_positive("t_drive", t_drive, unit="s")
    t_reverse = check_positive("t_reverse", t_reverse, unit="s")
    runs = check_count("runs", runs, 4)
    options = dict(simulate_options)
    if rtol is not None:
        options["rtol"] = rtol
    if atol is not None:
        options["atol"] = atol
    t_end = t_drive + t_reverse
    running = scene.replace(initial={"rotor_speed": 0.0, "state": "relaxed"})

    pushing = simulate(_with_drive(running, kind, forward, None, t_drive, t_drive), t_drive,
                       t_eval="steps", **options)
    clamp = abs(float(pushing["stop_force"][-1]))
    if clamp == 0.0:
        raise ValueError(f"t_drive = {t_drive!r} is invalid for end_stop_jam: the load does "
                         "not press on an end stop at its end (a stop out of reach, or a "
                         "longer t_drive)")
    # Settled: the thread stuck, or (a DC motor's back-EMF damps the approach
    # to the quasi-static clamp, which the slip then reaches only
    # asymptotically, never stopping at a zero of the slip) a clamp force
    # that changed by less than 1e-3 over the drive's last tenth.
    stuck = pushing["stick"][-1] == 1.0
    earlier = abs(float(np.interp(0.9 * t_drive, pushing.t, pushing["stop_force"])))
    if not (stuck or abs(clamp - earlier) <= 1e-3 * clamp):
        raise ValueError(f"t_drive = {t_drive!r} is invalid for end_stop_jam: the clamp has "
                         "not settled at its end (the thread does not stick against the stop, "
                         f"and the stop's force changed from {earlier:.6g} N to {clamp:.6g} N "
                         "over the last tenth of t_drive: a longer t_drive, or more "
                         "end_stops.damping)")
    peak_current = (float(np.max(np.abs(pushing["motor_current"]))) if kind == "voltage"
                    else math.nan)
    sign = math.copysign(1.0, forward)
    # The stop that clamps (its force pushes the load along +x: the lower one).
    clamping = "lower end stop" if float(pushing["stop_force"][-1]) > 0.0 else "upper end stop"

    rows = []
    histories: Dict[str, Any] = {}
    bar = _progress_bar(runs, "end_stop_jam", progress)
    # (On a flexible drive, or in play, a slip at the end may be the springs'
    # or the play's motion, not the clamp's release: there the stop must let go.)
    slipping_frees = scene["concept"] == "rigid" and "backlash" not in scene

    def frees(x: float) -> Optional[bool]:
        """One reversing run: -sign x after t_drive; True if the clamping stop let
        go of the load after the reversal (whatever the load met then: the
        other stop, or the screw's end), or (rigid, without play) the thread
        slips away from the stop at the run's end; None if the run raised
        (it decides nothing: its row carries the message)."""
        bar.update()
        try:
            result = simulate(_with_drive(running, kind, forward, -sign * x, t_drive, t_end),
                              t_end, t_eval="steps", **options)
        except SimulationError as error:
            # Only a load that left the stop runs the nut to the screw's end.
            free = error.time > t_drive and isinstance(error, NutOffScrewError)
            rows.append({"reverse": x, "broke_free": free, "stop_force_end": math.nan,
                         "error": None if free else f"{type(error).__name__}: {error}"})
            return True if free else None
        except (ValueError, ArithmeticError, RuntimeError) as error:
            rows.append({"reverse": x, "broke_free": False, "stop_force_end": math.nan,
                         "error": f"{type(error).__name__}: {error}"})
            return None
        free = any(event.time > t_drive and f"{clamping} release" in event.kind
                   for event in result.events) or float(result["stop_force"][-1]) == 0.0
        if not free and slipping_frees:
            # Rigid, without play: a thread slipping away from the stop at the
            # end has broken free (the clamp it must overcome only falls as
            # the load moves back), however long the load takes to leave
            # the stop (a worm seat creeps back 0.7 mm at a few mm/s: with
            # the release alone 0.2 s read 6.87 V for the closed form's 4.10 V).
            away = float(result["v_load"][-1]) * (1.0 if clamping == "lower end stop" else -1.0)
            free = (result["stick"][-1] == 0.0 and away > 0.0
                    and abs(float(result["stop_force"][-1])) < clamp)
        rows.append({"reverse": x, "broke_free": free,
                     "stop_force_end": float(result["stop_force"][-1]), "error": None})
        histories["freeing" if free else "held"] = (x, result.t.tolist(),
                                                    result["stop_force"].tolist())
        return free

    # The thread holds the load against the stop's force and the axial load
    # together (the load at rest): the clamp the thread carries.
    thread_force = abs(float(pushing["stop_force"][-1]) + float(pushing["axial_force"][-1]))
    closed = _closed_form(scene, kind, thread_force)
    # (in the units of the reverse drive: the rotor's torque, or the voltage)
    n = abs(gear_ratio(scene))
    estimate = (closed["breakaway_voltage_closed_form"] if kind == "voltage"
                else closed["breakaway_motor_torque_closed_form"])
    # The bracket: the forward drive itself holds (the run's state at t_drive);
    # the reverse is doubled from max(|forward|, the closed form) until it frees.
    low = -abs(forward)
    high = max(abs(forward), estimate if math.isfinite(estimate) else 0.0)
    found = False
    # With a DC motor the torque at rest is k_t min(U / R, i_max): beyond R i_max
    # volts a larger reverse voltage adds nothing.
    ceiling = math.inf
    if kind == "voltage" and "current_limit" in scene["motor"]:
        ceiling = scene["motor"]["resistance"] * scene["motor"]["current_limit"]
    # A run that raised decides nothing (a Moreau-Jean step too long for
    # the stall or the breakaway raises JammingError): the doubling goes on
    # past it with low where it was, and the bisection stops at it, the
    # bracket [low, high] the runs that decided (the summary's
    # `undecided`: the reverses that raised).
    undecided = []
    while len(rows) < runs:
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
    while found and len(rows) < runs:
        middle = 0.5 * (low + high)
        outcome = frees(middle)
        if outcome is None:
            undecided.append(middle)
            break
        if outcome:
            high = middle
        else:
            low = middle
    bar.close()
    breakaway = high if found else math.inf

    summary = {"drive": kind, "clamp_force": clamp, "thread_force": thread_force,
               "peak_clamp_force": float(np.max(np.abs(pushing["stop_force"]))),
               "peak_current": peak_current, **closed,
               "bracket": (low, high if found else math.inf),
               "t_drive": t_drive, "t_reverse": t_reverse, "runs": len(rows),
               "undecided": undecided}
    # The motor's torque at the breakaway and the driven part's through the
    # train's branch (an ideal stage or none: n times the motor's).
    k = _breakaway_split(scene, thread_force)[1]
    friction_torque = _train(scene)["motor_friction_torque"]
    if kind == "voltage":
        motor = scene["motor"]
        current = min(breakaway / motor["resistance"], motor.get("current_limit", math.inf))
        summary["breakaway_voltage"] = breakaway
        motor_torque = motor["torque_constant"] * current if found else math.inf
        summary["breakaway_torque"] = (n * (motor["torque_constant"] * current - friction_torque)
                                       / k if found else math.inf)
    else:
        summary["breakaway_voltage"] = math.nan
        motor_torque = breakaway
        summary["breakaway_torque"] = n * (breakaway - friction_torque) / k
    summary["breakaway_motor_torque"] = motor_torque
    column = "reverse_voltage" if kind == "voltage" else "reverse_torque"
    frame = frame_of({column: [row["reverse"] for row in rows],
                      "broke_free": [row["broke_free"] for row in rows],
                      "stop_force_end": [row["stop_force_end"] for row in rows],
                      "error": [row["error"] for row in rows]})
    frame.attrs["histories"] = {name: {"reverse": x, "t": t, "stop_force": f}
                                for name, (x, t, f) in histories.items()}
    return annotate(frame, UNITS, study="end_stop_jam",
                    summary_units={**_SUMMARY_UNITS, "bracket": UNITS[column],
                                   "undecided": UNITS[column]}, **summary)


def plot_end_stop_jam(frame: pd.DataFrame, ax: Optional[Any] = None):
    """Draw the stop's force over time in the last run that held and the
    first that broke free, with the clamp force and the breakaway (simulated
    and closed form) in the legend.

    Args:
        frame: what :func:`end_stop_jam` returned (its ``attrs["histories"]``
            and summary are drawn).
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes, the stop's force [N] over the time [s].
    """
    ax = axes(ax)
    summary = frame.attrs.get("summary", {})
    unit = "V" if summary.get("drive") == "voltage" else "N*m"
    for name, style in (("held", "-"), ("freeing", "--")):
        history = frame.attrs.get("histories", {}).get(name)
        if history:
            ax.plot(history["t"], np.abs(history["stop_force"]), style,
                    label=f"{name}: reverse {history['reverse']:.4g} {unit}")
    clamp = summary.get("clamp_force")
    if clamp is not None:
        ax.axhline(clamp, color="k", linestyle=":", label=f"clamp force {clamp:.4g} N")
    key = "breakaway_voltage" if unit == "V" else "breakaway_torque"
    simulated, closed = summary.get(key), summary.get(f"{key}_closed_form")
    if simulated is not None and closed is not None:
        ax.plot([], [], " ", label=f"breakaway {simulated:.4g} {unit} "
                                   f"(closed form {closed:.4g} {unit})")
    t_drive = summary.get("t_drive")
    if t_drive is not None:
        ax.axvline(t_drive, color="0.6", linewidth=0.8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("|stop force| [N]")
    ax.legend(loc="best", fontsize="small")
    return ax
