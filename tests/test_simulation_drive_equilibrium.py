"""A drive started at rest in static equilibrium under its loads at t = 0
(``initial.state = "equilibrium"``): the state against the closed forms of
tests/helpers/static_equilibrium.py, no static equilibrium where the loads
drive the thread (NoEquilibriumError), the energy account starting there,
and a drive under constant loads that then stays at rest."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers import static_equilibrium as closed
from helpers.scenes import thesis_scene

PITCH, DIAMETER = 1e-3, 20e-3
# Stiffness overrides: constant screw stiffness (eq. 4.24's follows the nut).
SPRINGS = {"nut_axial": 3.0e8, "nut_torsional": 2.0e3, "screw_axial": 5.0e8,
           "screw_torsional": 4.0e3}


def scene(concept="flexible_nut", torque=5e-3, force=-40.0, hand="right", **changes):
    overrides = {"nut_axial_stiffness": SPRINGS["nut_axial"],
                 "nut_torsional_stiffness": SPRINGS["nut_torsional"]}
    if concept == "flexible":
        overrides.update(screw_axial_stiffness=SPRINGS["screw_axial"],
                         screw_torsional_stiffness=SPRINGS["screw_torsional"])
    return ls.Scene.from_dict(thesis_scene(
        concept=concept, thread={"hand": hand}, overrides=overrides,
        loads={"drive_torque": torque, "axial_force": force},
        initial={"state": "equilibrium"}, **changes))


def springs_of(concept):
    names = ("nut_axial", "nut_torsional") + (
        ("screw_axial", "screw_torsional") if concept == "flexible" else ())
    return {name: SPRINGS[name] for name in names}


@pytest.mark.parametrize("torque, force", [(0.0, 0.0), (5e-3, -40.0), (-2e-3, 15.0)])
def test_rigid_without_play_nothing_changes(torque, force):
    start = scene("rigid", torque, force).initial_state()
    assert start["q"] == {"phi_rotor": 0.0, "u_load": 0.0}
    assert start["v"] == {"phi_rotor": 0.0, "u_load": 0.0}
    # The thread carries the loads: |(N, T)| is the loads' in-plane force.
    magnitude = math.hypot(start["normal_force"], start["friction_force"])
    assert magnitude == pytest.approx(closed.thread_force(torque, force, DIAMETER), rel=1e-12,
                                      abs=1e-12)


def test_rigid_under_an_axial_force_alone_splits_it_by_the_lead_angle():
    start = scene("rigid", 0.0, -40.0).initial_state()
    alpha = ls.Thread(PITCH, DIAMETER).lead_angle
    assert abs(start["normal_force"]) == pytest.approx(40.0 * math.cos(alpha), rel=1e-12)
    assert abs(start["friction_force"]) == pytest.approx(40.0 * math.sin(alpha), rel=1e-12)


@pytest.mark.parametrize("concept", ["flexible_nut", "flexible"])
@pytest.mark.parametrize("hand", ["right", "left"])
@pytest.mark.parametrize("torque, force", [(5e-3, -40.0), (-3e-3, 25.0), (0.0, -10.0)])
def test_flexible_spring_deflections_are_load_over_stiffness(concept, hand, torque, force):
    s = scene(concept, torque, force, hand)
    start = s.initial_state()
    h = 1 if hand == "right" else -1
    expected = closed.screw_driven(torque, force, PITCH, h, springs_of(concept))
    assert set(start["q"]) == set(expected)
    scale = max(abs(value) for value in expected.values())
    for name, value in expected.items():
        assert start["q"][name] == pytest.approx(value, rel=1e-9, abs=1e-12 * scale), name
    assert all(value == 0.0 for value in start["v"].values())
    assert start["iterations"] >= 1
    assert math.hypot(start["normal_force"], start["friction_force"]) == pytest.approx(
        closed.thread_force(torque, force, DIAMETER), rel=1e-9)


@pytest.mark.parametrize("force, flank", [(-40.0, 0.5e-4), (30.0, -0.5e-4)])
def test_exact_play_puts_the_nut_on_the_loaded_flank(force, flank):
    s = scene("flexible_nut", 2e-3, force, backlash={"axial": 1e-4, "contact": "exact"})
    start = s.initial_state()
    assert start["play"] == pytest.approx(flank, rel=1e-12)
    assert abs(start["play"]) >= 0.5e-4  # closed: on the flank, not a hair inside
    expected = closed.screw_driven(2e-3, force, PITCH, 1, springs_of("flexible_nut"), flank)
    for name, value in expected.items():
        assert start["q"][name] == pytest.approx(value, rel=1e-9, abs=1e-15), name
    rigid = scene("rigid", 2e-3, force, backlash={"axial": 1e-4, "contact": "exact"})
    # The rigid drive's load moves by half the play along the force.
    assert rigid.initial_state()["q"]["u_load"] == pytest.approx(-flank, rel=1e-12)


def test_a_penalty_flank_is_penetrated_as_far_as_its_force_takes():
    s = scene("flexible_nut", 2e-3, -40.0,
              backlash={"axial": 1e-4, "contact": "bistop", "stiffness": 1e9, "exponent": 1.5})
    start = s.initial_state()
    alpha = ls.Thread(PITCH, DIAMETER).lead_angle
    penetration = (abs(start["normal_force"]) * math.cos(alpha) / 1e9) ** (1 / 1.5)
    assert start["play"] == pytest.approx(0.5e-4 + penetration, rel=1e-9)
    assert penetration > 1e-7
    assert math.hypot(start["normal_force"], start["friction_force"]) == pytest.approx(
        closed.thread_force(2e-3, -40.0, DIAMETER), rel=1e-9)


@pytest.mark.parametrize("concept", ["rigid", "flexible"])
def test_an_equilibrium_exists_iff_the_torque_lies_in_the_holding_band(concept):
    """The stuck thread's friction force lies in the cone exactly where the
    torque lies inside the power-screw holding band of the axial force
    (static_holding_band); outside it the loads drive the thread."""
    from leadscrew.studies import static_holding_band

    force = -40.0
    low, high = static_holding_band(scene(concept), force)
    for torque in (0.98 * low, 0.5 * low, 0.0, 0.5 * high, 0.98 * high):
        scene(concept, torque, force).initial_state()  # holds
    for torque in (1.02 * low, 1.02 * high, 1.0):
        with pytest.raises(ls.NoEquilibriumError, match=r"initial.state = \"equilibrium\" is "
                           r"invalid for the loads at t = 0 .*friction cone"):
            scene(concept, torque, force).initial_state()
    assert issubclass(ls.NoEquilibriumError, ValueError)
    # A torque without an axial force drives the load.
    with pytest.raises(ls.NoEquilibriumError, match="no static equilibrium exists"):
        ls.simulate(scene(concept, 1e-3, 0.0), 0.01)


def test_the_start_is_checked_where_the_scene_is_made():
    for changes, match in [
            ({"loads": {"drive_torque": None, "drive_speed": 1.0}}, "loads.drive_speed"),
            ({"initial": {"rotor_speed": 1.0}}, "initial.rotor_speed = 1.0 is invalid with "
                                                "initial.state = 'equilibrium'"),
            ({"initial": {"play_position": 1e-5}, "backlash": {"axial": 1e-4}},
             "initial.play_position = 1e-05 is invalid with initial.state")]:
        with pytest.raises(ValueError, match=match):
            scene().replace(**changes)
    with pytest.raises(ValueError, match="initial.state = 'resting' is invalid: must be one "
                                         "of 'relaxed', 'equilibrium'"):
        scene().replace(initial={"state": "resting"})
    relaxed = scene().replace(initial={"state": "relaxed"}).initial_state()
    assert all(value == 0.0 for value in relaxed["q"].values()) and relaxed["iterations"] == 0
    assert relaxed["normal_force"] == 0.0 and relaxed["friction_force"] == 0.0
    assert "state" in ls.scene.describe_schema() and "equilibrium" in ls.scene.describe_schema()


def test_the_state_survives_a_toml_round_trip(tmp_path):
    path = tmp_path / "drive.toml"
    scene().to_toml(path)
    assert ls.Scene.from_toml(path)["initial"]["state"] == "equilibrium"


@pytest.mark.parametrize("concept, backlash", [
    ("flexible_nut", None), ("flexible", None),
    ("flexible_nut", {"axial": 1e-4, "contact": "exact"}),
    ("flexible", {"axial": 1e-4, "contact": "exact"})])
def test_under_constant_loads_the_drive_stays_at_rest(concept, backlash):
    """Started in its equilibrium, nothing moves: the velocities stay at the
    integration's noise, the positions where they began; the elastic energy
    at t = 0 is stored energy (the closed form's), the residual starts at 0
    and stays within the integration error. Started relaxed, the same drive
    rings."""
    changes = {"backlash": backlash} if backlash else {}
    s = scene(concept, 5e-3, -40.0, **changes)
    times = np.linspace(0.0, 0.2, 201)
    result = ls.simulate(s, 0.2, t_eval=times)
    flank = 0.5e-4 if backlash else 0.0
    expected = closed.screw_driven(5e-3, -40.0, PITCH, 1, springs_of(concept), flank)
    assert result["u_load"][0] == pytest.approx(expected["u_load"], rel=1e-9)
    energy = closed.elastic_energy(5e-3, -40.0, springs_of(concept))
    assert result["elastic"][0] == pytest.approx(energy, rel=1e-9)
    assert result["energy_residual"][0] == 0.0
    # At most the load's work over the absolute tolerance (atol 1e-10 m): the
    # closed flank's drift within the integration error (1e-13 m).
    assert np.max(np.abs(result["energy_residual"])) <= 40.0 * 1e-10
    assert np.max(np.abs(result["v_load"])) <= 1e-9
    assert np.ptp(result["u_load"]) <= 1e-12
    assert np.ptp(result["elastic"]) <= 1e-9 * energy
    assert not any(event.kind.endswith("->open") for event in result.events)
    relaxed = ls.simulate(s.replace(initial={"state": "relaxed"}), 0.2, t_eval=times)
    assert np.max(np.abs(relaxed["v_load"])) > 1e3 * max(np.max(np.abs(result["v_load"])), 1e-12)


def test_moreau_starts_from_the_equilibrium_too():
    s = scene("flexible_nut", 5e-3, -40.0, backlash={"axial": 1e-4, "contact": "exact"})
    result = ls.simulate(s, 0.05, integrator="moreau", dt=1e-5)
    energy = closed.elastic_energy(5e-3, -40.0, springs_of("flexible_nut"))
    assert result["elastic"][0] == pytest.approx(energy, rel=1e-9)
    assert result["energy_residual"][0] == 0.0
    assert np.max(np.abs(result["v_load"])) <= 1e-9


def test_a_static_coefficient_holds_up_to_its_own_cone():
    """Coulomb with mu_static > mu: at rest the thread holds up to the
    static cone, so a torque beyond the kinetic band but inside the static
    one has an equilibrium."""
    from leadscrew.studies import static_holding_band

    high = static_holding_band(scene("rigid"), -40.0)[1]
    static_high = static_holding_band(
        scene("rigid", friction={"law": "coulomb", "mu": 0.35}), -40.0)[1]
    torque = 0.5 * (high + static_high)
    with pytest.raises(ls.NoEquilibriumError, match="mu_static"):
        scene("rigid", torque, -40.0).initial_state()
    start = scene("rigid", torque, -40.0,
                  friction={"law": "coulomb", "mu": 0.3, "mu_static": 0.35}).initial_state()
    assert abs(start["friction_force"]) > ls.Thread(PITCH, DIAMETER).effective_mu(0.3) * abs(
        start["normal_force"])


@pytest.mark.parametrize("friction", [{"law": "arctan_velocity", "mu": 0.3, "k_v": 1e4},
                                      {"law": "lugre", "mu": 0.3}])
def test_a_law_without_friction_at_rest_starts_there_and_barely_moves(friction):
    """A regularized law carries no friction at rest (LuGre's bristles start
    relaxed): the drive starts from the same state and slips from it, at
    micrometres per second, with the energy account closed from t = 0."""
    s = scene("flexible_nut", 5e-3, -40.0, friction=friction)
    coulomb = scene("flexible_nut", 5e-3, -40.0).initial_state()
    assert s.initial_state()["q"] == coulomb["q"]
    result = ls.simulate(s, 0.05, t_eval=np.linspace(0.0, 0.05, 51))
    assert result["energy_residual"][0] == 0.0
    assert result["elastic"][0] == pytest.approx(
        closed.elastic_energy(5e-3, -40.0, springs_of("flexible_nut")), rel=1e-9)
    assert 0.0 < np.max(np.abs(result["v_load"])) < 1e-5
