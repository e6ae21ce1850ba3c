"""Position holding under random vibration (issue 34): the creep of a drive
shaken by a vehicle's vibration, over several seeds and scattered parameters.

:func:`holding_under_vibration` runs the scene once per seed, each seed with
its own realisation of a random excitation (a profile, a PSD) and its own
draw of the scattered parameters (:mod:`leadscrew.studies._vibration_runs`),
and judges the creep against an allowed creep over the run.

What it measures as creep is what the other creep studies measure: the load
travel the thread's turning gives, -h p (phi_drive(t) - phi_drive(0)) / n.
The load's own displacement u_load adds its place in the play and the
elastic deflections of the spindle and the nut, which under vibration ring
with amplitudes far above any creep (about 2 mm on the shipped
``seat_adjuster_vibration``) and come back; the frame gives it too
(``displacement``, ``max_displacement``).
"""

from __future__ import annotations

import functools
import math
import numbers
import warnings
from typing import Any, Dict, List, Optional, Sequence

import numpy as np
import pandas as pd

from .._progress import shown
from ..errors import StudyWarning
from ._batch import check_simulate_options
from ._common import (annotate, as_counts, as_scene, axes, check_count, check_positive,
                      numeric_or_nan, with_tolerances)
from ._sweep import run_cases
from ._vibration_runs import (SCATTER_KEYS, WHERE_UNITS, check_draws, check_record_length,
                              check_scatter, check_where,
                              describe, draw_scatter, excitation_template, is_random,
                              target_psd, varied_scene, vibration_run)
from ._vibration_verdict import (RATE_HORIZON, creep_mechanism, default_allowed_rate,
                                 static_holding, verdict)

__all__ = ["holding_under_vibration", "plot_holding_under_vibration", "SCATTER_KEYS"]

_MEASURES = ("creep", "creep_rate", "max_creep", "creep_scatter", "displacement", "max_displacement",
             "input_rms", "wall_time", "steps", "events")
# (the measures before the verdict's column, and after it)
_BEFORE_HOLDS = 7

#: What a seed's verdict judges (the summary's ``judged_by``): the worst
#: creep over the run, not the creep at the end, which a drive that creeps
#: out and back (or oscillates) would pass.
JUDGED_BY = ("max |creep(t)| over the run (max_creep) <= allowed_creep and the fitted rate "
             "|creep_rate| <= allowed_creep_rate (default allowed_creep per hour, whatever "
             "the run's length); undecided where the run cannot resolve that rate or the "
             "thread is not self-locking at rest")

_UNITS = {"seed": "1", "creep": "m", "creep_rate": "m/s", "max_creep": "m", "creep_scatter": "m", "displacement": "m",
          "max_displacement": "m", "holds": "", "wall_time": "s", "steps": "1",
          "events": "1", "error": ""}

_SUMMARY_UNITS = {"seeds": "1", "duration": "s", "settle_time": "s", "allowed_creep": "m",
                  "allowed_creep_rate": "m/s", "rate_horizon": "s", "mu": "1", "mu_static": "1",
                  "creep_mean": "m", "creep_std": "m", "creep_worst": "m",
                  "creep_rate_mean": "m/s", "creep_rate_std": "m/s", "creep_rate_worst": "m/s",
                  "max_creep_worst": "m", "max_displacement_worst": "m"}

#: The most seeds the figure names in a legend.
_LEGEND_SEEDS = 10

#: Seeds are integers in [0, 2^53], as a RandomVibration's.
_MAX_SEED = 2 ** 53


def _check_seeds(seeds: Any) -> List[int]:
    """A count n (the seeds 0 ... n-1) or a list of distinct seeds, checked.

    Raises:
        ValueError: naming ``seeds``, its value and what it takes.
    """
    if isinstance(seeds, numbers.Integral) and not isinstance(seeds, bool):
        return list(range(check_count("seeds", seeds, 1)))
    form = ("a count >= 1 or a non-empty list of distinct integers in [0, 2^53]")
    try:
        values = list(seeds)
    except TypeError:
        raise ValueError(f"seeds = {seeds!r} is invalid: must be {form}") from None
    if not values or isinstance(seeds, (str, bytes)) or len(set(values)) != len(values) or any(
            isinstance(s, bool) or not isinstance(s, numbers.Integral) or not 0 <= s <= _MAX_SEED
            for s in values):
        raise ValueError(f"seeds = {seeds!r} is invalid: must be {form}")
    return [int(s) for s in values]


def _check_times(duration: Any, settle_time: Any, points: Any):
    duration = check_positive("duration", duration, unit="s")
    points = check_count("points", points, 11)
    if settle_time is None:
        settle_time = 0.1 * duration
    settle_time = check_positive("settle_time", settle_time, allow_zero=True, unit="s")
    # at least 3 output times after the settling for the slope
    latest = duration * (1.0 - 2.0 / (points - 1))
    if settle_time > latest:
        raise ValueError(f"settle_time = {settle_time!r} is invalid: must be in [0, "
                         f"{latest:g}] s (3 output times before duration = {duration:g} s)")
    return duration, settle_time, points


def _seed_case(case, scene, where, template, duration, settle_time, points, options):
    """One seed's run (module-level: process executors pickle it)."""
    seed, draws = case
    varied = varied_scene(scene, where, template, seed, duration, draws)
    return vibration_run(varied, where, duration, settle_time, points, **options)


def _summary(frame: pd.DataFrame, allowed_rate: float, window: float,
             static) -> Dict[str, Any]:
    """Mean, sample std (ddof 1; NaN for one row) and worst (largest
    magnitude, signed) of the creep and its rate over the rows that ran,
    and the verdict with its reason (:func:`_vibration_verdict.verdict`)."""
    ran = frame[frame["error"].isna()]
    out: Dict[str, Any] = {}
    for name in ("creep", "creep_rate"):
        values = ran[name].to_numpy(dtype=float)
        out[f"{name}_mean"] = float(np.mean(values)) if len(values) else math.nan
        out[f"{name}_std"] = float(np.std(values, ddof=1)) if len(values) > 1 else math.nan
        out[f"{name}_worst"] = (float(values[np.argmax(np.abs(values))]) if len(values)
                                else math.nan)
    for name in ("max_creep", "max_displacement"):
        out[f"{name}_worst"] = float(ran[name].max()) if len(ran) else math.nan
    out["verdict"], out["verdict_reason"] = verdict(ran.to_dict("records"), allowed_rate,
                                                     window, static)
    return out


def _holds(row: Dict[str, Any], allowed_creep: float, allowed_rate: float) -> bool:
    """A seed's verdict (:data:`JUDGED_BY`): its worst creep over the run
    within the allowed creep, its fitted rate within the allowed rate."""
    return bool(row["max_creep"] <= allowed_creep and abs(row["creep_rate"]) <= allowed_rate)


def _frame(seeds, draws, outcomes, scatter_keys, allowed, unit):
    rows, series = [], {"creep": [], "psd_f": [], "psd": []}
    for seed, drawn, outcome in zip(seeds, draws, outcomes):
        value = outcome.value or {}
        row: Dict[str, Any] = {"seed": seed, **{key: drawn.get(key, math.nan)
                                                for key in scatter_keys}}
        for name in _MEASURES:
            row[name] = numeric_or_nan(value.get(name))
        row["holds"] = None if outcome.error else _holds(row, *allowed)
        row["error"] = outcome.error
        rows.append(row)
        for name in series:
            series[name].append(value.get(f"{name}_series" if name == "creep" else name))
    columns = ["seed", *scatter_keys, *_MEASURES[:_BEFORE_HOLDS], "holds",
               *_MEASURES[_BEFORE_HOLDS:], "error"]
    frame = as_counts(pd.DataFrame(rows, columns=columns))
    frame["holds"] = frame["holds"].astype(object)
    units = dict(_UNITS, input_rms=unit, **{k: SCATTER_KEYS[k] for k in scatter_keys})
    return frame, series, units


def holding_under_vibration(scene: Any, excitation: Any = None, duration: float = 5.0,
                            seeds: Any = 5, allowed_creep: float = 1e-4,
                            where: str = "loads.base_acceleration",
                            scatter: Optional[Dict[str, Sequence]] = None,
                            settle_time: Optional[float] = None, points: int = 1001,
                            rtol: Optional[float] = None, atol: Optional[float] = None,
                            allowed_creep_rate: Optional[float] = None, executor=None,
                            progress: bool = True,
                            **simulate_options: Any) -> pd.DataFrame:
    scene = as_scene(scene, gear=True)
    progress = shown(progress)
    where = check_where(where)
    if "drive_speed" in scene["loads"]:
        raise ValueError("loads.drive_speed is invalid for holding_under_vibration: a "
                         "speed-controlled rotor cannot creep; give loads.drive_torque or a motor")
    duration, settle_time, points = _check_times(duration, settle_time, points)
    allowed_creep = check_positive("allowed_creep", allowed_creep, unit="m")
    allowed_creep_rate = (default_allowed_rate(allowed_creep) if allowed_creep_rate is None else
                          check_positive("allowed_creep_rate", allowed_creep_rate, unit="m/s"))
    seeds = _check_seeds(seeds)
    scatter = check_scatter(scatter)
    template, excitation_from = excitation_template(scene, excitation, where)
    asked = len(seeds)
    if not is_random(template) and not scatter:
        seeds = seeds[:1]  # every seed would run the same scene: run it once
    draws = [draw_scatter(scatter, seed) for seed in seeds]
    check_draws(scene, seeds, draws)
    # The first seed's scene checks the excitation, the scatter's keys and the
    # options once, before the cases run (naming the field).
    first = varied_scene(scene, where, template, seeds[0], duration, draws[0])
    check_record_length(first["loads"][where.split(".", 1)[1]], where, duration)
    options = with_tolerances(simulate_options, rtol, atol)
    check_simulate_options(first, options, duration)
    function = functools.partial(_seed_case, scene=scene, where=where, template=template,
                                 duration=duration, settle_time=settle_time, points=points,
                                 options=options)
    outcomes = run_cases(function, list(zip(seeds, draws)), executor=executor,
                         progress=progress, description="holding_under_vibration")
    frame, series, units = _frame(seeds, draws, outcomes, list(scatter),
                                  (allowed_creep, allowed_creep_rate), WHERE_UNITS[where])
    target_f, target = target_psd(first, where)
    frame.attrs["series"] = {"t": np.linspace(0.0, duration, points).tolist(), **series,
                             "target_f": target_f, "target_psd": target}
    static = static_holding(first)
    summary = _summary(frame, allowed_creep_rate, duration - settle_time, static)
    spread = "; ".join(f"{key} ~ {kind}({a:g}, {b:g})"
                       for key, (kind, a, b) in scatter.items()) or "none"
    note = (f"{asked} seeds asked, ran once: the excitation is not random and nothing is "
            "scattered, so every seed gives the same run" if asked > len(seeds) else "")
    if note:
        warnings.warn(f"holding_under_vibration: {note}", StudyWarning, stacklevel=2)
    return annotate(frame, units, study="holding_under_vibration",
                    summary_units=dict(_SUMMARY_UNITS), seeds=len(seeds), seeds_note=note,
                    duration=duration,
                    settle_time=settle_time, allowed_creep=allowed_creep,
                    allowed_creep_rate=allowed_creep_rate, rate_horizon=RATE_HORIZON,
                    **summary, judged_by=JUDGED_BY, creep_mechanism=creep_mechanism(first),
                    at_rest=static[1],
                    excitation=describe(template, first["loads"][where.split(".", 1)[1]]),
                    excitation_from=excitation_from, where=where,
                    random=is_random(template), scatter=spread,
                    friction_law=first["friction"]["law"], mu=float(scene["friction"]["mu"]),
                    mu_static=scene["friction"].get("mu_static"))


holding_under_vibration.__doc__ = """Creep of a drive under vibration, per seed, with
    its spread and a verdict (issue 34).

    Every seed runs the scene from rest (springs relaxed, whatever its
    ``initial`` says) for ``duration`` with the excitation at ``where``: a
    random excitation realised with that seed (its period, ``duration`` of
    a RandomVibration, set to the run's), any other load the same in every
    seed; and with its own draw of the ``scatter``. The loads follow the
    rule of every study (:mod:`leadscrew.studies`): ``excitation`` given
    overrides, the scene's load at ``where`` is the default
    (``attrs["summary"]["excitation_from"]``: ``"arguments"`` or
    ``"scene"``); an excitation that is not random, without a scatter,
    runs once (every seed would give the same run; ``seeds_note`` and a
    StudyWarning say so); a Measured record that ends before ``duration``
    is refused unless it repeats. The scene's other loads (a static axial force, a drive
    torque, a motor at its voltage) act as they are.

    Creep is the load travel the thread's turning gives (signed along +x:
    -h p (phi_drive(t) - phi_drive(0)) / n, p = lead / 2 pi, h = +1 right
    hand, n the gear ratio), not the load's displacement u_load, which adds
    its place in the play and the elastic deflections that ring under
    vibration and come back. A seed **holds** iff its worst creep over the
    run and its trend stay within what is allowed: ``max_creep`` (max
    |creep(t)| over the output times) ``<= allowed_creep`` and
    ``|creep_rate| <= allowed_creep_rate`` (by default ``allowed_creep`` per
    hour, :data:`~leadscrew.studies._vibration_verdict.RATE_HORIZON`,
    whatever the run's length), not its creep at the end, which a drive
    that creeps out and comes back, or oscillates, would pass. The study's
    verdict is ``"creeps"`` if a seed that ran creeps; ``"holds"`` if every
    seed holds, the run resolves the allowed rate (its travel over the
    fitted window above twice the creep's RMS about its trend,
    ``creep_scatter``) and the thread is self-locking at rest with
    mu_static; ``"undecided"`` otherwise, the summary's ``verdict_reason``
    saying why (docs/guide/studies.md).

    With exact Coulomb friction (``friction.law = "coulomb"``) a
    self-locking thread does not creep under axial vibration alone: every
    impulse stays inside the friction cone: "holds" follows from
    self-locking at rest. The mechanism of real creep, the transverse slip
    of a 2-D friction cone, runs where the scene has
    ``loads.transverse_slip_velocity`` (docs/physics/transverse_slip.md; at
    the housing or ``where="loads.axial_force"``); the summary's ``creep_mechanism``
    says which the model gives the drive. A regularized law (``arctan_velocity``)
    slips at any load, at a rate set by its k_v: its creep is the
    regularization's, not the thread's (docs/guide/studies.md).

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict) with a torque-
            controlled drive (a drive torque or a DC motor, not
            ``loads.drive_speed``); a gear stage is taken by its ratio.
        excitation: a profile's name (:func:`leadscrew.profiles.names`), a
            :class:`~leadscrew.RandomVibration`, a ``{"type": "random", ...}``
            dict (``frequencies`` and ``psd``, or ``profile``; its ``seed``
            and ``duration`` replaced per seed), a :class:`~leadscrew.Measured`
            record or any other load of ``where``'s unit (default: the
            scene's load at ``where``).
        duration: the run's length [s], > 0 (default 5 s).
        seeds: a count n (the seeds 0 ... n-1) or a list of distinct
            integers in [0, 2^53] (default 5).
        allowed_creep: the creep allowed over the run [m], > 0 (default
            0.1 mm).
        where: the load the excitation enters: ``"loads.base_acceleration"``
            (default; m/s^2, the housing's vibration),
            ``"loads.base_angular_acceleration"`` (rad/s^2) or
            ``"loads.axial_force"`` (N).
        scatter: scene parameters drawn per seed, ``{key: (kind, a, b)}``
            with key ``"friction.mu"``, ``"backlash.axial"`` [m] or
            ``"nut.preload"`` [N] and ``("uniform", low, high)`` (0 <= low <
            high) or ``("normal", mean, std)`` (std > 0, mean + 3 std > 0;
            draws below 0 drawn again); values may be strings with units.
            Drawn from ``numpy.random.default_rng(seed)`` in sorted key
            order: the same seed gives the same draws. Default: none.
        settle_time: the start of the creep-rate fit [s], in [0, duration)
            with 3 output times after it (default: a tenth of duration).
        points: output times, evenly spaced over the run, >= 11.
        rtol, atol: integration tolerances (default simulate's: 1e-8 and
            1e-10; not with integrator ``"moreau"``).
        allowed_creep_rate: the largest |creep_rate| a seed that holds may
            have [m/s], > 0 (default ``allowed_creep`` / 3600 s: the allowed
            creep per hour of vibration, independent of the run's length).
        executor: a :class:`concurrent.futures.Executor` (default: a thread
            pool over all cores); scene and cases pickle, so process pools
            and ``dask.distributed.Client(...).get_executor()`` work too.
        progress: show a tqdm progress bar.
        **simulate_options: passed on to :func:`leadscrew.simulate`.

    Returns:
        DataFrame with one row per seed: ``seed``, one column per scattered
        key (its draw), ``creep`` [m] (at the end), ``creep_rate`` [m/s]
        (least-squares slope of the creep over t >= settle_time),
        ``max_creep`` [m] (max |creep(t)| over the run), ``creep_scatter``
        [m] (RMS of the creep about its fitted line), ``displacement``
        [m] (u_load(end) - u_load(0)), ``max_displacement`` [m] (max
        |u_load - u_load(0)|), ``input_rms`` (the realised input's
        RMS on the output times, in ``where``'s unit), ``holds`` (bool; None
        where the case raised), ``wall_time`` [s, C++], ``steps``, ``events``
        [1] (integers, pandas' Int64) and ``error`` (None, or the message of
        a case that raised: its numbers are NaN, its counts <NA>).
        ``attrs["units"]``; ``attrs["summary"]``:
        ``seeds``, ``duration``, ``settle_time``, ``allowed_creep``,
        ``seeds_note``, ``allowed_creep_rate``, ``rate_horizon`` [s],
        ``creep_mean``, ``creep_std`` (sample, ddof 1; NaN for one seed),
        ``creep_worst`` (largest magnitude, signed), the same of
        ``creep_rate``, ``max_creep_worst``, ``max_displacement_worst``,
        ``verdict``, ``verdict_reason``, ``judged_by`` (what the verdict
        judges), ``at_rest`` (the self-locking test with mu_static),
        ``creep_mechanism`` (by which mechanism the model lets this drive
        creep), ``mu`` and ``mu_static`` (the scene's; a scatter of mu
        keeps mu_static),
        ``excitation``, ``excitation_from``, ``where``, ``random``,
        ``scatter``, ``friction_law``, ``raised`` and ``raised_reasons`` (the
        seeds that raised, which decide nothing; a
        :class:`~leadscrew.StudyWarning` names them). ``attrs["series"]``:
        the output times ``t``, each seed's ``creep`` series, the realised
        input's Welch PSD (``psd_f``, ``psd``) and the ``target_psd`` at
        ``target_f`` (the profile's whole band, its breakpoints included;
        None for a load that is not random), which
        :func:`plot_holding_under_vibration` draws.

    Raises:
        ValueError: invalid scene or arguments (naming the argument, the
            value and the valid range; a measured record shorter than the
            run, not repeated; a scatter of mu above the scene's mu_static;
            the excitation and scatter checked on
            the first seed's scene, the simulate options once, before the
            cases run).
        TypeError: an unknown keyword in ``simulate_options``.

    Warns:
        ProfileWarning: a profile not verified against its source.
        StudyWarning: seeds that raised; several seeds run once (an
            excitation that is not random, no scatter).
    """


def plot_holding_under_vibration(frame: pd.DataFrame, ax: Optional[Any] = None):
    """Draw the creep against time of every seed and, beside it, the realised
    input's Welch PSD of every seed against the target PSD (log-log).

    Args:
        frame: the DataFrame :func:`holding_under_vibration` returned.
        ax: a matplotlib Axes (default: a new figure's); its place in the
            figure is split into the two panels.

    Returns:
        The two Axes (creep, PSD).
    """
    ax = axes(ax)
    spec = ax.get_subplotspec()
    figure = ax.figure
    if spec is not None:
        ax.remove()
        left, right = (figure.add_subplot(s) for s in spec.subgridspec(1, 2))
    else:  # an Axes placed by hand: the PSD in an inset
        left, right = ax, ax.inset_axes([0.6, 0.6, 0.38, 0.38])
    series, summary = frame.attrs["series"], frame.attrs.get("summary", {})
    t = np.asarray(series["t"])
    for seed, creep in zip(frame["seed"], series["creep"]):
        if creep is not None:
            left.plot(t, np.asarray(creep) * 1e6, lw=0.8, label=f"seed {seed}")
    allowed = summary.get("allowed_creep")
    if allowed is not None:
        for sign in (1, -1):
            left.axhline(sign * allowed * 1e6, color="k", ls="--", lw=0.8)
    left.set_xlabel("time [s]")
    left.set_ylabel("creep [um]")
    mechanism = str(summary.get("creep_mechanism", "?")).split(":")[0]
    left.set_title(f"verdict: {summary.get('verdict', '?')}\ncreep mechanism: {mechanism}",
                   fontsize="small")
    for seed, f, psd in zip(frame["seed"], series["psd_f"], series["psd"]):
        if f:
            right.loglog(f, psd, lw=0.6, alpha=0.6, label=f"seed {seed}")
    if series.get("target_psd"):
        f, target = np.asarray(series["target_f"]), np.asarray(series["target_psd"])
        band = target > 0  # the target is zero outside its band
        right.loglog(f[band], target[band], "k", lw=1.5, label="target")
        right.set_ylim(bottom=target[band].min() / 100.0)
    if len(frame) <= _LEGEND_SEEDS:  # (more seeds: a legend hides the panel)
        for panel in (left, right):
            if panel.get_legend_handles_labels()[0]:
                panel.legend(fontsize="small")
    elif series.get("target_psd"):
        right.legend(handles=right.get_lines()[-1:], fontsize="small")
    unit = frame.attrs.get("units", {}).get("input_rms", "")
    right.set_xlabel("frequency [Hz]")
    right.set_ylabel(f"input PSD [({unit})^2/Hz]")
    return left, right
