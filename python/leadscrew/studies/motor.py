"""A DC motor's characteristics on the drive (issue 19, item 5).

The scene's DC motor (section ``motor``, constant voltage U) raises each axial
load from rest; at the end of the run the drive turns at its steady speed.
Beside the simulation, the rigid drive's steady state in closed form
(docs/physics/dc_motor.md), from rest: with the stall torque
T_s = k_t min(U / R, i_max) and rho_s' = atan(mu_static'),

- raising where T_s > F r_m tan(alpha + rho_s') (the breakaway): the train
  needs the raise torque T = F r_m tan(alpha + rho') (:func:`leadscrew.raise_torque`),
  so i = T / k_t, omega = (U - R T / k_t) / k_e, the input power U i and the
  whole train's efficiency F v / (U i) with v = omega lead / (2 pi);
- back-driven where the thread can be (tan(alpha) > mu_static') and
  T_s < F r_m tan(alpha - rho_s'): the load turns the rotor against the
  voltage; the torque that holds the lowering load, T = F r_m tan(alpha - rho')
  (-:func:`leadscrew.lower_torque`), gives i = T / k_t > U / R and
  omega = (U - R T / k_t) / k_e < 0; where i > i_max the driver, bounded by
  its supply, saturates at -U against the current once the back-EMF passes
  it, and the load settles at omega = -(U + R T / k_t) / k_e
  (``back_driven_saturated``, the input power -U i: the driver absorbs);
- else stalled: at rest at the stall current.

The stall load (from rest) is T_s / (r_m tan(alpha + rho_s')); a drive already
moving keeps raising up to T_s / (r_m tan(alpha + rho')). The efficiency is
that of motoring: 0 at rest, NaN where the load is lowered (it gives power).
At steady state the springs of the flexible concepts carry the load
statically, so the closed form holds for every concept.

The drive runs free: the scene's end stops (section ``end_stops``) are left
out (:func:`end_stop_jam` drives into them).

Behind an ideal gear stage of ratio n (section ``gear``; the rotor turns n
times per turn of the driven part) the rotor supplies the driven part's torque
over |n|, T = F r_m tan(alpha + rho') / |n|, and turns |n| times as fast:
v = omega lead / (2 pi |n|) (docs/physics/gear.md). A reversing stage (n < 0)
raises the load in the other direction. Through a lossy or worm stage (on the
rigid concept without play) the rotor supplies that torque over eta (at
breakaway the stage's static efficiency), and a lowering load turns it back
only where the thread and the stage both pass power back (eta_b times the
thread's holding torque); the motor's own friction T_c (``motor.friction_torque``)
adds to the torque the motor gives raising and holds with it against a
back-driving load (docs/physics/gear.md, "Friction stages").
"""

from __future__ import annotations

import functools
import math
from typing import Any, Dict, Optional, Sequence, Tuple

import numpy as np
import pandas as pd

from .. import _core
from .._progress import shown
from ._batch import DriveBatch
from ._common import (annotate, as_scene, axes, check_grid, check_positive, check_window,
                      constant_value, frame_of, gear_ratio, with_tolerances)
from ._sweep import SerialExecutor, default_workers, run_batches, run_chunks

__all__ = ["motor_characteristics", "plot_motor_characteristics"]

UNITS = {"load": "N", "speed": "rad/s", "speed_closed_form": "rad/s", "current": "A",
         "current_closed_form": "A", "input_power": "W", "input_power_closed_form": "W",
         "efficiency": "1", "efficiency_closed_form": "1", "load_speed": "m/s",
         "window_change": "1", "stalled": "", "mode": "", "wall_time": "s", "error": ""}

# What each case samples at the window's start, middle and end.
_CHANNELS = ("omega_drive", "motor_current", "motor_voltage", "v_load", "work_drive",
             "work_axial", "copper_loss", "magnetic_energy")
_OMEGA, _CURRENT, _VOLTAGE, _VLOAD, _WORK, _AXIAL, _COPPER, _MAGNETIC = range(len(_CHANNELS))


def has_dc_motor(scene) -> bool:
    """Whether a DC motor drives the scene's rotor (a motor section without
    a type gives a torque-driven rotor's friction only)."""
    return "motor" in scene and scene["motor"].get("type") == "dc"


def constant_voltage(scene) -> Optional[float]:
    """The scene's DC motor voltage [V] where it is constant; None without a
    DC motor or with a voltage that varies."""
    return constant_value(scene["motor"]["voltage"]) if has_dc_motor(scene) else None


def _voltage(scene) -> float:
    """The scene's motor voltage, a constant [V].

    Raises:
        ValueError: the scene has no DC motor, or its voltage is not constant.
    """
    if not has_dc_motor(scene):
        raise ValueError("scene has no DC motor: motor_characteristics needs one "
                         "(motor = {type = \"dc\", voltage, resistance, ...})")
    voltage = constant_voltage(scene)
    if voltage is None:
        raise ValueError(f"motor.voltage = {scene['motor']['voltage']!r} is invalid for motor_characteristics: "
                         "must be a constant voltage (the steady state it reaches)")
    if voltage == 0.0:
        raise ValueError("motor.voltage = 0.0 is invalid for motor_characteristics: must be "
                         "nonzero (the motor raises each load)")
    return voltage


def _motor_constants(scene, voltage: float) -> Tuple[float, float, float, float]:
    """(R [ohm], k_t [N*m/A], k_e [V*s/rad], the stall current min(|U| / R, i_max) [A])."""
    motor = scene["motor"]
    resistance, k_t = motor["resistance"], motor["torque_constant"]
    k_e = motor.get("back_emf_constant", k_t)
    stall_current = abs(voltage) / resistance
    if "current_limit" in motor:
        stall_current = min(stall_current, motor["current_limit"])
    return resistance, k_t, k_e, stall_current


def _thread_torques(scene) -> Dict[str, float]:
    """The rigid drive's torques on the rotor per newton of axial load [N*m/N =
    m]: to raise and to lower it, with mu (moving) and with mu_static (from
    rest), over |n| behind a gear stage (over n eta raising through a lossy or
    worm stage, times eta_b lowering: at breakaway with its static
    efficiencies); a negative lowering torque: the train back-drives (the
    thread with tan(alpha) > mu' behind a stage with eta_b > 0). ``motor``:
    the motor's own friction torque T_c [N*m] (docs/physics/gear.md,
    "Friction stages")."""
    friction = scene["friction"]
    mu = friction["mu"]
    mu_static = friction.get("mu_static", mu)
    thread = scene.thread
    n = abs(gear_ratio(scene))
    train = scene.model().train_friction or {
        "motor_friction_torque": 0.0, "efficiency": 1.0, "efficiency_backdrive": 1.0,
        "efficiency_static": 1.0, "efficiency_backdrive_static": 1.0}

    def lower(mu_thread, backdrive):
        # The lowering load turns the rotor only where the thread and the
        # stage both pass power back.
        torque = _core.lower_torque(thread, mu_thread, 1.0) / n
        return torque * backdrive if torque < 0.0 and backdrive > 0.0 else abs(torque)

    return {"raise": _core.raise_torque(thread, mu, 1.0) / (n * train["efficiency"]),
            "raise_static": (_core.raise_torque(thread, mu_static, 1.0) /
                             (n * train["efficiency_static"])),
            "lower": lower(mu, train["efficiency_backdrive"]),
            "lower_static": lower(mu_static, train["efficiency_backdrive_static"]),
            "motor": train["motor_friction_torque"]}


def stall_from_rest(scene, voltage: float) -> Dict[str, float]:
    """The rigid drive's stall from rest at a constant ``voltage`` (plain nut,
    behind the scene's gear stage): the stall ``current`` min(|U| / R, i_max)
    [A], its ``torque`` k_t i on the rotor [N*m], and the axial ``load`` [N]
    whose raise torque with mu_static (plus the motor's friction) that torque
    just reaches."""
    _, k_t, _, current = _motor_constants(scene, voltage)
    torque = k_t * current
    torques = _thread_torques(scene)
    return {"current": current, "torque": torque,
            "load": max(torque - torques["motor"], 0.0) / torques["raise_static"]}


def _closed_form(scene, loads: np.ndarray, voltage: float) -> Dict[str, Any]:
    """The rigid drive's steady state for each load, from rest (module docstring).

    From rest the thread sticks while the stall torque T_s = k_t min(U/R, i_max)
    lies between the torques that break it free with mu_static: it raises the
    load where T_s exceeds the raise torque with mu_static, the load back-drives
    it where T_s falls short of the torque that holds the load (-lower torque
    with mu_static, a thread with tan(alpha) > mu_static'), else it stays at
    rest. Moving, the train needs the torque T with mu: the raise torque
    (raising), or -the lower torque (back-driven: the rotor turns against the
    voltage, i = T / k_t > U / R, omega < 0). Beyond i_max the driver holds
    the limit until the hold voltage R i_max + k_e omega passes its supply
    -|U|; then it saturates at U_d = -|U| (docs/physics/dc_motor.md, "Beyond
    the supply") and the load settles where i = (-|U| - k_e omega) / R =
    T / k_t: omega = -(|U| + R i) / k_e, the driver absorbing |U| i
    (``back_driven_saturated``).
    """
    resistance, k_t, k_e, stall_current = _motor_constants(scene, voltage)
    torques = _thread_torques(scene)
    stall = stall_from_rest(scene, voltage)
    stall_torque = stall["torque"]
    friction = torques["motor"]  # the motor's own: against the motion either way
    raising = loads * torques["raise_static"] + friction < stall_torque
    back_driven = ~raising & (-loads * torques["lower_static"] > stall_torque + friction)
    torque = np.where(back_driven, -loads * torques["lower"] - friction,
                      loads * torques["raise"] + friction)
    current = torque / k_t
    limit = scene["motor"].get("current_limit", math.inf)
    saturated = back_driven & (current > limit)
    stalled = ~raising & ~back_driven
    current = np.where(stalled, stall_current, current)
    # (the driver's voltage: |U|, or -|U| saturated against the current)
    driver = np.where(saturated, -abs(voltage), abs(voltage))
    speed = np.where(stalled, 0.0, (driver - resistance * current) / k_e)
    # (stalled: the driver puts out R i at rest, U itself without a limit)
    power = np.where(stalled, resistance * stall_current ** 2, driver * current)
    # (the load's travel per radian of the rotor)
    lead_per_rad = scene.thread.lead / (2.0 * math.pi * abs(gear_ratio(scene)))
    with np.errstate(divide="ignore", invalid="ignore"):
        # Motoring only: 0 at rest, NaN where the load is lowered (it gives power).
        efficiency = np.where(raising, loads * lead_per_rad * speed / power,
                              np.where(stalled, 0.0, np.nan))
    sign = math.copysign(1.0, voltage)
    mode = np.where(raising, "raising", np.where(stalled, "stalled", np.where(
        saturated, "back_driven_saturated", "back_driven"))).astype(object)
    holding = -torques["lower_static"]
    return {"speed": sign * speed, "current": sign * current, "input_power": power,
            "efficiency": efficiency, "stalled": stalled, "mode": mode,
            "stall_torque": stall_torque,
            "stall_load": stall["load"],
            "stall_load_moving": max(stall_torque - friction, 0.0) / torques["raise"],
            "back_drive_load": ((stall_torque + friction) / holding if holding > 0.0
                                else math.inf)}


def _closed_form_curve(scene, loads: np.ndarray, voltage: float,
                       closed: Dict[str, Any]) -> Dict[str, list]:
    """The closed form over a fine grid of loads from 0 to past the largest
    (for the figure's lines), with the loads just below and at the stall and
    back-drive loads, where it jumps."""
    top = 1.05 * float(np.max(loads))
    grid = [np.linspace(0.0, top, 401)]
    for jump in (closed["stall_load"], closed["back_drive_load"]):
        if 0.0 < jump < top:
            grid.append([np.nextafter(jump, 0.0), jump])
    grid = np.unique(np.concatenate(grid))
    curve = _closed_form(scene, grid, voltage)
    return {"load": grid.tolist(),
            **{name: curve[name].tolist() for name in ("speed", "current", "efficiency")}}


def _chunk(loads: Any, batch: DriveBatch, raising: float, workers: int = 1,
           torque_ratio: float = 0.0, speed_scale: float = 1.0) -> Dict[str, Any]:
    """The measures of a chunk of loads from one C++ batch call.

    Args:
        torque_ratio: (k_t - k_e) / k_t: the part of the motor's mechanical
            work that work_drive books beyond the electrical input.
        speed_scale: the no-load speed |U| / k_e [rad/s], the scale of the
            speed's change where the speed is ~0.
    """
    forces = np.asarray(loads, dtype=float).reshape(-1, 1) * raising
    samples, errors, wall_time = batch.run(forces, workers)

    def change(index):
        return samples[:, index, 2] - samples[:, index, 0]

    # work_drive = electrical input + (k_t - k_e) X, with k_t X (X = the
    # integral of i omega) = work_drive - copper loss - magnetic energy's change
    # (docs/physics/dc_motor.md): the integral of U_d i over the window.
    work = change(_WORK)
    electrical = work - torque_ratio * (work - change(_COPPER) - change(_MAGNETIC))
    useful = -change(_AXIAL)
    with np.errstate(divide="ignore", invalid="ignore"):
        # Motoring only: NaN where the load is lowered (useful work below the
        # round-off of the input) or no electrical power goes in.
        lowered = (useful < -1e-9 * np.abs(electrical)) | ~(electrical > 0.0)
        efficiency = np.where(lowered, np.nan, np.maximum(useful, 0.0) / electrical) + 0.0
        omega = samples[:, _OMEGA, :]
        # Relative to the speed, or to 1e-3 of the no-load speed where the
        # drive is (nearly) at rest: a steady stall reads ~0.
        scale = np.maximum(np.abs(omega[:, 2]), 1e-3 * speed_scale)
        window_change = np.abs(omega[:, 2] - omega[:, 1]) / scale
    return {"speed": omega[:, 2], "current": samples[:, _CURRENT, 2],
            "load_speed": samples[:, _VLOAD, 2], "efficiency": efficiency,
            "input_power": samples[:, _VOLTAGE, 2] * samples[:, _CURRENT, 2],
            "window_change": window_change,
            "wall_time": np.asarray(wall_time, dtype=float), "error": errors}


def motor_characteristics(
    scene: Any,
    loads: Sequence[float],
    t_end: float = 1.0,
    window: Optional[Tuple[float, float]] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    executor=None,
    progress: bool = True,
    **simulate_options: Any,
) -> pd.DataFrame:
    """Steady speed, current, input power and the whole train's efficiency of
    the scene's DC motor against the axial load, and the stall load, simulated
    and in closed form.

    Each load is raised from rest (``loads.axial_force`` set against the
    motion the motor's voltage drives) by the scene's motor at its constant
    voltage; the speed, current and input power (the driver's voltage times
    the current) are taken at ``t_end``, the efficiency (useful axial work
    over the electrical input, the integral of U_d i) over ``window``. The
    drive starts from rest, so the closed form's stall is the breakaway with
    ``friction.mu_static``; a thread that can be back-driven runs backwards
    under a load the stalled motor cannot hold (module docstring).

    Args:
        scene: a :class:`~leadscrew.Scene` (or dict) with a DC motor
            (``motor.type = "dc"``) of constant ``voltage``.
        loads: axial loads to raise [N], > 0.
        t_end: simulated time [s], > 0: long enough for the mechanical time
            constant J R / (k_t k_e) (``window_change`` shows what is left).
        window: (start, end) [s], 0 <= start < end <= t_end (default: the
            last fifth of the run).
        rtol, atol: integration tolerances (default simulate's).
        executor: as :func:`leadscrew.studies.efficiency_vs_mu` (default: the
            core's own threads).
        progress: show a tqdm progress bar.
        **simulate_options: passed on to :func:`leadscrew.simulate` (all but
            ``t_eval``).

    Returns:
        DataFrame with one row per load: ``load`` [N], ``speed`` and
        ``speed_closed_form`` [rad/s] (the rotor's), ``current`` and
        ``current_closed_form`` [A], ``input_power`` and
        ``input_power_closed_form`` [W], ``efficiency`` and
        ``efficiency_closed_form`` [1] (the useful axial work over the
        electrical input, the integral of U_d i; closed form F v / (U i);
        motoring only: 0 at rest, NaN where the load is lowered and gives
        power), ``load_speed`` [m/s], ``window_change`` [1] (the speed's
        change over the window's second half relative to the speed, or to
        1e-3 of the no-load speed |U| / k_e where the drive is nearly at
        rest: ~0 at steady state), ``stalled`` (closed form: the drive stays
        at rest, the stall from rest with mu_static), ``mode`` (closed form:
        ``"raising"``, ``"stalled"``, ``"back_driven"`` (the load turns the
        rotor against the voltage: a thread with tan(alpha) > mu_static') or
        ``"back_driven_saturated"`` (back-driven beyond the current limit:
        the driver saturates at -|U| and the rotor settles at omega =
        -(|U| + R i) / k_e, faster than unlimited)), ``wall_time`` [s],
        ``error``.
        ``attrs["summary"]``: ``voltage`` [V], ``stall_load`` [N] (closed
        form, from rest: breakaway with mu_static), ``stall_load_moving``
        [N] (with mu: the load up to which a drive already raising keeps
        moving), ``back_drive_load`` [N] (beyond it the load back-drives the
        stalled motor; inf for a self-locking thread), ``stall_torque``
        [N*m], ``window`` [s], ``raised``, ``raised_reasons``.
        ``attrs["closed_form_curve"]``: the closed form's ``load`` [N],
        ``speed`` [rad/s], ``current`` [A] and ``efficiency`` [1] over a fine
        grid of loads (lists), which the figure draws.

    Raises:
        ValueError: no DC motor or a voltage that is not constant, invalid
            loads, t_end or window (naming the argument).
    """
    progress = shown(progress)
    scene = as_scene(scene, gear=True)
    if scene["nut"]["preload"] > 0.0:
        raise ValueError(f"nut.preload = {scene['nut']['preload']!r} is invalid for "
                         "motor_characteristics: must be 0 (its closed form is the plain nut's; "
                         "preload_tradeoff prices a preload)")
    voltage = _voltage(scene)
    forces = check_grid("loads", loads, unit="N")
    t_end = check_positive("t_end", t_end, unit="s")
    start, end = check_window(window, t_end, 0.8)
    # A right-hand screw turning forward moves the load along -x
    # (docs/physics/drive_models.md): the load to raise acts along +x then.
    # A reversing gear stage (n < 0) turns the driven part the other way.
    raising = (scene.thread.hand_sign * math.copysign(1.0, voltage) *
               math.copysign(1.0, gear_ratio(scene)))
    # The train's characteristic runs free: the scene's end stops (if any) are
    # left out, so that each load reaches its steady state (end_stop_jam runs
    # the drive into them).
    running = scene.replace(initial={"rotor_speed": 0.0, "state": "relaxed"}, end_stops=None)
    _, k_t, k_e, _ = _motor_constants(scene, voltage)
    measures = {"raising": raising, "torque_ratio": (k_t - k_e) / k_t,
                "speed_scale": abs(voltage) / k_e}
    batch = DriveBatch(running, ("axial_force",), _CHANNELS, t_end,
                       [start, 0.5 * (start + end), end],
                       **with_tolerances(simulate_options, rtol, atol))
    serial = type(executor) is SerialExecutor and not executor.is_shutdown
    workers = 1 if serial else max(1, min(default_workers(), len(forces)))
    if executor is None or serial:
        chunks = run_batches(lambda rows: _chunk(forces[rows.start:rows.stop], batch,
                                                 workers=workers, **measures),
                             len(forces), workers, progress=progress,
                             description="motor_characteristics")
    else:
        chunks = run_chunks(functools.partial(_chunk, batch=batch, **measures),
                            forces.tolist(), executor=executor, progress=progress,
                            description="motor_characteristics")
    names = ("speed", "current", "load_speed", "efficiency", "input_power", "window_change",
             "wall_time")
    columns = {name: np.full(len(forces), np.nan) for name in names}
    errors = np.empty(len(forces), dtype=object)
    for chunk in chunks:
        rows = slice(chunk.cases.start, chunk.cases.stop)
        if chunk.ok:
            for name in names:
                columns[name][rows] = chunk.value[name]
            errors[rows] = chunk.value["error"]
        else:
            errors[rows] = chunk.error
    closed = _closed_form(scene, forces, voltage)
    frame = frame_of({
        "load": forces, "speed": columns["speed"], "speed_closed_form": closed["speed"],
        "current": columns["current"], "current_closed_form": closed["current"],
        "input_power": columns["input_power"],
        "input_power_closed_form": closed["input_power"],
        "efficiency": columns["efficiency"], "efficiency_closed_form": closed["efficiency"],
        "load_speed": columns["load_speed"], "window_change": columns["window_change"],
        "stalled": closed["stalled"], "mode": closed["mode"], "wall_time": columns["wall_time"],
        "error": errors})
    frame.attrs["closed_form_curve"] = _closed_form_curve(scene, forces, voltage, closed)
    return annotate(frame, UNITS, errors_checked=True, study="motor_characteristics",
                    summary_units={"voltage": "V", "stall_load": "N", "stall_load_moving": "N",
                                   "back_drive_load": "N", "stall_torque": "N*m",
                                   "window": "s"},
                    voltage=voltage, stall_load=float(closed["stall_load"]),
                    stall_load_moving=float(closed["stall_load_moving"]),
                    back_drive_load=closed["back_drive_load"],
                    stall_torque=float(closed["stall_torque"]), window=(start, end))


def plot_motor_characteristics(frame: pd.DataFrame, ax: Optional[Any] = None):
    """Draw speed, current and efficiency against the load, simulated (points)
    and in closed form (lines over the fine grid of
    ``attrs["closed_form_curve"]``, so that the stall is a jump; the frame's
    loads without it), with the stall load; the legend below the axes.

    Args:
        frame: the DataFrame :func:`motor_characteristics` returned.
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes (speed); the current and the efficiency share its x axis on
        twin axes.
    """
    ax = axes(ax)
    frame = frame.sort_values("load")
    load = frame["load"]
    curve = frame.attrs.get("closed_form_curve") or {
        "load": load, **{name: frame[f"{name}_closed_form"]
                         for name in ("speed", "current", "efficiency")}}
    ax.plot(load, frame["speed"], "o", color="C0", label="speed (simulated)")
    ax.plot(curve["load"], curve["speed"], "-", color="C0", label="speed (closed form)")
    ax.set_xlabel("axial load [N]")
    ax.set_ylabel("rotor speed [rad/s]", color="C0")
    current = ax.twinx()
    current.plot(load, frame["current"], "s", color="C3", label="current (simulated)")
    current.plot(curve["load"], curve["current"], "-", color="C3",
                 label="current (closed form)")
    current.set_ylabel("current [A]", color="C3")
    efficiency = ax.twinx()
    efficiency.spines["right"].set_position(("axes", 1.12))
    efficiency.plot(load, frame["efficiency"], "^", color="C2", label="efficiency (simulated)")
    efficiency.plot(curve["load"], curve["efficiency"], "--", color="C2",
                    label="efficiency (closed form)")
    efficiency.set_ylabel("efficiency [1]", color="C2")
    # On its own scale from 0 to 1 (autoscaled, a curve of the shape of the
    # speed's hid the speed under it: a review).
    efficiency.set_ylim(0.0, 1.0)
    stall = frame.attrs.get("summary", {}).get("stall_load")
    if stall is not None and math.isfinite(stall):
        ax.axvline(stall, color="k", linestyle=":", label=f"stall load {stall:.4g} N")
    handles = []
    for axis in (ax, current, efficiency):
        handles += axis.get_legend_handles_labels()[0]
    # Below the axes, off the data (a constrained layout makes room for it).
    ax.legend(handles, [h.get_label() for h in handles], loc="upper center",
              bbox_to_anchor=(0.5, -0.13), ncol=3, fontsize="small")
    return ax
