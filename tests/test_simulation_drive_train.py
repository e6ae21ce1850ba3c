"""The drive train's friction stages on the rigid drive without play (issue
19, item 1 motor.friction_torque, item 2 gear.type = 'lossy' and 'worm';
docs/physics/gear.md, "Friction stages"), against the closed forms of
tests/helpers/train_reference.py: the motor's friction in the breakaway
torque and the DC motor's steady state, the lossy stage's and the worm's
steady states and the train's efficiency, their self-locking, a worm that
back-drives, the energy account with each stage's loss, the refusals, and
the scene's fields."""

import dataclasses
import math
import re

import numpy as np
import pytest

import leadscrew as ls
from leadscrew import _core
from leadscrew.simulation import Result, _drive_arguments
from helpers import dc_motor_reference
from helpers import train_reference as reference
from helpers.scenes import thesis_scene

R, KT, L, U, F = 2.0, 0.05, 1e-3, 3.0, 10.0  # [Ohm], [N m/A], [H], [V], [N]
DC_MOTOR = {"type": "dc", "voltage": U, "resistance": R, "inductance": L, "torque_constant": KT}
RATIO = 4.0
LOSSY = {"type": "lossy", "ratio": RATIO, "efficiency": 0.7, "efficiency_backdrive": 0.4}
WORM_ANGLE, WORM_MU = 0.3, 0.05  # [rad], a worm that back-drives (tan 0.3 > mu')
WORM = {"type": "worm", "ratio": RATIO, "lead_angle": WORM_ANGLE, "mu": WORM_MU}
DEFAULT_FLANK = math.radians(40.0)


def efficiencies(gear):
    """(eta, eta_b) of a scene's gear section."""
    if gear["type"] == "worm":
        return reference.worm_efficiencies(gear["lead_angle"], gear["mu"],
                                           gear.get("flank_angle", DEFAULT_FLANK))
    return gear.get("efficiency", 1.0), gear.get("efficiency_backdrive", 1.0)


def assert_losses_never_fall(result):
    for name in ("gear_loss", "motor_friction_loss", "friction_loss"):
        if name in result.channels:
            assert np.all(np.diff(result[name]) >= -1e-15), name
    work = np.max(np.abs(result["work_drive"])) + np.max(np.abs(result["work_axial"]))
    assert np.max(np.abs(result["energy_residual"])) <= 1e-6 * work


def dc_scene(gear, friction_torque=0.0):
    scene = thesis_scene(loads={"axial_force": F}, gear=gear,
                         motor={**DC_MOTOR, "friction_torque": friction_torque})
    scene["loads"].pop("drive_torque")
    return ls.Scene.from_dict(scene)


@pytest.mark.parametrize("gear", [{"type": "ideal", "ratio": RATIO}, LOSSY, WORM])
@pytest.mark.parametrize("friction_torque", [0.0, 2e-3])
def test_dc_motor_steady_state_through_the_train(gear, friction_torque):
    """The DC motor raising the load through the stage with its own friction
    T_c: i = T / k_t, omega = (U - R i) / k_e with the rotor's steady torque
    T = (k T_d + |n| T_c) / n (k = 1 / eta, T_d the bare drive's); without
    T_c the train's efficiency F v / (T omega) is eta times the thread's."""
    s = dc_scene(gear, friction_torque)
    result = ls.simulate(s, 2.0)
    eta, eta_b = efficiencies(gear)
    drive = dc_motor_reference.rigid_drive(s.to_dict(), s.derived())
    torque = reference.steady_rotor_torque(drive, RATIO, F, 1, friction_torque, eta, eta_b)
    current = torque / KT
    omega = (U - R * current) / KT
    assert result["motor_current"][-1] == pytest.approx(current, rel=1e-6)
    assert result["omega_drive"][-1] == pytest.approx(omega, rel=1e-6)
    assert [e.kind for e in result.events] == ["stick->slip+"]
    if friction_torque == 0.0:
        efficiency = -F * result["v_load"][-1] / (result["drive_torque"][-1] * omega)
        assert efficiency == pytest.approx(eta * ls.efficiency(s.thread, 0.3), rel=1e-6)
        assert "motor_friction_loss" not in result.channels
    else:
        # The motor's friction loses T_c omega_rotor at the steady speed.
        loss, t = result["motor_friction_loss"], result.t
        rate = (loss[-1] - loss[-2]) / (t[-1] - t[-2])
        assert rate == pytest.approx(friction_torque * omega, rel=1e-6)
    assert ("gear_loss" in result.channels) == (gear["type"] != "ideal")
    assert_losses_never_fall(result)


def test_zero_friction_torque_runs_bit_identically():
    """motor.friction_torque = 0 is the motor without the key: the same
    channels, the same bits."""
    scene = thesis_scene(loads={"axial_force": F}, motor=DC_MOTOR)
    scene["loads"].pop("drive_torque")
    plain = ls.simulate(ls.Scene.from_dict(scene), 0.5)
    scene["motor"] = {**DC_MOTOR, "friction_torque": 0.0}
    zero = ls.simulate(ls.Scene.from_dict(scene), 0.5)
    assert plain.channels == zero.channels
    for name in plain.channels:
        np.testing.assert_array_equal(plain[name], zero[name], err_msg=name)


def torque_ramp_run(friction_torque, gear):
    """The rigid drive behind a stage at rest under F, its rotor's torque
    ramped from 0 (torque-controlled: motor.friction_torque through the
    core's parameters, the scene's motor section being the DC motor's)."""
    scene = thesis_scene(rotor={"inertia": 1e-6}, gear=gear,
                         loads={"drive_torque": {"type": "table", "times": [0.0, 1.0],
                                                 "values": [0.0, 0.1]},
                                "axial_force": -F})
    s = ls.Scene.from_dict(scene)
    parameters = s.model().parameters
    parameters.motor_friction_torque = friction_torque
    arguments = _drive_arguments(0.5, None, None, None, None, None, None, [], 1_000_000,
                                 100_000, None, None, None, None)
    result = Result(_core.simulate_drive(_core.DriveModel(parameters), **arguments))
    return s, result


@pytest.mark.parametrize("gear", [
    {"type": "ideal", "ratio": 3.0},
    {**LOSSY, "ratio": 3.0},
    {**WORM, "ratio": 3.0, "mu_static": 0.08},
])
def test_breakaway_torque_through_the_train(gear):
    """The drive at rest starts where the rotor's torque reaches the raise
    torque through the stage at its static efficiency (a worm's from
    mu_static), T_d / (n eta_static), plus the motor's friction T_c; T_c
    raises it by itself."""
    t_c = 1e-3
    s, result = torque_ramp_run(t_c, gear)
    static = {**gear, "mu": gear["mu_static"]} if "mu_static" in gear else gear
    eta, eta_b = efficiencies(static)
    drive = dc_motor_reference.rigid_drive(s.to_dict(), s.derived())
    breakaway = reference.steady_rotor_torque(drive, 3.0, -F, 1, t_c, eta, eta_b)
    start = result.events[0]
    assert start.kind == "stick->slip+"
    assert 0.1 * start.time == pytest.approx(breakaway, rel=1e-9)
    _, plain = torque_ramp_run(0.0, gear)
    assert 0.1 * (start.time - plain.events[0].time) == pytest.approx(t_c, rel=1e-9)
    assert "motor_friction_loss" in result.channels
    assert_losses_never_fall(result)


def test_a_lossless_stage_is_the_ideal_gear():
    """gear.type = 'lossy' with efficiency 1 both ways moves the drive as the
    ideal stage, to round-off (the same events; no loss)."""
    t = np.linspace(0.0, 2.0, 201)
    base = thesis_scene(rotor={"inertia": 1e-6}, nut={"position": 0.25},
                        gear={"type": "ideal", "ratio": 3.0})
    ideal = ls.simulate(ls.Scene.from_dict(base), 2.0, t_eval=t, rtol=1e-6, atol=1e-10)
    lossy = ls.simulate(ls.Scene.from_dict(
        {**base, "gear": {"type": "lossy", "ratio": 3.0, "efficiency": 1.0,
                          "efficiency_backdrive": 1.0}}), 2.0, t_eval=t, rtol=1e-6, atol=1e-10)
    assert [e.kind for e in lossy.events] == [e.kind for e in ideal.events]
    assert len(ideal.events) >= 5
    assert max(abs(a.time - b.time) for a, b in zip(lossy.events, ideal.events)) <= 1e-12
    for name in ("u_load", "omega_drive", "normal_force", "friction_force", "friction_loss"):
        scale = np.max(np.abs(ideal[name]))
        assert np.max(np.abs(lossy[name] - ideal[name])) <= 1e-12 * scale, name
    np.testing.assert_array_equal(lossy["gear_loss"], 0.0)


def held_run(gear, mu, force, t_end=0.1):
    scene = thesis_scene(rotor={"inertia": 1e-6}, nut={"position": 0.25}, gear=gear,
                         loads={"drive_torque": 0.0, "axial_force": force},
                         friction={"law": "coulomb", "mu": mu})
    s = ls.Scene.from_dict(scene)
    return s, ls.simulate(s, t_end, t_eval=np.linspace(0.0, t_end, 11))


SELF_LOCKING_WORM = {"type": "worm", "ratio": 10.0, "lead_angle": math.radians(3.0), "mu": 0.1}


@pytest.mark.parametrize("gear", [
    {"type": "lossy", "ratio": 10.0, "efficiency": 0.8, "efficiency_backdrive": 0.0},
    {"type": "lossy", "ratio": 10.0, "efficiency": 0.8, "efficiency_backdrive": -0.5},
    SELF_LOCKING_WORM,
])
@pytest.mark.parametrize("mu", [0.3, 0.005])
@pytest.mark.parametrize("force", [-50.0, 50.0])
def test_a_self_locking_stage_holds(gear, mu, force):
    """A stage with eta_b <= 0 (a worm with rho' >= its lead angle) holds
    the load with a free rotor under either direction of the axial load,
    behind a self-locking thread (mu = 0.3: both hold) and behind one the
    load back-drives (mu = 0.005: the back-driving torque on the driven
    part is the stage's to hold)."""
    s, result = held_run(gear, mu, force)
    _, eta_b = efficiencies(gear)
    assert eta_b <= 0.0
    assert ls.is_self_locking(s.thread, mu) == (mu == 0.3)
    assert np.all(result["stick"] == 1.0)
    np.testing.assert_array_equal(result["u_load"], 0.0)
    np.testing.assert_array_equal(result["omega_drive"], 0.0)
    assert result.events == []


def test_a_worm_above_its_friction_angle_back_drives():
    """A worm whose lead angle exceeds its friction angle (eta_b > 0) behind
    a thread that back-drives: the load drives the train from rest at the
    constant acceleration of the consistent combination (the stage's power
    flowing back to the rotor), phi'' = (a U + eta_b b F) / (eta_b + a n^2 J_r)."""
    gear = {"type": "worm", "ratio": 10.0, "lead_angle": math.radians(30.0), "mu": 0.05}
    s, result = held_run(gear, 0.005, -50.0)
    eta, eta_b = efficiencies(gear)
    assert eta_b > 0.0
    drive = dc_motor_reference.rigid_drive(s.to_dict(), s.derived())
    starts = reference.consistent_starts(drive, 10.0, 0.0, -50.0, 0.0, eta, eta_b)
    assert len(starts) == 1
    np.testing.assert_allclose(result["omega_drive"], 10.0 * starts[0] * result.t, rtol=1e-9,
                               atol=1e-12)
    assert result["gear_loss"][-1] > 0.0
    assert_losses_never_fall(result)


@pytest.mark.parametrize("gear", [LOSSY, WORM])
def test_lowering_through_a_stage_that_back_drives(gear):
    """The DC motor at a voltage too low to hold the load on a thread that
    back-drives: the load lowers the train at the steady state where the
    stage's power flows back, T = eta_b T_d / n (T_d < 0 along the motion)."""
    scene = thesis_scene(loads={"axial_force": 50.0}, gear=gear,
                         friction={"law": "coulomb", "mu": 0.005},
                         motor={**DC_MOTOR, "voltage": 0.0, "inductance": 0.0})
    scene["loads"].pop("drive_torque")
    s = ls.Scene.from_dict(scene)
    result = ls.simulate(s, 2.0)
    eta, eta_b = efficiencies(gear)
    drive = dc_motor_reference.rigid_drive(s.to_dict(), s.derived())
    direction = int(np.sign(result["omega_drive"][-1]))
    torque = reference.steady_rotor_torque(drive, RATIO, 50.0, direction, 0.0, eta, eta_b)
    current = torque / KT
    assert result["motor_current"][-1] == pytest.approx(current, rel=1e-6)
    assert result["omega_drive"][-1] == pytest.approx(-R * current / KT, rel=1e-6)
    assert_losses_never_fall(result)


REFUSED = [
    # (Every thread law but eq. (3.15) runs with the stages on Moreau-Jean:
    # tests/test_moreau_smooth_laws.py.)
    (dict(friction={"law": "arctan_acceleration", "mu": 0.3}), LOSSY,
     'friction.law = "arctan_acceleration": Moreau-Jean\'s velocity-level step has no slip '
     "acceleration for eq. (3.15)'s friction (it would follow dt), and the event-driven "
     "scheme's rotor contact does not take it yet"),
    # (A preloaded nut runs with the stages on Moreau-Jean, with lift-off
    # too: tests/test_moreau_preloaded_nut.py, test_simulation_drive_moreau_train.py.)
    # (Penalty end stops run with the stages now; exact ones are refused on
    # the rigid concept: tests/test_simulation_drive_train_stops.py.)
    (dict(initial={"state": "equilibrium"}), LOSSY, "initial.state"),
    (dict(friction={"law": "coulomb", "mu": 80.0}), LOSSY, "a torque cannot drive the thread"),
    # (Penalty flanks run with the stages on Moreau-Jean now:
    # tests/test_simulation_drive_moreau_flanks.py.)
]


@pytest.mark.parametrize("changes, gear, message", REFUSED)
def test_a_stage_elsewhere_is_refused_naming_the_key(changes, gear, message):
    with pytest.raises(ValueError) as info:
        ls.Scene.from_dict(thesis_scene(gear=gear, **changes)).model()
    assert message in str(info.value)
    assert "gear.type" in str(info.value)


# Off the rigid drive without play, or with another law than Coulomb's on the
# thread, the stages run on Moreau-Jean alone (its default there):
# tests/test_simulation_drive_moreau_train.py.
MOREAU_ONLY = [
    # (issue 32: the flexible concepts and penalty play run with the rotor's
    # friction contact, tests/test_event_driven_rotor_friction.py, exact play
    # and mu_static too, tests/test_event_driven_rotor_play.py)
    # (issue 32: a static coefficient runs, tests/test_event_driven_train_stages.py;
    # Stribeck's slip coefficient follows the slip speed)
    (dict(friction={"law": "stribeck", "mu": 0.12, "mu_static": 0.15}), WORM,
     'here friction.law = "stribeck"'),
    # (the train solver's closed forms are the plain thread's)
    (dict(friction={"law": "coulomb", "mu": 0.3}, nut={"preload": 20.0}), LOSSY,
     "here nut.preload = 20 N"),
]


@pytest.mark.parametrize("changes, gear, message", MOREAU_ONLY)
def test_the_event_driven_scheme_refuses_a_stage_elsewhere_naming_moreau(changes, gear, message):
    scene = ls.Scene.from_dict(thesis_scene(gear=gear, **changes))
    assert _core.drive_integrators(scene.model().parameters) == ["moreau"]
    with pytest.raises(ValueError) as info:
        ls.simulate(scene, 0.01, integrator="event_driven")
    text = str(info.value)
    assert text.startswith(f'integrator = "event_driven" is invalid with gear.type = '
                           f'"{gear["type"]}": the event-driven scheme runs the train\'s '
                           "friction stages with a torque or DC motor on the rigid concept "
                           "without play")
    assert message in text and 'use integrator = "moreau"' in text
    assert ls.simulate(scene, 0.05).integrator == "moreau"  # the default


def test_motor_friction_elsewhere_is_refused_naming_the_key():
    # (Stribeck on the rigid concept without play; exact play runs since
    # issue 32, tests/test_event_driven_rotor_play.py.)
    scene = thesis_scene(loads={"axial_force": F},
                         motor={**DC_MOTOR, "friction_torque": 1e-3},
                         friction={"law": "stribeck", "mu": 0.12, "mu_static": 0.15})
    scene["loads"].pop("drive_torque")
    with pytest.raises(ValueError, match=r"integrator = \"event_driven\" is invalid with "
                                         r"motor\.friction_torque = 0\.001: .* here friction\."
                                         r"law = \"stribeck\"; use integrator = \"moreau\""):
        ls.simulate(ls.Scene.from_dict(scene), 0.01, integrator="event_driven")
    speed = thesis_scene(loads={"drive_speed": 1.0})
    speed["loads"].pop("drive_torque")
    parameters = ls.Scene.from_dict(speed).model().parameters
    parameters.motor_friction_torque = 1e-3
    # (A prescribed rotor speed runs the stages on both schemes, Moreau-Jean
    # the default: tests/test_event_driven_train_stages.py.)
    assert _core.drive_integrators(parameters) == ["moreau", "event_driven"]
    assert ls.simulate(ls.Scene.from_dict({**speed, "motor": {"friction_torque": 1e-3}}), 0.01,
                       integrator="event_driven").integrator == "event_driven"


def test_other_integrators_are_refused():
    # (Moreau-Jean runs the stages: tests/test_simulation_drive_moreau_train.py.)
    with pytest.raises(ValueError, match=r"integrator = \"dopri5\" is invalid with "
                                         r"gear\.type = \"lossy\": the train's friction stages "
                                         r"run on Moreau-Jean \(integrator = \"moreau\", every thread law "
                                         r"but arctan_acceleration\)"):
        ls.simulate(ls.Scene.from_dict(thesis_scene(gear=LOSSY)), 0.01, integrator="dopri5")


@pytest.mark.parametrize("gear, message", [
    ({**LOSSY, "efficiency": 0.0}, "gear.efficiency = 0.0 is invalid"),
    ({**LOSSY, "efficiency_backdrive": 1.5}, "gear.efficiency_backdrive = 1.5 is invalid"),
    ({"type": "lossy", "ratio": 2.0}, "gear.efficiency is missing"),
    ({"type": "worm", "ratio": 2.0, "mu": 0.1}, "gear.lead_angle is missing"),
    ({**WORM, "efficiency": 0.5}, "gear.efficiency = 0.5 is invalid: must be absent with "
                                  "gear.type = 'worm'"),
    ({**LOSSY, "mu": 0.1}, "gear.mu = 0.1 is invalid: must be absent with gear.type = 'lossy'"),
    ({**WORM, "mu_static": 0.01}, "gear.mu_static = 0.01 is invalid: must be at least gear.mu"),
    ({**WORM, "lead_angle": 1.5, "mu": 0.5}, "gear.lead_angle = 1.5 rad is invalid "
                                             "with gear.mu = 0.5: the worm cannot be driven"),
])
def test_invalid_stage_fields_raise_naming_the_key(gear, message):
    with pytest.raises(ValueError) as info:
        ls.Scene.from_dict(thesis_scene(gear=gear)).model()
    assert message in str(info.value)


def test_the_stage_round_trips_through_toml_and_the_core_spec(tmp_path):
    path = tmp_path / "worm.toml"
    path.write_text(
        'concept = "rigid"\n[thread]\npitch = "1 mm"\nmean_diameter = "20 mm"\n'
        '[friction]\nmu = 0.3\n[loads]\ndrive_torque = "0.1 N*m"\naxial_force = "10 N"\n'
        '[gear]\ntype = "worm"\nratio = 40\nlead_angle = "5 deg"\nmu = 0.08\n'
        'mu_static = 0.1\nflank_angle = "40 deg"\n')
    scene = ls.Scene.from_toml(path)
    gear = scene.to_dict()["gear"]
    assert gear["type"] == "worm" and gear["lead_angle"] == pytest.approx(math.radians(5.0))
    parameters, options = _core.read_core_spec(scene.to_core_toml())
    assert parameters.gear == "worm"
    assert (parameters.gear_mu, parameters.gear_mu_static) == (0.08, 0.1)
    assert parameters.gear_lead_angle == pytest.approx(math.radians(5.0), rel=1e-15)


def test_the_schema_documents_every_stage_field():
    text = ls.scene_schema.describe_schema()
    for key, unit in (("type", None), ("efficiency", None), ("efficiency_backdrive", None),
                      ("lead_angle", "rad"), ("mu", None), ("mu_static", None),
                      ("flank_angle", "rad")):
        line = next(line for line in text.splitlines() if line.startswith(f"gear.{key} "))
        if unit:
            assert f"[{unit}]" in line
    line = next(line for line in text.splitlines() if line.startswith("motor.friction_torque"))
    assert "[N*m] (default 0.0; a finite number >= 0)" in line and "motor_friction_loss" in line


def test_a_drive_without_stages_has_no_new_channel():
    """Without a friction stage nothing is added: no channel (nor state: the
    stepper's channels are the run's)."""
    result = ls.simulate(ls.Scene.from_dict(thesis_scene(gear={"ratio": 3.0})), 0.05)
    assert "gear_loss" not in result.channels and "motor_friction_loss" not in result.channels
    assert ls.Scene.from_dict(thesis_scene(gear={"ratio": 3.0})).model().train_friction is None


def test_check_reports_the_stage(capsys, tmp_path):
    """``leadscrew check`` reports the stage's efficiencies (the worm's from
    mu and mu_static), whether it is self-locking, and the motor's friction."""
    from helpers.cli_runs import run_main

    gear = {"type": "worm", "ratio": 40.0, "lead_angle": math.radians(4.0), "mu": 0.08,
            "mu_static": 0.1}
    scene = thesis_scene(loads={"axial_force": F}, gear=gear,
                         motor={**DC_MOTOR, "friction_torque": 1e-3})
    scene["loads"].pop("drive_torque")
    path = tmp_path / "worm.toml"
    ls.Scene.from_dict(scene).to_toml(path)
    code, out, err = run_main(capsys, "check", str(path))
    assert code == 0 and err == ""
    eta, eta_b = efficiencies(gear)
    eta_s, eta_b_s = reference.worm_efficiencies(gear["lead_angle"], 0.1, DEFAULT_FLANK)
    assert eta_b < 0.0
    assert (f"  efficiency {eta:.6g} rotor -> driven part, {eta_b:.6g} back (at breakaway "
            f"{eta_s:.6g}, {eta_b_s:.6g}); self-locking: yes") in out
    assert "motor friction: 0.001 N*m on the rotor" in out
    lossy = thesis_scene(gear=LOSSY)
    ls.Scene.from_dict(lossy).to_toml(path)
    code, out, _ = run_main(capsys, "check", str(path))
    assert "  efficiency 0.7 rotor -> driven part, 0.4 back; self-locking: no" in out


@pytest.mark.parametrize("rotor_inertia, jams", [(1e-7, True), (1e-4, False)])
def test_a_light_rotor_behind_a_self_locking_stage_jams(rotor_inertia, jams):
    """The stage's Painleve paradox: where eta_b + n^2 J_rotor a_driven <= 0
    (a_driven the driven side's acceleration per unit torque on it), driving
    forward makes the forward combination and the backward one (both sides
    pushing into the stage, a negative effective inertia) consistent at
    once: JammingError naming the stage's margin. A heavier rotor runs."""
    gear = {"type": "lossy", "ratio": 3.0, "efficiency": 0.5, "efficiency_backdrive": -0.16}
    scene = thesis_scene(rotor={"inertia": rotor_inertia}, gear=gear,
                         friction={"law": "coulomb", "mu": 0.005},
                         loads={"drive_torque": 0.01, "axial_force": 5.0})
    s = ls.Scene.from_dict(scene)
    drive = dc_motor_reference.rigid_drive(s.to_dict(), s.derived())
    driven = dataclasses.replace(drive, rotor_inertia=0.0)
    margin = min(-0.16 + 9.0 * rotor_inertia * driven.a(eps) for eps in (1.0, -1.0))
    assert (margin <= 0.0) == jams
    if not jams:
        result = ls.simulate(s, 0.1)
        assert result["omega_drive"][-1] > 0.0
        assert_losses_never_fall(result)
        return
    with pytest.raises(ls.JammingError) as info:
        ls.simulate(s, 0.1)
    found = re.search(r"the gear stage's Painleve margin eta_b \+ n\^2 J_rotor a_driven = "
                      r"(\S+) \(<= 0", str(info.value))
    assert found and float(found.group(1)) == pytest.approx(margin, rel=1e-9)


def run_constant(ratio, eta, eta_b, friction_torque, torque, force, t_end=0.01):
    """A torque-driven rigid drive (rotor 1e-5 kg m^2) behind a lossy stage
    under constant loads, the motor's friction through the core's parameters."""
    gear = {"type": "lossy", "ratio": ratio, "efficiency": eta, "efficiency_backdrive": eta_b}
    s = ls.Scene.from_dict(thesis_scene(rotor={"inertia": 1e-5}, gear=gear,
                                        loads={"drive_torque": torque, "axial_force": force}))
    parameters = s.model().parameters
    parameters.motor_friction_torque = friction_torque
    arguments = _drive_arguments(t_end, None, None, None, None, None, None, [], 1_000_000,
                                 100_000, None, None, None, None)
    return Result(_core.simulate_drive(_core.DriveModel(parameters), **arguments))


def test_the_static_stick_test_is_no_start_in_the_regular_regime():
    """Outside the stage's Painleve regime the train holds at rest (Coulomb's
    static solution) exactly where no slip start is consistent in either
    direction (the task's breakaway test): the reference's two forms of the
    stick test agree over random loads and stages, each outcome often; and
    the simulation sticks from rest where they say so."""
    rng = np.random.default_rng(5)
    s = ls.Scene.from_dict(thesis_scene(rotor={"inertia": 1e-5}))
    drive = dc_motor_reference.rigid_drive(s.to_dict(), s.derived())
    driven = dataclasses.replace(drive, rotor_inertia=0.0)
    outcomes = {True: 0, False: 0}
    simulated = 0
    for _ in range(300):
        ratio = float(rng.choice([-3.0, 2.0, 10.0]))
        eta = float(rng.uniform(0.3, 1.0))
        eta_b = float(rng.uniform(-0.5, 1.0))
        t_c = float(rng.choice([0.0, 1e-3]))
        torque, force = float(rng.uniform(-0.05, 0.05)), float(rng.uniform(-60.0, 60.0))
        if min(eta_b + ratio ** 2 * drive.rotor_inertia * driven.a(e) for e in (1.0, -1.0)) <= 0:
            continue
        starts = [a for d in (1, -1) for a in reference.slip_acceleration(
            drive, ratio, torque, force, d, t_c, eta, eta_b) if a * d > 0.0]
        holds = reference.holds_at_rest(drive, ratio, torque, force, t_c, eta, eta_b)
        assert holds == (len(starts) == 0), (ratio, eta, eta_b, t_c, torque, force)
        assert len(starts) <= 1
        outcomes[holds] += 1
        if simulated < 12:
            result = run_constant(ratio, eta, eta_b, t_c, torque, force)
            assert bool(result["stick"][-1]) == holds
            if not holds:  # from rest at the one consistent start's acceleration
                phi_dd = result["omega_drive"][-1] / (ratio * result.t[-1])
                assert phi_dd == pytest.approx(starts[0], rel=1e-9)
            simulated += 1
    assert min(outcomes.values()) > 50


def test_a_sine_driven_train_meets_the_mode_by_mode_reference():
    """A sine torque through a lossy stage with the motor's friction, against
    a thread that self-locks under a constant load: stick, slips both ways,
    the stage's power flow reversing within them. The friction mode changes
    (train_reference.simulate: the consistent combination's acceleration
    integrated mode by mode, the static stick test bisected) to 1e-8 s, the
    driven part's speed to 1e-9 of its range."""
    gear = {"type": "lossy", "ratio": 3.0, "efficiency": 0.7, "efficiency_backdrive": 0.4}
    t_c, amplitude, omega_load = 2e-3, 0.03, 4.0 * math.pi
    scene = thesis_scene(rotor={"inertia": 1e-5}, gear=gear,
                         loads={"drive_torque": {"type": "sine", "amplitude": amplitude,
                                                 "omega": omega_load},
                                "axial_force": -10.0})
    s = ls.Scene.from_dict(scene)
    parameters = s.model().parameters
    parameters.motor_friction_torque = t_c
    t = np.linspace(0.0, 1.0, 101)
    arguments = _drive_arguments(1.0, None, None, 1e-10, 1e-12, None, None, list(t),
                                 1_000_000, 100_000, None, None, None, None)
    result = Result(_core.simulate_drive(_core.DriveModel(parameters), **arguments))
    drive = dc_motor_reference.rigid_drive(s.to_dict(), s.derived())
    events, omega = reference.simulate(
        drive, 3.0, lambda time: amplitude * math.sin(omega_load * time), -10.0, 1.0, t_c,
        0.7, 0.4)
    ours = [(e.time, e.kind) for e in result.events if "->" in e.kind]
    assert [kind for _, kind in ours] == [kind for _, kind in events]
    assert len(events) >= 4
    assert "gear stage power flow reversal" in [e.kind for e in result.events]
    assert max(abs(a - b) for (a, _), (b, _) in zip(ours, events)) <= 1e-8
    speed = np.array([omega(time) for time in result.t])
    assert np.max(np.abs(result["omega_drive"] / 3.0 - speed)) <= 1e-9 * np.max(np.abs(speed))
    assert_losses_never_fall(result)
