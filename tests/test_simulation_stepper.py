"""The resumable stepper (``_core.DriveStepper``, model/drive_stepper.hpp):
a drive advanced in pieces with its inputs held, against one
``leadscrew.simulate`` run of the same drive."""

import math

import numpy as np
import pytest

import leadscrew as ls
from leadscrew import _core
from helpers import rigid_drive_reference as reference
from helpers.scenes import thesis_scene
from leadscrew.simulation import _run_options

RTOL, ATOL = 1e-8, 1e-10
PIECE = 1e-3  # [s]
T_END = 0.1   # [s]


def stepper(scene, **options):
    return _core.DriveStepper(scene.model(), **_run_options(**options))


def constant_loads(scene, torque, force):
    return scene.replace(loads={"drive_torque": torque, "axial_force": force})


def base_scene(concept, friction, backlash):
    """The default drive (Tr 10x2, 2 kg slide) as `concept`, under a
    constant torque that lifts the slide (slip) and its weight."""
    scene = ls.scenes.load("default").replace(concept=concept)
    if friction == "arctan_velocity":
        scene = scene.replace(friction={"law": "arctan_velocity", "k_v": 1e3})
    if backlash:
        scene = scene.replace(backlash={"axial": 0.05e-3, "contact": "exact"
                                        if friction == "coulomb" else "bistop"})
    return constant_loads(scene, -0.03, -19.62)


CASES = [(concept, friction, backlash)
         for concept in ("rigid", "flexible_nut", "flexible")
         for friction in ("coulomb", "arctan_velocity")
         for backlash in (False, True)]


def channel_scale(values):
    return max(float(np.max(np.abs(values))), 1e-300)


@pytest.mark.parametrize("concept,friction,backlash", CASES)
def test_pieces_agree_with_one_run(concept, friction, backlash):
    scene = base_scene(concept, friction, backlash)
    times = np.arange(1, int(round(T_END / PIECE)) + 1) * PIECE
    reference = ls.simulate(scene, T_END, t_eval=times, rtol=RTOL, atol=ATOL)
    s = stepper(scene, rtol=RTOL, atol=ATOL)
    names = ["u_load", "v_load", "phi_drive", "omega_drive", "friction_loss", "work_drive"]
    stepped = {name: [] for name in names}
    for t in times:
        s.advance(t)
        assert s.time == t
        for name in names:
            stepped[name].append(s.channel(name))
    for name in names:
        expected = np.asarray(reference[name])
        got = np.asarray(stepped[name])
        # Two runs of the same tolerance that stop at different times: they
        # agree to a small multiple of it, relative to the channel's scale
        # (measured: at most 1.2e-7, v_load of the rigid drive with arctan
        # friction and bistop flanks).
        tolerance = 100 * RTOL * channel_scale(expected)
        assert np.max(np.abs(got - expected)) <= tolerance, (name, np.max(np.abs(got - expected)),
                                                             tolerance)
    # N pieces cost about one run, not N runs from t = 0: at most one step
    # more per piece than the run's own steps (each piece ends a step).
    steps_one_run = reference.stats["steps"]
    assert s.stats["steps"] <= 2 * steps_one_run + 2 * len(times)
    # The energy account of the stepped run closes (the run's own bound:
    # K (rtol E + atol G), far above this; docs/physics/result_checks.md).
    flow = (abs(s.channel("work_drive")) + abs(s.channel("work_axial"))
            + s.channel("friction_loss") + s.channel("damping_loss"))
    # (Measured: at most 6.9e-9 of the energy flow.)
    assert abs(s.channel("energy_residual")) <= 10 * RTOL * flow


def test_same_events_as_one_run():
    scene = ls.scenes.load("default")  # sine torque: stick/slip in both directions
    reference = ls.simulate(scene, 1.0, rtol=RTOL, atol=ATOL)
    s = stepper(scene, rtol=RTOL, atol=ATOL)
    for k in range(1, 1001):
        s.advance(k * PIECE)
    assert [kind for _, kind in s.events] == [e.kind for e in reference.events]
    times = np.array([t for t, _ in s.events])
    expected = np.array([e.time for e in reference.events])
    assert np.max(np.abs(times - expected)) < 1e-6
    assert s.channel("u_load") == pytest.approx(reference["u_load"][-1], rel=1e-6)
    assert s.channel("stick") == reference["stick"][-1]


def test_channels_are_simulates():
    scene = ls.scenes.load("default")
    s = stepper(scene)
    reference = ls.simulate(scene, 0.01, t_eval=[0.0, 0.01])
    assert list(s.channel_names) == list(reference.channels)
    s.advance(0.01)
    assert s.channels() == pytest.approx(
        [reference[name][-1] for name in s.channel_names], rel=1e-5, abs=1e-9)


def test_a_set_input_equals_a_constant_load():
    scene = ls.scenes.load("default")
    held = stepper(scene, rtol=RTOL, atol=ATOL)
    held.set_input("drive_torque", -0.03)
    assert held.input("drive_torque") == -0.03
    constant = stepper(constant_loads(scene, -0.03, -19.62), rtol=RTOL, atol=ATOL)
    for t in (0.05, 0.1, 0.2):
        held.advance(t)
        constant.advance(t)
        assert held.channel("u_load") == pytest.approx(constant.channel("u_load"), rel=1e-7)


def test_an_input_step_starts_a_slip_and_the_energy_account_closes():
    """Held at rest by self-locking, the slide lifts once the torque steps
    past the raise torque (20.2 N*mm), and sticks again after it steps back."""
    scene = constant_loads(ls.scenes.load("default"), 0.0, -19.62)
    s = stepper(scene, rtol=RTOL, atol=ATOL)
    s.advance(0.05)
    assert s.channel("stick") == 1 and abs(s.channel("u_load")) < 1e-9
    s.set_input("drive_torque", -0.03)
    s.advance(0.1)
    assert s.channel("stick") == 0 and s.channel("u_load") > 1e-5
    lifted = s.channel("u_load")
    s.set_input("drive_torque", 0.0)
    s.advance(0.3)
    assert s.channel("stick") == 1
    assert s.channel("u_load") >= lifted
    assert s.channel("v_load") == 0.0
    flow = abs(s.channel("work_drive")) + abs(s.channel("work_axial")) + s.channel("friction_loss")
    assert abs(s.channel("energy_residual")) <= 1e-6 * flow
    assert s.stats["restarts"] >= 2


def test_reset_goes_back_to_the_start():
    scene = ls.scenes.load("default")
    s = stepper(scene)
    s.advance(0.2)
    first = s.channels()
    s.set_input("axial_force", -5.0)
    s.advance(0.3)
    s.reset()
    assert s.time == 0.0
    assert s.input("axial_force") == -19.62
    s.advance(0.2)
    assert s.channels() == first


def test_bad_requests_are_refused():
    scene = ls.scenes.load("default")
    s = stepper(scene)
    with pytest.raises(ValueError, match='"drive_torque", "axial_force"'):
        s.set_input("torque", 1.0)
    with pytest.raises(ValueError, match="axial_force"):
        s.set_input("axial_force", math.nan)
    with pytest.raises(ValueError, match="channel"):
        s.channel("no_such_channel")
    s.advance(0.1)
    with pytest.raises(ValueError, match=r"t = 0.05 is invalid: must be >= the stepper's time"):
        s.advance(0.05)
    s.advance(0.1)  # the time it is at: nothing to do
    with pytest.raises(ValueError, match="moreau"):
        stepper(scene, integrator="moreau")
    speed = scene.replace(loads={"drive_torque": None, "drive_speed": 10.0})
    with pytest.raises(ValueError, match='"drive_speed", "axial_force"'):
        stepper(speed).set_input("drive_torque", 5.0)
    with pytest.raises(ValueError, match="drive_speed"):
        stepper(speed).set_input("drive_speed", math.inf)


def test_a_step_past_the_screws_end_is_refused_and_stays_refused():
    # Lowered by its weight with the drive torque helping: the nut runs 50 mm
    # to the screw's drive end.
    scene = constant_loads(ls.scenes.load("default").replace(friction={"mu": 0.05}), 0.05, -19.62)
    s = stepper(scene)
    with pytest.raises(ls.SimulationError, match="screw") as failure:
        s.advance(10.0)
    assert 0.0 < failure.value.time < 10.0
    with pytest.raises(ls.SimulationError, match="stopped at its failure"):
        s.advance(11.0)
    s.reset()
    s.advance(0.01)
    assert s.time == 0.01


def test_an_ode_method_runs_alone():
    scene = constant_loads(ls.scenes.load("default"), -0.03, -19.62).replace(
        friction={"law": "arctan_velocity", "k_v": 1e3})
    reference = ls.simulate(scene, 0.1, integrator="rk_verner6", rtol=RTOL, atol=ATOL,
                            t_eval=[0.1])
    s = stepper(scene, integrator="rk_verner6", rtol=RTOL, atol=ATOL)
    for k in range(1, 101):
        s.advance(k * PIECE)
    assert s.channel("u_load") == pytest.approx(reference["u_load"][-1], rel=1e-6)


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut"])
def test_lugres_bristles_are_kept_between_pieces(concept):
    # The bristles' stiff state converges with the tolerance (rigid: 1.4e-3,
    # 1.9e-5 and 1.1e-8 of its scale apart at rtol 1e-6, 1e-8, 1e-10).
    rtol, atol = 1e-10, 1e-12
    scene = base_scene(concept, "coulomb", False).replace(friction={"law": "lugre"})
    times = np.arange(1, 101) * PIECE
    reference = ls.simulate(scene, 0.1, t_eval=times, rtol=rtol, atol=atol)
    s = stepper(scene, rtol=rtol, atol=atol)
    stepped = []
    for t in times:
        s.advance(t)
        stepped.append((s.channel("bristle_deflection"), s.channel("u_load")))
    stepped = np.array(stepped)
    for k, name in enumerate(["bristle_deflection", "u_load"]):
        expected = np.asarray(reference[name])
        assert np.max(np.abs(stepped[:, k] - expected)) <= 1e-6 * channel_scale(expected), name


def test_a_jam_in_a_piece_is_the_runs():
    """The nut-driven thesis drive just above its critical translating mass
    (eq. m r^2 tan a (mu' - tan a) >= J (1 + mu' tan a)) jams dynamically:
    in 1 ms pieces at the time one run finds."""
    probe = reference.thesis_drive(drive="nut")
    t, mu, r = probe.tan_alpha, probe.mu_eff, probe.mean_radius
    critical = probe.J * (1 + mu * t) / (r * r * t * (mu - t)) - probe.screw_mass
    thread = {"pitch": 1e-3, "mean_diameter": 20e-3}
    scene = ls.Scene.from_dict(thesis_scene(drive="nut", thread=thread, rotor={"inertia": 1e-6},
                                            load={"mass": critical * 1.001}))
    with pytest.raises(ls.JammingError) as one_run:
        ls.simulate(scene, 2.0)
    s = stepper(scene)
    with pytest.raises(ls.JammingError) as pieces:
        for k in range(1, 2001):
            s.advance(k * PIECE)
    assert pieces.value.time == pytest.approx(one_run.value.time, abs=1e-9)
    assert "Painleve" in str(pieces.value)
    with pytest.raises(ls.SimulationError, match="stopped at its failure"):
        s.advance(2.0)


def speed_scene():
    """The default drive (rigid, self-locking) with a speed-controlled motor at rest."""
    return ls.scenes.load("default").replace(loads={"drive_torque": None, "drive_speed": 0.0})


def test_a_drive_speed_input_ramps_over_the_next_advance():
    """A prescribed speed is not stepped (an infinite acceleration): set
    before the first advance it is the speed the drive starts at; later it
    ramps linearly from the speed at the advance's start to the value at its
    end, then holds. The rotor's angle is the ramp's integral, the trapezoid
    h (omega_0 + omega_1) / 2, exactly; the run equals simulate's under the
    same speeds as a table load, the channels at an advance's end those of
    the ramp that ends there."""
    s = stepper(speed_scene(), rtol=RTOL, atol=ATOL)
    assert list(s.input_names) == ["drive_speed", "axial_force"]
    s.set_input("drive_speed", 2.0)  # before the first advance: the start speed
    assert s.channel("omega_drive") == 2.0
    s.advance(0.01)
    assert s.channel("phi_drive") == pytest.approx(0.02, rel=1e-9)
    s.set_input("drive_speed", 10.0)
    assert s.input("drive_speed") == 10.0
    s.advance(0.02)
    assert s.channel("omega_drive") == pytest.approx(10.0, rel=1e-12)
    assert s.channel("phi_drive") == pytest.approx(0.02 + 0.01 * (2.0 + 10.0) / 2, rel=1e-9)
    ramp_end = {name: s.channel(name) for name in ("normal_force", "drive_torque")}
    s.advance(0.03)  # held
    assert s.channel("omega_drive") == pytest.approx(10.0, rel=1e-12)
    assert s.channel("phi_drive") == pytest.approx(0.08 + 0.1, rel=1e-9)
    s.set_input("drive_speed", -4.0)
    s.advance(0.05)
    assert s.channel("omega_drive") == pytest.approx(-4.0, rel=1e-12)
    assert s.channel("phi_drive") == pytest.approx(0.18 + 0.02 * (10.0 - 4.0) / 2, rel=1e-9)
    # As one run under the same speeds as a table load (its energy account
    # and self-checks included).
    table = speed_scene().replace(loads={"drive_speed": {
        "type": "table", "times": [0.0, 0.01, 0.02, 0.03, 0.05],
        "values": [2.0, 2.0, 10.0, 10.0, -4.0]}})
    run = ls.simulate(table, 0.05, t_eval=[0.02 - 1e-9, 0.05], rtol=RTOL, atol=ATOL)
    assert run.checks["energy_balance"]["passed"]
    # the ramp's end: its acceleration (800 rad/s^2) in the forces, the left limit
    for name, value in ramp_end.items():
        assert value == pytest.approx(run[name][0], rel=1e-5), name
    for name in ("u_load", "phi_drive", "omega_drive"):
        assert s.channel(name) == pytest.approx(run[name][-1], rel=1e-7, abs=1e-12), name
    # The work integrals to the energy check's bound (their integration error:
    # the two runs take different steps).
    energy_tolerance = run.checks["energy_balance"]["bound"]
    for name in ("work_drive", "work_axial", "friction_loss"):
        assert s.channel(name) == pytest.approx(run[name][-1], rel=0, abs=energy_tolerance), name
    assert abs(s.channel("energy_residual")) <= energy_tolerance
    # the same speed again: no ramp, and after the hold began no restart
    s.set_input("drive_speed", -4.0)
    s.advance(0.06)
    restarts = s.stats["restarts"]
    s.set_input("drive_speed", -4.0)
    s.advance(0.07)
    assert s.stats["restarts"] == restarts
    assert s.channel("phi_drive") == pytest.approx(0.24 - 0.08, rel=1e-9)


def test_a_motor_voltage_input_reaches_the_closed_form_steady_state():
    """A DC motor's stepper takes motor_voltage as its input, held: the
    drive settles at the rigid drive's closed-form steady state for the new
    voltage (tests/helpers/dc_motor_reference.py)."""
    from test_simulation_drive_dc_motor import F, KT, R, motor_scene, rigid_reference
    from helpers import dc_motor_reference

    scene = motor_scene(voltage=3.0)
    s = stepper(ls.Scene.from_dict(scene), rtol=RTOL, atol=ATOL)
    assert list(s.input_names) == ["motor_voltage", "axial_force"]
    assert s.input("motor_voltage") == 3.0
    s.advance(0.5)
    s.set_input("motor_voltage", 1.5)
    assert s.input("motor_voltage") == 1.5
    s.advance(2.5)
    current, omega, _ = dc_motor_reference.steady_state(rigid_reference(scene), F, 1.5, R, KT, KT)
    assert s.channel("motor_current") == pytest.approx(current, rel=1e-6)
    assert s.channel("omega_drive") == pytest.approx(omega, rel=1e-6)
    assert s.channel("motor_voltage") == 1.5
    flow = abs(s.channel("work_drive")) + abs(s.channel("work_axial")) + s.channel("friction_loss")
    assert abs(s.channel("energy_residual")) <= 1e-6 * flow
