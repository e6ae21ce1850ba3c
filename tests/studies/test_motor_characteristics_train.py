"""leadscrew.studies.motor_characteristics through the train's friction
stages (docs/physics/gear.md, "Friction stages"): a lossy or worm stage and
the motor's own friction on the rigid drive without play, simulated beside
the study's closed form and against tests/helpers/train_reference.py."""

import math

import pytest

import leadscrew as ls
from helpers import dc_motor_reference
from helpers import train_reference as reference
from helpers.scenes import thesis_scene

R, KT, L, U = 2.0, 0.05, 1e-3, 3.0
RATIO, T_C = 4.0, 2e-3
STAGES = [
    {"type": "lossy", "ratio": RATIO, "efficiency": 0.7, "efficiency_backdrive": 0.4},
    {"type": "worm", "ratio": RATIO, "lead_angle": 0.3, "mu": 0.05, "mu_static": 0.07},
]


def scene_with(gear, friction_torque=T_C, mu=0.3):
    d = thesis_scene(loads={"axial_force": 0.0}, gear=gear, friction={"law": "coulomb", "mu": mu},
                     motor={"type": "dc", "voltage": U, "resistance": R, "inductance": L,
                            "torque_constant": KT, "friction_torque": friction_torque})
    d["loads"].pop("drive_torque")
    return ls.Scene.from_dict(d)


def stage_efficiencies(gear, static=False):
    if gear["type"] == "lossy":
        return gear["efficiency"], gear["efficiency_backdrive"]
    mu = gear["mu_static"] if static else gear["mu"]
    return reference.worm_efficiencies(gear["lead_angle"], mu, math.radians(40.0))


@pytest.mark.parametrize("gear", STAGES)
def test_raising_through_the_stage_matches_both_closed_forms(gear):
    """Raising: the study's closed form (T = F r tan(alpha + rho') / (n eta) + T_c)
    equals the reference's steady state to round-off and the simulation to
    1e-6; the stall load from rest is (k_t U / R - T_c) n eta_static /
    (r tan(alpha + rho'))."""
    scene = scene_with(gear)
    frame = ls.studies.motor_characteristics(scene, [2.0, 10.0, 200.0], t_end=2.0,
                                             progress=False)
    assert frame["error"].isna().all()
    drive = dc_motor_reference.rigid_drive(scene.to_dict(), scene.derived())
    eta, eta_b = stage_efficiencies(gear)
    eta_s, _ = stage_efficiencies(gear, static=True)
    stall_load = (KT * U / R - T_C) * RATIO * eta_s / ls.raise_torque(scene.thread, 0.3, 1.0)
    assert frame.attrs["summary"]["stall_load"] == pytest.approx(stall_load, rel=1e-12)
    for row in frame.itertuples():
        if row.load > stall_load:
            assert row.stalled and row.speed == 0.0
            continue
        torque = reference.steady_rotor_torque(drive, RATIO, row.load, 1, T_C, eta, eta_b)
        current = torque / KT
        omega = (U - R * current) / KT
        assert row.mode == "raising"
        assert row.current_closed_form == pytest.approx(current, rel=1e-12)
        assert row.speed_closed_form == pytest.approx(omega, rel=1e-12)
        assert row.current == pytest.approx(current, rel=1e-6)
        assert row.speed == pytest.approx(omega, rel=1e-6)
        assert row.efficiency == pytest.approx(row.efficiency_closed_form, rel=1e-6)


@pytest.mark.parametrize("gear", STAGES)
def test_back_driven_through_the_stage(gear):
    """A thread the load back-drives (mu = 0.005) behind a stage that passes
    power back: beyond the back-drive load the load turns the rotor against
    the voltage at the steady state T = eta_b T_d / n - T_c."""
    scene = scene_with(gear, mu=0.005)
    summary_frame = ls.studies.motor_characteristics(scene, [1.0], t_end=0.2, progress=False)
    back_drive_load = summary_frame.attrs["summary"]["back_drive_load"]
    assert math.isfinite(back_drive_load)
    load = 3.0 * back_drive_load
    frame = ls.studies.motor_characteristics(scene, [load], t_end=2.0, progress=False)
    row = frame.iloc[0]
    assert row["mode"] == "back_driven"
    drive = dc_motor_reference.rigid_drive(scene.to_dict(), scene.derived())
    eta, eta_b = stage_efficiencies(gear)
    torque = reference.steady_rotor_torque(drive, RATIO, load, -1, T_C, eta, eta_b)
    current = torque / KT
    assert row["current_closed_form"] == pytest.approx(current, rel=1e-12)
    assert row["current"] == pytest.approx(current, rel=1e-6)
    assert row["speed"] == pytest.approx((U - R * current) / KT, rel=1e-6)


def test_a_self_locking_stage_is_never_back_driven():
    """eta_b <= 0: the lowering load cannot turn the rotor (back_drive_load
    inf), whatever the thread."""
    gear = {"type": "lossy", "ratio": RATIO, "efficiency": 0.7, "efficiency_backdrive": -0.2}
    frame = ls.studies.motor_characteristics(scene_with(gear, mu=0.005), [5.0], t_end=0.2,
                                             progress=False)
    assert frame.attrs["summary"]["back_drive_load"] == math.inf
