"""Hostile values in every numeric scene field (issue 17, defect 15): a scene
either is valid, and its derived() and model() give finite values, or a
ValueError names the key the user set; never an OverflowError, a message
about an internal (``tol``, ``screw axial damping``) or a derived quantity
alone (``nut mass = 0``), and never a key the user did not give."""

import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import leadscrew as ls
import leadscrew.scene as scene_module
from helpers.scenes import thesis_scene
from leadscrew.scene import SCHEMA, Field

PLAY = {"none": None,
        "exact": {"axial": 1e-4, "contact": "exact"},
        "bistop": {"axial": 1e-4, "contact": "bistop"},
        "cubic": {"axial": 1e-4, "contact": "cubic"}}


def base_scene(concept, drive, play):
    """A valid scene of each concept, drive and play; a sine drive torque and
    a table axial force, so that every load entry can be made hostile."""
    law = ({"law": "coulomb", "mu": 0.3} if play in ("none", "exact")
           else {"law": "arctan_velocity", "mu": 0.3})
    return thesis_scene(concept=concept, drive=drive, backlash=PLAY[play], friction=law,
                        loads={"drive_torque": {"type": "sine", "amplitude": -0.04,
                                                "omega": 12.0, "phase": 0.1, "offset": 0.0},
                               "axial_force": {"type": "table", "times": [0.0, 0.5, 1.0],
                                               "values": [-10.0, -5.0, -10.0]}})


# A DC motor (scene section motor) for the motor's fields.
MOTOR = {"type": "dc", "voltage": 12.0, "resistance": 2.0, "inductance": 1e-3,
         "torque_constant": 0.05}

# End stops (scene section end_stops) and a load spring (load_spring) for their fields.
END_STOPS = {"lower": -0.01, "upper": 0.01, "stiffness": 1e7}
LOAD_SPRING = {"stiffness": 1e4, "preload": 5.0}

BASES = [(c, d, p) for c in ("rigid", "flexible_nut", "flexible") for d in ("screw", "nut")
         for p in PLAY]

# Every numeric field of the schema (choices and loads aside) with its unit.
FIELDS = [(f"{section}.{key}", f.unit) for section, entry in SCHEMA.items()
          if isinstance(entry, dict) for key, f in entry.items()
          if isinstance(f, Field) and f.kind in ("float", "int")]
# The numbers inside the loads (a path into the base's loads, its unit).
LOAD_ENTRIES = [("loads.drive_torque.amplitude", "N*m"), ("loads.drive_torque.omega", "rad/s"),
                ("loads.drive_torque.phase", "rad"), ("loads.drive_torque.offset", "N*m"),
                ("loads.axial_force.times[1]", "s"), ("loads.axial_force.values[1]", "N")]
PATHS = FIELDS + LOAD_ENTRIES

HOSTILE = [0, 0.0, -0.0, 5e-324, -5e-324, 1e-300, 1e300, -1e300, 1e80, 10**400, -10**400,
           math.nan, math.inf, -math.inf, -1.0, -1e-3, 2.5e-308, 1.7976931348623157e308]


def wrong_unit(unit):
    """A string with a unit of another dimension than ``unit``."""
    return "3 N" if unit == "m" else "3 m"


def values_for(unit):
    return st.one_of(st.sampled_from(HOSTILE), st.just(wrong_unit(unit)),
                     st.floats(allow_nan=True, allow_infinity=True),
                     st.integers(min_value=-10**400, max_value=10**400),
                     st.sampled_from(["1e400 m", "nan m", "-0 m", "5e-324", "1e300"]))


def with_value(d, path, value):
    """``d`` with ``value`` at ``path`` (``section.key`` or a load entry)."""
    match = re.fullmatch(r"(\w+)\.(\w+)(?:\.(\w+)(?:\[(\d+)\])?)?", path)
    section, key, entry, index = match.groups()
    d = {k: (dict(v) if isinstance(v, dict) else v) for k, v in d.items()}
    target = d.setdefault(section, {})
    if entry is None:
        target[key] = value
        return d
    load = target[key] = dict(target[key])
    if index is None:
        load[entry] = value
    else:
        items = load[entry] = list(load[entry])
        items[int(index)] = value
    return d


def named(message, path):
    """The message names ``path``: it starts with it, or gives its value
    (``path = ...``); a load entry ``loads.x.values[1]`` may be named by its
    load (``loads.x``) or its list (``loads.x.values``)."""
    names = {path, path.split("[")[0], ".".join(path.split(".")[:2])}
    return any(message.startswith(name) or f"{name} = " in message for name in names)


def assert_finite_model(scene):
    derived = scene.derived()
    for key, value in derived.items():
        assert math.isfinite(value), (key, value)
    model = scene.model()
    assert np.all(np.isfinite(model.mass)) and np.all(model.mass > 0)
    for spring in model.springs:
        assert math.isfinite(spring["stiffness"]) and spring["stiffness"] > 0, spring
        assert math.isfinite(spring["damping"]) and spring["damping"] >= 0, spring
    assert math.isfinite(model.effective_mu)


@settings(max_examples=600, deadline=None, derandomize=True)
@given(base=st.sampled_from(BASES), path_unit=st.sampled_from(PATHS), data=st.data())
def test_a_hostile_value_gives_a_valid_scene_or_names_its_key(base, path_unit, data):
    path, unit = path_unit
    value = data.draw(values_for(unit), label="value")
    if path.startswith("backlash.") and base[2] == "none":
        base = (base[0], base[1], "bistop")  # the backlash fields need a backlash
    d = base_scene(*base)
    if path.startswith("motor."):  # the motor's fields need a motor instead of the torque
        d["loads"] = {k: v for k, v in d["loads"].items() if k != "drive_torque"}
        d["motor"] = dict(MOTOR)
    if path.startswith("gear."):  # the gear's fields need a gear stage
        d["gear"] = {"ratio": 3.0}
    if path.startswith("end_stops."):  # the stops' fields need stops
        d["end_stops"] = dict(END_STOPS)
    if path.startswith("load_spring."):  # the spring's fields need a spring
        d["load_spring"] = dict(LOAD_SPRING)
    d = with_value(d, path, value)
    try:
        scene = ls.Scene.from_dict(d)
        assert_finite_model(scene)
    except ValueError as error:
        message = str(error)
        assert named(message, path), message
        assert "\n" not in message


@settings(max_examples=300, deadline=None, derandomize=True)
@given(values=st.fixed_dictionaries(
    {q.key: st.sampled_from([0.0, 5e-324, 1e-7, 1.0, 1e6, 1e300, math.inf, -1.0, math.nan])
     for q in scene_module._QUANTITIES}))
def test_the_fast_range_check_agrees_with_each_quantitys(values):
    """Scene.derived() checks every quantity at once (scene._in_range) and
    only on a failure one by one (their messages): both give one verdict."""
    thread = {key: values.pop(key) for key in ("tan_lead_angle", "effective_mu")}
    each = all(q.problem({**thread, **values}[q.key]) is None
               for q in scene_module._QUANTITIES)
    assert scene_module._in_range(values, thread) == each


@pytest.mark.parametrize("concept, changes, message", [
    # Overflow in the derivation: ValueError naming the key, not OverflowError.
    ("flexible", {"nut": {"outer_radius": 1e300}},
     "nut.outer_radius = 1e+300 is invalid: with it the nut's mass (nut.density * pi "
     "(nut.outer_radius^2 - screw.radius^2) * nut.length) comes to inf kg: must be a finite "
     "number > 0 (or set overrides.nut_mass)"),
    ("flexible", {"nut": {"outer_radius": 1e80}},
     "nut.outer_radius = 1e+80 is invalid: with it the nut's polar inertia (nut mass * "
     "(nut.outer_radius^2 + screw.radius^2) / 2) comes to inf kg*m^2: must be a finite "
     "number > 0 (or set overrides.nut_inertia)"),
    ("rigid", {"nut": {"outer_radius": 1e300}}, "nut.outer_radius = 1e+300 is invalid"),
    # A derived quantity named with the key that made it so.
    ("flexible", {"screw": {"density": 1.0, "radius": 1e-170}},
     "screw.radius = 1e-170 is invalid: with it the screw's mass (screw.density * pi "
     "screw.radius^2 * screw.length) comes to 0.0 kg: must be a finite number > 0 (or set "
     "overrides.screw_mass)"),
    # thread.mean_diameter = 1e300 (rigid) ended in "tol = inf is invalid"
    ("rigid", {"thread": {"pitch": 1e-3, "mean_diameter": 1e300}},
     "thread.mean_diameter = 1e+300 is invalid: with it the tangent of the lead angle "
     "(thread.starts * thread.pitch / (pi thread.mean_diameter)) comes to "
     "3.183098861837907e-304: must be in [1e-06, 1e+06]"),
    ("flexible", {"thread": {"pitch": 1e-12, "mean_diameter": 1e3}},
     "thread.pitch = 1e-12 and thread.mean_diameter = 1000.0 are invalid together: with "
     "them the tangent of the lead angle"),
    # screw.length = 1e300 ended in "screw axial damping = inf is invalid"
    ("flexible", {"screw": {"length": 1e300}},
     "screw.length = 1e+300 is invalid: with it the model's screw axial damping comes to inf: "
     "must be a finite number"),
    # nut.density = 5e-324 said "nut mass = 0 is invalid"
    ("flexible", {"nut": {"density": 5e-324}},
     "nut.density = 5e-324 is invalid: must be a finite number in [1, 100000]"),
    # with bistop play, nut.youngs_modulus = 5e-324 blamed backlash.stiffness
    ("flexible_nut", {"nut": {"youngs_modulus": 5e-324}},
     "nut.youngs_modulus = 5e-324 is invalid: must be a finite number in [10000, 1e+13]"),
    # finite, but a part too stiff for its mass ran into "the nut reached the end of the
    # screw" (nut.length = 1e-14 m) or NaN
    ("flexible_nut", {"nut": {"length": 1e-14}},
     "nut.length = 1e-14 is invalid: with it the nut's axial natural frequency sqrt(stiffness "
     "/ nut mass) comes to 1.19"),
    ("flexible_nut", {"nut": {"length": 1e-300}},
     "nut.length = 1e-300 is invalid: with it the nut's axial natural frequency"),
    ("flexible", {"overrides": {"screw_inertia": 1e-30}},
     "overrides.screw_inertia = 1e-30 is invalid: with it the screw's torsion natural "
     "frequency sqrt(stiffness / screw inertia) comes to"),
    # damping_ratio and moduli of 1e300 ran into "nut position nan"
    ("flexible", {"overrides": {"damping_ratio": 1e300}},
     "overrides.damping_ratio = 1e+300 is invalid: must be a finite number in [0, 10]"),
    ("flexible", {"nut": {"youngs_modulus": 1e300}},
     "nut.youngs_modulus = 1e+300 is invalid: must be a finite number in [10000, 1e+13]"),
    # integers beyond the float range
    ("rigid", {"loads": {"axial_force": 10**400}}, f"loads.axial_force = {10**400} is invalid"),
    ("rigid", {"loads": {"drive_torque": {"type": "constant", "value": -10**400}}},
     f"loads.drive_torque.value = {-10**400} is invalid"),
    ("rigid", {"thread": {"pitch": 1e-3, "mean_diameter": 0.02, "starts": 10**400}},
     f"thread.starts = {10**400} is invalid: must be an integer in [1, 100]"),
    ("rigid", {"load": {"mass": 10**400}}, f"load.mass = {10**400} is invalid"),
])
def test_defect_15_messages_name_the_key_that_was_set(concept, changes, message):
    play = {"backlash": {"axial": 1e-4, "contact": "bistop"},
            "friction": {"law": "arctan_velocity", "mu": 0.3}} if "youngs" in message else {}
    d = thesis_scene(concept=concept, **{**play, **changes})
    with pytest.raises(ValueError) as info:
        scene = ls.Scene.from_dict(d)
        scene.derived()
        scene.model()
    assert str(info.value).startswith(message), str(info.value)
    if "with it" in message or "with them" in message:  # derived: the scene itself is valid
        scene = ls.Scene.from_dict(d)
        model_only = "the model's" in message or "natural frequency" in message
        if model_only:
            assert all(math.isfinite(value) for value in scene.derived().values())
        calls = (scene.model, lambda: ls.simulate(scene, 1e-3)) + (() if model_only
                                                                    else (scene.derived,))
        for call in calls:
            with pytest.raises(ValueError, match=re.escape(message)):
                call()


@pytest.mark.parametrize("changes", [
    {"overrides": {"damping_ratio": 10.0}}, {"overrides": {"damping_ratio": 0.0}},
    {"nut": {"youngs_modulus": 1e4}}, {"nut": {"youngs_modulus": 1e13}},
    {"screw": {"youngs_modulus": 1e13}}, {"nut": {"density": 1.0}},
    {"screw": {"density": 1e5}},
    {"thread": {"pitch": 2e-5, "mean_diameter": 6.3}},  # tan(alpha) = 1.01e-6
    {"nut": {"length": 1e-6}},  # natural frequency 1.2e9 rad/s
])
@pytest.mark.parametrize("concept", ["flexible_nut", "flexible"])
def test_the_ends_of_the_ranges_simulate(concept, changes):
    """The documented ranges (moduli, densities, damping ratio, lead angle)
    end where the models still run (a short run each)."""
    scene = ls.Scene.from_dict(thesis_scene(concept=concept, **changes))
    r = ls.simulate(scene, 2e-3, max_steps=100_000)
    assert all(np.all(np.isfinite(r[name])) for name in r.channels)


def test_the_ranges_are_documented():
    text = ls.scene.describe_schema()
    for fragment in ("in [1e4, 1e13] Pa", "in [1, 1e5] kg/m^3", "at most 10",
                     "1e-6 <= tan(alpha)"):
        assert fragment in text, fragment
