"""End stops in Moreau-Jean's time stepping (issue 19, item 3;
docs/physics/end_stops.md, "Moreau-Jean"): the penalty stop's static
deflection F / k and the torque-limited clamp of a slow approach, the clamp
of a stalled DC motor through a stage (tests/helpers/end_stop_reference.py),
the exact stop's Newton rebound -e u' in free flight and its closed contact,
the energy account (the run's own checks and the independent invariants,
the stops' loss never falling), and stops out of reach change no bit."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers import end_stop_reference as reference
from helpers.result_invariants import check_result, failed
from helpers.scenes import thesis_scene

# Its checks read each run step by step: every step kept (simulate's default
# samples a long run's steps).
pytestmark = pytest.mark.usefixtures("every_step")

K = 1e7  # [N/m]


def assert_checked(result, scene, dt, t_end, **options):
    """The run's own checks and the independent invariants pass; the losses
    never fall. ``options``: the run's others (theta, t_eval), which the
    invariants read."""
    assert [k for k, c in result.checks.items() if c["applies"] and not c["passed"]] == []
    options = {**options, "integrator": "moreau", "dt": dt, "t_end": t_end}
    assert failed(check_result(result, ls.Scene.from_dict(scene).to_dict(), options)) == []
    for name in ("damping_loss", "friction_loss", "contact_loss"):
        assert np.all(np.diff(result[name]) >= 0.0), name


def critical_damping(scene, stiffness):
    """2 sqrt(k m_eff) of the rigid screw-driven drive (the load, the nut, the
    rotor's and the screw's inertia through the lead)."""
    derived = ls.Scene.from_dict(scene).derived()
    lead = scene["thread"]["pitch"] * scene["thread"].get("starts", 1)
    mass = (scene["load"]["mass"] + derived["nut_mass"] +
            (scene["rotor"]["inertia"] + derived["screw_inertia"]) * (2 * math.pi / lead) ** 2)
    return 2.0 * math.sqrt(stiffness * mass)


@pytest.mark.parametrize("force, face", [(50.0, "upper"), (-80.0, "lower")])
@pytest.mark.parametrize("dt", [1e-4, 1e-5])
def test_penalty_stop_static_deflection(force, face, dt):
    # The frictionless rigid drive pushed into the stop by the axial force,
    # critically damped: at rest d = F / k, the stop's force -F.
    position = 1e-4 if face == "upper" else -1e-4
    scene = thesis_scene(friction={"mu": 0.0}, loads={"drive_torque": 0.0, "axial_force": force},
                         end_stops={face: position, "stiffness": K})
    scene["end_stops"]["damping"] = critical_damping(scene, K)
    result = ls.simulate(ls.Scene.from_dict(scene), 1.0, integrator="moreau", dt=dt)
    deflection = reference.static_deflection(abs(force), K)
    assert abs(result["u_load"][-1] - position) == pytest.approx(deflection, rel=1e-9)
    assert result["stop_force"][-1] == pytest.approx(-force, rel=1e-12)
    assert_checked(result, scene, dt, 1.0)


@pytest.mark.parametrize("mu, flank_angle", [(0.3, 0.0), (0.1, math.radians(30.0))])
def test_penalty_stop_clamp_of_a_slow_approach(mu, flank_angle):
    # The rigid drive turned by M into the lower stop, overdamped: the stop's
    # force settles at M / (r_m tan(alpha + rho')).
    torque, dt = 0.5, 1e-4
    scene = thesis_scene(thread={"flank_angle": flank_angle}, friction={"mu": mu},
                         loads={"drive_torque": torque, "axial_force": 0.0},
                         end_stops={"lower": -1e-9, "stiffness": 1e8})
    scene["end_stops"]["damping"] = 2.0 * critical_damping(scene, 1e8)
    result = ls.simulate(ls.Scene.from_dict(scene), 1.5, integrator="moreau", dt=dt)
    clamp = reference.clamp_force(torque, scene["thread"], mu)
    assert result["stop_force"][-1] == pytest.approx(clamp, rel=1e-9)
    assert result["u_load"][-1] == pytest.approx(-1e-9 - clamp / 1e8, rel=1e-9)
    assert_checked(result, scene, dt, 1.5)


R, KT, L, U = 2.0, 0.05, 1e-3, 3.0  # [Ohm], [N m/A], [H], [V]
THREAD = {"pitch": 1e-3, "mean_diameter": 20e-3, "flank_angle": 0.0}


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut"])
@pytest.mark.parametrize("dt", [1e-4, 1e-5])
def test_penalty_stop_clamp_of_a_stalled_dc_motor(concept, dt):
    # A DC motor through an ideal stage (n = 10) drives the load into the
    # stop (damped well beyond critical); it stalls where the train needs
    # k_t U / R: F r_m tan(alpha + rho') / n = k_t U / R (gear.md, "The clamp
    # of a stalled motor"). The steady state is a fixed point of the step:
    # reached to round-off at every dt.
    ratio = 10.0
    scene = thesis_scene(concept=concept, thread=THREAD, friction={"mu": 0.3},
                         loads={"axial_force": 0.0}, gear={"ratio": ratio},
                         end_stops={"lower": -1e-9, "stiffness": 1e7, "damping": 3e5},
                         motor={"type": "dc", "voltage": U, "resistance": R, "inductance": L,
                                "torque_constant": KT})
    scene["loads"].pop("drive_torque")
    result = ls.simulate(ls.Scene.from_dict(scene), 1.5, integrator="moreau", dt=dt)
    clamp = reference.train_clamp_force(KT * U / R, THREAD, 0.3, ratio, 1.0)
    assert result["stop_force"][-1] == pytest.approx(clamp, rel=1e-10)
    assert result["motor_current"][-1] == pytest.approx(U / R, rel=1e-10)
    assert_checked(result, scene, dt, 1.5)


def test_penalty_stops_out_of_reach_change_no_bit():
    # The stops never engage: every channel but stop_force is the run's
    # without stops, bit for bit (the flexible nut with exact play, a sine drive).
    scene = thesis_scene(concept="flexible_nut", backlash={"axial": 1e-4, "contact": "exact"})
    with_stops = dict(scene, end_stops={"lower": -0.05, "upper": 0.05, "stiffness": K,
                                        "damping": 300.0})
    plain = ls.simulate(ls.Scene.from_dict(scene), 0.2, integrator="moreau", dt=1e-5)
    stopped = ls.simulate(ls.Scene.from_dict(with_stops), 0.2, integrator="moreau", dt=1e-5)
    assert stopped.channels == plain.channels + ["stop_force"] or \
        set(stopped.channels) == set(plain.channels) | {"stop_force"}
    for name in plain.channels:
        np.testing.assert_array_equal(stopped[name], plain[name], err_msg=name)
    assert np.all(stopped["stop_force"] == 0.0)


def test_penalty_stops_bounce_and_converge_to_the_event_driven_run_at_first_order():
    # A sine drive rattles the rigid drive between two soft stops 0.4 mm
    # apart (contacts, releases, stick and slips of the thread): the load's
    # path converges to the event-driven run's at first order in dt (the
    # largest difference at 601 output times; measured orders 1.00, 1.01).
    scene = thesis_scene(friction={"mu": 0.02},
                         loads={"drive_torque": {"type": "sine", "amplitude": 0.2,
                                                 "omega": 20.0}, "axial_force": 0.0},
                         end_stops={"lower": -2e-4, "upper": 2e-4, "stiffness": 1e6,
                                    "damping": 500.0})
    s = ls.Scene.from_dict(scene)
    t_end = 0.6
    t_eval = np.linspace(0.0, t_end, 601)
    exact = ls.simulate(s, t_end, rtol=1e-11, atol=1e-14, t_eval=t_eval)
    kinds = [e.kind for e in exact.events]
    assert kinds.count("lower end stop contact") >= 2 and "upper end stop release" in kinds
    errors = []
    for dt in (4e-5, 2e-5, 1e-5):
        result = ls.simulate(s, t_end, integrator="moreau", dt=dt, t_eval=t_eval)
        assert_checked(result, scene, dt, t_end, t_eval=list(t_eval))
        errors.append(np.max(np.abs(result["u_load"] - exact["u_load"])))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all((orders > 0.9) & (orders < 1.2)), (errors, orders)
    assert errors[-1] < 1e-4 * np.ptp(exact["u_load"])


# --- exact stops ---------------------------------------------------------------


def free_flight_scene(restitution):
    """The frictionless flexible nut (screw-driven: the load hangs on the nut's
    spring), every body moving with the thread at 50 rad/s: the load flies
    at a constant speed into the lower stop 0.1 mm away."""
    return thesis_scene(concept="flexible_nut", friction={"mu": 0.0},
                        loads={"drive_torque": 0.0, "axial_force": 0.0},
                        initial={"rotor_speed": 50.0},
                        end_stops={"lower": -1e-4, "upper": 1e-4, "contact": "exact",
                                   "restitution": restitution})


@pytest.mark.parametrize("restitution", [1.0, 0.5, 0.2, 0.0])
def test_exact_stop_rebound_is_restitution_times_the_approach_speed(restitution):
    # The step whose predicted position closes the gap ends at -e u'
    # exactly (Newton's law on the velocity level), within a step of
    # u_face / u'.
    dt = 1e-5
    scene = free_flight_scene(restitution)
    result = ls.simulate(ls.Scene.from_dict(scene), 0.02, integrator="moreau", dt=dt)
    speed = result["v_load"]
    approach = speed[0]
    assert approach < 0.0
    impact = np.flatnonzero(np.abs(speed - approach) > 1e-9 * abs(approach))[0]
    assert abs(result.t[impact] - (-1e-4 / approach)) <= dt
    assert speed[impact - 1] == pytest.approx(approach, rel=1e-12)
    # (u' at the step's start: the free flight's, to round-off)
    assert speed[impact] == pytest.approx(-restitution * speed[impact - 1], rel=1e-14, abs=1e-18)
    assert result["stop_force"][impact] > 0.0  # the stop pushes toward +u
    # On the velocity level the face is met a step late: within three steps
    # of the load's largest speed (as the flanks, result_checks.md, flank_gap).
    assert result["u_load"].min() >= -1e-4 - 3.0 * dt * np.max(np.abs(speed))
    assert_checked(result, scene, dt, 0.02)


def test_exact_stop_closes_holds_the_load_and_opens_when_the_force_reverses():
    # Pressed into the lower stop by -40 N (a self-locking thread): the
    # plastic stop holds the load (zero velocity, a position within a step's
    # travel of the face), its force balances the axial force and the nut's
    # spring-damper, and it lets go after the force turns at 0.1 s.
    force = {"type": "table", "times": [0.0, 0.1, 0.11, 0.2], "values": [-40.0, -40.0, 40.0, 40.0]}
    scene = thesis_scene(concept="flexible_nut", loads={"drive_torque": 0.0, "axial_force": force},
                         end_stops={"lower": -1e-6, "contact": "exact"})
    s = ls.Scene.from_dict(scene)
    dt = 1e-5
    result = ls.simulate(s, 0.2, integrator="moreau", dt=dt)
    spring = next(sp for sp in s.model().springs if sp["name"] == "nut axial")
    on_load = (result["axial_force"] + spring["stiffness"] * (result["u_nut"] - result["u_load"])
               + spring["damping"] * (result["v_nut"] - result["v_load"]))
    held = (result.t > 0.02) & (result.t < 0.1)
    assert np.all(np.abs(result["v_load"][held]) < 1e-18)  # (round-off of the solve)
    assert np.all(np.abs(result["u_load"][held] + 1e-6) < 1e-8)
    np.testing.assert_allclose(result["stop_force"][held], -on_load[held], rtol=0,
                               atol=1e-9 * 40.0)
    assert np.all(result["stop_force"][held] > 0.0)
    pushing = np.flatnonzero(result["stop_force"] > 0.0)
    assert 0.1 < result.t[pushing[-1]] < 0.11
    assert np.all(result["stop_force"][result.t > 0.11] == 0.0)
    assert_checked(result, scene, dt, 0.2)


def test_theta_below_one_half_is_refused_where_springs_are():
    # theta < 1/2 lets the springs' modes grow from step to step: the flexible
    # seat at theta = 0.3 ran its nut 0.337 m off the screw and was told to
    # change the loads (a new user's review, 2026-11-27).
    flexible = ls.scenes.load("seat_adjuster_worm_flexible")
    for theta in (0.0, 0.3, 0.49):
        with pytest.raises(ValueError, match=r"theta = 0\.?[0-9]* is invalid .*springs.*\[0\.5, 1\]"):
            ls.simulate(flexible, 0.01, integrator="moreau", theta=theta)
    ls.simulate(flexible, 0.01, integrator="moreau", theta=0.5)
    # a rigid drive without springs or penalty stops takes any theta in [0, 1]
    rigid = ls.Scene.from_dict(thesis_scene(concept="rigid"))
    result = ls.simulate(rigid, 0.01, integrator="moreau", theta=0.3)
    assert result.integrator == "moreau"
