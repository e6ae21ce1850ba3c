"""The event-driven scheme with the train's friction stages and a torque or
DC motor on the flexible concepts without play and with penalty play
(bistop, cubic; issue 32, "fill the matrix": the rotor's friction contact,
cpp/src/model/drive/hybrid_rotor_contact.cpp; docs/physics/gear.md, "The
event-driven rotor contact"): lossy and worm stages and the motor's
friction, against Moreau-Jean (its losses converge
to the event-driven scheme's at first order in dt), the closed forms of a
lossy stage's steady state (T_screw / (n eta) driving, eta_b T_screw / n
back-driven), of a self-locking worm's hold and breakaway and of the
motor's friction; with arctan_velocity on the thread (every concept
without play, the rigid one's on the rotor contact too) against Moreau-Jean
and the steady slip's closed form at the law's coefficient; the stage's
Painleve case raises JammingError; LuGre and Stribeck on the rigid
concept without play stay refused by name (exact play, mu_static and
Stribeck elsewhere: test_event_driven_rotor_play.py). Every run
passes its own checks and the independent invariants
(helpers/result_invariants.py: the account closes, friction never works
positively, the losses never fall)."""

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import leadscrew as ls
from helpers import dc_motor_reference
from helpers import train_reference as reference
from helpers.result_invariants import checked_run as checked
from helpers.scenes import thesis_scene

pytestmark = pytest.mark.usefixtures("every_step")

LOSSY = {"type": "lossy", "ratio": 4.0, "efficiency": 0.7, "efficiency_backdrive": 0.4}
WORM = {"type": "worm", "ratio": 4.0, "lead_angle": 0.3, "mu": 0.05}
SELF_LOCKING_WORM = {"type": "worm", "ratio": 4.0, "lead_angle": 0.05, "mu": 0.2}
BISTOP = {"axial": 1e-4, "contact": "bistop", "stiffness": 1e8}
CUBIC = {"axial": 1e-4, "contact": "cubic", "stiffness": 1e12}
DC = {"type": "dc", "voltage": {"type": "sine", "amplitude": 6.0, "omega": 40.0},
      "resistance": 1.0, "inductance": 5e-4, "torque_constant": 0.03}
DEFAULT_FLANK = math.radians(40.0)
ARCTAN = {"law": "arctan_velocity", "mu": 0.3, "k_v": 1e4}


def scene(concept="flexible_nut", gear=LOSSY, torque=None, motor=None, **changes):
    """The thesis drive on ``concept`` behind ``gear`` (the thesis's sine
    torque, a constant ``torque`` [N m] or the DC ``motor``)."""
    d = thesis_scene(concept=concept, gear=gear, **changes)
    if torque is not None:
        d["loads"]["drive_torque"] = torque
    if motor is not None:
        d["motor"] = motor
        if motor.get("type") == "dc":
            d["loads"].pop("drive_torque")
    return d


# (concept, gear, play, motor): the matrix's corners, each run on both schemes.
COMBINATIONS = {
    "nut-lossy-sine": scene(),
    "nut-lossy-friction": scene(torque=0.02, motor={"friction_torque": 3e-3}),
    "flexible-worm-friction": scene("flexible", WORM, torque=0.02,
                                    motor={"friction_torque": 3e-3}),
    "flexible-worm-sine": scene("flexible", WORM),
    "nut-lossy-bistop": scene(backlash=BISTOP),
    "flexible-worm-cubic": scene("flexible", WORM, backlash=CUBIC),
    "rigid-lossy-bistop": scene("rigid", backlash=BISTOP),
    "nut-lossy-dc": scene(motor={**DC, "friction_torque": 2e-3}),
    # arctan_velocity on the thread (a force of the state, no thread modes;
    # on the rigid concept without play the rotor contact, not TrainSolver)
    "nut-lossy-arctan": scene(friction=ARCTAN),
    "flexible-worm-arctan-friction": scene("flexible", WORM, torque=0.02, friction=ARCTAN,
                                           motor={"friction_torque": 3e-3}),
    "rigid-lossy-arctan": scene("rigid", friction=ARCTAN),
    "rigid-worm-arctan-dc": scene("rigid", WORM, friction=ARCTAN,
                                  motor={**DC, "friction_torque": 2e-3}),
    "nut-lossy-arctan-bistop": scene(friction=ARCTAN, backlash=BISTOP),
}


@pytest.mark.parametrize("name", sorted(COMBINATIONS))
def test_moreau_jean_converges_to_the_event_driven_losses(name):
    """Moreau-Jean's thread, stage and motor losses at dt, dt/2, dt/4 approach
    the event-driven scheme's, the difference shrinking at first order
    (fitted order 0.7 to 1.5 on the sum of the losses)."""
    d = COMBINATIONS[name]
    t_end = 0.1
    exact = checked(d, t_end, integrator="event_driven")
    assert exact.integrator == "event_driven"
    names = [c for c in ("friction_loss", "gear_loss", "motor_friction_loss")
             if c in exact.channels]
    reference_losses = sum(exact[c][-1] for c in names)
    errors = []
    for dt in (1e-4, 5e-5, 2.5e-5):
        stepped = checked(d, t_end, integrator="moreau", dt=dt)
        errors.append(abs(sum(stepped[c][-1] for c in names) - reference_losses))
    assert errors[0] > errors[1] > errors[2]
    order = math.log2(errors[0] / errors[2]) / 2.0
    assert 0.7 <= order <= 1.5, (errors, order)
    assert errors[2] <= 5e-3 * reference_losses


def test_moreau_jean_stays_the_default_and_rtol_chooses_the_event_driven_scheme():
    """Moreau-Jean ran these scenes before: it stays their default (results
    unchanged); rtol chooses the event-driven scheme."""
    s = ls.Scene.from_dict(COMBINATIONS["nut-lossy-sine"])
    assert ls.simulate(s, 0.01).integrator == "moreau"
    assert ls.simulate(s, 0.01, rtol=1e-8).integrator == "event_driven"


def dc_steady_scene(concept, force, voltage):
    """A DC motor (no inductance) through the lossy stage against the
    constant axial force ``force`` [N], on ``concept``."""
    motor = {"type": "dc", "voltage": voltage, "resistance": 2.0, "inductance": 0.0,
             "torque_constant": 0.05}
    return scene(concept, LOSSY, motor=motor, loads={"axial_force": force},
                 friction={"law": "coulomb", "mu": 0.005})


@pytest.mark.parametrize("force, voltage, driving", [(10.0, 3.0, True), (40.0, 0.0, False)])
def test_a_lossy_stage_takes_the_closed_forms_torque_at_steady_slip(force, voltage, driving):
    """The DC motor at its steady state on flexible_nut: the rotor's torque is
    T_screw / (n eta) where it raises the load, eta_b T_screw / n where the
    load drives the train against the motor's back-EMF (T_screw the bare
    drive's torque on the screw: train_reference, from the rigid drive)."""
    d = dc_steady_scene("flexible_nut", force, voltage)
    result = checked(d, 1.0, integrator="event_driven")
    rigid = ls.Scene.from_dict(dc_steady_scene("rigid", force, voltage))
    drive = dc_motor_reference.rigid_drive(rigid.to_dict(), rigid.derived())
    direction = 1 if driving else -1
    eta, eta_b = LOSSY["efficiency"], LOSSY["efficiency_backdrive"]
    torque = reference.steady_rotor_torque(drive, LOSSY["ratio"], force, direction, 0.0, eta,
                                           eta_b)
    assert direction * result["omega_drive"][-1] > 0.0
    assert result["drive_torque"][-1] == pytest.approx(torque, rel=1e-6)
    rigid_result = ls.simulate(rigid, 1.0)
    assert result["drive_torque"][-1] == pytest.approx(rigid_result["drive_torque"][-1],
                                                       rel=1e-6)


def ramp_scene(gear, force, slope, concept="flexible_nut"):
    """``concept`` at rest under ``force`` [N] on a frictionless thread (the
    stage alone holds), its springs critically damped, the rotor's torque
    ramped at ``slope`` [N m/s] from 0 (a rotor of 1e-4 kg m^2: eta_b J_s +
    R > 0, outside the stage's Painleve case)."""
    return scene(concept, gear, rotor={"inertia": 1e-4},
                 torque={"type": "table", "times": [0.0, 1.0], "values": [0.0, slope]},
                 loads={"axial_force": force}, friction={"law": "coulomb", "mu": 0.0},
                 overrides={"damping_ratio": 1.0})


def test_a_self_locking_worm_holds_a_back_driving_load_and_breaks_away_in_closed_form():
    """A self-locking worm (eta_b < 0) holds the load that back-drives a lossy
    stage (eta_b = 0.4) on the same drive: its rotor never breaks away under
    the load alone. A motor torque rising against the load starts the rotor
    where n T reaches T_screw / eta (train_reference's raise torque through
    the worm), as the rigid concept's train solver (its own code) starts."""
    hold = checked(ramp_scene(SELF_LOCKING_WORM, -20.0, 0.0), 0.2, integrator="event_driven")
    assert "rotor breakaway" not in [e.kind for e in hold.events]
    assert np.max(np.abs(hold["omega_drive"])) <= 1e-12  # (its round-off: held at rest)
    lowered = checked(ramp_scene(LOSSY, -20.0, 0.0), 0.2, integrator="event_driven")
    assert lowered["omega_drive"][-1] > 0.1  # (F < 0 drives phi' > 0)
    slope = -0.05  # raising: against the load
    ramp = checked(ramp_scene(SELF_LOCKING_WORM, -20.0, slope), 0.2, integrator="event_driven")
    eta, eta_b = reference.worm_efficiencies(SELF_LOCKING_WORM["lead_angle"],
                                             SELF_LOCKING_WORM["mu"], DEFAULT_FLANK)
    assert eta_b < 0.0
    rigid_scene = ramp_scene(SELF_LOCKING_WORM, -20.0, slope, "rigid")
    rigid = ls.Scene.from_dict(rigid_scene)
    drive = dc_motor_reference.rigid_drive(rigid.to_dict(), rigid.derived())
    breakaway = reference.steady_rotor_torque(drive, 4.0, -20.0, -1, 0.0, eta, eta_b)
    start = next(e for e in ramp.events if e.kind == "rotor breakaway")
    assert slope * start.time == pytest.approx(breakaway, rel=1e-4)
    rigid_start = checked(rigid_scene, 0.2, integrator="event_driven").events[0]
    assert start.time == pytest.approx(rigid_start.time, rel=1e-6)
    assert np.max(np.abs(ramp["omega_drive"][ramp.t < start.time])) <= 1e-12
    assert ramp["omega_drive"][-1] < 0.0


@pytest.mark.parametrize("share, starts", [(0.9, False), (1.1, True)])
def test_the_motors_friction_holds_a_torque_below_it(share, starts):
    """Without an axial load the drive starts where the motor's torque
    exceeds its friction T_c, not below."""
    t_c = 5e-3
    d = scene("flexible", LOSSY, torque=share * t_c, motor={"friction_torque": t_c},
              loads={"axial_force": 0.0})
    result = checked(d, 0.05, integrator="event_driven")
    moved = np.max(np.abs(result["omega_drive"])) > 0.0
    assert moved == starts
    assert (result["motor_friction_loss"][-1] > 0.0) == starts


@settings(max_examples=20, deadline=None)
@given(efficiency=st.floats(0.3, 1.0), backdrive=st.floats(-0.5, 1.0),
       friction_torque=st.sampled_from([0.0, 1e-3, 5e-3]),
       force=st.floats(-30.0, 30.0), play=st.sampled_from([None, "bistop"]))
def test_random_lossy_trains_on_flexible_nut_keep_the_invariants(
        efficiency, backdrive, friction_torque, force, play):
    """Random lossy stages, motor frictions and loads on flexible_nut: every
    run keeps its checks and the invariants, or the stage's Painleve case
    raises JammingError (a self-locking stage back-driven with eta_b J_s + R
    <= 0)."""
    gear = {"type": "lossy", "ratio": 4.0, "efficiency": efficiency,
            "efficiency_backdrive": min(backdrive, efficiency)}
    d = scene(gear=gear, motor={"friction_torque": friction_torque} if friction_torque else None,
              loads={"axial_force": force}, backlash=BISTOP if play else None)
    try:
        checked(d, 0.05, integrator="event_driven")
    except ls.JammingError as error:
        assert "Painleve case" in str(error)


def test_the_stages_painleve_case_raises_jamming_error():
    """A self-locking worm back-driven with eta_b J_s + R <= 0 (the screw's
    inertia beyond R / |eta_b|) has no consistent rotor mode: JammingError
    naming the case."""
    d = scene(gear=SELF_LOCKING_WORM)
    s = ls.Scene.from_dict(d)
    with pytest.raises(ls.JammingError, match="Painleve case: back-driven, eta_b J_s"):
        ls.simulate(s, 0.2, integrator="event_driven")


@pytest.mark.parametrize("concept, k_v", [("flexible_nut", 10.0), ("flexible", 30.0),
                                          ("rigid", 10.0)])
def test_arctan_velocity_takes_its_coefficient_at_the_steady_slip_speed(concept, k_v):
    """The DC motor's steady raise through the lossy stage with
    arctan_velocity on the thread: the rotor's torque is T_screw / (n eta)
    with the thread's coefficient mu (2/pi) atan(k_v |gamma|) at the run's
    steady slip speed gamma (train_reference's closed form on the rigid
    drive of that coefficient)."""
    d = dc_steady_scene(concept, 10.0, 3.0)
    d["friction"] = {"law": "arctan_velocity", "mu": 0.05, "k_v": k_v}
    result = checked(d, 1.0, integrator="event_driven")
    assert result.integrator == "event_driven"
    gamma = result["slip_velocity"][-1]
    assert result["slip_velocity"][-2] == pytest.approx(gamma, rel=1e-9)  # (steady)
    mu = 0.05 * 2.0 / math.pi * math.atan(k_v * abs(gamma))
    assert 0.2 * 0.05 < mu < 0.9 * 0.05  # (the speed matters)
    rigid = ls.Scene.from_dict(dc_steady_scene("rigid", 10.0, 3.0))
    drive = dataclasses.replace(dc_motor_reference.rigid_drive(rigid.to_dict(), rigid.derived()),
                                mu=mu)
    torque = reference.steady_rotor_torque(drive, LOSSY["ratio"], 10.0, 1, 0.0,
                                           LOSSY["efficiency"], LOSSY["efficiency_backdrive"])
    assert result["omega_drive"][-1] > 0.0
    assert result["drive_torque"][-1] == pytest.approx(torque, rel=1e-6)


@settings(max_examples=15, deadline=None)
@given(concept=st.sampled_from(["flexible_nut", "flexible", "rigid"]),
       efficiency=st.floats(0.3, 1.0), backdrive=st.floats(-0.5, 1.0),
       friction_torque=st.sampled_from([0.0, 2e-3]), force=st.floats(-30.0, 30.0),
       k_v=st.sampled_from([10.0, 1e3, 1e5]))
def test_random_lossy_trains_with_arctan_velocity_keep_the_invariants(
        concept, efficiency, backdrive, friction_torque, force, k_v):
    """Random lossy stages, motor frictions, loads and arctan_velocity's
    k_v on every concept without play: every run keeps its checks and the
    invariants, or the stage's Painleve case raises JammingError."""
    gear = {"type": "lossy", "ratio": 4.0, "efficiency": efficiency,
            "efficiency_backdrive": min(backdrive, efficiency)}
    d = scene(concept, gear, friction={"law": "arctan_velocity", "mu": 0.2, "k_v": k_v},
              motor={"friction_torque": friction_torque} if friction_torque else None,
              loads={"axial_force": force})
    try:
        checked(d, 0.05, integrator="event_driven")
    except ls.JammingError as error:
        assert "Painleve case" in str(error)


def test_a_lossless_stage_runs_arctan_velocity_as_the_ideal_gear():
    """eta = eta_b = 1, no motor friction: the rotor contact's drive (an
    element on the constrained solve) is the ideal gear's (none), on the
    rigid concept too, to the integrators' tolerance."""
    lossless = {"type": "lossy", "ratio": 4.0, "efficiency": 1.0, "efficiency_backdrive": 1.0}
    for concept in ("flexible_nut", "rigid"):
        runs = [checked(scene(concept, gear, friction=ARCTAN), 0.1, integrator="event_driven",
                        rtol=1e-10, atol=1e-12)
                for gear in (lossless, {"type": "ideal", "ratio": 4.0})]
        assert runs[0]["friction_loss"][-1] == pytest.approx(runs[1]["friction_loss"][-1],
                                                             rel=1e-6)
        assert runs[0]["gear_loss"][-1] == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("concept", ["flexible_nut", "flexible", "rigid"])
def test_what_the_rotor_contact_does_not_take_stays_refused_on_the_event_driven_scheme(concept):
    """What the rotor's contact does not take stays refused by name: LuGre,
    Stribeck on the rigid concept without play (exact play, mu_static and
    Stribeck elsewhere run: tests/test_event_driven_rotor_play.py)."""
    d = scene(concept, backlash={"axial": 1e-4, "contact": "exact"})
    assert ls.simulate(ls.Scene.from_dict(d), 0.01).integrator == "moreau"
    for friction in ({"law": "stribeck", "mu": 0.2, "mu_static": 0.3},
                     {"law": "lugre", "mu": 0.3, "sigma0": 1e3}):
        static = scene(concept, friction=friction)
        if concept != "rigid" and friction["law"] == "stribeck":
            continue  # (the rotor's contact runs it off the rigid concept without play)
        with pytest.raises(ValueError, match=f'here friction.law = "{friction["law"]}"'):
            ls.simulate(ls.Scene.from_dict(static), 0.01, integrator="event_driven")
