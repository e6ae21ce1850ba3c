"""A spring on the load (scene section ``load_spring``; an element added as one
source file and one registry line, cpp/src/model/elements/load_spring.cpp):
the free oscillation of a frictionless rigid drive and the static deflection
of a self-locking one against their closed forms
(tests/helpers/load_spring_reference.py), its force channel, its energy in
the account, the scene's and the core's checks, TOML and the core spec."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers import load_spring_reference as reference
from helpers.result_invariants import check_result, failed
from helpers.scenes import thesis_scene

# Its checks read each run step by step: every step kept (simulate's default
# samples a long run's steps).
pytestmark = pytest.mark.usefixtures("every_step")

K, P = 2e4, 30.0  # [N/m], [N]
LEAD = 1e-3  # the thesis thread's [m]


def free_scene(**spring):
    """The rigid thesis drive without friction or loads, the spring's preload
    pushing the load from rest."""
    return thesis_scene(friction={"mu": 0.0}, loads={"drive_torque": 0.0, "axial_force": 0.0},
                        load_spring={"stiffness": K, "preload": P, **spring})


def rigid_effective_mass(scene):
    mass = ls.Scene.from_dict(scene).model().mass  # [phi_rotor, u_load]
    return reference.effective_mass(mass[1], mass[0], LEAD)


@pytest.mark.parametrize("damping", [0.0, 20.0])
def test_free_oscillation_of_a_frictionless_rigid_drive(damping):
    # omega^2 = k / (m + J (2 pi / lead)^2) about u* = -P / k.
    scene = free_scene(damping=damping)
    mass = rigid_effective_mass(scene)
    period = 2.0 * math.pi * math.sqrt(mass / K)
    t_eval = np.linspace(0.0, 2.0 * period, 401)
    options = {"rtol": 1e-12, "atol": 1e-14, "t_eval": t_eval}
    result = ls.simulate(ls.Scene.from_dict(scene), 2.0 * period, **options)
    u, v = reference.free_oscillation(result.t, K, P, damping, mass)
    amplitude = P / K
    # (the integrator's error over two periods at rtol = 1e-12: 8e-10 seen)
    np.testing.assert_allclose(result["u_load"], u, rtol=0, atol=1e-8 * amplitude)
    np.testing.assert_allclose(result["v_load"], v, rtol=0,
                               atol=1e-8 * amplitude * math.sqrt(K / mass))
    # Its channel: the force on the load, -(P + k u) - c u'.
    np.testing.assert_allclose(result["load_spring_force"],
                               -(P + K * result["u_load"]) - damping * result["v_load"],
                               rtol=1e-12, atol=1e-12 * P)
    # Its energy: (P + k u)^2 / (2 k) in elastic, c u'^2 in the damping loss.
    np.testing.assert_allclose(result["elastic"], (P + K * result["u_load"]) ** 2 / (2 * K),
                               rtol=1e-12, atol=1e-15)
    # What the spring gives up at the end is its damper's loss (1.6e-9 seen).
    stored = P ** 2 / (2 * K)
    assert result["damping_loss"][-1] == pytest.approx(
        stored - result["elastic"][-1] - result["kinetic"][-1], rel=0, abs=5e-9 * stored)
    if damping == 0.0:
        assert result["damping_loss"][-1] == 0.0
    else:
        assert result["damping_loss"][-1] > 0.01 * stored
    assert np.max(np.abs(result["energy_residual"])) <= 5e-9 * stored
    assert failed(check_result(result, ls.Scene.from_dict(scene).to_dict(),
                               {"t_end": 2.0 * period, **options})) == []


@pytest.mark.parametrize("state", ["relaxed", "equilibrium"])
def test_static_deflection_under_a_self_locking_thread(state):
    # The flexible nut, screw-driven, mu = 0.3 (self-locking): the thread
    # stays stuck, the nut does not move, and the load comes to rest on its
    # spring and the nut's axial spring in parallel, u* = -P / (k + k_nut).
    k, preload = 2e5, 40.0
    scene = thesis_scene(concept="flexible_nut", loads={"drive_torque": 0.0, "axial_force": 0.0},
                         load_spring={"stiffness": k, "preload": preload, "damping": 200.0},
                         initial={"state": state})
    s = ls.Scene.from_dict(scene)
    nut = next(spring["stiffness"] for spring in s.model().springs
               if spring["name"] == "nut axial")
    expected = reference.static_deflection(preload, k, nut)
    options = {"rtol": 1e-10, "atol": 1e-14}
    result = ls.simulate(s, 0.1, **options)
    assert result["u_load"][-1] == pytest.approx(expected, rel=1e-9)
    if state == "equilibrium":
        assert result["u_load"][0] == pytest.approx(expected, rel=1e-12)
    assert np.all(result["stick"][1:] == 1.0)
    assert np.max(np.abs(result["u_nut"])) <= 1e-9 * abs(expected)  # (round-off: 1e-11 seen)
    assert result["load_spring_force"][-1] == pytest.approx(-(preload + k * expected), rel=1e-9)
    assert failed(check_result(result, s.to_dict(), {"t_end": 0.1, **options})) == []


@pytest.mark.parametrize("integrator, options", [
    ("event_driven", {}),
    ("moreau", {"dt": 1e-4}),
])
def test_the_energy_account_closes_on_a_driven_run(integrator, options):
    # The thesis's load case with friction and the spring on the load: the
    # result checks (the simulator's own and the independent ones) pass.
    scene = thesis_scene(load_spring={"stiffness": 5e3, "preload": 5.0, "damping": 2.0})
    result = ls.simulate(ls.Scene.from_dict(scene), 0.5, integrator=integrator, **options)
    assert "load_spring_force" in result.channels
    if integrator == "event_driven":
        scale = np.max(np.abs(result["work_drive"])) + np.max(np.abs(result["work_axial"]))
        assert np.max(np.abs(result["energy_residual"])) <= 1e-7 * scale
    assert failed(check_result(result, ls.Scene.from_dict(scene).to_dict(),
                               {"t_end": 0.5, "integrator": integrator, **options})) == []


@pytest.mark.parametrize("spring, changes, message", [
    ({"preload": 1.0}, {}, "load_spring.stiffness is missing"),
    ({"stiffness": -1.0}, {}, "load_spring.stiffness = -1.0 is invalid: must be a finite number > 0"),
    ({"stiffness": K, "damping": -1.0}, {}, "load_spring.damping = -1.0 is invalid"),
    ({"stiffness": K, "length": 1.0}, {}, "load_spring.length is not a known key"),
    ({"stiffness": "20 N/mm"}, {}, None),
    ({"stiffness": K}, {"gear": {"type": "lossy", "ratio": 2.0, "efficiency": 0.8}},
     "load_spring is invalid with gear.type = 'lossy'"),
])
def test_the_scene_checks_the_spring(spring, changes, message):
    scene = thesis_scene(load_spring=spring, **changes)
    if message is None:
        assert ls.Scene.from_dict(scene)["load_spring"]["stiffness"] == pytest.approx(2e4)
        return
    with pytest.raises(ValueError) as raised:
        ls.Scene.from_dict(scene)
    assert message in str(raised.value)


def test_the_core_checks_the_spring_too():
    from leadscrew import _core

    parameters = ls.Scene.from_dict(thesis_scene()).model().parameters
    assert parameters.load_spring is False
    parameters.load_spring = True
    with pytest.raises(ValueError, match="load_spring.stiffness is missing"):
        _core.DriveModel(parameters)
    parameters.load_spring_stiffness = -5.0
    with pytest.raises(ValueError, match="load_spring.stiffness = -5 N/m is invalid: must be > 0"):
        _core.DriveModel(parameters)
    # Given as 0 (the value its absence stands for) it is out of range, as
    # the Scene says, not missing.
    parameters.load_spring_stiffness = 0.0
    with pytest.raises(ValueError, match="load_spring.stiffness = 0 N/m is invalid: must be > 0"):
        _core.DriveModel(parameters)
    parameters.load_spring_stiffness = K
    parameters.gear = "lossy"
    parameters.gear_efficiency = 0.8
    with pytest.raises(ValueError, match='load_spring is invalid with gear.type = "lossy"'):
        _core.DriveModel(parameters)


def test_the_core_takes_the_section_as_the_scene_gives_it():
    # DriveParameters.sections: the scene's section as is, by name; its
    # attributes read the same values.
    from leadscrew import _core

    parameters = ls.Scene.from_dict(free_scene(damping=3.0)).model().parameters
    assert parameters.sections == {"load_spring": {"stiffness": K, "preload": P, "damping": 3.0}}
    assert (parameters.load_spring, parameters.load_spring_damping) == (True, 3.0)
    with pytest.raises(ValueError, match="load_spring.stiffness = 'stiff' is invalid: must be a "
                                         "number"):
        parameters.sections = {"load_spring": {"stiffness": "stiff"}}
    with pytest.raises(ValueError, match="load_spring.length is not a known key"):
        parameters.sections = {"load_spring": {"length": 1.0}}
    with pytest.raises(ValueError, match='section "springs" is invalid: must be one of '
                                         "end_stops, load_spring"):
        parameters.sections = {"springs": {}}
    parameters.sections = {}
    assert parameters.load_spring is False
    assert _core.DriveModel(parameters).coordinate_names == ["phi_rotor", "u_load"]


def test_scene_round_trips_through_toml_and_the_core_spec(tmp_path):
    from leadscrew import _core

    scene = ls.Scene.from_dict(free_scene(damping="3 N*s/m"))
    path = tmp_path / "spring.toml"
    scene.to_toml(path)
    assert "[load_spring]" in path.read_text()
    assert ls.Scene.from_toml(path) == scene
    text = scene.to_core_toml()
    assert "load_spring = true" in text and "load_spring_stiffness = 20000.0" in text
    parameters, options = _core.read_core_spec(text)
    assert parameters.load_spring is True
    assert (parameters.load_spring_stiffness, parameters.load_spring_preload,
            parameters.load_spring_damping) == (K, P, 3.0)
    assert _core.write_core_spec(parameters, **options) == text


def test_a_batch_varies_the_spring():
    # The batch's overrides take the section's numbers by attribute: at a
    # quarter period u = -P / k (1 - cos(pi / 2)) = -P / k.
    from leadscrew.studies._batch import DriveBatch

    scene = ls.Scene.from_dict(free_scene())
    mass = rigid_effective_mass(free_scene())
    for k in (1e4, 4e4):
        t = 0.5 * math.pi * math.sqrt(mass / k)
        samples, errors, _ = DriveBatch(scene, ["load_spring_stiffness"], ["u_load"], t, [t],
                                        rtol=1e-10, atol=1e-14).run([[k]])
        assert errors == [None]
        assert samples[0][0][0] == pytest.approx(-P / k, rel=1e-7)


def test_schema_documents_every_field():
    text = ls.scene.describe_schema()
    for key, unit in (("stiffness", "N/m"), ("preload", "N"), ("damping", "N*s/m")):
        line = next(line for line in text.splitlines() if line.startswith(f"load_spring.{key}"))
        assert line.startswith(f"load_spring.{key} [{unit}]")
    assert "load_spring.stiffness [N/m] (required; a finite number > 0)" in text
    assert ls.units.channel_unit("load_spring_force") == "N"
