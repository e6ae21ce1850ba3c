"""Scenes shared by the tests: the thesis's Table 5.1 drive (masses chosen from
the geometry, see python/leadscrew/scene.py defaults) and variants."""

import math

THESIS_THREAD = {"pitch": 1e-3, "mean_diameter": 20e-3}  # s = 1 mm, r_m = 10 mm


def thesis_scene(**changes):
    """Table 5.1 with load case eq. (5.1): F = -10 N, M = -40 sin(4 pi t) N mm, mu = 0.3."""
    d = {
        "concept": "rigid",
        "drive": "screw",
        "thread": dict(THESIS_THREAD),
        "friction": {"law": "coulomb", "mu": 0.3},
        "screw": {"radius": 10e-3, "length": 0.5, "youngs_modulus": 210e9},
        "nut": {"outer_radius": 12e-3, "length": 20e-3, "youngs_modulus": 2e9,
                "position": 0.1},
        "rotor": {"inertia": 1e-5},
        "load": {"mass": 1.0},
        "loads": {
            "drive_torque": {"type": "sine", "amplitude": -40e-3, "omega": 4 * math.pi},
            "axial_force": -10.0,
        },
    }
    for key, value in changes.items():
        if isinstance(value, dict) and isinstance(d.get(key), dict):
            d[key] = {**d[key], **value}
        elif value is None:
            d.pop(key, None)
        else:
            d[key] = value
    return d
