"""Penalty end stops through the train's friction stages (issue 19, items 2
and 3; docs/physics/gear.md, "End stops through the stages"): a DC motor
through a self-locking worm drives the load into a penalty stop; the steady
clamp against the closed form (the motor's stall torque, or its current
limit's, through the stage and the thread:
tests/helpers/end_stop_reference.py's train_clamp_force); switched off at
the stop, the self-locking train holds the clamp; the energy account closes;
stops out of reach change nothing; exact stops stay refused on the rigid
concept (tests/test_event_driven_stages_elements.py runs them off it)."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers import end_stop_reference as reference
from helpers import train_reference
from helpers.result_invariants import check_result, failed
from helpers.scenes import thesis_scene

# Its checks read each run step by step: every step kept (simulate's default
# samples a long run's steps).
pytestmark = pytest.mark.usefixtures("every_step")

R, KT, L, U = 2.0, 0.05, 1e-3, 3.0  # [Ohm], [N m/A], [H], [V]
RATIO = 10.0
# A self-locking worm: mu' = 0.1 / cos(20 deg) = 0.106 > tan(0.06).
WORM = {"type": "worm", "ratio": RATIO, "lead_angle": 0.06, "mu": 0.1,
        "flank_angle": math.radians(40.0)}
THREAD = {"pitch": 1e-3, "mean_diameter": 20e-3, "flank_angle": 0.0}
# The load starts at the stop's face; a stiff stop damped well beyond
# critical: the approach does not overshoot (the self-locking train would
# keep an overshoot's clamp).
STOP = {"lower": -1e-9, "stiffness": 1e7}


def worm_efficiency():
    return train_reference.worm_efficiencies(WORM["lead_angle"], WORM["mu"],
                                             WORM["flank_angle"])[0]


def stop_scene(mu=0.3, damping=3e5, friction_torque=0.0, **motor):
    d = thesis_scene(thread=THREAD, friction={"mu": mu}, loads={"axial_force": 0.0},
                     gear=WORM, end_stops={**STOP, "damping": damping},
                     motor={"type": "dc", "voltage": U, "resistance": R, "inductance": L,
                            "torque_constant": KT, "friction_torque": friction_torque,
                            **motor})
    d["loads"].pop("drive_torque")
    return d


def assert_account_closes(result, scene, options):
    """The energy account with the stop's and the stages' terms: the result
    checks pass, the losses never fall, the residual stays at round-off."""
    for name in ("gear_loss", "motor_friction_loss", "friction_loss", "damping_loss"):
        if name in result.channels:
            assert np.all(np.diff(result[name]) >= -1e-12 * max(1.0, result[name][-1])), name
    work = np.max(np.abs(result["work_drive"]))
    assert np.max(np.abs(result["energy_residual"])) <= 1e-6 * work
    assert failed(check_result(result, ls.Scene.from_dict(scene).to_dict(), options)) == []


@pytest.mark.parametrize("friction_torque", [0.0, 2e-3])
@pytest.mark.parametrize("current_limit", [None, 1.4])
def test_dc_motor_through_a_self_locking_worm_clamps_at_its_stall_torque(friction_torque,
                                                                          current_limit):
    # The motor drives the load into the lower stop from its face; the
    # back-EMF and the stop's damper damp the approach (the slip never ends),
    # the motor stalls, and the stop's force settles where
    # the train needs the stall torque k_t U / R (or k_t i_max):
    # F r_m tan(alpha + rho') / (n eta) + T_c = T_stall.
    motor = {} if current_limit is None else {"current_limit": current_limit}
    scene = stop_scene(friction_torque=friction_torque, **motor)
    t_eval = np.linspace(0.0, 1.5, 751)
    options = {"rtol": 1e-10, "atol": 1e-12}
    result = ls.simulate(ls.Scene.from_dict(scene), 1.5, t_eval=t_eval, **options)
    current = U / R if current_limit is None else current_limit
    clamp = reference.train_clamp_force(KT * current, THREAD, 0.3, RATIO, worm_efficiency(),
                                        friction_torque)
    assert result["stop_force"][-1] == pytest.approx(clamp, rel=1e-6)
    assert result["motor_current"][-1] == pytest.approx(current, rel=1e-6)
    assert result["u_load"][-1] == pytest.approx(STOP["lower"] - clamp / STOP["stiffness"],
                                                 rel=1e-6)
    assert "lower end stop contact" in [e.kind for e in result.events]
    assert_account_closes(result, scene, {"t_end": 1.5, "t_eval": t_eval, **options})


@pytest.mark.parametrize("mu", [0.3, 0.01])
def test_switched_off_at_the_stop_the_self_locking_train_holds_the_clamp(mu):
    # The voltage drops to 0 at 0.5 s, the load pressed into the stop: the
    # self-locking worm holds the stop's force (behind a self-locking thread,
    # mu = 0.3, and behind one the load back-drives, mu = 0.01): the train
    # sticks, the clamp and the load's position stay, the current decays.
    voltage = {"type": "table", "times": [0.0, 0.5, 0.5 + 1e-6, 1.0],
               "values": [U, U, 0.0, 0.0]}
    scene = stop_scene(mu=mu, voltage=voltage)
    t_eval = np.linspace(0.0, 1.0, 1001)
    options = {"rtol": 1e-10, "atol": 1e-12}
    result = ls.simulate(ls.Scene.from_dict(scene), 1.0, t_eval=t_eval, **options)
    late = result.t >= 0.6
    held = result["stop_force"][late]
    assert held[0] > 0.0
    np.testing.assert_array_equal(result["stick"][late], 1.0)
    np.testing.assert_array_equal(held, held[0])
    np.testing.assert_array_equal(result["u_load"][late], result["u_load"][late][0])
    assert abs(result["motor_current"][-1]) <= 1e-9 * U / R
    # The load does not back off the stop: it is held at least as deep as at
    # the switch-off (the stop's damper force, c times the approach, goes).
    at_switch = abs(result["u_load"][np.searchsorted(result.t, 0.5)])
    assert abs(result["u_load"][-1]) >= at_switch
    assert not any(e.kind.startswith("stick->slip-") for e in result.events if e.time > 0.5)
    assert_account_closes(result, scene, {"t_end": 1.0, "t_eval": t_eval, **options})


def test_stops_out_of_reach_change_nothing_on_the_train():
    # The train with stops takes BDF between events instead of Verner: the
    # same motion to the integration tolerance, the same events.
    scene = stop_scene()
    scene["loads"]["axial_force"] = 10.0  # (no flank change at the normal force's round-off)
    scene["end_stops"] = {"lower": -0.05, "upper": 0.05, "stiffness": 1e6}
    t_eval = np.linspace(0.0, 0.5, 51)
    far = ls.simulate(ls.Scene.from_dict(scene), 0.5, t_eval=t_eval)
    scene.pop("end_stops")
    plain = ls.simulate(ls.Scene.from_dict(scene), 0.5, t_eval=t_eval)
    np.testing.assert_array_equal(far["stop_force"], 0.0)
    scale = np.max(np.abs(plain["u_load"]))
    np.testing.assert_allclose(far["u_load"], plain["u_load"], rtol=0, atol=1e-6 * scale)
    np.testing.assert_allclose(far["motor_current"], plain["motor_current"], rtol=0,
                               atol=1e-6 * np.max(np.abs(plain["motor_current"])))
    assert [e.kind for e in far.events] == [e.kind for e in plain.events]


def test_exact_stops_with_a_stage_run_on_moreau_jean_and_carry_the_drive():
    # The event-driven TrainSolver does not take the closed exact stop: the
    # default integrator is Moreau-Jean, the event-driven scheme is refused
    # naming the stops. At the closed stop the stop carries what the drive
    # presses with and every friction contact nothing (end_stops.md, "The
    # rigid drive at a closed stop"): the stop force is the ideal train's,
    # n T / p with T the motor's torque on the rotor (the stalled motor's
    # k_t U / R).
    scene = stop_scene()
    scene["end_stops"] = {"lower": -2e-4, "contact": "exact"}
    s = ls.Scene.from_dict(scene)
    with pytest.raises(ValueError, match="end_stops.contact = .exact."):
        ls.simulate(s, 0.05, integrator="event_driven")
    options = {"t_eval": list(np.linspace(0.0, 0.3, 301)), "dt": 1e-5}
    result = ls.simulate(s, 0.3, **options)
    assert result.integrator == "moreau"
    # (reached at 0.22 s; after the closing and the stalled current's rise,
    # 10 ms: Moreau-Jean's step takes the mean current over the step, its
    # row the step's end's)
    reached = np.flatnonzero(result["u_load"] <= -2e-4 + 1e-7)
    held = reached[10:]
    assert len(held) > 50 and np.all(np.diff(reached) == 1)
    p = scene["thread"]["pitch"] / (2 * np.pi)
    np.testing.assert_allclose(result["stop_force"][held],
                               RATIO * result["drive_torque"][held] / p, rtol=1e-6)
    assert result["drive_torque"][-1] == pytest.approx(KT * U / R, rel=1e-6)
    assert np.all(result["friction_force"][held] == 0.0)
    assert failed(check_result(result, s.to_dict(), {**options, "t_end": 0.3,
                                                      "integrator": "moreau"})) == []


def test_the_train_and_stop_channels_have_their_units():
    # (leadscrew run wrote no result of a train: motor_friction_loss and
    # gear_loss had no unit.)
    result = ls.simulate(ls.Scene.from_dict(stop_scene(friction_torque=2e-3)), 0.05)
    units = result.units()
    assert units["motor_friction_loss"] == units["gear_loss"] == "J"
    assert units["stop_force"] == "N"
    assert list(result.to_frame().columns) == list(units)


def test_the_shipped_worm_seat_adjuster_runs_into_its_stop_and_stalls():
    # The seat's motor stalls against the rear stop through the self-locking
    # worm: the clamp where the train needs the stall torque, the stop's force
    # and the 80 N axial load on the thread together:
    # (F_stop + F_axial) r_m tan(alpha + rho') / (n eta) + T_c = k_t U / R.
    scene = ls.scenes.load("seat_adjuster_worm")
    d = scene.to_dict()
    one = ls.simulate(scene, 1.0)  # the CLI's default run
    assert [e.kind for e in one.events] == ["stick->slip+", "lower end stop contact"]
    motor, gear = d["motor"], d["gear"]
    stall = motor["voltage"] / motor["resistance"]
    assert one["motor_current"][-1] > 0.99 * stall
    result = ls.simulate(scene, 2.0, rtol=1e-10, atol=1e-12)
    eta = train_reference.worm_efficiencies(gear["lead_angle"], gear["mu"],
                                            gear["flank_angle"])[0]
    thread = reference.train_clamp_force(motor["torque_constant"] * stall, d["thread"],
                                         d["friction"]["mu"], gear["ratio"], eta,
                                         motor["friction_torque"])
    assert result["stop_force"][-1] + d["loads"]["axial_force"] == pytest.approx(thread,
                                                                                rel=1e-6)
    assert result["motor_current"][-1] == pytest.approx(stall, rel=1e-6)
    assert failed(check_result(result, d, {"t_end": 2.0, "rtol": 1e-10, "atol": 1e-12})) == []


@pytest.mark.parametrize("drive", ["screw", "nut"])
def test_a_nut_driven_train_raises_and_clamps_as_the_closed_form(drive):
    # The rotor turning the nut (drive = "nut"): the slip's sign is minus
    # phi''s there, which the motor's friction, the stage's power flow and a
    # start's direction follow (every nut-driven train ran into max_steps at
    # its start before). Raising 80 N at 12 V through the worm: the steady
    # current T / k_t, T = (F r_m tan(alpha + rho') / eta + |n| T_c) / n; then
    # the stall at the stop as the shipped scene's.
    d = ls.scenes.load("seat_adjuster_worm").to_dict()
    d["drive"] = drive
    motor, gear = d["motor"], d["gear"]
    eta = train_reference.worm_efficiencies(gear["lead_angle"], gear["mu"],
                                            gear["flank_angle"])[0]
    unit = reference.train_clamp_force(1.0 + motor["friction_torque"], d["thread"],
                                       d["friction"]["mu"], gear["ratio"], eta,
                                       motor["friction_torque"])  # F per N m of the motor
    free = {key: value for key, value in d.items() if key != "end_stops"}
    steady = ls.simulate(ls.Scene.from_dict(free), 0.3, rtol=1e-10, atol=1e-12)
    torque = d["loads"]["axial_force"] / unit + motor["friction_torque"]
    assert steady["motor_current"][-1] == pytest.approx(torque / motor["torque_constant"],
                                                        rel=1e-6)
    assert steady["v_load"][-1] < 0.0  # (+12 V moves the seat rearward, uphill)
    clamped = ls.simulate(ls.Scene.from_dict(d), 2.0, rtol=1e-10, atol=1e-12)
    stall = motor["voltage"] / motor["resistance"]
    force = (motor["torque_constant"] * stall - motor["friction_torque"]) * unit
    assert clamped["stop_force"][-1] + d["loads"]["axial_force"] == pytest.approx(force,
                                                                                 rel=1e-6)
