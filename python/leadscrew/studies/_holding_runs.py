"""What the holding and creep studies share: their scenes, excitations and one run's response.

A holding study runs a scene with a constant drive torque (``_constant_torque``)
under an alternating axial force: the scene's own sine, an argument's or the
fallback 30 N, 20 Hz (``_alternating_excitation``, ``_sine_parameters``), the
nut placed in the play and every run started at rest (:func:`alternating_scene`).
:func:`cycle_response` runs one such scene for whole cycles and measures the
creep per cycle, the largest displacement and the flights across the play;
:func:`static_holding_band` is the closed-form band of torques a thread holds
under a static axial force. :mod:`leadscrew.studies.position`
(``position_holding``), :mod:`leadscrew.studies.holding`
(``min_holding_preload``) and :mod:`leadscrew.studies.creep` build on them.
"""

from __future__ import annotations

import math
from typing import Any, Dict, Optional, Tuple

import numpy as np

from ..excitation import Sine, check_load_unit
from ..scene import _DEFAULT_DRIVE_TORQUE, Scene
from ..simulation import simulate
from ..thread import lower_torque, raise_torque
from ._common import (as_scene, check_count, gear_ratio, check_finite, check_positive, constant_value,
                      in_unit)

__all__ = ["cycle_response", "alternating_scene", "static_holding_band", "check_cycles"]


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
    value = constant_value(torque)
    if value is not None:
        return value
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

    Behind an ideal gear stage (``gear.type = "ideal"``, ratio n: the rotor
    turns n times per turn of the driven part, n < 0 reversing) the rotor's
    torque T puts n T on the driven part (the stage loses no power:
    T phi_rotor' = (n T) phi_driven', docs/physics/gear.md), so the rotor's
    band is the driven part's divided by n, its ends swapped for n < 0. A
    lossy or worm stage is refused: its own friction holds torque (a worm
    may lock by itself), which the thread's band does not give.

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict): thread, mu and
            an ideal gear stage if it has one.
        axial_force: static axial force on the load along +x [N].

    Returns:
        (low, high) [N*m] in the sign convention of ``loads.drive_torque``
        (the rotor's torque); (0, 0) for a zero force.

    Raises:
        ValueError: invalid scene, a lossy or worm gear stage, or a force
            that is not finite.
    """
    scene = as_scene(scene, gear=True)
    if "gear" in scene and scene["gear"]["type"] != "ideal":
        kind = scene["gear"]["type"]
        raise ValueError(f"gear.type = {kind!r} is invalid for static_holding_band: the band "
                         "is derived for an ideal stage only (the driven part's band divided "
                         f"by the ratio); a {kind} stage's own friction holds torque (its "
                         "efficiency forward and back differ, a worm may lock by itself), "
                         "which the thread's band does not give")
    axial_force = check_finite("axial_force", axial_force, unit="N")
    thread, mu = scene.thread, scene["friction"]["mu"]
    if axial_force == 0.0:
        return 0.0, 0.0
    raising = raise_torque(thread, mu, abs(axial_force))
    lowering = lower_torque(thread, mu, abs(axial_force))
    # Positive torque raises the load iff -h points against the force.
    low, high = (-lowering, raising) if thread.hand_sign * axial_force > 0 else (-raising,
                                                                                 lowering)
    n = gear_ratio(scene)  # (1 without a stage: the band as it is)
    return (low / n, high / n) if n > 0 else (high / n, low / n)


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
    # (phi_drive is the rotor's; the driven part turns by phi_drive / n: an
    # ideal gear stage of ratio n, 1 without one.)
    turn = float(np.dot(k, angle - angle.mean()) / np.dot(k, k)) / gear_ratio(scene)
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
