"""Stick-slip transitions under an alternating drive torque (thesis section 5.1, Fig. 5.1).

The thesis drives its Table 5.1 drive with a constant axial force and an
alternating torque, eq. (5.1): F = -10 N, M = -40 sin(4 pi t) N mm, mu = 0.3.
Whenever the tangential force the torque asks of the flank exceeds
mu' times the normal force the drive slips; otherwise it sticks. The load moves
in steps with pauses, the pattern Fig. 5.1 shows for the rigid concept.
"""

from __future__ import annotations

from typing import Any, List, Optional, Sequence, Tuple

import numpy as np
import pandas as pd

from .._progress import shown
from ..simulation import simulate
from ._common import annotate, axes, as_scene, check_count, check_positive, with_tolerances

__all__ = ["stick_slip", "stick_slip_phases", "plot_stick_slip"]

_CHANNELS = ("u_load", "v_load", "phi_drive", "omega_drive", "drive_torque", "axial_force",
             "normal_force", "friction_force", "slip_velocity", "stick")

UNITS = {
    "t": "s", "u_load": "m", "v_load": "m/s", "phi_drive": "rad", "omega_drive": "rad/s",
    "drive_torque": "N*m", "axial_force": "N", "normal_force": "N", "friction_force": "N",
    "slip_velocity": "m/s", "stick": "1", "gap": "m", "phase": "",
    "start": "s", "end": "s", "duration": "s",
}


#: Output points of a run when neither ``points`` nor ``t_eval`` is given
#: (as ``leadscrew run``'s default).
DEFAULT_POINTS = 2001

# Units of the summary (attrs["summary_units"]).
SUMMARY_UNITS = {"stick_phases": "1", "slip_phases": "1", "stick_fraction": "1", "events": "1",
                 "u_final": "m", "wall_time": "s"}


def _labels(frame: pd.DataFrame) -> np.ndarray:
    """Phase of each sample: 'stick', 'slip+', 'slip-' or (with backlash) 'open'."""
    stick = frame["stick"].to_numpy() == 1.0
    slip = np.sign(frame["slip_velocity"].to_numpy())
    labels = np.where(stick, "stick", np.where(slip > 0, "slip+", "slip-")).astype(object)
    undecided = ~stick & (slip == 0)
    if "gap" in frame:
        is_open = (frame["gap"].to_numpy() > 0.0) & (frame["normal_force"].to_numpy() == 0.0)
        labels[is_open] = "open"
        undecided &= ~is_open
    # The sample just before an event (its time repeats) is still in the
    # phase the event ends: it takes the label of the sample before it (its
    # slip velocity is zero up to round-off at a slip -> stick event). A
    # sample with zero slip velocity that is not stuck starts a slip (just
    # after a stick -> slip event): it takes the label of the sample after it.
    t = frame["t"].to_numpy()
    ends_phase = np.zeros(len(t), dtype=bool)
    ends_phase[:-1] = t[1:] == t[:-1]
    for i in np.flatnonzero(undecided & ~ends_phase)[::-1]:
        if i + 1 < len(t):
            labels[i] = labels[i + 1]
    for i in np.flatnonzero(ends_phase | (undecided & (np.arange(len(t)) == len(t) - 1))):
        if i > 0:
            labels[i] = labels[i - 1]
    return labels


def _phase_of_mode(mode: str) -> Optional[str]:
    """The phase a mode of an event's kind stands for ('upper flank stick'
    -> 'stick'); None for the modes of a regularized law or a penalty contact
    ('free', 'regularized'), which do not say."""
    if mode == "open":
        return "open"
    for phase in ("stick", "slip+", "slip-"):
        if mode.endswith(phase):
            return phase
    return None


def _event_phases(events: Sequence[Tuple[float, str]], start: float,
                  end: float) -> Optional[List[list]]:
    """The phases ``[phase, start, end]`` between the mode changes of a run
    (the events' kinds, ``'[what, ]before->after'``), or None if there are
    none or a mode does not name a phase."""
    changes = [(time, kind.rsplit("->", 1)) for time, kind in events
               if "->" in kind and start <= time <= end]
    if not changes:
        return None
    first = _phase_of_mode(changes[0][1][0].rsplit(", ", 1)[-1])
    phases = [_phase_of_mode(after) for _, (_, after) in changes]
    if first is None or None in phases:
        return None
    rows = [[first, start, start]]
    for (time, _), phase in zip(changes, phases):
        rows[-1][2] = time
        if phase != rows[-1][0]:
            rows.append([phase, time, time])
    rows[-1][2] = end
    return [row for row in rows if row[2] > row[1]]


def stick_slip_phases(frame: pd.DataFrame) -> pd.DataFrame:
    """The stick and slip phases of a :func:`stick_slip` time series.

    With the run's events (``attrs["events"]``, which :func:`stick_slip`
    sets) the phases start and end at the events, exactly, whatever the
    output times; without them, or for a law whose modes do not name the
    phases (a regularized law: no stick), they change between the output
    times whose ``phase`` labels differ (exactly at the events if the series
    holds every event time twice: ``points=0``).

    Args:
        frame: the DataFrame :func:`stick_slip` returned.

    Returns:
        DataFrame with one row per phase: ``phase`` ('stick', 'slip+',
        'slip-', 'open'), ``start`` [s], ``end`` [s], ``duration`` [s].

    Raises:
        ValueError: the frame lacks the columns ``t`` and ``phase``.
    """
    if "t" not in frame or "phase" not in frame:
        raise ValueError("frame is invalid: must be the output of stick_slip (columns t, phase)")
    t = frame["t"].to_numpy()
    labels = frame["phase"].to_numpy()
    rows = (_event_phases(frame.attrs["events"], t[0], t[-1]) if "events" in frame.attrs
            and len(t) > 1 else None)
    if rows is None:
        rows = []
        for i in range(len(t) - 1):
            if t[i + 1] <= t[i]:
                continue  # the two samples of one event
            if rows and rows[-1][0] == labels[i] and rows[-1][2] == t[i]:
                rows[-1][2] = t[i + 1]
            else:
                rows.append([labels[i], t[i], t[i + 1]])
    phases = pd.DataFrame(rows, columns=["phase", "start", "end"])
    phases["duration"] = phases["end"] - phases["start"]
    return annotate(phases, UNITS)


def stick_slip(scene: Any, t_end: float = 2.0, points: Optional[int] = None,
               rtol: Optional[float] = None, atol: Optional[float] = None, executor=None,
               progress: bool = True, **simulate_options: Any) -> pd.DataFrame:
    """Load position and stick/slip phases of one simulation (thesis Fig. 5.1).

    Run it on the scene of load case (5.1): the rigid Table 5.1 drive with
    ``loads.drive_torque = {"type": "sine", "amplitude": -0.04, "omega": 4 pi}``
    and ``loads.axial_force = -10``. The loads are the scene's, as they are
    (the rule of every study, :mod:`leadscrew.studies`).

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict) with an exact
            (Coulomb) or regularized friction law.
        t_end: simulated time [s], > 0.
        points: output points, evenly spaced over [0, t_end], >= 2 (default
            2001, as ``leadscrew run``; not with ``t_eval``); 0 writes every
            integrator step and, twice, every event time (the shipped
            flexible thesis drive: 45,623 rows for 1 s). The phases start and
            end at the events either way (:func:`stick_slip_phases`).
        rtol, atol: integration tolerances (relative [1], absolute [SI];
            default the scene's [simulation] ones, else simulate's, 1e-8 and
            1e-10; not with integrator "moreau").
        executor: a :class:`concurrent.futures.Executor` to run the
            simulation on (e.g. a Dask client's, to run it on a cluster;
            default: the calling thread).
        progress: True or False, checked as by every study; one simulation
            shows no bar.
        **simulate_options: passed on to :func:`leadscrew.simulate`
            (``integrator``, ``t_eval`` instead of ``points``, ...;
            ``max_steps`` defaults to simulate's, 1e6 per simulated
            second, at least 1e6).

    Returns:
        DataFrame with columns ``t`` [s], ``u_load`` [m], ``v_load`` [m/s],
        ``phi_drive`` [rad], ``omega_drive`` [rad/s], ``drive_torque`` [N*m],
        ``axial_force`` [N], ``normal_force`` [N], ``friction_force`` [N],
        ``slip_velocity`` [m/s], ``stick`` [1], ``gap`` [m] (with backlash)
        and ``phase`` ('stick', 'slip+', 'slip-', 'open'). ``attrs["units"]``
        maps columns to units; ``attrs["events"]`` lists the run's events as
        ``(time [s], kind)``; ``attrs["summary"]`` holds ``stick_phases``
        (number of stick phases), ``slip_phases``, ``stick_fraction`` (time
        in stick / t_end), ``events`` (number of mode changes), ``u_final``
        [m] and ``wall_time`` [s, inside the C++ core].

    Raises:
        ValueError: invalid scene or arguments.
        SimulationError, JammingError: the simulation failed.
    """
    progress = shown(progress)
    scene = as_scene(scene)
    t_end = check_positive("t_end", t_end, unit="s")
    if points is not None and "t_eval" in simulate_options:
        raise ValueError(f"points = {points!r} is invalid with t_eval: give one of them")
    if "t_eval" not in simulate_options:
        points = DEFAULT_POINTS if points is None else check_count("points", points, 0)
        if points == 1:
            raise ValueError("points = 1 is invalid: must be 0 (every step and event) or >= 2")
        simulate_options["t_eval"] = np.linspace(0.0, t_end, points) if points else "steps"
    if executor is None:
        result = simulate(scene, t_end, **with_tolerances(simulate_options, rtol, atol))
    else:  # result() raises the simulation's own exception
        result = executor.submit(simulate, scene, t_end,
                                 **with_tolerances(simulate_options, rtol, atol)).result()
    columns = {"t": result.t}
    for name in _CHANNELS + (("gap",) if "gap" in result else ()):
        columns[name] = result[name]
    frame = pd.DataFrame(columns)
    frame["phase"] = _labels(frame)
    frame.attrs["events"] = [(event.time, event.kind) for event in result.events]
    phases = stick_slip_phases(frame)
    stick_time = float(phases.loc[phases["phase"] == "stick", "duration"].sum())
    span = float(frame["t"].iloc[-1] - frame["t"].iloc[0])
    return annotate(
        frame, UNITS, summary_units=SUMMARY_UNITS,
        stick_phases=int((phases["phase"] == "stick").sum()),
        slip_phases=int(phases["phase"].isin(["slip+", "slip-"]).sum()),
        stick_fraction=stick_time / span if span > 0 else float("nan"),
        events=len(result.events),
        u_final=float(result["u_load"][-1]),
        wall_time=float(result.stats["wall_time"]),
    )


def plot_stick_slip(frame: pd.DataFrame, ax: Optional[Any] = None):
    """Draw the load position [mm] over time with the stick phases shaded (Fig. 5.1).

    Args:
        frame: the DataFrame :func:`stick_slip` returned.
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes.

    Raises:
        ValueError: the frame is not a stick_slip result.
    """
    phases = stick_slip_phases(frame)
    ax = axes(ax)
    ax.plot(frame["t"], frame["u_load"] * 1e3, color="C0", label="load position")
    first = True
    for row in phases.itertuples():
        if row.phase == "stick":
            ax.axvspan(row.start, row.end, color="0.85", zorder=0,
                       label="stick" if first else None)
            first = False
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("load position u [mm]")
    ax.legend(loc="best")
    return ax
