"""The train's friction stages in Moreau-Jean's time stepping (issue 19,
items 1 and 2 on every concept; docs/physics/gear.md, "Moreau-Jean"): the
motor's Coulomb friction and a lossy or worm stage as the rotor's friction
contact beside the thread's. Against the event-driven TrainSolver (itself
tested against tests/helpers/train_reference.py) on the rigid drive without
play: the steady state, the stages' losses at first order in dt, holding;
against the closed forms on every concept: a self-locking worm and thread
hold with play, a worm above its friction angle back-drives at the
combination's acceleration, the train's efficiency is the product of the
stages'; the shipped flexible seat adjuster with its worm; the refusals."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers import dc_motor_reference
from helpers import end_stop_reference
from helpers import train_reference as reference
from helpers.result_invariants import check_result, failed
from helpers.scenes import thesis_scene

# Its checks read each run step by step: every step kept (simulate's default
# samples a long run's steps).
pytestmark = pytest.mark.usefixtures("every_step")

R, KT, L, U, F = 2.0, 0.05, 1e-3, 3.0, 10.0  # [Ohm], [N m/A], [H], [V], [N]
DC_MOTOR = {"type": "dc", "voltage": U, "resistance": R, "inductance": L, "torque_constant": KT}
RATIO = 4.0
LOSSY = {"type": "lossy", "ratio": RATIO, "efficiency": 0.7, "efficiency_backdrive": 0.4}
WORM = {"type": "worm", "ratio": RATIO, "lead_angle": 0.3, "mu": 0.05}  # back-drives
SELF_LOCKING_WORM = {"type": "worm", "ratio": 10.0, "lead_angle": math.radians(3.0), "mu": 0.1}
DEFAULT_FLANK = math.radians(40.0)


def efficiencies(gear):
    """(eta, eta_b) of a scene's gear section."""
    if gear["type"] == "worm":
        return reference.worm_efficiencies(gear["lead_angle"], gear["mu"],
                                           gear.get("flank_angle", DEFAULT_FLANK))
    return gear["efficiency"], gear["efficiency_backdrive"]


def assert_checked(result, scene, dt, t_end):
    """The run's own checks and the independent invariants pass; every loss
    never falls."""
    assert [k for k, c in result.checks.items() if c["applies"] and not c["passed"]] == []
    options = {"integrator": "moreau", "dt": dt, "t_end": t_end}
    assert failed(check_result(result, ls.Scene.from_dict(scene).to_dict(), options)) == []
    for name in ("gear_loss", "motor_friction_loss", "friction_loss", "damping_loss"):
        if name in result.channels:
            assert np.all(np.diff(result[name]) >= 0.0), name


def dc_scene(gear, friction_torque=0.0, concept="rigid"):
    scene = thesis_scene(concept=concept, loads={"axial_force": F}, gear=gear,
                         motor={**DC_MOTOR, "friction_torque": friction_torque})
    scene["loads"].pop("drive_torque")
    return scene


@pytest.mark.parametrize("gear", [LOSSY, WORM])
@pytest.mark.parametrize("friction_torque", [0.0, 2e-3])
def test_the_train_converges_to_the_event_driven_run(gear, friction_torque):
    # The DC motor raising the load through the stage from rest, 2 s: the
    # steady current and speed are the step's fixed point (to the event-driven
    # run's own tolerance); the stages' losses, integrals over the start,
    # converge at first order in dt (measured 1.00 to 1.02).
    scene = dc_scene(gear, friction_torque)
    s = ls.Scene.from_dict(scene)
    exact = ls.simulate(s, 2.0, rtol=1e-10, atol=1e-12)
    losses = [name for name in ("gear_loss", "motor_friction_loss") if name in exact.channels]
    errors = {name: [] for name in losses}
    for dt in (1e-3, 5e-4, 2.5e-4):
        result = ls.simulate(s, 2.0, integrator="moreau", dt=dt)
        assert_checked(result, scene, dt, 2.0)
        for name in ("motor_current", "omega_drive"):
            assert result[name][-1] == pytest.approx(exact[name][-1], rel=1e-8), name
        for name in losses:
            errors[name].append(abs(result[name][-1] - exact[name][-1]))
    for name, error in errors.items():
        orders = np.log2(np.array(error[:-1]) / np.array(error[1:]))
        assert np.all((orders > 0.9) & (orders < 1.1)), (name, error, orders)


SELF_LOCKING_STAGES = [{"type": "lossy", "ratio": 10.0, "efficiency": 0.8,
                        "efficiency_backdrive": backdrive} for backdrive in (0.0, -0.5)]


@pytest.mark.parametrize("gear", SELF_LOCKING_STAGES + [SELF_LOCKING_WORM])
@pytest.mark.parametrize("mu, force", [(mu, force) for mu in (0.3, 0.005)
                                       for force in (-50.0, 50.0)])
def test_a_self_locking_stage_holds_on_the_rigid_drive(gear, mu, force):
    # eta_b <= 0 holds the load with a free rotor behind a self-locking
    # thread (mu = 0.3) and behind one the load back-drives (mu = 0.005: the
    # back-driving torque on the driven part is the stage's to hold): no
    # motion beyond round-off, the thread stuck at every step.
    dt = 1e-4
    scene = thesis_scene(rotor={"inertia": 1e-6}, nut={"position": 0.25}, gear=gear,
                         loads={"drive_torque": 0.0, "axial_force": force},
                         friction={"law": "coulomb", "mu": mu})
    result = ls.simulate(ls.Scene.from_dict(scene), 0.1, integrator="moreau", dt=dt)
    assert efficiencies(gear)[1] <= 0.0
    assert np.max(np.abs(result["omega_drive"])) <= 1e-15
    assert np.max(np.abs(result["u_load"])) <= 1e-15
    assert np.all(result["stick"][1:] == 1.0)
    assert_checked(result, scene, dt, 0.1)


def held_with_play(concept, gear, mu, force):
    dt, t_end = 1e-4, 0.1
    scene = thesis_scene(concept=concept, rotor={"inertia": 1e-6}, nut={"position": 0.25},
                         gear=gear, backlash={"axial": 1e-4, "contact": "exact"},
                         loads={"drive_torque": 0.0, "axial_force": force},
                         friction={"law": "coulomb", "mu": mu})
    result = ls.simulate(ls.Scene.from_dict(scene), t_end, integrator="moreau", dt=dt)
    assert_checked(result, scene, dt, t_end)
    return result


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut", "flexible"])
@pytest.mark.parametrize("mu", [0.3, 0.005])
@pytest.mark.parametrize("force", [-50.0, 50.0])
def test_a_self_locking_worm_and_thread_hold_with_play_on_every_concept(concept, mu, force):
    # 0.1 mm of exact play: the load falls onto a flank and the springs take
    # the load, while the self-locking worm holds the rotor at rest (round-off)
    # under a pure axial load (mu = 0.3, a self-locking thread) and under the
    # back-driving torque a thread of mu = 0.005 puts on the driven part; the
    # load crosses the play (0.1 mm) at most and comes to rest on a flank,
    # half the play and the springs' deflection (5 um) from its start. The
    # same train with a worm above its friction angle is back-driven: its
    # rotor runs away (the test's power).
    result = held_with_play(concept, SELF_LOCKING_WORM, mu, force)
    assert np.max(np.abs(result["omega_drive"])) <= 1e-15
    assert np.max(np.abs(result["phi_drive"])) <= 1e-15
    assert np.max(np.abs(result["u_load"])) <= 1e-4
    assert abs(result["u_load"][-1]) == pytest.approx(0.5e-4, abs=1e-5)
    assert np.sign(result["u_load"][-1]) == np.sign(force)
    if mu == 0.005:
        runs = held_with_play(concept, {**SELF_LOCKING_WORM, "lead_angle": math.radians(30.0)},
                              mu, force)
        assert np.abs(runs["phi_drive"][-1]) > 1.0


def test_a_worm_above_its_friction_angle_back_drives():
    # gamma = 30 deg > rho'_w behind a thread that back-drives: the load
    # drives the train from rest at the consistent backward combination's
    # constant acceleration phi'' = (a U + eta_b b F) / (eta_b + a n^2 J_r),
    # which the step integrates exactly.
    gear = {"type": "worm", "ratio": 10.0, "lead_angle": math.radians(30.0), "mu": 0.05}
    scene = thesis_scene(rotor={"inertia": 1e-6}, nut={"position": 0.25}, gear=gear,
                         loads={"drive_torque": 0.0, "axial_force": -50.0},
                         friction={"law": "coulomb", "mu": 0.005})
    s = ls.Scene.from_dict(scene)
    eta, eta_b = efficiencies(gear)
    assert eta_b > 0.0
    drive = dc_motor_reference.rigid_drive(s.to_dict(), s.derived())
    starts = reference.consistent_starts(drive, 10.0, 0.0, -50.0, 0.0, eta, eta_b)
    assert len(starts) == 1
    dt = 1e-4
    result = ls.simulate(s, 0.1, integrator="moreau", dt=dt)
    np.testing.assert_allclose(result["omega_drive"], 10.0 * starts[0] * result.t, rtol=1e-12,
                               atol=1e-15)
    assert result["gear_loss"][-1] > 0.0
    assert_checked(result, scene, dt, 0.1)


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut"])
@pytest.mark.parametrize("gear", [LOSSY, WORM])
def test_the_train_efficiency_is_the_product_of_the_stages(concept, gear):
    # The DC motor raising the load at the steady state: F v / (T omega_rotor)
    # = eta tan(alpha) / tan(alpha + rho') (measured: 1e-11 and below).
    dt = 1e-4
    scene = dc_scene(gear, concept=concept)
    s = ls.Scene.from_dict(scene)
    result = ls.simulate(s, 2.0, integrator="moreau", dt=dt)
    efficiency = -F * result["v_load"][-1] / (result["drive_torque"][-1] *
                                              result["omega_drive"][-1])
    eta, _ = efficiencies(gear)
    assert efficiency == pytest.approx(eta * ls.efficiency(s.thread, 0.3), rel=1e-9)
    assert_checked(result, scene, dt, 2.0)


def test_a_worm_breaks_away_at_its_static_efficiency():
    # A torque ramp on the rotor against an axial load, through a
    # self-locking worm with mu_static = 1.5 mu: the train sticks (the
    # static efficiencies, the thread's static cone) until the event-driven
    # TrainSolver's breakaway (tested against the closed form T_d / n k_s),
    # and the first step that slips is the step that contains it.
    gear = {**SELF_LOCKING_WORM, "mu_static": 0.15}
    scene = thesis_scene(rotor={"inertia": 1e-6}, nut={"position": 0.25}, gear=gear,
                         loads={"drive_torque": {"type": "table", "times": [0.0, 1.0],
                                                 "values": [0.0, 0.05]},
                                "axial_force": -20.0})
    s = ls.Scene.from_dict(scene)
    exact = ls.simulate(s, 1.0)
    assert [e.kind for e in exact.events] == ["stick->slip+"]
    breakaway = exact.events[0].time
    for dt in (1e-3, 1e-4):
        result = ls.simulate(s, 1.0, integrator="moreau", dt=dt)
        moving = np.flatnonzero(np.abs(result["omega_drive"]) > 1e-9)
        assert result.t[moving[0]] - dt <= breakaway <= result.t[moving[0]]
        assert np.max(np.abs(result["omega_drive"][:moving[0]])) <= 1e-12  # (round-off)
        assert_checked(result, scene, dt, 1.0)


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut"])
@pytest.mark.parametrize("friction_torque", [0.0, 2e-3])
def test_a_stalled_motor_clamps_through_the_worm_at_the_closed_form(concept, friction_torque):
    # A DC motor drives the load through a self-locking worm into a penalty
    # stop (damped well beyond critical, from its face) and stalls where
    # F r_m tan(alpha + rho') / (n eta) + T_c = k_t U / R (gear.md, "The clamp
    # of a stalled motor"): the step's fixed point, to round-off.
    dt = 1e-4
    worm = {"type": "worm", "ratio": 10.0, "lead_angle": 0.06, "mu": 0.1,
            "flank_angle": DEFAULT_FLANK}
    thread = {"pitch": 1e-3, "mean_diameter": 20e-3, "flank_angle": 0.0}
    scene = thesis_scene(concept=concept, thread=thread, friction={"mu": 0.3},
                         loads={"axial_force": 0.0}, gear=worm,
                         end_stops={"lower": -1e-9, "stiffness": 1e7, "damping": 3e5},
                         motor={**DC_MOTOR, "friction_torque": friction_torque})
    scene["loads"].pop("drive_torque")
    result = ls.simulate(ls.Scene.from_dict(scene), 1.5, integrator="moreau", dt=dt)
    clamp = end_stop_reference.train_clamp_force(KT * U / R, thread, 0.3, 10.0,
                                                 efficiencies(worm)[0], friction_torque)
    assert result["stop_force"][-1] == pytest.approx(clamp, rel=1e-12)
    assert result["motor_current"][-1] == pytest.approx(U / R, rel=1e-12)
    assert_checked(result, scene, dt, 1.5)


def test_the_flexible_seat_adjuster_runs_with_its_worm():
    # The shipped scene (flexible, nut-driven, 0.1 mm exact play, exact stops,
    # the self-locking worm and the motor's friction) on its default
    # integrator, Moreau-Jean: the seat reaches its rear stop within the
    # first second and the motor stalls there at U / R = 20 A, the exact stop
    # holding the seat and balancing the clamp; the account closes.
    scene = ls.scenes.load("seat_adjuster_worm_flexible")
    assert ls._core.drive_integrators(scene.model().parameters) == ["moreau"]
    result = ls.simulate(scene, 1.0)
    assert result.integrator == "moreau"
    first = np.flatnonzero(result["stop_force"] > 0.0)[0]
    assert 0.4 < result.t[first] < 0.7
    # The plastic impact's step (v+ = 0, q+ = q0 + h v_theta) ends within
    # h |u'0| / 2 of the face, short of it or beyond it (the exact flank's
    # position before decides which: 4.3e-7 m short since the flanks are met
    # without passing them, 2.7e-7 m beyond before): the load never leaves
    # the face by more, comes back within 2 ms and is held from then on.
    reach = 0.5 * 1e-4 * abs(result["v_load"][first - 1])
    assert np.all(result["u_load"][first:] + 5e-3 <= reach)
    assert np.all(result["stop_force"][result.t >= result.t[first] + 2e-3] > 0.0)
    assert result["stop_force"][-1] > 1e3  # the clamp
    assert result["motor_current"][-1] == pytest.approx(12.0 / 0.6, rel=1e-9)
    late = result.t > 0.8
    assert np.all(np.abs(result["v_load"][late]) < 1e-15)
    assert np.all(np.abs(result["u_load"][late] + 5e-3) < 1e-5)
    assert result["gear_loss"][-1] > 0.0 and result["motor_friction_loss"][-1] > 0.0
    assert_checked(result, scene.to_dict(), 1e-4, 1.0)


def test_what_still_cannot_run_is_refused_naming_the_integrator_that_runs_it():
    # (Stribeck on the rigid concept without play: the event-driven scheme
    # does not take it; exact play it does since issue 32.)
    d = dc_scene(SELF_LOCKING_WORM, 2e-3, concept="rigid")
    d["friction"] = {"law": "stribeck", "mu": 0.12, "mu_static": 0.15}
    scene = ls.Scene.from_dict(d)
    with pytest.raises(ValueError) as info:
        ls.simulate(scene, 0.01, integrator="cvode_bdf")
    assert str(info.value).startswith(
        'integrator = "cvode_bdf" is invalid with gear.type = "worm": the train\'s friction '
        'stages run on Moreau-Jean (integrator = "moreau", every thread law but '
        'arctan_acceleration)')
    # (Only Moreau-Jean runs this scene: no other integrator is offered.)
    assert str(info.value).endswith('; this scene runs on Moreau-Jean only (here '
                                    'friction.law = "stribeck")')
    assert "event_driven" not in str(info.value)
    with pytest.raises(ValueError) as info:
        ls.simulate(scene, 0.01, integrator="event_driven")
    assert 'here friction.law = "stribeck"; use integrator = "moreau"' in str(info.value)


def test_the_flexible_seat_adjusters_refusals_offer_moreau_jean_alone():
    # (A new user's review: dt = 0.01, rtol and a failed check offered the
    # event-driven scheme or rtol, which this scene refuses.)
    scene = ls.scenes.load("seat_adjuster_worm_flexible")
    with pytest.raises(ValueError) as info:
        ls.simulate(scene, 0.01, rtol=1e-6)
    message = str(info.value)
    assert message.startswith("rtol = 1e-06 is invalid with integrator 'moreau' (the default "
                              "here)")
    assert message.endswith("this scene runs on Moreau-Jean only, so rtol has no use here: a "
                            "shorter dt makes the run more accurate")
    assert "event_driven" not in message and "cvode" not in message
    # A step too long for the flank impacts fails its check; the hint names dt.
    with pytest.raises(ls.SimulationError) as info:
        ls.simulate(scene, 0.5, dt=1e-3)
    message = str(info.value)
    assert "the result fails its check 'flank_gap'" in message
    assert "the run did not resolve the scene (shorten dt)" in message
    assert "rtol" not in message and "atol" not in message


@pytest.mark.parametrize("stage", ["worm", "friction_torque"])
def test_a_preloaded_nut_with_a_train_stage_runs_on_moreau_with_and_without_lift_off(stage):
    # (A new user's review: a worm and a preloaded nut were refused in two
    # rounds, first for friction.mu_static, then for the worm. The stages
    # now take a preloaded nut without lift-off on Moreau-Jean, the default:
    # the seat's exact play closed by 500 N of preload, which holds its
    # motor start's swing; docs/physics/preloaded_nut.md, "Moreau-Jean".)
    scene = ls.scenes.load("seat_adjuster_worm_flexible").to_dict()
    scene["nut"]["preload"] = 500.0
    if stage == "friction_torque":  # the motor's friction alone
        scene["gear"] = {"type": "ideal", "ratio": 10.0}
        scene["motor"]["friction_torque"] = 2e-3
    what = 'gear.type = "worm"' if stage == "worm" else "motor.friction_torque = 0.002 N m"
    dt = 1e-4
    result = ls.simulate(ls.Scene.from_dict(scene), 0.05, dt=dt)
    assert result.t[-1] == 0.05
    assert result["friction_loss"][-1] > 0.0
    assert_checked(result, scene, dt, 0.05)
    # A nut that lifts off (penalty play) runs with the stage on Moreau-Jean
    # too (moreau_lift_off.cpp; issue 32): its account and checks hold.
    scene["backlash"] = {"axial": 1e-4, "contact": "bistop", "stiffness": 1e8, "exponent": 1.0}
    scene["nut"]["preload_stiffness"] = 1e6
    scene.get("initial", {}).pop("play_position", None)  # (the assembled nut: ignored)
    result = ls.simulate(ls.Scene.from_dict(scene), 0.05, dt=dt)
    assert result.integrator == "moreau"
    assert result.t[-1] == 0.05 and what
    assert np.ptp(result["preload_force"]) > 0.0  # (the spring works)
    assert_checked(result, scene, dt, 0.05)


# Issue 31, reproduction 4: a rigid drive without play whose thread is in the
# Painleve regime (a nut-driven drive, mu = 0.4, a light screw and load) with
# the motor's friction. The event-driven train solver takes the modes in closed
# form outside that regime only, so only Moreau-Jean runs the scene: it is the
# default (docs/physics/gear.md, "Friction stages"), and event_driven is refused
# naming the regime and the way out.
PAINLEVE_TRAIN = {"drive": "nut", "thread": {"pitch": 0.002, "mean_diameter": 0.03,
                                             "hand": "left"},
                  "friction": {"mu": 0.4},
                  "motor": {"type": "dc", "voltage": 20.0, "resistance": 3.0,
                            "torque_constant": 0.04, "friction_torque": 3e-05},
                  "gear": {"ratio": 0.3}}


def test_a_train_in_the_painleve_regime_runs_on_moreau_by_default():
    scene = ls.Scene.from_dict(PAINLEVE_TRAIN)
    assert list(ls._core.drive_integrators(scene.model().parameters)) == ["moreau"]
    result = ls.simulate(scene, 0.5)
    assert result.integrator == "moreau"
    assert_checked(result, PAINLEVE_TRAIN, 1e-4, 0.5)
    assert result["motor_friction_loss"][-1] > 0.0
    with pytest.raises(ValueError, match=r"integrator = \"event_driven\" is invalid with "
                                         r"motor\.friction_torque = 3e-05.*Painleve regime.*"
                                         r"use integrator = \"moreau\""):
        ls.simulate(scene, 0.5, integrator="event_driven")
