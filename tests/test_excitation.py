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
