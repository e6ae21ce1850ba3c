"""Moreau-Jean with the smooth thread laws and the train's friction stages
with every law and a speed-controlled rotor (issue 32, item 3;
docs/physics/drive_models.md, "Moreau-Jean with the smooth laws";
docs/physics/gear.md, "The smooth thread laws and a prescribed rotor
speed"): arctan_velocity and LuGre converge at first order in dt to the cvode_bdf solution; the implicit
friction runs a stiff k_v at a long step and tends to exact Coulomb as
k_v grows; a lossy stage behind a prescribed rotor speed takes the closed
form's motor torque, T_screw / (n eta) driving and T_screw eta_b / n
back-driven; a worm with the arctan law on the flexible concept closes its
account; the defaults run every such combination on Moreau-Jean; eq.
(3.15) is refused on Moreau-Jean with its reason. Every run passes its own
checks and the independent invariants (helpers/result_invariants.py)."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers.result_invariants import checked_run as checked
from helpers.scenes import thesis_scene

# The invariants read each run step by step.
pytestmark = pytest.mark.usefixtures("every_step")

ARCTAN = {"law": "arctan_velocity", "mu": 0.3, "k_v": 1e4}
LUGRE = {"law": "lugre", "mu": 0.3, "sigma0": 1e3}
LOSSY = {"type": "lossy", "ratio": 4.0, "efficiency": 0.7, "efficiency_backdrive": 0.4}
WORM = {"type": "worm", "ratio": 4.0, "lead_angle": 0.3, "mu": 0.05}


def order(dts, errors):
    """The slope of log(error) over log(dt)."""
    return np.polyfit(np.log(dts), np.log(errors), 1)[0]


@pytest.mark.parametrize("law, dts", [
    (ARCTAN, [1e-3, 5e-4, 2.5e-4, 1.25e-4]),
    # (sigma0 = 1e3: the bristles' time constant mu / (sigma0 |gamma|) near
    # 1e-3 s, which these steps resolve; at the default 1e5 the same fit needs
    # steps below 1e-6 s)
    (LUGRE, [1e-4, 5e-5, 2.5e-5, 1.25e-5]),
])
def test_a_smooth_law_on_moreau_jean_converges_at_first_order(law, dts):
    # The thesis drive under its sine torque, 0.2 s: the rotor's speed at the
    # end against cvode_bdf at rtol 1e-11 (measured orders 0.99 to 1.01).
    scene = thesis_scene(friction=law)
    exact = ls.simulate(ls.Scene.from_dict(scene), 0.2, integrator="cvode_bdf", rtol=1e-11,
                        atol=1e-13)
    errors = []
    for dt in dts:
        result = checked(scene, 0.2, integrator="moreau", dt=dt)
        errors.append(abs(result["omega_drive"][-1] - exact["omega_drive"][-1]))
    assert 0.9 < order(dts, errors) < 1.1, errors
    assert errors[-1] < 1e-3 * abs(exact["omega_drive"][-1])


def test_lugres_bristles_stay_in_their_bound_and_store_their_energy():
    # A long step against the default stiff bristles (dt 1e-3 s, 1e3 times
    # their time constant): the implicit bristle step stays in |z| <=
    # mu_static / sigma0 and, sliding, settles on the law's steady deflection
    # mu / sigma0 (Stribeck's mu at the slip speed) exactly.
    scene = thesis_scene(friction={"law": "lugre", "mu": 0.3, "sigma0": 1e5})
    result = checked(scene, 0.2, integrator="moreau", dt=1e-3)
    z = result["bristle_deflection"]
    assert np.max(np.abs(z)) <= 0.3 / 1e5 * (1 + 1e-12)
    # (rows sliding faster than 2 cm/s, and the row before: h |gamma| >= 7
    # mu / sigma0, a contraction of 1 / 8 a step towards the steady deflection)
    slip = result["slip_velocity"]
    sliding = np.abs(slip) > 0.02
    sliding[1:] &= np.abs(slip[:-1]) > 0.02
    assert np.count_nonzero(sliding) > 50
    np.testing.assert_allclose(z[sliding], 0.3 / 1e5 * np.sign(slip[sliding]), rtol=1e-9)


def test_a_stiff_arctan_law_runs_at_a_long_step_and_tends_to_exact_coulomb():
    # The friction is implicit in the step: k_v up to 1e8 s/m runs at dt
    # 1e-4 s on the flexible nut (an explicit step would need dt below
    # 1 / (mu' k_v |N| / m), 1e-9 s). The run tends to exact Coulomb on
    # Moreau-Jean at the same dt as k_v grows: the gap in the load's
    # position falls with every decade.
    dt, t_end = 1e-4, 0.2
    base = thesis_scene(concept="flexible_nut")
    coulomb = checked(base, t_end, integrator="moreau", dt=dt)
    gaps = []
    for k_v in (1e4, 1e5, 1e6, 1e8):
        scene = thesis_scene(concept="flexible_nut", friction={**ARCTAN, "k_v": k_v})
        result = checked(scene, t_end, integrator="moreau", dt=dt)
        gaps.append(np.max(np.abs(result["u_load"] - coulomb["u_load"])))
    assert all(b < a for a, b in zip(gaps, gaps[1:])), gaps
    assert gaps[-1] < 1e-3 * np.max(np.abs(coulomb["u_load"]))


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut", "flexible"])
@pytest.mark.parametrize("law", [ARCTAN, LUGRE])
def test_a_smooth_law_runs_with_exact_play_and_end_stops(concept, law):
    # Every concept with 0.1 mm of exact play and end stops 0.15 mm either
    # side that the load reaches (exact ones where the load is a body of its
    # own, penalty ones on the rigid drive), on Moreau-Jean: the account
    # closes, friction never works positively (arctan), the law holds on
    # every row.
    stops = ({"contact": "penalty", "stiffness": 1e8} if concept == "rigid"
             else {"contact": "exact"})
    scene = thesis_scene(concept=concept, friction=law,
                         backlash={"axial": 1e-4, "contact": "exact"},
                         loads={"drive_torque": 0.05},
                         end_stops={"lower": -1.5e-4, "upper": 1.5e-4, **stops})
    result = checked(scene, 0.1, integrator="moreau", dt=1e-4)
    # (a penalty stop of 1e8 N/m yields 2.4 um under the clamp of ~240 N)
    assert np.max(np.abs(result["u_load"])) <= 1.5e-4 + 1e-5
    assert np.max(np.abs(result["stop_force"])) > 0.0


def speed_scene(gear, force, mu=0.05):
    scene = thesis_scene(gear=gear, loads={"axial_force": force, "drive_speed": 20.0},
                         friction={"law": "coulomb", "mu": mu})
    scene["loads"].pop("drive_torque")
    return scene


@pytest.mark.parametrize("force", [-50.0, 50.0])
@pytest.mark.parametrize("mu", [0.05, 0.3])
def test_a_lossy_stage_behind_a_prescribed_speed_takes_the_closed_forms_torque(force, mu):
    # The rigid drive at a constant rotor speed: the thread's power P_t =
    # -F v / eta_t where the motor raises the load, -F v eta_t' where the
    # load drives the screw (eta_t' <= 0: self-locking at mu = 0.3, the
    # motor drives then too); the stage passes P_t on and takes P_t / eta in
    # (forward) or gives eta_b P_t out (back-driven): the motor's torque
    # T_m = P_t / (eta omega) = T_screw / (n eta), or T_screw eta_b / n. At the
    # default integrator (Moreau-Jean: the event-driven scheme runs the
    # stages with a torque or DC motor alone).
    scene = speed_scene(LOSSY, force, mu)
    result = checked(scene, 0.05)
    assert result.integrator == "moreau"
    s = ls.Scene.from_dict(scene)
    eta_t = ls.efficiency(s.thread, mu)
    eta_t_back = ls.efficiency(s.thread, mu, backdrive=True)
    late = result.t > 0.01
    omega, v = result["omega_drive"][late], result["v_load"][late]
    raising = -force * v[0] > 0.0
    thread_power = -force * v / eta_t if raising else -force * v * eta_t_back
    eta, eta_b = LOSSY["efficiency"], LOSSY["efficiency_backdrive"]
    motor_power = thread_power / eta if thread_power[0] > 0.0 else thread_power * eta_b
    np.testing.assert_allclose(result["drive_torque"][late], motor_power / omega, rtol=1e-9)
    # The stage's loss: the power difference, booked at every step.
    expected_loss = np.abs(motor_power - thread_power)[0]
    rate = np.diff(result["gear_loss"][late]) / np.diff(result.t[late])
    np.testing.assert_allclose(rate, expected_loss, rtol=1e-9)


def test_a_prescribed_speed_with_the_motors_friction_and_a_worm_on_the_flexible_drive():
    # A sine speed through a worm with the motor's Coulomb friction on the
    # flexible concept with play: the motion is the prescribed one, the
    # losses never fall, the account closes.
    scene = thesis_scene(concept="flexible", gear=WORM, motor={"friction_torque": 2e-3},
                         backlash={"axial": 1e-4, "contact": "exact"},
                         loads={"axial_force": -20.0,
                                "drive_speed": {"type": "sine", "amplitude": 30.0,
                                                "omega": 20.0}})
    scene["loads"].pop("drive_torque")
    result = checked(scene, 0.3)
    assert result.integrator == "moreau"
    np.testing.assert_allclose(result["omega_drive"], 30.0 * np.sin(20.0 * result.t),
                               atol=1e-12)
    for name in ("gear_loss", "motor_friction_loss"):
        assert np.all(np.diff(result[name]) >= 0.0) and result[name][-1] > 0.0, name


def test_a_worm_with_a_smooth_law_on_the_flexible_concept_closes_its_account():
    # The default integrator is Moreau-Jean (it ran the scene before the
    # event-driven rotor contact took arctan_velocity,
    # tests/test_event_driven_rotor_friction.py) at its default dt; the
    # losses never fall, the account closes.
    scene = thesis_scene(concept="flexible", gear=WORM, friction=ARCTAN,
                         motor={"friction_torque": 1e-3},
                         loads={"drive_torque": 0.03, "axial_force": -20.0})
    assert ls._core.drive_integrators(ls.Scene.from_dict(scene).model().parameters) == [
        "moreau", "event_driven"]
    result = checked(scene, 0.2)
    assert result.integrator == "moreau"
    assert result["gear_loss"][-1] > 0.0 and result["friction_loss"][-1] > 0.0
    for name in ("gear_loss", "motor_friction_loss"):
        assert np.all(np.diff(result[name]) >= 0.0), name


# Six of 10,000 random drive trains (tests/fuzz_scenes.py --generator train,
# at dd97af1) returned LuGre on Moreau-Jean with a friction off its law
# where a row of the step's solve held the slip (the train's rotor contact,
# an exact stop holding a load rigid in the thread); refused until the held
# rows took the bristles' force (moreau_held_bristles.cpp). They run now,
# the law at every row (the invariants' friction_law).
@pytest.mark.parametrize("changes", [
    dict(gear=WORM, motor={"friction_torque": 1e-3}),
    dict(concept="rigid", motor={"friction_torque": 1e-3}),
    dict(concept="rigid", end_stops={"upper": 1e-3, "contact": "exact"}),
])
def test_lugre_where_a_row_holds_the_slip_runs_on_moreau_jean(changes):
    scene = thesis_scene(**dict(dict(concept="flexible", friction=LUGRE,
                                     loads={"drive_torque": 0.03, "axial_force": -20.0}),
                                **changes))
    result = checked(scene, 0.01, integrator="moreau")
    assert result["friction_loss"][-1] > 0.0


# The rest of those six: a penalty flank whose law's viscous term (on
# wherever the flank carries a force) pulls it open, where without the
# friction it pushes: no impulse of the step is consistent. Their rows
# reported the flank's force with no friction beside it (57 N the law's
# viscous term gives, 0 reported); the step says so now, as the Coulomb
# step's (a fuzz case of seed 20261127, its rotor's modes each inconsistent).
def test_a_penalty_flank_the_viscous_friction_pulls_open_is_no_silent_separation():
    scene = {"concept": "rigid", "drive": "nut",
             "thread": {"pitch": 0.0007466549622819766, "mean_diameter": 0.01792667635686734,
                        "flank_angle": 1.0471975511965976},
             "friction": {"law": "lugre", "mu": 0.01149542642874986,
                          "mu_static": 0.019439125174292495,
                          "stribeck_exponent": 2.433389151502366, "viscous": 88.3607964627995},
             "backlash": {"axial": 0.00013568520891631998, "contact": "bistop"},
             "screw": {"radius": 0.006315571089313526, "length": 0.09174083455798439,
                       "youngs_modulus": 229429483065.50024},
             "nut": {"outer_radius": 0.009842290267073263, "length": 0.009714523479015946,
                     "youngs_modulus": 44575622301.605316, "position": 0.07711147570991189},
             "rotor": {"inertia": 3.4959546566242743e-07}, "load": {"mass": 4.444471360720106},
             "loads": {"axial_force": {"type": "sine", "amplitude": -2.7872332438687506,
                                       "omega": 223.82329123820972,
                                       "phase": 3.6467226234855072},
                       "drive_torque": {"type": "table",
                                        "times": [0.00129709166177281, 0.0088192062062111],
                                        "values": [-0.0029960458712690254,
                                                   -0.017925992675088275]}},
             "gear": {"type": "lossy", "ratio": -0.514692583301361,
                      "efficiency": 0.20659356122314324,
                      "efficiency_backdrive": 0.569434834444488}}
    with pytest.raises(ls.SimulationError, match="pulls the flank open, without it the flank "
                                                  "pushes"):
        ls.simulate(ls.Scene.from_dict(scene), 0.020349508576621086, integrator="moreau")


def test_stribeck_on_the_rigid_stage_refuses_an_explicit_event_driven_run():
    # (arctan_velocity runs there: the rotor contact, its default Moreau-Jean;
    # tests/test_event_driven_rotor_friction.py)
    stribeck = {"law": "stribeck", "mu": 0.2, "mu_static": 0.3}
    scene = ls.Scene.from_dict(thesis_scene(gear=LOSSY, friction=stribeck))
    with pytest.raises(ValueError) as info:
        ls.simulate(scene, 0.01, integrator="event_driven")
    assert 'here friction.law = "stribeck"; use integrator = "moreau"' in str(info.value)
    assert ls.simulate(scene, 0.01).integrator == "moreau"
    smooth = ls.Scene.from_dict(thesis_scene(gear=LOSSY, friction=ARCTAN))
    assert ls.simulate(smooth, 0.01).integrator == "moreau"
    assert ls.simulate(smooth, 0.01, integrator="event_driven").integrator == "event_driven"


@pytest.mark.parametrize("gear", [None, LOSSY])
def test_eq_3_15_on_moreau_jean_is_refused_with_its_reason(gear):
    scene = thesis_scene(friction={"law": "arctan_acceleration", "mu": 0.3},
                         **({"gear": gear} if gear else {}))
    with pytest.raises(ValueError) as info:
        s = ls.Scene.from_dict(scene)
        ls.simulate(s, 0.01, integrator="moreau")
    text = str(info.value)
    assert 'friction.law = "arctan_acceleration"' in text
    assert "slip acceleration" in text
    if gear is None:
        assert text.startswith('integrator = "moreau" is invalid')
        assert 'use friction.law = "arctan_velocity" or "lugre" on Moreau-Jean' in text
    else:
        assert text.startswith('gear.type = "lossy" is invalid')
