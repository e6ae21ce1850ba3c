"""The DC motor's driver and armature on both schemes (issue 31; docs/physics/
dc_motor.md): drive_torque = k_t i at every row (reproduction 5)."""

import numpy as np
import pytest

import leadscrew as ls

# Reproduction 5: a sine voltage on an inductance-free motor: i(0) = U(0) / R =
# 3 V / 2 Ohm = 1.5 A, drive_torque(0) = k_t i = 0.075 N m.
SINE = {"concept": "rigid", "thread": {"pitch": 0.002, "mean_diameter": 0.012},
        "friction": {"law": "coulomb", "mu": 0.1}, "load": {"mass": 1.0},
        "loads": {"axial_force": -10.0},
        "motor": {"type": "dc", "voltage": {"type": "sine", "amplitude": 12.0, "omega": 300.0,
                                            "offset": 3.0},
                  "resistance": 2.0, "inductance": 0.0, "torque_constant": 0.05}}


@pytest.mark.parametrize("inductance", [0.0, 1e-3])
@pytest.mark.parametrize("options", [{}, {"integrator": "moreau", "dt": 1e-4}])
def test_drive_torque_is_the_motors_torque_at_every_row(inductance, options):
    scene = ls.Scene.from_dict({**SINE, "motor": {**SINE["motor"], "inductance": inductance}})
    result = ls.simulate(scene, 0.02, **options)
    np.testing.assert_allclose(result["drive_torque"], 0.05 * result["motor_current"],
                               rtol=1e-12, atol=1e-15)
    if inductance == 0.0:
        assert result["motor_current"][0] == pytest.approx(1.5, rel=1e-12)
        assert result["drive_torque"][0] == pytest.approx(0.075, rel=1e-12)


@pytest.mark.parametrize("options", [{}, {"integrator": "moreau", "dt": 1e-4}])
def test_a_torque_driven_rotor_reports_its_torque_from_row_0(options):
    torque_driven = {key: value for key, value in SINE.items() if key != "motor"}
    torque_driven["loads"] = {"axial_force": -10.0, "drive_torque": 0.05}
    scene = ls.Scene.from_dict(torque_driven)
    result = ls.simulate(scene, 0.02, **options)
    np.testing.assert_allclose(result["drive_torque"], 0.05, rtol=1e-15)
    # Moreau-Jean's account still books the torque's work over each step.
    assert result["work_drive"][-1] == pytest.approx(0.05 * result["phi_drive"][-1], rel=1e-12)
