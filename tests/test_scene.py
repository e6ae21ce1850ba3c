"""Scene validation: key paths, defaults, round trip, derived parameters."""

import math
import re

import pytest

import leadscrew as ls
from helpers.scenes import thesis_scene


def test_round_trip_and_defaults():
    scene = ls.Scene.from_dict(thesis_scene())
    d = scene.to_dict()
    assert ls.Scene.from_dict(d) == scene
    assert d["thread"]["starts"] == 1 and d["thread"]["hand"] == "right"
    assert d["friction"]["k_v"] == 1.0e4
    assert "backlash" not in d  # a thread without play unless asked for
    assert d["overrides"]["damping_ratio"] == 0.05


def test_the_constructor_validates_as_from_dict_does():
    """Scene(d) is Scene.from_dict(d): it once stored d unchecked, and a
    scene without its drive section failed later with a KeyError."""
    d = thesis_scene()
    assert ls.Scene(d).to_dict() == ls.Scene.from_dict(d).to_dict()
    with pytest.raises(ValueError, match="thread is missing"):
        ls.Scene({"concept": "rigid"})
    with pytest.raises(ValueError, match="bogus"):
        ls.Scene({**d, "bogus": 1})


def test_backlash_section_fills_defaults():
    scene = ls.Scene.from_dict(thesis_scene(backlash={"axial": 0.2e-3}))
    b = scene["backlash"]
    assert b["contact"] == "exact" and b["restitution"] == 0.0
    derived = scene.derived()
    assert derived["contact_penetration"] == pytest.approx(2e-6)
    assert derived["contact_stiffness"] == pytest.approx(derived["nut_axial_stiffness"])


@pytest.mark.parametrize(
    "changes, path",
    [
        (dict(backlash={"axial": -1e-3}), "backlash.axial"),
        (dict(backlash={"axial": 1e-3, "contact": "soft"}), "backlash.contact"),
        (dict(backlash={"axial": 1e-3, "stiffnes": 1.0}), "backlash.stiffnes"),
        (dict(thread={"pitch": 0.0, "mean_diameter": 0.02}), "thread.pitch"),
        (dict(friction={"law": "coulomb", "mu": float("nan")}), "friction.mu"),
        (dict(friction={"law": "viscous", "mu": 0.1}), "friction.law"),
        (dict(concept="elastic"), "concept"),
        (dict(drive="belt"), "drive"),
        (dict(screw={"support": "floating"}), "screw.support"),
        (dict(nut={"outer_radius": 5e-3}), "nut.outer_radius"),
        (dict(nut={"position": 0.6}), "nut.position"),
        (dict(drive="nut", nut={"position": 0.9}), "nut.position"),
        (dict(drive="nut", nut={"position": 0.5}), "nut.position"),
        (dict(loads={"drive_torque": {"type": "sine", "amplitude": 1.0}}), "loads.drive_torque.omega"),
        (dict(loads={"drive_torque": {"type": "square"}}), "loads.drive_torque.type"),
        (dict(loads={"drive_torque": 1.0, "drive_speed": 2.0}), "loads.drive_speed"),
        (dict(initial={"play_position": 1e-3}), "initial.play_position"),
        (dict(rotor={"inertia": 0}), "rotor.inertia"),
        (dict(gearbox={}), "gearbox"),
    ],
)
def test_bad_scene_names_key_path(changes, path):
    with pytest.raises(ValueError, match=path.replace(".", r"\.")):
        ls.Scene.from_dict(thesis_scene(**changes))


def test_missing_required():
    d = thesis_scene()
    del d["thread"]["pitch"]
    with pytest.raises(ValueError, match=r"thread\.pitch is missing"):
        ls.Scene.from_dict(d)
    d = thesis_scene()
    del d["friction"]
    with pytest.raises(ValueError, match="friction is missing"):
        ls.Scene.from_dict(d)


def test_derived_values_from_geometry():
    scene = ls.Scene.from_dict(thesis_scene())
    d = scene.derived()
    r_s, r_o, length = 10e-3, 12e-3, 0.5
    assert d["screw_mass"] == pytest.approx(7850 * math.pi * r_s**2 * length)
    assert d["screw_inertia"] == pytest.approx(0.5 * d["screw_mass"] * r_s**2)
    area_n = math.pi * (r_o**2 - r_s**2)
    assert d["nut_mass"] == pytest.approx(1400 * area_n * 20e-3)
    assert d["nut_inertia"] == pytest.approx(0.5 * d["nut_mass"] * (r_o**2 + r_s**2))
    # eq. (4.17) with the polar moment for torsion, G = E / (2 (1 + nu))
    assert d["nut_axial_stiffness"] == pytest.approx(2e9 * area_n / 20e-3)
    g = 2e9 / (2 * 1.3)
    assert d["nut_torsional_stiffness"] == pytest.approx(g * math.pi * (r_o**4 - r_s**4) / 2 / 20e-3)
    assert d["screw_axial_rigidity"] == pytest.approx(210e9 * math.pi * r_s**2)


def test_overrides_replace_derived_values():
    scene = ls.Scene.from_dict(thesis_scene(overrides={"nut_mass": 0.5, "nut_axial_stiffness": 1e6}))
    d = scene.derived()
    assert d["nut_mass"] == 0.5 and d["nut_axial_stiffness"] == 1e6


def test_replace_merges_sections():
    scene = ls.Scene.from_dict(thesis_scene())
    other = scene.replace(friction={"mu": 0.1}, backlash={"axial": 1e-4})
    assert other["friction"]["mu"] == 0.1 and other["friction"]["law"] == "coulomb"
    assert other["backlash"]["axial"] == 1e-4
    assert "backlash" not in other.replace(backlash=None)


def _merged(d, changes):
    """The reference for replace: merge into a full copy, validate all of it."""
    d = {key: dict(value) if isinstance(value, dict) else value for key, value in d.items()}
    for key, value in changes.items():
        if value is None:
            d.pop(key, None)
        elif isinstance(value, dict) and isinstance(d.get(key), dict):
            d[key].update(value)
        else:
            d[key] = value
    return ls.Scene.from_dict(d)


@pytest.mark.parametrize("changes", [
    {"friction": {"mu": 0.1}},
    {"concept": "flexible", "nut": {"length": "30 mm"}},
    {"backlash": {"axial": "0.1 mm", "contact": "bistop"}},
    {"loads": {"axial_force": {"type": "sine", "amplitude": "5 N", "omega": "2 Hz"}}},
    {"loads": {"drive_torque": None, "drive_speed": 10.0}},
    {"drive": None},
    {"overrides": {"nut_mass": 0.3}, "initial": {"rotor_speed": 2.0}},
])
def test_replace_equals_validating_the_merged_dict(changes):
    # replace checks only the named sections again; it must give exactly the
    # scene that validating the whole merged dict gives.
    scene = ls.Scene.from_dict(thesis_scene(drive="nut", backlash={"axial": 2e-4}))
    assert scene.replace(**changes) == _merged(scene.to_dict(), changes)


@pytest.mark.parametrize("changes, path", [
    ({"friction": {"mu": -0.1}}, "friction.mu"),
    ({"thread": {"pitch": "3 N"}}, "thread.pitch"),
    ({"gearbox": {}}, "gearbox"),
    ({"thread": None}, "thread"),
    ({"loads": {"drive_speed": 10.0}}, "loads.drive_speed"),  # both torque and speed
])
def test_replace_checks_what_it_changes(changes, path):
    scene = ls.Scene.from_dict(thesis_scene())
    with pytest.raises(ValueError, match=path.replace(".", r"\.")):
        scene.replace(**changes)


def test_scene_data_is_not_shared_with_callers():
    table = {"type": "table", "times": [0.0, 1.0], "values": [0.0, -5.0]}
    scene = ls.Scene.from_dict(thesis_scene(loads={"axial_force": table}))
    before = scene.to_dict()
    d = scene.to_dict()
    d["loads"]["axial_force"]["values"][1] = 99.0
    d["friction"]["mu"] = 0.9
    scene["loads"]["axial_force"]["times"].append(2.0)
    other = scene.replace(friction={"mu": 0.2})
    other_loads = other["loads"]
    other_loads["axial_force"]["values"][0] = 7.0
    assert scene.to_dict() == before
    assert other["loads"] == before["loads"] and other["friction"]["mu"] == 0.2

def test_schema_documents_every_field():
    text = ls.scene.describe_schema()
    for path in ("thread.pitch [m]", "backlash.axial [m]", "loads.drive_torque [N*m]",
                 "screw.support", "overrides.damping_ratio"):
        assert path in text


def test_schema_says_what_is_required_and_the_valid_values():
    # (A review of issue 18: the lines said "(default required)" and no range.)
    lines = {line.split(" ", 1)[0]: line for line in ls.scene.describe_schema().splitlines()}
    assert lines["thread.pitch"].startswith("thread.pitch [m] (required; a finite number > 0): ")
    assert lines["thread.starts"].startswith("thread.starts (default 1; an integer in [1, 100]): ")
    assert lines["thread.hand"].startswith("thread.hand (default 'right'; one of 'right', 'left'): ")
    assert lines["screw.youngs_modulus"].startswith(
        "screw.youngs_modulus [Pa] (default 210000000000.0; a finite number in [10000, 1e+13]): ")
    # The elements' own sections (the core's registry) read the same way.
    assert lines["load_spring.stiffness"].startswith("load_spring.stiffness [N/m] (required; ")
    assert not any("default required" in line for line in lines.values())


def test_schema_says_a_speed_controlled_drive_starts_at_drive_speed():
    line = next(line for line in ls.scene.describe_schema().splitlines()
                if line.startswith("initial.rotor_speed"))
    assert line.startswith("initial.rotor_speed [rad/s] (default 0, or drive_speed(0) for a "
                           "speed-controlled drive; a finite number): ")
    assert "A speed-controlled drive (loads.drive_speed) starts at drive_speed(0)" in line


def test_schema_says_which_schemes_run_the_trains_friction_stages():
    # (A new user's review: the docs said the stages need the rigid concept
    # without play and no end stops, after Moreau-Jean gained them.)
    lines = {line.split(" ", 1)[0]: line for line in ls.scene.describe_schema().splitlines()}
    for key in ("motor.friction_torque", "gear.type"):
        line = lines[key]
        # (Penalty flanks run with the stages on Moreau-Jean now; issue 32:
        # behind a prescribed rotor speed on the event-driven scheme too.)
        assert ("With a torque (loads.drive_torque) or a DC motor Moreau-Jean (integrator = "
                "'moreau') runs them on every concept and play with 'coulomb', 'stribeck', "
                "'arctan_velocity' and 'lugre' on the thread (a preloaded nut also lifting "
                "off with 'coulomb' or 'stribeck' without viscous), the event-driven "
                "scheme on the rigid concept without play with friction.law = 'coulomb' "
                "(mu_static too) outside the thread's Painleve regime and without a load spring "
                "or 'arctan_velocity', and on the flexible concepts without play and with exact "
                "or penalty play ('exact', 'bistop', 'cubic') with friction.law = 'coulomb' "
                "(mu_static too), 'stribeck' or 'arctan_velocity' (there with exact end stops, "
                "not beside exact play, and a preloaded nut too, lifting off too, 'stribeck' "
                "there without viscous; not on the rigid concept); where only "
                "Moreau-Jean fits, with "
                "mu_static, and off the rigid concept "
                "without play, it is the default. Behind a prescribed rotor speed "
                "(loads.drive_speed) the event-driven scheme runs them on every concept and play "
                "with every law, and Moreau-Jean, the default, where it runs the scene") in line, key
        assert "no end stops" not in line, key


SPEED_SINE = {"type": "sine", "amplitude": 2.0, "omega": 3.0, "phase": 0.5, "offset": 1.0}


@pytest.mark.parametrize("speed, rotor_speed, prescribed", [
    (5.0, 2.0, 5.0),
    (5.0, 0.0, 5.0),  # an explicit 0 is not "left out"
    ({"type": "constant", "value": "60 rpm"}, 5.0, 2 * math.pi),
    (SPEED_SINE, 1.0, 1.0 + 2.0 * math.sin(0.5)),
    (ls.Table([0.0, 1.0], [3.0, 4.0]), 4.0, 3.0),
    (lambda t: 3.0 + t, 2.0, 3.0),
])
def test_a_rotor_speed_that_contradicts_the_drive_speed_is_refused(speed, rotor_speed,
                                                                    prescribed):
    """A speed-controlled drive starts at drive_speed(0): another
    initial.rotor_speed would be overridden silently."""
    loads = {"drive_torque": None, "drive_speed": speed}
    message = (rf"^initial\.rotor_speed = {rotor_speed!r} is invalid: must be "
               rf"{re.escape(repr(prescribed))} rad/s or absent: loads\.drive_speed prescribes "
               rf"{re.escape(repr(prescribed))} rad/s at t = 0")
    with pytest.raises(ValueError, match=message):
        ls.Scene.from_dict(thesis_scene(loads=loads, initial={"rotor_speed": rotor_speed}))
    # replace: the speed given to a speed-controlled scene, or the drive
    # switched to speed control under a scene's rotor speed
    speed_scene = ls.Scene.from_dict(thesis_scene(loads=loads))
    with pytest.raises(ValueError, match=message):
        speed_scene.replace(initial={"rotor_speed": rotor_speed})
    torque_scene = ls.Scene.from_dict(thesis_scene(initial={"rotor_speed": rotor_speed}))
    with pytest.raises(ValueError, match=message):
        torque_scene.replace(loads=loads)
    # drive_speed(0) itself, or none, is the same scene
    same = speed_scene.replace(initial={"rotor_speed": prescribed})
    assert same == speed_scene
    assert same["initial"]["rotor_speed"] == prescribed


def test_a_speed_controlled_drive_starts_at_drive_speed(tmp_path):
    scene = ls.Scene.from_dict(thesis_scene(loads={"drive_torque": None, "drive_speed": 5.0}))
    assert "rotor_speed" not in scene["initial"]
    assert ls.Scene.from_dict(scene.to_dict()) == scene
    scene.to_toml(tmp_path / "speed.toml")
    assert ls.Scene.from_toml(tmp_path / "speed.toml") == scene
    result = ls.simulate(scene, 0.01, t_eval=[0.0, 0.01])
    assert result["omega_drive"][0] == 5.0
    # a torque-driven scene starts at initial.rotor_speed, 0 if left out
    torque = ls.Scene.from_dict(thesis_scene())
    assert "rotor_speed" not in torque["initial"]
    assert torque == torque.replace(initial={"rotor_speed": 0.0})
    assert torque != torque.replace(initial={"rotor_speed": 1.0})
    assert ls.simulate(torque.replace(initial={"rotor_speed": 1.0}), 0.01,
                       t_eval=[0.0])["omega_drive"][0] == 1.0
    # switched back to a torque, the drive's given speed is its own again
    given = scene.replace(initial={"rotor_speed": 5.0})
    assert given.replace(loads={"drive_speed": None, "drive_torque": 0.0})["initial"][
        "rotor_speed"] == 5.0


@pytest.mark.parametrize("changes, path, default", [
    ({"load": {"mass": None}}, "load.mass", "its default 1.0"),
    ({"thread": {"hand": None}}, "thread.hand", "its default 'right'"),
    ({"loads": {"axial_force": None}}, "loads.axial_force", "its default 0.0"),
    ({"initial": {"play_position": None}}, "initial.play_position", "its default 0.0"),
    ({"thread": {"pitch": None}}, "thread.pitch", "thread.pitch is required"),
])
def test_none_for_a_field_that_is_not_optional_is_refused(changes, path, default):
    """None does not mean the schema's default (a replaced load.mass of 2 kg
    came out 1 kg): refused, naming the key, in from_dict and replace."""
    scene = ls.Scene.from_dict(thesis_scene(load={"mass": 2.0}, thread={
        **thesis_scene()["thread"], "hand": "left"}))
    message = rf"^{re.escape(path)} = None is invalid: must be .*\(None removes only an " \
              rf"optional field: .*{re.escape(default)}"
    with pytest.raises(ValueError, match=message):
        scene.replace(**changes)
    with pytest.raises(ValueError, match=message):
        ls.Scene.from_dict(_merged(thesis_scene(), changes))
    # None still removes an optional field
    assert "nut_mass" not in scene.replace(overrides={"nut_mass": 0.3}).replace(
        overrides={"nut_mass": None})["overrides"]
    assert scene.replace(initial={"rotor_speed": 1.0}).replace(
        initial={"rotor_speed": None}) == scene


def test_nut_position_is_checked_for_both_drives():
    # The model takes the nut's centre as the point where the thread force
    # enters the screw (segments a and L - a), the whole nut on the screw:
    # nut.length / 2 < a < screw.length - nut.length / 2 for either drive.
    for drive, end in (("screw", "drive end"), ("nut", "load end")):
        for position in (0.9, 0.495, 0.01, 0.002):
            with pytest.raises(ValueError) as info:
                ls.scenes.load("thesis_table_5_1").replace(drive=drive,
                                                           nut={"position": position})
            assert str(info.value).startswith(
                f"nut.position = {position} is invalid: must be in (nut.length / 2, "
                f"screw.length - nut.length / 2) = (0.01, 0.49) (the distance of the nut's "
                f"centre from the screw's {end}")
        for position in (0.4899, 0.0101):
            scene = ls.Scene.from_dict(thesis_scene(drive=drive, nut={"position": position}))
            assert scene["nut"]["position"] == position
        # the bounds follow the nut's length
        scene = ls.Scene.from_dict(thesis_scene(drive=drive, nut={"position": 0.495,
                                                                  "length": 8e-3}))
        assert scene["nut"]["position"] == 0.495


SINE = {"type": "sine", "amplitude": -40e-3, "omega": 4 * math.pi}


@pytest.mark.parametrize("loads, message", [
    ({"drive_torque": {**SINE, "amplitude": [1.0]}},
     "loads.drive_torque.amplitude = [1.0] is invalid: must be a finite number [N*m]"),
    ({"drive_torque": {**SINE, "amplitude": {"a": 1}}},
     "loads.drive_torque.amplitude = {'a': 1} is invalid: must be a finite number [N*m]"),
    ({"drive_torque": {**SINE, "omega": True}},
     "loads.drive_torque.omega = True is invalid: must be a finite number [rad/s]"),
    ({"drive_torque": {**SINE, "phase": float("nan")}},
     "loads.drive_torque.phase = nan is invalid: must be a finite number [rad]"),
    ({"drive_torque": {"type": "constant", "value": None}},
     "loads.drive_torque.value = None is invalid: must be a finite number [N*m]"),
    ({"axial_force": {"type": "table", "times": [0.0, 1.0], "values": [[1], [2]]}},
     "loads.axial_force.values[0] = [1] is invalid: must be a finite number [N]"),
    ({"axial_force": {"type": "table", "times": [0.0, False], "values": [1.0, 2.0]}},
     "loads.axial_force.times[1] = False is invalid: must be a finite number [s]"),
    ({"axial_force": {"type": "table", "times": {0.0: 1.0}, "values": [1.0]}},
     "loads.axial_force.times = {0.0: 1.0} is invalid: must be a list of numbers [s]"),
    ({"axial_force": {"type": ["table"], "times": [0.0], "values": [1.0]}},
     "loads.axial_force.type = ['table'] is invalid: must be one of"),
])
def test_bad_load_entries_name_the_entry(loads, message):
    with pytest.raises(ValueError) as info:
        ls.Scene.from_dict(thesis_scene(loads=loads))
    assert str(info.value).startswith(message), str(info.value)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("starts, message", [
    (2**40, "thread.starts = 1099511627776 is invalid: must be an integer in [1, 100]"),
    (101, "thread.starts = 101 is invalid: must be an integer in [1, 100]"),
    (float("inf"), "thread.starts = inf is invalid: must be an integer in [1, 100]"),
    (float("nan"), "thread.starts = nan is invalid: must be an integer in [1, 100]"),
    (1.5, "thread.starts = 1.5 is invalid: must be an integer in [1, 100]"),
])
def test_thread_starts_is_bounded(starts, message):
    with pytest.raises(ValueError) as info:
        ls.Scene.from_dict(thesis_scene(thread={"starts": starts}))
    assert str(info.value) == message
    assert ls.Scene.from_dict(thesis_scene(thread={"starts": 100})).thread.starts == 100


def test_big_integer_in_a_float_field_names_the_key():
    with pytest.raises(ValueError, match=r"^load\.mass = 1000+ is invalid: must be a finite"):
        ls.Scene.from_dict(thesis_scene(load={"mass": 10**400}))


def test_excitation_objects_are_stored_as_dicts_that_compare_equal():
    objects = {"drive_torque": ls.Sine(-40e-3, 4 * math.pi, 0.5),
               "axial_force": ls.Table([0.0, 0.1], [-10.0, -20.0])}
    dicts = {"drive_torque": {"type": "sine", "amplitude": -40e-3, "omega": 4 * math.pi,
                              "phase": 0.5},
             "axial_force": {"type": "table", "times": [0.0, 0.1], "values": [-10.0, -20.0]}}
    scene = ls.Scene.from_dict(thesis_scene(loads=objects))
    assert scene == ls.Scene.from_dict(thesis_scene(loads=objects))
    assert scene == ls.Scene.from_dict(thesis_scene(loads=dicts))
    assert scene["loads"]["axial_force"] == {"type": "table", "times": [0.0, 0.1],
                                             "values": [-10.0, -20.0]}
    constant = ls.Scene.from_dict(thesis_scene(loads={"axial_force": ls.Constant(-10.0)}))
    assert constant["loads"]["axial_force"] == {"type": "constant", "value": -10.0}
    assert constant.replace(loads={"axial_force": ls.Constant(-10.0)}) == constant


def _without_torque(**changes):
    d = thesis_scene(**changes)
    del d["loads"]["drive_torque"]
    return ls.Scene.from_dict(d)


def test_default_drive_torque_is_not_stored():
    scene = _without_torque()
    assert scene["loads"] == {"axial_force": -10.0}
    assert "drive_torque" not in scene.to_dict()["loads"]
    assert "drive_torque" not in scene.to_toml()
    # The model applies 0 N*m: the same scene as an explicit 0, and the same motion.
    explicit = ls.Scene.from_dict(thesis_scene(loads={"drive_torque": 0.0}))
    assert scene == explicit and explicit == scene
    assert scene != explicit.replace(loads={"drive_torque": 1e-3})
    a, b = ls.simulate(scene, 0.05), ls.simulate(explicit, 0.05)
    assert a.t.tolist() == b.t.tolist() and a["u_load"].tolist() == b["u_load"].tolist()


def test_replace_switches_between_torque_and_speed():
    scene = _without_torque()
    speed = scene.replace(loads={"drive_speed": 2.0})
    assert speed["loads"] == {"axial_force": -10.0, "drive_speed": 2.0}
    back = speed.replace(loads={"drive_speed": None})
    assert back == scene and back["loads"] == scene["loads"]
    assert back.replace(loads={"drive_speed": 3.0})["loads"]["drive_speed"] == 3.0
    torque = speed.replace(loads={"drive_speed": None, "drive_torque": 0.5})
    assert torque["loads"] == {"axial_force": -10.0, "drive_torque": 0.5}
    explicit = ls.Scene.from_dict(thesis_scene())
    switched = explicit.replace(loads={"drive_torque": None, "drive_speed": 2.0})
    assert switched == speed
    assert switched.replace(loads={"drive_speed": None, "drive_torque": SINE}) == explicit
    for changed in (speed, back, torque, switched):
        changed.model()


def test_loads_given_as_objects_with_units():
    """A Sine with units is the same load as its dict; a load whose unit is
    not that of its key is refused, naming the key."""
    base = thesis_scene(loads={"axial_force": {"type": "constant", "value": -10.0}})
    with_units = ls.Scene.from_dict(thesis_scene(loads={
        "drive_torque": ls.Sine("-40 N*mm", "2 Hz"), "axial_force": ls.Constant("-10 N")}))
    assert with_units == ls.Scene.from_dict(base)
    speed = ls.Scene.from_dict(thesis_scene(loads={"drive_torque": None,
                                                   "drive_speed": ls.Table([0, 1], ["0 rpm",
                                                                                    "60 rpm"])}))
    assert speed["loads"]["drive_speed"]["values"] == [0.0, 2 * math.pi]
    for key, load, message in (
            ("axial_force", ls.Sine("50 N*m", 1.0), "its values are a torque (N*m), not a force"),
            ("drive_torque", ls.Constant("5 N"), "its values are a force (N), not a torque"),
            ("drive_speed", ls.Table([0, 1], ["0 N", "1 N"]), "not an angular velocity"),
            ("axial_force", ls.Sine("12 V", "5 Hz"), "its values are a voltage (V), not a force"),
            ("drive_torque", ls.Constant("12 V"), "its values are a voltage (V), not a torque")):
        loads = {key: load, **({"drive_torque": None} if key == "drive_speed" else {})}
        with pytest.raises(ValueError, match=rf"^loads\.{key} = .* is invalid: .*"
                                             rf"{re.escape(message)}"):
            ls.Scene.from_dict(thesis_scene(loads=loads))


def test_the_model_is_built_once_and_a_scene_still_pickles():
    """A scene is immutable and so is its core model: built on the first
    model() call and kept (simulate calls it on every run), left out when
    the scene is pickled for a process pool."""
    import pickle

    scene = ls.scenes.load("default")
    model = scene.model()
    assert scene.model() is model
    scene["loads"]["drive_torque"] = 1.0  # a copy: the scene (and its model) stay
    assert scene.model() is model and scene["loads"]["drive_torque"] != 1.0
    again = pickle.loads(pickle.dumps(scene))
    assert again == scene and again.model() is not model
    assert again.model().coordinate_names == model.coordinate_names
    changed = scene.replace(friction={"mu": 0.2})
    assert changed.model() is not model and changed.model().parameters.mu == 0.2
