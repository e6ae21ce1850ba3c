"""Random drive trains for the fuzz test of :func:`leadscrew.simulate`
(``tests/test_fuzz_train.py``, and ``tests/fuzz_scenes.py --generator
train``): issue 19's elements drawn freely against one another.

The generator of :mod:`helpers.scene_fuzz` draws the drive train only where
the scene takes it (a stage only on the rigid drive without play, stops and
a preload only where they run), so that the share of answered cases stays
high and its seed-pinned cases stay as they were. This one draws every
element independently of the others and of the integrator:

- a concept, a thread, a friction law (exact Coulomb in most cases, with or
  without ``mu_static``), play (none, exact, bistop, cubic), bodies and loads
  as :mod:`helpers.scene_fuzz` draws them;
- the rotor's drive: a torque, a prescribed speed, or a DC motor (with or
  without inductance, current limit and its own friction torque);
- a gear stage: none, ideal, lossy or worm (with or without ``mu_static``);
- end stops: none, exact (restitution) or penalty, one side or both;
- a preloaded nut (with ``preload_stiffness`` on the flexible concepts);
- the integrator: the scene's default, ``event_driven`` or ``moreau`` (with
  its ``dt``).

So a case is often a combination the core refuses. The property is the fuzz
test's: exactly one of a result that passes its checks, a ``ValueError``
naming a key or option the case set (a refused combination names one of
its keys), a ``SimulationError`` or a ``JammingError``; never another
exception, a crash, a hang or a non-finite number. The cases have no
hostile values (:mod:`helpers.scene_fuzz` draws those) but one: a preloaded
nut with penalty play on a flexible concept left without ``preload_stiffness``,
which that concept requires there (marked hostile: the refusal answers an
input that breaks a documented rule, not a missing combination).

A case has the layout of :func:`helpers.scene_fuzz.make_case`'s (``seed``,
``scene``, ``options``, ``hostile`` (empty), ``tags``: concept, law,
contact, integrator, motor, gear, stops, preload), so that
:func:`helpers.scene_fuzz.run_case` and ``run_isolated`` run it.
"""

from __future__ import annotations

from typing import Any, Dict, List

from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st

from helpers import scene_fuzz as base

__all__ = ["make_train_case", "generate_train", "TRAIN_SEED"]

TRAIN_SEED = 20261127

# Each run is short and bounded (a Moreau-Jean run by its steps, t_end / dt).
MAX_MOREAU_STEPS = 20_000


def _motor(r, scene: dict, t_end: float) -> str:
    """The rotor's drive: keeps the drawn torque or speed, or puts a DC motor
    in their place. Returns its tag."""
    loads = scene["loads"]
    if "drive_speed" in loads:
        return "speed"
    if not r.chance(0.5):
        return "torque"
    loads.pop("drive_torque", None)
    motor = base.dc_motor(r)
    if r.chance(0.4):
        motor["friction_torque"] = r.log_uniform(1e-5, 0.05)
    scene["motor"] = motor
    return "dc+friction" if "friction_torque" in motor else "dc"


def _gear(r, scene: dict) -> str:
    kind = r.pick(("none", "none", "ideal", "lossy", "worm"))
    if kind == "none":
        return kind
    ratio = r.signed(r.log_uniform(0.2, 60.0))
    if kind == "ideal":
        gear = {"ratio": ratio} if r.chance(0.5) else {"type": "ideal", "ratio": ratio}
    elif kind == "lossy":
        gear = {"type": "lossy", "ratio": ratio, "efficiency": r.uniform(0.2, 1.0),
                "efficiency_backdrive": r.uniform(-1.0, 1.0)}
    else:
        gear = {"type": "worm", "ratio": ratio, "lead_angle": r.uniform(0.02, 0.6),
                "mu": r.uniform(0.0, 0.4)}
        if r.chance(0.3):
            gear["mu_static"] = gear["mu"] * r.uniform(1.0, 1.5)
        if r.chance(0.3):
            gear["flank_angle"] = r.uniform(0.0, 1.0)
    scene["gear"] = gear
    return kind


def _stops(r, scene: dict) -> str:
    kind = r.pick(("none", "exact", "penalty"))
    if kind == "none":
        return kind
    room = base.travel_room(scene)
    stops: Dict[str, Any] = {"contact": kind}
    if kind == "exact":
        if r.chance(0.6):
            stops["restitution"] = r.uniform(0.0, 1.0)
    else:
        stops["stiffness"] = r.log_uniform(1e4, 1e9)
        if r.chance(0.7):
            stops["damping"] = r.log_uniform(1.0, 1e4)
    for side, sign in (("lower", -1.0), ("upper", 1.0)):
        if r.chance(0.7):
            stops[side] = sign * r.log_uniform(1e-5, max(2e-5, 0.5 * room))
    if "lower" not in stops and "upper" not in stops:
        stops["upper"] = r.log_uniform(1e-5, max(2e-5, 0.5 * room))
    scene["end_stops"] = stops
    return kind


def _preload(r, scene: dict, hostile: list) -> str:
    if not r.chance(0.3):
        return "none"
    scene["nut"]["preload"] = r.log_uniform(1.0, 2000.0)
    if scene["concept"] != "rigid" and r.chance(0.8):
        scene["nut"]["preload_stiffness"] = r.log_uniform(1e5, 1e9)
    elif (scene["concept"] != "rigid"
          and scene.get("backlash", {}).get("contact") in ("bistop", "cubic")):
        # With penalty play on a flexible concept the spring's rate is
        # required (the spring carries the load beyond lift-off;
        # nut.preload_stiffness's doc): a scene without it breaks the input's
        # rule, not a combination. (Exact play: half A's lift-off into it is
        # an error of its own, the rate not needed.)
        hostile.append({"path": "nut.preload_stiffness", "kind": "missing where required"})
    return "preload"


def _options(r, t_end: float) -> dict:
    options: Dict[str, Any] = {"t_end": t_end, "max_events": base.MAX_EVENTS,
                               "max_steps": base.MAX_STEPS}
    kind = r.pick(("default", "default", "event_driven", "moreau"))
    if kind == "event_driven":
        options["integrator"] = "event_driven"
    elif kind == "moreau" or r.chance(0.3):
        # Moreau-Jean: the scene's default where only it runs the train
        # (then integrator is left out), or asked for; its step either way.
        if kind == "moreau":
            options["integrator"] = "moreau"
        options["dt"] = max(t_end / MAX_MOREAU_STEPS, r.log_uniform(1e-6, 1e-4))
        options.pop("max_steps")
    if "integrator" not in options and "dt" not in options and r.chance(0.3):
        options["rtol"] = r.log_uniform(1e-10, 1e-6)
    return options


def make_train_case(case_seed: int) -> dict:
    """The drive-train case of the seed ``case_seed`` (module docstring)."""
    r = base._Draw([case_seed, 27])
    concept = r.pick(base.CONCEPTS)
    scene: Dict[str, Any] = {"concept": concept}
    if r.chance(0.8):
        scene["drive"] = r.pick(("screw", "nut"))
    scene["thread"] = base._thread(r)
    friction = base._friction(r, scene["thread"])
    if r.chance(0.7):  # mostly exact Coulomb, what the train's elements take
        friction = {"law": "coulomb", "mu": friction["mu"]}
        if r.chance(0.3):
            friction["mu_static"] = friction["mu"] * r.uniform(1.0, 1.5)
    scene["friction"] = friction
    backlash = base._backlash(r, friction["law"])
    if backlash is not None:
        scene["backlash"] = backlash
    scene["screw"], scene["nut"] = base._bodies(r, scene["thread"])
    scene["rotor"] = {"inertia": r.log_uniform(1e-7, 1e-2)}
    scene["load"] = {"mass": r.log_uniform(1e-2, 200.0)}
    t_end = r.log_uniform(0.01, 0.1)
    scene["loads"], _ = base._loads(r, scene, t_end)
    tags = {"concept": concept, "drive": scene.get("drive", "screw"), "law": friction["law"],
            "contact": backlash["contact"] if backlash else "none",
            "motor": _motor(r, scene, t_end), "gear": _gear(r, scene),
            "stops": _stops(r, scene)}
    hostile: List[dict] = []
    tags["preload"] = _preload(r, scene, hostile)
    options = _options(r, t_end)
    tags["integrator"] = options.get("integrator") or "default"
    return {"seed": case_seed, "scene": scene, "options": options, "hostile": hostile,
            "tags": tags}


def generate_train(n: int, seed_value: int = TRAIN_SEED) -> List[dict]:
    """``n`` drive-train cases drawn by hypothesis with the seed
    ``seed_value``: the same list on every call (no example database,
    generation only)."""
    out: List[dict] = []

    @settings(max_examples=n, database=None, deadline=None, phases=[Phase.generate],
              suppress_health_check=list(HealthCheck), derandomize=False)
    @seed(seed_value)
    @given(st.integers(0, 2 ** 63 - 1).map(make_train_case))
    def collect(case):
        out.append(case)

    collect()
    return out[:n]
