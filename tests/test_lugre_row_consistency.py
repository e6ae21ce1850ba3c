"""LuGre's law at every output row: the reported friction_force,
bristle_deflection, slip_velocity and normal_force satisfy

    F = -|N|' (sigma0 z + sigma1 z') - c v,  z' = v - sigma0 |v| z / g(|v|),

|N|' = |N| / cos(beta / 2), on both schemes (the train fuzz's independent
check, helpers/train_invariants.py's friction_law; its bound 1e-9 of the
force's scale).

Moreau-Jean: a prescribed rotor speed winds a flexible screw up against an
exact end stop (the train fuzz's case 6473, reduced): the normal force
grows to 7e8 N, the step's frictionless slip c to 200 m/s against an end
slip of 1e-8..1e-4 m/s. The end state's slip is the root's c + d P_T only
to the round-off of the step's solve (2e-11 m/s there), and LuGre's slope
near zero slip turned that into 1.3e-6 of the friction between the row's
friction and its slip and bristles; the row now reports the slip of its
friction (moreau_smooth_friction.cpp, "The rows' slip").

Event-driven: the rigid drive held at its closed exact stop. The bristles'
friction at the held zero slip is the law's, -sigma0 z |N|' (z held), not
the set-valued rule's 0 (the stop carrying everything); the clamp is the
raise torque's force with the bristles' coefficient sigma0 |z|, as
Moreau-Jean's (test_moreau_held_bristles.py)."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers import end_stop_reference as reference
from helpers.result_invariants import stribeck_curve
from helpers.train_invariants import check_train
from test_moreau_held_bristles import stop_scene

pytestmark = pytest.mark.usefixtures("every_step")

ROUND_OFF_REL = 1e-9  # (train_invariants.py's bound of the law's error)

WOUND_UP = {
    "concept": "flexible", "drive": "nut",
    "thread": {"pitch": 0.0184, "mean_diameter": 0.0322},
    "friction": {"law": "lugre", "mu": 0.0166, "mu_static": 0.0227,
                 "stribeck_velocity": 0.02, "sigma0": 1.43e6, "sigma1": 7.49},
    "screw": {"radius": 0.0154, "length": 0.0828, "youngs_modulus": 8.8e10},
    "nut": {"outer_radius": 0.0272, "length": 0.00607, "youngs_modulus": 3.88e10,
            "position": 0.0183},
    "rotor": {"inertia": 2.18e-7}, "load": {"mass": 22.1},
    "loads": {"drive_speed": -200.0}, "gear": {"type": "ideal", "ratio": 0.4545},
    "end_stops": {"contact": "exact", "lower": -0.00345, "upper": 1.36e-5},
}


def law_error(result, scene):
    """|friction_force - LuGre's law at the row's channels| [N] per row."""
    friction = scene["friction"]
    sigma0, sigma1 = friction["sigma0"], friction.get("sigma1") or 0.0
    z, slip = result["bristle_deflection"], result["slip_velocity"]
    rate = slip - sigma0 * np.abs(slip) * z / stribeck_curve(friction, np.abs(slip))
    loaded = np.abs(result["normal_force"]) / math.cos(scene["thread"]["flank_angle"] / 2)
    return np.abs(result["friction_force"] + loaded * (sigma0 * z + sigma1 * rate))


@pytest.mark.parametrize("speed", [-200.0, -44.5])
def test_a_wound_up_screw_at_its_stop_reports_the_law_at_every_moreau_row(speed):
    scene = ls.Scene.from_dict({**WOUND_UP, "loads": {"drive_speed": speed}})
    t_end = 0.02 if speed == -200.0 else 0.06
    result = ls.simulate(scene, t_end, integrator="moreau", dt=7.3e-6)
    assert [k for k, c in result.checks.items() if c["applies"] and not c["passed"]] == []
    # (the case: the screw wound up, the stop holding the load)
    assert np.max(np.abs(result["normal_force"])) > 1e8
    assert np.sum(result["stop_force"] != 0.0) > 1000
    d = scene.to_dict()
    error = law_error(result, d)
    # The friction impulse is the root of the step's scalar law to its
    # round-off; the law's slope in P (1 + d kappa' |P_N|, 1e6 here) makes
    # that 2e-10 of the force at most (1.3e-6 before: the rows' slip).
    assert np.max(error) <= ROUND_OFF_REL * np.max(np.abs(result["friction_force"]))
    ch = {c: np.asarray(result[c], dtype=float) for c in result.channels}
    report = check_train(result, d, {"integrator": "moreau", "dt": 7.3e-6}, ch, 0.0, 0.0)
    assert report["friction_law"]["ok"], report["friction_law"]


@pytest.mark.parametrize("flank_angle", [0.0, math.radians(30.0)])
def test_a_held_stop_clamps_with_the_bristles_force_on_the_event_driven_scheme(flank_angle):
    scene = stop_scene(flank_angle=flank_angle)
    d = ls.Scene.from_dict(scene).to_dict()
    t_eval = np.linspace(0.0, 0.05, 501)
    result = ls.simulate(ls.Scene.from_dict(scene), 0.05, integrator="event_driven",
                         t_eval=t_eval)
    assert [k for k, c in result.checks.items() if c["applies"] and not c["passed"]] == []
    closed = [e.time for e in result.events if "closed" in e.kind]
    assert len(closed) == 1
    held = (np.asarray(result.t) > closed[0]) & (result["stop_force"] < 0.0)
    assert held.sum() > 50 and held[-1]
    z = result["bristle_deflection"][held]
    assert abs(z[0]) == pytest.approx(0.1 / 1e5, rel=1e-6)  # (the slide's mu / sigma0)
    # The law at the held rows (zero slip, z held): -|N|' sigma0 z, not 0.
    assert np.all(result["friction_force"][held] != 0.0)
    error = law_error(result, d)
    assert np.max(error) <= 1e-12 * np.max(np.abs(result["friction_force"]))
    # The clamp: the raise torque's force at the bristles' coefficient,
    # as Moreau-Jean's held stop (not the rule's M / (r_m tan alpha)).
    clamp = reference.clamp_force(0.05, scene["thread"], 1e5 * abs(z[0]))
    np.testing.assert_allclose(-result["stop_force"][held], clamp, rtol=1e-9)
    moreau = ls.simulate(ls.Scene.from_dict(scene), 0.05, integrator="moreau", dt=1e-6)
    np.testing.assert_allclose(moreau["stop_force"][-1], result["stop_force"][-1], rtol=1e-5)
    ch = {c: np.asarray(result[c], dtype=float) for c in result.channels}
    report = check_train(result, d, {"integrator": "event_driven", "t_eval": t_eval}, ch,
                         1e-9, 1e-12)
    assert report["friction_law"]["ok"], report["friction_law"]


def test_a_self_locking_held_stop_takes_the_smaller_friction_as_moreau_jean():
    # A thread self-locking at the held rows (mu' = 0.052 > tan(lead) =
    # 0.016) pressed by a torque and an axial force: both signs of N agree
    # with the bristles' friction. The one of the smaller |T| (Moreau-Jean's
    # held_friction) keeps the stop pushing; the other's stop pulled, and
    # the released load ran into it again (100,000 impacts: Zeno).
    thread = {"pitch": 1e-3, "mean_diameter": 20e-3, "flank_angle": 0.5}
    scene = ls.Scene.from_dict({
        "concept": "rigid", "thread": thread,
        "friction": {"law": "lugre", "mu": 0.05, "sigma0": 1e5, "sigma1": 0.0},
        "load": {"mass": 0.5}, "loads": {"drive_torque": -0.05, "axial_force": 30.0},
        "end_stops": {"upper": 1e-5, "contact": "exact"}})
    event = ls.simulate(scene, 0.02, integrator="event_driven")
    moreau = ls.simulate(scene, 0.02, integrator="moreau", dt=1e-5)
    for result in (event, moreau):
        assert [k for k, c in result.checks.items() if c["applies"] and not c["passed"]] == []
        assert result["stop_force"][-1] < 0.0  # (held, pushing the load back)
    assert len(event.events) == 1
    for name in ("stop_force", "normal_force", "friction_force"):
        assert event[name][-1] == pytest.approx(moreau[name][-1], rel=1e-8), name
    error = law_error(event, scene.to_dict())
    assert np.max(error) <= 1e-12 * np.max(np.abs(event["friction_force"]))
