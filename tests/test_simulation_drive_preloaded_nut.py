"""The preloaded split nut (issue 19, item 4) on the rigid drive, against the
closed forms of tests/helpers/preloaded_nut_reference.py
(docs/physics/preloaded_nut.md): the steady raising torque and efficiency
over mu, F and P, no cost without friction, the plain thread at P = 0,
holding and breakaway, half A's flank change, the energy account and
friction's sign, and the refused inputs."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers import preloaded_nut_reference as reference
from helpers.scenes import thesis_scene
from leadscrew.scene_schema import describe_schema

SPEED = 20.0  # [rad/s] of the rotor: the load moves at 3.2 mm/s
T_END = 0.05  # [s]: a speed-controlled rigid drive is steady at once


def preload_scene(mu=0.3, preload=0.0, **changes):
    """The thesis drive (rigid, screw-driven, right-hand) with a preloaded nut."""
    nut = {"preload": preload, **changes.pop("nut", {})}
    return thesis_scene(friction={"law": "coulomb", "mu": mu}, nut=nut, **changes)


def raising(mu, load, preload, speed=SPEED, **changes):
    """The scene speed-controlled at `speed` in the direction that raises the
    axial load `load` (it acts along -x, so on the nut's flank of lambda_N < 0:
    half A's): the rotor turns at -h speed."""
    omega = -speed
    return preload_scene(mu, preload, loads={"drive_torque": None, "drive_speed": omega,
                                             "axial_force": -load},
                         initial={"rotor_speed": omega}, **changes)


def thread_values(scene, mu):
    s = ls.Scene.from_dict(scene)
    t = s.thread
    return t.lead_angle, reference.effective_mu(mu, t.flank_angle), t.mean_radius


def window_efficiency(result):
    """eta = 1 - W_friction / W_in over the run's second half (eq. 5.2)."""
    i = len(result.t) // 2
    work = result["work_drive"][-1] - result["work_drive"][i]
    loss = result["friction_loss"][-1] - result["friction_loss"][i]
    return 1.0 - loss / work


@pytest.mark.parametrize("mu", [0.05, 0.3])
@pytest.mark.parametrize("load", [5.0, 200.0])
@pytest.mark.parametrize("preload", [10.0, 500.0])
def test_steady_raising_matches_the_closed_form(mu, load, preload):
    scene = raising(mu, load, preload)
    result = ls.simulate(ls.Scene.from_dict(scene), T_END)
    alpha, mu_eff, r_m = thread_values(scene, mu)
    torque = reference.raise_torque(load, preload, alpha, mu_eff, r_m)
    # The motor's torque raises along -x (negative for the right hand).
    assert result["drive_torque"][-1] == pytest.approx(-torque, rel=1e-9)
    eta = reference.efficiency(load, preload, alpha, mu_eff)
    assert window_efficiency(result) == pytest.approx(eta, rel=1e-3)
    assert abs(window_efficiency(result) - eta) <= 1e-9
    # Below the plain thread's, which the preload costs.
    assert eta < reference.efficiency(load, 0.0, alpha, mu_eff)
    assert np.all(result["stick"] == 0.0)


@pytest.mark.parametrize("load", [50.0, -300.0])
def test_lowering_and_a_load_beyond_the_preload_on_half_bs_side(load):
    # The nut moved with a load on half A's side (lowering), and against the
    # flank side changing: a load that starts on half A's flank (t = 0) and
    # then presses half B's beyond the preload (half A on its other flank).
    preload = 100.0
    start = -10.0 if load < 0 else -load  # axial force at t = 0: half A's side
    table = {"type": "table", "times": [0.0, 0.01], "values": [start, -load]}
    scene = preload_scene(0.3, preload, loads={"drive_torque": None, "drive_speed": SPEED,
                                               "axial_force": table},
                          initial={"rotor_speed": SPEED})
    result = ls.simulate(ls.Scene.from_dict(scene), T_END)
    alpha, mu_eff, r_m = thread_values(scene, 0.3)
    # Rotor at +speed moves the load along +x: with a load on half A's side
    # (along -x) that lowers it; a load beyond P on half B's side is raised by
    # the plain thread's torque (both halves on one flank).
    if load > 0:
        expected = reference.lower_torque(load, preload, alpha, mu_eff, r_m)
    else:
        expected = reference.half_torque(-load, True, alpha, mu_eff, r_m)
        plain = r_m * -load * math.tan(alpha + math.atan(mu_eff))
        assert expected == pytest.approx(plain, rel=1e-12)
    assert result["drive_torque"][-1] == pytest.approx(expected, rel=1e-9)


def test_without_friction_the_preload_costs_nothing():
    plain = ls.simulate(ls.Scene.from_dict(raising(0.0, 50.0, 0.0)), T_END)
    preloaded = ls.simulate(ls.Scene.from_dict(raising(0.0, 50.0, 500.0)), T_END)
    for channel in ("drive_torque", "work_drive", "v_load", "normal_force"):
        np.testing.assert_allclose(preloaded[channel], plain[channel], rtol=1e-12, atol=0.0)
    np.testing.assert_array_equal(preloaded["friction_loss"], 0.0)
    assert window_efficiency(preloaded) == pytest.approx(1.0, abs=1e-12)


def test_zero_preload_is_the_plain_thread_bit_for_bit():
    scene = thesis_scene()  # the thesis's load case: sticks and slips both ways
    plain = ls.simulate(ls.Scene.from_dict(scene), 0.5)
    zero = ls.simulate(ls.Scene.from_dict(preload_scene(0.3, 0.0)), 0.5)
    assert plain.channels == zero.channels
    np.testing.assert_array_equal(zero.t, plain.t)
    for channel in plain.channels:
        np.testing.assert_array_equal(zero[channel], plain[channel])


def holding_scene(torque, preload, load=100.0):
    return preload_scene(0.3, preload, loads={"drive_torque": torque, "axial_force": -load})


def test_a_self_locking_drive_holds_its_load_and_the_preload_widens_the_band():
    load, preload = 100.0, 50.0
    alpha, mu_eff, r_m = thread_values(holding_scene(0.0, preload), 0.3)
    assert mu_eff > math.tan(alpha)  # self-locking
    # At rest under the load alone.
    held = ls.simulate(ls.Scene.from_dict(holding_scene(0.0, preload)), 0.2)
    assert np.all(held["stick"] == 1.0)
    np.testing.assert_array_equal(held["omega_drive"], 0.0)
    # A raising torque between the plain thread's and the preloaded nut's
    # breakaway: the preload holds it, the plain thread turns.
    plain_raise = reference.raise_torque(load, 0.0, alpha, mu_eff, r_m)
    preloaded_raise = reference.raise_torque(load, preload, alpha, mu_eff, r_m)
    torque = -0.5 * (plain_raise + preloaded_raise)
    held = ls.simulate(ls.Scene.from_dict(holding_scene(torque, preload)), 0.2)
    assert np.all(held["stick"] == 1.0)
    np.testing.assert_array_equal(held["v_load"], 0.0)
    moved = ls.simulate(ls.Scene.from_dict(holding_scene(torque, 0.0)), 0.2)
    assert moved["stick"][-1] == 0.0 and moved["v_load"][-1] > 0.0
    # And a lowering torque beyond the plain lower torque, within the preloaded one.
    plain_lower = reference.lower_torque(load, 0.0, alpha, mu_eff, r_m)
    preloaded_lower = reference.lower_torque(load, preload, alpha, mu_eff, r_m)
    torque = 0.5 * (plain_lower + preloaded_lower)
    held = ls.simulate(ls.Scene.from_dict(holding_scene(torque, preload)), 0.2)
    assert np.all(held["stick"] == 1.0)
    moved = ls.simulate(ls.Scene.from_dict(holding_scene(torque, 0.0)), 0.2)
    assert moved["stick"][-1] == 0.0 and moved["v_load"][-1] < 0.0


@pytest.mark.parametrize("direction", [1, -1])
def test_breakaway_from_rest_at_the_closed_form_torque(direction):
    # A torque ramp from rest: the thread sticks until the torque reaches the
    # raise (direction -1 on the rotor) or lower torque, then slips.
    load, preload, rate = 100.0, 50.0, 10.0  # [N], [N], [N m/s]
    ramp = {"type": "table", "times": [0.0, 1.0], "values": [0.0, direction * rate]}
    scene = holding_scene(ramp, preload, load)
    alpha, mu_eff, r_m = thread_values(scene, 0.3)
    expected = (reference.raise_torque if direction < 0 else reference.lower_torque)(
        load, preload, alpha, mu_eff, r_m)
    result = ls.simulate(ls.Scene.from_dict(scene), 1.2 * expected / rate)
    assert_breaks_free_at(result, expected)


def assert_breaks_free_at(result, expected):
    """The run sticks from rest, then slips from the row where |drive_torque|
    is ``expected`` [N m] (to 1e-9); it never exceeds it while stuck.
    Returns the stick column (bool) and the first slipping row."""
    stuck = result["stick"] == 1.0
    assert stuck[0] and not stuck[-1]
    first_slip = np.argmax(~stuck)
    # The slip starts at an event row: the torque there is the breakaway torque.
    assert abs(result["drive_torque"][first_slip]) == pytest.approx(expected, rel=1e-9)
    assert np.all(np.abs(result["drive_torque"][stuck]) <= expected * (1 + 1e-9))
    return stuck, first_slip


def test_energy_account_closes_and_friction_never_pushes():
    # A sine drive torque on a loaded preloaded nut: stick, slip both ways.
    scene = preload_scene(0.1, 5.0, loads={
        "drive_torque": {"type": "sine", "amplitude": -40e-3, "omega": 4 * math.pi},
        "axial_force": -10.0})
    # (the result checks run; rtol 1e-10 puts the integration error of the
    # account below 1e-9 of the work)
    result = ls.simulate(ls.Scene.from_dict(scene), 1.0, rtol=1e-10)
    stick = result["stick"]
    assert np.any(stick == 1.0) and np.any(stick == 0.0)
    assert np.any(result["slip_velocity"] > 0.0) and np.any(result["slip_velocity"] < 0.0)
    work = result["work_drive"] + result["work_axial"]
    stored = result["kinetic"] + result["friction_loss"]
    assert np.max(np.abs(work - stored)) <= 1e-9 * np.max(np.abs(result["work_drive"]))
    power = result["friction_force"] * result["slip_velocity"]
    assert np.all(power <= 1e-12 * np.max(np.abs(power)))
    assert np.all(np.diff(result["friction_loss"]) >= -1e-15)
    # The preload's friction is lost where it slips: more than the plain thread.
    plain = ls.simulate(ls.Scene.from_dict(preload_scene(0.1, 0.0, loads=scene["loads"])), 1.0)
    assert result["friction_loss"][-1] > plain["friction_loss"][-1]
    assert all(check["passed"] for check in result.checks.values())


@pytest.mark.parametrize("changes, message", [
    ({"nut": {"preload": -1.0}},
     r"nut\.preload = -1\.0 is invalid: must be a finite number >= 0"),
    ({"nut": {"preload_stiffness": -1.0}},
     r"nut\.preload_stiffness = -1\.0 is invalid: must be a finite number >= 0"),
])
def test_invalid_inputs_name_the_key(changes, message):
    scene = preload_scene(0.3, 10.0)
    for key, value in changes.items():
        scene[key] = {**scene.get(key, {}), **value} if isinstance(value, dict) else value
    with pytest.raises(ValueError, match=message):
        ls.simulate(ls.Scene.from_dict(scene), 0.01)


@pytest.mark.parametrize("concept, backlash", [
    ("rigid", None), ("flexible", None),
    ("flexible_nut", {"axial": 1e-4, "contact": "bistop", "stiffness": 1e9, "exponent": 1.0})])
def test_a_preload_the_nut_cannot_carry_is_refused_up_front(concept, backlash):
    # 1e12 N ground to CV_TOO_MUCH_WORK on penalty flanks without naming the
    # preload. The nut carries at most 10 % axial strain of its body:
    # 0.1 k_nut l_nut (docs/physics/preloaded_nut.md, "Valid preloads").
    changes = {"concept": concept, **({"backlash": backlash} if backlash else {})}
    scene = ls.Scene.from_dict(preload_scene(0.3, 1e12, nut={"preload_stiffness": 1e6},
                                             **changes))
    parameters = ls.Scene.from_dict(preload_scene(0.3, 0.0, **changes)).model().parameters
    limit = 0.1 * parameters.nut_axial_stiffness * parameters.nut_length
    with pytest.raises(ValueError, match=r"nut\.preload = 1e\+12 N is invalid: must be <= "
                                         + f"{limit:.6g}"[:6].replace(".", r"\.")
                                         + r".* N, what the nut carries \(10 % axial strain"):
        ls.simulate(scene, 0.01)
    # At the limit it is a valid model.
    ls.Scene.from_dict(preload_scene(0.3, limit, nut={"preload_stiffness": 1e6}, **changes)).model()


def test_a_preload_that_presses_half_a_through_the_thread_is_refused():
    # With lift-off, half A's flank penetration at the preload, f^-1(P),
    # must stay below the thread's depth (half the pitch, 0.5 mm here): a
    # soft flank of 1e4 N/m at P = 10 N would be pressed in by 1 mm.
    soft = {"axial": 1e-4, "contact": "bistop", "stiffness": 1e4, "exponent": 1.0}
    scene = preload_scene(0.3, 10.0, concept="flexible_nut", backlash=soft,
                          nut={"preload_stiffness": 1e6})
    with pytest.raises(ValueError, match=r"nut\.preload = 10 N is invalid with backlash\.contact "
                                         r"= \"bistop\": it presses half A's flank in by 0\.001 m "
                                         r".*half of thread\.pitch = 0\.0005 m"):
        ls.simulate(ls.Scene.from_dict(scene), 0.01)
    soft["stiffness"] = 1e5  # 0.1 mm: runs
    assert ls.simulate(ls.Scene.from_dict(scene), 0.01).t[-1] == 0.01


def test_integrators_other_than_event_driven_and_moreau_are_refused():
    # (Moreau-Jean runs the preloaded nut without lift-off:
    # tests/test_moreau_preloaded_nut.py.)
    scene = ls.Scene.from_dict(preload_scene(0.3, 10.0))
    with pytest.raises(ValueError, match=r"integrator = \"cvode_bdf\" is invalid with "
                                         r"nut\.preload = 10 N.*\"event_driven\" or \"moreau\""):
        ls.simulate(scene, 0.01, integrator="cvode_bdf")


def test_with_play_on_the_rigid_concept_the_preload_closes_it():
    load, preload = 20.0, 40.0
    played = raising(0.3, load, preload, backlash={"contact": "exact", "axial": 1e-4})
    closed = raising(0.3, load, preload)
    a = ls.simulate(ls.Scene.from_dict(played), T_END)
    b = ls.simulate(ls.Scene.from_dict(closed), T_END)
    np.testing.assert_array_equal(a["drive_torque"], b["drive_torque"])
    assert "gap" not in a.channels or np.all(a["gap"] == 0.0)


def test_scene_toml_and_core_spec_carry_the_preload(tmp_path):
    scene = ls.Scene.from_dict(preload_scene(0.3, "50 N", nut={"preload_stiffness": "2e5 N/mm"}))
    assert scene["nut"]["preload"] == 50.0 and scene["nut"]["preload_stiffness"] == 2e8
    path = tmp_path / "preloaded.toml"
    scene.to_toml(path)
    assert ls.Scene.from_toml(path) == scene
    parameters, _ = ls._core.read_core_spec(scene.to_core_toml())
    assert parameters.nut_preload == 50.0 and parameters.nut_preload_stiffness == 2e8
    text = describe_schema()
    assert "nut.preload [N]" in text and "nut.preload_stiffness [N/m]" in text


def test_in_the_painleve_regime_a_stuck_preloaded_drive_keeps_sticking():
    # A light rotor, a heavy load and a steep thread: mu' |G_NT| >= G_NN. At
    # zero slip the drive keeps sticking where the stick force lies in the
    # cone (as the plain thread does); the preload's friction holds the
    # thesis's torque, under which the plain thread slips and jams.
    changes = dict(rotor={"inertia": 1e-9}, load={"mass": 1000.0},
                   thread={"pitch": 5e-3, "mean_diameter": 20e-3})
    result = ls.simulate(ls.Scene.from_dict(preload_scene(0.3, 30.0, **changes)), 0.5)
    assert np.all(result["stick"] == 1.0)
    np.testing.assert_array_equal(result["omega_drive"], 0.0)
    with pytest.raises(ls.JammingError):
        ls.simulate(ls.Scene.from_dict(preload_scene(0.3, 0.0, **changes)), 0.5)


def test_the_integrators_a_preloaded_nut_lists_are_the_ones_it_runs():
    # One list, the true one (issue 17 item 16): a review found "moreau" listed, then refused.
    # Moreau-Jean runs the nut, with lift-off too (tests/test_moreau_preloaded_nut.py).
    scene = ls.Scene.from_dict(preload_scene(0.3, 10.0))
    assert ls._core.drive_integrators(scene.model().parameters) == ["event_driven", "moreau"]
    assert ls.simulate(scene, 0.01, integrator="moreau", dt=1e-4).t[-1] == 0.01
    lift_off = ls.Scene.from_dict(preload_scene(
        0.3, 10.0, concept="flexible_nut", nut={"preload_stiffness": 1e6},
        backlash={"axial": 1e-4, "contact": "bistop", "stiffness": 1e9, "exponent": 1.0}))
    assert ls._core.drive_integrators(lift_off.model().parameters) == ["event_driven", "moreau"]
    assert ls.simulate(lift_off, 0.01, integrator="moreau", dt=1e-5).t[-1] == 0.01
    with pytest.raises(ValueError, match=r"integrator = \"cvode_bdf\" is invalid with "
                                         r"nut\.preload = 10 N"):
        ls.simulate(scene, 0.01, integrator="cvode_bdf")
