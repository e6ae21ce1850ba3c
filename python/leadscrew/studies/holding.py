"""Position holding under static and alternating axial load (thesis section 5.2, Fig. 5.4).

A self-locking thread (tan(alpha) < mu', eq. 3.5) holds its position under a
static axial force: the nut moves across the backlash onto a flank and sticks
there. Under an alternating axial force without static preload the flank
unloads every half period: the nut leaves the flank and flies across the
backlash. In flight nothing holds the rotating part, so a torque acting on it
(the scene's ``loads.drive_torque``: a residual motor torque, or the torque a
load exerts on the rotating side through a gear) turns it; the small turns
add up and the load creeps. With exact Coulomb friction, plastic flank
impacts and no torque the rigid drive cannot creep at all: a self-locking
flank stops the relative motion at every impact (the impulse that stops an
axial motion lies inside the friction cone iff tan(alpha) <= mu'), so nothing
turns; the flexible concepts, whose light nut body rattles in the play, keep
the screw still to the integration tolerance. A regularized friction law
creeps under any load (it slips at a small speed wherever friction acts).

:func:`position_holding` runs the static and the alternating case of one
scene; :func:`min_holding_preload` answers the design question the thesis ends
section 5.2 with: the smallest static preload that keeps the nut on its flank
and the creep below a limit. The frequency and backlash sweeps are in
:mod:`leadscrew.studies.creep`.
"""

from __future__ import annotations

import functools
import math
import numbers
import warnings
from typing import Any, Dict, List, Optional, Tuple

import numpy as np
import pandas as pd

from ..errors import NoEquilibriumError, StudyWarning
from ..excitation import Constant, Sine, check_load_unit
from ..scene import _DEFAULT_DRIVE_TORQUE, Scene
from ..simulation import simulate
from ..thread import is_self_locking, lower_torque, raise_torque
from ._common import (annotate, as_scene, axes, check_count, check_finite, check_positive,
                      in_unit, numeric_or_nan, raised_rows, with_tolerances)
from ._batch import check_simulate_options
from ._sweep import run_cases

__all__ = [
    "cycle_response",
    "alternating_scene",
    "static_holding_band",
    "position_holding",
    "plot_position_holding",
    "min_holding_preload",
    "plot_min_holding_preload",
]

#: Share of the clearance below which a gap is not a flight: the core's
#: plastic-bounce resolution (kPlasticHeight), far above a closed flank's drift.
FLIGHT_RESOLUTION = 1e-6

# Units of the summaries (attrs["summary_units"]).
SUMMARY_UNITS = {
    "holding_torque": "N*m", "static_band_low": "N*m", "static_band_high": "N*m",
    "static_creep_per_cycle": "m", "static_max_displacement": "m",
    "dynamic_creep_per_cycle": "m", "dynamic_max_displacement": "m",
    "dynamic_separations": "1", "dynamic_flight_fraction": "1", "amplitude": "N",
    "frequency": "Hz", "static_force": "N", "min_preload": "N", "bracket_low": "N",
    "bracket_high": "N", "iterations": "1", "quasi_static_preload": "N",
    "creep_limit": "m", "ramp_cycles": "1", "settle_cycles": "1", "judged_cycles": "1"}

# Backlash contacts modelled by a spring (no open/closed flank states).
_PENALTY_CONTACTS = ("bistop", "cubic")

# Where a nut "on the flank" of a penalty contact starts: this share of the
# half play short of it (see _alternating).
_PENALTY_INSIDE = 1e-3

UNITS = {
    "t": "s", "axial_force_static": "N", "u_load_static": "m", "axial_force_dynamic": "N",
    "u_load_dynamic": "m", "phi_drive_dynamic": "rad", "gap_dynamic": "m",
    "iteration": "1", "preload": "N", "holds": "", "separated": "", "start": "", "separations": "1",
    "creep_per_cycle": "m", "max_displacement": "m", "flight_fraction": "1",
    "wall_time": "s", "error": "",
}

_OPEN = "->open"

#: How every run of these studies starts, whatever the scene's ``initial``
#: section says (a study of holding must not depend on how a run starts):
#: at rest, springs relaxed, the nut where the study puts it
#: (:func:`min_holding_preload` replaces this by the static equilibrium).
_AT_REST = {"rotor_speed": 0.0, "state": "relaxed"}


def _constant_torque(scene: Scene) -> float:
    """The scene's drive torque [N*m], which must be constant."""
    loads = scene["loads"]
    if "drive_speed" in loads:
        raise ValueError("loads.drive_speed is invalid for a position-holding study: the "
                         "drive must be torque-controlled (loads.drive_torque, constant)")
    torque = loads.get("drive_torque", _DEFAULT_DRIVE_TORQUE)
    if isinstance(torque, numbers.Real):
        return float(torque)
    if isinstance(torque, dict) and torque.get("type") == "constant":
        return float(torque["value"])
    if isinstance(torque, Constant):
        return float(torque.value)
    raise ValueError(f"loads.drive_torque = {torque!r} is invalid for a position-holding "
                     "study: must be constant (the torque held by the thread)")


#: The alternating axial force of a study whose scene has no sine to take
#: (and whose arguments give none): amplitude [N], frequency [Hz].
FALLBACK_AMPLITUDE, FALLBACK_FREQUENCY = 30.0, 20.0


def _scene_sine(scene: Scene) -> Optional[Dict[str, float]]:
    """The scene's alternating axial force: ``loads.axial_force`` as the dict
    ``{"amplitude", "omega", "phase", "offset"}`` [N, rad/s, rad, N] if it is
    a sine with amplitude != 0 and omega > 0, else None (a constant, a table
    or a callable: nothing alternating to take)."""
    try:
        sine = _sine_parameters(scene["loads"]["axial_force"])
    except ValueError:
        return None
    return sine if sine["amplitude"] != 0.0 and sine["omega"] > 0.0 else None


def _alternating_excitation(scene: Scene, amplitude: Optional[float],
                           frequency: Optional[float]) -> Tuple[float, float, str]:
    """The studies' one rule for the alternating axial force: an argument
    given overrides, the scene's sine (:func:`_scene_sine`) is the default,
    and without one the fallback 30 N, 20 Hz.

    Args:
        scene: the study's scene.
        amplitude: the amplitude argument [N] (None: not given).
        frequency: the frequency argument [Hz] (None: not given).

    Returns:
        ``(amplitude, frequency, excitation_from)``: |amplitude| [N] > 0,
        frequency [Hz] > 0, and ``"arguments"`` (both given), ``"scene"``
        (one or both from the scene's sine) or ``"defaults"`` (from the
        fallback).

    Raises:
        ValueError: an argument that is not a finite number > 0.
    """
    sine = _scene_sine(scene)
    excitation_from = "arguments"
    if amplitude is None or frequency is None:
        excitation_from = "scene" if sine is not None else "defaults"
    if amplitude is None:
        amplitude = abs(sine["amplitude"]) if sine is not None else FALLBACK_AMPLITUDE
    if frequency is None:
        frequency = (sine["omega"] / (2.0 * math.pi) if sine is not None
                     else FALLBACK_FREQUENCY)
    return (check_positive("amplitude", amplitude, unit="N"),
            check_positive("frequency", frequency, unit="Hz"), excitation_from)


def static_holding_band(scene: Any, axial_force: float) -> Tuple[float, float]:
    """Drive torques [N*m] a stuck rigid drive holds under a static axial force
    (Coulomb friction; thesis eq. 3.5-3.8).

    A positive torque turns the rotor forward, which moves the load along
    -h x (h = +1 for a right-hand thread). A torque that moves the load
    against the force must exceed the raising torque
    R = F r_m (tan a + mu') / (1 - mu' tan a) (``inf`` where no torque can);
    one that moves it with the force, the lowering torque
    L = F r_m (mu' - tan a) / (1 + mu' tan a), negative for a thread that is
    not self-locking (then the force back-drives it unless a torque of at
    least -L holds it back). The drive holds iff the torque lies strictly
    inside the band.

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict): thread and mu.
        axial_force: static axial force on the load along +x [N].

    Returns:
        (low, high) [N*m] in the sign convention of ``loads.drive_torque``;
        (0, 0) for a zero force.

    Raises:
        ValueError: invalid scene or a force that is not finite.
    """
    scene = as_scene(scene)
    axial_force = check_finite("axial_force", axial_force, unit="N")
    thread, mu = scene.thread, scene["friction"]["mu"]
    if axial_force == 0.0:
        return 0.0, 0.0
    raising = raise_torque(thread, mu, abs(axial_force))
    lowering = lower_torque(thread, mu, abs(axial_force))
    # Positive torque raises the load iff -h points against the force.
    if thread.hand_sign * axial_force > 0:
        return -lowering, raising
    return -raising, lowering


def _holds(band: Tuple[float, float], torque: float, axial_force: float) -> bool:
    if axial_force == 0.0:
        return torque == 0.0
    return band[0] < torque < band[1]


def alternating_scene(scene: Scene, amplitude: float, frequency: float, offset: float = 0.0,
                      backlash: Optional[float] = None, on_flank: bool = False,
                      phase: float = 0.0) -> Scene:
    """The scene under the axial force ``offset + amplitude sin(2 pi f t + phase)``,
    starting at rest with its springs relaxed (``initial.rotor_speed`` 0 and
    ``initial.state`` ``"relaxed"``, whatever the scene's ``initial`` says).

    Args:
        scene: the scene (its drive torque and everything else are kept).
        amplitude: force amplitude [N].
        frequency: excitation frequency f [Hz], > 0.
        offset: static axial force (preload) along +x [N].
        backlash: if given, the total axial clearance [m] replacing the scene's.
        on_flank: start with the nut on the flank the static force presses it
            against (a penalty contact's: 1e-3 of the half play short of
            it, where its contact starts right) (else centred in the
            backlash, as in thesis Fig. 5.4).
        phase: phase of the sine [rad].

    Returns:
        The new scene.

    Raises:
        ValueError: a value is not finite, or the frequency is not > 0 (the
            scene check names any other invalid field).
    """
    frequency = check_positive("frequency", frequency, unit="Hz")
    if backlash is not None:
        backlash = in_unit("backlash", backlash, "m")
    return _alternating(scene, amplitude, 2.0 * math.pi * frequency, offset, backlash, on_flank,
                        phase)


def _alternating(scene: Scene, amplitude: float, omega: float, offset: float,
                 backlash: Optional[float], on_flank: bool, phase: float) -> Scene:
    """alternating_scene with the angular frequency omega [rad/s] > 0 as given
    (a user's Sine keeps its omega bit for bit: no round trip through f)."""
    amplitude = check_finite("amplitude", amplitude, unit="N")
    offset = check_finite("offset", offset, unit="N")
    phase = check_finite("phase", phase, unit="rad")
    changes: Dict[str, Any] = {"loads": {"axial_force": {
        "type": "sine", "amplitude": float(amplitude), "omega": float(omega),
        "phase": float(phase), "offset": float(offset)}}}
    if backlash is not None:
        changes["backlash"] = {"axial": float(backlash)}
    clearance = backlash if backlash is not None else (
        scene["backlash"]["axial"] if "backlash" in scene else 0.0)
    play = 0.0
    if on_flank and offset != 0.0:
        # A force along +x moves the translating part along +x: the nut (drive
        # = "screw") lowers the play coordinate e = u_screw - u_nut - h p dphi,
        # the screw (drive = "nut") raises it (docs/physics/drive_models.md).
        side = -1.0 if scene["drive"] == "screw" else 1.0
        contact = scene["backlash"]["contact"] if "backlash" in scene else "exact"
        # A penalty flank touched at exactly zero penetration carries no
        # friction in the core (issue 17, defect 11: a self-locking drive
        # back-drives); a thousandth of the half play inside it works.
        inside = 1.0 - _PENALTY_INSIDE if contact in _PENALTY_CONTACTS else 1.0
        play = side * math.copysign(0.5 * clearance * inside, offset)
    changes["initial"] = dict(_AT_REST, play_position=play)
    return scene.replace(**changes)


def check_cycles(cycles: Any, settle_cycles: Any, points_per_cycle: Any) -> Tuple[int, int, int]:
    """The cycle counts of :func:`cycle_response`, checked: ``(cycles,
    settle_cycles, points_per_cycle)`` as ints (the sweeps check them once,
    before their cases run).

    Raises:
        ValueError: settle_cycles < 0, cycles <= settle_cycles or
            points_per_cycle < 4 (or not integers).
    """
    settle_cycles = check_count("settle_cycles", settle_cycles, 0)
    cycles = check_count("cycles", cycles, settle_cycles + 1)
    points_per_cycle = check_count("points_per_cycle", points_per_cycle, 4)
    return cycles, settle_cycles, points_per_cycle


def _open_flank(result, backlash: Dict[str, Any]) -> np.ndarray:
    """Whether the nut is off both flanks at each output time of a run with
    backlash.

    An exact contact has flank states: the nut is in flight where the state
    the last event at or before the output time left is 'open' (before the
    first event, the state that event left; without events, the state at
    t = 0 throughout, told by the gap there as for a penalty contact). Its
    ``gap`` channel is no verdict: a closed flank drifts with the
    integration error, by more than a flight's resolution (+3.6e-9 m of a
    0.1 mm play, 36 times 1e-6 of it, on a flexible nut within 0.27 s at
    rtol 1e-8). A penalty contact (``bistop``, ``cubic``) has no states: in
    flight where the gap exceeds :data:`FLIGHT_RESOLUTION` of the clearance
    (below it the core takes a bounce to be plastic).
    """
    t, clearance = result.t, backlash["axial"]
    if clearance <= 0:
        return np.zeros(len(t), dtype=bool)
    in_flight = result["gap"] > FLIGHT_RESOLUTION * clearance
    if backlash["contact"] in _PENALTY_CONTACTS:
        return in_flight
    changes = [(event.time, event.kind.rsplit("->", 1)) for event in result.events
               if "->" in event.kind]
    if not changes:  # the state of t = 0 throughout, before any drift
        return np.full(len(t), in_flight[0])
    # the states: before the first change, then after each
    states = [changes[0][1][0].rsplit(", ", 1)[-1]] + [after for _, (_, after) in changes]
    is_open = np.array([state == "open" for state in states])
    times = np.array([time for time, _ in changes])
    return is_open[np.searchsorted(times, t, side="right")]


def cycle_response(scene: Scene, frequency: float, cycles: int, settle_cycles: int = 1,
                   points_per_cycle: int = 100, series: bool = False, judged_from: int = 0,
                   **simulate_options: Any) -> Dict[str, Any]:
    """Simulate whole excitation cycles and measure creep and flight.

    Args:
        scene: the scene, excited at ``frequency``.
        frequency: excitation frequency f [Hz], > 0; the run lasts cycles / f.
        cycles: number of cycles, > settle_cycles.
        settle_cycles: cycles left out of the creep fit, >= 0.
        points_per_cycle: output points per cycle, >= 4.
        series: also return the time series (``t``, ``result``).
        judged_from: the first cycle of the window in which the flank
            openings, the flight and the displacement are measured, in
            [0, cycles) (default 0: the whole run).
        **simulate_options: passed on to :func:`leadscrew.simulate`.

    Returns:
        dict with ``creep_per_cycle`` [m]: the load travel the thread's
        turning gives per cycle, -h p times the slope of a least-squares line
        through the rotor angle at the cycle boundaries k = settle_cycles ..
        cycles (p = lead / 2 pi, h = +1 right hand), signed along +x. The load
        position is u_load = -h p phi_drive plus its place in the play plus
        elastic deflections; those two stay bounded, and a flexible nut
        rattling in the play puts the load anywhere in it at a cycle boundary,
        so the load position itself would measure that scatter rather than
        creep (for the rigid drive, back on its flank at every boundary, both
        agree). In the window from cycle ``judged_from`` on:
        ``max_displacement`` [m]: max |u_load(t) - u_load(t_0)| on the
        output times, t_0 the window's start; ``separations`` [1]: flank
        openings (events to 'open'; for a penalty contact, ``bistop`` or
        ``cubic``, which has no flank states, the output times at which a
        flight begins); ``flight_fraction`` [1]: share of output times with
        the nut off both flanks (an exact contact: its flank state 'open'; a
        penalty contact: a gap above 1e-6 of the clearance, the resolution
        below which the core treats a bounce as plastic). ``wall_time`` [s,
        C++]; ``steps``, ``events`` [1] (of the whole run).

    Raises:
        ValueError: invalid arguments.
        SimulationError, JammingError: the simulation failed.
    """
    frequency = check_positive("frequency", frequency, unit="Hz")
    cycles, settle_cycles, points_per_cycle = check_cycles(cycles, settle_cycles,
                                                           points_per_cycle)
    judged_from = check_count("judged_from", judged_from, 0)
    if judged_from >= cycles:
        raise ValueError(f"judged_from = {judged_from} is invalid: must be an integer in "
                         f"[0, cycles = {cycles})")
    t_end = cycles / frequency
    t_eval = np.linspace(0.0, t_end, cycles * points_per_cycle + 1)
    result = simulate(scene, t_end, t_eval=t_eval, **simulate_options)
    first = judged_from * points_per_cycle  # the window's first output time
    u = result["u_load"][first:]
    angle = result["phi_drive"][::points_per_cycle][settle_cycles:]
    # Least-squares slope, written out so that equal angles give exactly 0.
    k = np.arange(settle_cycles, cycles + 1, dtype=float)
    k -= k.mean()
    thread = scene.thread
    turn = float(np.dot(k, angle - angle.mean()) / np.dot(k, k))
    creep = -thread.hand_sign * thread.lead_per_radian * turn
    start = t_eval[first]
    separations = sum(1 for event in result.events
                      if event.kind.endswith(_OPEN) and event.time >= start)
    if "gap" in result:
        in_flight = _open_flank(result, scene["backlash"])[first:]
        flight = float(np.mean(in_flight))
        if scene["backlash"]["contact"] in _PENALTY_CONTACTS:
            # A penalty contact has no flank states, hence no events to
            # 'open': count the output times at which a flight begins.
            separations = int(np.count_nonzero(in_flight[1:] & ~in_flight[:-1]))
    else:
        flight = 0.0
    out = {
        "creep_per_cycle": creep,
        "max_displacement": float(np.max(np.abs(u - u[0]))),
        "separations": separations,
        "flight_fraction": flight,
        "wall_time": float(result.stats["wall_time"]),
        "steps": int(result.stats["steps"]),
        "events": len(result.events),
    }
    if series:
        out["t"] = t_eval
        out["result"] = result
    return out


def position_holding(
    scene: Any,
    amplitude: Optional[float] = None,
    frequency: Optional[float] = None,
    static_force: Optional[float] = None,
    cycles: int = 8,
    settle_cycles: int = 1,
    points_per_cycle: int = 200,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    executor=None,
    progress: bool = True,
    **simulate_options: Any,
) -> pd.DataFrame:
    """Static against dynamic position holding (thesis Fig. 5.4).

    Two runs of the scene, both with its (constant) drive torque and the nut
    starting in the middle of the backlash: under the static axial force
    ``static_force``, and under the alternating axial force
    ``amplitude sin(2 pi f t)`` without static part.

    The excitation follows the rule of every study (:mod:`leadscrew.studies`):
    an argument given overrides, the scene's own load is the default: here
    the amplitude and frequency of the scene's ``loads.axial_force`` if it
    is a sine (not its phase and offset: the force is purely alternating),
    else 30 N and 20 Hz.

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict) with a constant
            ``loads.drive_torque`` and, for flight, a backlash section.
        amplitude: amplitude of the alternating axial force [N], > 0
            (default: that of the scene's axial force if it is a sine, else
            30 N; ``attrs["summary"]["excitation_from"]`` says which was used).
        frequency: its frequency [Hz], > 0 (default: the scene's sine's,
            else 20 Hz).
        static_force: static axial force along +x [N] (default ``-amplitude``:
            the alternating force's peak, held statically).
        cycles: excitation cycles simulated (both runs last cycles / f).
        settle_cycles: cycles before the creep fit.
        points_per_cycle: output points per cycle.
        rtol, atol: integration tolerances (relative [1], absolute [SI];
            default simulate's, 1e-8 and 1e-10; not with integrator "moreau").
        executor: a :class:`concurrent.futures.Executor` on which the two
            runs go, at once (default: the calling thread, one after the
            other: each takes milliseconds; a Dask client's executor runs
            them on the cluster).
        progress: accepted as by every study; two runs show no bar.
        **simulate_options: passed on to :func:`leadscrew.simulate`.

    Returns:
        DataFrame with ``t`` [s], ``axial_force_static``, ``u_load_static``,
        ``axial_force_dynamic`` [N], ``u_load_dynamic`` [m],
        ``phi_drive_dynamic`` [rad] and ``gap_dynamic`` [m] (with backlash).
        ``attrs["summary"]``: closed form ``self_locking`` (tan a < mu',
        eq. 3.5), ``holding_torque`` [N*m], ``static_band_low`` and
        ``static_band_high`` [N*m] (:func:`static_holding_band` under
        ``static_force``), ``holds_statically`` (the torque inside the band);
        from the
        simulations ``static_creep_per_cycle``, ``static_max_displacement``,
        ``dynamic_creep_per_cycle``, ``dynamic_max_displacement`` [m],
        ``dynamic_separations`` [1], ``dynamic_flight_fraction`` [1] (see
        :func:`cycle_response`), ``amplitude`` [N], ``frequency`` [Hz],
        ``excitation_from`` (``"arguments"``; ``"scene"`` or ``"defaults"``
        if amplitude or frequency was not given), ``static_force`` [N].

    Raises:
        ValueError: invalid scene or arguments (a time-varying or
            speed-controlled drive).
        TypeError: an unknown keyword in ``simulate_options``.
        SimulationError, JammingError: a simulation failed.
    """
    scene = as_scene(scene)
    torque = _constant_torque(scene)
    amplitude, frequency, excitation_from = _alternating_excitation(scene, amplitude, frequency)
    static_force = -amplitude if static_force is None else check_finite("static_force",
                                                                         static_force, unit="N")
    cycles, settle_cycles, points_per_cycle = check_cycles(cycles, settle_cycles,
                                                           points_per_cycle)
    options = with_tolerances(simulate_options, rtol, atol)
    check_simulate_options(scene, options, cycles / frequency)
    centred = scene.replace(initial=dict(_AT_REST, play_position=0.0))
    runs = [centred.replace(loads={"axial_force": static_force}),
            alternating_scene(scene, amplitude, frequency)]
    arguments = (frequency, cycles, settle_cycles, points_per_cycle)
    if executor is None:  # in turn: a failed static run ends the study
        static, dynamic = [cycle_response(run, *arguments, series=True, **options)
                           for run in runs]
    else:
        # Each future's result() raises its run's own exception (SimulationError, ...).
        futures = [executor.submit(cycle_response, run, *arguments, series=True, **options)
                   for run in runs]
        try:
            static, dynamic = [future.result() for future in futures]
        except BaseException:  # one run failed: the other is not waited for
            for future in futures:
                future.cancel()
            raise
    s, d = static["result"], dynamic["result"]
    frame = pd.DataFrame({
        "t": static["t"],
        "axial_force_static": s["axial_force"],
        "u_load_static": s["u_load"],
        "axial_force_dynamic": d["axial_force"],
        "u_load_dynamic": d["u_load"],
        "phi_drive_dynamic": d["phi_drive"],
    })
    if "gap" in d:
        frame["gap_dynamic"] = d["gap"]
    self_locking = bool(is_self_locking(scene.thread, scene["friction"]["mu"]))
    band = static_holding_band(scene, static_force)
    return annotate(
        frame, UNITS, summary_units=SUMMARY_UNITS,
        self_locking=self_locking,
        holding_torque=torque,
        static_band_low=float(band[0]),
        static_band_high=float(band[1]),
        holds_statically=_holds(band, torque, static_force),
        static_creep_per_cycle=static["creep_per_cycle"],
        static_max_displacement=static["max_displacement"],
        dynamic_creep_per_cycle=dynamic["creep_per_cycle"],
        dynamic_max_displacement=dynamic["max_displacement"],
        dynamic_separations=dynamic["separations"],
        dynamic_flight_fraction=dynamic["flight_fraction"],
        amplitude=amplitude,
        frequency=frequency,
        excitation_from=excitation_from,
        static_force=static_force,
    )


def plot_position_holding(frame: pd.DataFrame, ax: Optional[Any] = None):
    """Draw the load position [mm] under static and alternating load (Fig. 5.4).

    Args:
        frame: the DataFrame :func:`position_holding` returned.
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes.
    """
    ax = axes(ax)
    ax.plot(frame["t"], frame["u_load_static"] * 1e3, "-", label="static axial force")
    ax.plot(frame["t"], frame["u_load_dynamic"] * 1e3, "--", label="alternating axial force")
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("load position u [mm]")
    ax.legend(loc="best")
    return ax


#: The units of a sine excitation's parameters (those of an axial force).
_SINE_UNITS = {"amplitude": "N", "omega": "rad/s", "phase": "rad", "offset": "N"}


def _sine_parameters(excitation: Any) -> Dict[str, float]:
    """A sine excitation of the axial force as ``{"amplitude", "omega",
    "phase", "offset"}`` [N, rad/s, rad, N]: from a :class:`~leadscrew.Sine`
    (a force's, or of plain numbers) or a dict ``{"type": "sine", ...}``
    whose values may be strings with units, as in a scene (``"20 N"``,
    ``"10 Hz"``).

    Raises:
        ValueError: not a sine, an unknown or missing key, a value that is no
            finite number, or one of another dimension (naming
            ``excitation.<key>``).
    """
    if isinstance(excitation, Sine):
        check_load_unit("excitation", excitation, "N")
        return {"amplitude": excitation.amplitude, "omega": excitation.omega,
                "phase": excitation.phase, "offset": excitation.offset}
    if isinstance(excitation, dict) and excitation.get("type") == "sine":
        keys = {"type", *_SINE_UNITS}
        unknown = set(excitation) - keys
        if unknown:
            raise ValueError(f"excitation.{sorted(unknown)[0]} is not a known key; a sine "
                             "excitation takes amplitude, omega, phase, offset")
        missing = [key for key in ("amplitude", "omega") if key not in excitation]
        if missing:
            raise ValueError(f"excitation.{missing[0]} is missing: a sine excitation "
                             "needs amplitude and omega")
        out = {}
        for key, unit in _SINE_UNITS.items():
            value = in_unit(f"excitation.{key}", excitation.get(key, 0.0), unit)
            try:
                out[key] = float(value)
            except (TypeError, ValueError, OverflowError):
                raise ValueError(f"excitation = {excitation!r} is invalid: values must be "
                                 "numbers") from None
        if not all(math.isfinite(v) for v in out.values()):
            raise ValueError(f"excitation = {excitation!r} is invalid: values must be finite")
        return out
    raise ValueError(f"excitation = {excitation!r} is invalid: must be a leadscrew.Sine or a "
                     "dict {'type': 'sine', 'amplitude', 'omega', 'phase', 'offset'}")


#: The ramp's start, a share of the full loads: a ramp from exactly zero
#: loads made the core take the flank for slipping at t = 1e-9 s from
#: round-off (a flexible nut then ran away, friction pushing it: issue 17,
#: defect 2); a thousandth of the loads at once starts a transient a
#: thousandth of the one without a ramp.
RAMP_START = 1e-3


#: The default upper end of :func:`min_holding_preload`'s search, a
#: multiple of the quasi-static preload: 0.4 of it is no dyadic fraction, so
#: no bisection point falls on the rigid drive's stick limit (with twice it,
#: every other point did, where the rigid drive chatters between stick and
#: slip beyond max_events).
UPPER_FACTOR = 2.5


class _Ramped:
    """A load that grows smoothly to ``static + amplitude sin(omega t +
    phase)``: that times r(t) = s + (1 - s) (1 - cos(pi t / ramp_time)) / 2,
    s = :data:`RAMP_START`, up to ``ramp_time`` [s] (r' = 0 at both ends),
    and itself after. A Python callable load (module level, so that it
    pickles for process pools)."""

    __slots__ = ("static", "amplitude", "omega", "phase", "ramp_time")

    def __init__(self, static: float, amplitude: float, omega: float, phase: float,
                 ramp_time: float):
        self.static, self.amplitude, self.omega = float(static), float(amplitude), float(omega)
        self.phase, self.ramp_time = float(phase), float(ramp_time)

    def __call__(self, t: float) -> float:
        value = self.static + self.amplitude * math.sin(self.omega * t + self.phase)
        if t >= self.ramp_time:
            return value
        rise = 0.5 * (1.0 - math.cos(math.pi * t / self.ramp_time))
        return (RAMP_START + (1.0 - RAMP_START) * rise) * value

    def __reduce__(self):
        return (_Ramped, (self.static, self.amplitude, self.omega, self.phase, self.ramp_time))

    def __repr__(self) -> str:
        return (f"_Ramped(static={self.static!r}, amplitude={self.amplitude!r}, "
                f"omega={self.omega!r}, phase={self.phase!r}, ramp_time={self.ramp_time!r})")


def _preload_case(preload: float, scene: Scene, sine: Dict[str, float], direction: float,
                  cycles: int, settle_cycles: int, points_per_cycle: int,
                  options: Dict[str, Any], ramp_cycles: int = 0) -> Dict[str, Any]:
    """One preload of :func:`min_holding_preload`: the drive at rest in
    static equilibrium under the loads at t = 0 (``initial.state =
    "equilibrium"``; where the loads at t = 0 have none, at rest on the
    loaded flank with its springs relaxed), ``ramp_cycles`` cycles of
    ramped loads (none: the full loads from t = 0), then ``cycles`` cycles
    of which those after ``settle_cycles`` are judged. The result has
    :func:`cycle_response`'s entries and ``start``, ``"equilibrium"`` or
    ``"relaxed"``."""
    static = sine["offset"] + direction * preload
    loaded = _alternating(scene, sine["amplitude"], sine["omega"], static, None, True,
                          sine["phase"])
    frequency = sine["omega"] / (2.0 * math.pi)
    if ramp_cycles:
        # Every load ramped alike: the ramp passes through scaled copies of
        # the full loading, each holding iff the full one holds quasi-statically.
        ramp_time = ramp_cycles / frequency
        loads: Dict[str, Any] = {"axial_force": _Ramped(
            static, sine["amplitude"], sine["omega"], sine["phase"], ramp_time)}
        torque = _constant_torque(scene)
        if torque != 0.0:
            loads["drive_torque"] = _Ramped(torque, 0.0, sine["omega"], 0.0, ramp_time)
        loaded = loaded.replace(loads=loads)
    judged_from = ramp_cycles + settle_cycles
    arguments = (frequency, ramp_cycles + cycles, judged_from, points_per_cycle)
    try:
        out = cycle_response(loaded.replace(initial={"state": "equilibrium",
                                                     "play_position": 0.0}),
                             *arguments, judged_from=judged_from, **options)
        start = "equilibrium"
    except NoEquilibriumError:
        # The loads at t = 0 cannot be held at rest (nor, then, their
        # smallest value over a cycle): the run shows how the drive fails.
        out = cycle_response(loaded, *arguments, judged_from=judged_from, **options)
        start = "relaxed"
    out["start"] = start
    return out


def _cycles(count: int, kind: str = "") -> str:
    """``"1 settle cycle"``, ``"2 settle cycles"``."""
    return f"{count} {kind}cycle{'' if count == 1 else 's'}"


def _bracket_report(rows: List[Dict[str, Any]], found: bool, low: float, high: float,
                    low_holds: bool) -> Tuple[bool, bool, str]:
    """Whether the bracket's ends were simulated with the verdicts they
    stand for (``high`` held, ``low`` failed; 0 held if ``low_holds``),
    whether every evaluated preload agrees with one threshold, and a text
    saying either (the contradicting pair if not)."""
    verdicts: Dict[float, List[bool]] = {}
    for row in rows:
        if row["holds"] is not None:  # a case that raised decides nothing
            verdicts.setdefault(row["preload"], []).append(row["holds"])
    holding = [p for p, v in verdicts.items() if all(v)]
    failing = [p for p, v in verdicts.items() if not any(v)]
    mixed = [p for p, v in verdicts.items() if any(v) and not all(v)]
    if not found:
        verified = False
    elif low_holds:
        verified = 0.0 in holding
    else:
        verified = high in holding and low in failing
    monotonic = not mixed and (not holding or not failing or max(failing) < min(holding))
    if monotonic:
        decided = sum(len(v) for v in verdicts.values())
        text = (f"all {decided} evaluated preloads" if decided == len(rows) else
                f"all {decided} decided preloads (of {len(rows)} evaluated)")
        text += " agree with one threshold"
    elif mixed:
        text = f"NOT monotonic: {mixed[0]:.6g} N both held and failed"
    else:
        text = (f"NOT monotonic: {min(holding):.6g} N held but {max(failing):.6g} N "
                "failed")
    return verified, monotonic, text


def min_holding_preload(
    scene: Any,
    excitation: Any = None,
    creep_limit: float = 1e-9,
    direction: float = -1.0,
    upper: Optional[float] = None,
    tolerance: float = 1e-3,
    max_iterations: int = 30,
    points_per_round: int = 1,
    cycles: int = 4,
    settle_cycles: int = 1,
    points_per_cycle: int = 100,
    ramp_cycles: int = 0,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    executor=None,
    progress: bool = True,
    **simulate_options: Any,
) -> pd.DataFrame:
    """Smallest static axial preload that holds the position under an alternating force.

    The axial force is ``direction * preload + excitation(t)``. Every run
    starts at rest in static equilibrium under the loads at t = 0
    (``initial.state = "equilibrium"``, :meth:`~leadscrew.Scene.initial_state`:
    the nut on the flank the loads press it against, the springs deflected
    by the loads, the thread stuck), whatever the scene's ``initial``
    section says: the answer does not depend on how a run starts. (Started
    with relaxed springs under the full loads, the start-up's ringing
    decided instead: a flexible nut needed 15.0 N, against 13.3 N
    quasi-statically, and a start at a rotor speed of 2 or 6 rad/s other
    answers again.) A preload whose loads at t = 0 have no static
    equilibrium (their friction force would lie outside the cone: below the
    quasi-static preload, it cannot hold) starts at rest on the loaded flank
    with its springs relaxed, and its run shows how it fails; the row's
    ``start`` says which. ``ramp_cycles`` > 0 starts from the equilibrium
    under 1e-3 (:data:`RAMP_START`) of the loads instead and ramps them, all
    by one smooth factor, to the full ones over that many cycles (the
    study's start before the equilibrium existed; no longer needed).

    ``settle_cycles`` cycles (after the ramp, if any) let the transient of
    the excitation's start settle, and the following cycles are judged: a
    preload *holds* if there the flank never separates (no event to 'open'
    and no output time with the nut off its flank; an exact contact's flank
    state decides, not its gap, which drifts with the integration error) and
    |creep per cycle| <= ``creep_limit`` (:func:`cycle_response`). Holding
    is taken to be monotonic in the preload; the search bisects (or, with
    ``points_per_round`` = n > 1, evaluates n evenly spaced preloads per
    round on the executor) until the bracket is narrower than ``tolerance``
    times its upper end or ``max_iterations`` rounds have run. A case that
    raises (a :class:`~leadscrew.JammingError`, a
    :class:`~leadscrew.SimulationError`) decides nothing: its row has
    ``holds`` None and the message in ``error``, the bracket ignores it,
    the summary counts such rows (``raised``, ``raised_reasons``) and a
    :class:`~leadscrew.StudyWarning` says so. A round in which every case
    raised is evaluated once more a third of its spacing higher (a point
    exactly on a rigid drive's stick limit may chatter between stick and
    slip beyond ``max_events``); if those raise too, the search ends (not
    converged). The answer is then checked: the bracket's ends were
    simulated with their verdicts (``bracket_verified``) and every decided
    preload agrees with one threshold (``monotonic``; a StudyWarning if
    not); ``decided_by`` says how the answer was found.

    For the rigid concept the answer has a closed form: stuck, the load is at
    rest, so the flank carries exactly the applied force, whose smallest
    value along ``direction`` is preload + direction * offset - |amplitude|;
    the flank stays loaded iff that is >= 0, and the stuck flank holds the
    torque M iff M stays inside :func:`static_holding_band` of that force.
    The smallest such preload, max(0, |amplitude| - direction * offset +
    |M| / band edge), is ``attrs["summary"]["quasi_static_preload"]``; it is
    also the flexible drives' answer for an excitation slow and small
    against their springs: from the static equilibrium the seat drive of
    ``tests/studies/test_min_holding_preload.py`` (flexible nut, and the
    flexible concept) finds it within the search's tolerance (1e-3 of the
    bracket's upper end) at any initial rotor speed of the scene.

    The excitation follows the rule of every study (:mod:`leadscrew.studies`):
    an argument given overrides, the scene's own load is the default: here
    the scene's ``loads.axial_force`` if it is a sine, whole (amplitude,
    omega, phase and its offset, a static part of the axial force).

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict) with a backlash
            section, a constant drive torque and a self-locking thread.
        excitation: the alternating axial force: a :class:`~leadscrew.Sine` or
            a dict ``{"type": "sine", "amplitude", "omega", "phase",
            "offset"}`` [N, rad/s, rad, N]; its frequency sets the cycles
            (default: the scene's ``loads.axial_force`` if it is a sine).
        creep_limit: largest admissible |creep per cycle| [m], >= 0.
        direction: +1 or -1, the preload's direction along x.
        upper: a preload [N] expected to hold (default 2.5 times the
            quasi-static preload, or |amplitude| where that is 0: at 0.4 of
            the bracket, no bisection point is the quasi-static preload, on
            which a rigid drive's stick limit lies); doubled up to 10 times
            until it holds.
        tolerance: relative width of the final bracket, > 0.
        max_iterations: bound on the search rounds, >= 1.
        points_per_round: preloads evaluated per round, >= 1.
        cycles: cycles after the ramp, > settle_cycles; those after the
            first ``settle_cycles`` are judged.
        settle_cycles: cycles after the ramp left for the transient to
            settle, >= 0.
        points_per_cycle: output points per cycle, >= 4.
        ramp_cycles: cycles over which the loads grow from 1e-3 of
            themselves, >= 0 (default 0: the full loads from t = 0, the
            drive in equilibrium under them); a ramp must be long against the
            drive's slowest mode on a closed flank.
        rtol, atol: integration tolerances (relative [1], absolute [SI];
            default simulate's, 1e-8 and 1e-10; not with integrator "moreau").
        executor: a :class:`concurrent.futures.Executor` (default: a thread
            pool over all cores).
        progress: show a progress bar per round.
        **simulate_options: passed on to :func:`leadscrew.simulate`.

    Returns:
        DataFrame with one row per evaluated preload, in evaluation order:
        ``iteration`` [1], ``preload`` [N], ``holds`` (None where the case
        raised), ``separated``, ``start`` (``"equilibrium"`` or
        ``"relaxed"``, see above), ``separations`` [1], ``creep_per_cycle``
        [m], ``max_displacement`` [m], ``flight_fraction`` [1] (those four
        in the judged cycles),
        ``wall_time`` [s], ``error``. ``attrs["summary"]``: ``min_preload``
        [N] (the bracket's upper end: the smallest preload seen to hold; if
        none held, the text ``"not found in [0, P] N"``, P the largest
        preload evaluated), ``bracket_low``, ``bracket_high`` [N] (NaN if not
        found), ``iterations``, ``converged``, ``found``,
        ``bracket_verified``, ``monotonic``, ``decided_by`` (how the answer
        was found: the bracket, its verdicts, the start and the judged
        cycles), ``quasi_static_preload`` [N], ``amplitude`` [N],
        ``frequency`` [Hz], ``creep_limit`` [m], ``ramp_cycles``,
        ``settle_cycles``, ``judged_cycles`` [1], ``excitation_from``
        (``"arguments"`` or ``"scene"``), ``raised`` [1] and
        ``raised_reasons`` (the rows whose case raised: their count, and
        their exception types with the first message, or ``"none"``).

    Raises:
        ValueError: invalid scene or arguments, no excitation (neither given
            nor a sine in the scene), or a thread that is not self-locking
            (a preload then drives it back instead of holding it).
        TypeError: an unknown keyword in ``simulate_options``.
    """
    scene = as_scene(scene)
    if not is_self_locking(scene.thread, scene["friction"]["mu"]):
        raise ValueError(f"friction.mu = {scene['friction']['mu']!r} is invalid for "
                         "min_holding_preload: the thread is not self-locking (tan a >= mu'), "
                         "so a static preload back-drives it")
    if "backlash" not in scene:
        raise ValueError("scene.backlash is missing: the flank can only separate across a "
                         "backlash; add a backlash section")
    torque = _constant_torque(scene)
    excitation_from = "arguments"
    if excitation is None:
        sine = _scene_sine(scene)
        if sine is None:
            raise ValueError("excitation is missing: the scene's loads.axial_force is not an "
                             "alternating sine; give excitation={'type': 'sine', "
                             "'amplitude': ..., 'omega': ...}")
        excitation_from = "scene"
    else:
        sine = _sine_parameters(excitation)
    if sine["amplitude"] == 0.0 or sine["omega"] <= 0.0:
        raise ValueError(f"excitation = {excitation!r} is invalid: needs amplitude != 0 and "
                         "omega > 0")
    creep_limit = check_positive("creep_limit", creep_limit, allow_zero=True, unit="m")
    if isinstance(direction, bool) or direction not in (1, -1, 1.0, -1.0):
        raise ValueError(f"direction = {direction!r} is invalid: must be +1 or -1")
    tolerance = check_positive("tolerance", tolerance, unit="")
    max_iterations = check_count("max_iterations", max_iterations, 1)
    points_per_round = check_count("points_per_round", points_per_round, 1)
    ramp_cycles = check_count("ramp_cycles", ramp_cycles, 0)
    amplitude = abs(sine["amplitude"])
    # Self-locking: the band per newton of force contains 0; the torque needs
    # the force |M| / (band edge on its side).
    low_per_newton, high_per_newton = static_holding_band(scene, float(direction))
    edge = high_per_newton if torque > 0 else -low_per_newton
    torque_share = abs(torque) / edge if torque != 0.0 else 0.0
    # The smallest flank force, preload + direction offset - |A|, must carry
    # the torque's share.
    quasi_static = max(0.0, amplitude - float(direction) * sine["offset"] + torque_share)
    if upper is None:
        upper = UPPER_FACTOR * quasi_static if quasi_static > 0.0 else amplitude
    upper = check_positive("upper", upper, unit="N")
    cycles, settle_cycles, points_per_cycle = check_cycles(cycles, settle_cycles,
                                                           points_per_cycle)
    frequency = sine["omega"] / (2.0 * math.pi)
    options = with_tolerances(simulate_options, rtol, atol)
    check_simulate_options(scene, options, (ramp_cycles + cycles) / frequency)
    case = functools.partial(_preload_case, scene=scene, sine=sine, direction=float(direction),
                             cycles=cycles, settle_cycles=settle_cycles,
                             points_per_cycle=points_per_cycle, options=options,
                             ramp_cycles=ramp_cycles)
    rows: List[Dict[str, Any]] = []

    def evaluate(preloads, iteration):
        """The verdicts: True (holds), False (fails) or None (the case
        raised: its row carries the message and decides nothing)."""
        outcomes = run_cases(case, preloads, executor=executor, progress=progress,
                             description=f"min_holding_preload round {iteration}")
        verdicts = []
        for preload, outcome in zip(preloads, outcomes):
            value = outcome.value or {}
            separated = None if not outcome.ok else bool(
                value["separations"] > 0 or value["flight_fraction"] > 0.0)
            holds = None if not outcome.ok else bool(
                not separated and abs(value["creep_per_cycle"]) <= creep_limit)
            rows.append({
                "iteration": iteration, "preload": float(preload), "holds": holds,
                "separated": separated, "start": value.get("start"),
                "separations": numeric_or_nan(value.get("separations")),
                "creep_per_cycle": numeric_or_nan(value.get("creep_per_cycle")),
                "max_displacement": numeric_or_nan(value.get("max_displacement")),
                "flight_fraction": numeric_or_nan(value.get("flight_fraction")),
                "wall_time": numeric_or_nan(value.get("wall_time")),
                "error": outcome.error,
            })
            verdicts.append(holds)
        return verdicts

    low_holds, high_holds = (verdict is True for verdict in evaluate([0.0, upper], 0))
    low, high = 0.0, upper
    expansions = 0
    while not high_holds and expansions < 10:
        low, high = high, 2.0 * high
        expansions += 1
        high_holds = evaluate([high], 0)[0] is True
    iterations = 0
    undecided: List[float] = []  # the preloads of a round that decided nothing
    if low_holds:
        high = 0.0
    elif high_holds:
        while high - low > tolerance * high and iterations < max_iterations:
            iterations += 1
            step = (high - low) / (points_per_round + 1)
            # A round whose every case raised is evaluated again a third of
            # the spacing higher (a preload exactly on a rigid drive's stick
            # limit may chatter between stick and slip beyond max_events);
            # if those raise too, the search ends.
            for shift in (0.0, 1.0 / 3.0):
                preloads = [low + step * (i + 1 + shift) for i in range(points_per_round)]
                verdicts = evaluate(preloads, iterations)
                holding = [p for p, ok in zip(preloads, verdicts) if ok is True]
                failing = [p for p, ok in zip(preloads, verdicts) if ok is False and
                           (not holding or p < holding[0])]
                if holding or failing:
                    break
                undecided += preloads
            if not holding and not failing:
                break
            undecided = []
            if holding:
                high = holding[0]
            if failing:
                low = max(failing)
    found = bool(low_holds or high_holds)
    if low_holds:
        low = 0.0
    elif not found:
        low = high  # every preload evaluated failed (or raised), the largest too
    converged = bool(found and not undecided and (low_holds or high - low <= tolerance * high))
    verified, monotonic, agreement = _bracket_report(rows, found, low, high, low_holds)
    judged = cycles - settle_cycles
    relaxed = sum(1 for row in rows if row["start"] == "relaxed")
    start = "from rest in static equilibrium under the loads at t = 0"
    if ramp_cycles:
        start = (f"from rest in static equilibrium under {RAMP_START:g} of the loads, "
                 f"ramped to them over {_cycles(ramp_cycles)}")
    if relaxed:
        start += (f" ({relaxed} of {len(rows)} preloads, without one at t = 0: from rest on "
                  "the loaded flank, springs relaxed)")
    run = (f"each run: {start}, {_cycles(settle_cycles, 'settle ')}, then "
           f"{_cycles(judged, 'judged ')} at {frequency:.6g} Hz")
    if low_holds:
        decision = "preload 0 N held: no preload needed"
    elif found:
        width = (high - low) / high
        decision = (f"bisection: {high:.6g} N held and {low:.6g} N failed (bracket "
                    f"{width:.2g} of its upper end{'' if converged else ', not converged'}; "
                    f"{'both simulated' if verified else 'NOT both simulated'})")
        if undecided:
            decision += (f"; stopped in round {iterations}: "
                         f"{', '.join(f'{p:.6g}' for p in undecided)} N raised")
    else:
        decision = f"no preload up to {high:.6g} N held"
    frame = pd.DataFrame(rows)
    raised, _ = raised_rows(frame)
    if raised:
        decision += f"; {raised} of {len(rows)} evaluated preloads raised and decided nothing"
    decided_by = f"{decision}; {agreement}; {run}"
    if not monotonic:
        warnings.warn(f"min_holding_preload: {agreement}: the answer {high:.6g} N assumes "
                      "that holding is monotonic in the preload", StudyWarning, stacklevel=2)
    units = dict(SUMMARY_UNITS)
    if not found:
        units.pop("min_preload")  # a text
    return annotate(
        frame, UNITS, summary_units=units, study="min_holding_preload",
        min_preload=float(high) if found else f"not found in [0, {high:.6g}] N",
        bracket_low=float(low),
        bracket_high=float(high) if found else float("nan"),
        iterations=iterations,
        converged=converged,
        found=found,
        bracket_verified=verified,
        monotonic=monotonic,
        decided_by=decided_by,
        quasi_static_preload=float(quasi_static),
        amplitude=amplitude,
        frequency=frequency,
        creep_limit=creep_limit,
        ramp_cycles=ramp_cycles,
        settle_cycles=settle_cycles,
        judged_cycles=judged,
        excitation_from=excitation_from,
    )


def plot_min_holding_preload(frame: pd.DataFrame, ax: Optional[Any] = None):
    """Draw |creep per cycle| [m] over the evaluated preloads [N], holding
    preloads filled, with the bracket shaded.

    Args:
        frame: the DataFrame :func:`min_holding_preload` returned.
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes.
    """
    ax = axes(ax)
    ok = frame[frame["error"].isna()]  # the rows that decided (holds True or False)
    verdicts = ok["holds"].astype(bool).to_numpy()
    holds, fails = ok[verdicts], ok[~verdicts]
    floor = 1e-15  # zero creep on a log axis
    ax.semilogy(holds["preload"], np.maximum(np.abs(holds["creep_per_cycle"]), floor), "o",
                color="C2", label="holds")
    ax.semilogy(fails["preload"], np.maximum(np.abs(fails["creep_per_cycle"]), floor), "x",
                color="C3", label="separates or creeps")
    summary = frame.attrs.get("summary", {})
    if summary.get("found"):
        ax.axvspan(summary["bracket_low"], summary["bracket_high"], color="0.85", zorder=0,
                   label="bracket")
    ax.set_xlabel("static preload [N]")
    ax.set_ylabel("|creep per cycle| [m]")
    ax.legend(loc="best")
    return ax
