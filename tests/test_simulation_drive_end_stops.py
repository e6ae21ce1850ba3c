"""The penalty end stops of the load's travel (issue 19, item 3): the static
deflection F / k under a held force, the torque-limited clamp force of a slow
approach M / (r_m tan(alpha + rho')) (tests/helpers/end_stop_reference.py),
the stop's elastic energy and loss in the energy account, friction that never
does positive work, the scene's and the core's checks, TOML and the core spec."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers import end_stop_reference as reference
from helpers.result_invariants import check_result, failed
from helpers.scenes import thesis_scene

# Its checks read each run step by step: every step kept (simulate's default
# samples a long run's steps).
pytestmark = pytest.mark.usefixtures("every_step")

K = 1e7  # [N/m]
SINE = {"type": "sine", "amplitude": 0.05, "omega": 20.0}  # [N m], [rad/s]
BOUNCING = {"lower": -2e-4, "upper": 2e-4, "stiffness": 1e6, "damping": 500.0}


def critical_damping(scene, stiffness):
    """2 sqrt(k m_eff) of the rigid screw-driven drive: the load and the nut
    with the rotor's and the screw's inertia through the lead,
    m_eff = m + m_nut + (J_rotor + J_screw) (2 pi / lead)^2."""
    s = ls.Scene.from_dict(scene)
    derived = s.derived()
    lead = scene["thread"]["pitch"] * scene["thread"].get("starts", 1)
    mass = (scene["load"]["mass"] + derived["nut_mass"] +
            (scene["rotor"]["inertia"] + derived["screw_inertia"]) * (2 * math.pi / lead) ** 2)
    return 2.0 * math.sqrt(stiffness * mass)


@pytest.mark.parametrize("force, face", [(50.0, "upper"), (-80.0, "lower")])
def test_static_deflection_under_a_held_force(force, face):
    # A frictionless rigid drive: the axial force alone moves the load into
    # the stop, critically damped, and the stop holds it at d = F / k.
    position = 1e-4 if face == "upper" else -1e-4
    scene = thesis_scene(friction={"mu": 0.0}, loads={"drive_torque": 0.0, "axial_force": force},
                         end_stops={face: position, "stiffness": K})
    scene["end_stops"]["damping"] = critical_damping(scene, K)
    result = ls.simulate(ls.Scene.from_dict(scene), 1.0)
    deflection = reference.static_deflection(abs(force), K)
    assert abs(result["u_load"][-1] - position) == pytest.approx(deflection, rel=1e-6)
    assert result["stop_force"][-1] == pytest.approx(-force, rel=1e-6)
    assert [e.kind for e in result.events][0] == f"{face} end stop contact"


@pytest.mark.parametrize("mu, flank_angle", [(0.3, 0.0), (0.1, math.radians(30.0))])
def test_clamp_force_of_a_slow_approach_is_the_torque_limited_value(mu, flank_angle):
    # The rigid drive turned by M from 1 nm before the lower stop (a right-hand
    # screw turning +x moves the load along -x): the thread slips forward into
    # the stop, overdamped, until the stop's force balances M through the
    # thread, F = M / (r_m tan(alpha + rho')); there it sticks (self-locking).
    torque = 0.5
    scene = thesis_scene(thread={"flank_angle": flank_angle}, friction={"mu": mu},
                         loads={"drive_torque": torque, "axial_force": 0.0},
                         end_stops={"lower": -1e-9, "stiffness": 1e8})
    scene["end_stops"]["damping"] = 2.0 * critical_damping(scene, 1e8)
    result = ls.simulate(ls.Scene.from_dict(scene), 1.5)
    clamp = reference.clamp_force(torque, scene["thread"], mu)
    assert result["stop_force"][-1] == pytest.approx(clamp, rel=1e-6)
    assert result["u_load"][-1] == pytest.approx(-1e-9 - clamp / 1e8, rel=1e-6)
    assert result["stick"][-1] == 1.0


def test_a_fast_approach_clamps_harder_than_the_quasi_static_value():
    # 0.2 mm of run-up: the kinetic energy at the contact adds to the clamp,
    # and the self-locking thread keeps it.
    torque = 0.5
    scene = thesis_scene(loads={"drive_torque": torque, "axial_force": 0.0},
                         end_stops={"lower": -2e-4, "stiffness": 1e8, "damping": 1e4})
    result = ls.simulate(ls.Scene.from_dict(scene), 0.5)
    clamp = reference.clamp_force(torque, scene["thread"], 0.3)
    assert result["stop_force"][-1] > 2.0 * clamp
    assert result["stick"][-1] == 1.0


@pytest.mark.parametrize("name, scene", [
    # rigid, not self-locking (mu' < tan alpha): the stops push the load back
    ("rigid", thesis_scene(friction={"mu": 0.01}, loads={"drive_torque": SINE, "axial_force": 0.0},
                           end_stops=BOUNCING)),
    ("flexible_nut, exact play", thesis_scene(
        concept="flexible_nut", friction={"mu": 0.2},
        backlash={"axial": 1e-4, "contact": "exact", "restitution": 0.5},
        loads={"drive_torque": SINE, "axial_force": 0.0}, end_stops=BOUNCING)),
    ("flexible, bistop play", thesis_scene(
        concept="flexible", friction={"mu": 0.2}, backlash={"axial": 1e-4, "contact": "bistop"},
        loads={"drive_torque": SINE, "axial_force": 0.0}, end_stops=BOUNCING)),
])
def test_energy_account_closes_and_friction_never_does_positive_work(name, scene):
    t_eval = np.linspace(0.0, 1.0, 4001)
    options = {"rtol": 1e-10, "atol": 1e-12}
    result = ls.simulate(ls.Scene.from_dict(scene), 1.0, t_eval=t_eval, **options)
    kinds = [e.kind for e in result.events]
    assert any("end stop contact" in kind for kind in kinds), name
    scale = np.max(np.abs(result["work_drive"]))
    assert np.max(np.abs(result["energy_residual"])) <= 1e-7 * scale
    assert np.all(np.diff(result["friction_loss"]) >= -1e-12 * scale)
    assert np.all(np.diff(result["damping_loss"]) >= -1e-12 * scale)
    assert failed(check_result(result, ls.Scene.from_dict(scene).to_dict(),
                               {"t_end": 1.0, "t_eval": t_eval, **options})) == []


def test_the_stop_force_elastic_energy_and_loss_follow_the_law():
    # The rigid drive has no other spring: elastic is the stop's k d^2 / 2,
    # damping_loss the integral of F d' - k d d' (trapezoids of the output).
    scene = thesis_scene(friction={"mu": 0.01}, loads={"drive_torque": SINE, "axial_force": 0.0},
                         end_stops=BOUNCING)
    t_eval = np.linspace(0.0, 1.0, 20001)
    result = ls.simulate(ls.Scene.from_dict(scene), 1.0, t_eval=t_eval, rtol=1e-10, atol=1e-12)
    kinds = [e.kind for e in result.events]
    assert "lower end stop release" in kinds and "upper end stop contact" in kinds
    k, c = BOUNCING["stiffness"], BOUNCING["damping"]
    u, v = result["u_load"], result["v_load"]
    d = np.maximum(u - BOUNCING["upper"], BOUNCING["lower"] - u)
    rate = np.where(u > 0.0, v, -v)
    force = np.where(u > 0.0, -1.0, 1.0) * reference.pushing_force(d, rate, k, c)
    scale = np.max(np.abs(result["stop_force"]))
    np.testing.assert_allclose(result["stop_force"], force, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(result["elastic"], reference.elastic_energy(d, k),
                               rtol=0, atol=1e-12 * np.max(result["elastic"]))
    power = reference.loss_power(d, rate, k, c)
    loss = np.concatenate([[0.0], np.cumsum(np.diff(t_eval) * 0.5 * (power[1:] + power[:-1]))])
    np.testing.assert_allclose(result["damping_loss"], loss, rtol=0,
                               atol=1e-3 * result["damping_loss"][-1])
    assert np.all(power >= 0.0)


def test_stops_out_of_reach_change_nothing_on_the_rigid_drive():
    # A rigid drive with stops takes the general constrained solve (and BDF)
    # instead of the rigid drive's closed form: the same motion.
    t_eval = np.linspace(0.0, 1.0, 11)
    plain = ls.simulate(ls.Scene.from_dict(thesis_scene()), 1.0, t_eval=t_eval)
    far = ls.simulate(ls.Scene.from_dict(thesis_scene(end_stops={"lower": -0.05, "upper": 0.05,
                                                                  "stiffness": K})),
                      1.0, t_eval=t_eval)
    assert "stop_force" not in plain.channels
    np.testing.assert_array_equal(far["stop_force"], 0.0)
    scale = np.max(np.abs(plain["u_load"]))
    np.testing.assert_allclose(far["u_load"], plain["u_load"], rtol=0, atol=1e-6 * scale)
    assert [e.kind for e in far.events] == [e.kind for e in plain.events]


@pytest.mark.parametrize("stops, message", [
    ({"lower": 0.0, "stiffness": K}, "end_stops.lower = 0.0 is invalid: must be a finite number < 0"),
    ({"lower": "1 mm", "stiffness": K}, 'end_stops.lower = "1 mm" (= 0.001 m) is invalid'),
    ({"upper": 0.0, "stiffness": K}, "end_stops.upper = 0.0 is invalid: must be a finite number > 0"),
    ({"upper": -0.1, "stiffness": K}, "end_stops.upper = -0.1 is invalid"),
    ({"upper": 0.1, "stiffness": -1.0}, "end_stops.stiffness = -1.0 is invalid: must be a finite number > 0"),
    ({"upper": 0.1, "stiffness": K, "damping": -1.0}, "end_stops.damping = -1.0 is invalid"),
    ({"upper": 0.1, "stiffness": K, "contact": "rubber"}, "end_stops.contact = 'rubber' is invalid"),
    ({"upper": 0.1}, "end_stops.stiffness is missing"),
    ({"stiffness": K}, "give end_stops.lower [m] (< 0), end_stops.upper [m] (> 0) or both"),
    ({"upper": 0.1, "stiffness": K, "restitution": 0.5}, "end_stops.restitution = 0.5 is invalid"),
    ({"upper": 0.1, "contact": "exact", "stiffness": K}, "end_stops.stiffness = 10000000.0 is "
                                                         "invalid: must be absent"),
    ({"upper": 0.1, "stiffness": K, "gap": 1.0}, "end_stops.gap is not a known key"),
])
def test_invalid_end_stops_are_refused_naming_the_key(stops, message):
    with pytest.raises(ValueError, match=None) as raised:
        ls.Scene.from_dict(thesis_scene(end_stops=stops))
    assert message in str(raised.value)


def test_the_core_checks_the_stops_too():
    from leadscrew import _core

    parameters = ls.Scene.from_dict(thesis_scene()).model().parameters
    parameters.end_stops = "penalty"
    parameters.end_stop_stiffness = K
    parameters.end_stop_lower = 0.0
    with pytest.raises(ValueError, match="end_stops.lower = 0 m is invalid: must be < 0"):
        _core.DriveModel(parameters)
    parameters.end_stop_lower = -0.01
    parameters.end_stop_stiffness = 0.0
    with pytest.raises(ValueError, match="end_stops.stiffness = 0 N/m is invalid: must be > 0"):
        _core.DriveModel(parameters)
    parameters.end_stop_lower = -math.inf
    parameters.end_stop_stiffness = K
    with pytest.raises(ValueError, match="without end_stops.lower or end_stops.upper"):
        _core.DriveModel(parameters)
    with pytest.raises(ValueError, match="end_stops.contact"):
        parameters.end_stops = "rubber"


def test_moreau_jean_runs_the_stops():
    # (Moreau-Jean takes end stops since issue 19's stages:
    # tests/test_simulation_drive_moreau_stops.py; an equilibrium start with
    # stops: tests/test_simulation_drive_rigid_exact_stops.py.)
    scene = ls.Scene.from_dict(thesis_scene(end_stops={"upper": 0.1, "stiffness": K}))
    assert "stop_force" in ls.simulate(scene, 0.01, integrator="moreau", dt=1e-4).channels


def test_scene_round_trips_through_toml_and_the_core_spec(tmp_path):
    from leadscrew import _core

    scene = ls.Scene.from_dict(thesis_scene(end_stops={"upper": "2 mm", "stiffness": "1e7 N/m",
                                                       "damping": "300 N*s/m"}))
    path = tmp_path / "stops.toml"
    scene.to_toml(path)
    assert "[end_stops]" in path.read_text()
    assert ls.Scene.from_toml(path) == scene
    text = scene.to_core_toml()
    assert 'end_stops = "penalty"' in text
    parameters, options = _core.read_core_spec(text)
    original = scene.model().parameters
    assert parameters.end_stops == "penalty"
    for name in ("end_stop_lower", "end_stop_upper", "end_stop_stiffness", "end_stop_damping"):
        assert getattr(parameters, name) == getattr(original, name), name
    assert parameters.end_stop_lower == -math.inf and parameters.end_stop_upper == 2e-3
    assert _core.write_core_spec(parameters, **options) == text


def test_schema_documents_every_end_stop_field():
    text = ls.scene.describe_schema()
    for key, unit in (("lower", "m"), ("upper", "m"), ("contact", None), ("stiffness", "N/m"),
                      ("damping", "N*s/m"), ("restitution", None)):
        line = next(line for line in text.splitlines() if line.startswith(f"end_stops.{key}"))
        if unit:
            assert line.startswith(f"end_stops.{key} [{unit}]")
    assert ls.units.channel_unit("stop_force") == "N"


# --- exact stops (contact = "exact"): Newton impacts, a closed contact --------


def free_flight_scene(restitution, **changes):
    """The flexible nut (screw-driven: the load hangs on the nut's spring)
    frictionless, without loads, every body moving with the thread at 50
    rad/s: the load flies at a constant speed into the lower stop 0.1 mm away."""
    return thesis_scene(concept="flexible_nut", friction={"mu": 0.0},
                        loads={"drive_torque": 0.0, "axial_force": 0.0},
                        initial={"rotor_speed": 50.0},
                        end_stops={"lower": -1e-4, "upper": 1e-4, "contact": "exact",
                                   "restitution": restitution}, **changes)


@pytest.mark.parametrize("restitution", [1.0, 0.5, 0.2])
def test_exact_stop_rebound_is_restitution_times_the_approach_speed(restitution):
    scene = free_flight_scene(restitution)
    result = ls.simulate(ls.Scene.from_dict(scene), 0.02, rtol=1e-10, atol=1e-14)
    approach = result["v_load"][0]
    assert approach < 0.0  # a right-hand screw turning +x moves the load along -x
    impact = next(e for e in result.events if e.kind.startswith("lower end stop impact"))
    assert impact.time == pytest.approx(-1e-4 / approach, rel=1e-9)
    rows = np.flatnonzero(result.t == impact.time)
    before, after = result["v_load"][rows[0]], result["v_load"][rows[-1]]
    assert before == pytest.approx(approach, rel=1e-12)
    assert after == pytest.approx(-restitution * approach, rel=1e-12)
    assert result["u_load"][rows[-1]] == -1e-4
    loss = 0.5 * scene["load"]["mass"] * (1.0 - restitution ** 2) * approach ** 2
    assert result["impact_loss"][rows[-1]] == pytest.approx(loss, rel=1e-12, abs=1e-18)
    scale = np.max(result["kinetic"])  # (the nut's spring rings after the impact)
    assert np.max(np.abs(result["energy_residual"])) <= 1e-8 * scale


def test_exact_stop_closes_holds_the_load_and_opens_when_the_force_reverses():
    # Pressed into the lower stop by -40 N on a self-locking thread: the
    # plastic stop (e = 0) holds the load at its face, balancing the axial
    # force and the nut's spring, until the force turns at 0.1 s.
    force = {"type": "table", "times": [0.0, 0.1, 0.11, 0.2], "values": [-40.0, -40.0, 40.0, 40.0]}
    scene = thesis_scene(concept="flexible_nut", loads={"drive_torque": 0.0, "axial_force": force},
                         end_stops={"lower": -1e-6, "contact": "exact"})
    s = ls.Scene.from_dict(scene)
    result = ls.simulate(s, 0.2, rtol=1e-10, atol=1e-14)
    # (The impact stops the load, and the nut's damper jumps: the thread may slip.)
    closed = next(e.time for e in result.events
                  if e.kind.startswith("lower end stop impact, closed"))
    opens = next(e.time for e in result.events if e.kind.startswith("lower end stop opens"))
    assert 0.0 < closed < opens and 0.1 < opens < 0.11
    inside = (result.t > closed) & (result.t < opens)
    assert np.all(result["u_load"][inside] == -1e-6)
    assert np.all(result["v_load"][inside] == 0.0)
    # The stop balances the forces on the held load: the axial force and the
    # nut's spring-damper k (u_nut - u_load) + c (v_nut - v_load).
    spring = next(sp for sp in s.model().springs if sp["name"] == "nut axial")
    on_load = (result["axial_force"] + spring["stiffness"] * (result["u_nut"] - result["u_load"])
               + spring["damping"] * (result["v_nut"] - result["v_load"]))
    np.testing.assert_allclose(result["stop_force"][inside], -on_load[inside], rtol=0,
                               atol=1e-9 * 40.0)
    assert np.all(result["stop_force"][inside] > 0.0)  # it pushes, toward +u
    assert np.all(result["stop_force"][result.t > opens] == 0.0)
    scale = np.max(np.abs(result["work_axial"]))
    assert np.max(np.abs(result["energy_residual"])) <= 1e-6 * scale


@pytest.mark.parametrize("changes, message", [
    ({"backlash": {"axial": 1e-4, "contact": "exact"}, "friction": {"law": "lugre"}},
     "end_stops.contact = 'exact' is invalid with backlash.contact = 'exact' and "
     "friction.law = 'lugre' on concept = 'rigid'"),
    ({"concept": "flexible_nut", "drive": "nut",
      "backlash": {"axial": 1e-4, "contact": "exact"}, "friction": {"law": "arctan_velocity"}},
     "the load rides on the part that carries the flank"),
    ({"concept": "flexible_nut", "end_stops": {"stiffness": K}},
     "end_stops.stiffness = 10000000.0 is invalid: must be absent with end_stops.contact = 'exact'"),
    ({"concept": "flexible_nut", "end_stops": {"restitution": 1.5}},
     "end_stops.restitution = 1.5 is invalid"),
])
def test_exact_stops_are_refused_naming_the_keys(changes, message):
    # (Exact stops run on every concept, the rigid drive's in
    # test_simulation_drive_rigid_exact_stops.py; exact play is refused
    # with a smooth law where the load rides on the flank's part.)
    stops = {"lower": -1e-4, "contact": "exact", **changes.pop("end_stops", {})}
    with pytest.raises(ValueError) as raised:
        ls.Scene.from_dict(thesis_scene(end_stops=stops, **changes))
    assert message in str(raised.value)


def test_the_core_refuses_exact_stops_with_exact_play_and_a_smooth_law_on_a_rigid_drive():
    from leadscrew import _core

    parameters = ls.Scene.from_dict(
        thesis_scene(backlash={"axial": 1e-4, "contact": "exact"},
                     friction={"law": "lugre"})).model().parameters
    parameters.end_stops = "exact"
    parameters.end_stop_lower = -1e-3
    with pytest.raises(ValueError, match="two impacts at once"):
        _core.DriveModel(parameters)


@pytest.mark.parametrize("stops", [{"lower": -1e-6, "contact": "exact"},
                                   {"lower": -1e-6, "stiffness": 1e8, "damping": 1e4}])
def test_the_stepper_carries_the_stops_across_its_pieces(stops):
    # The axial force changed at every piece (each rebuilds the run): the
    # held load stays held, an exact stop closes once.
    from leadscrew import _core

    scene = ls.Scene.from_dict(thesis_scene(
        concept="flexible_nut", loads={"drive_torque": 0.0, "axial_force": -40.0},
        end_stops=stops))
    stepper = _core.DriveStepper(scene.model(), "", "", 1e-8, 1e-12, 1_000_000, 100_000, 0.0,
                                 0.0, 1e-6, 0)
    for k in range(1, 11):
        stepper.set_input("axial_force", -40.0 - k)
        stepper.advance(0.01 * k)
    assert "stop_force" in stepper.channel_names
    assert stepper.channel("stop_force") > 0.0
    contacts = [kind for _, kind in stepper.events if kind.startswith("lower end stop")]
    assert len(contacts) == 1, contacts
    if stops.get("contact") == "exact":
        assert stepper.channel("u_load") == -1e-6 and stepper.channel("v_load") == 0.0


def test_the_integrators_listed_with_end_stops_are_the_ones_that_run():
    # One list, the true one (issue 17 item 16): a review found "moreau" listed, then refused.
    # Moreau-Jean runs end stops with every law but eq. (3.15) (moreau.hpp;
    # the smooth ones implicit: moreau_smooth_friction.cpp).
    for friction, expected in [({"law": "coulomb", "mu": 0.3}, ["event_driven", "moreau"]),
                               ({"law": "arctan_velocity", "mu": 0.3, "k_v": 1e3}, True),
                               ({"law": "arctan_acceleration", "mu": 0.3, "k_v": 1e3}, None)]:
        scene = ls.Scene.from_dict(thesis_scene(concept="rigid", friction=friction,
                                                end_stops={"lower": -0.01, "stiffness": 1e7}))
        listed = ls._core.drive_integrators(scene.model().parameters)
        if isinstance(expected, list):
            assert listed == expected
        else:
            assert ("moreau" in listed) == (expected is True)
        for integrator in listed:
            options = ({} if integrator == "event_driven" else {"dt": 1e-5}
                       if integrator == "moreau" else {"rtol": 1e-6, "atol": 1e-9})
            ls.simulate(scene, 0.002, integrator=integrator, max_steps=200_000, **options)
    with pytest.raises(ValueError, match=r"integrator = \"cvode_bdf\" is invalid for "
                                         r"friction\.law = \"coulomb\" and end_stops: must be "
                                         r"one of \"event_driven\""):
        ls.simulate(ls.Scene.from_dict(thesis_scene(concept="rigid", end_stops={
            "lower": -0.01, "stiffness": 1e7})), 0.01, integrator="cvode_bdf")
