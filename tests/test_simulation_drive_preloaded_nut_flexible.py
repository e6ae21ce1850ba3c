"""The preloaded split nut (issue 19, item 4) on the flexible concepts
(docs/physics/preloaded_nut.md, "The flexible concepts"): without play the
same element as on the rigid concept, whose steady raise has the rigid
drive's thread forces (tests/helpers/preloaded_nut_reference.py)."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers import preloaded_nut_reference as reference
from helpers.scenes import thesis_scene

FLEXIBLE = ("flexible_nut", "flexible")
# Constant screw stiffnesses (eq. 4.24's follow the nut, so a moving nut's
# deflections change slowly and a speed-controlled raise is never steady) and
# damping that lets the start's transient die out within the run.
STEADY = {"damping_ratio": 0.5, "screw_axial_stiffness": 5e8,
          "screw_torsional_stiffness": 500.0}


def flexible_scene(concept, mu=0.3, preload=0.0, **changes):
    """The thesis drive (screw-driven, right-hand) of `concept` with a preloaded nut."""
    nut = {"preload": preload, **changes.pop("nut", {})}
    overrides = {**STEADY, **changes.pop("overrides", {})}
    return thesis_scene(concept=concept, friction={"law": "coulomb", "mu": mu}, nut=nut,
                        overrides=overrides, **changes)


def thread_values(scene, mu):
    t = ls.Scene.from_dict(scene).thread
    return t.lead_angle, reference.effective_mu(mu, t.flank_angle), t.mean_radius


def all_checks_pass(result):
    return all(check["passed"] for check in result.checks.values())


@pytest.mark.parametrize("concept", FLEXIBLE)
@pytest.mark.parametrize("mu, load, preload",
                         [(0.3, 200.0, 500.0), (0.05, 5.0, 10.0), (0.3, 5.0, 500.0),
                          (0.05, 200.0, 10.0)])
def test_steady_raise_has_the_rigid_closed_form(concept, mu, load, preload):
    # Speed-controlled raise of the load `load` (along -x: half A's flank is
    # lambda_N < 0). Once the start's transient has died out the springs
    # carry constant forces and the thread's forces are the rigid drive's.
    omega = -20.0
    scene = flexible_scene(concept, mu, preload,
                           loads={"drive_torque": None, "drive_speed": omega,
                                  "axial_force": -load},
                           initial={"rotor_speed": omega})
    result = ls.simulate(ls.Scene.from_dict(scene), 0.1, rtol=1e-10)
    alpha, mu_eff, r_m = thread_values(scene, mu)
    torque = reference.raise_torque(load, preload, alpha, mu_eff, r_m)
    assert result["drive_torque"][-1] == pytest.approx(-torque, rel=1e-9)
    efficiency = (-result["axial_force"][-1] * result["v_load"][-1]
                  / (result["drive_torque"][-1] * result["omega_drive"][-1]))
    assert efficiency == pytest.approx(reference.efficiency(load, preload, alpha, mu_eff),
                                       rel=1e-9)
    assert result["stick"][-1] == 0.0
    assert all_checks_pass(result)


@pytest.mark.parametrize("concept", FLEXIBLE)
@pytest.mark.parametrize("direction", ["raise", "lower"])
def test_the_preload_widens_the_holding_band(concept, direction):
    # A torque ramped to the middle of the band the preload adds (between the
    # plain thread's and the preloaded nut's raise or lower torque): the
    # preloaded nut holds it, the plain nut moves.
    load, preload = 100.0, 50.0
    alpha, mu_eff, r_m = thread_values(flexible_scene(concept), 0.3)
    if direction == "raise":
        edge = reference.raise_torque
        sense = -1.0
    else:
        edge = reference.lower_torque
        sense = 1.0
    torque = sense * 0.5 * (edge(load, 0.0, alpha, mu_eff, r_m)
                            + edge(load, preload, alpha, mu_eff, r_m))
    ramp = {"type": "table", "times": [0.0, 0.05], "values": [0.0, torque]}
    loads = {"drive_torque": ramp, "axial_force": -load}
    held = ls.simulate(ls.Scene.from_dict(flexible_scene(concept, 0.3, preload, loads=loads)),
                       0.3)
    assert np.all(held["stick"] == 1.0)
    assert abs(held["v_load"][-1]) < 1e-9
    assert all_checks_pass(held)
    moved = ls.simulate(ls.Scene.from_dict(flexible_scene(concept, 0.3, 0.0, loads=loads)), 0.3)
    assert moved["stick"][-1] == 0.0
    assert sense * -moved["v_load"][-1] > 0.01  # raising moves the load along +x


@pytest.mark.parametrize("concept", FLEXIBLE)
def test_energy_account_closes_and_friction_never_pushes(concept):
    # A sine drive torque on a loaded preloaded nut: stick and slip both ways.
    loads = {"drive_torque": {"type": "sine", "amplitude": -40e-3, "omega": 4 * math.pi},
             "axial_force": -10.0}
    scene = flexible_scene(concept, 0.1, 5.0, loads=loads, overrides={"damping_ratio": 0.05})
    result = ls.simulate(ls.Scene.from_dict(scene), 1.0, rtol=1e-10)
    stick = result["stick"]
    assert np.any(stick == 1.0) and np.any(stick == 0.0)
    assert np.any(result["slip_velocity"] > 0.0) and np.any(result["slip_velocity"] < 0.0)
    work = result["work_drive"] + result["work_axial"]
    stored = (result["kinetic"] + result["elastic"] - result["elastic"][0]
              + result["friction_loss"] + result["damping_loss"])
    # (rtol 1e-10: the plain flexible drive's account closes to ~1e-8 of the work)
    scale = np.max(np.abs(result["work_drive"]))
    assert np.max(np.abs(work - stored)) <= 1e-7 * scale
    assert np.max(np.abs(result["energy_residual"])) <= 1e-7 * scale
    power = result["friction_force"] * result["slip_velocity"]
    assert np.all(power <= 1e-12 * np.max(np.abs(power)))
    assert np.all(np.diff(result["friction_loss"]) >= -1e-15)
    plain = ls.simulate(ls.Scene.from_dict(flexible_scene(concept, 0.1, 0.0, loads=loads,
                                                          overrides={"damping_ratio": 0.05})),
                        1.0)
    assert result["friction_loss"][-1] > plain["friction_loss"][-1]
    assert all_checks_pass(result)


@pytest.mark.parametrize("concept", FLEXIBLE)
def test_zero_preload_is_the_plain_flexible_drive_bit_for_bit(concept):
    scene = thesis_scene(concept=concept)
    plain = ls.simulate(ls.Scene.from_dict(scene), 0.2)
    zero = ls.simulate(ls.Scene.from_dict(thesis_scene(concept=concept, nut={"preload": 0.0})),
                       0.2)
    assert plain.channels == zero.channels
    np.testing.assert_array_equal(zero.t, plain.t)
    for channel in plain.channels:
        np.testing.assert_array_equal(zero[channel], plain[channel])
