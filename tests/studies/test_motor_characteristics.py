"""leadscrew.studies.motor_characteristics (issue 19, item 5): the DC motor's
steady speed, current, input power and efficiency against the load, simulated
beside the closed form, the stall load, its figure and the command line."""

import json
import math

import numpy as np
import pandas as pd
import pytest

import leadscrew as ls
from helpers import dc_motor_reference as reference
from helpers.scenes import thesis_scene
from leadscrew import cli

R, KT, L, U = 2.0, 0.05, 1e-3, 3.0
LOADS = [2.0, 10.0, 30.0]  # [N]: the last one beyond the stall load
# t_end = 2 s in the closed-form test: 28 mechanical time constants J R / (k_t k_e) = 58 ms
# before the window (0.8 t_end), whose efficiency the start-up would shift by 1e-6 at 1 s.


def motor_scene(concept="rigid", **motor):
    d = thesis_scene(concept=concept, loads={"axial_force": 0.0},
                     motor={"type": "dc", "voltage": U, "resistance": R, "inductance": L,
                            "torque_constant": KT, **motor})
    d["loads"].pop("drive_torque")
    return d


@pytest.mark.parametrize("limit", [None, 1.0])
def test_rigid_drive_matches_the_closed_form(limit):
    scene = ls.Scene.from_dict(motor_scene(**({"current_limit": limit} if limit else {})))
    frame = ls.studies.motor_characteristics(scene, LOADS, t_end=2.0, progress=False)
    assert frame["error"].isna().all()
    drive = reference.rigid_drive(scene.to_dict(), scene.derived())
    stall_current = U / R if limit is None else limit
    stall_load = KT * stall_current / ls.raise_torque(scene.thread, 0.3, 1.0)
    assert frame.attrs["summary"]["stall_load"] == pytest.approx(stall_load, rel=1e-12)
    assert frame.attrs["summary"]["stall_torque"] == pytest.approx(KT * stall_current, rel=1e-12)
    for row in frame.itertuples():
        if row.load < stall_load:
            # The helper's steady state, from the rigid drive's slip mode
            # (the axial force against the motion: +load for a right-hand screw).
            current, omega, _ = reference.steady_state(drive, row.load, U, R, KT, KT)
            assert not row.stalled
            assert row.current_closed_form == pytest.approx(current, rel=1e-12)
            assert row.speed_closed_form == pytest.approx(omega, rel=1e-12)
            assert row.current == pytest.approx(current, rel=1e-6)
            assert row.speed == pytest.approx(omega, rel=1e-6)
            assert row.input_power == pytest.approx(U * current, rel=1e-6)
            efficiency = row.load * 1e-3 / (2 * math.pi) * omega / (U * current)
            assert row.efficiency_closed_form == pytest.approx(efficiency, rel=1e-12)
            assert row.efficiency == pytest.approx(efficiency, rel=1e-6)
            assert row.window_change < 1e-5
        else:
            assert row.stalled
            assert row.speed == 0.0 and row.speed_closed_form == 0.0
            assert row.current == pytest.approx(stall_current, rel=1e-9)
            assert row.input_power == pytest.approx(R * stall_current ** 2, rel=1e-6)
            assert row.efficiency == 0.0


def test_flexible_concept_reaches_the_same_steady_state():
    scene = ls.Scene.from_dict(motor_scene(concept="flexible_nut"))
    frame = ls.studies.motor_characteristics(scene, [10.0], t_end=1.0, progress=False)
    row = frame.iloc[0]
    assert row["error"] is None
    assert row["speed"] == pytest.approx(row["speed_closed_form"], rel=1e-5)
    assert row["current"] == pytest.approx(row["current_closed_form"], rel=1e-5)


def test_units_and_plot():
    frame = ls.studies.motor_characteristics(motor_scene(), [5.0, 30.0], t_end=0.5,
                                             progress=False)
    units = frame.attrs["units"]
    assert units["speed"] == "rad/s" and units["current"] == "A"
    assert units["input_power"] == "W" and units["efficiency"] == "1"
    from matplotlib.figure import Figure

    ax = ls.studies.plot_motor_characteristics(frame, ax=Figure().subplots())
    assert "stall load" in " ".join(t.get_text() for t in ax.get_legend().get_texts())


def test_the_figure_draws_the_closed_form_over_a_fine_grid_with_the_legend_off_the_data():
    """The closed form's lines jump at the stall load (mu_static > mu: the
    breakaway from rest fails while a moving drive would still turn at about
    half its no-load speed), not a slope between the sampled loads; the
    legend lies outside the axes."""
    from matplotlib.figure import Figure

    d = motor_scene()
    d["friction"] = {**d["friction"], "mu": 0.15, "mu_static": 0.3}
    frame = ls.studies.motor_characteristics(d, [5.0, 30.0], t_end=0.2, progress=False)
    stall = frame.attrs["summary"]["stall_load"]
    figure = Figure(figsize=(8.0, 5.0), layout="constrained")
    ax = ls.studies.plot_motor_characteristics(frame, ax=figure.subplots())
    line = next(line for line in ax.get_lines() if line.get_label() == "speed (closed form)")
    load, speed = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
    assert len(load) > 100 and load.max() >= 30.0
    below, at = np.searchsorted(load, stall) - 1, np.searchsorted(load, stall)
    assert load[at] == stall and stall - load[below] < 1e-9 * stall
    no_load = U / KT
    assert speed[0] == pytest.approx(no_load, rel=1e-12)
    assert speed[below] > 0.4 * no_load and speed[at] == 0.0
    assert np.all(np.diff(speed[:below + 1]) < 0.0)
    figure.canvas.draw()
    legend = ax.get_legend().get_window_extent()
    assert not legend.overlaps(ax.get_window_extent())
    # The efficiency on its own 0..1 scale (autoscaled, its curve hid the speed's).
    twin = next(other for other in figure.axes
                if any(line.get_label() == "efficiency (closed form)" for line in other.get_lines()))
    assert twin.get_ylim() == (0.0, 1.0)


@pytest.mark.parametrize("change, kwargs, match", [
    ({"motor": None}, {}, r"scene has no DC motor"),
    ({"motor": {"voltage": {"type": "sine", "amplitude": 3.0, "omega": 1.0}}}, {},
     r"motor\.voltage = .* must be a constant voltage"),
    ({}, {"loads": [-1.0]}, r"loads"),
    ({}, {"t_end": 0.0}, r"t_end"),
    ({}, {"window": (0.5, 0.2)}, r"window"),
])
def test_bad_arguments(change, kwargs, match):
    scene = ls.Scene.from_dict(motor_scene())
    if change:
        scene = scene.replace(**change)
    arguments = {"loads": [5.0], "progress": False, **kwargs}
    with pytest.raises(ValueError, match=match):
        ls.studies.motor_characteristics(scene, **arguments)


def test_command_line_writes_the_table_and_figure(tmp_path, capsys):
    path = tmp_path / "motor.toml"
    ls.Scene.from_dict(motor_scene()).to_toml(path)
    code = cli.main(["study", "motor_characteristics", str(path), "loads=5,30", "t_end=0.5",
                     "progress=false", "-o", str(tmp_path)])
    out, err = capsys.readouterr()
    assert code == 0 and err == "", err
    stem = tmp_path / "motor_characteristics_motor"
    frame = pd.read_csv(stem.with_suffix(".csv"), skiprows=[1])
    assert list(frame["load"]) == [5.0, 30.0]
    assert stem.with_suffix(".png").stat().st_size > 10_000
    summary = json.loads(stem.with_suffix(".summary.json").read_text())
    assert summary["stall_load"] > 5.0
    assert np.isfinite(frame["speed"]).all()


@pytest.mark.parametrize("drive", ["screw", "nut"])
@pytest.mark.parametrize("hand", ["right", "left"])
@pytest.mark.parametrize("voltage", [U, -U])
def test_every_drive_hand_and_voltage_sign_raises_the_load(drive, hand, voltage):
    """The load to raise acts against the motion the voltage drives, whichever
    part turns and whichever the hand: the same steady state, mirrored."""
    d = motor_scene(voltage=voltage)
    d["drive"] = drive
    d["thread"] = {**d["thread"], "hand": hand}
    d["nut"] = {**d["nut"], "position": 0.25}
    row = ls.studies.motor_characteristics(d, [10.0], t_end=2.0, progress=False).iloc[0]
    assert row["error"] is None and not row["stalled"]
    assert math.copysign(1.0, row["speed"]) == math.copysign(1.0, voltage)
    assert row["speed"] == pytest.approx(row["speed_closed_form"], rel=1e-6)
    assert row["current"] == pytest.approx(row["current_closed_form"], rel=1e-6)
    assert row["efficiency"] == pytest.approx(row["efficiency_closed_form"], rel=1e-6)
    assert row["efficiency"] > 0.0


def test_the_batch_varies_the_motor_and_refuses_what_it_would_ignore():
    from leadscrew.studies._batch import DriveBatch

    scene = ls.Scene.from_dict(motor_scene())
    batch = DriveBatch(scene, ("motor_resistance", "axial_force"), ("omega_drive",), 2.0, [2.0])
    samples, errors, _ = batch.run(np.array([[R, 10.0], [2 * R, 10.0]]), 1)
    assert not any(errors)
    drive = reference.rigid_drive(scene.to_dict(), scene.derived())
    for resistance, omega in zip((R, 2 * R), samples[:, 0, 0]):
        expected = reference.steady_state(drive, 10.0, U, resistance, KT, KT)[1]
        assert omega == pytest.approx(expected, rel=1e-6)
    for name in ("drive_torque", "drive_speed"):
        with pytest.raises(ValueError, match=rf"\"{name}\" is invalid for a drive with a DC motor"):
            DriveBatch(scene, (name,), ("motor_current",), 0.1, [0.1])
    with pytest.raises(ValueError, match=r"\"motor_resistance\" is invalid for a drive without"):
        DriveBatch(ls.Scene.from_dict(thesis_scene()), ("motor_resistance",), ("u_load",), 0.1,
                   [0.1])


def _friction_torque_per_newton(scene, mu, sign):
    """r_m tan(alpha + sign rho') [m], rho' = atan(mu / cos(beta / 2)): the
    torque per newton to raise (+1) or to hold a lowering load (-1, the
    negative lower torque) on the thesis thread (flank angle 0 unless given)."""
    thread = scene["thread"]
    radius = thread["mean_diameter"] / 2
    alpha = math.atan(thread["pitch"] * thread.get("starts", 1) / (2 * math.pi * radius))
    rho = math.atan(mu / math.cos(thread.get("flank_angle", 0.0) / 2))
    return radius * math.tan(alpha + sign * rho)


def _run_at(voltage, d, loads, t_end):
    """The study's frame without errors and the stall torque k_t U / R [N m]."""
    frame = ls.studies.motor_characteristics(d, loads, t_end=t_end, progress=False)
    assert frame["error"].isna().all()
    return frame, frame.attrs["summary"], KT * voltage / R


def test_a_back_drivable_thread_is_raised_held_or_back_driven():
    """tan(alpha) = 0.35 > mu' = 0.05: below the stall load the motor raises the
    load, up to the back-drive load it holds it at rest, beyond that the load
    drives the rotor backwards at i = T / k_t > U / R (T the torque holding the
    lowering load), which the closed form gives (not a stall); the efficiency
    is NaN there (the load gives power)."""
    voltage = 12.0
    d = motor_scene(voltage=voltage)
    d["thread"] = {**d["thread"], "pitch": 10e-3, "mean_diameter": 9e-3}
    d["friction"] = {**d["friction"], "mu": 0.05}
    # raised along -x at 0.15 m/s, back-driven along +x at 0.3 m/s: room for both
    d["nut"] = {**d["nut"], "position": 0.18}
    scene = ls.Scene.from_dict(d)
    frame, summary, stall_torque = _run_at(voltage, scene, [100.0, 200.0, 400.0], 0.9)
    assert summary["stall_load"] == pytest.approx(
        stall_torque / _friction_torque_per_newton(d, 0.05, 1), rel=1e-12)
    assert summary["back_drive_load"] == pytest.approx(
        stall_torque / _friction_torque_per_newton(d, 0.05, -1), rel=1e-12)
    assert summary["stall_load"] < 200.0 < summary["back_drive_load"] < 400.0
    drive = reference.rigid_drive(scene.to_dict(), scene.derived())
    raised, held, lowered = frame.itertuples()
    assert list(frame["mode"]) == ["raising", "stalled", "back_driven"]
    assert list(frame["stalled"]) == [False, True, False]
    current, omega, _ = reference.steady_state(drive, 100.0, voltage, R, KT, KT)
    assert raised.speed_closed_form == pytest.approx(omega, rel=1e-12) and omega > 0.0
    assert raised.speed == pytest.approx(omega, rel=1e-6)
    # (over the window: the start-up's tail shifts the mean by 3e-6)
    assert raised.efficiency == pytest.approx(raised.efficiency_closed_form, rel=1e-5)
    assert held.speed == 0.0 and held.speed_closed_form == 0.0
    assert held.current == pytest.approx(voltage / R, rel=1e-7)
    assert held.efficiency == 0.0 and held.efficiency_closed_form == 0.0
    current, omega, _ = reference.steady_state(drive, 400.0, voltage, R, KT, KT, direction=-1.0)
    assert omega < 0.0 and current > voltage / R
    assert lowered.speed_closed_form == pytest.approx(omega, rel=1e-12)
    assert lowered.current_closed_form == pytest.approx(current, rel=1e-12)
    assert lowered.input_power_closed_form == pytest.approx(voltage * current, rel=1e-12)
    assert lowered.speed == pytest.approx(omega, rel=1e-6)
    assert lowered.current == pytest.approx(current, rel=1e-6)
    assert lowered.window_change < 1e-5
    assert math.isnan(lowered.efficiency) and math.isnan(lowered.efficiency_closed_form)


def test_a_load_back_driving_beyond_the_current_limit_saturates_the_driver():
    """The back-drivable thread under 400 N with i_max = U / R = 6 A: holding
    the lowering load takes i = T / k_t > i_max, so the driver holds 6 A
    while the load speeds the rotor up, until the hold voltage R i_max +
    k_e omega passes -U; then it saturates at -U (its supply, reversed
    against the current) and the load settles where (-U - k_e omega) / R =
    T / k_t: omega = -(U + R T / k_t) / k_e (issue 31: the driver once held
    the limit there with more than its supply; the closed form said the load
    runs away)."""
    voltage = 12.0
    d = motor_scene(voltage=voltage, current_limit=voltage / R)
    d["thread"] = {**d["thread"], "pitch": 10e-3, "mean_diameter": 9e-3}
    d["friction"] = {**d["friction"], "mu": 0.05}
    # (1.1 m/s at the steady -670 rad/s: 5 s of travel on a 20 m screw, thin
    # so that the mechanical time constant J_eff R / (k_t k_e) is 0.06 s)
    d["nut"] = {**d["nut"], "position": 0.18}
    d["screw"] = {**d.get("screw", {}), "length": 20.0, "radius": 4e-3}
    scene = ls.Scene.from_dict(d)
    frame, _, _ = _run_at(voltage, scene, [400.0], 5.0)
    row = frame.iloc[0]
    assert row["mode"] == "back_driven_saturated"
    drive = reference.rigid_drive(scene.to_dict(), scene.derived())
    current = reference.steady_torque(drive, 400.0, direction=-1.0) / KT
    omega = -(voltage + R * current) / KT
    assert current > voltage / R
    assert row["current_closed_form"] == pytest.approx(current, rel=1e-12)
    assert row["speed_closed_form"] == pytest.approx(omega, rel=1e-12)
    assert row["input_power_closed_form"] == pytest.approx(-voltage * current, rel=1e-12)
    assert row["speed"] == pytest.approx(omega, rel=1e-6)
    assert row["current"] == pytest.approx(current, rel=1e-6)


def test_the_stall_from_rest_takes_mu_static():
    """From rest the motor must break the thread free with mu_static: the
    stall load is F_stall = k_t U / R / (r_m tan(alpha + rho_s')); between it
    and the stall load with mu the drive stays at rest (one already moving
    would keep moving)."""
    voltage = 12.0
    d = motor_scene(voltage=voltage)
    d["friction"] = {**d["friction"], "mu": 0.15, "mu_static": 0.3}
    frame, summary, stall_torque = _run_at(voltage, d, [80.0, 150.0], 1.0)
    assert summary["stall_load"] == pytest.approx(
        stall_torque / _friction_torque_per_newton(d, 0.3, 1), rel=1e-12)
    assert summary["stall_load_moving"] == pytest.approx(
        stall_torque / _friction_torque_per_newton(d, 0.15, 1), rel=1e-12)
    assert summary["stall_load"] < 150.0 < summary["stall_load_moving"]
    assert summary["back_drive_load"] == math.inf  # self-locking
    raised, held = frame.itertuples()
    assert raised.mode == "raising" and raised.speed > 0.0
    assert raised.speed == pytest.approx(raised.speed_closed_form, rel=1e-5)
    assert held.mode == "stalled" and held.stalled
    assert held.speed == 0.0 and held.speed_closed_form == 0.0
    assert held.current == pytest.approx(voltage / R, rel=1e-7)
    assert held.current_closed_form == pytest.approx(voltage / R, rel=1e-12)


def test_efficiency_is_the_useful_power_over_the_electrical_input():
    """With k_e != k_t the work_drive channel books (k_t - k_e) i omega beyond
    the electrical input U i: the efficiency is F v / (U i) all the same."""
    d = motor_scene(back_emf_constant=0.04)
    row = ls.studies.motor_characteristics(d, [20.0], t_end=2.0, progress=False).iloc[0]
    assert row["error"] is None and not row["stalled"]
    useful_over_input = 20.0 * abs(row["load_speed"]) / row["input_power"]
    assert row["efficiency"] == pytest.approx(useful_over_input, rel=1e-6)
    assert row["efficiency"] == pytest.approx(row["efficiency_closed_form"], rel=1e-6)
    drive = reference.rigid_drive(ls.Scene.from_dict(d).to_dict(), ls.Scene.from_dict(d).derived())
    current, omega, _ = reference.steady_state(drive, 20.0, U, R, KT, 0.04)
    assert row["efficiency_closed_form"] == pytest.approx(
        20.0 * 1e-3 / (2 * math.pi) * omega / (U * current), rel=1e-12)


def test_a_steady_stall_reads_steady_on_the_flexible_concept():
    """At rest the speed is round-off (~1e-8 rad/s): its change is measured
    against the no-load speed scale, not against itself."""
    frame = ls.studies.motor_characteristics(motor_scene(concept="flexible_nut"), [30.0],
                                             t_end=1.0, progress=False)
    row = frame.iloc[0]
    assert row["error"] is None and row["stalled"]
    assert abs(row["speed"]) < 1e-6 * U / KT
    assert row["window_change"] < 1e-5
    assert row["efficiency"] == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("ratio", [4.0, -4.0])
def test_an_ideal_gear_stage_reflects_the_train_torque_and_speed(ratio):
    # Behind a stage of ratio n the rotor supplies T_d / |n| and turns |n|
    # times the driven part (docs/physics/gear.md): i = F r_m tan(alpha + rho')
    # / (|n| k_t), omega_rotor = (U - R i) / k_e, the load's speed omega lead /
    # (2 pi |n|); a reversing stage raises the load the other way.
    d = motor_scene()
    d["gear"] = {"ratio": ratio}
    scene = ls.Scene.from_dict(d)
    loads = [10.0, 60.0]
    frame = ls.studies.motor_characteristics(scene, loads, t_end=2.0, progress=False)
    assert frame["error"].isna().all()
    for row in frame.itertuples():
        current = ls.raise_torque(scene.thread, 0.3, row.load) / (abs(ratio) * KT)
        omega = (U - R * current) / KT
        assert not row.stalled
        assert row.current_closed_form == pytest.approx(current, rel=1e-12)
        assert row.speed_closed_form == pytest.approx(omega, rel=1e-12)
        assert row.current == pytest.approx(current, rel=1e-6)
        assert row.speed == pytest.approx(omega, rel=1e-6)
        v_load = 1e-3 / (2 * math.pi * abs(ratio)) * omega
        assert abs(row.load_speed) == pytest.approx(v_load, rel=1e-6)
        assert row.efficiency == pytest.approx(row.load * v_load / (U * current), rel=1e-6)
    # The stall load grows with |n| (the rotor's torque is |n| times smaller).
    assert frame.attrs["summary"]["stall_load"] == pytest.approx(
        abs(ratio) * KT * U / R / ls.raise_torque(scene.thread, 0.3, 1.0), rel=1e-12)

