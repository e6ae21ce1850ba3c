"""The drive's 2-D flank cone under a transverse slip (issue 34, item 3) with
play and with a DC motor: penalty play (backlash.contact "bistop", "cubic")
on every concept on Moreau-Jean, on the rigid concept's event-driven scheme
and with LuGre's bristles on the ODE methods; exact play on Moreau-Jean; a
DC motor on the schemes the law runs on. Against the quasi-static creep
(tests/helpers/transverse_slip_reference.py), the cone's invariants, no
friction where a flank of the play does not touch, the energy account, and
the refusals of what stays out.

Play: quasi-statically the flank that carries the load carries the stick
forces whatever the play, so the load creeps at the closed form on either
flank; an axial force that reverses sends the nut across the play (a free
flight, no friction at all, the transverse one included) onto the other
flank, where it creeps the other way at the same rate (free rotor: q =
tan(alpha) / mu' whatever |F|).

DC motor (no inductance): its torque M = k (V - k phi') / R follows the
rotor speed the creep itself moves, phi' = gamma / rho, so the helix balance
T~_st(M) = mu' |N~_st(M)| gamma / |(gamma, w)| is solved at each w and
averaged by quadrature (thread_dc_motor_mean_creep_speed_sine); at V = 0 the
motor brakes the creep."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers.transverse_slip_reference import (thread_dc_motor_mean_creep_speed_sine,
                                               thread_load_creep_speed,
                                               thread_load_creep_speed_driven)
from test_transverse_slip_drive import (FORCE, INERTIA, MASS, PERIODS, STRIBECK, closed_form,
                                        scene, stribeck_closed_form, thread)

FREQUENCY = 20.0  # Hz
AMPLITUDE = 0.01  # m/s
# The axial force reverses at half time: the nut crosses the play.
REVERSING = ls.Table([0.0, 0.25, 0.26, 0.5], [FORCE, FORCE, -FORCE, -FORCE])
PLAYS = {"bistop": {"axial": 1e-4, "contact": "bistop", "stiffness": 1e8},
         "cubic": {"axial": 1e-4, "contact": "cubic", "stiffness": 1e8},
         "exact": {"axial": 1e-4, "contact": "exact", "restitution": 0.5}}
MOTOR = {"type": "dc", "resistance": 0.5, "torque_constant": 0.2}  # Ohm, N m/A


def step_options(integrator, steps=2000):
    """Moreau-Jean's step: `steps` a period of w."""
    return {"dt": 1.0 / (steps * FREQUENCY)} if integrator == "moreau" else {}


def run_reversing(concept, play, integrator, friction=None):
    """The reversing force; exact play on the flexible concepts at 5,000
    steps a period (dt = 1e-5 s): at 2,000 their landing on the flank
    creates energy with or without a transverse slip (1.5e-2 of the flow
    without, the check failing; none from dt = 1e-5 s down)."""
    s = scene(ls.Sine(AMPLITUDE, 2 * math.pi * FREQUENCY), concept=concept,
              backlash=PLAYS[play], friction=friction).replace(loads={"axial_force": REVERSING})
    steps = 5000 if play == "exact" and concept != "rigid" else 2000
    return ls.simulate(s, 0.5, integrator=integrator, **step_options(integrator, steps))


def window_speed(result, start, end):
    t, u = result["t"], result["u_load"]
    return (np.interp(end, t, u) - np.interp(start, t, u)) / (end - start)


def assert_flank_invariants(result, mu_eff, viscous=0.0):
    """|(T, T_w)| <= mu' |N| + c s every row (= in slip where the flank
    carries a force, for Coulomb), no friction at all where it carries none
    (the play's flight), and the friction's power never positive."""
    friction, across = result["friction_force"], result["transverse_friction"]
    normal = np.abs(result["normal_force"])
    speed = np.hypot(result["slip_velocity"], result["transverse_velocity"])
    magnitude = np.hypot(friction, across)
    assert np.all(magnitude <= (mu_eff * normal + viscous * speed) * (1 + 1e-12) + 1e-12)
    flight = normal == 0.0
    assert flight.any() and np.all(friction[flight] == 0.0) and np.all(across[flight] == 0.0)
    power = friction * result["slip_velocity"] + across * result["transverse_velocity"]
    assert np.all(power <= 1e-12 * np.max(magnitude) * np.max(speed))


def flow(result):
    return max(np.max(np.abs(result["work_axial"])), result["work_transverse"][-1],
               np.max(np.abs(result["work_drive"])))


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut", "flexible"])
@pytest.mark.parametrize("play", ["bistop", "cubic", "exact"])
def test_play_creeps_both_ways_on_moreau(concept, play):
    """Penalty and exact play on Moreau-Jean: the load creeps down at the
    closed form on one flank, crosses the play when the force reverses, and
    creeps up at it on the other, each to 1 % over four whole periods
    (measured 1.3e-5..2.7e-4; exact play on the flexible concept 1.9e-4);
    the account creates no energy beyond 1e-3 of its flow."""
    r = run_reversing(concept, play, "moreau")
    down = closed_form(AMPLITUDE)
    assert window_speed(r, 0.05, 0.25) == pytest.approx(down, rel=1e-2)
    assert window_speed(r, 0.30, 0.50) == pytest.approx(-down, rel=1e-2)
    assert_flank_invariants(r, thread().effective_mu(0.3))
    assert np.max(-r["energy_residual"]) < 1e-3 * flow(r)
    assert r.checks["energy_balance"]["passed"] and r.checks["friction_cone"]["passed"]


@pytest.mark.parametrize("play", ["bistop", "cubic"])
def test_penalty_play_on_the_event_driven_rigid_drive(play):
    """The rigid drive's event-driven scheme takes penalty play (the cone a
    velocity law's factor on the penalty force): both ways at the closed
    form to 1 % (measured 1.1e-5..1.5e-4), the account to the integration's
    tolerance (< 1e-6 of the flow)."""
    r = run_reversing("rigid", play, "event_driven")
    down = closed_form(AMPLITUDE)
    assert window_speed(r, 0.05, 0.25) == pytest.approx(down, rel=1e-2)
    assert window_speed(r, 0.30, 0.50) == pytest.approx(-down, rel=1e-2)
    assert_flank_invariants(r, thread().effective_mu(0.3))
    assert np.max(np.abs(r["energy_residual"])) < 1e-6 * flow(r)


@pytest.mark.parametrize("concept, integrator, play", [
    ("rigid", "event_driven", "bistop"), ("rigid", "moreau", "bistop"),
    ("flexible", "moreau", "bistop"), ("rigid", "moreau", "exact"),
    ("flexible", "moreau", "exact")])
def test_stribeck_with_play_has_no_friction_in_flight(concept, integrator, play):
    """Stribeck's viscous term acts along the 2-D slip only where the flank
    touches (the helix's does: mode_forces): in the play's flight the
    transverse friction is zero too (it was -c w there, failing the
    friction_law check at the first flight). Both ways at the quasi-static
    balance to 1 % (measured 3.7e-6..2.7e-4; exact play 2.0e-5..2.5e-4)."""
    r = run_reversing(concept, play, integrator, friction=STRIBECK)
    down = stribeck_closed_form(AMPLITUDE)
    assert window_speed(r, 0.05, 0.25) == pytest.approx(down, rel=1e-2)
    assert window_speed(r, 0.30, 0.50) == pytest.approx(-down, rel=1e-2)
    assert_flank_invariants(r, thread().effective_mu(STRIBECK["mu_static"]), STRIBECK["viscous"])
    assert all(check["passed"] for check in r.checks.values())


@pytest.mark.parametrize("concept", ["rigid", "flexible"])
@pytest.mark.parametrize("play", ["bistop", "exact"])
def test_lugre_with_play_on_moreau(concept, play):
    """LuGre's 2-D bristles with penalty and exact play on Moreau-Jean: both
    ways at the closed form to 1 % (measured 1.3e-5..2.3e-4), no friction in
    flight, no energy created beyond 1e-3 of the flow (measured none above
    round-off)."""
    friction = {"law": "lugre", "mu": 0.3, "sigma0": 1e6}
    r = run_reversing(concept, play, "moreau", friction=friction)
    down = closed_form(AMPLITUDE)
    assert window_speed(r, 0.05, 0.25) == pytest.approx(down, rel=1e-2)
    assert window_speed(r, 0.30, 0.50) == pytest.approx(-down, rel=1e-2)
    flight = r["normal_force"] == 0.0
    assert flight.any() and np.all(r["transverse_friction"][flight] == 0.0)
    assert np.max(-r["energy_residual"]) < 1e-3 * flow(r)
    assert all(check["passed"] for check in r.checks.values())


@pytest.mark.parametrize("play", ["bistop", "cubic"])
def test_lugre_with_penalty_play_on_cvode(play):
    """LuGre's 2-D bristles on the flexible concept with penalty play on
    CVODE: both ways at the closed form (mu_static = mu, no viscous term) to
    1 % (measured 8e-6..1e-4); the bristles' friction is zero in flight
    (their normal force is)."""
    friction = {"law": "lugre", "mu": 0.3, "sigma0": 1e6}
    r = run_reversing("flexible", play, "cvode_bdf", friction=friction)
    down = closed_form(AMPLITUDE)
    assert window_speed(r, 0.05, 0.25) == pytest.approx(down, rel=1e-2)
    assert window_speed(r, 0.30, 0.50) == pytest.approx(-down, rel=1e-2)
    flight = r["normal_force"] == 0.0
    assert flight.any() and np.all(r["transverse_friction"][flight] == 0.0)
    assert np.max(np.abs(r["energy_residual"])) < 1e-6 * flow(r)
    assert all(check["passed"] for check in r.checks.values())


def dc_scene(voltage, concept="rigid", friction=None, inductance=0.0):
    """The drive of test_transverse_slip_drive with a DC motor for the
    drive torque (MOTOR, its voltage and inductance given)."""
    motor = dict(MOTOR, voltage=voltage, inductance=inductance)
    return ls.Scene({
        "concept": concept,
        "thread": {"pitch": "4 mm", "mean_diameter": "16 mm", "flank_angle": "30 deg"},
        "friction": friction or {"law": "coulomb", "mu": 0.3},
        "rotor": {"inertia": INERTIA}, "load": {"mass": MASS}, "motor": motor,
        "loads": {"axial_force": FORCE,
                  "transverse_slip_velocity": ls.Sine(AMPLITUDE, 2 * math.pi * FREQUENCY)}})


def dc_closed_form(voltage, torque_constant=MOTOR["torque_constant"]):
    th = thread()
    return thread_dc_motor_mean_creep_speed_sine(
        FORCE, th.lead_angle, th.mean_radius, th.effective_mu(0.3), th.hand_sign, voltage,
        MOTOR["resistance"], torque_constant, AMPLITUDE)


def speed_after_first_period(result):
    return window_speed(result, 1.0 / FREQUENCY, result["t"][-1])


def test_dc_motor_reference_limits():
    """The reference's limits: a motor without torque constant is the free
    rotor's closed form; at V = 0 it brakes the creep (slower, same way);
    a voltage that drives the load down speeds it up, one that lifts it
    reverses it."""
    th = thread()
    free = 2.0 / math.pi * thread_load_creep_speed(FORCE, th.lead_angle, th.effective_mu(0.3),
                                                   AMPLITUDE)
    assert dc_closed_form(0.0, torque_constant=1e-9) == pytest.approx(free, rel=1e-9)
    braked = dc_closed_form(0.0)
    assert 0.0 < braked / free < 0.9
    assert dc_closed_form(0.25) / free > 1.5 and dc_closed_form(-0.25) * free < 0.0


@pytest.mark.parametrize("concept, integrator", [("rigid", "event_driven"), ("rigid", "moreau"),
                                                 ("flexible_nut", "moreau"),
                                                 ("flexible", "moreau")])
@pytest.mark.parametrize("voltage", [0.0, 0.25, -0.25])
def test_dc_motor_creeps_at_the_quasi_static_balance(concept, integrator, voltage):
    """A DC motor on the rotor (no inductance): the load creeps at the helix
    balance with the motor's speed-dependent torque, to 1 % after the first
    period (measured 3.2e-4..1.5e-3), braked at V = 0, sped up or reversed
    by a voltage; the account (the motor's work in it) closes, event-driven
    to 1e-8 of the flow, Moreau-Jean dissipative within 1e-3."""
    r = ls.simulate(dc_scene(voltage, concept), PERIODS / FREQUENCY, integrator=integrator,
                    **step_options(integrator))
    assert speed_after_first_period(r) == pytest.approx(dc_closed_form(voltage), rel=1e-2)
    residual = r["energy_residual"]
    if integrator == "event_driven":
        assert np.max(np.abs(residual)) < 1e-8 * flow(r)
    else:
        assert np.max(-residual) < 1e-3 * flow(r)
    assert all(check["passed"] for check in r.checks.values())


def test_dc_motor_inductance_is_a_lag_that_vanishes():
    """With inductance the current lags the back-EMF by L / R: the creep
    departs from the balance without it (1.0e-2 at L/R = 2 ms against the
    period of 50 ms) and returns to it as L falls (differences from the run
    without inductance 1.0e-2, 1.8e-3, 3.2e-4 at L = 1e-3, 3e-4, 1e-4 H)."""
    def speed(inductance):
        r = ls.simulate(dc_scene(0.25, inductance=inductance), PERIODS / FREQUENCY,
                        integrator="event_driven")
        return speed_after_first_period(r)

    without = speed(0.0)
    differences = [abs(speed(inductance) / without - 1.0) for inductance in (1e-3, 3e-4, 1e-4)]
    assert differences[0] < 2e-2
    assert differences[1] < 0.3 * differences[0] and differences[2] < 0.3 * differences[1]


@pytest.mark.parametrize("integrator", ["cvode_bdf", "moreau"])
@pytest.mark.parametrize("concept", ["rigid", "flexible"])
def test_dc_motor_with_lugre(concept, integrator):
    """LuGre's 2-D bristles (mu_static = mu) with the DC motor on CVODE and
    Moreau-Jean: the same balance to 1 % after the first period (measured
    2.8e-4, 1.5e-3 on CVODE; 1.6e-3 Moreau-Jean, flexible)."""
    friction = {"law": "lugre", "mu": 0.3, "sigma0": 1e6}
    r = ls.simulate(dc_scene(0.25, concept, friction), PERIODS / FREQUENCY,
                    integrator=integrator, **step_options(integrator))
    assert speed_after_first_period(r) == pytest.approx(dc_closed_form(0.25), rel=1e-2)
    assert all(check["passed"] for check in r.checks.values())


@pytest.mark.parametrize("concept, integrator, friction", [
    ("rigid", "event_driven", None), ("rigid", "moreau", None), ("flexible", "moreau", None),
    ("rigid", "cvode_bdf", {"law": "lugre", "mu": 0.3, "sigma0": 1e6})])
@pytest.mark.parametrize("torque", [0.0, 0.03, -0.03])
def test_an_ideal_gear_passes_the_torque_on(concept, integrator, friction, torque):
    """An ideal gear (ratio 3) is a transmission: the screw takes 3 M, and
    the load creeps at the closed form with it (to 1 %; measured 1.1e-3..2.6e-3,
    above the drive's without a gear: the rotor's inertia reflected, n^2 J,
    raises the inertia number nine-fold)."""
    s = scene(ls.Sine(AMPLITUDE, 2 * math.pi * FREQUENCY), concept=concept, torque=torque,
              friction=friction).replace(gear={"type": "ideal", "ratio": 3.0})
    r = ls.simulate(s, PERIODS / FREQUENCY, integrator=integrator, **step_options(integrator))
    th = thread()
    expected = 2.0 / math.pi * thread_load_creep_speed_driven(
        3.0 * torque, FORCE, th.lead_angle, th.mean_radius, th.effective_mu(0.3), AMPLITUDE,
        th.hand_sign)
    assert speed_after_first_period(r) == pytest.approx(expected, rel=1e-2)
    assert all(check["passed"] for check in r.checks.values())


def speed_scene(speed, concept):
    """The drive at a prescribed rotor speed [rad/s] under the transverse slip."""
    return scene(ls.Sine(AMPLITUDE, 2 * math.pi * FREQUENCY), concept=concept).replace(
        loads={"drive_speed": speed, "drive_torque": None})


SPEED_SCHEMES = [("rigid", "event_driven"), ("rigid", "moreau"), ("flexible", "moreau")]


@pytest.mark.parametrize("concept, integrator", SPEED_SCHEMES)
@pytest.mark.parametrize("speed", [2.0, -2.0])
def test_a_prescribed_speed_needs_the_threads_torque_at_the_cones_share(concept, integrator,
                                                                         speed):
    """A prescribed rotor speed fixes the helix slip gamma = rho phi'; the
    cone's helix component is then mu' |N| gamma / |(gamma, w)|, the 1-D
    thread's at mu_eff(t) = mu |gamma| / |(gamma, w(t))|: the motor's torque
    is ls.thread's lowering torque (phi' > 0 lowers the load) or raising
    torque at mu_eff, row by row (the rigid drive to 1e-12 of its size,
    measured 1e-15; the flexible one 1e-3, measured 6e-5: its springs)."""
    r = ls.simulate(speed_scene(speed, concept), 0.2, integrator=integrator,
                    **step_options(integrator))
    late = r["t"] > 0.05
    gamma, w = r["slip_velocity"][late], r["transverse_velocity"][late]
    th = thread()
    mu_eff = 0.3 * np.abs(gamma) / np.hypot(gamma, w)
    expected = np.array([ls.thread.lower_torque(th, m, abs(FORCE)) if speed > 0
                         else -ls.thread.raise_torque(th, m, abs(FORCE)) for m in mu_eff])
    torque = r["drive_torque"][late]
    tolerance = 1e-12 if concept == "rigid" else 1e-3
    assert np.max(np.abs(torque - expected)) <= tolerance * np.max(np.abs(expected))
    assert np.ptp(mu_eff) > 0.01  # (the cone's share moves with w)
    assert all(check["passed"] for check in r.checks.values())


@pytest.mark.parametrize("concept, integrator", SPEED_SCHEMES)
def test_a_drive_held_at_zero_speed_carries_the_frictionless_torque(concept, integrator):
    """Held at zero speed (gamma = 0) under the transverse slip, the cone's
    helix component vanishes wherever w does not: the motor carries the
    whole load, the frictionless thread's torque -F r tan(alpha) (to 1e-12
    of it on the rigid drive, 1e-5 on the flexible one). Left out: the rows
    at w's zeros, where the split between the motor and the flank's static
    friction is indeterminate (Moreau-Jean's steps that end at sin's
    round-off, w = -2.7e-17 m/s, took 0.04 N of the load there: the cone's
    direction at the apex is round-off's)."""
    r = ls.simulate(speed_scene(0.0, concept), 0.2, integrator=integrator,
                    **step_options(integrator))
    rows = (r["t"] > 0.05) & (np.abs(r["transverse_velocity"]) > 1e-9 * AMPLITUDE)
    frictionless = -ls.thread.raise_torque(thread(), 0.0, abs(FORCE))
    tolerance = 1e-12 if concept == "rigid" else 1e-5
    assert np.max(np.abs(r["drive_torque"][rows] - frictionless)) <= tolerance * abs(
        frictionless)


@pytest.mark.parametrize("changes, integrator, match", [
    ({"backlash": PLAYS["exact"]}, "event_driven",
     r"backlash.contact = \"exact\" and integrator = \"event_driven\""),
    ({"gear": {"type": "lossy", "ratio": 3.0, "efficiency": 0.7, "efficiency_backdrive": 0.4}},
     "moreau", r"gear.type = \"lossy\""),
    ({"nut": {"preload": 50.0, "preload_stiffness": 1e7}}, "moreau", r"a preloaded nut"),
])
def test_what_stays_refused(changes, integrator, match):
    """Exact play on the event-driven scheme, the train's friction stages and a
    preloaded nut stay refused by name, saying what runs (exact end stops:
    test_transverse_slip_drive_elements.py)."""
    s = scene(ls.Sine(0.01, 100.0)).replace(**changes)
    with pytest.raises(ValueError, match=r"loads\.transverse_slip_velocity = .* is invalid with "
                                         + match + r".*\"bistop\" or \"cubic\".*DC motor"):
        ls.simulate(s, 0.01, integrator=integrator, **step_options(integrator))
