"""Base excitation (loads.base_acceleration, loads.base_angular_acceleration):
the housing's vibration as the inertial loads -m a on the translating bodies
and -J alpha on the rotating ones, the coordinates relative to the housing.
A constant base acceleration on the rigid frictionless drive moves it as the
equivalent axial force -m a on the load does (and as the closed form of a
constant force on the reduced mass), the angular one as the equivalent drive
torque -J alpha; the energy account closes with the base's work, with
friction on, in both schemes and on every concept; a sine vibration of the
flexible-nut drive moves it as an independent Lagrangian model does."""

import math
import warnings

import numpy as np
import pytest

import leadscrew as ls

RIGID = {"concept": "rigid", "thread": {"pitch": 1e-3, "mean_diameter": 20e-3},
         "friction": {"law": "coulomb", "mu": 0.0}, "load": {"mass": 2.0}}
SCHEMES = [{}, {"integrator": "moreau", "dt": 1e-5}]


def scene(loads, **changes):
    return ls.Scene.from_dict({**RIGID, **changes, "loads": loads})


@pytest.mark.parametrize("options", SCHEMES)
@pytest.mark.parametrize("drive", ["screw", "nut"])
def test_constant_axial_base_acceleration_is_the_equivalent_axial_force(options, drive):
    a = 3.0
    vibrated = scene({"base_acceleration": f"{a} m/s^2"}, drive=drive)
    derived = vibrated.derived()
    translating = derived["nut_mass"] if drive == "screw" else derived["screw_mass"]
    rotating = derived["screw_inertia"] if drive == "screw" else derived["nut_inertia"]
    m = 2.0 + translating  # every body on the load's coordinate
    equivalent = scene({"axial_force": -m * a}, drive=drive)
    t_end = 0.05
    r, ref = ls.simulate(vibrated, t_end, **options), ls.simulate(equivalent, t_end, **options)
    for channel in ("u_load", "v_load", "phi_drive", "omega_drive", "normal_force"):
        scale = np.abs(ref[channel]).max()
        assert np.allclose(r[channel], ref[channel], rtol=0, atol=1e-9 * scale), channel
    assert np.allclose(r["base_force"], -m * a, rtol=1e-15)
    assert np.allclose(r["base_work"], ref["work_axial"], rtol=0,
                       atol=1e-9 * abs(ref["work_axial"][-1]))
    # the closed form: a constant force on the reduced mass m + J / p^2
    p = 1e-3 / (2 * math.pi)
    inertia = vibrated.model().parameters.rotor_inertia + rotating
    expected = -0.5 * m * a / (m + inertia / p ** 2) * t_end ** 2
    assert r["u_load"][-1] == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("options", SCHEMES)
def test_constant_angular_base_acceleration_is_the_equivalent_drive_torque(options):
    alpha = 5.0
    vibrated = scene({"base_angular_acceleration": f"{alpha} rad/s^2"})
    inertia = vibrated.model().parameters.rotor_inertia + vibrated.derived()["screw_inertia"]
    equivalent = scene({"drive_torque": -inertia * alpha})
    r, ref = ls.simulate(vibrated, 0.05, **options), ls.simulate(equivalent, 0.05, **options)
    for channel in ("u_load", "phi_drive", "omega_drive", "normal_force"):
        scale = np.abs(ref[channel]).max()
        assert np.allclose(r[channel], ref[channel], rtol=0, atol=1e-9 * scale), channel
    assert np.allclose(r["base_torque"], -inertia * alpha, rtol=1e-15)
    assert np.allclose(r["base_work"], ref["work_drive"], rtol=0,
                       atol=1e-9 * abs(ref["work_drive"][-1]))


def _vibrated_holding(concept, contact):
    """A self-locking drive holding a load against a random axial vibration
    of its housing and a rotational one (flexible concepts: the nut's and
    the screw's own bodies feel them too)."""
    return ls.Scene.from_dict({
        "concept": concept, "thread": {"pitch": 1.5e-3, "mean_diameter": 7.25e-3},
        "friction": {"law": "coulomb", "mu": 0.15},
        "backlash": {"axial": 0.1e-3, "contact": contact},
        "load": {"mass": 5.0},
        "loads": {"axial_force": -50.0,
                  "base_acceleration": {"type": "random", "frequencies": [10.0, 200.0],
                                        "psd": [20.0, 5.0], "seed": 3, "duration": 1.0},
                  "base_angular_acceleration": {"type": "sine", "amplitude": "300 rad/s^2",
                                                "omega": "40 Hz"}},
    })


@pytest.mark.parametrize("concept, contact, options", [
    ("rigid", "exact", {}),
    ("rigid", "exact", {"integrator": "moreau", "dt": 2e-5}),
    ("flexible_nut", "exact", {}),
    ("flexible_nut", "exact", {"integrator": "moreau", "dt": 2e-5}),
    ("flexible", "bistop", {"integrator": "moreau", "dt": 1e-5}),
])
def test_energy_account_closes_with_the_base_work_and_friction(concept, contact, options):
    r = ls.simulate(_vibrated_holding(concept, contact), 0.1, **options)
    balance = r.checks["energy_balance"]
    assert balance["passed"]
    assert r["friction_loss"][-1] > 0.0
    # the base's work is what the account needs to close: without it the
    # residual would exceed the check's bound a hundredfold or more
    flow = np.abs(r["base_work"]).max()
    assert flow > 100.0 * balance["bound"]
    assert r.checks["friction_power"]["passed"]


def test_outputs_stay_relative_to_the_housing():
    # A rigid drive with the thread stuck (mu far above self-locking) moves
    # with its housing: relative to it, nothing moves, whatever the vibration.
    stuck = scene({"base_acceleration": {"type": "sine", "amplitude": "20 m/s^2",
                                         "omega": "30 Hz"}},
                  friction={"law": "coulomb", "mu": 0.8})
    r = ls.simulate(stuck, 0.1)
    assert np.all(r["stick"]) and np.abs(r["u_load"]).max() == 0.0
    assert np.abs(r["base_work"]).max() == 0.0


def test_invalid_base_excitations_are_refused_naming_the_key():
    with pytest.raises(ValueError, match=r'loads.base_acceleration = "3 N" is invalid: '
                                         r'"3 N" is not an acceleration \(m/s\^2\)'):
        scene({"base_acceleration": "3 N"})
    with pytest.raises(ValueError, match=r"loads.base_angular_acceleration = Sine.* is "
                                         r"invalid with a gear stage"):
        ls.simulate(scene({"base_angular_acceleration": ls.Sine("1 rad/s^2", "5 Hz")},
                          gear={"ratio": 5.0}), 0.01)
    worm = ls.scenes.load("seat_adjuster_worm").replace(loads={"base_acceleration": 2.0})
    with pytest.raises(ValueError, match=r"loads.base_acceleration = Constant\(2\)"):
        ls.simulate(worm, 0.01, integrator="event_driven")
    r = ls.simulate(worm, 0.01)  # Moreau-Jean, its default there
    assert r.checks["energy_balance"]["passed"] and "base_work" in r.to_frame()


def test_core_spec_round_trips_the_base_excitation():
    vibrated = scene({"base_acceleration": {"type": "sine", "amplitude": "4 m/s^2",
                                            "omega": "20 Hz"},
                      "base_angular_acceleration": 2.5})
    text = vibrated.to_core_toml()
    assert "[loads.base_acceleration]  # m/s^2" in text
    parameters, options = ls._core.read_core_spec(text)
    assert ls._core.write_core_spec(parameters, **options) == text
    t = np.linspace(0.0, 0.2, 21)
    assert np.array_equal(parameters.base_acceleration(t), 4.0 * np.sin(40 * math.pi * t))
    assert "base_acceleration" not in scene({}).to_core_toml()  # at rest: not written


def _flexible_nut_reference(scene_, accel, alpha, t_eval):
    """An independent model of the frictionless flexible-nut drive without
    play (docs/physics/drive_models.md): Lagrange's equations in (phi_rotor,
    phi_nut, u_load) with u_nut = p (phi_nut - phi_rotor) eliminated by the
    thread, the nut's axial spring to the load and torsion spring to the
    ground with their dampers, and the housing's inertial loads -m a, -J alpha
    on each body; solved by scipy's Radau."""
    from scipy.integrate import solve_ivp

    d = scene_.derived()
    over = scene_.to_dict()["overrides"]
    p = 1e-3 / (2 * math.pi)
    j_r = scene_.model().parameters.rotor_inertia + d["screw_inertia"]
    j_n, m_n, m_l = d["nut_inertia"], d["nut_mass"], 2.0
    k_a, k_t = d["nut_axial_stiffness"], d["nut_torsional_stiffness"]
    c_a, c_t = over["nut_axial_damping"], over["nut_torsional_damping"]
    # u_nut = G q, q = (phi_r, phi_n, u_l)
    g = np.array([-p, p, 0.0])
    mass = np.diag([j_r, j_n, m_l]) + m_n * np.outer(g, g)

    def rhs(t, y):
        q, v = y[:3], y[3:]
        stretch, rate = g @ q - q[2], g @ v - v[2]
        axial = k_a * stretch + c_a * rate  # on the nut, its opposite on the load
        force = -axial * g + np.array([0.0, 0.0, axial])
        force[1] -= k_t * q[1] + c_t * v[1]
        force -= accel(t) * (m_n * g + np.array([0.0, 0.0, m_l]))
        force -= alpha(t) * np.array([j_r, j_n, 0.0])
        return np.concatenate([v, np.linalg.solve(mass, force)])

    solution = solve_ivp(rhs, (0.0, t_eval[-1]), np.zeros(6), method="Radau", t_eval=t_eval,
                         rtol=1e-11, atol=1e-16, max_step=2e-5)
    return solution.y[2], g @ solution.y[:3]


@pytest.mark.parametrize("options", [{"rtol": 1e-10, "atol": 1e-14},
                                     {"integrator": "moreau", "dt": 2e-6}])
def test_sine_base_excitation_on_the_flexible_nut_drive_matches_an_independent_model(options):
    a0, wa, al0, wal = 20.0, 2 * math.pi * 300.0, 500.0, 2 * math.pi * 80.0
    flexible = scene({"base_acceleration": {"type": "sine", "amplitude": a0, "omega": wa},
                      "base_angular_acceleration": {"type": "sine", "amplitude": al0,
                                                    "omega": wal}},
                     concept="flexible_nut",
                     overrides={"nut_axial_damping": 50.0, "nut_torsional_damping": 2e-3})
    t = np.linspace(0.0, 0.02, 201)
    r = ls.simulate(flexible, 0.02, t_eval=t, **options)
    u_load, u_nut = _flexible_nut_reference(flexible, lambda s: a0 * math.sin(wa * s),
                                            lambda s: al0 * math.sin(wal * s), t)
    # (measured: 2.5e-8 and 3.2e-5; without the angular or the axial part the
    # reference moves the load 29 % or 88 % of its amplitude otherwise)
    tolerance = 1e-6 if "rtol" in options else 2e-4  # Moreau-Jean: first order in dt
    assert np.abs(u_load).max() > 1e-7
    assert np.allclose(r["u_load"], u_load, rtol=0, atol=tolerance * np.abs(u_load).max())
    assert np.allclose(r["u_nut"], u_nut, rtol=0, atol=tolerance * np.abs(u_nut).max())


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut"])
def test_the_stepper_carries_the_base_excitation_and_its_work(concept):
    # (the C API and the FMU advance a drive in pieces, its inputs held)
    from leadscrew import _core
    from leadscrew.simulation import _run_options

    vibrated = ls.scenes.load("default").replace(concept=concept, loads={
        "drive_torque": -0.03, "axial_force": -19.62,
        "base_acceleration": {"type": "random", "frequencies": [10.0, 300.0],
                              "psd": [5.0, 5.0], "seed": 2, "duration": 1.0}})
    times = np.arange(1, 101) * 1e-3
    reference = ls.simulate(vibrated, 0.1, t_eval=times, rtol=1e-8, atol=1e-10)
    stepper = _core.DriveStepper(vibrated.model(), **_run_options(rtol=1e-8, atol=1e-10))
    stepped = []
    for t in times:
        stepper.advance(t)
        stepped.append([stepper.channel("u_load"), stepper.channel("base_work")])
    stepped = np.array(stepped)
    for k, name in enumerate(["u_load", "base_work"]):
        scale = np.abs(reference[name]).max()
        assert np.allclose(stepped[:, k], reference[name], rtol=0, atol=1e-6 * scale), name
    stepper.set_input("drive_torque", 0.0)  # the model rebuilt, the account carried on
    stepper.advance(0.2)
    flow = abs(stepper.channel("work_drive")) + abs(stepper.channel("base_work"))
    assert abs(stepper.channel("energy_residual")) <= 1e-6 * flow
