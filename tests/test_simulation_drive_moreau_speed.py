"""Moreau-Jean's speed-controlled rotor: each step ends at the prescribed
speed, so the rotor turns by h omega_theta and the drive's work is h T
omega_theta (issue 31: a case of the drive-train fuzz at 4a12346)."""

import numpy as np
import pytest

import leadscrew as ls


# A case of the drive-train fuzz: a rigid, nut-driven drive with exact play,
# its rotor held at rest (drive_speed 0) under a load of -1.2 N. Moreau-Jean's
# step took the rotor's end speed from its solve, round-off apart from the
# prescribed 0: the rotor's angle crept by 2e-21 rad and the drive's work
# took 7e-19 J, of either sign, where the rows (the state's prescribed speed)
# give a rotor at rest that does no work.
HELD = {"concept": "rigid", "drive": "nut",
        "thread": {"pitch": 0.01730878228605096, "mean_diameter": 0.051483189894070795,
                   "flank_angle": 0.475498678122824, "hand": "right"},
        "friction": {"law": "coulomb", "mu": 0.6739278895542882},
        "backlash": {"axial": 0.00038805950628653354, "contact": "exact",
                     "restitution": 0.6880872746519744},
        "screw": {"radius": 0.017320976112611255, "length": 0.10892173690043272,
                  "youngs_modulus": 19218061842.31475},
        "nut": {"outer_radius": 0.03099967440308308, "length": 0.005675165871019201,
                "youngs_modulus": 37930462426.62511, "position": 0.09601378979302301},
        "rotor": {"inertia": 3.82754648958519e-05}, "load": {"mass": 0.21774646726287003},
        "loads": {"axial_force": {"type": "constant", "value": -1.200288806263863},
                  "drive_speed": 0.0}}


@pytest.mark.parametrize("speed", [0.0, {"type": "sine", "amplitude": 30.0, "omega": 200.0}])
def test_moreaus_speed_controlled_rotor_turns_at_its_prescribed_speed(speed):
    """A speed-controlled rotor ends each Moreau-Jean step at its prescribed
    speed (the constraint's value): it turns by h omega_theta, omega_theta =
    (1 - theta) omega_k + theta omega_k+1 of the rows, and the drive's work is
    its impulse h T times omega_theta (docs/physics/result_checks.md,
    "Moreau-Jean time stepping"); a rotor held at 0 neither turns nor works."""
    scene = ls.Scene.from_dict({**HELD, "loads": {**HELD["loads"], "drive_speed": speed}})
    r = ls.simulate(scene, 0.03, integrator="moreau", dt=2.5e-6, t_eval="steps")
    omega, torque, h = r["omega_drive"], r["drive_torque"], np.diff(r.t)
    omega_theta = 0.5 * (omega[:-1] + omega[1:])
    if speed == 0.0:
        assert np.max(np.abs(torque)) > 0  # (the rotor holds the load)
        np.testing.assert_array_equal(r["phi_drive"], r["phi_drive"][0])
        np.testing.assert_array_equal(r["work_drive"], 0.0)
    else:
        np.testing.assert_allclose(np.diff(r["phi_drive"]), h * omega_theta, rtol=1e-12,
                                   atol=1e-15 * np.max(np.abs(r["phi_drive"])))
        work = h * torque[1:] * omega_theta
        np.testing.assert_allclose(np.diff(r["work_drive"]), work, rtol=1e-12,
                                   atol=1e-15 * np.max(np.abs(r["work_drive"])))
