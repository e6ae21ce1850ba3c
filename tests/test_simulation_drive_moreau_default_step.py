"""Moreau-Jean's default step where the drive's stiffness needs a shorter
one (issue 31: the drive-train fuzz's case 8897 at 4a12346).

A flexible drive with a DC motor, its own friction and a lossy stage runs
on Moreau-Jean only (its default). At simulate's default dt = 1e-4 s the
step's iteration matrix W = M + theta h C + theta^2 h^2 K lets the flank's
friction impulse drive its own normal impulse (mu' |G~_NT| / G~_NN >= 1,
moreau_step_check.cpp): a jam of the time discretization that the drive
does not have. The run was refused with a ValueError naming dt, which the
user never set. Now the default is shortened to half the longest step
that resolves the drive; a dt the user gives is still refused.
"""

import pytest

import leadscrew as ls

pytestmark = pytest.mark.usefixtures("every_step")

# The case's scene as the fuzz drew it (a left-hand flexible drive, mu 0.52,
# a 31 kg load, a DC motor at -13.7 V behind a lossy stage of ratio -0.34).
SCENE = {
    "concept": "flexible",
    "thread": {"pitch": 0.007228706476215395, "mean_diameter": 0.027722931081398897,
               "flank_angle": 0.5061454830783556, "hand": "left"},
    "friction": {"law": "coulomb", "mu": 0.5175730179648066},
    "screw": {"radius": 0.01191855389886384, "length": 0.05253365738008195,
              "youngs_modulus": 43412350038.51028, "density": 2577.4131535933843,
              "support": "both_ends"},
    "nut": {"outer_radius": 0.02585132016813518, "length": 0.008907387000307996,
            "youngs_modulus": 3078805129.050934, "position": 0.028214271762098453},
    "rotor": {"inertia": 2.5258325663283644e-05},
    "load": {"mass": 31.002405573329693},
    "motor": {"type": "dc", "voltage": -13.72884377649726,
              "resistance": 0.2997156290601983, "torque_constant": 0.010490516156146571,
              "inductance": 7.0951395429783e-05, "friction_torque": 0.001949080544766039},
    "gear": {"type": "lossy", "ratio": -0.34472216331437805,
             "efficiency": 0.32358828008347146, "efficiency_backdrive": -0.7490546789402162},
}
T_END = 0.058711061589121684


def test_the_default_step_is_shortened_where_the_drive_needs_it():
    scene = ls.Scene.from_dict(SCENE)
    result = ls.simulate(scene, T_END)
    assert result.integrator == "moreau"
    assert result.t[-1] == pytest.approx(T_END, rel=1e-12)
    steps = result.t[1:] - result.t[:-1]
    # every step shorter than the 8.46e-5 s the drive's springs allow at theta 1/2
    assert steps.max() < 8.46e-5
    failed = [name for name, check in result.checks.items()
              if check["applies"] and not check["passed"]]
    assert failed == []


def test_a_step_the_user_gives_is_obeyed_or_refused():
    scene = ls.Scene.from_dict(SCENE)
    with pytest.raises(ValueError, match=r"dt = 0\.0001 is invalid: must be < 8\.4"):
        ls.simulate(scene, T_END, dt=1e-4)
    result = ls.simulate(scene, T_END, dt=4e-5)
    assert (result.t[1:] - result.t[:-1]).max() == pytest.approx(4e-5, rel=1e-9)
