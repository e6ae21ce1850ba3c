"""The ideal gear stage (issue 19, item 2; docs/physics/gear.md) between the
rotor and the driven part, against the closed forms of
tests/helpers/gear_reference.py: the geared rigid drive against the exact
reference of the drive whose rotor is reflected through the stage (inertia
n^2 J, torque n T), every concept and Moreau-Jean against the reflected
scene, the DC motor's and the speed-controlled rotor's steady states, the
train's efficiency, self-locking, the energy account, the drive without a
stage unchanged, and the scene's checks."""

import math

import numpy as np
import pytest

import leadscrew as ls
from leadscrew import _core
from helpers import dc_motor_reference
from helpers import gear_reference as reference
from helpers import rigid_drive_reference as rigid
from helpers.scenes import thesis_scene

T_EVAL = np.linspace(0.0, 2.0, 201)


def geared_rigid_scene(ratio, **changes):
    """The reference's thesis drive (rotor 1e-6 kg m^2, nut mid-screw) behind
    an ideal stage of ratio n."""
    return thesis_scene(rotor={"inertia": 1e-6}, nut={"position": 0.25},
                        gear={"type": "ideal", "ratio": ratio}, **changes)


@pytest.mark.parametrize("ratio", [3.0, -3.0, 1.5])
def test_rigid_geared_drive_meets_the_reflected_closed_form(ratio):
    """The geared rigid drive (its RigidSolver path) against the exact
    piecewise closed form of the drive without a stage whose rotor has the
    inertia n^2 J and the torque n M(t): the events, the load's motion, and
    the rotor's angle, speed and torque (the channels stay the rotor's)."""
    torque, force = rigid.thesis_loads()
    drive = reference.reflected_drive(rigid.thesis_drive(), ratio)
    ref = rigid.simulate(drive, reference.reflected_torque(torque, ratio), force, 2.0)
    result = ls.simulate(ls.Scene.from_dict(geared_rigid_scene(ratio)), 2.0,
                         integrator="event_driven", rtol=1e-6, atol=1e-10, t_eval=T_EVAL)
    assert len(result.events) == len(ref.events) >= 5
    assert max(abs(a.time - b.time) for a, b in zip(result.events, ref.events)) <= 1e-9
    u_ref = ref.u_load(result.t)
    assert np.max(np.abs(result["u_load"] - u_ref)) <= 1e-9 * np.max(np.abs(u_ref))
    omega = ratio * ref.omega(result.t)
    assert np.max(np.abs(result["omega_drive"] - omega)) <= 1e-9 * np.max(np.abs(omega))
    phi = ratio * ref.phi(result.t)
    assert np.max(np.abs(result["phi_drive"] - phi)) <= 1e-9 * np.max(np.abs(phi))
    np.testing.assert_allclose(result["drive_torque"], torque(result.t), rtol=1e-12,
                               atol=1e-15)


def run_with_reflected(scene, ratio, t_end, **options):
    """The runs of the geared scene and of its reflected one (no stage)."""
    return tuple(ls.simulate(ls.Scene.from_dict(d), t_end, **options)
                 for d in (scene, reference.reflected_scene(scene, ratio)))


def assert_reflected(geared, plain, ratio, bound, same=(), torque=True):
    """The geared run against the reflected one, within ``bound`` of each
    channel's range: the load's motion and the channels in ``same`` alike,
    the rotor's speed n times, its torque 1/n times the reflected ones."""
    pairs = [(geared["u_load"], plain["u_load"]),
             (geared["omega_drive"], ratio * plain["omega_drive"])]
    if torque:
        pairs.append((ratio * geared["drive_torque"], plain["drive_torque"]))
    pairs += [(geared[name], plain[name]) for name in same]
    for ours, theirs in pairs:
        assert np.max(np.abs(ours - theirs)) <= bound * np.max(np.abs(theirs))


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut", "flexible"])
def test_every_concept_equals_the_reflected_drive_to_round_off(concept):
    """Moreau-Jean (fixed steps, the same decisions) on each concept with play
    and a reversing stage: the geared scene and the reflected one move the load
    alike to round-off; the rotor turns n times the driven part, and its torque
    is 1/n of the reflected one."""
    ratio = -3.0
    scene = thesis_scene(concept=concept, backlash={"axial": 1e-5},
                         gear={"ratio": ratio})
    geared, plain = run_with_reflected(scene, ratio, 0.2, integrator="moreau", dt=1e-5)
    np.testing.assert_allclose(ratio * geared["drive_torque"], plain["drive_torque"],
                               rtol=1e-12)
    assert_reflected(geared, plain, ratio, 1e-12,
                     same=("work_drive", "friction_loss", "kinetic"))


@pytest.mark.parametrize("concept, backlash, bound", [
    ("rigid", {"axial": 1e-5}, 1e-12),
    ("flexible_nut", None, 1e-6),
])
def test_event_driven_geared_drive_equals_the_reflected_drive(concept, backlash, bound):
    """The event-driven scheme's general path (ConstrainedSolver, and on the
    rigid drive with play the load roots planned from its coefficients per
    unit rotor torque): the same events, the load and the rotor alike, to
    round-off on the rigid drive (the same steps); the flexible nut's BDF
    steps, which round-off can make differ, agree to its global error at
    rtol 1e-8."""
    ratio = -3.0
    scene = thesis_scene(concept=concept, backlash=backlash, gear={"ratio": ratio})
    geared, plain = run_with_reflected(scene, ratio, 0.5, t_eval=np.linspace(0.0, 0.5, 51))
    assert [e.kind for e in geared.events] == [e.kind for e in plain.events]
    assert len(geared.events) >= 3
    assert max(abs(a.time - b.time) for a, b in zip(geared.events, plain.events)) <= bound
    assert_reflected(geared, plain, ratio, bound, torque=False)


R, KT, L, U, F = 2.0, 0.05, 1e-3, 3.0, 10.0  # [Ohm], [N m/A], [H], [V], [N]
DC_MOTOR = {"type": "dc", "voltage": U, "resistance": R, "inductance": L, "torque_constant": KT}


@pytest.mark.parametrize("drive, ratio", [("speed", -3.0), ("dc", 3.0)])
def test_moreau_speed_and_dc_motor_behind_a_stage_equal_the_reflected_drive(drive, ratio):
    """Moreau-Jean on the flexible nut with play behind a stage: a prescribed
    rotor speed omega(t) (the driven part at omega / n; a reversing stage) and
    a DC motor with a current limit (its constants reflected, n k_t and n k_e:
    positive, as the reflected scene's motor section needs) move the load as
    the reflected scene to round-off; the rotor's torque is 1/n of the
    reflected one, the motor's current the same."""
    if drive == "speed":
        loads = {"drive_speed": {"type": "sine", "amplitude": 20.0, "omega": 10.0},
                 "axial_force": F}
        extra = {}
    else:
        loads, extra = {"axial_force": F}, {"motor": {**DC_MOTOR, "current_limit": 0.2}}
    scene = thesis_scene(concept="flexible_nut", backlash={"axial": 1e-5}, loads=loads,
                         gear={"ratio": ratio}, **extra)
    scene["loads"].pop("drive_torque")
    geared, plain = run_with_reflected(scene, ratio, 0.1, integrator="moreau", dt=1e-5)
    assert_reflected(geared, plain, ratio, 1e-12,
                     same=("motor_current",) if drive == "dc" else ())


@pytest.mark.parametrize("ratio", [4.0, -4.0])
def test_dc_motor_through_the_gear_meets_the_closed_form(ratio):
    """i = T_d / (n k_t), omega_rotor = (U - R i) / k_e = n omega_driven with
    T_d the bare drive's steady torque on the driven part (raising for n > 0,
    the driven part turning backwards and lowering for n < 0)."""
    scene = thesis_scene(loads={"axial_force": F}, gear={"ratio": ratio}, motor=DC_MOTOR)
    scene["loads"].pop("drive_torque")
    s = ls.Scene.from_dict(scene)
    result = ls.simulate(s, 2.0)
    drive = dc_motor_reference.rigid_drive(s.to_dict(), s.derived())
    current, omega, torque = reference.steady_state(drive, ratio, F, U, R, KT, KT)
    assert omega > 0.0
    assert result["motor_current"][-1] == pytest.approx(current, rel=1e-6)
    assert result["omega_drive"][-1] == pytest.approx(omega, rel=1e-6)
    assert result["drive_torque"][-1] == pytest.approx(torque, rel=1e-6)
    assert result["motor_voltage"][-1] == pytest.approx(U, rel=1e-12)
    # The load moves with the driven part: v = -h p omega_rotor / n.
    lead = s.thread.lead
    assert result["v_load"][-1] == pytest.approx(-lead / (2 * math.pi) * omega / ratio, rel=1e-6)
    if ratio > 0:
        # The train's efficiency F v / (T omega_rotor) is the thread's.
        efficiency = -F * result["v_load"][-1] / (result["drive_torque"][-1] * omega)
        assert efficiency == pytest.approx(ls.efficiency(s.thread, 0.3), rel=1e-6)


def test_speed_controlled_rotor_through_the_gear():
    """A prescribed rotor speed omega turns the driven part at omega / n; at
    the steady speed the rotor's torque is the raise torque / n."""
    ratio, speed = 5.0, 20.0
    scene = thesis_scene(loads={"drive_speed": speed, "axial_force": F}, gear={"ratio": ratio})
    scene["loads"].pop("drive_torque")
    s = ls.Scene.from_dict(scene)
    result = ls.simulate(s, 0.05)
    np.testing.assert_array_equal(result["omega_drive"], speed)
    expected = ls.raise_torque(s.thread, 0.3, F) / ratio
    assert result["drive_torque"][-1] == pytest.approx(expected, rel=1e-9)
    np.testing.assert_allclose(result["v_load"], -s.thread.lead / (2 * math.pi) * speed / ratio,
                               rtol=1e-12)
    assert abs(result["energy_residual"][-1]) <= 1e-9 * result["work_drive"][-1]


@pytest.mark.parametrize("mu, holds", [(0.3, True), (0.005, False)])
def test_self_locking_is_unchanged_by_the_gear(mu, holds):
    """Under an axial load alone a self-locking thread (mu' > tan alpha)
    holds behind the stage as without it; a thread with mu' < tan alpha is
    back-driven, and the rotor turns n times the driven part."""
    ratio = 10.0
    loads = {"drive_torque": 0.0, "axial_force": -50.0}
    scene = geared_rigid_scene(ratio, loads=loads, friction={"law": "coulomb", "mu": mu})
    s = ls.Scene.from_dict(scene)
    assert ls.is_self_locking(s.thread, mu) == holds
    result = ls.simulate(s, 0.1, t_eval=np.linspace(0.0, 0.1, 11))
    if holds:
        assert np.all(result["stick"] == 1.0)
        np.testing.assert_array_equal(result["u_load"], 0.0)
        np.testing.assert_array_equal(result["omega_drive"], 0.0)
        return
    drive = reference.reflected_drive(rigid.thesis_drive(mu=mu), ratio)
    ref = rigid.simulate(drive, rigid.Harmonic(), rigid.Harmonic(-50.0), 0.1)
    assert result["stick"][-1] == 0.0 and result["u_load"][-1] < 0.0
    np.testing.assert_allclose(result["u_load"], ref.u_load(result.t), rtol=1e-8, atol=1e-15)
    np.testing.assert_allclose(result["omega_drive"], ratio * ref.omega(result.t), rtol=1e-8,
                               atol=1e-12)


def test_energy_account_closes_with_a_gear():
    """A flexible nut with play and a DC motor behind a reduction, event-driven:
    the account (the stage stores and loses nothing) closes to the result
    checks' tolerance, and the drive's work is the motor's."""
    scene = thesis_scene(concept="flexible_nut", backlash={"axial": 1e-5},
                         loads={"axial_force": F}, gear={"ratio": 8.0}, motor=DC_MOTOR)
    scene["loads"].pop("drive_torque")
    result = ls.simulate(ls.Scene.from_dict(scene), 0.05)
    work = np.max(np.abs(result["work_drive"]))
    assert work > 0.0
    assert np.max(np.abs(result["energy_residual"])) <= 1e-6 * work


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut"])
def test_a_stage_of_ratio_one_is_the_drive_without_a_stage(concept):
    """n = 1 multiplies and divides by 1 only: bit-identical to no gear."""
    scene = thesis_scene(concept=concept)
    plain = ls.simulate(ls.Scene.from_dict(scene), 0.3)
    geared = ls.simulate(ls.Scene.from_dict({**scene, "gear": {"ratio": 1.0}}), 0.3)
    assert plain.channels == geared.channels
    for name in plain.channels:
        np.testing.assert_array_equal(plain[name], geared[name], err_msg=name)


@pytest.mark.parametrize("gear, message", [
    ({"ratio": 0.0}, "gear.ratio = 0.0 is invalid: must be in [0.0001, 10000] or in "
                     "[-10000, -0.0001]"),
    ({"ratio": 2e4}, "gear.ratio = 20000.0 is invalid: must be a finite number in "
                     "[-10000, 10000]"),
    ({"ratio": float("nan")}, "gear.ratio = nan is invalid"),
    ({}, "gear.ratio is missing"),
    ({"ratio": 2.0, "type": "lossy"}, "gear.efficiency is missing: gear.type = 'lossy' needs it"),
    ({"ratio": 2.0, "type": "worm"}, "gear.lead_angle is missing: gear.type = 'worm' needs it"),
    ({"ratio": 2.0, "type": "helical"}, "gear.type = 'helical' is invalid"),
    ({"ratio": 2.0, "efficiency": 0.9}, "gear.efficiency = 0.9 is invalid: must be absent "
                                        "with gear.type = 'ideal'"),
    ({"ratio": 2.0, "backlash": 1e-3}, "gear.backlash"),
])
def test_an_invalid_gear_raises_value_error_naming_the_key(gear, message):
    with pytest.raises(ValueError, match=None) as info:
        ls.Scene.from_dict(thesis_scene(gear=gear))
    assert message in str(info.value)


def test_the_core_checks_the_ratio_too():
    parameters = ls.Scene.from_dict(thesis_scene()).model().parameters
    parameters.gear_ratio = 2.0
    with pytest.raises(ValueError, match=r"gear_ratio = 2 is invalid without a gear stage"):
        _core.DriveModel(parameters)
    parameters.gear = "ideal"
    parameters.gear_ratio = 0.0
    with pytest.raises(ValueError, match=r"gear.ratio = 0 is invalid: must be in \[0.0001, "):
        _core.DriveModel(parameters)
    with pytest.raises(ValueError, match="gear.type"):
        parameters.gear = "helical"


def test_the_gear_round_trips_through_toml_and_the_core_spec(tmp_path):
    """A scene file's [gear] table, and the core spec's drive.gear and
    parameters.gear_ratio."""
    path = tmp_path / "geared.toml"
    path.write_text(
        'concept = "rigid"\n[thread]\npitch = "1 mm"\nmean_diameter = "20 mm"\n'
        '[friction]\nmu = 0.3\n[loads]\ndrive_torque = "0.1 N*m"\naxial_force = "10 N"\n'
        '[gear]\ntype = "ideal"\nratio = 12.5\n')
    scene = ls.Scene.from_toml(path)
    assert scene.to_dict()["gear"] == {"type": "ideal", "ratio": 12.5}
    text = scene.to_core_toml()
    assert 'gear = "ideal"' in text and "gear_ratio = 12.5" in text
    parameters, options = _core.read_core_spec(text)
    assert (parameters.gear, parameters.gear_ratio) == ("ideal", 12.5)
    assert _core.write_core_spec(parameters, **options) == text
    assert _core.DriveModel(parameters).mass.tolist() == scene.model().mass.tolist()
    assert scene.model().mass[0] == pytest.approx(12.5**2 * 1e-5 + scene.derived()["screw_inertia"],
                                                  rel=1e-15)


@pytest.mark.parametrize("study", ["efficiency_vs_mu", "stick_slip"])
def test_the_studies_refuse_a_gear_stage(study):
    """The studies' closed forms are the bare drive's: a geared scene is
    refused, naming the section."""
    arguments = {"efficiency_vs_mu": ([0.1, 0.2], [10.0]), "stick_slip": ()}[study]
    with pytest.raises(ValueError, match=r"gear = \{'type': 'ideal', 'ratio': 2.0\} is invalid "
                                         r"for this study: must be absent"):
        getattr(ls.studies, study)(thesis_scene(gear={"ratio": 2.0}), *arguments)


def test_a_batch_varies_the_ratio():
    """DriveBatch's override gear_ratio (a DriveParameters field) runs each
    ratio as the scene with that ratio; without a stage it is refused."""
    from leadscrew.studies._batch import DriveBatch
    channels = ["u_load", "omega_drive", "drive_torque"]
    t_eval = np.linspace(0.0, 0.3, 7)
    base = ls.Scene.from_dict(thesis_scene(gear={"ratio": 2.0}))
    samples, errors, _ = DriveBatch(base, ["gear_ratio"], channels, 0.3, t_eval).run(
        [[3.0], [-0.5]])
    assert errors == [None, None]
    for ratio, ours in zip([3.0, -0.5], samples):
        result = ls.simulate(base.replace(gear={"ratio": ratio}), 0.3, t_eval=t_eval)
        np.testing.assert_array_equal(ours, np.array([result[c] for c in channels]))
    plain = ls.Scene.from_dict(thesis_scene())
    _, errors, _ = DriveBatch(plain, ["gear_ratio"], channels, 0.3, t_eval).run([[3.0]])
    assert "gear_ratio = 3 is invalid without a gear stage" in errors[0]


def test_check_reports_the_reflected_rotor(capsys, tmp_path):
    """`leadscrew check` on a geared scene: the rigid drive's J is n^2 J_rotor
    plus the screw's, and the jamming margins are taken with it."""
    from helpers.cli_runs import run_main
    path = tmp_path / "geared.toml"
    path.write_text('[thread]\npitch = "1 mm"\nmean_diameter = "20 mm"\n[friction]\nmu = 0.3\n'
                    '[gear]\nratio = 20\n')
    code, out, err = run_main(capsys, "check", path)
    assert code == 0 and err == ""
    scene = ls.Scene.from_toml(path)
    inertia = 400 * 1e-5 + scene.derived()["screw_inertia"]
    assert f"rigid drive: J = n^2 rotor (n = 20) + screw = {inertia:.6g} kg*m^2" in out


def test_the_stepper_runs_a_geared_drive_in_pieces():
    """The stepper (C API, FMU) builds the same geared model: its pieces agree
    with one run to a small multiple of the tolerance, and its channels are
    the rotor's."""
    from leadscrew.simulation import _run_options
    scene = ls.Scene.from_dict(thesis_scene(concept="flexible_nut", gear={"ratio": -4.0}))
    times = np.arange(1, 11) * 0.02
    tolerances = dict(rtol=1e-10, atol=1e-12)
    one_run = ls.simulate(scene, 0.2, t_eval=times, **tolerances)
    stepper = _core.DriveStepper(scene.model(), **_run_options(**tolerances))
    pieces = {name: [] for name in ("u_load", "omega_drive", "drive_torque")}
    for t in times:
        stepper.advance(t)
        for name, values in pieces.items():
            values.append(stepper.channel(name))
    for name, values in pieces.items():
        expected = np.asarray(one_run[name])
        assert np.max(np.abs(np.asarray(values) - expected)) <= 1e-8 * np.max(np.abs(expected))


@pytest.mark.parametrize("mu", [0.005, 0.05, 0.3])
def test_the_lossy_stage_closed_form_is_the_coulomb_screws(mu):
    """The closed form docs/physics/gear.md derives for type 'lossy' (refused
    by the simulator for now), checked where it must hold: a lead screw at a
    steady motion is a lossy stage from its screw's angle to its load's
    travel (|n| = 2 pi / lead rad per m) with the thread's efficiencies, so
    the stage's rotor torque is the raise torque for a resisting load, the
    lower torque for a driving one, and it locks exactly where the thread is
    self-locking; in series with an ideal thread the train's efficiency is
    the product."""
    thread = ls.Scene.from_dict(thesis_scene()).thread
    ratio = 2 * math.pi / thread.lead
    forward, backward = ls.efficiency(thread, mu), ls.efficiency(thread, mu, backdrive=True)
    load = 100.0  # [N]
    raising = reference.lossy_rotor_torque(load, ratio, forward, backward)
    lowering = reference.lossy_rotor_torque(-load, ratio, forward, backward)
    assert raising == pytest.approx(ls.raise_torque(thread, mu, load), rel=1e-12)
    assert lowering == pytest.approx(ls.lower_torque(thread, mu, load), rel=1e-12, abs=1e-15)
    assert reference.lossy_stage_locks(backward) == ls.is_self_locking(thread, mu)
    # A stage of eta = 0.8 before the screw: rotor torque raise / (n eta).
    gear = 12.0
    train = reference.lossy_rotor_torque(raising, gear, 0.8, 0.5)
    ideal = load * thread.lead / (2 * math.pi) / gear
    assert ideal / train == pytest.approx(0.8 * forward, rel=1e-12)


def test_the_static_equilibrium_start_is_the_reflected_drives():
    """initial.state = 'equilibrium' behind a stage: the torque n T holds the
    driven side as in the reflected drive (the same state); a refusal names
    the torque on the rotor."""
    ratio = 5.0
    scene = thesis_scene(concept="flexible_nut", initial={"state": "equilibrium"},
                         loads={"drive_torque": 0.001, "axial_force": -10.0},
                         gear={"ratio": ratio})
    geared = ls.Scene.from_dict(scene).initial_state()
    plain = ls.Scene.from_dict(reference.reflected_scene(scene, ratio)).initial_state()
    assert geared == plain
    scene["loads"]["drive_torque"] = 0.1
    with pytest.raises(ls.NoEquilibriumError, match=r"drive torque 0\.1 N\*m, axial force -10 N"):
        ls.Scene.from_dict(scene).initial_state()
