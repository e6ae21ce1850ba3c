"""Which model concept does a load case need? (thesis section 5.1.1, Figs. 5.1-5.3)

The same scene runs on each concept of thesis section 4.1: ``rigid`` (4.1.1),
``flexible_nut`` (4.1.2) and ``flexible`` (4.1.3). The study reports each run's
cost and how far its load position departs from the most detailed concept's:
if the rigid drive's departure is below what the design cares about, the
cheaper concept is enough.
"""

from __future__ import annotations

import functools
from typing import Any, Dict, Optional, Sequence

import numpy as np
import pandas as pd

from ..scene import SCHEMA
from ..simulation import simulate
from .._progress import shown
from ._common import (annotate, as_counts, axes, as_scene, check_count, check_positive,
                      numeric_or_nan, with_tolerances)
from ._batch import check_simulate_options
from ._sweep import run_cases

__all__ = ["CONCEPTS", "compare_concepts", "plot_compare_concepts"]

#: The concepts from the least to the most detailed.
CONCEPTS = SCHEMA["concept"].choices  # the core's: rigid, flexible_nut, flexible

UNITS = {"concept": "", "reference": "", "wall_time": "s", "steps": "1", "events": "1",
         "max_abs_diff": "m", "rms_diff": "m", "u_final": "m", "t": "s", "u_load": "m",
         "error": ""}


def _run_concept(concept: str, scene, t_end: float, t_eval: np.ndarray,
                 options: Dict[str, Any]) -> Dict[str, Any]:
    result = simulate(scene.replace(concept=concept), t_end, t_eval=t_eval, **options)
    return {"u_load": np.array(result["u_load"]), "wall_time": float(result.stats["wall_time"]),
            "steps": int(result.stats["steps"]), "events": len(result.events)}


def compare_concepts(
    scene: Any,
    concepts: Sequence[str] = CONCEPTS,
    t_end: float = 2.0,
    points: int = 2001,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    executor=None,
    progress: bool = True,
    **simulate_options: Any,
) -> pd.DataFrame:
    """Run one load case on several concepts and compare their load positions.

    Args:
        scene: a :class:`~leadscrew.Scene` (or scene dict); its ``concept``
            is replaced by each of ``concepts``.
        concepts: names from :data:`CONCEPTS`, each at most once.
        t_end: simulated time [s], > 0.
        points: number of common output times in [0, t_end], >= 2.
        rtol, atol: integration tolerances (relative [1], absolute [SI];
            default the scene's [simulation] ones, else simulate's, 1e-8 and
            1e-10; not with integrator "moreau").
        executor: a :class:`concurrent.futures.Executor` (default: a thread
            pool over all cores).
        progress: show a progress bar.
        **simulate_options: passed on to :func:`leadscrew.simulate`.

    Returns:
        DataFrame with one row per concept (in the order given): ``concept``,
        ``wall_time`` [s, inside the C++ core], ``steps`` and ``events`` [1],
        ``reference`` (the most detailed concept that ran), ``max_abs_diff``
        and ``rms_diff`` [m] (of u_load against the reference on the common
        times; 0 for the reference), ``u_final`` [m], ``error`` (None, or why
        the run failed: then the numbers are NaN), and the series ``t`` [s] and
        ``u_load`` [m] as arrays (None for a failed run). ``attrs["summary"]``:
        ``raised`` [1] and ``raised_reasons`` (the runs that raised: their
        count, and their exception types with the first message, or
        ``"none"``; a :class:`~leadscrew.StudyWarning` names them).

    Raises:
        ValueError: invalid scene, concept or argument (also a simulate option
            that every concept refuses, checked before the runs; one that
            only some refuse fails their rows).
        TypeError: an unknown keyword in ``simulate_options``.
    """
    progress = shown(progress)
    scene = as_scene(scene)
    concepts = list(concepts)
    if not concepts:
        raise ValueError("concepts = [] is invalid: must name at least one of "
                         + ", ".join(CONCEPTS))
    for name in concepts:
        if name not in CONCEPTS:
            raise ValueError(f"concepts entry {name!r} is invalid: must be one of "
                             + ", ".join(CONCEPTS))
    if len(set(concepts)) != len(concepts):
        raise ValueError(f"concepts = {concepts!r} is invalid: a concept appears twice")
    t_end = check_positive("t_end", t_end, unit="s")
    points = check_count("points", points, 2)
    t_eval = np.linspace(0.0, t_end, points)
    options = with_tolerances(simulate_options, rtol, atol)
    # Options that no concept takes are refused once; those that only some
    # refuse (max_order: the rigid concept's default method is one-step)
    # fail those concepts' rows.
    checked, refusals = 0, []
    for name in concepts:
        try:
            concept_scene = scene.replace(concept=name)
            concept_scene.model()
        except ValueError:  # that concept's model is invalid: its row says why
            continue
        checked += 1
        try:
            check_simulate_options(concept_scene, options, t_end)
        except ValueError as error:
            refusals.append(error)
    if refusals and len(refusals) == checked:
        raise refusals[0]
    function = functools.partial(_run_concept, scene=scene, t_end=t_end, t_eval=t_eval,
                                 options=options)
    outcomes = run_cases(function, concepts, executor=executor, progress=progress,
                         description="compare_concepts")
    succeeded = [(CONCEPTS.index(c), c, o.value) for c, o in zip(concepts, outcomes) if o.ok]
    reference_name, reference = (max(succeeded, key=lambda s: s[0])[1:] if succeeded
                                 else (None, None))
    rows = []
    for concept, outcome in zip(concepts, outcomes):
        value = outcome.value or {}
        u = value.get("u_load")
        difference = None if u is None or reference is None else u - reference["u_load"]
        rows.append({
            "concept": concept,
            "wall_time": numeric_or_nan(value.get("wall_time")),
            "steps": numeric_or_nan(value.get("steps")),
            "events": numeric_or_nan(value.get("events")),
            "reference": reference_name,
            "max_abs_diff": numeric_or_nan(None if difference is None
                                           else np.max(np.abs(difference))),
            "rms_diff": numeric_or_nan(None if difference is None
                                       else np.sqrt(np.mean(difference ** 2))),
            "u_final": numeric_or_nan(None if u is None else u[-1]),
            "error": outcome.error,
            "t": None if u is None else t_eval,
            "u_load": u,
        })
    return annotate(as_counts(pd.DataFrame(rows)), UNITS, study="compare_concepts")


def plot_compare_concepts(frame: pd.DataFrame, ax: Optional[Any] = None):
    """Draw each concept's load position [mm] over time (Figs. 5.1-5.3).

    Args:
        frame: the DataFrame :func:`compare_concepts` returned.
        ax: a matplotlib Axes (default: a new figure's).

    Returns:
        The Axes.
    """
    ax = axes(ax)
    for row in frame.itertuples():
        if row.u_load is None:
            continue
        label = row.concept if row.concept == row.reference else \
            f"{row.concept} (max diff {row.max_abs_diff * 1e3:.3g} mm)"
        ax.plot(row.t, np.asarray(row.u_load) * 1e3, label=label)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("load position u [mm]")
    ax.legend(loc="best")
    return ax
