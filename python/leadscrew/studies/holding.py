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

:func:`position_holding` is in :mod:`leadscrew.studies.position` and what
the holding studies share (their scenes, excitations and
:func:`cycle_response`) in :mod:`leadscrew.studies._holding_runs`; this
module holds :func:`min_holding_preload` and re-exports the others, so that
``leadscrew.studies.holding`` names every holding study.
"""

from __future__ import annotations

import functools
import math
import warnings
from typing import Any, Dict, List, Optional, Tuple

import numpy as np
import pandas as pd

from ..errors import NoEquilibriumError, StudyWarning
from ..scene import Scene
from ..thread import is_self_locking
from .._progress import shown
from ._batch import check_simulate_options
from ._common import (annotate, as_counts, as_scene, axes, check_count, check_positive,
                      numeric_or_nan, raised_rows, with_tolerances)
# (_preload_case calls cycle_response through this module, where tests replace it.)
from ._holding_runs import (FALLBACK_AMPLITUDE, FALLBACK_FREQUENCY,  # noqa: F401
                            FLIGHT_RESOLUTION, SUMMARY_UNITS, UNITS, _alternating,
                            _constant_torque, _scene_sine, _sine_parameters, alternating_scene,
                            check_cycles, cycle_response, static_holding_band)
from ._sweep import run_cases
from .position import plot_position_holding, position_holding

__all__ = [
    "cycle_response",
    "alternating_scene",
    "static_holding_band",
    "position_holding",
    "plot_position_holding",
    "min_holding_preload",
    "plot_min_holding_preload",
]


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
            default the scene's [simulation] ones, else simulate's, 1e-8 and
            1e-10; not with integrator "moreau").
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
    progress = shown(progress)
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
    frame = as_counts(pd.DataFrame(rows))
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
    """Draw |creep per cycle| [um] over the evaluated preloads [N], holding
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
    floor = 1e-9  # [um]: zero creep on a log axis
    # In um, as every other study's creep (the frame keeps metres).
    ax.semilogy(holds["preload"], np.maximum(np.abs(holds["creep_per_cycle"]) * 1e6, floor), "o",
                color="C2", label="holds")
    ax.semilogy(fails["preload"], np.maximum(np.abs(fails["creep_per_cycle"]) * 1e6, floor), "x",
                color="C3", label="separates or creeps")
    summary = frame.attrs.get("summary", {})
    if summary.get("found"):
        ax.axvspan(summary["bracket_low"], summary["bracket_high"], color="0.85", zorder=0,
                   label="bracket")
    ax.set_xlabel("static preload [N]")
    ax.set_ylabel("|creep per cycle| [um]")
    ax.legend(loc="best")
    return ax
