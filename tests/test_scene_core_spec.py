"""The core spec (model/core_spec.hpp): Scene.to_core_toml, its reader and
``leadscrew scene resolve``."""

import math

import pytest

import leadscrew as ls
from leadscrew import _core, cli
from leadscrew.simulation import _run_options


def scalar_fields(parameters):
    names = [name for name in dir(parameters) if not name.startswith("_")]
    return {name: getattr(parameters, name) for name in names
            if isinstance(getattr(parameters, name), (int, float, str, bool))}


@pytest.mark.parametrize("name", ls.scenes.available())
def test_every_shipped_scene_round_trips(name):
    scene = ls.scenes.load(name)
    text = scene.to_core_toml()
    parameters, options = _core.read_core_spec(text)
    original = scene.model().parameters
    assert scalar_fields(parameters) == scalar_fields(original)
    assert parameters.friction_values == original.friction_values
    for load in ("drive_torque", "drive_speed", "axial_force"):
        assert getattr(parameters, load).describe() == getattr(original, load).describe()
    # simulate's options, or those the scene stores (position_holding: its
    # [simulation] rtol 1e-6, atol 1e-8)
    assert options == _run_options(**(scene["simulation"] if "simulation" in scene else {}))
    # One writer: what is read is written back the same, digit for digit.
    assert _core.write_core_spec(parameters, **options) == text
    # And it is the same drive.
    assert _core.DriveModel(parameters).mass.tolist() == scene.model().mass.tolist()


def test_a_table_load_and_options_round_trip():
    scene = ls.scenes.load("default").replace(
        loads={"axial_force": ls.Table([0.0, 0.1, 0.3], [-1.0, -20.0, 1.0 / 3.0])})
    text = scene.to_core_toml(rtol=1e-7, integrator="event_driven", max_order=4)
    parameters, options = _core.read_core_spec(text)
    assert parameters.axial_force(0.2) == scene.model().parameters.axial_force(0.2)
    assert options["rtol"] == 1e-7 and options["max_order"] == 4
    assert "values = [-1.0, -20.0, 0.3333333333333333]" in text


def test_what_a_spec_cannot_hold_is_refused():
    scene = ls.scenes.load("default").replace(loads={"drive_torque": lambda t: 0.01 * t})
    with pytest.raises(ValueError, match="loads.drive_torque .* callable"):
        scene.to_core_toml()
    with pytest.raises(ValueError, match="rtool"):
        ls.scenes.load("default").to_core_toml(rtool=1e-6)


@pytest.mark.parametrize("change,message", [
    (("version = 1", "version = 2"), "version must be 1"),
    (("[thread]\n", "[thread]\nlead = 1.0\n"), "thread.lead is an unknown key"),
    (("pitch = 0.002", 'pitch = "2 mm"'), "thread.pitch is invalid: must be a number"),
    (('type = "sine"', 'type = "ramp"'), "loads.drive_torque.type"),
    (("omega = ", "frequency = "), "loads.drive_torque.frequency is an unknown key"),
    (('law = "coulomb"', 'law = "dry"'), "friction.law"),
    (("max_steps = 1000000", "max_steps = 1.5"), "options.max_steps is invalid"),
])
def test_a_bad_spec_names_the_key(change, message):
    text = ls.scenes.load("default").to_core_toml()
    assert change[0] in text
    with pytest.raises(ValueError, match=message):
        _core.read_core_spec(text.replace(*change, 1))


def test_the_values_are_checked_by_the_model():
    text = ls.scenes.load("default").to_core_toml().replace("load_mass = 2.0", "load_mass = nan")
    parameters, _ = _core.read_core_spec(text)
    assert math.isnan(parameters.load_mass)
    with pytest.raises(ValueError, match="load.mass = nan is invalid"):
        _core.DriveModel(parameters)


def test_cli_scene_resolve(tmp_path, capsys):
    out = tmp_path / "core.toml"
    assert cli.main(["scene", "resolve", "default", "-o", str(out)]) == 0
    assert out.read_text(encoding="utf-8") == ls.scenes.load("default").to_core_toml()
    assert cli.main(["scene", "resolve", "thesis_table_5_1"]) == 0
    assert capsys.readouterr().out.endswith(ls.scenes.load("thesis_table_5_1").to_core_toml())
    assert cli.main(["scene", "resolve", "no_such_scene"]) == 2
