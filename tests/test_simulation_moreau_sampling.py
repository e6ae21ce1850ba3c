"""Moreau-Jean's sampled output (cpp/src/integrate/moreau.cpp): a run with
output times computes the channels only at the ends of the steps its rows
interpolate between, so its rows must be the every-step run's rows
interpolated linearly between the step ends, bit for bit (the same formula,
prev + s (next - prev) with s = (t_out - t_k) / (t_k+1 - t_k)). Drives with
a penalty flank, an exact flank and exact stops, a DC motor's element
channels, and the friction block."""

import numpy as np
import pytest

import leadscrew as ls

T_END = 0.01
DT = 5e-6
# Output times on step ends, between them, two within one step, the last
# step's end, and the start.
T_OUT = [0.0, 1.3e-6, 0.002, 0.0041234, 0.005, 0.0050000001, 0.0099999, T_END]


def drive(play, stops=None, motor=None):
    d = {"concept": "flexible_nut", "thread": {"pitch": 0.004, "mean_diameter": 0.016},
         "friction": {"mu": 0.15}, "load": {"mass": 0.5},
         "loads": {"axial_force": {"type": "sine", "amplitude": 40.0, "omega": 900.0,
                                   "offset": 10.0},
                   "drive_torque": {"type": "sine", "amplitude": 0.3, "omega": 600.0}},
         "backlash": play}
    if stops:
        d["end_stops"] = stops
    if motor:
        del d["loads"]["drive_torque"]
        d["motor"] = motor
    return ls.Scene(d)


SCENES = {
    "bistop": drive({"axial": 1e-4, "contact": "bistop", "stiffness": 1e8}),
    "exact play, exact stop": drive({"axial": 1e-4, "contact": "exact", "restitution": 0.5},
                                    {"upper": 2e-5, "contact": "exact", "restitution": 0.3}),
    "bistop, penalty stops, dc motor": drive(
        {"axial": 1e-4, "contact": "bistop", "stiffness": 1e8},
        {"upper": 2e-5, "lower": -2e-5, "contact": "penalty", "stiffness": 1e7,
         "damping": 100.0},
        {"type": "dc", "voltage": {"type": "sine", "amplitude": 6.0, "omega": 600.0},
         "resistance": 1.0, "inductance": 5e-4, "torque_constant": 0.03,
         "current_limit": 2.0}),
}


def interpolated(steps, t_out):
    """The every-step run's rows at t_out, as simulate_moreau interpolates:
    between the ends of the step that reaches t_out first."""
    t = np.asarray(steps.t)
    rows = {}
    for name in steps.channels:
        values = np.asarray(steps[name], dtype=float)
        column = []
        for time in t_out:
            k = int(np.searchsorted(t, time, side="left"))  # first step end >= time
            if k == 0:
                column.append(values[0])
                continue
            s = (time - t[k - 1]) / (t[k] - t[k - 1])
            column.append(values[k - 1] + s * (values[k] - values[k - 1]))
        rows[name] = np.array(column)
    return rows


@pytest.mark.parametrize("name", list(SCENES))
def test_sampled_rows_are_the_step_rows_interpolated(name):
    scene = SCENES[name]
    steps = ls.simulate(scene, T_END, integrator="moreau", dt=DT, t_eval="steps")
    sampled = ls.simulate(scene, T_END, integrator="moreau", dt=DT, t_eval=T_OUT)
    assert np.array_equal(np.asarray(sampled.t), np.asarray(T_OUT))
    expected = interpolated(steps, T_OUT)
    assert list(sampled.channels) == list(steps.channels)
    for channel in steps.channels:
        assert np.array_equal(np.asarray(sampled[channel], dtype=float), expected[channel],
                              equal_nan=True), channel


def test_sampled_block_rows_are_the_step_rows_interpolated():
    block = ls.FrictionBlock(1.0, 0.3, g=10.0, force=ls.Sine(4.0, 4 * np.pi))
    steps = ls.simulate(block, 0.5, integrator="moreau", dt=1e-4, t_eval="steps")
    t_out = [0.0, 0.00123, 0.2, 0.3000001, 0.5]
    sampled = ls.simulate(block, 0.5, integrator="moreau", dt=1e-4, t_eval=t_out)
    expected = interpolated(steps, t_out)
    for channel in steps.channels:
        assert np.array_equal(np.asarray(sampled[channel], dtype=float), expected[channel],
                              equal_nan=True), channel
