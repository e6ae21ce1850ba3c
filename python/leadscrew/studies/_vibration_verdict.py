"""How :func:`leadscrew.studies.holding_under_vibration` judges its seeds: a
creep rate allowed in physical terms (not per run), whether the run resolves
it, whether the thread can hold its load at rest, and by which mechanism the
model lets the drive creep.

A verdict must not depend on the run's length. A drive that slides steadily
at a small rate stays within any allowed creep over a short enough run, so
the rate is judged against :data:`RATE_HORIZON`: by default a parked drive may
creep its ``allowed_creep`` over one hour of vibration (0.1 mm/h for the
default 0.1 mm; a seat's, a window lifter's or a valve's parked position is
shaken for hours in a vehicle's life, and 0.1 mm is below what its user
notices). A run too short to tell that rate from the creep's own oscillation
(the travel the allowed rate gives over the fitted window below twice the RMS
of the creep about its fitted line) decides nothing: ``"undecided"``.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Tuple

import numpy as np

from ..scene import Scene
from ..thread import is_self_locking

__all__ = ["RATE_HORIZON", "default_allowed_rate", "static_holding", "creep_mechanism",
           "verdict"]

#: The time over which the default allowed rate may creep ``allowed_creep`` [s]: one hour.
RATE_HORIZON = 3600.0

_LAWS_WITH_STICK = ("coulomb", "stribeck", "lugre")


def default_allowed_rate(allowed_creep: float) -> float:
    """The default allowed |creep_rate| [m/s]: ``allowed_creep`` [m] over
    :data:`RATE_HORIZON` (one hour), whatever the run's length."""
    return allowed_creep / RATE_HORIZON


def _mu_static(friction: Dict[str, Any]) -> float:
    value = friction.get("mu_static")
    return float(friction["mu"] if value is None else value)


def static_holding(scene: Scene) -> Tuple[bool, str]:
    """Whether the thread's static friction holds a load at rest: the closed
    form of self-locking (mu_static' > tan(lead angle),
    :func:`leadscrew.is_self_locking`) with mu_static (mu where the law has
    none), and a line saying so.

    Returns:
        ``(holds, text)``.
    """
    friction = scene["friction"]
    mu_static = _mu_static(friction)
    thread = scene.thread
    holds = bool(is_self_locking(thread, mu_static)) and friction["law"] in _LAWS_WITH_STICK
    tan_a = math.tan(thread.lead_angle)
    if friction["law"] not in _LAWS_WITH_STICK:
        return False, (f"friction.law = {friction['law']!r} has no sticking: it slips under "
                       "any load, at a rate its regularization sets")
    state = "self-locking" if holds else "NOT self-locking"
    return holds, (f"at rest {state}: mu_static' = {thread.effective_mu(mu_static):.4g} "
                   f"{'>' if holds else '<='} tan(lead angle) = {tan_a:.4g} "
                   f"(friction.mu_static = {mu_static:.4g}, from the scene)")


def creep_mechanism(scene: Scene) -> str:
    """By which mechanism the model lets this scene's drive creep, in one line."""
    law = scene["friction"]["law"]
    if "transverse_slip_velocity" in scene["loads"]:
        return ("transverse slip (loads.transverse_slip_velocity): the thread's 2-D friction "
                "cone lets any load creep while the flank slips across "
                "(docs/physics/transverse_slip.md)")
    if law not in _LAWS_WITH_STICK:
        return (f"the {law} law's regularization: it slips under any load at a rate set by "
                "its k_v, an artefact of the law, not the thread")
    holds, _ = static_holding(scene)
    if not holds:
        return "back-driving: the thread is not self-locking at rest, any load turns it"
    return ("none under axial vibration alone: exact friction keeps every impulse inside the "
            "friction cone of a thread self-locking at rest, so 'holds' follows from "
            "self-locking; the mechanism of real creep, transverse slip, runs where the scene "
            "has loads.transverse_slip_velocity (docs/physics/transverse_slip.md)")


def creep_scatter(t: np.ndarray, creep: np.ndarray) -> float:
    """The RMS of the creep about its least-squares line [m]: the oscillation
    that hides a trend over the fitted window."""
    fit = np.polyfit(t, creep, 1) if len(t) > 1 else np.zeros(2)
    return float(np.sqrt(np.mean((creep - np.polyval(fit, t)) ** 2)))


def verdict(rows: List[Dict[str, Any]], allowed_rate: float, window: float,
            static: Tuple[bool, str]) -> Tuple[str, str]:
    """The study's verdict and its reason from the seeds that ran.

    Args:
        rows: one dict per seed that ran, with ``holds`` (bool) and
            ``creep_scatter`` [m].
        allowed_rate: the allowed |creep_rate| [m/s].
        window: the length of the rate's fitted window [s].
        static: :func:`static_holding` of the scene.

    Returns:
        ``(verdict, reason)``: ``"creeps"`` if a seed creeps; else
        ``"undecided"`` if none ran, if the run cannot resolve the allowed rate
        or if the thread does not hold at rest; else ``"holds"``.
    """
    if not rows:
        return "undecided", "no seed ran"
    if not all(row["holds"] for row in rows):
        return "creeps", "a seed's creep or fitted rate exceeds what is allowed"
    resolution = 2.0 * max(row["creep_scatter"] for row in rows)
    if allowed_rate * window <= resolution:
        return "undecided", (
            f"the run is too short to resolve the allowed rate: {allowed_rate:.4g} m/s over "
            f"the fitted {window:.4g} s is {allowed_rate * window:.4g} m, within the creep's "
            f"oscillation (2 x RMS about its trend, {resolution:.4g} m); run longer")
    if not static[0]:
        return "undecided", (f"no seed crept within this run, but the thread cannot hold a "
                             f"load at rest ({static[1]}); run longer")
    return "holds", "every seed within the allowed creep and rate"
