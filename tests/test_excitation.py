"""leadscrew.Excitation by kind (the C++ core's loads) against closed forms,
and its errors: a wrong parameter count is a ValueError naming the values and
what the kind takes, never an IndexError."""

import math

import numpy as np
import pytest

import leadscrew as ls


def test_kinds_match_their_closed_forms():
    t = np.linspace(-1.0, 3.0, 41)
    assert np.all(ls.Excitation("constant", [2.5])(t) == 2.5)
    full = ls.Excitation("sine", [3.0, 4.0, 0.5, -1.0])
    assert np.allclose(full(t), 3.0 * np.sin(4.0 * t + 0.5) - 1.0, rtol=0, atol=1e-15)
    # phase and offset default to zero, as in leadscrew.Sine
    assert np.all(ls.Excitation("sine", [3.0, 4.0])(t) == ls.Sine(3.0, 4.0)(t))
    assert np.all(ls.Excitation("sine", [3.0, 4.0, 0.5])(t) == ls.Sine(3.0, 4.0, 0.5)(t))
    table = ls.Excitation("table", [], [0.0, 1.0, 2.0], [0.0, 10.0, -10.0])
    assert np.allclose(table(t), np.interp(t, [0.0, 1.0, 2.0], [0.0, 10.0, -10.0]),
                       rtol=0, atol=1e-14)
    assert table(0.25) == pytest.approx(2.5, abs=1e-15)
    assert math.isclose(full(0.0), 3.0 * math.sin(0.5) - 1.0, abs_tol=1e-15)


@pytest.mark.parametrize("kind, parameters, times, values, message", [
    ("constant", [], [], [], r"parameters = \[\] is invalid for kind = \"constant\": must hold \[value\]"),
    ("constant", [1.0, 2.0], [], [], r"parameters = \[1, 2\] is invalid for kind = \"constant\""),
    ("sine", [1.0], [], [], r"parameters = \[1\] is invalid for kind = \"sine\": must hold \[amplitude, omega\]"),
    ("sine", [1.0, 2.0, 3.0, 4.0, 5.0], [], [], r"parameters = \[1, 2, 3, 4, 5\] is invalid"),
    ("sine", [1.0, float("nan")], [], [], r"omega = nan is invalid"),
    ("sine", [1.0, 2.0], [0.0], [1.0], r"times and values are invalid for kind = \"sine\""),
    ("table", [1.0], [0.0], [1.0], r"parameters = \[1\] is invalid for kind = \"table\""),
    ("table", [], [], [], r"times = \[\] is invalid"),
    ("ramp", [1.0], [], [], r"kind = \"ramp\" is invalid: must be one of"),
])
def test_bad_arguments_raise_value_error(kind, parameters, times, values, message):
    with pytest.raises(ValueError, match=message):
        ls.Excitation(kind, parameters, times, values)


def test_parameters_are_read_only_and_match_what_the_core_evaluates():
    # A scene stores these loads as the dicts of their parameters, and to_toml
    # writes them: a parameter changed after construction would differ from
    # what the core evaluates.
    sine, constant = ls.Sine(3.0, 4.0, 0.5, -1.0), ls.Constant(2.5)
    for excitation, name in ((sine, "amplitude"), (sine, "omega"), (sine, "phase"),
                             (sine, "offset"), (constant, "value")):
        with pytest.raises(AttributeError):
            setattr(excitation, name, 7.0)
    times, values = np.array([0.0, 1.0]), np.array([0.0, 10.0])
    table = ls.Table(times, values)
    times[1], values[1] = 2.0, -10.0  # the caller's arrays are not the table's
    assert table.times.tolist() == [0.0, 1.0] and table.values.tolist() == [0.0, 10.0]
    assert table(0.5) == 5.0
    with pytest.raises(ValueError, match="read-only"):
        table.values[1] = 3.0
    with pytest.raises(AttributeError):
        table.times = np.array([0.0, 2.0])


# --- unit strings, as in a scene -----------------------------------------------------


@pytest.mark.parametrize("given, expected, unit", [
    (lambda: ls.Constant("-10 N"), ls.Constant(-10.0), "N"),
    (lambda: ls.Constant("40 N*mm"), ls.Constant(0.04), "N*m"),
    (lambda: ls.Constant("120 rpm"), ls.Constant(4 * math.pi), "rad/s"),
    (lambda: ls.Sine("50 N", 94.2), ls.Sine(50.0, 94.2), "N"),
    (lambda: ls.Sine("50 N", "15 Hz", "90 deg", "-1 kN"),
     ls.Sine(50.0, 30 * math.pi, math.pi / 2, -1000.0), "N"),
    (lambda: ls.Sine(5.0, "2 Hz", offset="1 N"), ls.Sine(5.0, 4 * math.pi, 0.0, 1.0), "N"),
    (lambda: ls.Table(["0 s", "250 ms"], ["0 N*mm", "40 N*mm"]), ls.Table([0, 0.25], [0, 0.04]),
     "N*m"),
    (lambda: ls.Table([0.0, 1.0], [0.0, 5.0]), ls.Table([0.0, 1.0], [0.0, 5.0]), ""),
    # a DC motor's voltage (motor.voltage) is a load too
    (lambda: ls.Constant("12 V"), ls.Constant(12.0), "V"),
    (lambda: ls.Sine("12 V", "5 Hz"), ls.Sine(12.0, 10 * math.pi), "V"),
    (lambda: ls.Table([0, 1], ["0 V", "12 V"]), ls.Table([0.0, 1.0], [0.0, 12.0]), "V"),
    (lambda: ls.Constant("3000 mV"), ls.Constant(3.0), "V"),
])
def test_loads_take_unit_strings(given, expected, unit):
    load = given()
    assert load.unit == unit and expected.unit == ""
    t = np.linspace(0.0, 1.0, 11)
    np.testing.assert_allclose(load(t), expected(t), rtol=1e-15, atol=1e-15)
    # repr, pickle and copies keep the unit
    import pickle

    for copy in (pickle.loads(pickle.dumps(load)), eval("ls." + repr(load))):  # noqa: S307
        assert type(copy) is type(load) and copy.unit == unit
        np.testing.assert_array_equal(copy(t), load(t))


@pytest.mark.parametrize("call, message", [
    (lambda: ls.Sine("50 kg", 94.2),
     'amplitude = "50 kg" is invalid: "50 kg" is not a force (N), a torque (N*m), an '
     "angular velocity or frequency (rad/s), a voltage (V), a velocity (m/s), an acceleration "
     "(m/s^2) or an angular acceleration (rad/s^2) (the loads' units)"),
    (lambda: ls.Sine("12 V", 94.2, offset="1 N"),
     'offset = "1 N" is invalid: a force (N), but amplitude is a voltage (V): the values '
     "of one load share their unit"),
    (lambda: ls.Sine("50 N", "3 m"), 'omega = "3 m" is invalid: "3 m" is not an angular'),
    (lambda: ls.Sine("50 N", 94.2, offset="1 N*m"),
     'offset = "1 N*m" is invalid: a torque (N*m), but amplitude is a force (N): the values '
     "of one load share their unit"),
    (lambda: ls.Sine("40 Nm", 94.2),
     'amplitude = "40 Nm" is invalid: "40 Nm" is not a force (N), a torque (N*m), an angular '
     "velocity or frequency (rad/s), a voltage (V), a velocity (m/s), an acceleration (m/s^2) "
     "or an angular acceleration (rad/s^2) (the loads' units) "
     '("Nm" is number_meter to pint, not a newton metre: write "N*m")'),
    (lambda: ls.Constant("12 v"), 'value = "12 v" is invalid: unit \'v\' does not parse: \'v\' '
     'is not defined in the unit registry; units are case-sensitive: write "V" for volt'),
    (lambda: ls.Sine(None, 1.0), "amplitude = None is invalid: must be a number"),
    (lambda: ls.Sine(1.0, "fast"), 'omega = "fast" is invalid: not one number'),
    (lambda: ls.Sine(1.0, 2.0, phase=True), "phase = True is invalid: must be a number [rad]"),
    (lambda: ls.Constant("1,5 N"), 'value = "1,5 N" is invalid: a comma'),
    (lambda: ls.Constant(10**400), "value = 1000"),
    (lambda: ls.Table([0, "1 N"], [0, 1]), 'times[1] = "1 N" is invalid: "1 N" is not a time'),
    (lambda: ls.Table([0, 1], ["0 N", "1 N*m"]), 'values[1] = "1 N*m" is invalid: a torque'),
    (lambda: ls.Table([0, 1], 5), "values = 5 is invalid: must be a sequence of numbers"),
    (lambda: ls.Table([0, 1], [0, None]), "values[1] = None is invalid: must be a number"),
])
def test_bad_load_parameters_are_named(call, message):
    with pytest.raises(ValueError) as info:
        call()
    assert str(info.value).startswith(message), str(info.value)


# --- Python callables --------------------------------------------------------------


@pytest.mark.parametrize("returned", ["x", None, True, np.array([1.0]), [1.0], 1j])
def test_a_callable_load_that_returns_no_number_is_named(returned):
    def sensor(t):
        return returned if t > 0.01 else 1.0

    block = ls.FrictionBlock(1.0, 0.3, force=sensor)
    with pytest.raises(ValueError) as info:
        ls.simulate(block, 0.1)
    text = str(info.value)
    assert text.startswith("force = <function ") and "sensor" in text, text
    assert f"it returned {returned!r}, not a number [N]" in text
    t_text = text.split("at t = ")[1].split(" s")[0]
    t = float(t_text)
    assert 0.01 <= t <= 0.1 and t_text == f"{t:.4g}"  # (4 significant digits, not repr)
    from helpers.scenes import thesis_scene

    scene = ls.Scene.from_dict(thesis_scene(loads={"axial_force": sensor}))
    with pytest.raises(ValueError, match=r"^loads\.axial_force = <function .*sensor.* is "
                                         r"invalid: at t = .* s it returned .*, not a number "
                                         r"\[N\]"):
        ls.simulate(scene, 0.1)
    speed = ls.Scene.from_dict(thesis_scene(loads={"drive_torque": None, "drive_speed": sensor}))
    with pytest.raises(ValueError, match=r"^loads\.drive_speed = .* not a number \[rad/s\]"):
        ls.simulate(speed, 0.1)


def test_a_callable_load_returns_numbers_of_any_real_type():
    """ints and numpy scalars are numbers; the result equals a float's."""
    def as_float(t):
        return 2.0 if t < 0.5 else -3.0

    reference = ls.simulate(ls.FrictionBlock(1.0, 0.3, force=as_float), 1.0)
    for kind in (int, np.float32, np.int64, np.float64):
        r = ls.simulate(ls.FrictionBlock(1.0, 0.3, force=lambda t: kind(as_float(t))), 1.0)
        np.testing.assert_array_equal(r["u"], reference["u"])


def test_the_core_names_the_load_of_a_callable_returning_nan():
    from helpers.scenes import thesis_scene

    scene = ls.Scene.from_dict(thesis_scene(loads={"axial_force": lambda t: math.nan}))
    with pytest.raises(ls.SimulationError, match=r"<lambda> \(loads\.axial_force\) at 0x.* "
                                                 r"returned nan"):
        ls.simulate(scene, 0.1)


def test_a_scene_keeps_the_callable_it_was_given():
    from helpers.scenes import thesis_scene

    def force(t):
        return -10.0

    scene = ls.Scene.from_dict(thesis_scene(loads={"axial_force": force}))
    assert scene["loads"]["axial_force"] is force
    assert ls.simulate(scene, 0.05)["axial_force"][-1] == -10.0


def test_velocity_loads_carry_their_unit_where_the_key_takes_a_velocity():
    """(A new user's trial: Sine("2 mm/s", "5 Hz"), Table, Constant and
    Measured(unit="m/s") were refused as no load's unit, while
    FrictionBlock(transverse_velocity="2 mm/s") took the string.) A velocity
    load is in SI, drives a transverse slip as the number does, and is refused
    by a key of another dimension, naming both."""
    sine = ls.Sine("2 mm/s", "5 Hz")
    assert sine.amplitude == 2e-3 and sine.unit == "m/s"
    assert ls.Constant("2 mm/s")(0.3) == 2e-3
    assert ls.Table([0, 1], ["0 mm/s", "2 mm/s"])(0.5) == pytest.approx(1e-3, rel=1e-15)
    assert ls.Measured([0.0, 1.0], [0.0, 2.0], unit="mm/s")(1.0) == pytest.approx(2e-3, rel=1e-15)
    with_unit = ls.simulate(ls.FrictionBlock(mass=1.0, mu=0.3, force=1.0,
                                             transverse_velocity=sine), 0.2)
    plain = ls.simulate(ls.FrictionBlock(mass=1.0, mu=0.3, force=1.0,
                                         transverse_velocity=ls.Sine(2e-3, 10 * math.pi)), 0.2)
    np.testing.assert_array_equal(with_unit["u"], plain["u"])
    with pytest.raises(ValueError, match=r"loads\.axial_force = Sine\(.*\) is invalid: its "
                                         r"values are a velocity \(m/s\), not a force \(N\)"):
        ls.scenes.load("default").replace(loads={"axial_force": sine})
