"""Fuzz test of ``leadscrew.simulate`` over random scenes (issue 17, item 3).

Every case of the generator (``helpers.scene_fuzz``: all concepts, drives,
laws, contacts, integrators, excitations and start states, about 15 % with
hostile values) has exactly one of the outcomes the issue allows: a result
that passes its checks (``helpers.result_invariants``), a ``ValueError``
naming a key or option the case set, a ``SimulationError`` or a
``JammingError``. Never another exception, a crash, a hang or a non-finite
number. Each case runs in its own forked child process with a time limit
(``CASE_TIMEOUT``), two at a time; the cases are drawn by hypothesis with a
fixed seed, so CI runs the same ones every time. ``tests/fuzz_scenes.py``
runs the same generator for 10,000 cases.

The other tests here check the harness itself: the checker on hand-made good
and bad results, the classification of outcomes, crashes and hangs.
"""

import json
import math
import os
import signal
import time

import numpy as np
import pytest
from hypothesis import given, settings

import leadscrew as ls
from helpers.fake_result import FakeResult
from helpers.result_invariants import INVARIANTS, check_result, failed
from helpers.scene_fuzz import (ALLOWED, DEFAULT_SEED, FAILURES, OUTCOMES, cases, generate,
                                make_case, names_user_key, prepare_parent, run_all_allowed, run_case,
                                run_isolated)
from helpers.scenes import thesis_scene
from leadscrew.simulation import unused_option

# Its checks read each run step by step: every step kept (simulate's default
# samples a long run's steps).
pytestmark = pytest.mark.usefixtures("every_step")

# A few hundred cases in well under two minutes on the 2-core machine
# (measured: 300 cases in 14 s with two workers on a quiet machine, 45 s at a
# load average of 4.5).
FUZZ_CASES = 300
# A case that takes longer is a hang (the slowest valid cases stop at their
# max_steps within about two seconds).
CASE_TIMEOUT = 8.0
# Not only refusals: the share of the cases that run and pass. The cases are
# the fixed seed's and the core is deterministic, so the count moves only
# when the code does: 210 of the 300 passed at 8fe563d (51 named ValueErrors,
# 34 SimulationErrors, 3 results refused by their own checks, 2 jams; 251 of
# the 300 are valid). The margin is one case (a borderline check that a
# different compiler or libm may round the other way): two cases turned into
# refusals (what two of the mutants of issue 31 did, unnoticed) fail the
# test. A change that answers more cases may raise it; one that answers fewer
# must say why where it lowers it.
MIN_PASSED = 209


def test_jamming_error_is_a_simulation_error():
    assert issubclass(ls.JammingError, ls.SimulationError)
    assert not issubclass(ls.SimulationError, ValueError)


def test_fuzz_simulate():
    prepare_parent()
    drawn = generate(FUZZ_CASES, DEFAULT_SEED)
    assert len(drawn) == FUZZ_CASES
    counts = run_all_allowed(drawn, CASE_TIMEOUT)
    assert counts["passed"] >= MIN_PASSED, counts


# --- the generator -----------------------------------------------------------

def test_generator_is_deterministic_and_covers_the_space():
    first = [json.dumps(c, sort_keys=True) for c in generate(60, 5)]
    assert first == [json.dumps(c, sort_keys=True) for c in generate(60, 5)]
    assert first != [json.dumps(c, sort_keys=True) for c in generate(60, 6)]
    drawn = generate(400, DEFAULT_SEED)
    for tag, values in [("concept", {"rigid", "flexible_nut", "flexible"}),
                        ("drive", {"screw", "nut"}),
                        ("law", {"coulomb", "arctan_velocity", "arctan_acceleration", "stribeck",
                             "lugre"}),
                        ("contact", {"none", "exact", "bistop", "cubic"}),
                        ("motor", {"torque", "speed", "dc"})]:
        assert {c["tags"][tag] for c in drawn} == values, tag
    # Issue 19's elements (a DC motor, an ideal gear stage, end stops, a
    # preloaded nut, a lossy or worm stage, the motor's friction), and the
    # preloaded nut on every concept.
    trains = {part for c in drawn for part in c["tags"]["train"].split("+")}
    assert trains == {"none", "dc_motor", "gear", "end_stops", "preload", "stage",
                      "motor_friction"}
    assert {c["tags"]["concept"] for c in drawn if "preload" in c["tags"]["train"]} == {
        "rigid", "flexible_nut", "flexible"}
    integrators = {c["tags"]["integrator"] for c in drawn}
    assert integrators >= {"event_driven", "moreau", "default", "cvode_bdf", "cvode_adams",
                           "dopri5", "verner6", "rk_dopri5", "rk_verner6"}
    hostile = sum(bool(c["hostile"]) for c in drawn) / len(drawn)
    assert 0.10 < hostile < 0.20
    # A case is its seed's.
    case = drawn[17]
    assert json.dumps(make_case(case["seed"]), sort_keys=True) == json.dumps(case, sort_keys=True)


@settings(max_examples=20, deadline=None, derandomize=True, database=None)
@given(cases())
def test_strategy_draws_cases(case):
    assert set(case) == {"seed", "scene", "options", "hostile", "tags"}
    assert json.dumps(make_case(case["seed"]), sort_keys=True) == json.dumps(case, sort_keys=True)


def test_valid_cases_are_valid_scenes():
    """Without hostile values a case's scene is valid (from_dict accepts it),
    its integrator fits, its run is bounded and short, and it sets only
    options its integrator takes (simulate refuses the others)."""
    for case in generate(200, 11, hostile_share=0.0):
        assert not case["hostile"]
        scene = ls.Scene.from_dict(case["scene"])
        options = case["options"]
        assert 0.01 <= options["t_end"] <= 0.2
        assert options["max_steps"] <= 100_000 and options["max_events"] <= 2_000
        try:  # (a valid scene may still have no model: load.mass = 0 with a flexible nut)
            model = scene.model()
        except ValueError:
            continue
        integrator = options.get("integrator") or ls._core.drive_integrators(
            model.parameters)[0]
        assert unused_option(integrator, options, scene) is None, case


def test_names_user_key():
    case = {"scene": {"concept": "rigid", "nut": {"density": 5e-324, "outer_radius": {"x": 1}},
                      "loads": {"drive_torque": {"type": "sine", "omega": math.nan}}},
            "options": {"t_end": 0.1, "max_steps": 10, "dt": 1e-4}}
    assert names_user_key("nut.density = 5e-324 is invalid", case) == "nut.density"
    assert names_user_key("nut.outer_radius = {'x': 1} is invalid", case) == "nut.outer_radius"
    assert names_user_key("loads.drive_torque.omega = nan is invalid", case) == (
        "loads.drive_torque.omega")
    assert names_user_key("loads.drive_torque: times must increase", case) == (
        "loads.drive_torque")
    assert names_user_key("max_steps = 10 is too small", case) == "max_steps"
    assert names_user_key("dt = 0.0001 is invalid", case) == "dt"
    # Derived quantities, keys never given, or a longer name are not the key.
    assert names_user_key("nut mass = 0 is invalid", case) is None
    assert names_user_key("backlash.stiffness = 0 is invalid", case) is None
    assert names_user_key("max_step = 1 is invalid", case) is None
    assert names_user_key("tol = inf is invalid", case) is None
    assert names_user_key("width = 3", case) is None


# --- outcomes ---------------------------------------------------------------

def _case(scene, **options):
    options.setdefault("t_end", 0.05)
    return {"scene": scene, "options": options, "hostile": [], "tags": {}}


def test_run_case_outcomes():
    good = run_case(_case(thesis_scene()))
    assert good["outcome"] == "passed", good
    named = run_case(_case(thesis_scene(nut={"youngs_modulus": "3 N"})))
    assert named["outcome"] == "value_error_named" and "nut.youngs_modulus" in named["message"]
    option = run_case(_case(thesis_scene(), dt=-1.0, integrator="moreau"))
    assert option["outcome"] == "value_error_named" and "dt" in option["message"]
    # The nut leaves the screw: a SimulationError inside the run.
    speed = thesis_scene()
    speed["loads"] = {"drive_speed": 4000.0}
    off = run_case(_case(speed, t_end=1.0))
    assert off["outcome"] == "simulation_error", off
    # Every outcome of run_case is one of the table's.
    assert {good["outcome"], named["outcome"], off["outcome"]} <= set(OUTCOMES)


def _crash(case):
    os.kill(os.getpid(), signal.SIGSEGV)


def _sleep(case):
    time.sleep(30)


def _raise(case):
    raise RuntimeError("not an outcome")


def test_run_isolated_reports_crashes_and_hangs():
    prepare_parent()
    start = time.monotonic()
    crash = dict(run_isolated([(0, {})], timeout=5.0, function=_crash))[0]
    assert crash["outcome"] == "crash" and "signal 11" in crash["message"]
    hang = dict(run_isolated([(0, {})], timeout=0.5, function=_sleep))[0]
    assert hang["outcome"] == "hang"
    died = dict(run_isolated([(0, {})], timeout=5.0, function=_raise))[0]
    assert died["outcome"] == "crash" and "exit code 1" in died["message"]
    assert time.monotonic() - start < 10.0
    # Two workers, answers of every case, in any order.
    answers = dict(run_isolated(((i, _case(thesis_scene())) for i in range(4)), timeout=30.0))
    assert sorted(answers) == [0, 1, 2, 3]
    assert {a["outcome"] for a in answers.values()} == {"passed"}


@pytest.mark.parametrize("case_seed, what", [
    # ARKODE's step size became NaN from initial.rotor_speed = 1e300: the
    # SimulationError reported t = NaN (now the last time reached)
    (18151288792, "error_time"),
    # a rigid drive with exact play and penalty end stops, speed-controlled:
    # the play 1.4e-3 of the clearance beyond a flank, 0.6 atol, within the
    # documented bound 1e-3 c + 10 atol that the checker had left out
    (2749764, "check_failed"),
])
def test_cases_a_long_run_failed_now_pass(case_seed, what):
    """Cases of the 10,000-case run of 2026-11-27 (seed 20261217) that failed
    (outcome ``what`` then), replayed from their case seeds."""
    outcome = run_case(make_case(case_seed))
    assert outcome["outcome"] in ALLOWED, (what, outcome)


@pytest.mark.parametrize("case_seed", [406739, 92707])
def test_a_trial_stage_off_the_screw_does_not_end_an_own_runge_kutta_run(case_seed):
    """Flexible drives on rk_verner6 / rk_dopri5 whose first step's trial
    stage put the nut beyond the screw's end (15 mm off, in 0.1 ms) ended
    with NutOffScrewError at that stage, where the run of 2026-11-27 01:00
    had answered: the own Runge-Kutta engines now reject such a step as a
    non-finite one and shorten it (as the SUNDIALS integrators retry), and
    raise only where shorter steps meet the screw's end too."""
    outcome = run_case(make_case(case_seed))
    assert outcome["outcome"] == "passed", outcome


def test_failures_are_the_outcomes_not_allowed():
    assert set(FAILURES) | ALLOWED == set(OUTCOMES)
    assert ALLOWED == {"passed", "value_error_named", "simulation_error", "self_check_raised",
                       "jamming_error"}


# --- the checker on hand-made results -----------------------------------------

def _good(scene_dict, **options):
    options.setdefault("t_end", 0.5)
    scene = ls.Scene.from_dict(scene_dict)
    result = ls.simulate(scene, **options)
    report = check_result(result, scene.to_dict(), options)
    assert not failed(report), report
    return result, scene.to_dict(), options


@pytest.fixture(scope="module")
def coulomb_run():
    """The thesis drive (rigid, exact Coulomb, 30 deg flanks): sticks and slips."""
    return _good(thesis_scene(thread={"pitch": 1e-3, "mean_diameter": 20e-3,
                                      "flank_angle": math.radians(30)}))


def test_checker_passes_good_results(coulomb_run):
    result, scene, options = coulomb_run
    assert len(result.events) > 2 and np.any(result["stick"] == 0)
    report = check_result(result, scene, options)
    assert set(report) == {"finite", "time_axis", "event_times", "friction_power",
                           "friction_loss", "other_losses", "friction_cone", "friction_law",
                           "energy_balance", "kinetic_energy", "motor_torque"}
    assert set(report) <= set(INVARIANTS)
    # A flexible drive with a regularized law and bistop play, an exact-play
    # drive stepped by Moreau-Jean, and arctan_acceleration pass too.
    flexible = thesis_scene(concept="flexible_nut",
                            friction={"law": "arctan_velocity", "mu": 0.3, "k_v": 1e3},
                            backlash={"axial": 1e-4, "contact": "bistop"})
    _good(flexible, t_end=0.2, integrator="cvode_bdf", rtol=1e-8, atol=1e-12)
    moreau = thesis_scene(concept="flexible_nut", backlash={"axial": 1e-4, "contact": "exact"})
    result, scene, options = _good(moreau, t_end=0.2, integrator="moreau", dt=1e-5)
    assert "flank_penetration" in check_result(result, scene, options)
    _good(thesis_scene(friction={"law": "arctan_acceleration", "mu": 0.3, "k_v": 100.0}),
          t_end=0.2)


def _violated(run, **changes):
    result, scene, options = run
    return failed(check_result(FakeResult(result, **changes), scene, options))


def test_checker_flags_non_finite_values(coulomb_run):
    u = np.array(coulomb_run[0]["u_load"])
    u[3] = math.nan
    assert _violated(coulomb_run, u_load=u) == ["finite"]
    t = np.array(coulomb_run[0].t)
    t[-1] = math.inf
    assert _violated(coulomb_run, t=t) == ["finite"]


def test_checker_flags_times(coulomb_run):
    result = coulomb_run[0]
    n = len(result.t) - 5
    short = {name: np.array(result[name])[:n] for name in result.channels}
    assert _violated(coulomb_run, t=np.array(result.t)[:n], **short) == ["time_axis"]
    events = list(result.events)
    events[0] = ls.Event(-0.233, events[0].kind)
    assert _violated(coulomb_run, events=events) == ["event_times"]
    events[0] = ls.Event(0.5 + 1e-6, events[0].kind)
    assert _violated(coulomb_run, events=events) == ["event_times"]


def test_checker_flags_friction_doing_positive_work(coulomb_run):
    result = coulomb_run[0]
    slip = np.array(result["slip_velocity"])
    force = np.array(result["friction_force"])
    i = int(np.argmax(np.abs(slip)))
    force[i] = -force[i]  # pushes the slip it should oppose
    assert _violated(coulomb_run, friction_force=force) == ["friction_power"]
    bound = check_result(*coulomb_run)["friction_loss"]["bound"]
    loss = np.array(result["friction_loss"])
    k = len(loss) // 2
    loss[k] = loss[k - 1] - 0.9 * bound  # falls by 0.9 of the bound
    assert _violated(coulomb_run, friction_loss=loss) == []
    loss[k] = loss[k - 1] - 1.1 * bound
    assert _violated(coulomb_run, friction_loss=loss) == ["friction_loss"]


def test_checker_flags_friction_outside_the_cone_or_off_it_in_slip(coulomb_run):
    result = coulomb_run[0]
    force = np.array(result["friction_force"])
    slip = np.where(np.array(result["stick"]) == 0, np.abs(result["slip_velocity"]), 0.0)
    i = int(np.argmax(slip))
    assert slip[i] > 1e-3
    on_cone = force[i]
    force[i] = on_cone * (1 + 1e-4)
    assert _violated(coulomb_run, friction_force=force) == ["friction_cone"]
    force[i] = on_cone * (1 - 1e-4)  # inside the cone, but it slips
    assert _violated(coulomb_run, friction_force=force) == ["friction_law"]
    force[i] = on_cone * (1 + 1e-8)  # on the cone to round-off
    assert _violated(coulomb_run, friction_force=force) == []


def test_checker_flags_a_wrong_arctan_velocity_law():
    run = _good(thesis_scene(friction={"law": "arctan_velocity", "mu": 0.3, "k_v": 1e3}),
                t_end=0.2, integrator="rk_verner6")
    force = np.array(run[0]["friction_force"])
    i = int(np.argmax(np.abs(force)))
    force[i] *= 1 - 1e-3
    assert _violated(run, friction_force=force) == ["friction_law"]
    force[i] = 0.0  # a flank without friction (issue 17, reproduction 11)
    assert _violated(run, friction_force=force) == ["friction_law"]


def test_checker_flags_energy_and_losses(coulomb_run):
    result = coulomb_run[0]
    report = check_result(*coulomb_run)
    bound = report["energy_balance"]["bound"]
    residual = np.array(result["energy_residual"])
    assert _violated(coulomb_run, energy_residual=residual + 0.9 * bound) == []
    assert _violated(coulomb_run, energy_residual=residual + 2 * bound) == ["energy_balance"]
    assert _violated(coulomb_run, energy_residual=residual - 2 * bound) == ["energy_balance"]
    damping = np.array(result["damping_loss"])
    damping[-1] = -1.0
    assert _violated(coulomb_run, damping_loss=damping) == ["other_losses"]


def test_checker_moreau_may_dissipate_but_not_create_energy():
    run = _good(thesis_scene(concept="flexible_nut", backlash={"axial": 1e-4,
                                                                 "contact": "exact"}),
                t_end=0.2, integrator="moreau", dt=1e-5)
    result = run[0]
    scale = float(np.max(np.abs(result["work_drive"]) + np.abs(result["work_axial"])))
    residual = np.array(result["energy_residual"])
    assert _violated(run, energy_residual=residual + 0.5 * scale) == []
    assert _violated(run, energy_residual=residual - 0.5 * scale) == ["energy_balance"]
    gap = np.array(result["gap"])
    gap[len(gap) // 2] = -0.5e-4  # half the clearance beyond a flank
    assert _violated(run, gap=gap) == ["flank_penetration"]


def test_checker_lets_arctan_acceleration_do_positive_work():
    scene = thesis_scene(friction={"law": "arctan_acceleration", "mu": 0.3, "k_v": 100.0})
    run = _good(scene, t_end=0.2)
    result = run[0]
    force = np.array(result["friction_force"])
    slip = np.array(result["slip_velocity"])
    pushing = np.where(slip != 0, np.abs(force) * np.sign(slip), force)
    loss = np.array(result["friction_loss"])
    assert _violated(run, friction_force=pushing, friction_loss=loss[::-1]) == []
    residual = np.array(result["energy_residual"])
    bound = check_result(*run)["energy_balance"]["bound"]
    assert _violated(run, energy_residual=residual + 2 * bound) == ["energy_balance"]
