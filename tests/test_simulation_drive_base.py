"""Base excitation (loads.base_acceleration, loads.base_angular_acceleration):
the housing's vibration as the inertial loads -m a on the translating bodies
and -J alpha on the rotating ones, the coordinates relative to the housing.
A constant base acceleration on the rigid frictionless drive moves it as the
equivalent axial force -m a on the load does (and as the closed form of a
constant force on the reduced mass), the angular one as the equivalent drive
torque -J alpha; the energy account closes with the base's work, with
friction on, in both schemes and on every concept."""

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
