"""The preloaded split nut with two friction coefficients (issue 19, item 4;
Coulomb's law with friction.mu_static above mu; docs/physics/preloaded_nut.md,
"Two coefficients"): the halves stick together while the friction lies in
the bound at mu_static', half B at its edge's state at mu_static', and slip
at mu'. A rigid drive at rest breaks free at the raise (lower) torque with
rho_s' = atan mu_static', r_m [(F + P) tan(alpha + rho_s') + P tan(rho_s' -
alpha)], and moves on at mu''s (tests/helpers/preloaded_nut_reference.py)."""

import numpy as np
import pytest

import leadscrew as ls
from helpers import preloaded_nut_reference as reference
from helpers.scenes import thesis_scene
from test_simulation_drive_preloaded_nut import assert_breaks_free_at

MU, MU_STATIC = 0.2, 0.3
LOAD, PRELOAD = 100.0, 50.0  # [N]


def static_scene(preload=PRELOAD, mu_static=MU_STATIC, **changes):
    """The thesis drive (rigid, screw-driven, right-hand) with a preloaded nut
    and Coulomb's law with mu_static; the axial load along -x (half A's)."""
    loads = {"axial_force": -LOAD, **changes.pop("loads", {})}
    return thesis_scene(friction={"law": "coulomb", "mu": MU, "mu_static": mu_static},
                        nut={"preload": preload, **changes.pop("nut", {})}, loads=loads,
                        **changes)


def thread_values(scene):
    t = ls.Scene.from_dict(scene).thread
    return (t.lead_angle, reference.effective_mu(MU, t.flank_angle),
            reference.effective_mu(MU_STATIC, t.flank_angle), t.mean_radius)


def all_checks_pass(result):
    return all(check["passed"] for check in result.checks.values())


@pytest.mark.parametrize("direction", [1, -1])
def test_breakaway_from_rest_at_the_static_closed_form(direction):
    # A torque ramp from rest: the nut sticks until the torque reaches the
    # raise (direction -1 on the rotor) or lower torque at mu_static', then slips.
    rate = 10.0  # [N m/s]
    ramp = {"type": "table", "times": [0.0, 1.0], "values": [0.0, direction * rate]}
    scene = static_scene(loads={"drive_torque": ramp})
    alpha, mu_eff, mu_static_eff, r_m = thread_values(scene)
    closed_form = reference.raise_torque if direction < 0 else reference.lower_torque
    expected = closed_form(LOAD, PRELOAD, alpha, mu_static_eff, r_m)
    kinetic = closed_form(LOAD, PRELOAD, alpha, mu_eff, r_m)
    assert expected > 1.3 * kinetic  # the breakaway is the static one, well apart
    result = ls.simulate(ls.Scene.from_dict(scene), 1.2 * expected / rate)
    stuck, first_slip = assert_breaks_free_at(result, expected)
    # Slipping, the friction is mu''s: |T| = mu' (|N_A| + |N_B|), half B at
    # its slip's state (the result checks' friction_law and cone pass).
    assert np.all(stuck[:first_slip]) and not np.any(stuck[first_slip:])
    assert all_checks_pass(result)


def test_steady_raise_is_at_the_kinetic_closed_form():
    # A speed-controlled raise: the torque and efficiency are mu''s.
    speed = -20.0
    scene = static_scene(loads={"drive_torque": None, "drive_speed": speed},
                         initial={"rotor_speed": speed})
    alpha, mu_eff, _, r_m = thread_values(scene)
    result = ls.simulate(ls.Scene.from_dict(scene), 0.05)
    assert result["drive_torque"][-1] == pytest.approx(
        -reference.raise_torque(LOAD, PRELOAD, alpha, mu_eff, r_m), rel=1e-9)
    i = len(result.t) // 2
    work = result["work_drive"][-1] - result["work_drive"][i]
    loss = result["friction_loss"][-1] - result["friction_loss"][i]
    assert 1.0 - loss / work == pytest.approx(
        reference.efficiency(LOAD, PRELOAD, alpha, mu_eff), rel=1e-9)
    assert np.all(result["stick"] == 0.0) and all_checks_pass(result)


def test_a_torque_between_the_kinetic_and_static_breakaway_is_held_from_rest():
    # Between the kinetic and the static raise torque: held from rest with
    # mu_static, turned by the nut of one coefficient (mu_static = mu).
    scene = static_scene()
    alpha, mu_eff, mu_static_eff, r_m = thread_values(scene)
    torque = -0.5 * (reference.raise_torque(LOAD, PRELOAD, alpha, mu_eff, r_m)
                     + reference.raise_torque(LOAD, PRELOAD, alpha, mu_static_eff, r_m))
    held = ls.simulate(ls.Scene.from_dict(static_scene(loads={"drive_torque": torque})), 0.2)
    assert np.all(held["stick"] == 1.0) and all_checks_pass(held)
    np.testing.assert_array_equal(held["v_load"], 0.0)
    moved = ls.simulate(ls.Scene.from_dict(
        static_scene(mu_static=MU, loads={"drive_torque": torque})), 0.2)
    assert moved["stick"][-1] == 0.0 and moved["v_load"][-1] > 0.0


def test_stick_slip_cycles_close_the_energy_account():
    # A sine torque: breakaway at mu_static', slip at mu', stick again.
    scene = static_scene(loads={"drive_torque": {"type": "sine", "amplitude": -1.0,
                                                 "omega": 4 * np.pi}})
    result = ls.simulate(ls.Scene.from_dict(scene), 1.0, rtol=1e-10)
    stick = result["stick"]
    assert np.any(stick == 1.0) and np.any(stick == 0.0)
    work = result["work_drive"] + result["work_axial"]
    stored = result["kinetic"] + result["friction_loss"]
    assert np.max(np.abs(work - stored)) <= 1e-9 * np.max(np.abs(result["work_drive"]))
    assert all_checks_pass(result)


@pytest.mark.parametrize("concept, backlash", [
    ("flexible_nut", None), ("flexible", None),
    ("flexible_nut", {"axial": 1e-4, "contact": "bistop", "stiffness": 1e7, "exponent": 1.0})])
def test_the_flexible_concepts_run_with_mu_static(concept, backlash):
    # A torque ramp from rest to beyond the static raise torque: stick, then
    # slip; the result checks (the cone at mu_static', the law at mu') pass.
    rate = 10.0
    scene = static_scene(concept=concept, nut={"preload_stiffness": 1e6},
                         loads={"drive_torque": {"type": "table", "times": [0.0, 1.0],
                                                 "values": [0.0, -rate]}},
                         **({"backlash": backlash} if backlash else {}))
    alpha, _, mu_static_eff, r_m = thread_values(scene)
    expected = reference.raise_torque(LOAD, PRELOAD, alpha, mu_static_eff, r_m)
    result = ls.simulate(ls.Scene.from_dict(scene), 1.3 * expected / rate)
    stuck = result["stick"] == 1.0
    assert stuck[0] and not stuck[-1] and all_checks_pass(result)


def test_a_static_coefficient_that_locks_half_b_is_refused():
    # mu_static' tan(a) >= 1: half B's flank force at the stick limit has no
    # finite value (its spring would lock it): refused, naming mu_static.
    steep = {"pitch": 40e-3, "mean_diameter": 20e-3}  # tan(a) = 0.64
    scene = static_scene(mu_static=2.0, thread=steep)
    with pytest.raises(ValueError, match=r"friction\.mu_static = 2 is invalid with "
                                         r"nut\.preload = 50: mu_static' tan\(lead angle\) = "
                                         r".* >= 1"):
        ls.simulate(ls.Scene.from_dict(scene), 0.01)
