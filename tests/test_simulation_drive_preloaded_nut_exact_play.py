"""The preloaded split nut closing exact play on the flexible concepts
(issue 19, item 4: "with backlash given, the preload closes it";
docs/physics/preloaded_nut.md, "Exact play closed by the preload"): the
element without play, exact while half A bears on its flank, so a run
equals the no-play scene's bit for bit; where the load on half B's side
would lift half A off its flank (its normal force reaching zero: P / cos^2 a
quasi-statically in stick) the run raises a SimulationError at that time,
never an answer."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers import preloaded_nut_reference as reference
from helpers.scenes import thesis_scene

FLEXIBLE = ("flexible_nut", "flexible")
PRELOAD, PLAY = 50.0, 1e-4  # [N], [m]
EXACT = {"axial": PLAY, "contact": "exact", "restitution": 0.0}
LIFT_OFF = r"half A of the preloaded nut lifts off its flank into the exact play"


def without_play(scene):
    plain = dict(scene)
    plain.pop("backlash")
    return plain


def assert_same_run(result, plain):
    assert result.channels == plain.channels
    np.testing.assert_array_equal(result.t, plain.t)
    for channel in plain.channels:
        np.testing.assert_array_equal(result[channel], plain[channel], err_msg=channel)


def energy_closes(result):
    """The account's residual within 1e-7 of the work in, every check passed."""
    scale = np.max(np.abs(result["work_drive"])) + np.max(np.abs(result["work_axial"]))
    assert scale > 0.0
    assert np.max(np.abs(result["energy_residual"])) <= 1e-7 * scale
    assert all(check["passed"] for check in result.checks.values())


def seat_adjuster(concept, preload=20.0, **changes):
    """The shipped seat adjuster (nut-driven, 12 V motor, ideal 5:1 stage,
    0.1 mm exact play) of `concept` with a preloaded nut."""
    scene = ls.scenes.load("seat_adjuster").to_dict()
    scene["concept"] = concept
    scene["nut"] = {**scene["nut"], "preload": preload}
    scene.update(changes)
    return scene


@pytest.mark.parametrize("concept", FLEXIBLE)
def test_the_seat_adjuster_runs_as_its_scene_without_play(concept):
    # The motor starts the seat uphill (80 N on half A): stick, breakaway,
    # slip, and the seat's mass swinging on the springs reverses the thread's
    # force by up to 380 N (no-play run), which 500 N of preload holds.
    scene = seat_adjuster(concept, preload=500.0)
    assert scene["backlash"]["contact"] == "exact"
    result = ls.simulate(ls.Scene.from_dict(scene), 0.2)
    plain = ls.simulate(ls.Scene.from_dict(without_play(scene)), 0.2)
    assert_same_run(result, plain)
    assert np.max(np.abs(result["omega_drive"])) > 100.0  # it runs
    assert np.min(result["normal_force"]) < 0.0 < np.max(result["normal_force"])  # reversed
    energy_closes(result)


@pytest.mark.parametrize("concept", FLEXIBLE)
def test_the_screw_driven_raise_runs_as_its_scene_without_play(concept):
    omega = -20.0
    scene = thesis_scene(concept=concept, friction={"law": "coulomb", "mu": 0.3},
                         nut={"preload": PRELOAD}, backlash=dict(EXACT),
                         loads={"drive_torque": None, "drive_speed": omega,
                                "axial_force": -100.0},
                         initial={"rotor_speed": omega},
                         overrides={"damping_ratio": 0.5})
    result = ls.simulate(ls.Scene.from_dict(scene), 0.1)
    plain = ls.simulate(ls.Scene.from_dict(without_play(scene)), 0.1)
    assert_same_run(result, plain)
    energy_closes(result)


def half_a_bearing(result, scene, preload, side):
    """Half A's normal force on its own flank in a no-play run, -side (N - N_B)
    (PreloadedNut::half_a_bearing): half B at N_B^s = side P / (cos a -
    s side mu' sin a) where the thread slips in the direction s, at its
    spring's side P / cos a in stick; half A's sign -side."""
    thread = scene.thread
    alpha = thread.lead_angle
    mu = reference.effective_mu(scene["friction"]["mu"], thread.flank_angle)
    normal = np.asarray(result["normal_force"])
    s = np.sign(np.asarray(result["slip_velocity"]))
    half_b = side * preload / (math.cos(alpha) - s * side * mu * math.sin(alpha))
    return -side * (normal - half_b)


def crossing(t, margin):
    """Where `margin` first falls below zero, linear between rows."""
    rows = np.flatnonzero(margin < 0.0)
    assert rows.size and rows[0] > 0 and margin[0] > 0.0
    i = rows[0]
    return t[i - 1] + (t[i] - t[i - 1]) * margin[i - 1] / (margin[i - 1] - margin[i])


def lift_off_case(scene, preload, t_end, closed_form_time=None):
    """The closed exact play raises where the no-play run's half A reaches
    zero (to 1e-9 of the run, both runs on the same output rows: the same
    steps) and where the quasi-static closed form says (to 1e-3 of the
    run); up to there the run is the no-play one's."""
    s, plain_scene = ls.Scene.from_dict(scene), ls.Scene.from_dict(without_play(scene))
    # The first zero on 4000 rows, then on rows 1e-3 of theirs apart about it.
    t_eval = np.linspace(0.0, t_end, 4001)
    plain = ls.simulate(plain_scene, t_end, t_eval=t_eval)
    # Half A's sign: the net normal force's under the start's load.
    normal = np.asarray(plain["normal_force"])
    side = -np.sign(normal[np.flatnonzero(normal)[0]])
    coarse = crossing(t_eval, half_a_bearing(plain, s, preload, side))
    step = t_eval[1]
    fine = np.concatenate([[0.0], np.linspace(coarse - 2.0 * step, coarse + 2.0 * step, 4001)])
    plain = ls.simulate(plain_scene, fine[-1], t_eval=fine)
    expected = crossing(fine, half_a_bearing(plain, s, preload, side))
    with pytest.raises(ls.SimulationError, match=LIFT_OFF + r".*\"bistop\" or \"cubic\" with "
                                                 r"nut\.preload_stiffness") as error:
        ls.simulate(s, fine[-1], t_eval=fine)
    assert error.value.time == pytest.approx(expected, abs=1e-9 * t_end)
    with pytest.raises(ls.SimulationError, match=LIFT_OFF):  # the default rows too
        ls.simulate(s, t_end)
    if closed_form_time is not None:
        assert error.value.time == pytest.approx(closed_form_time, abs=1e-3 * t_end)
    before = 0.9 * error.value.time
    assert_same_run(ls.simulate(s, before), ls.simulate(plain_scene, before))


@pytest.mark.parametrize("concept", FLEXIBLE)
def test_the_seat_adjusters_start_lifts_half_a_off_a_small_preload(concept):
    # 20 N of preload: the seat swinging on the springs after the motor's
    # start reverses the thread's force beyond it, in slip.
    lift_off_case(seat_adjuster(concept, preload=20.0), 20.0, 0.02)


@pytest.mark.parametrize("concept", FLEXIBLE)
def test_lift_off_raises_at_half_a_s_zero_screw_driven(concept):
    # The rotor held, an axial load ramped from -1 N (on half A's flank) to
    # 199 N over 1 s: quasi-statically stuck, the thread's force axial, half
    # A's normal force is zero at F = P / cos^2 a.
    scene = thesis_scene(concept=concept, friction={"law": "coulomb", "mu": 0.3},
                         nut={"preload": PRELOAD}, backlash=dict(EXACT),
                         loads={"drive_torque": None, "drive_speed": 0.0,
                                "axial_force": {"type": "table", "times": [0.0, 1.0],
                                                "values": [-1.0, 199.0]}},
                         overrides={"damping_ratio": 0.5})
    alpha = ls.Scene.from_dict(scene).thread.lead_angle
    lift = PRELOAD / math.cos(alpha) ** 2
    lift_off_case(scene, PRELOAD, 1.0, (lift + 1.0) / 200.0)


@pytest.mark.parametrize("concept", FLEXIBLE)
def test_lift_off_raises_at_half_a_s_zero_nut_driven(concept):
    # The seat adjuster, its motor replaced by a held nut, its 80 N uphill
    # load (half A) ramped over 1 s to 120 N the other way: on `flexible`
    # quasi-statically, half A free at F = -P / cos^2 a. (On `flexible_nut`
    # the seat keeps swinging on its springs by some 60 N, in the no-play
    # run too: the no-play run's zero alone.)
    preload = 20.0
    scene = seat_adjuster(concept, preload, overrides={"damping_ratio": 0.5})
    scene.pop("motor")
    scene["loads"] = {"drive_speed": 0.0,
                      "axial_force": {"type": "table", "times": [0.0, 1.0],
                                      "values": [80.0, -120.0]}}
    alpha = ls.Scene.from_dict(scene).thread.lead_angle
    lift = preload / math.cos(alpha) ** 2
    lift_off_case(scene, preload, 1.0,
                  (80.0 + lift) / 200.0 if concept == "flexible" else None)


def test_a_load_the_preload_holds_returns():
    # The same ramp ending below the lift-off load: the run returns, the
    # no-play run's, half A bearing throughout.
    scene = thesis_scene(concept="flexible_nut", friction={"law": "coulomb", "mu": 0.3},
                         nut={"preload": PRELOAD}, backlash=dict(EXACT),
                         loads={"drive_torque": None, "drive_speed": 0.0,
                                "axial_force": {"type": "table", "times": [0.0, 1.0],
                                                "values": [-1.0, 0.9 * PRELOAD]}},
                         overrides={"damping_ratio": 0.5})
    result = ls.simulate(ls.Scene.from_dict(scene), 1.0)
    assert_same_run(result, ls.simulate(ls.Scene.from_dict(without_play(scene)), 1.0))
    assert result["axial_force"][-1] == pytest.approx(0.9 * PRELOAD)
