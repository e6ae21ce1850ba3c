"""The reproductions of issue 17 ("No silent wrong answer"), each a scene
that random testing or a new user found returning a wrong answer without a
word: friction doing positive work, jamming where there is none or at the
wrong time, an energy account that does not close, a flank without
friction, options that made the answer meaningless. Every test failed
before its fix; each asserts the physics with the result's own checks off
(``check=False``), so that it holds on its own, not only through them."""

import math
import os
import signal
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import leadscrew as ls
from helpers import rigid_drive_reference as reference

SPEED_DRIVE = {"concept": "rigid", "thread": {"pitch": 0.003, "mean_diameter": 0.02},
               "friction": {"law": "coulomb", "mu": 0.3}, "load": {"mass": 5.0},
               "loads": {"drive_speed": {"type": "sine", "amplitude": 5.0, "omega": 10.0},
                         "axial_force": -50.0}}


def scene(d, **changes):
    """The scene of dict d with sections replaced (a None value drops the key)."""
    d = {key: (dict(value) if isinstance(value, dict) else value) for key, value in d.items()}
    for key, value in changes.items():
        if value is None:
            d.pop(key, None)
        elif isinstance(value, dict) and isinstance(d.get(key), dict):
            d[key] = {**d[key], **value}
        else:
            d[key] = value
    return ls.Scene.from_dict(d)


def work_scale(r):
    return np.abs(r["work_drive"]).max() + np.abs(r["work_axial"]).max()


def assert_dissipative(r):
    """Friction does no positive work: at every output point beyond a
    relative 1e-9 of the run's largest friction power, and never in the
    integral (its loss ends non-negative and never falls by more than 1e-9
    of its largest value)."""
    power = r["friction_force"] * r["slip_velocity"]
    scale = np.abs(r["friction_force"]).max() * np.abs(r["slip_velocity"]).max()
    assert power.max() <= 1e-9 * scale
    loss = r["friction_loss"]
    assert loss[-1] >= 0.0
    assert (np.maximum.accumulate(loss) - loss).max() <= 1e-9 * max(np.abs(loss).max(), 1e-300)


def assert_checks_pass(r):
    failed = [name for name, c in r.checks.items() if c["applies"] and not c["passed"]]
    assert not failed, r.checks


# --- friction that does positive work ---------------------------------------

REPRODUCTION_1 = {
    "concept": "rigid", "thread": {"pitch": 0.0075, "mean_diameter": 0.0236, "flank_angle": 0.44},
    "friction": {"law": "coulomb", "mu": 0.85}, "rotor": {"inertia": 6e-6}, "load": {"mass": 0.17},
    "loads": {"drive_torque": {"type": "sine", "amplitude": 5e-4, "omega": 4.0},
              "axial_force": {"type": "sine", "amplitude": 1000.0, "omega": 1400.0}}}


def test_1_a_slip_that_reverses_within_a_step_is_located():
    """A stick->slip+ whose slip reverses 11 ns later, within a step of
    0.28 ms: the root of the slip velocity started at +1e-200 (on its
    surface), the secant stuck to that end of the bracket, and the event was
    taken at the step's end, the drive slipping backwards against friction
    that pushed it (+24.6 W, friction_loss -1.47e-2 J). Against the
    independent reference of the rigid drive."""
    s = ls.Scene.from_dict(REPRODUCTION_1)
    r = ls.simulate(s, 0.1, rtol=1e-6, atol=1e-8, check=False)
    assert_dissipative(r)
    assert_checks_pass(r)
    assert np.abs(r["energy_residual"]).max() <= 1e-6 * max(work_scale(r), 1e-12)
    d = s.derived()
    drive = reference.RigidDrive(
        lead=s.thread.lead, mean_radius=0.0118, mu=0.85, rotor_inertia=6e-6,
        screw_inertia=d["screw_inertia"], screw_mass=d["screw_mass"],
        nut_inertia=d["nut_inertia"], nut_mass=d["nut_mass"], load_mass=0.17,
        flank_angle=0.44, hand="right", drive="screw")
    ref = reference.simulate(drive, reference.Harmonic(0.0, 5e-4, 4.0),
                             reference.Harmonic(0.0, 1000.0, 1400.0), 0.1)
    scale = np.abs(ref.u_load(r.t)).max()
    np.testing.assert_allclose(r["u_load"], ref.u_load(r.t), rtol=0, atol=1e-6 * scale + 1e-15)


REPRODUCTION_2 = {
    "concept": "flexible_nut", "drive": "screw",
    "thread": {"pitch": 0.0056, "mean_diameter": 0.015, "flank_angle": 0.093},
    "friction": {"law": "coulomb", "mu": 0.275},
    "screw": {"radius": 0.0067, "length": 0.27, "youngs_modulus": 3.9e10},
    "nut": {"outer_radius": 0.0117, "length": 0.0068, "youngs_modulus": 4.1e8, "position": 0.214},
    "rotor": {"inertia": 2.8e-4}, "load": {"mass": 22.0},
    "loads": {"drive_torque": {"type": "sine", "amplitude": -0.0102, "omega": 2.72},
              "axial_force": -2.8},
    "overrides": {"damping_ratio": 0.0}}


@pytest.mark.parametrize("rtol", [1e-6, 1e-8, 1e-10])
def test_2_a_slip_direction_is_not_taken_from_round_off(rtol):
    """The relaxed flexible nut starts with forces of 1e-15 N: the slip
    direction was taken from a slip velocity of -2.4e-38 m/s, and the drive
    then slipped the other way with friction pushing it, at every rtol. The
    drive is self-locking and its torque stays below the breakaway torque
    (closed form): it holds, up to the nut's elastic deflection."""
    s = ls.Scene.from_dict(REPRODUCTION_2)
    thread = s.thread
    lower = ls.lower_torque(thread, mu=0.275, load=2.8)
    assert 0.0102 * math.sin(2.72 * 0.05) < lower  # the torque never reaches breakaway
    r = ls.simulate(s, 0.05, rtol=rtol, check=False)
    assert_dissipative(r)
    assert_checks_pass(r)
    assert np.abs(r["u_load"]).max() < 1e-6


REPRODUCTION_3 = {
    "concept": "rigid", "thread": {"pitch": 0.03, "mean_diameter": 0.046},
    "friction": {"law": "arctan_velocity", "mu": 0.44, "k_v": 3e4},
    "rotor": {"inertia": 7.4e-5}, "load": {"mass": 139.0},
    "loads": {"drive_torque": -0.08}, "initial": {"rotor_speed": 6.0}}


@pytest.mark.parametrize("integrator", ["cvode_bdf", "cvode_adams", "rk_verner6", "dopri5",
                                        "event_driven"])
def test_3_the_regularized_law_jams_where_it_starts_in_its_painleve_regime(integrator):
    """kappa |G_NT| >= G_NN at the start (k_V gamma_T = 4200: kappa = mu'):
    the run went on with the normal force's sign inconsistent, friction
    pushing (+2.38 N at +0.141 m/s); exact Coulomb jams there at t = 0."""
    with pytest.raises(ls.JammingError, match="regularized law") as error:
        ls.simulate(ls.Scene.from_dict(REPRODUCTION_3), 0.01, integrator=integrator)
    assert error.value.time == 0.0
    coulomb = scene(REPRODUCTION_3, friction={"law": "coulomb"})
    with pytest.raises(ls.JammingError) as exact:
        ls.simulate(coulomb, 0.01)
    assert exact.value.time == 0.0


def test_4_jamming_is_never_reported_before_the_run_began():
    s = scene(REPRODUCTION_3, loads={"drive_torque": 0.08}, initial={"rotor_speed": -6.0})
    with pytest.raises(ls.JammingError) as error:
        ls.simulate(s, 0.01)
    assert error.value.time == 0.0


# --- a speed-controlled drive reverses ---------------------------------------


def speed_kinematics(s, t, amplitude=5.0, omega=10.0):
    """Rotor angle of the sine speed and the load's travel it prescribes."""
    phi = amplitude / omega * (1.0 - np.cos(omega * t))
    return phi, -s.thread.lead_per_radian * phi


@pytest.mark.parametrize("integrator", ["event_driven", "moreau"])
@pytest.mark.parametrize("axial_force", [-50.0, 0.0])
def test_5_a_speed_controlled_rigid_drive_reverses(integrator, axial_force):
    """Through zero speed the motor prescribes the slip: its acceleration
    decides the new slip direction (the LCP had no solution: d = 0, and the
    run raised JammingError at t = pi/10 saying the Painleve condition does
    not hold). The load follows the thread exactly; friction dissipates
    mu' |N| |gamma_T|."""
    s = scene(SPEED_DRIVE, loads={"axial_force": axial_force})
    r = ls.simulate(s, 1.0, integrator=integrator, t_eval=np.linspace(0, 1, 101), check=False)
    _, u = speed_kinematics(s, r.t)
    np.testing.assert_allclose(r["u_load"], u, rtol=0, atol=1e-9 if integrator == "event_driven"
                               else 1e-6)
    assert_dissipative(r)
    assert_checks_pass(r)
    mu = s.model().effective_mu
    slipping = np.abs(r["slip_velocity"]) > 1e-9
    np.testing.assert_allclose(np.abs(r["friction_force"][slipping]),
                               mu * np.abs(r["normal_force"][slipping]), rtol=1e-9)


def test_5_a_table_speed_from_one_to_minus_one():
    s = scene(SPEED_DRIVE, loads={"drive_speed": {"type": "table", "times": [0.0, 0.2],
                                                   "values": [1.0, -1.0]}})
    r = ls.simulate(s, 0.2)
    assert_dissipative(r)
    assert r["omega_drive"][-1] == pytest.approx(-1.0)
    assert any("slip" in e.kind for e in r.events)


def test_5_a_motor_held_at_zero_speed_leaves_the_load_to_the_thread():
    """drive_speed = 0: every velocity is fixed, the friction force is
    statically indeterminate, and the thread holds what its friction can (the
    run failed with 'constraint equations singular'). This thread
    self-locks (tan alpha < mu'): the motor needs no torque."""
    s = scene(SPEED_DRIVE, loads={"drive_speed": 0.0})
    assert ls.is_self_locking(s.thread, mu=0.3)
    r = ls.simulate(s, 0.1)
    assert np.all(r["stick"] == 1.0)
    np.testing.assert_allclose(r["drive_torque"], 0.0, rtol=0, atol=1e-15)  # of 0.05 N*m load
    np.testing.assert_array_equal(r["u_load"], 0.0)
    # A thread that cannot hold the load alone (mu' < tan alpha): the motor
    # carries the rest, the friction at the cone's edge.
    steep = scene(SPEED_DRIVE, thread={"pitch": 0.03}, friction={"mu": 0.1},
                  loads={"drive_speed": 0.0})
    assert not ls.is_self_locking(steep.thread, mu=0.1)
    r = ls.simulate(steep, 0.1)
    mu = steep.model().effective_mu
    np.testing.assert_allclose(np.abs(r["friction_force"]), mu * np.abs(r["normal_force"]),
                               rtol=1e-12)
    assert np.all(np.abs(r["drive_torque"]) > 0.0)


@pytest.mark.parametrize("speed", [-1.3, 1.3])
@pytest.mark.parametrize("mu", [0.0, 0.3])
def test_6_speed_controlled_with_exact_play(speed, mu):
    """The load flies across the play and lands on a flank that the motor
    moves at its prescribed speed: the impact's impulses are decided with
    the slip prescribed (JammingError before, with mu = 0 too); the motor's
    impulsive work enters the account (1-2 % of the work was missing);
    Moreau-Jean keeps the load on the thread (it fell through: -4.99 cm)."""
    s = scene(SPEED_DRIVE, friction={"mu": mu}, backlash={"axial": 1e-4, "contact": "exact"},
              loads={"drive_speed": speed})
    r = ls.simulate(s, 0.1, check=False)
    assert_checks_pass(r)
    assert np.abs(r["energy_residual"]).max() <= 1e-8 * work_scale(r)
    moreau = ls.simulate(s, 0.1, integrator="moreau", check=False)
    assert_checks_pass(moreau)
    # the load stays within the play of where the thread carries it
    travel = -s.thread.lead_per_radian * speed * 0.1
    assert abs(moreau["u_load"][-1] - travel) <= 1e-4
    assert abs(r["u_load"][-1] - travel) <= 1e-4


REPRODUCTION_7 = {
    "concept": "flexible_nut", "drive": "nut",
    "thread": {"pitch": 0.0048, "mean_diameter": 0.035, "flank_angle": 0.23},
    "friction": {"law": "coulomb", "mu": 0.8},
    "screw": {"radius": 0.015, "length": 0.34, "youngs_modulus": 5.2e9},
    "nut": {"outer_radius": 0.044, "length": 0.0135, "youngs_modulus": 3.1e9, "position": 0.078},
    "rotor": {"inertia": 4.4e-4}, "load": {"mass": 219.0}, "loads": {"drive_torque": 0.0014}}


def test_7_a_moreau_step_too_long_for_the_stiffness_is_refused_with_its_limit():
    """At dt 7e-4 s the springs in Moreau-Jean's iteration matrix make the
    flank's step problem Painleve-like (mu' |G~_NT| / G~_NN = 1.58) though
    the drive is not (0.025): it 'jammed' at t = 0 from rest. The error
    names dt and the longest step that resolves it; that step runs and
    agrees with the event-driven scheme."""
    s = ls.Scene.from_dict(REPRODUCTION_7)
    with pytest.raises(ValueError, match=r"dt = 0\.0007 is invalid: must be < ") as error:
        ls.simulate(s, 0.013, integrator="moreau", dt=7e-4)
    limit = float(str(error.value).split("must be < ")[1].split(" ")[0])
    assert 1e-4 < limit < 7e-4
    exact = ls.simulate(s, 0.013, t_eval=[0.013])
    moreau = ls.simulate(s, 0.013, integrator="moreau", dt=0.013 / math.ceil(4 * 0.013 / limit),
                         t_eval=[0.013])
    assert moreau["u_load"][-1] == pytest.approx(exact["u_load"][-1], rel=1e-2)


# --- an energy account that does not close ----------------------------------

REPRODUCTION_8 = {
    "concept": "flexible_nut", "drive": "screw",
    "thread": {"pitch": 0.012701057127884987, "mean_diameter": 0.02477978590032844,
               "flank_angle": 0.5550048109809842, "hand": "left"},
    "friction": {"law": "coulomb", "mu": 1.0},
    "screw": {"radius": 0.01276591664968776, "length": 0.115786998939626,
              "youngs_modulus": 600529774809.0536, "support": "both_ends"},
    "nut": {"outer_radius": 0.023843499938524883, "length": 0.01636097288664384,
            "youngs_modulus": 371505641001.5734, "position": 0.07758107098042413},
    "rotor": {"inertia": 3.458116564136407e-05}, "load": {"mass": 0.014401822776506056},
    "loads": {"drive_speed": {"type": "sine", "amplitude": -1.3433794185110852,
                              "omega": 58.610669396453666, "phase": 1.7401004550551524},
              "axial_force": {"type": "sine", "amplitude": 0.9046689163755995,
                              "omega": 346.55842246414926}},
    "backlash": {"axial": 0.0009444031430869865, "contact": "exact",
                 "restitution": 0.8172834444438978}}


def test_8_a_speed_controlled_motors_impulse_is_booked_as_work():
    """At an impact the speed-controlled motor's impulse does work at its
    held speed; it was booked in the impact's loss only (residual 4.3e-2 of
    the work at any rtol)."""
    s = ls.Scene.from_dict(REPRODUCTION_8)
    r = ls.simulate(s, 0.23314758276234152, rtol=1e-11, atol=1e-15, check=False)
    assert_checks_pass(r)
    assert np.abs(r["energy_residual"]).max() <= 1e-7 * work_scale(r)


REPRODUCTION_9 = {
    "concept": "flexible_nut", "drive": "nut", "thread": {"pitch": 0.006, "mean_diameter": 0.012},
    "friction": {"law": "coulomb", "mu": 0.0},
    "backlash": {"axial": 9e-4, "contact": "exact", "restitution": 0.5},
    "screw": {"radius": 0.006, "length": 0.64, "youngs_modulus": 5e10},
    "nut": {"outer_radius": 0.01, "length": 0.02, "youngs_modulus": 1.9e11, "position": 0.33},
    "rotor": {"inertia": 2.6e-4}, "load": {"mass": 0.0056}, "loads": {"axial_force": 8.0}}


def test_9_a_weak_bounce_closed_plastically_books_its_loss():
    """A bounce too weak to fly is closed (the flank stays shut): the normal
    velocity taken out was not booked (5e-4 of the work at every rtol). Now
    the residual falls with the tolerance."""
    s = ls.Scene.from_dict(REPRODUCTION_9)
    residuals = []
    for rtol in (1e-6, 1e-8, 1e-10):
        r = ls.simulate(s, 0.1, rtol=rtol, atol=rtol * 1e-4, check=False)
        assert_checks_pass(r)
        residuals.append(np.abs(r["energy_residual"]).max() / work_scale(r))
    assert residuals[0] < 1e3 * 1e-6 and residuals[1] < 1e3 * 1e-8 and residuals[2] < 1e3 * 1e-10
    assert residuals[0] > residuals[1] > residuals[2]


REPRODUCTION_10 = {
    "concept": "flexible_nut", "drive": "screw",
    "thread": {"pitch": 0.002410681735780869, "mean_diameter": 0.0067644474709859116,
               "flank_angle": 0.024024601854595515, "hand": "left"},
    "friction": {"law": "coulomb", "mu": 1.0},
    "screw": {"radius": 0.0034684256850596486, "length": 0.729732766209477,
              "youngs_modulus": 3693607.6109550716},
    "nut": {"outer_radius": 0.005438070871095242, "length": 0.04633776208259663,
            "youngs_modulus": 1377859466.4197507, "position": 0.5033441231594844},
    "rotor": {"inertia": 7.026161755920946e-07}, "load": {"mass": 5.882393314924229},
    "loads": {"drive_torque": {"type": "sine", "amplitude": 2.21134715841156,
                               "omega": 1107.120932550196, "phase": 6.177355927222431},
              "axial_force": {"type": "sine", "amplitude": -0.960646157974472,
                              "omega": 2.7496606243153203, "phase": 1.229219213246662,
                              "offset": -489.1313751490737}}}


def test_10_moreau_creating_energy_is_reported_not_returned():
    """dt 7.34e-4 s is too long for this soft screw: the account created 3.9
    times the work (kinetic energy 1.72 J against 0.166 J at dt/10). The
    run raises, naming the energy check; dt/10 passes it."""
    s = ls.Scene.from_dict(REPRODUCTION_10)
    t_end = 1.8761457349863935
    with pytest.raises(ls.SimulationError, match="energy_balance"):
        ls.simulate(s, t_end, integrator="moreau", dt=0.0007342097702184637,
                    t_eval=np.linspace(0, t_end, 20))
    fine = ls.simulate(s, t_end, integrator="moreau", dt=7.342097702184637e-5,
                       t_eval=np.linspace(0, t_end, 20))
    assert fine.checks["energy_balance"]["passed"]
    assert fine["kinetic"][-1] < 0.2


# --- a flank with no friction ---------------------------------------------


@pytest.mark.parametrize("law", ["coulomb", "arctan_velocity"])
@pytest.mark.parametrize("contact", ["bistop", "cubic"])
def test_11_a_penalty_flank_the_nut_starts_on_carries_friction(law, contact):
    """The nut placed exactly on a penalty flank: the flank's root started at
    zero, a crossing into it was not seen, and the flank carried no friction
    (0 N while the normal force reached -180 N): the self-locking drive
    back-drove 0.244 mm. Now it holds as it does 0.1 um off the flank."""
    base = ls.scenes.load("position_holding")
    runs = []
    for play in (0.1e-3, 0.0999e-3):
        s = base.replace(friction={"law": law}, backlash={"contact": contact},
                         loads={"axial_force": -100.0}, initial={"play_position": play})
        r = ls.simulate(s, 0.1, check=False)
        assert_checks_pass(r)
        assert np.abs(r["friction_force"]).max() > 1.0
        runs.append(r["u_load"][-1])
    assert abs(runs[0]) < 30e-6
    assert runs[0] == pytest.approx(runs[1], abs=1e-6)


# --- options that make the answer meaningless --------------------------------


def test_13_options_that_make_the_answer_meaningless_are_refused():
    s = ls.scenes.load("default")
    with pytest.raises(ValueError, match=r"rtol = 0\.5 is invalid: must be a finite number in "
                                         r"\(0, 0\.001\] \(a looser tolerance no longer "
                                         r"bounds the error"):
        ls.simulate(s, 1.0, rtol=0.5)
    with pytest.raises(ValueError, match=r"atol = 1e-300 is invalid: must be a finite number in "
                                         r"\[1e-100, 0\.001\] \(the error weights"):
        ls.simulate(s, 1.0, atol=1e-300)
    with pytest.raises(ValueError, match=r"dt = 10 is invalid: must be <= t_end = 1 s"):
        ls.simulate(s, 1.0, integrator="moreau", dt=10.0)
    sine = s.replace(loads={"axial_force": {"type": "sine", "amplitude": 50.0,
                                            "omega": 2 * math.pi * 20}})
    with pytest.raises(ValueError, match=r"dt = 0\.02 is invalid: must be <= 0\.0125 s, a quarter"):
        ls.simulate(sine, 1.0, integrator="moreau", dt=0.02)
    block = ls.FrictionBlock(1.0, 0.3, 10.0, ls.Sine(6.0, 4 * math.pi))
    with pytest.raises(ValueError, match="rtol = 0.01 is invalid"):
        ls.simulate(block, 1.0, rtol=0.01)
    with pytest.raises(ValueError, match="dt = 0.2 is invalid"):
        ls.simulate(block, 1.0, integrator="moreau", dt=0.2)


@pytest.mark.parametrize("model", ["scene", "block"])
@pytest.mark.parametrize("options, message", [
    ({"rtol": math.nan}, r"^rtol = nan is invalid: must be a finite number in \(0, 0\.001\]$"),
    ({"rtol": 0.0}, r"^rtol = 0 is invalid: must be a finite number in \(0, 0\.001\]$"),
    ({"rtol": -1e-6}, r"^rtol = -1e-06 is invalid: must be a finite number in \(0, 0\.001\]$"),
    ({"rtol": 1.0}, r"^rtol = 1 is invalid: must be a finite number in \(0, 0\.001\] \(a "
                    r"looser"),
    ({"rtol": math.inf}, r"^rtol = inf is invalid: must be a finite number in \(0, 0\.001\] "),
    ({"atol": math.nan}, r"^atol = nan is invalid: must be a finite number in "
                         r"\[1e-100, 0\.001\]$"),
    ({"atol": 0.0}, r"^atol = 0 is invalid: must be a finite number in \[1e-100, 0\.001\]$"),
])
def test_13_the_tolerances_are_refused_naming_their_real_range(model, options, message):
    """NaN and the values no integrator takes name the range that holds,
    (0, 1e-3] for rtol (it said "(0, 1)" before)."""
    run = (ls.scenes.load("default") if model == "scene"
           else ls.FrictionBlock(1.0, 0.3, 10.0, ls.Sine(6.0, 4 * math.pi)))
    with pytest.raises(ValueError, match=message):
        ls.simulate(run, 1.0, **options)


def test_16_the_integrators_a_penalty_contact_with_coulomb_takes_are_one_list():
    # (Moreau-Jean runs penalty flanks now: the list offers it, and it runs.)
    s = ls.scenes.load("position_holding").replace(friction={"law": "coulomb"})
    assert s["backlash"]["contact"] == "bistop"
    with pytest.raises(ValueError, match=r'must be one of "event_driven", "moreau"$'):
        ls.simulate(s, 0.01, integrator="cvode_bdf")  # (a name no integrator has: its own)
    result = ls.simulate(s, 0.01, integrator="moreau", dt=1e-5)
    assert [k for k, c in result.checks.items() if c["applies"] and not c["passed"]] == []
    exact = ls.simulate(s, 0.01)
    assert result["u_load"][-1] == pytest.approx(exact["u_load"][-1], abs=1e-8)


# --- the thesis's acceleration law on a flexible drive -----------------------

REPRODUCTION_17 = {
    "concept": "flexible", "drive": "nut",
    "thread": {"pitch": 0.00160867794255238, "mean_diameter": 0.00884069654504377,
               "flank_angle": 0.6562262516468828},
    "friction": {"law": "arctan_acceleration", "mu": 0.18643390006693725,
                 "k_v": 52.23702062093036},
    "screw": {"radius": 0.004062466573438834, "length": 0.563730536087546,
              "youngs_modulus": 68633538830.35904},
    "nut": {"outer_radius": 0.010436159955432879, "length": 0.016508715333711805,
            "youngs_modulus": 929420359709.0502, "position": 0.4293836047768},
    "rotor": {"inertia": 0.003506380591289315}, "load": {"mass": 486.25863531368094},
    "loads": {"drive_torque": {"type": "table",
                               "times": [0.01097117497804332, 0.4977293886112884,
                                         0.8320472503254633, 1.112042826542434,
                                         1.2167257181218767, 1.778878504238267],
                               "values": [0.24419941005905366, 0.0012313008063945764,
                                          6.547548240594329, -0.0007576822813489737,
                                          3.0553766539520386e-05, 0.24013645154470403]},
              "axial_force": 24.52354233802973}}


def test_17_cvode_newton_converges_on_the_acceleration_law():
    """Eq. (3.15)'s friction follows the slip acceleration, which carries the
    flexible drive's stiff modes: CVODE's Newton, with its default 3
    iterations, failed at every step (0.2 s: 229,147 steps, 225,258
    failures). With 10 it converges: a tenth of the steps, few failures,
    and the same trajectory as an explicit method that needs no Newton."""
    s = ls.Scene.from_dict(REPRODUCTION_17)
    r = ls.simulate(s, 0.2, t_eval=[0.1, 0.2])
    assert r.stats["steps"] < 30_000
    assert r.stats["nonlinear_failures"] < 0.2 * r.stats["steps"]
    explicit = ls.simulate(s, 0.2, integrator="rk_verner6", t_eval=[0.1, 0.2], max_steps=200_000)
    np.testing.assert_allclose(r["u_load"], explicit["u_load"], rtol=1e-5)


def test_17_progress_reports_the_simulated_time():
    s = ls.Scene.from_dict(REPRODUCTION_17)
    r = ls.simulate(s, 0.1, progress=True)
    assert r.t[-1] == 0.1


@pytest.mark.parametrize("what", ["scene", "block"])
def test_17_ctrl_c_interrupts_a_run_within_half_a_second(what):
    """SIGINT during a long run: KeyboardInterrupt within 0.5 s, and the
    process simulates again afterwards."""
    program = textwrap.dedent(f"""
        import os, signal, threading, time, math
        import leadscrew as ls
        from test_simulation_reproductions import REPRODUCTION_17
        if {what!r} == "scene":
            model, t_end = ls.Scene.from_dict(REPRODUCTION_17), 1.0
            options = dict()
        else:
            model = ls.FrictionBlock(1.0, 0.3, 10.0, lambda t: 6.0 * math.sin(4 * math.pi * t))
            t_end, options = 1e5, dict(max_steps=10**9)
        sent = []
        def interrupt():
            time.sleep(1.0)
            sent.append(time.monotonic())
            os.kill(os.getpid(), signal.SIGINT)
        threading.Thread(target=interrupt, daemon=True).start()
        try:
            ls.simulate(model, t_end, **options)
            print("FINISHED")
        except KeyboardInterrupt:
            print("INTERRUPTED", time.monotonic() - sent[0])
        r = ls.simulate(ls.scenes.load("default"), 0.05)
        print("USABLE", len(r.t) > 1)
    """)
    here = os.path.dirname(__file__)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [here] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    out = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                         timeout=120, env=env, cwd=here)
    assert out.returncode == 0, out.stderr
    lines = dict(line.split(" ", 1) for line in out.stdout.split("\n") if " " in line)
    assert "INTERRUPTED" in lines, out.stdout
    assert float(lines["INTERRUPTED"]) < 0.5
    assert lines["USABLE"] == "True"


# Found by the new-user review of this work.

def _resting_on_its_flank(mass, play_position=None):
    """The default drive at rest, its load held by the thread alone (no motor
    torque): mass m, axial force -m g. From m = 22 kg the Painleve condition
    holds (mu' |G_NT| >= G_NN); the load stays inside the static band."""
    changes = {"load": {"mass": mass}, "loads": {"drive_torque": 0.0, "axial_force": -9.81 * mass}}
    if play_position is not None:
        changes.update(backlash={"axial": 1e-4, "contact": "exact"},
                       initial={"play_position": play_position})
    return ls.scenes.load("default").replace(**changes)


@pytest.mark.parametrize("integrator,options", [("event_driven", {}),
                                                ("moreau", {"dt": 1e-5})])
@pytest.mark.parametrize("play_position", [None, 5e-5, -5e-5])
def test_review_a_drive_resting_on_its_loaded_flank_in_the_painleve_regime_holds(
        integrator, options, play_position):
    """The LCP of one normal-force sign may miss the stick that holds it in
    the Painleve regime: the nut on its loaded flank opened and jammed at its
    first impact 2.6e-11 s later (event-driven), Moreau-Jean jammed at t = 0
    without play and let the load fall through the thread with it."""
    scene = _resting_on_its_flank(22.0, play_position)
    resting = ls.simulate(_resting_on_its_flank(22.0), 0.05, check=False)  # no play: always held
    assert resting["u_load"][-1] == 0.0
    r = ls.simulate(scene, 0.05, integrator=integrator, check=False, **options)
    # held where it starts, or (starting on the other flank) down by the play
    # onto the flank that carries the load, and held there
    fall = 1e-4 if play_position == -5e-5 else 0.0
    assert r["u_load"][-1] == pytest.approx(-fall, abs=2e-7)
    assert r["stick"][-1] == 1.0
    assert r["normal_force"][-1] == pytest.approx(resting["normal_force"][-1], rel=1e-9)


def test_review_moreau_jeans_energy_check_accepts_the_schemes_own_friction_booking():
    """The default scene with Moreau-Jean at its default step was refused by
    energy_balance (5.0e-6 J created against 1.4e-6 J): a step's friction
    impulse is booked at the slip at its end while the positions advance
    with the theta-average, a first-order term wherever the slip speeds up
    (ResultCheckSpec::step_friction_excess). It is now in the bound; the
    answer agrees with the event-driven one."""
    scene = ls.scenes.load("default")
    t = np.linspace(0.0, 1.0, 11)
    exact = ls.simulate(scene, 1.0, rtol=1e-10, atol=1e-14, t_eval=t)
    for dt in (None, 2e-3):
        options = {} if dt is None else {"dt": dt}
        r = ls.simulate(scene, 1.0 if dt else 0.1, integrator="moreau", **options)
        assert r.checks["energy_balance"]["passed"]
        rows = np.searchsorted(r.t, t[t <= r.t[-1]])
        np.testing.assert_allclose(r["u_load"][rows], exact["u_load"][: len(rows)], atol=5e-5)


def test_review_moreau_jeans_flank_gap_bound_does_not_depend_on_the_output_times():
    """The flank_gap tolerance took the play's rate from the output rows:
    11 rows over 1 s made it 100 times tighter than every step's rows did,
    and a correct run was refused."""
    scene = ls.scenes.load("position_holding").replace(friction={"law": "coulomb"},
                                                       backlash={"contact": "exact"})
    bounds = []
    for t_eval in (None, np.linspace(0.0, 1.0, 11)):
        r = ls.simulate(scene, 1.0, integrator="moreau", dt=1e-4, t_eval=t_eval)
        bounds.append(r.checks["flank_gap"]["bound"])
    assert bounds[0] == bounds[1]


def test_review_moreau_jeans_restituting_step_creates_no_energy():
    """Fuzz case (seed 3338614132711679): a rigid drive with exact play and
    Newton restitution e = 1 under Coulomb friction; Moreau-Jean's step that
    closed the flank created 2.7e-4 J (0.3 of the run's energy scale) at
    every dt, as Kane and Levinson's paradox does at an impact, and the
    self-check let it pass. The step now takes the largest restitution that
    creates no more than its plastic version, as the event-driven impact
    does."""
    scene = ls.Scene.from_dict({
        "concept": "rigid",
        "thread": {"pitch": 0.0034402036125209525, "mean_diameter": 0.007603260656619499},
        "friction": {"law": "coulomb", "mu": 0.6428592238063809},
        "backlash": {"axial": 0.0009448993211137465, "contact": "exact", "restitution": 1.0},
        "rotor": {"inertia": 0.00038649918074686745}, "load": {"mass": 0.857529056882477},
        "loads": {"axial_force": {"type": "sine", "amplitude": -0.9297532013089855,
                                  "omega": 1538.3695374648876, "phase": 1.034684946709381,
                                  "offset": 0.8821517505180909},
                  "drive_torque": {"type": "table",
                                   "times": [0.005302112395912321, 0.006814573490251086,
                                             0.014398297702443445, 0.04666615755078447],
                                   "values": [0.0005388124722896245, -0.0002703199598216808,
                                              -0.0014019422328079895, -0.00034208540103732065]}},
        "initial": {"play_position": 0.00047244966055687325}})
    for dt in (4.483262026216875e-05, 4.483262026216875e-06):
        # (every step: the flank closes in a few of them, and each step's residual counts)
        r = ls.simulate(scene, 0.0496556958641739, integrator="moreau", dt=dt, t_eval="steps")
        flow = np.max(np.abs(r["work_drive"]) + np.abs(r["work_axial"]) + r["kinetic"])
        assert r.events or np.any(r["normal_force"] != 0)  # the flank closes
        assert np.min(r["energy_residual"]) >= -1e-9 * flow
