"""The runs of ``end_stop_jam``: the drive into the stop (its t_drive chosen
from the run itself where none is given) and the reversing runs, each
judged until it is decided (docs/physics/end_stops.md, "The study
end_stop_jam").

A run after a step of reverse drive is decided when the clamping stop lets
go of the load (freed), or when the thread sticks and has stuck over the
whole second half of the judged window (held at rest: with its inputs
constant, a stuck drive whose springs' ringing has decayed stays stuck).
A run that is still moving at the window's end (a stick-slip creep off the
stop, a slip that has not reached the stop's release) is run again with the
window doubled, up to a bound; it is not "held".
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, Optional, Tuple

import numpy as np

from ..simulation import simulate

#: The first t_drive tried where the caller gives none [s]; doubled until the
#: clamp settles, at most _T_DRIVE_DOUBLINGS times (up to 64 s of drive).
FIRST_T_DRIVE = 0.25
_T_DRIVE_DOUBLINGS = 8
#: Output rows of a run: the drive's part and the judged window's (the
#: decisions read the events and the window's rows; a run's every step
#: would cost as much as the integration itself).
_DRIVE_ROWS, _WINDOW_ROWS = 201, 2001
#: Settled: the clamp force and a DC motor's current changed by less than
#: this fraction over the drive's last tenth (a 1e-3 change of the clamp is
#: a 1e-3 change of the closed form, which is linear in it).
_SETTLED = 1e-3


def with_drive(scene, kind: str, forward: float, reverse: Optional[float], t_drive: float,
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


def output_times(t_drive: float, t_end: float) -> np.ndarray:
    """The rows a run keeps: coarse over the drive, fine over the window."""
    drive = np.linspace(0.0, t_drive, _DRIVE_ROWS)
    return np.concatenate([drive, np.linspace(t_drive, t_end, _WINDOW_ROWS)[1:]])


def _unsettled(pushing, kind: str, t_drive: float) -> Optional[str]:
    """Why the drive's run has not settled clamped at its end (None: it has).

    Settled: the load presses on a stop, and the thread sticks or (a DC
    motor's back-EMF damps the approach to the quasi-static clamp, which the
    slip then reaches only asymptotically, never stopping at a zero of the
    slip) the clamp force and the motor's current changed by less than
    _SETTLED over the drive's last tenth.
    """
    clamp = abs(float(pushing["stop_force"][-1]))
    if clamp == 0.0:
        return "the load does not press on an end stop at its end (a stop out of reach)"
    if pushing["stick"][-1] == 1.0:
        return None
    channels = [("stop_force", "N")] + ([("motor_current", "A")] if kind == "voltage" else [])
    for channel, unit in channels:
        end = abs(float(pushing[channel][-1]))
        earlier = abs(float(np.interp(0.9 * t_drive, pushing.t, pushing[channel])))
        if abs(end - earlier) > _SETTLED * end:
            return (f"the clamp has not settled at its end (the thread does not stick "
                    f"against the stop, and {channel} changed from {earlier:.6g} {unit} "
                    f"to {end:.6g} {unit} over the last tenth of t_drive)")
    return None


def push(running, kind: str, forward: float, t_drive: Optional[float],
         options: Dict[str, Any]) -> Tuple[Any, float]:
    """The drive into the stop: (its run, t_drive [s]). Without a t_drive the
    run is repeated with t_drive doubled from FIRST_T_DRIVE until the clamp
    settles (at most _T_DRIVE_DOUBLINGS doublings).

    Raises:
        ValueError: the clamp has not settled at the given t_drive, or at the
            longest tried.
    """
    tries = [t_drive] if t_drive is not None else [FIRST_T_DRIVE * 2.0 ** k
                                                   for k in range(_T_DRIVE_DOUBLINGS + 1)]
    for length in tries:
        pushing = simulate(with_drive(running, kind, forward, None, length, length), length,
                           t_eval=np.linspace(0.0, length, _WINDOW_ROWS), **options)
        reason = _unsettled(pushing, kind, length)
        if reason is None:
            return pushing, length
    name = "t_drive" if t_drive is not None else "the longest t_drive tried"
    raise ValueError(f"{name} = {tries[-1]!r} is invalid for end_stop_jam: {reason} (a longer "
                     "t_drive, more end_stops.damping, or a stop within the drive's reach)")


@dataclass
class Verdict:
    """A reversing run's outcome: freed (True), held at rest (False) or
    undecided within its window (None); the release's time after the
    reversal [s] (NaN: none in the window) and the thread's breakaways
    (stick to slip) before it."""

    free: Optional[bool]
    t_free: float = math.nan
    slips: int = 0


def _moving_late(result, t_drive: float, window: float) -> bool:
    """The thread slipped, or changed its friction mode, in the window's
    second half (its rows or its events)."""
    late = t_drive + 0.5 * window
    rows = result.t >= late
    if not np.all(result["stick"][rows] == 1.0):
        return True
    return any(event.time >= late and ("stick" in event.kind or "slip" in event.kind)
               for event in result.events)


def judge(result, t_drive: float, window: float, clamping: str, clamp: float,
          slipping_frees: bool) -> Verdict:
    """Freed: the clamping stop let go of the load after the reversal, or
    (``slipping_frees``: the rigid drive without play) the thread slips away
    from the stop at the window's end, the clamp falling (the clamp it must
    overcome only falls as the load moves back: a worm seat creeps back
    0.7 mm at a few mm/s, and with the release alone 0.2 s read 6.87 V for
    the closed form's 4.10 V). Held: the thread stuck over the window's
    whole second half. Else undecided."""
    after = [event for event in result.events if event.time > t_drive]
    releases = [event.time for event in after if f"{clamping} release" in event.kind]
    slips = sum(1 for event in after if "stick->" in event.kind
                and (not releases or event.time < releases[0]))
    if releases or float(result["stop_force"][-1]) == 0.0:
        return Verdict(True, releases[0] - t_drive if releases else math.nan, slips)
    stuck = result["stick"][-1] == 1.0
    if slipping_frees and not stuck:
        away = float(result["v_load"][-1]) * (1.0 if clamping == "lower end stop" else -1.0)
        if away > 0.0 and abs(float(result["stop_force"][-1])) < clamp:
            return Verdict(True, math.nan, slips)
    if stuck and not _moving_late(result, t_drive, window):
        return Verdict(False, math.nan, slips)
    return Verdict(None, math.nan, slips)
