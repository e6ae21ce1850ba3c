"""LuGre's bristles on Moreau-Jean where a row of the step holds the slip
(issue 32, "fill the matrix"; docs/physics/end_stops.md, "LuGre at a closed
stop"; docs/physics/gear.md, "LuGre's bristles beside the rotor's
contact"): an exact stop holding the rigid drive and the train's rotor
contact. Held, the bristles keep their deflection z and their force
sigma0 z |N|' is part of the balance the rows solve: a drive torque M
pressing the rigid drive into its stop after a slide (z = mu / sigma0, the
steady slide's) clamps it with the raise torque's force M / (r_m tan(alpha
+ rho')), rho' = atan(mu / cos(beta / 2)) (helpers/end_stop_reference.py),
where the set-valued rule's hold (the friction carries nothing) gives
M / (r_m tan alpha); through a stage of ratio n whose rotor contact the
stop's hold leaves unloaded (end_stops.md's rule), n M / (r_m tan(alpha +
rho')). The rotor's stuck contact holding the rigid drive under an axial
load (the relaxed bristles carrying nothing at the held slip) breaks away
at the stage's closed form, T_c + |F| r_m tan(alpha) / (n eta) raising,
T_c - |F| r_m tan(alpha) eta_b / n back-driven. The friction channel
follows LuGre's law at every row, the
account closes with the bristles' stored energy, the friction's loss never
falls (sigma1 = 0: the law is passive), and behind a prescribed rotor speed
Moreau-Jean's losses converge to the event-driven scheme's. Every run passes
its own checks and the independent invariants (helpers/result_invariants.py,
helpers/train_invariants.py)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import leadscrew as ls
from helpers import end_stop_reference as reference
from helpers.result_invariants import check_result, checked_run as checked, failed
from helpers.scenes import thesis_scene

pytestmark = pytest.mark.usefixtures("every_step")

LOSSY = {"type": "lossy", "ratio": 4.0, "efficiency": 0.7, "efficiency_backdrive": 0.4}


def stop_scene(torque=-0.05, mu=0.1, sigma0=1e5, flank_angle=0.0, gap=1e-4, **changes):
    """The rigid thesis drive pressed by a drive torque into its upper exact
    stop ``gap`` [m] away, LuGre on the thread (sigma1 = 0)."""
    thread = {"pitch": 1e-3, "mean_diameter": 20e-3, "flank_angle": flank_angle}
    return thesis_scene(concept="rigid", thread=thread,
                        friction={"law": "lugre", "mu": mu, "sigma0": sigma0, "sigma1": 0.0},
                        loads={"drive_torque": torque, "axial_force": 0.0},
                        end_stops={"upper": gap, "contact": "exact"}, **changes)


def run_checked(scene, t_end, dt, round_off=0.0):
    """A Moreau-Jean run at dt: its own checks and the independent
    invariants pass, the losses never fall (by more than ``round_off`` of
    their end value: where the rotor's stuck contact holds the slip, the
    smooth step books the friction's work at the slip's round-off, 1e-22
    m/s: 1e-48 J of either sign)."""
    result = ls.simulate(ls.Scene.from_dict(scene), t_end, integrator="moreau", dt=dt)
    assert [k for k, c in result.checks.items() if c["applies"] and not c["passed"]] == []
    options = {"integrator": "moreau", "dt": dt, "t_end": t_end}
    assert failed(check_result(result, ls.Scene.from_dict(scene).to_dict(), options)) == []
    for name in ("friction_loss", "damping_loss", "contact_loss"):
        assert np.all(np.diff(result[name]) >= -round_off * abs(result[name][-1])), name
    return result


def held_rows(result):
    """The rows of the last hold (the load at rest, pressed into the stop),
    without its first three: the closing step's (the impact's impulse over
    its step) and, where the velocity level met the face a few 1e-9 m
    short, the steps that close the rest of the gap."""
    pressed = result["stop_force"] < 0.0
    held = np.zeros_like(pressed)
    if pressed[-1]:
        start = len(pressed) - np.argmin(pressed[::-1]) if not pressed.all() else 0
        held[start + 3:] = True
    return held


def assert_lugre_law(result, scene):
    """The friction channel is LuGre's -|N|' sigma0 z at the held rows
    (zero slip, sigma1 = 0), to round-off."""
    friction = scene["friction"]
    held = held_rows(result)
    loaded = np.abs(result["normal_force"][held]) / math.cos(scene["thread"]["flank_angle"] / 2)
    expected = -loaded * friction["sigma0"] * result["bristle_deflection"][held]
    np.testing.assert_allclose(result["friction_force"][held], expected, rtol=1e-12,
                               atol=1e-12 * np.max(np.abs(expected)))
    assert np.all(result["slip_velocity"][held] == 0.0)


@pytest.mark.parametrize("flank_angle", [0.0, math.radians(30.0)])
@pytest.mark.parametrize("dt", [1e-5, 1e-6])
def test_a_held_stop_clamps_with_the_bristles_force_of_the_slide(flank_angle, dt):
    scene = stop_scene(flank_angle=flank_angle)
    result = run_checked(scene, 0.05, dt)
    held = held_rows(result)
    assert held.sum() > 100 and held[-1]
    # The bristles keep the steady slide's deflection mu / sigma0 (z rises
    # with the slip toward +u... its sign the slip's) while held.
    z = result["bristle_deflection"][held]
    assert np.all(z == z[0])
    assert abs(z[0]) == pytest.approx(0.1 / 1e5, rel=1e-9)
    # The clamp: the raise torque's force with the law's coefficient
    # sigma0 |z| = mu (the Coulomb slide's), not the rule's M / (r_m tan alpha).
    clamp = reference.clamp_force(0.05, scene["thread"], 1e5 * abs(z[0]))
    np.testing.assert_allclose(-result["stop_force"][held], clamp, rtol=1e-9)
    assert clamp < 0.2 * reference.clamp_force(0.05, scene["thread"], 0.0)
    assert_lugre_law(result, scene)
    # Held, the bristles neither work nor store: the account's terms stay.
    after = np.flatnonzero(held)[1:]
    for name in ("friction_loss", "work_drive", "elastic"):
        assert np.all(result[name][after] == result[name][after[0]]), name


def test_the_stages_rotor_contact_beside_a_held_stop_carries_nothing():
    # Through a lossy stage with the motor's friction (the train's rotor
    # contact) the stop's hold leaves the rotor's contact unloaded (the
    # rule, end_stops.md): the clamp is n M / (r_m tan(alpha + rho')).
    scene = stop_scene(torque=-0.05, gear=LOSSY, motor={"friction_torque": 1e-3})
    result = run_checked(scene, 0.05, 1e-5)
    held = held_rows(result)
    assert held.sum() > 100 and held[-1]
    z = result["bristle_deflection"][held]
    clamp = reference.train_clamp_force(0.05, scene["thread"], 1e5 * abs(z[0]), 4.0, 1.0)
    np.testing.assert_allclose(-result["stop_force"][held], clamp, rtol=1e-9)
    assert_lugre_law(result, scene)
    after = np.flatnonzero(held)[1:]
    for name in ("gear_loss", "motor_friction_loss"):
        assert np.all(result[name][after] == result[name][after[0]]), name


@settings(max_examples=12, deadline=None)
@given(torque=st.floats(0.03, 0.2), mu=st.floats(0.02, 0.4),
       sigma0=st.sampled_from([1e4, 1e5, 1e6]), flank=st.floats(0.0, 0.6))
def test_every_held_clamp_is_the_raise_torques_with_the_bristles_coefficient(
        torque, mu, sigma0, flank):
    scene = stop_scene(torque=-torque, mu=mu, sigma0=sigma0, flank_angle=flank, gap=1e-5)
    result = run_checked(scene, 0.03, 1e-5)
    held = held_rows(result)
    assert held[-1]
    z = result["bristle_deflection"][held]
    assert np.all(z == z[0]) and sigma0 * abs(z[0]) <= mu * (1 + 1e-12)
    clamp = reference.clamp_force(torque, scene["thread"], sigma0 * abs(z[0]))
    np.testing.assert_allclose(-result["stop_force"][held], clamp, rtol=1e-9)
    assert_lugre_law(result, scene)


def test_the_held_clamp_is_released_when_the_torque_reverses():
    # The torque turns at 0.03 s: the stop's impulse would pull, the stop
    # lets go, the bristles swing through to the reverse slide's -mu /
    # sigma0 as the drive runs back.
    torque = {"type": "table", "times": [0.0, 0.03, 0.031, 0.06],
              "values": [-0.05, -0.05, 0.05, 0.05]}
    scene = stop_scene(torque=torque, gap=1e-5)
    result = run_checked(scene, 0.06, 1e-5)
    pressed = np.flatnonzero(result["stop_force"] < 0.0)
    assert 0.03 < result.t[pressed[-1]] < 0.031
    assert result["u_load"][-1] < 0.0
    assert result["bristle_deflection"][-1] == pytest.approx(-result["bristle_deflection"][pressed[-1]],
                                                             rel=1e-6)


def speed_scene(friction, **changes):
    scene = thesis_scene(gear=LOSSY, friction=friction, motor={"friction_torque": 1e-3},
                         loads={"axial_force": -20.0,
                                "drive_speed": {"type": "sine", "amplitude": 30.0,
                                                "omega": 20.0}}, **changes)
    scene["loads"].pop("drive_torque")
    return scene


def test_behind_a_prescribed_speed_moreau_jean_converges_to_the_event_driven_losses():
    # LuGre (sigma0 = 1e3, resolved by these steps) with a lossy stage and
    # the motor's friction on the flexible nut: the stage's loss of
    # Moreau-Jean tends to the event-driven run's at first order or better;
    # the event-driven scheme stays the default.
    scene = speed_scene({"law": "lugre", "mu": 0.3, "sigma0": 1e3}, concept="flexible_nut")
    s = ls.Scene.from_dict(scene)
    assert ls._core.drive_integrators(s.model().parameters) == ["event_driven", "moreau"]
    exact = checked(scene, 0.1, integrator="event_driven", rtol=1e-11, atol=1e-13)
    dts = [2e-4, 1e-4, 5e-5, 2.5e-5]
    errors = [abs(checked(scene, 0.1, integrator="moreau", dt=dt)["gear_loss"][-1]
                  - exact["gear_loss"][-1]) for dt in dts]
    assert np.polyfit(np.log(dts), np.log(errors), 1)[0] > 0.9, errors
    assert errors[-1] < 1e-3 * exact["gear_loss"][-1]



@pytest.mark.parametrize("direction", [-1, 1])
@pytest.mark.parametrize("dt", [1e-5, 1e-6])
def test_the_rotors_contact_breaks_away_at_the_stages_closed_form(direction, dt):
    # The rigid drive without play through a lossy stage (n = 4, eta = 0.7,
    # eta_b = 0.4) under F = -20 N, the motor's friction T_c = 1e-3 N m
    # holding the rotor, a torque ramp of 0.5 N m/s. The rotor's contact and
    # the thread's row fix every velocity: the thread's slip is theirs (0),
    # the relaxed bristles (z = 0) carry nothing, so the thread passes the
    # load's frictionless torque |F| r_m tan(alpha) and the rotor breaks away
    # where the motor overcomes T_c and the stage's share: raising the load
    # (the motor drives the stage) at T_c + |F| r_m tan(alpha) / (n eta),
    # with the load back-driving at T_c - |F| r_m tan(alpha) eta_b / n.
    torque = {"type": "table", "times": [0.0, 0.1], "values": [0.0, direction * 0.05]}
    scene = thesis_scene(concept="rigid", thread={"pitch": 1e-3, "mean_diameter": 20e-3},
                         friction={"law": "lugre", "mu": 0.1, "sigma0": 1e5, "sigma1": 0.0},
                         gear=LOSSY, motor={"friction_torque": 1e-3},
                         loads={"drive_torque": torque, "axial_force": -20.0})
    result = run_checked(scene, 0.01, dt, round_off=1e-30)
    screw_torque = 20.0 * 0.01 * 1e-3 / (2 * math.pi * 0.01)  # |F| r_m tan(alpha)
    breakaway = (1e-3 + screw_torque / (4.0 * 0.7) if direction < 0
                 else 1e-3 - screw_torque * 0.4 / 4.0) / 0.5
    moving = np.flatnonzero(np.abs(result["omega_drive"]) > 1e-9)
    assert breakaway <= result.t[moving[0]] <= breakaway + 2 * dt
    held = result.t < breakaway
    assert np.all(np.abs(result["omega_drive"][held]) < 1e-15)
    assert np.all(np.abs(result["bristle_deflection"][held]) < 1e-20)
