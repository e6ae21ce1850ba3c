"""The DC motor's driver and armature on both schemes (issue 31, reproductions
2, 5 and 8; docs/physics/dc_motor.md): the current limiter bounded by its
supply |U(t)| (a back-EMF beyond it passes the limit), drive_torque = k_t i at
every row, Moreau-Jean's exact armature step at any dt, and k_e != k_t against
the steady-state closed form."""

import numpy as np
import pytest

import leadscrew as ls
from helpers import dc_motor_reference as reference
from test_simulation_drive_dc_motor import F, R, KT, motor_scene, rigid_reference

# (each step's armature is read: every step kept, not simulate's sampled default)
pytestmark = pytest.mark.usefixtures("every_step")

# Reproduction 2: the rotor spun to 200 rad/s (back-EMF k_e w = 10 V) against a
# 1 V driver limited to 2 A. Holding -2 A would take U_d = R (-2 A) + 10 V = 8 V,
# eight times the supply; the driver gives its utmost, +1 V, and the current is
# (1 V - 10 V) / 1 Ohm = -9 A, braking the rotor with k_t 9 A = 0.45 N m.
SPUN = {"concept": "rigid", "thread": {"pitch": 0.002, "mean_diameter": 0.012},
        "friction": {"law": "coulomb", "mu": 0.1}, "rotor": {"inertia": 0.0001},
        "load": {"mass": 1.0}, "initial": {"rotor_speed": 200.0},
        "motor": {"type": "dc", "voltage": 1.0, "resistance": 1.0, "inductance": 0.0,
                  "torque_constant": 0.05, "current_limit": 2.0}}
SCHEMES = [{}, {"integrator": "moreau", "dt": 1e-5}]


def spun(inductance=0.0, rotor_speed=200.0, voltage=1.0):
    return ls.Scene.from_dict({**SPUN, "initial": {"rotor_speed": rotor_speed},
                               "motor": {**SPUN["motor"], "inductance": inductance,
                                         "voltage": voltage}})


def assert_motor_checks_pass(result):
    for name in ("driver_voltage", "motor_torque"):
        assert result.checks[name]["applies"] and result.checks[name]["passed"], name
    assert result.checks["armature"]["passed"]  # (applies without inductance)


@pytest.mark.parametrize("options", SCHEMES)
@pytest.mark.parametrize("inductance", [0.0, 1e-3])
def test_a_back_emf_beyond_the_supply_passes_the_current_limit(inductance, options):
    result = ls.simulate(spun(inductance), 0.05, **options)
    voltage, current = result["motor_voltage"], result["motor_current"]
    omega = result["omega_drive"]
    assert np.max(np.abs(voltage)) <= 1.0 + 1e-12
    assert_motor_checks_pass(result)
    # The limit cannot hold: the current passes -2 A toward -9 A (L / R = 1 ms
    # lets it reach -8.5 A while the rotor slows).
    assert np.min(current) < -8.0
    if inductance == 0.0:
        # (Moreau-Jean: the step's armature, its back-EMF at omega_theta)
        speed = reference.step_speed(omega, result.integrator == "moreau")
        driver, expected = reference.limited_driver(1.0, speed, 1.0, 0.05, 2.0)
        np.testing.assert_allclose(current, expected, rtol=0, atol=1e-9)
        np.testing.assert_allclose(voltage, driver, rtol=0, atol=1e-9)
        # At t = 0: U_d = +1 V (the supply), i = -9 A, the brake k_t i = -0.45 N m.
        assert voltage[0] == pytest.approx(1.0, abs=1e-12)
        assert current[0] == pytest.approx(-9.0, rel=1e-12)
        assert result["drive_torque"][0] == pytest.approx(-0.45, rel=1e-12)
    elif not options:
        assert any("current limit passed" in e.kind for e in result.events)
    # The account books U_d i: it closes on the event-driven scheme.
    if not options:
        assert np.max(np.abs(result["energy_residual"])) <= 1e-7 * np.max(
            np.abs(result["work_drive"]))


@pytest.mark.parametrize("options", SCHEMES)
def test_the_driver_reverses_its_output_to_brake_a_back_driven_rotor(options):
    """A four-quadrant driver fed with |U|: the rotor driven backward at
    -200 rad/s (back-EMF -10 V) under U = +1 V drives +11 A; holding +2 A takes
    -8 V, so the driver puts out -1 V, its utmost, and the current is
    (-1 V + 10 V) / 1 Ohm = 9 A."""
    result = ls.simulate(spun(rotor_speed=-200.0), 1e-3, **options)
    assert result["motor_voltage"][1] == pytest.approx(-1.0, rel=1e-9)
    driver, expected = reference.limited_driver(1.0, result["omega_drive"], 1.0, 0.05, 2.0)
    if not options:
        assert result["motor_current"][0] == pytest.approx(9.0, rel=1e-12)
        np.testing.assert_allclose(result["motor_current"], expected, rtol=0, atol=1e-9)
    assert_motor_checks_pass(result)


@pytest.mark.parametrize("options", SCHEMES)
def test_the_limiter_takes_k_e_for_the_back_emf_and_k_t_for_the_torque(options):
    """k_e = 0.04 V s/rad != k_t = 0.05 N m/A: at 200 rad/s the back-EMF is
    8 V, holding -2 A would take 6 V, the driver puts out +1 V, and
    i = (1 - 8) / 1 = -7 A brakes with k_t i = -0.35 N m."""
    d = {**SPUN, "motor": {**SPUN["motor"], "back_emf_constant": 0.04}}
    result = ls.simulate(ls.Scene.from_dict(d), 0.01, **options)
    row = 0 if not options else 1  # (Moreau-Jean's first row after a step)
    # (Moreau-Jean: the step's armature, its back-EMF at omega_theta)
    omega = reference.step_speed(result["omega_drive"], bool(options))[row]
    assert result["motor_voltage"][row] == pytest.approx(1.0, rel=1e-9)
    assert result["motor_current"][row] == pytest.approx((1.0 - 0.04 * omega) / 1.0, rel=1e-9)
    assert result["drive_torque"][0] == pytest.approx(0.05 * -7.0, rel=1e-12)
    if not options:
        driver, expected = reference.limited_driver(1.0, result["omega_drive"], 1.0, 0.04, 2.0)
        np.testing.assert_allclose(result["motor_current"], expected, rtol=0, atol=1e-9)
    assert_motor_checks_pass(result)


def test_the_moreau_limiter_agrees_with_the_event_driven_one_with_inductance():
    exact = ls.simulate(spun(1e-3), 0.05)
    t = exact.t
    for dt in (1e-4, 5e-5):
        stepped = ls.simulate(spun(1e-3), 0.05, integrator="moreau", dt=dt)
        error = np.max(np.abs(np.interp(t, stepped.t, stepped["motor_current"]) -
                              exact["motor_current"]))
        # First order in dt (Moreau-Jean's impulses): 9 A over the braking's
        # time scale of a few ms.
        assert error <= 9.0 * dt / 1e-3, dt


# Reproduction 5: a sine voltage on an inductance-free motor: i(0) = U(0) / R =
# 3 V / 2 Ohm = 1.5 A, drive_torque(0) = k_t i = 0.075 N m.
SINE = {"concept": "rigid", "thread": {"pitch": 0.002, "mean_diameter": 0.012},
        "friction": {"law": "coulomb", "mu": 0.1}, "load": {"mass": 1.0},
        "loads": {"axial_force": -10.0},
        "motor": {"type": "dc", "voltage": {"type": "sine", "amplitude": 12.0, "omega": 300.0,
                                            "offset": 3.0},
                  "resistance": 2.0, "inductance": 0.0, "torque_constant": 0.05}}


@pytest.mark.parametrize("inductance", [0.0, 1e-3])
@pytest.mark.parametrize("options", [{}, {"integrator": "moreau", "dt": 1e-4}])
def test_drive_torque_is_the_motors_torque_at_every_row(inductance, options):
    scene = ls.Scene.from_dict({**SINE, "motor": {**SINE["motor"], "inductance": inductance}})
    result = ls.simulate(scene, 0.02, **options)
    np.testing.assert_allclose(result["drive_torque"], 0.05 * result["motor_current"],
                               rtol=1e-12, atol=1e-15)
    assert_motor_checks_pass(result)
    if inductance == 0.0:
        assert result["motor_current"][0] == pytest.approx(1.5, rel=1e-12)
        assert result["drive_torque"][0] == pytest.approx(0.075, rel=1e-12)


@pytest.mark.parametrize("options", [{}, {"integrator": "moreau", "dt": 1e-4}])
def test_a_torque_driven_rotor_reports_its_torque_from_row_0(options):
    torque_driven = {key: value for key, value in SINE.items() if key != "motor"}
    torque_driven["loads"] = {"axial_force": -10.0, "drive_torque": 0.05}
    scene = ls.Scene.from_dict(torque_driven)
    result = ls.simulate(scene, 0.02, **options)
    np.testing.assert_allclose(result["drive_torque"], 0.05, rtol=1e-15)
    # Moreau-Jean's account still books the torque's work over each step.
    assert result["work_drive"][-1] == pytest.approx(0.05 * result["phi_drive"][-1], rel=1e-12)


# Reproduction 8: a fast armature (L / R = 5 us) at Moreau-Jean's default
# dt = 1e-4 s, on a scene only Moreau-Jean runs (mu_static on the thread).
FAST = {"thread": {"pitch": 0.0006, "mean_diameter": 0.005},
        "friction": {"mu": 0.02, "mu_static": 0.03},
        "motor": {"type": "dc", "voltage": 0.0, "resistance": 4.0, "inductance": 2e-05,
                  "torque_constant": 0.05},
        "gear": {"ratio": 2.0, "type": "lossy", "efficiency": 0.7}}


def test_a_fast_armature_runs_at_moreaus_default_step():
    result = ls.simulate(ls.Scene.from_dict(FAST), 0.05)
    assert result.integrator == "moreau"
    np.testing.assert_array_equal(result["motor_current"], 0.0)  # (U = 0: at rest)
    driven = ls.simulate(ls.Scene.from_dict({**FAST, "motor": {**FAST["motor"],
                                                               "voltage": 3.0}}), 0.05)
    assert np.all(driven["motor_current"] <= 3.0 / 4.0 * (1 + 1e-12))  # the stall current


@pytest.mark.parametrize("inductance", [1e-6, 1e-5, 1e-4])
def test_moreaus_armature_agrees_with_the_event_driven_scheme_at_any_step(inductance):
    """The armature over a Moreau-Jean step is integrated exactly for the
    step's voltage and back-EMF: it never alternates (the theta-method's
    factor (1 - (1 - theta) x) / (1 + theta x), x = dt R / L, is negative
    beyond x = 1 / (1 - theta)), and the current agrees with the event-driven
    scheme's at first order in dt, the scheme's order, whether dt resolves
    L / R (1e-4 s against 5e-5 s) or not (5e-7 s)."""
    scene = ls.Scene.from_dict(motor_scene(inductance=inductance))
    t_end = 0.05
    exact = ls.simulate(scene, t_end)
    errors = []
    for dt in (2e-4, 1e-4):
        stepped = ls.simulate(scene, t_end, integrator="moreau", dt=dt)
        assert np.max(stepped["motor_current"]) <= 3.0 / R * (1 + 1e-9)  # the stall current
        late = stepped.t >= 10 * dt  # (the start's transient is the step's own)
        errors.append(np.max(np.abs(stepped["motor_current"][late] -
                                    np.interp(stepped.t[late], exact.t,
                                              exact["motor_current"]))))
    # First order: halving dt halves the error (within 20 %).
    assert errors[1] <= 0.6 * errors[0]
    assert errors[1] <= 1e-2 * 3.0 / R


@pytest.mark.parametrize("inductance", [1e-3, 0.0])
@pytest.mark.parametrize("options", [{}, {"integrator": "moreau", "dt": 1e-4}])
def test_a_back_emf_constant_apart_from_the_torque_constant(inductance, options):
    """k_e != k_t: the back-EMF takes k_e, the torque k_t. Steady state on
    the rigid drive: the torque T the train needs sets i = T / k_t, and
    omega = (U - R i) / k_e (i.e. (U k_t - R T) / (k_t k_e))."""
    back_emf_constant = 0.03  # [V s/rad] against k_t = 0.05 N m/A
    scene = motor_scene(inductance=inductance, back_emf_constant=back_emf_constant)
    result = ls.simulate(ls.Scene.from_dict(scene), 2.0, **options)
    current, omega, torque = reference.steady_state(rigid_reference(scene), F, 3.0, R, KT,
                                                    back_emf_constant)
    assert omega == pytest.approx((3.0 * KT - R * torque) / (KT * back_emf_constant))
    assert result["motor_current"][-1] == pytest.approx(current, rel=1e-6)
    assert result["omega_drive"][-1] == pytest.approx(omega, rel=1e-6)
    assert result["drive_torque"][-1] == pytest.approx(torque, rel=1e-6)
    assert_motor_checks_pass(result)


def test_the_steppers_next_piece_keeps_the_saturated_limiter():
    """The stepper (C API, FMU) rebuilds its elements when an input changes;
    the new limiter takes its mode from the state. The back-driven rotor's
    current beyond the limit (saturated at -1 V) under a new input of 0.9 V
    stays saturated at -0.9 V, as one run whose voltage steps there; started
    free it put out +0.9 V and drove the current toward 10 A."""
    from leadscrew import _core
    from leadscrew.simulation import _run_options

    scene = spun(1e-3, rotor_speed=-200.0)
    stepper = _core.DriveStepper(scene.model(), **_run_options())
    stepper.advance(0.002)
    assert stepper.channel("motor_current") > 2.0  # (beyond the limit, saturated)
    stepper.set_input("motor_voltage", 0.9)
    stepper.advance(0.004)
    stepped = {"type": "table", "times": [0.0, 0.002, 0.002 + 1e-12, 0.004],
               "values": [1.0, 1.0, 0.9, 0.9]}
    one = ls.simulate(ls.Scene.from_dict({**SPUN, "initial": {"rotor_speed": -200.0},
                                          "motor": {**SPUN["motor"], "inductance": 1e-3,
                                                    "voltage": stepped}}), 0.004)
    assert stepper.channel("motor_voltage") == pytest.approx(-0.9, rel=1e-12)
    assert one["motor_voltage"][-1] == pytest.approx(-0.9, rel=1e-12)
    assert stepper.channel("motor_current") == pytest.approx(one["motor_current"][-1], rel=1e-6)


# A case of the drive-train fuzz: a rigid drive with play (bistop) behind an
# ideal stage of -25.8, its motor limited to 4.72 A without inductance and
# with its own friction, so Moreau-Jean (dt 1e-4 s) is the scene's scheme. The
# rotor runs up at the limit until it releases at 10.8 ms. The step of the
# release held the limit at its omega_theta, but its row reported the hold's
# voltage (15.72 V, below the 15.74 V supply) with the free current at the
# row's own speed (4.55 A): neither U_d = R i + k_e omega_theta nor the same
# at the row's speed held (0.05 V and 0.016 V off), nor did the work booked,
# h U_d i_max, match the row's U_d i.
RELEASE = {
    "concept": "rigid", "thread": {"pitch": 0.0009867497182276664,
                                   "mean_diameter": 0.04232805346267221},
    "friction": {"law": "coulomb", "mu": 0.0},
    "backlash": {"axial": 0.0002622766470281645, "contact": "bistop",
                 "penetration": 2.0713684001826906e-07},
    "screw": {"radius": 0.015524551946062394, "length": 0.5266412592948401,
              "youngs_modulus": 2038643594.5248885},
    "nut": {"outer_radius": 0.01956703725183938, "length": 0.016667962517095437,
            "youngs_modulus": 25014783045.935326, "position": 0.1816570865129556},
    "rotor": {"inertia": 1.325359504653421e-07}, "load": {"mass": 57.073849531348124},
    "loads": {"axial_force": 1.0252468931673009},
    "motor": {"type": "dc", "voltage": 15.739488098555027, "resistance": 0.29985478721100356,
              "torque_constant": 0.0148109384665493, "current_limit": 4.720429547288519,
              "friction_torque": 0.0072754054880412615},
    "gear": {"type": "ideal", "ratio": -25.849654397446148}}


def test_the_step_that_releases_the_limit_reports_its_own_armature():
    """Every Moreau-Jean row reports its step's armature (dc_motor.md,
    "Moreau-Jean"): the limiter's mode decided for the whole step on the
    quasi-static current at omega_theta, U_d = R i + k_e omega_theta, and the
    step's electrical work and copper loss h U_d i and h R i^2 of that pair."""
    result = ls.simulate(ls.Scene.from_dict(RELEASE), 0.0123)
    assert result.integrator == "moreau"
    motor = RELEASE["motor"]
    u, resistance, k, limit = (motor[key] for key in ("voltage", "resistance",
                                                      "torque_constant", "current_limit"))
    current, voltage = result["motor_current"], result["motor_voltage"]
    held = np.abs(voltage) < u * (1 - 1e-9)
    assert held[1] and not held[-1]  # the limit holds from the start and releases
    speed = reference.step_speed(result["omega_drive"], True)
    driver, expected = reference.limited_driver(u, speed, resistance, k, limit)
    np.testing.assert_allclose(voltage, driver, rtol=0, atol=1e-9)
    np.testing.assert_allclose(current, expected, rtol=0, atol=1e-9)
    h = np.diff(result.t)
    for name, rate in (("work_drive", voltage * current), ("copper_loss", resistance * current ** 2)):
        np.testing.assert_allclose(np.diff(result[name]), h * rate[1:], rtol=1e-9, atol=0,
                                   err_msg=name)
    assert_motor_checks_pass(result)
    assert result.checks["armature"]["applies"]  # (the run checks the relation itself)
