"""Efficiency against the friction coefficient (thesis section 5.3, eq. 5.2, Fig. 5.6).

The thesis defines the efficiency by the work balance, eq. (5.2):
eta = W_out / W_in = (W_in - W_friction) / W_in, friction being the only loss.
Here a speed-controlled motor raises each axial load at constant speed, and the
works come from the simulation's energy account over a window after the
start-up: W_in is the motor's work (``work_drive``), W_friction the flank
friction's dissipation (``friction_loss``). At steady state the motor needs the
power-screw raising torque, so eta equals the closed form
tan(alpha) / tan(alpha + rho') (:func:`leadscrew.efficiency`) for any load.
"""

from __future__ import annotations

import functools
import itertools
from typing import Any, Dict, Optional, Sequence, Tuple

import pandas as pd

from ..simulation import simulate
from ..thread import efficiency, is_drivable
from ._common import annotate, axes, as_scene, check_grid, check_positive, numeric_or_nan
from ._sweep import run_cases

__all__ = ["efficiency_vs_mu", "plot_efficiency_vs_mu"]

UNITS = {"mu": "1", "load": "N", "efficiency": "1", "efficiency_closed_form": "1",
         "relative_error": "1", "window_change": "1", "drivable": "", "simulated": "",
         "drive_torque": "N*m", "work_drive": "J", "friction_loss": "J", "load_speed": "m/s",
         "wall_time": "s", "error": ""}


def _efficiency_case(case: Tuple[float, float], scene, speed: float, t_end: float,
                     window: Tuple[float, float], options: Dict[str, Any]) -> Dict[str, Any]:
    mu, load = case
    # Raise the load: move it along +x against the force -load. The rotor's
    # forward turn moves the load along -h x (docs/physics/drive_models.md).
    omega = -scene.thread.hand_sign * speed
    running = scene.replace(friction={"mu": mu},
                            loads={"drive_torque": None, "drive_speed": omega,
                                   "axial_force": -load},
                            initial={"rotor_speed": omega})
    start, end = window
    middle = 0.5 * (start + end)
    result = simulate(running, t_end, t_eval=[0.0, start, middle, end], **options)
    work = result["work_drive"]
    loss = result["friction_loss"]

    def eta(i, j):
        w_in = work[j] - work[i]
        return (w_in - (loss[j] - loss[i])) / w_in

    first, second = eta(1, 2), eta(2, 3)
    return {
        "efficiency": eta(1, 3),
        "window_change": abs(second - first) / abs(eta(1, 3)),
        "drive_torque": float(result["drive_torque"][3]),
        "work_drive": float(work[3] - work[1]),
        "friction_loss": float(loss[3] - loss[1]),
        "load_speed": float(result["v_load"][3]),
        "wall_time": float(result.stats["wall_time"]),
    }


def efficiency_vs_mu(
    scene: Any,
    mu: Sequence[float],
    loads: Sequence[float],
    speed: float = 10.0,
    t_end: float = 0.2,
    window: Optional[Tuple[float, float]] = None,
    rtol: float = 1e-8,
    atol: float = 1e-10,
    executor=None,
    progress: bool = True,
    **simulate_options: Any,
) -> pd.DataFrame:
    """Efficiency of raising each axial load, simulated and in closed form (Fig. 5.6).

    For each (mu, load) the scene (its concept, masses, stiffnesses, friction
    law) runs with ``friction.mu = mu``, ``loads.axial_force = -load`` and a
    speed-controlled motor turning at ``speed`` in the direction that raises
    the load (along +x), starting at that speed with relaxed springs.
    eta = (W_in - W_friction) / W_in over ``window``. Where the thread cannot
    be driven (mu' >= cot(alpha), :func:`leadscrew.is_drivable`) no torque
    moves the load: that row has ``drivable`` False, ``simulated`` False and
    efficiency 0 without a simulation.

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict); its loads are replaced.
        mu: friction coefficients [1], >= 0.
        loads: axial loads to raise [N], > 0.
        speed: rotor speed [rad/s], > 0.
        t_end: simulated time [s], > 0.
        window: (start, end) [s] of the measurement, 0 <= start < end <= t_end
            (default: the second half of the run).
        rtol, atol: integration tolerances (relative [1], absolute [SI]).
        executor: a :class:`concurrent.futures.Executor` (default: a thread
            pool over all cores).
        progress: show a tqdm progress bar.
        **simulate_options: passed on to :func:`leadscrew.simulate`.

    Returns:
        DataFrame with one row per (mu, load), mu-major: ``mu``, ``load``
        [N], ``efficiency`` [1], ``efficiency_closed_form`` [1]
        (tan a / tan(a + rho')), ``relative_error`` [1] (|simulated - closed
        form| / closed form), ``window_change`` [1] (relative change of eta
        between the window's halves: ~0 at steady state), ``drivable``,
        ``simulated``, ``drive_torque`` [N*m] (at the window's end),
        ``work_drive`` and ``friction_loss`` [J] (over the window),
        ``load_speed`` [m/s], ``wall_time`` [s, C++] and ``error`` (None, or
        the message of a failed simulation, whose numbers are NaN).

    Raises:
        ValueError: invalid scene or arguments.
    """
    scene = as_scene(scene)
    mus = check_grid("mu", mu, allow_zero=True)
    forces = check_grid("loads", loads)
    speed = check_positive("speed", speed)
    t_end = check_positive("t_end", t_end)
    if window is None:
        window = (0.5 * t_end, t_end)
    try:
        start, end = (float(w) for w in window)
    except (TypeError, ValueError):
        raise ValueError(f"window = {window!r} is invalid: must be (start, end) in s") from None
    if not (0.0 <= start < end <= t_end):
        raise ValueError(f"window = {window!r} is invalid: must satisfy 0 <= start < end <= "
                         f"t_end = {t_end:g}")
    thread = scene.thread
    cases = [(float(m), float(f)) for m, f in itertools.product(mus, forces)]
    drivable = [bool(is_drivable(thread, m)) for m, _ in cases]
    function = functools.partial(_efficiency_case, scene=scene, speed=speed, t_end=t_end,
                                 window=(start, end),
                                 options=dict(simulate_options, rtol=rtol, atol=atol))
    outcomes = iter(run_cases(function, [c for c, d in zip(cases, drivable) if d],
                              executor=executor, progress=progress,
                              description="efficiency_vs_mu"))
    rows = []
    for (m, force), can_drive in zip(cases, drivable):
        closed_form = float(efficiency(thread, m))
        row: Dict[str, Any] = {"mu": m, "load": force, "drivable": can_drive,
                               "simulated": can_drive}
        if can_drive:
            outcome = next(outcomes)
            value = outcome.value or {}
            row.update({name: numeric_or_nan(value.get(name)) for name in (
                "efficiency", "window_change", "drive_torque", "work_drive", "friction_loss",
                "load_speed", "wall_time")})
            row["error"] = outcome.error
        else:
            row.update(efficiency=0.0, window_change=0.0, drive_torque=float("inf"),
                       work_drive=0.0, friction_loss=0.0, load_speed=0.0, wall_time=0.0,
                       error=None)
        row["efficiency_closed_form"] = closed_form
        row["relative_error"] = (abs(row["efficiency"] - closed_form) / closed_form
                                 if closed_form > 0 else abs(row["efficiency"]))
        rows.append(row)
    columns = ["mu", "load", "efficiency", "efficiency_closed_form", "relative_error",
               "window_change", "drivable", "simulated", "drive_torque", "work_drive",
               "friction_loss", "load_speed", "wall_time", "error"]
    return annotate(pd.DataFrame(rows, columns=columns), UNITS, speed=speed,
                    window=(start, end))


def plot_efficiency_vs_mu(frame: pd.DataFrame, ax: Optional[Any] = None):
    """Draw the simulated efficiency against mu, one line per load, with the
    closed form (Fig. 5.6).

    Args:
        frame: the DataFrame :func:`efficiency_vs_mu` returned.
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes.
    """
    ax = axes(ax)
    for index, (load, group) in enumerate(frame.groupby("load", sort=True)):
        ax.plot(group["mu"], group["efficiency"], "o", color=f"C{index}",
                label=f"simulated, load {load:g} N")
    closed = frame.drop_duplicates("mu").sort_values("mu")
    ax.plot(closed["mu"], closed["efficiency_closed_form"], "k-",
            label="tan a / tan(a + rho')")
    ax.set_xlabel("friction coefficient mu [1]")
    ax.set_ylabel("efficiency eta [1]")
    ax.set_ylim(0.0, 1.05)
    ax.legend(loc="best")
    return ax
