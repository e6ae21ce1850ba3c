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
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
import pandas as pd

from .. import _core
from .._progress import shown
from ._batch import DriveBatch
from ._common import (annotate, axes, as_scene, check_grid, check_positive, check_window,
                      frame_of, with_tolerances)
from ._sweep import SerialExecutor, default_workers, run_batches, run_chunks

__all__ = ["efficiency_vs_mu", "plot_efficiency_vs_mu"]

UNITS = {"mu": "1", "load": "N", "efficiency": "1", "efficiency_closed_form": "1",
         "relative_error": "1", "efficiency_without_preload": "1", "window_change": "1",
         "drivable": "", "simulated": "",
         "drive_torque": "N*m", "work_drive": "J", "friction_loss": "J", "load_speed": "m/s",
         "wall_time": "s", "error": ""}

# What each case samples (at t = 0, start, middle and end of the window) and
# what the study measures from it.
_CHANNELS = ("work_drive", "friction_loss", "drive_torque", "v_load")
_WORK, _LOSS, _TORQUE, _SPEED = range(len(_CHANNELS))  # indices into _CHANNELS
# The two works, first in _CHANNELS (so works[:, _WORK] and works[:, _LOSS]
# below index them): eq. 5.2 takes both at once.
_WORKS = slice(_WORK, _LOSS + 1)
# A case's values from its (mu, load): the load is raised, so it acts along
# -x (loads.axial_force = -load).
_RAISING = np.array([1.0, -1.0])
# Sample indices of the whole window and its halves (eq. 5.2 over each).
_WINDOW_STARTS = np.array([1, 1, 2])
_WINDOW_ENDS = np.array([3, 2, 3])
_MEASURES = ("efficiency", "window_change", "drive_torque", "work_drive", "friction_loss",
             "load_speed", "wall_time")


def _efficiency_batch(scene, speed: float, t_end: float, window: Tuple[float, float],
                      options: Dict[str, Any]) -> DriveBatch:
    """The C++ batch of the sweep: the scene speed-controlled at ``speed`` in
    the direction that raises the load, each case setting mu and the axial
    force, sampled at the window's start, middle and end."""
    # Raise the load: move it along +x against the force -load. The rotor's
    # forward turn moves the load along -h x (docs/physics/drive_models.md).
    omega = -scene.thread.hand_sign * speed
    running = scene.replace(loads={"drive_torque": None, "drive_speed": omega},
                            initial={"rotor_speed": omega, "state": "relaxed"})
    start, end = window
    return DriveBatch(running, ("mu", "axial_force"), _CHANNELS, t_end,
                      [0.0, start, 0.5 * (start + end), end], **options)


def _efficiency_chunk(cases: Any, batch: DriveBatch, workers: int = 1) -> Dict[str, Any]:
    """The measures of a chunk of (mu, load) cases (a list of pairs or an
    (n, 2) array), from one C++ batch call on ``workers`` threads of the core.

    eta = (W_in - W_friction) / W_in (eq. 5.2) between two sample times, for
    every case of the chunk at once (columns of the samples).
    """
    mu_and_load = np.asarray(cases, dtype=float).reshape(-1, 2)
    samples, errors, wall_time = batch.run(mu_and_load * _RAISING, workers)
    # Both works over the whole window and its two halves (sample 1 to 3, 1
    # to 2, 2 to 3), one column each: two channels and three windows in one
    # operation.
    works = samples[:, _WORKS, _WINDOW_ENDS] - samples[:, _WORKS, _WINDOW_STARTS]
    work, loss = works[:, _WORK], works[:, _LOSS]
    eta = (work - loss) / work
    return {"efficiency": eta[:, 0],
            "window_change": np.abs(eta[:, 2] - eta[:, 1]) / np.abs(eta[:, 0]),
            "drive_torque": samples[:, _TORQUE, 3],
            "work_drive": work[:, 0],
            "friction_loss": loss[:, 0],
            "load_speed": samples[:, _SPEED, 3],
            "wall_time": np.asarray(wall_time, dtype=float),
            "error": errors}


def _measured_columns(chunks: List[Any], simulated: np.ndarray, count: int
                      ) -> Tuple[Dict[str, np.ndarray], np.ndarray]:
    """The measures of all ``count`` cases (one array per name of
    _MEASURES) and their error column (an object array of None and
    messages), from the chunks (:class:`~leadscrew.studies._sweep.ChunkOutcome`)
    over the ``simulated`` ones."""
    errors = np.empty(count, dtype=object)  # None in every row
    if len(simulated) == count and len(chunks) == 1 and chunks[0].ok:
        # The usual sweep: every case simulated, in order, by one call: its
        # measures are the columns.
        measures = chunks[0].value
        if any(measures["error"]):
            errors[:] = measures["error"]
        return measures, errors
    # A case that is not simulated: no torque moves the load, eta = 0.
    columns = {"efficiency": np.zeros(count), "window_change": np.zeros(count),
               "drive_torque": np.full(count, np.inf), "work_drive": np.zeros(count),
               "friction_loss": np.zeros(count), "load_speed": np.zeros(count),
               "wall_time": np.zeros(count)}
    for chunk in chunks:
        rows = simulated[chunk.cases.start:chunk.cases.stop]
        if chunk.ok:
            for name in _MEASURES:
                columns[name][rows] = chunk.value[name]
            errors[rows] = chunk.value["error"]
        else:  # the chunk function failed or the executor lost the task
            for name in _MEASURES:
                columns[name][rows] = np.nan
            errors[rows] = chunk.error
    return columns, errors


def efficiency_vs_mu(
    scene: Any,
    mu: Sequence[float],
    loads: Sequence[float],
    speed: float = 10.0,
    t_end: float = 0.2,
    window: Optional[Tuple[float, float]] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
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

    The cases run as calls of the C++ batch
    (:class:`leadscrew.studies._batch.DriveBatch`), which simulates them with
    the GIL released and returns the works at the window's ends. By default
    (``executor=None``) the thread pool is the core's: the calling thread
    sends the whole sweep to the batch, whose :func:`default_workers`
    threads (one per core: the calling thread and helper threads the core
    keeps between calls, woken as the study starts) take the cases one at a
    time; with ``progress``
    it sends a few consecutive ranges of the sweep instead, each taking
    about a quarter of a second (:func:`leadscrew.studies._sweep.run_batches`),
    and the bar moves after each. ``executor=SerialExecutor()`` makes the
    same calls with the calling thread as the batch's only worker (a
    subclass, or one shut down, is treated as any other executor). With
    any other ``executor`` the cases go to it in chunks
    (:func:`leadscrew.studies._sweep.run_chunks`), each chunk one
    single-threaded batch call. Every path gives the same numbers.

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict); its loads are replaced.
        mu: friction coefficients [1], >= 0.
        loads: axial loads to raise [N], > 0.
        speed: rotor speed [rad/s], > 0.
        t_end: simulated time [s], > 0.
        window: (start, end) [s] of the measurement, 0 <= start < end <= t_end
            (default: the second half of the run).
        rtol, atol: integration tolerances (relative [1], absolute [SI];
            default the scene's [simulation] ones, else simulate's, 1e-8 and
            1e-10; not with integrator "moreau").
        executor: a :class:`concurrent.futures.Executor` (a thread or process
            pool, a Dask client's executor), each task one chunk of cases;
            :class:`~leadscrew.studies._sweep.SerialExecutor`: the calling
            thread alone; default: the C++ core's own threads, one per core
            (see above).
        progress: show a tqdm progress bar.
        **simulate_options: passed on to :func:`leadscrew.simulate` (all but
            ``t_eval``).

    Returns:
        DataFrame with one row per (mu, load), mu-major: ``mu``, ``load``
        [N], ``efficiency`` [1], ``efficiency_closed_form`` [1]
        (tan a / tan(a + rho'); with a preloaded nut, ``nut.preload`` P > 0,
        F tan a / [(F + P) tan(a + rho') + P tan(rho' - a)], and then the
        column ``efficiency_without_preload`` [1], the plain thread's: the
        preload's cost is the difference), ``relative_error`` [1] (|simulated
        - closed form| / closed form), ``window_change`` [1] (relative change of eta
        between the window's halves: ~0 at steady state), ``drivable``,
        ``simulated``, ``drive_torque`` [N*m] (at the window's end),
        ``work_drive`` and ``friction_loss`` [J] (over the window),
        ``load_speed`` [m/s], ``wall_time`` [s, C++] and ``error`` (None, or
        the message of a failed simulation, whose numbers are NaN).
        ``attrs["summary"]``: ``speed`` [rad/s], ``window`` [s], ``raised``
        [1], ``preload`` [N] (where the scene has one) and ``raised_reasons``
        (the simulations that raised: their count, and their exception types
        with the first message, or ``"none"``; a :class:`~leadscrew.StudyWarning` names them).

    Raises:
        ValueError: invalid scene or arguments (also a ``friction`` option
            that is not the scene's law).
        TypeError: an unknown keyword in ``simulate_options``.
    """
    progress = shown(progress)
    scene = as_scene(scene)
    mus = check_grid("mu", mu, allow_zero=True, unit="")
    forces = check_grid("loads", loads, unit="N")
    speed = check_positive("speed", speed, unit="rad/s")
    t_end = check_positive("t_end", t_end, unit="s")
    start, end = check_window(window, t_end, 0.5)
    thread = scene.thread
    count = len(mus) * len(forces)
    # leadscrew.efficiency and is_drivable, elementwise over mu (one call each)
    closed_form = np.repeat(_core.efficiency_array(thread, mus), len(forces))
    drivable = np.repeat(_core.is_drivable_array(thread, mus), len(forces))
    # A preloaded nut (nut.preload, docs/physics/preloaded_nut.md): its
    # closed form depends on the load; the plain thread's is its column
    # efficiency_without_preload, the preload's cost the difference.
    preload = float(scene["nut"].get("preload", 0.0))
    without_preload = closed_form
    if preload > 0.0:
        closed_form = _core.preloaded_efficiency_array(
            thread, np.repeat(mus, len(forces)), np.tile(forces, len(mus)), preload)
    simulated = np.flatnonzero(drivable)
    # A SerialExecutor (exactly that class, not shut down) runs nothing but
    # what the calling thread would: the default path's calls, on one worker.
    serial = type(executor) is SerialExecutor and not executor.is_shutdown
    workers = 1 if serial else max(1, min(default_workers(), len(simulated)))
    batch = _efficiency_batch(scene, speed, t_end, (start, end),
                              with_tolerances(simulate_options, rtol, atol))
    mu_column = np.repeat(mus, len(forces))
    load_column = np.tile(forces, len(mus))
    if executor is None or serial:
        # The thread pool is in the core (one batch call per range); serial:
        # the same calls on the calling thread alone.
        cases = np.empty((len(simulated), 2))
        cases[:, 0], cases[:, 1] = mu_column[simulated], load_column[simulated]
        chunks = run_batches(lambda rows: _efficiency_chunk(cases[rows.start:rows.stop], batch,
                                                            workers),
                             len(cases), workers, progress=progress,
                             description="efficiency_vs_mu")
    else:
        chunks = run_chunks(functools.partial(_efficiency_chunk, batch=batch),
                            list(zip(mu_column[simulated].tolist(),
                                     load_column[simulated].tolist())),
                            executor=executor, progress=progress,
                            description="efficiency_vs_mu")
    columns, errors = _measured_columns(chunks, simulated, count)
    eta = columns["efficiency"]
    with np.errstate(divide="ignore", invalid="ignore"):
        relative_error = np.where(closed_form > 0, np.abs(eta - closed_form) / closed_form,
                                  np.abs(eta))
    frame = frame_of({
        "mu": mu_column, "load": load_column, "efficiency": eta,
        "efficiency_closed_form": closed_form, "relative_error": relative_error,
        "window_change": columns["window_change"], "drivable": drivable,
        "simulated": drivable.copy(), "drive_torque": columns["drive_torque"],
        "work_drive": columns["work_drive"], "friction_loss": columns["friction_loss"],
        "load_speed": columns["load_speed"], "wall_time": columns["wall_time"],
        "error": errors})
    summary = {"speed": speed, "window": (start, end)}
    if preload > 0.0:
        frame.insert(frame.columns.get_loc("relative_error"), "efficiency_without_preload",
                     without_preload)
        summary["preload"] = preload
    # errors: an object array of None and the messages of failed cases
    return annotate(frame, UNITS, errors_checked=True, study="efficiency_vs_mu",
                    summary_units={"speed": "rad/s", "window": "s", "preload": "N"},
                    **summary)


_MARKERS = ("o", "s", "^", "D", "v", "P")


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
    groups = list(frame.groupby("load", sort=True))
    for index, (load, group) in enumerate(groups):
        # Loads whose points coincide (the efficiency hardly depends on the
        # load) stay visible: each its own hollow marker, the first largest.
        ax.plot(group["mu"], group["efficiency"], linestyle="none",
                marker=_MARKERS[index % len(_MARKERS)], fillstyle="none",
                markersize=5.0 + 3.0 * (len(groups) - 1 - index), color=f"C{index}",
                label=f"simulated, load {load:g} N")
    if "efficiency_without_preload" in frame:
        # A preloaded nut: its closed form per load, the plain thread's dashed
        # (the preload's cost is the gap).
        for index, (load, group) in enumerate(frame.groupby("load", sort=True)):
            group = group.sort_values("mu")
            ax.plot(group["mu"], group["efficiency_closed_form"], "-", color=f"C{index}",
                    label=f"preloaded closed form, load {load:g} N")
        closed = frame.drop_duplicates("mu").sort_values("mu")
        ax.plot(closed["mu"], closed["efficiency_without_preload"], "k--",
                label="without preload: tan a / tan(a + rho')")
    else:
        closed = frame.drop_duplicates("mu").sort_values("mu")
        ax.plot(closed["mu"], closed["efficiency_closed_form"], "k-",
                label="tan a / tan(a + rho')")
    ax.set_xlabel("friction coefficient mu [1]")
    ax.set_ylabel("efficiency eta [1]")
    ax.set_ylim(0.0, 1.05)
    ax.legend(loc="best")
    return ax
