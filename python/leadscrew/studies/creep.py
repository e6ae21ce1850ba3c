"""Creep under an alternating axial force against frequency and backlash (thesis Fig. 5.5).

Each case runs the scene under ``amplitude sin(2 pi f t)`` (no static
preload, the nut starting centred in the backlash, the scene's constant drive
torque acting) for whole cycles and measures the creep per cycle and the
largest displacement (:func:`leadscrew.studies.holding.cycle_response`). The
creep comes from the rotating part turning under the drive torque while the
nut flies across the backlash: the longer the flight (more backlash, lower
frequency) the more it turns.
"""

from __future__ import annotations

import functools
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
import pandas as pd

from .._progress import shown
from ._common import (annotate, as_counts, as_scene, axes, check_grid, numeric_or_nan,
                      with_tolerances)
from ._batch import check_simulate_options
from ._sweep import run_cases
from ._holding_runs import (_alternating_excitation, _constant_torque, alternating_scene,
                           check_cycles, cycle_response)

__all__ = ["creep_vs_frequency", "creep_vs_backlash", "creep_map", "plot_creep",
           "plot_creep_map"]

UNITS = {"frequency": "Hz", "backlash": "m", "creep_per_cycle": "m", "creep_rate": "m/s",
         "max_displacement": "m", "separations": "1", "flight_fraction": "1",
         "wall_time": "s", "steps": "1", "error": ""}

_MEASURES = ("creep_per_cycle", "max_displacement", "separations", "flight_fraction",
             "wall_time", "steps")


def _creep_case(case: Tuple[float, float], scene, amplitude: float, cycles: int,
                settle_cycles: int, points_per_cycle: int,
                options: Dict[str, Any]) -> Dict[str, Any]:
    frequency, backlash = case
    excited = alternating_scene(scene, amplitude, frequency, backlash=backlash)
    return cycle_response(excited, frequency, cycles, settle_cycles, points_per_cycle, **options)


def _sweep(scene: Any, pairs: List[Tuple[float, float]], amplitude: float,
           excitation_from: str, cycles: int, settle_cycles: int, points_per_cycle: int,
           rtol: Optional[float], atol: Optional[float], executor, progress: bool,
           description: str, options: Dict[str, Any]) -> pd.DataFrame:
    cycles, settle_cycles, points_per_cycle = check_cycles(cycles, settle_cycles,
                                                           points_per_cycle)
    _constant_torque(scene)
    options = with_tolerances(options, rtol, atol)
    if pairs:  # every case has the first one's friction law and contact
        check_simulate_options(alternating_scene(scene, amplitude, pairs[0][0],
                                                 backlash=pairs[0][1]), options,
                               cycles / max(frequency for frequency, _ in pairs))
    function = functools.partial(_creep_case, scene=scene, amplitude=amplitude, cycles=cycles,
                                 settle_cycles=settle_cycles, points_per_cycle=points_per_cycle,
                                 options=options)
    outcomes = run_cases(function, pairs, executor=executor, progress=progress,
                         description=description)
    rows = []
    for (frequency, backlash), outcome in zip(pairs, outcomes):
        value = outcome.value or {}
        row = {"frequency": frequency, "backlash": backlash}
        for name in _MEASURES:
            row[name] = numeric_or_nan(value.get(name))
        row["creep_rate"] = row["creep_per_cycle"] * frequency
        row["error"] = outcome.error
        rows.append(row)
    columns = ["frequency", "backlash", "creep_per_cycle", "creep_rate", "max_displacement",
               "separations", "flight_fraction", "wall_time", "steps", "error"]
    return annotate(as_counts(pd.DataFrame(rows, columns=columns)), UNITS, study=description,
                    summary_units={"amplitude": "N", "cycles": "1", "settle_cycles": "1"},
                    amplitude=amplitude, cycles=cycles, settle_cycles=settle_cycles,
                    excitation_from=excitation_from)


def _scene_backlash(scene) -> float:
    if "backlash" not in scene:
        raise ValueError("scene.backlash is missing: creep needs a backlash to fly across; "
                         "add a backlash section or use creep_vs_backlash")
    return float(scene["backlash"]["axial"])


_EXCITATION = """

    The excitation follows the rule of every study (:mod:`leadscrew.studies`):
    an argument given overrides, the scene's own load is the default: here
    the amplitude (and frequency) of the scene's ``loads.axial_force`` if it
    is a sine (not its phase and offset: the force is purely alternating),
    else 30 N (and 20 Hz). ``attrs["summary"]["excitation_from"]`` says
    which: ``"arguments"``, ``"scene"`` or ``"defaults"``.

    Args:"""

_COMMON_ARGS = """
        amplitude: amplitude of the alternating axial force [N], > 0
            (default: the scene's sine's, else 30 N).
        cycles: cycles per run, > settle_cycles.
        settle_cycles: cycles before the creep fit, >= 0.
        points_per_cycle: output points per cycle, >= 4.
        rtol, atol: integration tolerances (relative [1], absolute [SI];
            default the scene's [simulation] ones, else simulate's, 1e-8 and
            1e-10; not with integrator "moreau").
        executor: a :class:`concurrent.futures.Executor` (default: a thread
            pool over all cores). Scene and cases pickle, so process pools and
            ``dask.distributed.Client(...).get_executor()`` work too.
        progress: show a tqdm progress bar.
        **simulate_options: passed on to :func:`leadscrew.simulate`.

    Returns:
        DataFrame with one row per case: ``frequency`` [Hz], ``backlash``
        [m], ``creep_per_cycle`` [m] (signed along +x), ``creep_rate`` [m/s],
        ``max_displacement`` [m], ``separations`` [1], ``flight_fraction``
        [1], ``wall_time`` [s, C++], ``steps`` [1] and ``error`` (None, or
        the message of a failed case, whose numbers are NaN).
        ``attrs["units"]`` maps columns to units; ``attrs["summary"]``:
        ``amplitude`` [N], ``cycles``, ``settle_cycles`` [1],
        ``excitation_from``, ``raised`` [1] and ``raised_reasons`` (the
        cases that raised: their count, and their exception types with the
        first message, or ``"none"``; a :class:`~leadscrew.StudyWarning`
        names them). Every run starts at rest with its springs relaxed, the
        nut centred (:func:`~leadscrew.studies.alternating_scene`).

    Raises:
        ValueError: invalid scene (no constant drive torque) or arguments (the
            simulate options too: checked once, before the cases run).
        TypeError: an unknown keyword in ``simulate_options``."""


def creep_vs_frequency(scene: Any, frequencies: Sequence[float],
                       amplitude: Optional[float] = None, cycles: int = 6,
                       settle_cycles: int = 1, points_per_cycle: int = 100,
                       rtol: Optional[float] = None, atol: Optional[float] = None,
                       executor=None, progress: bool = True,
                       **simulate_options: Any) -> pd.DataFrame:
    scene = as_scene(scene)
    progress = shown(progress)
    backlash = _scene_backlash(scene)
    pairs = [(float(f), backlash) for f in check_grid("frequencies", frequencies, unit="Hz")]
    # The frequencies are the sweep's: only the amplitude may come from the scene.
    amplitude, _, excitation_from = _alternating_excitation(scene, amplitude, pairs[0][0])
    return _sweep(scene, pairs, amplitude, excitation_from, cycles, settle_cycles,
                  points_per_cycle, rtol, atol, executor, progress, "creep_vs_frequency",
                  simulate_options)


creep_vs_frequency.__doc__ = """Creep per cycle and largest displacement against the
    excitation frequency (thesis Fig. 5.5a), at the scene's backlash.""" + _EXCITATION + """
        scene: a :class:`~leadscrew.Scene` (or scene dict) with a backlash
            section and a constant drive torque.
        frequencies: excitation frequencies [Hz], > 0.""" + _COMMON_ARGS


def creep_vs_backlash(scene: Any, backlash: Sequence[float], frequency: Optional[float] = None,
                      amplitude: Optional[float] = None, cycles: int = 6,
                      settle_cycles: int = 1, points_per_cycle: int = 100,
                      rtol: Optional[float] = None, atol: Optional[float] = None,
                      executor=None, progress: bool = True,
                      **simulate_options: Any) -> pd.DataFrame:
    scene = as_scene(scene)
    progress = shown(progress)
    amplitude, frequency, excitation_from = _alternating_excitation(scene, amplitude, frequency)
    pairs = [(frequency, float(c)) for c in check_grid("backlash", backlash, unit="m")]
    return _sweep(scene, pairs, amplitude, excitation_from, cycles, settle_cycles,
                  points_per_cycle, rtol, atol, executor, progress, "creep_vs_backlash",
                  simulate_options)


creep_vs_backlash.__doc__ = """Creep per cycle and largest displacement against the
    axial backlash (thesis Fig. 5.5b), at one frequency.""" + _EXCITATION + """
        scene: a :class:`~leadscrew.Scene` (or scene dict) with a constant
            drive torque; its backlash section (contact law, restitution,
            ...) is kept, or an exact one added, with ``axial`` replaced.
        backlash: total axial clearances [m], > 0.
        frequency: excitation frequency [Hz], > 0 (default: the scene's
            sine's, else 20 Hz).""" + _COMMON_ARGS


def creep_map(scene: Any, frequencies: Sequence[float], backlash: Sequence[float],
              amplitude: Optional[float] = None, cycles: int = 6, settle_cycles: int = 1,
              points_per_cycle: int = 100, rtol: Optional[float] = None,
              atol: Optional[float] = None, executor=None, progress: bool = True,
              **simulate_options: Any) -> pd.DataFrame:
    scene = as_scene(scene)
    progress = shown(progress)
    frequencies = check_grid("frequencies", frequencies, unit="Hz")
    clearances = check_grid("backlash", backlash, unit="m")
    pairs = [(float(f), float(c)) for f in frequencies for c in clearances]
    amplitude, _, excitation_from = _alternating_excitation(scene, amplitude, pairs[0][0])
    return _sweep(scene, pairs, amplitude, excitation_from, cycles, settle_cycles,
                  points_per_cycle, rtol, atol, executor, progress, "creep_map",
                  simulate_options)


creep_map.__doc__ = """Creep over every pair of frequency and backlash (Fig. 5.5,
    both axes).""" + _EXCITATION + """
        scene: a :class:`~leadscrew.Scene` (or scene dict) with a constant
            drive torque (its backlash section kept, ``axial`` replaced).
        frequencies: excitation frequencies [Hz], > 0.
        backlash: total axial clearances [m], > 0. Rows run over the
            clearances for the first frequency, then the second, ...""" + _COMMON_ARGS


def _quantity_label(quantity: str) -> str:
    """The axis label of a drawable creep measure (drawn in um or um/s).

    Raises:
        ValueError: ``quantity`` is not one of the drawable measures.
    """
    if quantity not in ("creep_per_cycle", "creep_rate", "max_displacement"):
        raise ValueError(f"quantity = {quantity!r} is invalid: must be creep_per_cycle, "
                         "creep_rate or max_displacement")
    unit = "um/s" if quantity == "creep_rate" else "um"
    return f"|{quantity.replace('_', ' ')}| [{unit}]"


def plot_creep(frame: pd.DataFrame, quantity: str = "creep_per_cycle", ax: Optional[Any] = None,
               x: Optional[str] = None):
    """Draw |creep per cycle| (or another measure) against the swept
    parameter, frequency or backlash (Fig. 5.5a or b).

    Args:
        frame: the DataFrame of :func:`creep_vs_frequency` or :func:`creep_vs_backlash`.
        quantity: the column to draw: ``creep_per_cycle`` (drawn in magnitude),
            ``creep_rate`` or ``max_displacement``.
        ax: a matplotlib Axes (default: a new figure's).
        x: the swept parameter, ``"frequency"`` or ``"backlash"`` (default:
            the one that varies in the frame; give it for a sweep of one
            value).

    Returns:
        The Axes.

    Raises:
        ValueError: without ``x``, neither or both parameters vary; an
            unknown ``x`` or quantity.
    """
    label = _quantity_label(quantity)
    if x is None:
        varying = [c for c in ("frequency", "backlash") if frame[c].nunique() > 1]
        if len(varying) != 1:
            raise ValueError("frame is invalid: exactly one of frequency and backlash must "
                             "vary (use plot_creep_map for a map, or give x)")
        x = varying[0]
    elif x not in ("frequency", "backlash"):
        raise ValueError(f"x = {x!r} is invalid: must be 'frequency' or 'backlash'")
    ax = axes(ax)
    scale = 1e3 if x == "backlash" else 1.0
    ax.plot(frame[x] * scale, np.abs(frame[quantity]) * 1e6, "o-")
    ax.set_xlabel("backlash [mm]" if x == "backlash" else "frequency [Hz]")
    ax.set_ylabel(label)
    return ax


def plot_creep_map(frame: pd.DataFrame, quantity: str = "creep_per_cycle",
                   ax: Optional[Any] = None):
    """Draw |quantity| over frequency and backlash as a colour map.

    Args:
        frame: the DataFrame :func:`creep_map` returned.
        quantity: ``creep_per_cycle``, ``creep_rate`` or ``max_displacement``.
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes.

    Raises:
        ValueError: an unknown quantity.
    """
    label = _quantity_label(quantity)
    grid = frame.pivot(index="backlash", columns="frequency", values=quantity).abs()
    ax = axes(ax)
    mesh = ax.pcolormesh(grid.columns.to_numpy(), grid.index.to_numpy() * 1e3,
                         grid.to_numpy() * 1e6, shading="nearest")
    ax.figure.colorbar(mesh, ax=ax, label=label)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("backlash [mm]")
    return ax
