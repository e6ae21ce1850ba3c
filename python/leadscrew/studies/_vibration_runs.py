"""What :func:`leadscrew.studies.holding_under_vibration` runs: its excitation
per seed, its parameter scatter, and one seed's run and measures.

The excitation is any load a scene takes at the study's entry point
(``where``, default ``loads.base_acceleration``): a profile's name, a
:class:`~leadscrew.RandomVibration`, a ``{type = "random", ...}`` dict, a
:class:`~leadscrew.Measured` record or any other load. A random one is
realised once per seed (``seed`` replaced, its ``duration``, the period of
the realisation, set to the run's); any other is the same in every seed.

The scatter draws scene parameters per seed from
``numpy.random.default_rng(seed)``, one number per key in sorted key order
(:func:`draw_scatter`): the same seed gives the same draws, whatever the
order of the dict.
"""

from __future__ import annotations

import math
import numbers
import re
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from .. import profiles
from .._hints import did_you_mean
from ..excitation_sampled import RandomVibration
from ..scene import Scene
from ..scene_loads import _make_excitation
from ..simulation import simulate
from ._common import gear_ratio, in_unit
from ._vibration_verdict import creep_scatter

__all__ = ["WHERE_UNITS", "SCATTER_KEYS", "check_where", "excitation_template", "realised",
           "check_scatter", "draw_scatter", "check_draws", "check_record_length", "varied_scene", "vibration_run", "thread_travel",
           "target_psd", "is_random", "describe"]

#: The loads the excitation may enter, with their units.
WHERE_UNITS = {"loads.base_acceleration": "m/s^2",
               "loads.base_angular_acceleration": "rad/s^2",
               "loads.axial_force": "N"}

#: The scene fields the scatter may draw, with their units; each takes values
#: >= 0 (a normal draw below 0 is drawn again: a normal truncated at 0).
SCATTER_KEYS = {"friction.mu": "1", "backlash.axial": "m", "nut.preload": "N"}

_DISTRIBUTIONS = ("uniform", "normal")

# What a constant load written as a string starts with (a number: "30 m/s^2",
# "-1e3 N", ".5 g"); any other string names a profile.
_NUMBER_FIRST = re.compile(r"\s*[-+]?(\d|\.\d|inf|nan)", re.IGNORECASE)

# Draws of a truncated normal before giving up (a mean many deviations below 0).
_MAX_REDRAWS = 1000


def check_where(where: Any) -> str:
    """The load the excitation enters, checked.

    Raises:
        ValueError: naming ``where``, its value and the loads it may name.
    """
    if not isinstance(where, str) or where not in WHERE_UNITS:
        raise ValueError(f"where = {where!r} is invalid: must be one of "
                         f"{', '.join(map(repr, WHERE_UNITS))}{did_you_mean(where, WHERE_UNITS)}")
    return where


def excitation_template(scene: Scene, excitation: Any, where: str) -> Tuple[Any, str]:
    """The excitation of every seed before its seed and duration are set.

    Args:
        scene: the study's scene (its load at ``where`` is the default).
        excitation: None (the scene's load), a profile's name, a
            RandomVibration, a Measured record or any load the scene takes
            at ``where``.
        where: the load it enters (:func:`check_where`).

    Returns:
        ``(template, excitation_from)``: the load (a profile's name as a
        ``{"type": "random", "profile": ...}`` dict) and ``"arguments"`` or
        ``"scene"``.

    Raises:
        ValueError: no excitation given and none in the scene at ``where``.
    """
    key = where.split(".", 1)[1]
    if excitation is None:
        if key not in scene["loads"]:
            raise ValueError(f"excitation = None is invalid: the scene has no {where}; give a "
                             f"profile's name ({', '.join(map(repr, profiles.names()))}), a "
                             "RandomVibration, a Measured record or a load dict")
        template, origin = scene["loads"][key], "scene"
    else:
        template, origin = excitation, "arguments"
    if isinstance(template, str) and template in profiles.names():
        template = {"type": "random", "profile": template}
    elif isinstance(template, str) and not _NUMBER_FIRST.match(template):
        # (a name, not a number with a unit: the unit parser's message would
        # not say that it was taken for a profile's name)
        raise ValueError(f"excitation = {template!r} is invalid: no vibration profile has that "
                         f"name{did_you_mean(template, profiles.names())}; the profiles are "
                         f"{', '.join(map(repr, profiles.names()))} (leadscrew.profiles.names(), "
                         f"leadscrew list); a constant load is a number with a unit "
                         f"({WHERE_UNITS[where]})")
    return template, origin


def describe(template: Any, validated: Any) -> str:
    """A one-line description of the excitation: a profile's name, a random
    load's band (from ``validated``, the scene's SI form of it), or the
    load's type."""
    if isinstance(template, dict) and "profile" in template:
        return f"profile {template['profile']}"
    if isinstance(validated, dict):
        if validated.get("type") == "measured":
            times = validated["times"]
            return (f"measured record, {len(times)} samples over {times[0]:g}-{times[-1]:g} s"
                    + (", repeated" if validated.get("repeat") else ""))
        if validated.get("type") == "random":
            band = validated["frequencies"]
            return f"random, {len(band)} breakpoints {band[0]:g}-{band[-1]:g} Hz"
        return str(validated.get("type"))
    return repr(validated) if isinstance(validated, numbers.Real) else type(validated).__name__


def realised(template: Any, seed: int, duration: float) -> Any:
    """The excitation of one seed: a random one with this seed and a period
    of ``duration`` [s]; any other as it is."""
    if isinstance(template, RandomVibration):
        return template.replace(seed=seed, duration=duration)
    if isinstance(template, dict) and template.get("type") == "random":
        return {**template, "seed": seed, "duration": duration}
    return template


def is_random(template: Any) -> bool:
    """Whether the excitation changes with the seed."""
    return isinstance(template, RandomVibration) or (
        isinstance(template, dict) and template.get("type") == "random")


def _distribution(key: str, spec: Any) -> Tuple[str, float, float]:
    """One scatter entry, checked: (kind, a, b) in SI."""
    path = f"scatter[{key!r}]"
    form = "('uniform', low, high) with 0 <= low < high, or ('normal', mean, std) with std > 0"
    if isinstance(spec, dict) or isinstance(spec, str) or not hasattr(spec, "__len__") \
            or len(spec) != 3:
        raise ValueError(f"{path} = {spec!r} is invalid: must be {form}")
    kind, a, b = spec
    if kind not in _DISTRIBUTIONS:
        raise ValueError(f"{path}[0] = {kind!r} is invalid: must be 'uniform' or 'normal'")
    unit = SCATTER_KEYS[key]
    values = []
    for index, value in ((1, a), (2, b)):
        value = in_unit(f"{path}[{index}]", value, None if unit == "1" else unit)
        if isinstance(value, bool) or not isinstance(value, numbers.Real) \
                or not math.isfinite(value):
            raise ValueError(f"{path}[{index}] = {value!r} is invalid: must be a finite number"
                             + ("" if unit == "1" else f" [{unit}]"))
        values.append(float(value))
    a, b = values
    if kind == "uniform" and not 0.0 <= a < b:
        raise ValueError(f"{path} = {spec!r} is invalid: must be {form}")
    if kind == "normal" and not (b > 0.0 and a + 3.0 * b > 0.0):
        raise ValueError(f"{path} = {spec!r} is invalid: must be {form} and mean + 3 std > 0 "
                         "(the draws are truncated at 0)")
    return kind, a, b


def check_scatter(scatter: Any) -> Dict[str, Tuple[str, float, float]]:
    """The scatter argument, checked: ``{key: (kind, a, b)}`` in SI, keys sorted.

    Raises:
        ValueError: not a dict, a key not in :data:`SCATTER_KEYS`, or an entry
            that is not ``("uniform", low, high)`` (0 <= low < high) or
            ``("normal", mean, std)`` (std > 0), naming the entry and its value.
    """
    if scatter is None:
        return {}
    if not isinstance(scatter, dict):
        raise ValueError(f"scatter = {scatter!r} is invalid: must be a dict {{key: (kind, a, "
                         f"b)}} with keys in {', '.join(SCATTER_KEYS)}")
    for key in scatter:
        if not isinstance(key, str) or key not in SCATTER_KEYS:
            raise ValueError(f"scatter key {key!r} is invalid: must be one of "
                             f"{', '.join(map(repr, SCATTER_KEYS))}"
                             f"{did_you_mean(key, SCATTER_KEYS)}")
    return {key: _distribution(key, scatter[key]) for key in sorted(scatter)}


def draw_scatter(scatter: Dict[str, Tuple[str, float, float]], seed: int) -> Dict[str, float]:
    """One seed's draw of every scattered parameter: from
    ``numpy.random.default_rng(seed)``, in sorted key order; a normal's draw
    below 0 drawn again (truncated at 0).

    Raises:
        ValueError: a normal that gave no draw >= 0 in 1000 tries.
    """
    rng = np.random.default_rng(seed)
    draws = {}
    for key in sorted(scatter):
        kind, a, b = scatter[key]
        if kind == "uniform":
            draws[key] = float(rng.uniform(a, b))
            continue
        for _ in range(_MAX_REDRAWS):
            value = float(rng.normal(a, b))
            if value >= 0.0:
                break
        else:
            raise ValueError(f"scatter[{key!r}] = {scatter[key]!r} is invalid: no draw >= 0 "
                             f"in {_MAX_REDRAWS} tries")
        draws[key] = value
    return draws


def check_draws(scene: Scene, seeds: List[int], draws: List[Dict[str, float]]) -> None:
    """Refuse a scatter of ``friction.mu`` that draws above the scene's
    ``friction.mu_static``: the scatter keeps mu_static, which comes from the
    scene (a scattered kinetic coefficient above its static one is no
    friction law).

    Raises:
        ValueError: naming the seed, its draw, the scene's mu_static and the
            remedies.
    """
    mu_static = scene["friction"].get("mu_static")
    if mu_static is None:
        return
    for seed, drawn in zip(seeds, draws):
        mu = drawn.get("friction.mu")
        if mu is not None and mu > mu_static:
            raise ValueError(
                f"scatter['friction.mu'] drew mu = {mu:.4g} (seed {seed}) above friction.mu_static "
                f"= {mu_static:.4g}, which comes from the scene: the scatter draws mu only and "
                "keeps the scene's mu_static; keep the range below it, or set the scene's "
                "friction.mu_static (above the range, or None: equal to mu)")


def check_record_length(validated: Any, where: str, duration: float) -> None:
    """Refuse a measured record (not repeated) that ends before the run: the
    load would be held at its last value, silently.

    Args:
        validated: the scene's SI form of the load at ``where``.
        where: the load's key path.
        duration: the run's length [s].

    Raises:
        ValueError: naming the record's length, the duration and the remedies.
    """
    if not isinstance(validated, dict) or validated.get("type") != "measured" \
            or validated.get("repeat"):
        return
    end = float(validated["times"][-1])
    if end < duration:
        raise ValueError(
            f"excitation at {where} is invalid for duration = {duration:.4g} s: the measured "
            f"record ends at {end:.4g} s, and after it the load would be held at its last "
            f"value; give a duration <= {end:.4g} s, or repeat=True (Measured(..., "
            "repeat=True), Measured.from_file(..., repeat=True)) to continue it periodically")


def varied_scene(scene: Scene, where: str, template: Any, seed: int, duration: float,
                 draws: Dict[str, float]) -> Scene:
    """The scene of one seed: its excitation at ``where`` and its drawn
    parameters, started at rest with its springs relaxed.

    Raises:
        ValueError: as :meth:`Scene.replace`, naming the field (a scattered
            backlash on a scene without a backlash section: ``backlash``).
    """
    changes: Dict[str, Dict[str, Any]] = {
        "loads": {where.split(".", 1)[1]: realised(template, seed, duration)},
        "initial": {"rotor_speed": 0.0, "state": "relaxed"}}
    for key, value in draws.items():
        section, field = key.split(".")
        if section not in scene:
            raise ValueError(f"scatter key {key!r} is invalid for this scene: it has no "
                             f"{section} section")
        changes.setdefault(section, {})[field] = value
    return scene.replace(**changes)


def thread_travel(scene: Scene, phi_drive: np.ndarray) -> np.ndarray:
    """The load travel the thread's turning gives since t = 0 [m], signed
    along +x: -h p (phi_drive - phi_drive(0)) / n (p = lead / 2 pi, h = +1
    right hand, n the gear ratio), as the other creep studies measure it."""
    thread = scene.thread
    turn = (phi_drive - phi_drive[0]) / gear_ratio(scene)
    return -thread.hand_sign * thread.lead_per_radian * turn


def slope(t: np.ndarray, y: np.ndarray) -> float:
    """Least-squares slope of y over t (written out: equal values give exactly 0)."""
    dt = t - t.mean()
    return float(np.dot(dt, y - y.mean()) / np.dot(dt, dt))


# The realised input's Welch PSD: at least this many samples per period of
# the highest frequency, and at most this many frequencies kept for the figure.
_SAMPLES_PER_PERIOD, _PSD_POINTS = 4.0, 300


def input_psd(load: Any, duration: float, f_max: float) -> Tuple[List[float], List[float]]:
    """The Welch PSD of a load's realised values (Hann, 8 segments, half
    overlapping), on at most 300 log-spaced lines: (frequencies [Hz], PSD
    [unit^2/Hz])."""
    from scipy import signal

    rate = _SAMPLES_PER_PERIOD * f_max
    count = max(64, int(rate * duration))
    t = np.arange(count) / rate
    values = np.asarray(load(t), dtype=float) if callable(load) else np.full(count, float(load))
    f, p = signal.welch(values, fs=rate, nperseg=max(16, count // 4))
    keep = np.unique(np.geomspace(1, len(f) - 1, _PSD_POINTS).astype(int))
    return f[keep].tolist(), p[keep].tolist()


def _band_top(load: Any, points: int, duration: float) -> float:
    """The highest frequency of a load [Hz]: a random one's last breakpoint,
    else the output's Nyquist frequency."""
    if isinstance(load, RandomVibration):
        return float(load.frequencies[-1])
    return 0.5 * (points - 1) / duration


def vibration_run(scene: Scene, where: str, duration: float, settle_time: float, points: int,
                  **options: Any) -> Dict[str, Any]:
    """Run one seed's scene and measure its creep.

    Returns:
        dict: ``creep`` [m] (the thread's travel at the end,
        :func:`thread_travel`), ``creep_rate`` [m/s] (its least-squares
        slope over t >= settle_time), ``max_creep`` [m] (max |creep| over
        the run), ``creep_scatter`` [m] (the RMS of the creep about its
        fitted line over t >= settle_time), ``displacement`` [m] (u_load(end) -
        u_load(0)), ``max_displacement`` [m] (max |u_load - u_load(0)|),
        ``input_rms`` (the realised input's RMS on the output times, in its
        unit), ``wall_time`` [s], ``steps``, ``events``, and the series
        ``t``, ``creep_series``, ``psd_f``, ``psd`` for the figure.
    """
    t_eval = np.linspace(0.0, duration, points)
    result = simulate(scene, duration, t_eval=t_eval, **options)
    creep = thread_travel(scene, result["phi_drive"])
    u = result["u_load"] - result["u_load"][0]
    judged = t_eval >= settle_time
    load = _make_excitation(scene["loads"][where.split(".", 1)[1]])
    values = np.asarray(load(t_eval), dtype=float) if callable(load) else np.full(points, load)
    f, p = input_psd(load, duration, _band_top(load, points, duration))
    return {"creep": float(creep[-1]), "creep_rate": slope(t_eval[judged], creep[judged]),
            "max_creep": float(np.max(np.abs(creep))),
            "creep_scatter": creep_scatter(t_eval[judged], creep[judged]),
            "displacement": float(u[-1]), "max_displacement": float(np.max(np.abs(u))),
            "input_rms": float(np.sqrt(np.mean(values ** 2))),
            "wall_time": float(result.stats["wall_time"]), "steps": int(result.stats["steps"]),
            "events": len(result.events), "creep_series": creep.tolist(),
            "psd_f": f, "psd": p}


def target_psd(scene: Scene, where: str) -> Tuple[Optional[List[float]], Optional[List[float]]]:
    """The target PSD of the scene's random load at ``where`` over its whole
    band: ``(frequencies [Hz], psd)`` on 300 log-spaced lines from its first
    to its last breakpoint and at every breakpoint (the realised input's Welch
    grid starts at its resolution, above the band's start in a short run);
    ``(None, None)`` for any other load."""
    load = _make_excitation(scene["loads"][where.split(".", 1)[1]])
    if not isinstance(load, RandomVibration):
        return None, None
    band = np.asarray(load.frequencies, dtype=float)
    f = np.unique(np.concatenate([np.geomspace(band[0], band[-1], _PSD_POINTS), band]))
    return f.tolist(), load.psd_at(f).tolist()
