"""The bearing friction of a torque-driven rotor (issue 33): motor.friction_torque
in a motor section without a type, beside loads.drive_torque, on both schemes
(docs/physics/gear.md, "Friction stages"). Against the closed form of the
breakaway from rest: the thread with mu (thesis Table 5.1, self-locking at
mu = 0.3) raises the axial force F where the drive torque exceeds the raise
torque F r_m tan(alpha + rho') (leadscrew.raise_torque) plus the motor's
friction T_c; below, the drive stays at rest."""

import numpy as np
import pytest

import leadscrew as ls
from helpers.scenes import thesis_scene

F, T_C = 10.0, 5e-3  # [N] against the raising motion, [N m]
SCHEMES = [{}, {"integrator": "moreau", "dt": 1e-4}]


def rotor_scene(torque, friction_torque=T_C):
    return ls.Scene.from_dict(thesis_scene(loads={"drive_torque": torque, "axial_force": F},
                                           motor={"friction_torque": friction_torque}))


def breakaway_torque():
    """The rotor's torque that starts raising F from rest: T_c + the raise torque."""
    scene = rotor_scene(0.01)
    return T_C + ls.raise_torque(scene.thread, 0.3, F)


@pytest.mark.parametrize("options", SCHEMES)
def test_a_torque_below_the_breakaway_leaves_the_drive_at_rest(options):
    result = ls.simulate(rotor_scene(0.98 * breakaway_torque()), 0.05, **options)
    np.testing.assert_array_equal(result["phi_drive"], 0.0)
    np.testing.assert_array_equal(result["motor_friction_loss"], 0.0)


@pytest.mark.parametrize("options", SCHEMES)
def test_a_torque_above_the_breakaway_raises_the_load_against_the_motors_friction(options):
    torque = 1.02 * breakaway_torque()
    result = ls.simulate(rotor_scene(torque), 0.05, **options)
    assert result["phi_drive"][-1] > 0.0 and np.all(np.diff(result["phi_drive"]) >= 0.0)
    assert result["v_load"][-1] < 0.0  # raised: along -x against F
    np.testing.assert_allclose(result["drive_torque"], torque, rtol=1e-15)
    # The friction's loss T_c |phi| (Moreau-Jean books it at each step's end
    # speed: first order in dt).
    loss = T_C * result["phi_drive"][-1]
    assert result["motor_friction_loss"][-1] == pytest.approx(
        loss, rel=1e-9 if not options else 1e-2)
    assert result["work_drive"][-1] == pytest.approx(torque * result["phi_drive"][-1],
                                                     rel=1e-9)
    # Without the motor's friction the same torque accelerates the drive more.
    free = ls.simulate(rotor_scene(torque, 0.0), 0.05, **options)
    assert free["phi_drive"][-1] > result["phi_drive"][-1]


def test_the_section_without_a_type_takes_only_the_friction():
    scene = rotor_scene(0.01)
    assert scene.to_dict()["motor"] == {"friction_torque": T_C}
    assert scene.model().parameters.motor_friction_torque == T_C
    assert not scene.model().parameters.dc_motor
    with pytest.raises(ValueError, match=r"motor\.type is missing: motor\.voltage = 3\.0 is a "
                                         r"DC motor's"):
        ls.Scene.from_dict(thesis_scene(motor={"voltage": 3.0, "friction_torque": T_C}))
