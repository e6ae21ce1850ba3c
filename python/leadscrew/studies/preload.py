"""The preload trade-off of a split nut (issue 19, item 5; docs/physics/preloaded_nut.md).

The thesis's design compromise in one table: "a higher preload leads to a
worse efficiency", but it holds the load against reversal and vibration.
For each preload P of ``nut.preload`` on the scene's drive (the rigid
concept's closed forms below; on the flexible concepts the axial stiffness
comes from the simulation, last item):

- **efficiency**: a speed-controlled motor raises the static load ``load``
  (the scene's static axial force by default) as in
  :func:`~leadscrew.studies.efficiency_vs_mu`, eq. (5.2) over the run's
  second half, beside the closed form F tan a / [(F + P) tan(a + rho') +
  P tan(rho' - a)];
- **axial stiffness** (closed form; the rigid model does not simulate a
  half lifting off): the nut is rigid while both halves bear, so it holds a
  reversed load up to P without moving (``held_reverse_load`` = P). The
  vibration of amplitude A about the static load F reverses the force by
  R = A - F where A > F; beyond P half A lifts off and the spring of rate
  k_p (``nut.preload_stiffness``) carries the excess, moving the load by
  (R - P) / k_p, so the secant stiffness against the reversed peak is
  k_p R / (R - P) (``axial_stiffness``; inf where R <= P, NaN where k_p is
  not given);
- **creep** under the scene's vibration: the static load plus the scene's
  alternating axial force (its sine's amplitude and frequency, else 30 N and
  20 Hz; ``amplitude=`` / ``frequency=`` override) with the scene's constant
  drive torque, from rest, whole cycles (:func:`~leadscrew.studies.cycle_response`);
  beside it ``holds_closed_form``: the stuck rigid drive's holding band
  (raise and lower torques of both halves) contains the drive torque at both
  extremes of the force, so the drive never slips (a stuck rigid drive is in
  static equilibrium: exact).

On the flexible concepts (``flexible_nut``, ``flexible``, without play or
with penalty play, where half A lifts off: docs/physics/preloaded_nut.md,
"Lift-off") the efficiency and creep runs are the same simulations;
``axial_stiffness`` is the simulated secant stiffness at the load, the
vibration's force range 2 A over the range of the load's place beyond the
thread's, u_load + h p phi_drive (the creep is the thread's turning), in
the settled cycles: the nut's and screw's springs, the play and, beyond
the lift-off, the split nut's spring; without play the thread holds the
nut at any preload (no lift-off), and
``held_reverse_load`` is where half A lifts off, P + k_p d_0
(:func:`lift_off_spring_force`; P without play). ``efficiency_closed_form``
and ``holds_closed_form`` stay the rigid drive's (the flexible drive's
quasi-static thread forces; with play the spring's force in steady raising
is P less k_p times half A's added penetration).

The drive train (the shipped ``seat_adjuster``; docs/physics/
preloaded_nut.md, "The study on a drive train"):

- **a DC motor** is replaced by the study's own drive: the efficiency run
  prescribes the speed, the creep runs hold the scene's constant
  ``loads.drive_torque``, 0 for a motor scene (the motor unpowered; a
  shorted winding's back-EMF braking is left out, so the creep is the
  larger one). ``attrs["summary"]["motor_replaced"]`` says so.
- **an ideal gear stage** of ratio n stays: the rotor turns at n times
  ``speed`` (``speed`` is the driven part's), its torque acts n-fold on the
  driven part (the holding band compares n M), the creep is the driven
  part's turning. The closed form of the efficiency stays the thread's;
  ``train_efficiency`` is the simulated whole train's (every loss of the
  run: the thread's, and a lossy or worm stage's and a motor's own friction
  where the core runs them; the ideal stage's equals ``efficiency``). A
  lossy or worm stage with a preload is refused by the study (its closed
  forms are the thread's behind an ideal stage; the core runs the scene on
  Moreau-Jean), which says what to do (``gear.type = "ideal"`` or
  ``nut.preload = 0``).
- **exact play on a flexible concept** (``backlash.contact = "exact"``):
  half A lifting off into the exact play is not modelled, so at P > 0 the
  study runs the thread without play, the preload closing it as on the
  rigid concept (``attrs["summary"]["play_closed"]``). That is exact while
  the load never presses half B's flank beyond the preload: always in the
  efficiency run (the load presses half A), and in the creep run where the
  vibration's reversed peak R = A - F is at most P. A row with R > P keeps
  its efficiency and says in ``error`` that its creep and stiffness need
  penalty play (``"bistop"`` with ``nut.preload_stiffness``). P = 0 runs
  the scene's exact play (the plain nut rattles in it). (The core closes
  exact play with a preload too, and raises a SimulationError where half A
  lifts off; the study drops the play itself because its creep runs start
  from relaxed springs, whose start transient, not the vibration asked
  about, reverses the seat adjuster's thread force by 22 N, 0.014 s into
  the run: the core would end P = 20 N's creep run there.)
"""

from __future__ import annotations

import functools
import math
import warnings
from typing import Any, Dict, Optional, Sequence, Tuple

import numpy as np
import pandas as pd

from .. import _core
from ..thread import lower_torque, raise_torque
from ..errors import StudyWarning
from .._progress import shown
from ._common import (annotate, as_scene, axes, check_grid, check_positive, constant_value,
                      gear_ratio, numeric_or_nan, with_tolerances)
from ._holding_runs import (_alternating_excitation, _constant_torque, _scene_sine,
                            alternating_scene, check_cycles, cycle_response)
from ._sweep import run_cases

__all__ = ["preload_tradeoff", "plot_preload_tradeoff", "preloaded_holding_band",
           "lift_off_spring_force"]

UNITS = {"preload": "N", "efficiency": "1", "efficiency_closed_form": "1",
         "relative_error": "1", "train_efficiency": "1", "efficiency_change": "1",
         "efficiency_t_end": "s", "held_reverse_load": "N", "axial_stiffness": "N/m",
         "creep_per_cycle": "m", "max_displacement": "m", "holds_closed_form": "",
         "wall_time": "s", "error": ""}


def _half_torque(thread, mu: float, axial: float, against: bool) -> float:
    """The torque [N*m] that moves one nut half with axial force ``axial`` on
    its flank against it (a power screw raising) or with it (lowering)."""
    if axial < 0.0:  # the half on its other flank: the sense turns
        axial, against = -axial, not against
    return raise_torque(thread, mu, axial) if against else lower_torque(thread, mu, axial)


def preloaded_holding_band(scene: Any, axial_force: float, preload: float,
                           loaded_side: float) -> Tuple[float, float]:
    """Drive torques [N*m] on the driven part (a gear stage's rotor torque
    times its ratio) a stuck rigid drive with a preloaded nut holds under a
    static axial force (docs/physics/preloaded_nut.md, "Holding").

    Half A bears on the flank that a force of sign ``loaded_side`` presses
    (the scene's axial force at t = 0), carrying F_A + P with F_A =
    loaded_side * axial_force; half B carries P. Moving against F_A needs
    T_raise = [half A against F_A + P] + [half B with P], moving with it
    T_lower = [half A with F_A + P] + [half B against P] (each half a power
    screw: raise_torque, lower_torque; a half whose force is negative bears
    on its other flank), at the stick limit: ``friction.mu_static`` where
    the scene gives one (the halves break free at mu_static': docs/physics/
    preloaded_nut.md, "Two coefficients"), else ``mu``. The band is
    (-T_lower, T_raise) in the sense that
    moves against F_A, mapped to the sign of ``loads.drive_torque`` as in
    :func:`~leadscrew.studies.static_holding_band` (P = 0: that band).

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict): thread and mu.
        axial_force: static axial force on the load along +x [N].
        preload: the nut's preload P [N], >= 0.
        loaded_side: +1 or -1, the sign of the force that presses half A.

    Returns:
        (low, high) [N*m]: the drive holds iff the torque lies strictly inside.
    """
    scene = as_scene(scene, gear=True)
    # A stuck drive breaks free at the stick limit: mu_static where given.
    friction = scene["friction"]
    thread, mu = scene.thread, friction.get("mu_static", friction["mu"])
    side = 1.0 if loaded_side > 0 else -1.0
    a_force = side * axial_force + preload
    against = _half_torque(thread, mu, a_force, True) + _half_torque(thread, mu, preload, False)
    along = _half_torque(thread, mu, a_force, False) + _half_torque(thread, mu, preload, True)
    # Positive torque moves the load along -h x: against F_A iff h side > 0.
    if thread.hand_sign * side > 0:
        return -along, against
    return -against, along


def _efficiency_case(scene, load: float, speed: float, t_end: float,
                     options: Dict[str, Any]) -> Dict[str, Any]:
    """eta = 1 - W_friction / W_in over the second half of a raising run,
    lengthened (t_end doubled, up to LONGEST_EFFICIENCY_RUN times) until the
    efficiency is steady over that window."""
    omega = -scene.thread.hand_sign * speed * gear_ratio(scene)  # the rotor's
    running = scene.replace(loads={"drive_torque": None, "drive_speed": omega,
                                   "axial_force": -load},
                            initial={"rotor_speed": omega, "state": "relaxed"})
    wall_time = 0.0
    run_end = t_end
    while True:
        out = _efficiency_run(running, run_end, options)
        wall_time += out["wall_time"]
        if out["efficiency_change"] <= STEADY_CHANGE or run_end >= LONGEST_EFFICIENCY_RUN * t_end:
            return dict(out, wall_time=wall_time, efficiency_t_end=run_end)
        run_end *= 2.0


#: The efficiency_change beyond which an efficiency run is not steady, and
#: how much longer than the study's t_end the study lets it run to get there.
STEADY_CHANGE = 1e-4
LONGEST_EFFICIENCY_RUN = 32


def _efficiency_run(running, t_end: float, options: Dict[str, Any]) -> Dict[str, Any]:
    """The efficiency over [t_end / 2, t_end] of the raising run ``running``,
    and its relative change between the halves of that window."""
    from ..simulation import simulate

    t_eval = np.array([0.0, 0.5 * t_end, 0.75 * t_end, t_end])
    result = simulate(running, t_end, t_eval=t_eval, **options)
    work_drive, friction_loss = result["work_drive"], result["friction_loss"]
    work = work_drive[3] - work_drive[1]
    loss = friction_loss[3] - friction_loss[1]
    # The whole train's: every loss of the run (the thread's, an ideal
    # stage's none; a lossy or worm stage's and a motor's own friction where
    # the core runs them).
    train = loss + sum(result[name][3] - result[name][1] for name in _TRAIN_LOSSES
                       if name in result.channels)
    # How steady the run is: the efficiency over each half of the window (a
    # flexible drive's springs still settling show as a change).
    # A half without work in (the nut crossing its play) is not steady.
    efficiency = (work - loss) / work
    halves = [(work_drive[k + 1] - work_drive[k], friction_loss[k + 1] - friction_loss[k])
              for k in (1, 2)]
    if all(half_work > 0.0 for half_work, _ in halves):
        (work_a, loss_a), (work_b, loss_b) = halves
        change = abs(loss_a / work_a - loss_b / work_b) / max(abs(efficiency), 1e-300)
    else:
        change = math.inf
    return {"efficiency": efficiency, "train_efficiency": (work - train) / work,
            "efficiency_change": change, "wall_time": float(result.stats["wall_time"])}



#: The train's losses besides the thread's friction (channels of a run).
_TRAIN_LOSSES = ("gear_loss", "motor_friction_loss")


def _closes_the_play(scene, preload: float) -> bool:
    """Whether the study runs ``scene`` at ``preload`` with the play closed:
    exact play on a flexible concept with a preload (module docstring)."""
    contact = scene["backlash"]["contact"] if "backlash" in scene else None
    return preload > 0.0 and scene["concept"] != "rigid" and contact == "exact"


def _case(preload: float, scene, load: float, speed: float, t_end: float, amplitude: float,
          frequency: float, cycles: int, settle_cycles: int, points_per_cycle: int,
          options: Dict[str, Any]) -> Dict[str, Any]:
    preloaded = scene.replace(nut={"preload": preload})
    closed_play = _closes_the_play(scene, preload)
    if closed_play:  # the preload closes the exact play (module docstring)
        preloaded = preloaded.replace(backlash=None)
    out = _efficiency_case(preloaded, load, speed, t_end, options)
    if closed_play and max(0.0, amplitude - load) > preload:
        # The vibration presses half B's flank beyond the preload: half A
        # would lift off into the exact play, which the core does not model.
        out["error"] = (f"nut.preload = {preload:g} N holds less than the vibration's reversed "
                        f"peak {amplitude - load:g} N: half A would lift off into the exact "
                        "play, which is not modelled (docs/physics/preloaded_nut.md); give "
                        "the scene penalty play (backlash.contact = \"bistop\" with "
                        "nut.preload_stiffness) for its creep and stiffness")
        return out
    excited = alternating_scene(preloaded, amplitude, frequency, offset=-load)
    flexible = scene["concept"] != "rigid"
    creep = cycle_response(excited, frequency, cycles, settle_cycles, points_per_cycle,
                           series=flexible, **options)
    out["creep_per_cycle"] = creep["creep_per_cycle"]
    out["max_displacement"] = creep["max_displacement"]
    out["wall_time"] += creep["wall_time"]
    if flexible:
        # The simulated secant stiffness at the load: the force's range 2 A
        # over the range of the load's place beyond the thread's, u_load +
        # h p phi_drive (the springs' deflections and the play; the creep is
        # the thread's turning), in the settled cycles.
        result, thread = creep["result"], scene.thread
        settled = creep["t"] >= settle_cycles / frequency
        # (phi_drive is the rotor's: the driven part turns by phi_drive / n.)
        turned = result["phi_drive"] / gear_ratio(scene)
        place = result["u_load"] + thread.hand_sign * thread.lead_per_radian * turned
        out["axial_stiffness"] = 2.0 * amplitude / float(np.ptp(place[settled]))
    return out


def lift_off_spring_force(scene: Any) -> Optional[Tuple[float, float]]:
    """Where half A of a preloaded nut with penalty play on a flexible concept
    lifts off (docs/physics/preloaded_nut.md, "Lift-off"): the spring's force
    P + k_p d_0 [N] and d_0 [m], half A's flank penetrated at the preload (the
    core starts the nut assembled there: its play position is c/2 + d_0).

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict) with ``nut.preload`` > 0.

    Returns:
        (P + k_p d_0, d_0), or None where half A does not lift off (the rigid
        concept, no play, no preload).

    Raises:
        ValueError: the scene's check.
    """
    scene = as_scene(scene, gear=True)
    preload = float(scene["nut"]["preload"])
    contact = scene["backlash"]["contact"] if "backlash" in scene else None
    if scene["concept"] == "rigid" or contact not in ("bistop", "cubic") or preload <= 0.0:
        return None
    parameters = scene.model().parameters
    penetration = abs(parameters.play_position) - 0.5 * parameters.clearance
    return preload + float(scene["nut"]["preload_stiffness"]) * penetration, penetration


def preload_tradeoff(
    scene: Any,
    preloads: Sequence[float],
    load: Optional[float] = None,
    speed: float = 10.0,
    t_end: float = 0.05,
    amplitude: Optional[float] = None,
    frequency: Optional[float] = None,
    cycles: int = 6,
    settle_cycles: int = 1,
    points_per_cycle: int = 50,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    executor=None,
    progress: bool = True,
    **simulate_options: Any,
) -> pd.DataFrame:
    """Efficiency, axial stiffness and creep against the split nut's preload.

    Each preload runs the scene (exact Coulomb: what a preloaded nut
    supports; any concept, the flexible ones' stiffness simulated) with ``nut.preload`` = P twice: raising the
    static load ``load`` at ``speed``, and at rest under the load plus the
    vibration with the scene's constant drive torque (module docstring).
    The static load presses along -x, so half A bears on its flank.

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict) with a constant ``loads.drive_torque`` (the torque the drive holds
            against; 0 for a scene without one), or a DC motor (replaced),
            an ideal gear stage (module docstring).
        preloads: the preloads P [N], >= 0.
        load: the static load [N], > 0 (default: the magnitude of the scene's
            static axial force, a constant or its sine's offset).
        speed: speed of the driven part (the rotor's without a gear stage,
            the rotor turning at n times it with one) in the efficiency run
            [rad/s], > 0.
        t_end: duration of the efficiency run [s], > 0, its first try:
            the efficiency is taken over [t_end / 2, t_end], and where it
            changes by more than 1e-4 between that window's halves (a
            flexible drive's springs still settling: the seat adjuster's
            efficiency is 8 % off the closed form at 0.05 s, 3e-5 at 1 s),
            the run is taken again with t_end doubled, up to 32 times the
            given one (``efficiency_t_end`` says which; the rigid drive is
            steady at once).
        amplitude: the vibration's amplitude [N], > 0 (default: the scene's
            sine's, else 30 N).
        frequency: its frequency [Hz], > 0 (default: the scene's sine's,
            else 20 Hz).
        cycles, settle_cycles, points_per_cycle: the creep runs'
            (:func:`~leadscrew.studies.cycle_response`).
        rtol, atol: integration tolerances (default simulate's).
        executor: a :class:`concurrent.futures.Executor` (default: a thread
            pool over all cores).
        progress: show a tqdm progress bar.
        **simulate_options: passed on to :func:`leadscrew.simulate`.

    Returns:
        DataFrame with one row per preload: ``preload`` [N], ``efficiency``
        [1], ``efficiency_closed_form`` [1], ``relative_error`` [1],
        ``train_efficiency`` [1] (the whole train's), ``efficiency_change``
        [1] (the efficiency's relative change between the halves of its
        window: ~0 for a steady run; above 1e-4 at the longest run the
        study warns), ``efficiency_t_end`` [s] (the run's length it took),
        ``held_reverse_load`` [N], ``axial_stiffness`` [N/m],
        ``creep_per_cycle`` [m] (signed along +x), ``max_displacement`` [m],
        ``holds_closed_form`` (bool), ``wall_time`` [s, C++] and ``error``
        (None, or the message of a failed case, whose numbers are NaN; a
        row whose creep run is not modelled keeps its efficiency).
        ``attrs["summary"]``: ``load`` [N], ``amplitude`` [N], ``frequency``
        [Hz], ``reversed_load`` [N] (max(0, amplitude - load)), ``drive_torque`` [N*m], ``preload_stiffness`` [N/m],
        ``excitation_from``, ``gear_ratio`` [1], ``motor_replaced``,
        ``play_closed``, ``unsteady`` (rows whose efficiency_change > 1e-4),
        ``raised``, ``raised_reasons``.

    Raises:
        ValueError: invalid scene (what a preloaded nut refuses: a lossy or
            worm stage, a law other than exact Coulomb, ...; no constant
            drive torque, no static load and no ``load``) or arguments.
        TypeError: an unknown keyword in ``simulate_options``.
    """
    progress = shown(progress)
    scene = as_scene(scene, gear=True)
    preloads = check_grid("preloads", preloads, allow_zero=True, unit="N")
    # The study drives the driven part itself: a DC motor is replaced by its
    # own drive (a prescribed speed raising, the scene's constant drive
    # torque at rest: 0 with the motor unpowered). A gear stage stays: its
    # ratio scales the rotor's speed and torque (module docstring).
    motor = scene.to_dict().get("motor")
    if motor is not None:
        scene = scene.replace(motor=None)
    # What a preloaded nut refuses (a lossy or worm stage, the law, the
    # start, ...), said once, up front, rather than in every row but P = 0's.
    if preloads.max() > 0.0:
        # The core runs a lossy or worm stage with a preload (on Moreau-Jean)
        # and every law but eq. (3.15), but this study's closed forms (the
        # efficiency at mu', the holding band) are exact Coulomb's on the
        # thread behind an ideal stage.
        data = scene.to_dict()
        gear = (data.get("gear") or {}).get("type", "ideal")
        law = (data.get("friction") or {}).get("law", "coulomb")
        refused = (("gear.type", gear, "the thread's behind an ideal stage", "ideal", "on Moreau-Jean")
                   if gear != "ideal" else
                   ("friction.law", law, "exact Coulomb's", "coulomb", "with its law")
                   if law != "coulomb" else None)
        if refused:
            key, value, whose, valid, how = refused
            raise ValueError(
                f"nut.preload = {float(preloads.max()):g} N is invalid with {key} = \"{value}\": "
                f"preload_tradeoff's closed forms (the efficiency, the holding band) are {whose}; "
                f"use nut.preload = 0, or {key} = \"{valid}\" (simulate runs the scene itself "
                f"{how})")
        largest = scene.replace(nut={"preload": float(preloads.max())})
        if _closes_the_play(scene, float(preloads.max())):
            largest = largest.replace(backlash=None)
        largest.model()
    torque = _constant_torque(scene)
    if load is None:
        load = abs(_static_force(scene))
        if load == 0.0:
            raise ValueError("load is missing: the scene has no static axial force (a "
                             "constant loads.axial_force or a sine's offset); give load=")
    load = check_positive("load", load, unit="N")
    speed = check_positive("speed", speed, unit="rad/s")
    t_end = check_positive("t_end", t_end, unit="s")
    amplitude, frequency, excitation_from = _alternating_excitation(scene, amplitude, frequency)
    cycles, settle_cycles, points_per_cycle = check_cycles(cycles, settle_cycles,
                                                           points_per_cycle)
    options = with_tolerances(simulate_options, rtol, atol)
    function = functools.partial(_case, scene=scene, load=load, speed=speed, t_end=t_end,
                                 amplitude=amplitude, frequency=frequency, cycles=cycles,
                                 settle_cycles=settle_cycles, points_per_cycle=points_per_cycle,
                                 options=options)
    outcomes = run_cases(function, list(preloads), executor=executor, progress=progress,
                         description="preload_tradeoff")
    thread, mu = scene.thread, scene["friction"]["mu"]
    closed = _core.preloaded_efficiency_array(thread, mu, load, preloads)
    stiffness = float(scene["nut"]["preload_stiffness"])
    reversed_load = max(0.0, amplitude - load)  # the vibration's peak on half B's side
    rows = []
    flexible = scene["concept"] != "rigid"
    for preload, expected, outcome in zip(preloads, closed, outcomes):
        value = outcome.value or {}
        eta = numeric_or_nan(value.get("efficiency"))
        error = outcome.error or value.get("error")
        held = preload
        if flexible:  # simulated; half A lifts off at the spring's P + k_p d_0
            secant = numeric_or_nan(value.get("axial_stiffness"))
            lift_off = lift_off_spring_force(scene.replace(nut={"preload": preload}))
            held = lift_off[0] if lift_off else preload
        elif preload >= reversed_load:
            secant = math.inf
        else:
            secant = (stiffness * reversed_load / (reversed_load - preload) if stiffness > 0
                      else math.nan)
        # The band is piecewise affine in the force, with its kink where half
        # A's force F_A + P is zero: the extremes of the force and the kink.
        forces = [-load - amplitude, -load + amplitude]
        if forces[0] < preload < forces[1]:
            forces.append(preload)
        bands = [preloaded_holding_band(scene, force, preload, -1.0) for force in forces]
        driven = torque * gear_ratio(scene)  # the rotor's torque on the driven part
        rows.append({
            "preload": preload, "efficiency": eta, "efficiency_closed_form": float(expected),
            "relative_error": abs(eta - expected) / expected if expected > 0 else abs(eta),
            "train_efficiency": numeric_or_nan(value.get("train_efficiency")),
            "efficiency_change": numeric_or_nan(value.get("efficiency_change")),
            "efficiency_t_end": numeric_or_nan(value.get("efficiency_t_end")),
            "held_reverse_load": held, "axial_stiffness": secant,
            "creep_per_cycle": numeric_or_nan(value.get("creep_per_cycle")),
            "max_displacement": numeric_or_nan(value.get("max_displacement")),
            "holds_closed_form": all(low < driven < high or low == driven == high
                                     for low, high in bands),
            "wall_time": numeric_or_nan(value.get("wall_time")), "error": error})
    frame = pd.DataFrame(rows, columns=list(UNITS))
    unsteady = int((frame["efficiency_change"] > STEADY_CHANGE).sum())
    if unsteady:
        warnings.warn(
            f"preload_tradeoff: in {unsteady} of {len(frame)} rows the efficiency still changed "
            f"by up to {frame['efficiency_change'].max():.3g} between the halves of its window "
            f"[t_end / 2, t_end] at {LONGEST_EFFICIENCY_RUN} times t_end = {t_end:g} s: the run "
            "is not steady and its efficiency is off the steady one by about as much; lengthen "
            "t_end", StudyWarning, stacklevel=2)
    return annotate(frame, UNITS, study="preload_tradeoff",
                    summary_units={"load": "N", "amplitude": "N", "frequency": "Hz",
                                   "reversed_load": "N", "drive_torque": "N*m",
                                   "preload_stiffness": "N/m", "gear_ratio": "1",
                                   "unsteady": "1"},
                    load=load, amplitude=amplitude, frequency=frequency,
                    reversed_load=reversed_load, drive_torque=torque,
                    preload_stiffness=stiffness, excitation_from=excitation_from,
                    gear_ratio=gear_ratio(scene), motor_replaced=motor is not None,
                    unsteady=unsteady,
                    play_closed=_closes_the_play(scene, float(preloads.max())))


def _static_force(scene) -> float:
    """The scene's static axial force [N]: a constant, or a sine's offset (0 otherwise)."""
    value = constant_value(scene["loads"].get("axial_force", 0.0))
    if value is not None:
        return value
    sine = _scene_sine(scene)
    return float(sine["offset"]) if sine else 0.0


#: The creep per cycle the figure draws as 0, relative to the row's
#: max_displacement: the integration's round-off, not a creep.
CREEP_RESOLUTION = 1e-6


def plot_preload_tradeoff(frame: pd.DataFrame, ax: Optional[Any] = None):
    """Draw the trade-off: efficiency (simulated, closed form) against the
    preload, on a second axis the creep per cycle under the vibration, on a
    third the axial stiffness.

    Args:
        frame: the DataFrame :func:`preload_tradeoff` returned.
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes (of the efficiency; the creep's and the stiffness's are its
        twins).
    """
    ax = axes(ax)
    ax.plot(frame["preload"], frame["efficiency"], "o", color="C0", label="efficiency, simulated")
    ax.plot(frame["preload"], frame["efficiency_closed_form"], "-", color="C0",
            label="efficiency, closed form")
    ax.set_xlabel("preload P [N]")
    ax.set_ylabel("efficiency eta [1]")
    ax.set_ylim(0.0, 1.05)
    creep_ax = ax.twinx()
    # A creep below a millionth of the load's motion per cycle is the
    # integration's round-off (the flexible seat: 4e-12 m against 1e-5 m),
    # drawn as 0 rather than as a trend (the frame keeps its values).
    creep = np.abs(frame["creep_per_cycle"].to_numpy(dtype=float))
    resolved = creep > CREEP_RESOLUTION * frame["max_displacement"].to_numpy(dtype=float)
    creep_ax.plot(frame["preload"], np.where(resolved | np.isnan(creep), creep, 0.0) * 1e6, "s--",
                  color="C3", label="|creep| per cycle (0: below 1e-6 of the motion)")
    creep_ax.set_ylabel("|creep| per cycle [um]")
    if not np.any(resolved):
        creep_ax.set_ylim(0.0, 1.0)
    # The third result, on an axis of its own beside the creep's: infinite
    # where the nut holds the reversed load without moving (not drawn).
    stiffness_ax = ax.twinx()
    stiffness_ax.spines["right"].set_position(("axes", 1.14))
    stiffness = frame["axial_stiffness"].to_numpy(dtype=float)
    stiffness_ax.plot(frame["preload"], np.where(np.isfinite(stiffness), stiffness, np.nan) * 1e-6,
                      "^:", color="C2", label="axial stiffness (inf: not drawn)")
    stiffness_ax.set_ylabel("axial stiffness [N/um]")
    lines = ax.get_lines() + creep_ax.get_lines() + stiffness_ax.get_lines()
    ax.legend(lines, [line.get_label() for line in lines], loc="upper right")
    return ax
