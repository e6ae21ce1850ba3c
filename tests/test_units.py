"""leadscrew.units.channel_unit: the unit of every channel any model writes,
and Result's units (its frame's attrs, r["t"])."""

import itertools

import numpy as np
import pytest

import leadscrew as ls
import leadscrew.scenes as shipped
from helpers.scenes import thesis_scene

# Every channel layout of the drive: each concept and drive, with and without
# play (the play adds gap and play; the flexible parts their coordinates).
LAYOUTS = [dict(concept=concept, drive=drive, backlash=backlash)
           for concept, drive, backlash in itertools.product(
               ("rigid", "flexible_nut", "flexible"), ("screw", "nut"),
               (None, {"axial": 1e-4, "contact": "exact"}))]


def drive_result(layout):
    return ls.simulate(ls.Scene.from_dict(thesis_scene(**layout)), 1e-3)


def block_result():
    return ls.simulate(ls.FrictionBlock(1.0, 0.3, force=ls.Sine(6.0, 4.0)), 0.01)


@pytest.mark.parametrize("layout", LAYOUTS,
                         ids=[f"{d['concept']}-{d['drive']}-{'play' if d['backlash'] else 'no_play'}"
                              for d in LAYOUTS])
def test_every_drive_channel_has_its_unit(layout):
    r = drive_result(layout)
    units = r.units()
    assert list(units) == ["t"] + r.channels
    assert units == {name: ls.units.channel_unit(name) for name in units}
    frame = r.to_frame()
    assert frame.attrs["units"] == units and list(frame.columns) == list(units)


@pytest.mark.parametrize("layout", LAYOUTS[:2] + LAYOUTS[-2:],
                         ids=["rigid-screw-no_play", "rigid-screw-play", "flexible-nut-no_play",
                              "flexible-nut-play"])
def test_the_core_declares_every_drive_channel_but_the_coordinates(layout):
    declared = ls._core.drive_channel_units()
    r = drive_result(layout)
    undeclared = [name for name in r.channels if name not in declared]
    assert undeclared == [name for name in r.channels
                          if name.partition("_")[0] in ("u", "v", "phi", "omega")
                          and name not in ("u_load", "v_load", "phi_drive", "omega_drive")]


def test_channel_unit_reads_the_core_and_keeps_only_the_rest():
    """The core's units are channel_unit's; the module's own table holds only
    channels the core does not declare (the time, the block's own)."""
    declared = ls._core.drive_channel_units()
    assert {"motor_current": "A", "motor_voltage": "V", "stop_force": "N",
            "gear_loss": "J", "bristle_deflection": "m"}.items() <= declared.items()
    assert {name: ls.units.channel_unit(name) for name in declared} == declared
    own = {name for names in ls.units._CHANNELS_BY_UNIT.values() for name in names}
    assert own and not own & set(declared)


def test_every_block_channel_has_its_unit():
    r = block_result()
    assert r.units() == {
        "t": "s", "u": "m", "v": "m/s", "acceleration": "m/s^2", "friction_force": "N",
        "normal_force": "N", "force": "N", "stick": "", "work_force": "J",
        "friction_loss": "J", "kinetic": "J", "energy_residual": "J", "spring_force": "N",
        "elastic": "J"}
    lugre = ls.simulate(ls.FrictionBlock(1.0, 0.3, force=1.0), 0.01, friction="lugre")
    assert lugre.units()["bristle_deflection"] == "m"


@pytest.mark.parametrize("name, unit", [
    ("t", "s"), ("u_load", "m"), ("v_load", "m/s"), ("phi_drive", "rad"),
    ("omega_drive", "rad/s"), ("u_nut", "m"), ("omega_screw", "rad/s"), ("phi_nut", "rad"),
    ("drive_torque", "N*m"), ("axial_force", "N"), ("normal_force", "N"),
    ("friction_force", "N"), ("slip_velocity", "m/s"), ("stick", ""), ("gap", "m"),
    ("play", "m"), ("work_drive", "J"), ("impact_loss", "J"), ("energy_residual", "J"),
])
def test_channel_units_by_name(name, unit):
    assert ls.units.channel_unit(name) == unit


@pytest.mark.parametrize("name", ["x", "u_", "u_gearbox", "omega", "phi", "torque", "U_load",
                                  "work", "stick_", ""])
def test_an_unknown_channel_has_no_unit(name):
    with pytest.raises(KeyError, match=f"channel {name!r} has no unit"):
        ls.units.channel_unit(name)


def test_a_result_frame_with_an_unknown_channel_fails():
    """A channel a new model writes without a unit here is an error, not an
    empty unit."""
    r = block_result()
    r._channels = r.channels[:-1] + ["new_channel"]
    with pytest.raises(KeyError, match="'new_channel' has no unit"):
        r.to_frame()


@pytest.mark.parametrize("make", [block_result, lambda: drive_result({})])
def test_t_is_read_like_a_channel(make):
    r = make()
    assert "t" in r and "t" not in r.channels
    t = r["t"]
    assert t is r.t and t[0] == 0.0 and len(t) > 2
    np.testing.assert_array_equal(r.to_frame()["t"].to_numpy(), t)
    fresh = make()
    np.testing.assert_array_equal(fresh["t"], t)  # before any other conversion
    with pytest.raises(KeyError, match=r"no channel 'w'; channels are \['t', "):
        fresh["w"]


BASE = ["u_load", "v_load", "phi_drive", "omega_drive", "drive_torque", "axial_force",
        "normal_force", "friction_force", "slip_velocity", "stick"]
ACCOUNT = ["work_drive", "work_axial", "friction_loss", "damping_loss", "contact_loss",
           "impact_loss"]


@pytest.mark.parametrize("name, channels", [
    # a DC motor, penalty end stops, a flexible screw and nut with play
    ("seat_adjuster", BASE + ["gap", "play", "motor_current", "motor_voltage", "stop_force",
                              "u_nut", "v_nut", "phi_nut", "omega_nut", "u_screw", "v_screw",
                              "phi_screw", "omega_screw"] + ACCOUNT
     + ["copper_loss", "kinetic", "elastic", "magnetic_energy", "energy_residual"]),
    # a DC motor, penalty end stops and the train's friction stages on the rigid drive
    ("seat_adjuster_worm", BASE + ["motor_current", "motor_voltage", "stop_force"] + ACCOUNT
     + ["copper_loss", "motor_friction_loss", "gear_loss", "kinetic", "elastic",
        "magnetic_energy", "energy_residual"]),
])
def test_the_elements_channels_follow_their_declarations(name, channels):
    """The elements' declared channels in the row: values after the base's and
    the play's, losses after impact_loss, stored energies after elastic, in the
    registry's order (cpp/src/model/drive/element_registry.cpp)."""
    r = ls.simulate(shipped.load(name), 1e-3)
    assert r.channels == channels
    units = r.units()
    assert [units[c] for c in ("motor_current", "motor_voltage", "stop_force",
                               "copper_loss", "magnetic_energy")] == ["A", "V", "N", "J", "J"]
