"""The DC motor element (issue 19, item 1): its armature current a state of the
drive, against the closed forms of tests/helpers/dc_motor_reference.py on the
rigid drive (steady state, the electrical time constant, the stall current),
the driver's current limit, the energy account with the electrical terms, the
scene's checks and the exclusivity with the drive loads."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers import dc_motor_reference as reference
from helpers.nested_approx import nested_approx
from helpers.scenes import thesis_scene

R, KT = 2.0, 0.05  # [Ohm], [N m/A] (= k_e in SI)
L = 1e-3  # [H]: L / R = 0.5 ms
U = 3.0  # [V]
F = 10.0  # [N]: against the load's motion (a right-hand screw turning +x moves it along -x)
STEADY_T_END = 2.0  # [s]: 34 mechanical time constants J_eff R / (k_t k_e) = 58 ms


def motor_scene(voltage=U, axial_force=F, **motor):
    """The thesis drive (rigid, screw-driven) with a DC motor instead of the
    drive torque."""
    section = {"type": "dc", "voltage": voltage, "resistance": R, "inductance": L,
               "torque_constant": KT, **motor}
    d = thesis_scene(loads={"axial_force": axial_force}, motor=section)
    d["loads"].pop("drive_torque")
    return d


def rigid_reference(scene):
    """The helper's rigid drive with the scene's derived masses and inertias."""
    s = ls.Scene.from_dict(scene)
    return reference.rigid_drive(s.to_dict(), s.derived())


@pytest.mark.parametrize("inductance", [L, 0.0])
def test_steady_state_on_the_rigid_drive_matches_the_closed_form(inductance):
    scene = motor_scene(inductance=inductance)
    result = ls.simulate(ls.Scene.from_dict(scene), STEADY_T_END)
    current, omega, torque = reference.steady_state(rigid_reference(scene), F, U, R, KT, KT)
    assert omega > 0.0 and torque > 0.0
    # The motor raises the load against F: the load moves along -x.
    assert result["v_load"][-1] < 0.0
    assert result["motor_current"][-1] == pytest.approx(current, rel=1e-6)
    assert result["omega_drive"][-1] == pytest.approx(omega, rel=1e-6)
    assert result["drive_torque"][-1] == pytest.approx(torque, rel=1e-6)
    assert result["motor_voltage"][-1] == pytest.approx(U, rel=1e-12)
    assert result["stick"][-1] == 0.0


def test_stalled_rotor_current_rises_with_the_electrical_time_constant():
    # 1000 N against a self-locking thread: the motor's largest torque k_t U / R
    # = 0.075 N m is far below the raise torque (3 N m): the rotor stays stuck.
    scene = motor_scene(axial_force=1000.0)
    t_eval = np.linspace(0.0, 10 * L / R, 41)
    result = ls.simulate(ls.Scene.from_dict(scene), t_eval[-1], t_eval=t_eval)
    assert np.all(result["stick"] == 1.0)
    assert np.all(result["omega_drive"] == 0.0)
    expected = reference.stalled_current(result.t, U, R, L)
    np.testing.assert_allclose(result["motor_current"], expected, rtol=1e-6, atol=1e-9 * U / R)
    # At one time constant the current is 1 - 1/e of the stall current.
    tau = np.interp(U / R * (1 - math.exp(-1)), result["motor_current"], result.t)
    assert tau == pytest.approx(L / R, rel=1e-3)
    assert result["motor_current"][-1] == pytest.approx(U / R, rel=1e-4)


def test_stall_current_without_inductance_is_reached_at_once():
    scene = motor_scene(axial_force=1000.0, inductance=0.0)
    result = ls.simulate(ls.Scene.from_dict(scene), 1e-3)
    np.testing.assert_allclose(result["motor_current"], U / R, rtol=1e-15)
    assert "magnetic_energy" in result.channels
    np.testing.assert_array_equal(result["magnetic_energy"], 0.0)


@pytest.mark.parametrize("inductance", [L, 0.0])
def test_current_limit_holds_when_stalled(inductance):
    limit = 0.5  # [A] < U / R = 1.5 A
    scene = motor_scene(axial_force=1000.0, inductance=inductance, current_limit=limit)
    result = ls.simulate(ls.Scene.from_dict(scene), 10 * L / R)
    current = result["motor_current"]
    assert np.max(np.abs(current)) <= limit * (1 + 1e-12)
    assert current[-1] == pytest.approx(limit, rel=1e-12)
    # The driver lowers its voltage to R i_max at rest.
    assert result["motor_voltage"][-1] == pytest.approx(R * limit, rel=1e-12)
    if inductance > 0.0:
        assert any("current limit reached" in e.kind for e in result.events)


def test_current_limit_releases_as_the_drive_speeds_up():
    limit = 1.0  # [A]: above the steady 0.64 A, below the start's U / R = 1.5 A
    scene = motor_scene(current_limit=limit)
    result = ls.simulate(ls.Scene.from_dict(scene), STEADY_T_END)
    descriptions = [e.kind for e in result.events]
    assert any("current limit reached" in d for d in descriptions)
    assert any("current limit released" in d for d in descriptions)
    assert np.max(np.abs(result["motor_current"])) <= limit * (1 + 1e-12)
    current, omega, _ = reference.steady_state(rigid_reference(scene), F, U, R, KT, KT)
    assert result["motor_current"][-1] == pytest.approx(current, rel=1e-6)
    assert result["omega_drive"][-1] == pytest.approx(omega, rel=1e-6)


def energy_closes(result):
    """The energy account with the electrical terms: the residual within
    1e-7 of the electrical work, the work in equal to int U_d i dt and the
    copper loss to int R i^2 dt (trapezoids of the dense output)."""
    work = result["work_drive"]
    scale = np.max(np.abs(work))
    assert scale > 0.0
    assert np.max(np.abs(result["energy_residual"])) <= 1e-7 * scale
    t = result.t
    power = result["motor_voltage"] * result["motor_current"]
    electrical = np.concatenate([[0.0], np.cumsum(np.diff(t) * 0.5 * (power[1:] + power[:-1]))])
    np.testing.assert_allclose(work, electrical, rtol=1e-3, atol=1e-4 * scale)
    loss = R * result["motor_current"] ** 2
    copper = np.concatenate([[0.0], np.cumsum(np.diff(t) * 0.5 * (loss[1:] + loss[:-1]))])
    np.testing.assert_allclose(result["copper_loss"], copper, rtol=1e-3, atol=1e-4 * scale)
    np.testing.assert_allclose(result["magnetic_energy"],
                               0.5 * L * result["motor_current"] ** 2, rtol=1e-12)
    # Friction never does positive work.
    assert np.all(np.diff(result["friction_loss"]) >= -1e-12 * scale)


def test_energy_closes_with_the_electrical_terms_on_the_rigid_drive():
    scene = motor_scene(voltage={"type": "sine", "amplitude": U, "omega": 2 * math.pi,
                                 "offset": 0.5}, current_limit=1.0)
    t_eval = np.linspace(0.0, 1.0, 4001)
    result = ls.simulate(ls.Scene.from_dict(scene), 1.0, t_eval=t_eval)
    energy_closes(result)
    # The sine reverses the drive: slip both ways and stick between.
    assert np.any(result["omega_drive"] > 0.0) and np.any(result["omega_drive"] < 0.0)


def test_energy_closes_on_a_flexible_concept():
    scene = motor_scene(voltage={"type": "sine", "amplitude": U, "omega": 2 * math.pi})
    scene["concept"] = "flexible_nut"
    scene["backlash"] = {"axial": 1e-4, "contact": "exact"}
    t_eval = np.linspace(0.0, 0.5, 2001)
    result = ls.simulate(ls.Scene.from_dict(scene), 0.5, t_eval=t_eval)
    energy_closes(result)
    assert np.max(np.abs(result["omega_drive"])) > 1.0


def test_channels_only_with_a_motor():
    plain = ls.simulate(ls.Scene.from_dict(thesis_scene()), 0.01)
    for name in ("motor_current", "motor_voltage", "copper_loss", "magnetic_energy"):
        assert name not in plain.channels
    with_motor = ls.simulate(ls.Scene.from_dict(motor_scene()), 0.01)
    for name, unit in (("motor_current", "A"), ("motor_voltage", "V"), ("copper_loss", "J"),
                       ("magnetic_energy", "J")):
        assert name in with_motor.channels
        assert ls.units.channel_unit(name) == unit


def test_back_emf_constant_defaults_to_the_torque_constant_and_takes_units():
    scene = ls.Scene.from_dict(motor_scene(voltage="3000 mV", resistance="2 ohm",
                                           inductance="1 mH", torque_constant="50 mN*m/A",
                                           current_limit="1 A"))
    motor = scene["motor"]
    assert motor["voltage"] == pytest.approx(3.0)
    assert motor["inductance"] == pytest.approx(1e-3)
    assert motor["torque_constant"] == pytest.approx(0.05)
    assert "back_emf_constant" not in motor
    given = ls.Scene.from_dict(motor_scene(back_emf_constant="0.05 V*s/rad", current_limit=1.0))
    a = ls.simulate(scene, 0.05)
    b = ls.simulate(given, 0.05)
    np.testing.assert_array_equal(a["motor_current"], b["motor_current"])


@pytest.mark.parametrize("voltage, expected", [
    (ls.Constant("3 V"), 3.0),
    (ls.Sine("3 V", "5 Hz", offset="1 V"), {"type": "sine", "amplitude": 3.0,
                                             "omega": 10 * math.pi, "phase": 0.0,
                                             "offset": 1.0}),
    (ls.Table([0, 1], ["0 V", "3 V"]), {"type": "table", "times": [0.0, 1.0],
                                        "values": [0.0, 3.0]}),
])
def test_voltage_takes_loads_in_volts(voltage, expected):
    scene = ls.Scene.from_dict(motor_scene(voltage=voltage))
    given = scene["motor"]["voltage"]
    if isinstance(expected, float):
        given = given["value"] if isinstance(given, dict) else given
    assert given == nested_approx(expected)


@pytest.mark.parametrize("voltage, match", [
    ("12 N", r'^motor\.voltage = "12 N" is invalid: "12 N" is not a voltage \(V\)$'),
    (ls.Constant("12 N"), r"^motor\.voltage = Constant\('12\.0 N'\) is invalid: its values "
                          r"are a force \(N\), not a voltage \(V\)$"),
    (ls.Sine("1 N*m", 2.0), r"^motor\.voltage = Sine\(.*\) is invalid: its values are a torque"),
])
def test_voltage_refuses_a_load_of_another_unit(voltage, match):
    with pytest.raises(ValueError, match=match):
        ls.Scene.from_dict(motor_scene(voltage=voltage))


def test_units_as_data_sheets_write_them():
    """"2 Ohm" is an ohm (an alias in the registry)."""
    scene = ls.Scene.from_dict(motor_scene(resistance="2 Ohm"))
    assert scene["motor"]["resistance"] == 2.0


@pytest.mark.parametrize("key, value, message", [
    ("torque_constant", "0.05 Nm/A",
     'motor.torque_constant = "0.05 Nm/A" is invalid: "0.05 Nm/A" is not a torque constant '
     '(N*m/A) ("Nm" is number_meter to pint, not a newton metre: write "N*m")'),
    ("torque_constant", "50 mNm/A", '("mNm" is millinumber_meter to pint, not a newton metre: '
                                    'write "mN*m")'),
    ("friction_torque", "0.01 Nm", '("Nm" is number_meter to pint, not a newton metre'),
    ("voltage", "12 v", "units are case-sensitive: write \"V\" for volt"),
    ("voltage", "3000 mv", "units are case-sensitive: write \"mV\" for millivolt"),
    ("resistance", "2 OHM", "units are case-sensitive: write \"ohm\" for ohm"),
])
def test_units_users_type_by_mistake_are_explained(key, value, message):
    with pytest.raises(ValueError) as raised:
        ls.Scene.from_dict(motor_scene(**{key: value}))
    assert message in str(raised.value)
    assert str(raised.value).startswith(f'motor.{key} = "{value}" is invalid: ')


def test_scene_round_trips_through_toml(tmp_path):
    scene = ls.Scene.from_dict(motor_scene(current_limit=1.0))
    path = tmp_path / "motor.toml"
    scene.to_toml(path)
    assert ls.Scene.from_toml(path) == scene
    assert "[motor]" in path.read_text()
    core = tmp_path / "core.toml"
    scene.to_core_toml(core)
    assert "dc_motor = true" in core.read_text()


def test_schema_documents_every_motor_field():
    text = ls.scene.describe_schema()
    for key, unit in (("type", None), ("voltage", "V"), ("resistance", "ohm"),
                      ("inductance", "H"), ("torque_constant", "N*m/A"),
                      ("back_emf_constant", "V*s/rad"), ("current_limit", "A"),
                      ("friction_torque", "N*m")):
        line = next(line for line in text.splitlines() if line.startswith(f"motor.{key}"))
        if unit:
            assert f"[{unit}]" in line


@pytest.mark.parametrize("key, value, match", [
    ("resistance", 0.0, r"motor\.resistance = 0\.0 is invalid"),
    ("resistance", -1.0, r"motor\.resistance = -1\.0 is invalid"),
    ("inductance", -1e-3, r"motor\.inductance = -0\.001 is invalid"),
    ("torque_constant", 0.0, r"motor\.torque_constant = 0\.0 is invalid"),
    ("back_emf_constant", -0.05, r"motor\.back_emf_constant = -0\.05 is invalid"),
    ("current_limit", 0.0, r"motor\.current_limit = 0\.0 is invalid"),
    ("friction_torque", -0.01, r"motor\.friction_torque = -0\.01 is invalid"),
    ("type", "ac", r"motor\.type = 'ac' is invalid"),
    ("voltage", "3 N", r"motor\.voltage"),
    ("resistance", "2 V", r"motor\.resistance"),
    ("speed", 1.0, r"motor\.speed is not a known key"),
])
def test_invalid_motor_raises_naming_the_key(key, value, match):
    with pytest.raises(ValueError, match=match):
        ls.Scene.from_dict(motor_scene(**{key: value}))


@pytest.mark.parametrize("factor, refused", [(0.5, True), (2.0, False)])
def test_a_motor_faster_than_any_built_is_refused_naming_its_keys(factor, refused):
    """The motor's mechanical time constant J R / (k_t k_e) below 1 us, or its
    electrical L / R below 1 ns, is a unit's mistake (the fastest motors have
    about 1 ms and 1 us): refused naming the inputs, where the run would have
    ground to a solver failure naming none (review of issue 19: k_t = 1e6
    N m/A). At twice the bound the model builds."""
    inertia = ls.Scene.from_dict(motor_scene())["rotor"]["inertia"]
    k = np.sqrt(inertia * R / (factor * 1e-6))  # J R / k^2 = factor * 1e-6 s
    strong = ls.Scene.from_dict(motor_scene(torque_constant=k))
    fast = ls.Scene.from_dict(motor_scene(inductance=factor * 1e-9 * R))
    if not refused:
        strong.model(), fast.model()
        return
    with pytest.raises(ValueError, match=r"motor\.torque_constant = .*, motor\.resistance = 2 "
                                         r"and rotor\.inertia = .* are invalid together: .*"
                                         r"mechanical time constant .* must be at least 1e-06 s"):
        strong.model()
    with pytest.raises(ValueError, match=r"motor\.inductance = .* and motor\.resistance = 2 are invalid "
                                         r"together: .* electrical time "
                                         r"constant .* must be at least 1e-09 s"):
        ls.simulate(fast, 0.01)


@pytest.mark.parametrize("missing", ["type", "voltage", "resistance", "torque_constant"])
def test_missing_motor_field_raises(missing):
    scene = motor_scene()
    del scene["motor"][missing]
    with pytest.raises(ValueError, match=rf"motor\.{missing} is missing"):
        ls.Scene.from_dict(scene)


@pytest.mark.parametrize("load", ["drive_torque", "drive_speed"])
def test_motor_is_exclusive_with_the_drive_loads(load):
    scene = motor_scene()
    scene["loads"][load] = 1.0
    with pytest.raises(ValueError, match=rf"loads\.{load} = 1\.0 is invalid with motor\.type"):
        ls.Scene.from_dict(scene)
    with pytest.raises(ValueError, match=rf"loads\.{load} = 1\.0 is invalid with motor\.type"):
        ls.Scene.from_dict(motor_scene()).replace(loads={load: 1.0})


@pytest.mark.parametrize("inductance", [L, 0.0])
@pytest.mark.parametrize("limit", [None, 1.0])
def test_moreau_jean_reaches_the_steady_state_within_the_limit(inductance, limit):
    motor = {"inductance": inductance, **({"current_limit": limit} if limit else {})}
    scene = motor_scene(**motor)
    result = ls.simulate(ls.Scene.from_dict(scene), STEADY_T_END, integrator="moreau", dt=1e-4)
    current, omega, _ = reference.steady_state(rigid_reference(scene), F, U, R, KT, KT)
    assert result["motor_current"][-1] == pytest.approx(current, rel=1e-6)
    assert result["omega_drive"][-1] == pytest.approx(omega, rel=1e-6)
    if limit:
        assert np.max(np.abs(result["motor_current"])) <= limit * (1 + 1e-12)
        assert np.max(np.abs(result["motor_current"])) == pytest.approx(limit, rel=1e-12)
    # Moreau-Jean dissipates by construction: it creates at most 1e-3 of the work.
    assert np.max(-result["energy_residual"]) <= 1e-3 * result["work_drive"][-1]


def test_moreau_jean_stalled_current_follows_the_time_constant():
    scene = motor_scene(axial_force=1000.0)
    t_end = 10 * L / R
    result = ls.simulate(ls.Scene.from_dict(scene), t_end, integrator="moreau", dt=1e-6,
                         theta=0.5)
    # The trapezoidal rule on i' = (U - R i) / L: second order in dt / (L / R) = 2e-3.
    np.testing.assert_allclose(result["motor_current"],
                               reference.stalled_current(result.t, U, R, L), rtol=1e-6,
                               atol=1e-6 * U / R)
    # At theta = 1/2 the magnetic energy's change is exact: the account closes.
    assert np.max(np.abs(result["energy_residual"])) <= 1e-9 * result["work_drive"][-1]


def test_removing_the_motor_restores_the_torque_drive():
    scene = ls.Scene.from_dict(motor_scene())
    plain = scene.replace(motor=None)
    assert "motor" not in plain
    assert "motor_current" not in ls.simulate(plain, 0.01).channels


def test_core_spec_carries_the_motor():
    from leadscrew import _core

    scene = ls.Scene.from_dict(motor_scene(voltage={"type": "sine", "amplitude": U,
                                                    "omega": 2 * math.pi, "offset": 0.5},
                                           current_limit=1.0))
    text = scene.to_core_toml()
    parameters, options = _core.read_core_spec(text)
    assert parameters.dc_motor
    original = scene.model().parameters
    for name in ("motor_resistance", "motor_inductance", "motor_torque_constant",
                 "motor_back_emf_constant", "motor_current_limit"):
        assert getattr(parameters, name) == getattr(original, name), name
    assert parameters.motor_voltage.describe() == original.motor_voltage.describe()
    assert _core.write_core_spec(parameters, **options) == text


@pytest.mark.parametrize("friction, options", [
    ({"law": "lugre", "mu": 0.3, "sigma0": 1e5}, {"rtol": 1e-9, "atol": 1e-13}),
    ({"law": "arctan_velocity", "mu": 0.3, "k_v": 1e4}, {"integrator": "cvode_bdf"}),
    ({"law": "arctan_velocity", "mu": 0.3, "k_v": 1e4}, {"integrator": "event_driven"}),
])
def test_energy_closes_with_other_laws_and_ode_methods(friction, options):
    """The motor's states follow LuGre's bristle states in y; an ODE method
    (a set-valued law's regularization) carries them as the event-driven
    scheme does."""
    scene = motor_scene(voltage={"type": "sine", "amplitude": U, "omega": 2 * math.pi},
                        current_limit=1.0)
    scene["friction"] = friction
    t_eval = np.linspace(0.0, 0.5, 2001)
    result = ls.simulate(ls.Scene.from_dict(scene), 0.5, t_eval=t_eval, **options)
    energy_closes(result)
    assert np.max(np.abs(result["motor_current"])) <= 1.0 * (1 + 1e-12)


def test_the_core_refuses_a_drive_torque_beside_the_motor():
    from leadscrew import _core

    parameters = ls.Scene.from_dict(motor_scene()).model().parameters
    parameters.drive_torque = 0.01
    with pytest.raises(ValueError, match=r"loads\.drive_torque = .* is invalid with motor\.type"):
        _core.DriveModel(parameters)
    parameters.drive_torque = 0.0
    parameters.speed_controlled = True
    with pytest.raises(ValueError, match=r"loads\.drive_speed is invalid with motor\.type"):
        _core.DriveModel(parameters)


@pytest.mark.parametrize("integrator", ["event_driven", "moreau"])
def test_the_driver_never_puts_out_more_than_its_voltage(integrator):
    """A flexible nut with play rattling under a reversing voltage, the
    current limited: where the current is held at the limit the driver's
    voltage lies below U(t) on the current's side (it holds the current
    with less than U), elsewhere it is U(t); the back-EMF stays within the
    supply, so the limit holds; the account closes."""
    amplitude, omega, limit = 2 * U, 4 * math.pi, 1.0
    scene = motor_scene(voltage={"type": "sine", "amplitude": amplitude, "omega": omega},
                        current_limit=limit)
    scene["concept"] = "flexible_nut"
    scene["backlash"] = {"axial": 1e-4, "contact": "exact", "restitution": 0.5}
    t_eval = np.linspace(0.0, 0.5, 2001)
    options = {"dt": 1e-5} if integrator == "moreau" else {}
    result = ls.simulate(ls.Scene.from_dict(scene), 0.5, t_eval=t_eval, integrator=integrator,
                         **options)
    current, voltage = result["motor_current"], result["motor_voltage"]
    supply = amplitude * np.sin(omega * result.t)
    assert np.max(np.abs(current)) <= limit * (1 + 1e-12)
    held = np.abs(current) >= limit * (1 - 1e-12)
    assert held.any() and not held.all()
    scale = 1e-9 * amplitude
    side = np.sign(current[held])
    assert np.all(side * voltage[held] <= side * supply[held] + scale)
    if integrator == "event_driven":
        np.testing.assert_allclose(voltage[~held], supply[~held], rtol=0, atol=scale)
        energy_closes(result)
        assert result["impact_loss"][-1] > 0.0  # (Moreau-Jean's impacts are its dissipation)


def test_a_callable_voltage_runs_as_its_constant():
    constant = ls.simulate(ls.Scene.from_dict(motor_scene()), 0.05)
    called = ls.simulate(ls.Scene.from_dict(motor_scene(voltage=lambda t: U)), 0.05)
    assert called["motor_current"][-1] == pytest.approx(constant["motor_current"][-1],
                                                        rel=1e-9)
    with pytest.raises(ValueError, match=r"motor\.voltage = .* returned .3 V., not a number \[V\]"):
        ls.simulate(ls.Scene.from_dict(motor_scene(voltage=lambda t: "3 V")), 0.05)


def test_a_derived_problem_beside_a_motor_names_its_input():
    """A derived quantity gone wrong (the nut's mass of a denormal nut.length)
    in a scene with a DC motor: the inputs are blamed by setting each back to
    its reference, and the motor's required fields have none (the fuzz run
    found a KeyError 'motor.resistance' there). The message names nut.length."""
    scene = motor_scene()
    scene.update(concept="flexible_nut")
    scene["nut"] = {**scene.get("nut", {}), "length": 5e-324}
    with pytest.raises(ValueError, match=r"nut\.length = 5e-324"):
        ls.simulate(ls.Scene.from_dict(scene), 0.01)


KE = 0.6 * KT  # [V s/rad]: a back-EMF constant apart from k_t (issue 31, item 12)


@pytest.mark.parametrize("integrator, friction, options", [
    ("event_driven", {"law": "coulomb", "mu": 0.3}, {}),
    ("moreau", {"law": "coulomb", "mu": 0.3}, {"dt": 1e-4}),
    # (an ODE method needs a smooth law: a frictionless flank, whose steady
    # torque the reference takes from mu = 0 too)
    ("cvode_bdf", {"law": "arctan_velocity", "mu": 0.0, "k_v": 1e4}, {}),
])
def test_steady_state_with_a_back_emf_constant_apart_from_the_torque_constant(
        integrator, friction, options):
    """With k_e = k_t almost everywhere, a motor whose back-EMF used k_t (or
    whose torque used k_e) passed. The steady speed of the closed form,
    omega = (U - R T / k_t) / k_e (dc_motor.md, "Closed forms"), is 57.68
    rad/s on the thesis drive (T = 0.0317 N m); with k_t omega as the
    back-EMF it would be (U - R T / k_t) / k_t = 0.6 of it, 34.61 rad/s,
    on every integrator."""
    scene = motor_scene(back_emf_constant=KE)
    scene["friction"] = friction
    result = ls.simulate(ls.Scene.from_dict(scene), STEADY_T_END, integrator=integrator,
                         **options)
    current, omega, torque = reference.steady_state(rigid_reference(scene), F, U, R, KT, KE)
    assert omega > 0.0 and torque > 0.0
    assert result["motor_current"][-1] == pytest.approx(current, rel=1e-6)
    assert result["omega_drive"][-1] == pytest.approx(omega, rel=1e-6)
    assert result["drive_torque"][-1] == pytest.approx(torque, rel=1e-6)
