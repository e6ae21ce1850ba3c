"""The preloaded split nut with every thread friction law (issue 32; docs/
physics/preloaded_nut.md, "Friction laws"): each half's flank takes the law
at the common slip, half B's normal force N_B = side P / (cos a - side
kappa' sin a) at the law's coefficient kappa'. Against the closed forms of
tests/helpers/preloaded_nut_reference.py at the law's coefficient of the
steady slip speed, the limits (arctan_velocity's k_v -> infinity meets
exact Coulomb, LuGre's steady state meets Stribeck's curve), the energy
account and friction's sign, the independent checker
(tests/helpers/result_invariants.py), a property-based closed form, and
what stays refused."""

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import leadscrew as ls
from helpers import preloaded_nut_reference as reference
from helpers.result_invariants import check_result, failed
from helpers.scenes import thesis_scene

SPEED = 20.0  # [rad/s] of the rotor: the thread slips at about 0.2 m/s
T_END = 0.05  # [s]
STRIBECK = {"mu": 0.3, "mu_static": 0.4, "stribeck_velocity": 0.25, "stribeck_exponent": 2.0}
LAWS = {
    "arctan_velocity": {"law": "arctan_velocity", "mu": 0.3, "k_v": 50.0},
    "stribeck": {"law": "stribeck", **STRIBECK},
    "lugre": {"law": "lugre", **STRIBECK, "sigma0": 1e5, "sigma1": 0.0},
}


def raising(friction, load, preload, concept="rigid", speed=SPEED, **changes):
    """The thesis drive speed-controlled raising the axial load `load` (along
    -x: on half A's flank) with a preloaded nut of preload `preload`."""
    return thesis_scene(concept=concept, friction=friction,
                        nut={"preload": preload, **changes.pop("nut", {})},
                        loads={"drive_torque": None, "drive_speed": -speed,
                               "axial_force": -load},
                        initial={"rotor_speed": -speed}, **changes)


def law_coefficient(friction, speed):
    """The law's friction coefficient mu(|slip|) (before the flank factor) at
    a steady slip speed [m/s]: eq. (3.16)'s (2/pi) mu atan(k_v v), Stribeck's
    curve (LuGre's steady state: z = mu(v) / sigma0, z' = 0)."""
    if friction["law"] == "arctan_velocity":
        return 2.0 / math.pi * friction["mu"] * math.atan(friction["k_v"] * speed)
    if friction["law"] in ("stribeck", "lugre"):
        mu, mu_s = friction["mu"], friction["mu_static"]
        ratio = (speed / friction["stribeck_velocity"]) ** friction["stribeck_exponent"]
        return mu + (mu_s - mu) * math.exp(-ratio)
    return friction["mu"]


def closed_form_torque(scene, result, load, preload):
    """The raise torque r_m [(F + P) tan(a + rho') + P tan(rho' - a)] with
    mu' the law's coefficient at the run's final slip speed."""
    s = ls.Scene.from_dict(scene)
    speed = abs(result["slip_velocity"][-1])
    mu_eff = reference.effective_mu(law_coefficient(scene["friction"], speed),
                                    s.thread.flank_angle)
    return reference.raise_torque(load, preload, s.thread.lead_angle, mu_eff,
                                  s.thread.mean_radius)


def all_checks_pass(result):
    return all(check["passed"] for check in result.checks.values() if check["applies"])


@pytest.mark.parametrize("law", sorted(LAWS))
@pytest.mark.parametrize("load, preload", [(100.0, 200.0), (5.0, 500.0), (300.0, 10.0)])
def test_steady_raise_is_the_closed_form_at_the_laws_coefficient(law, load, preload):
    # Both halves' flanks carry the law at the slip speed: the thread's raise
    # torque with mu' = the law's coefficient there (the rigid drive slips
    # at once at the prescribed speed; LuGre's bristles settle in 1e-5 s).
    scene = raising(LAWS[law], load, preload)
    result = ls.simulate(ls.Scene.from_dict(scene), T_END)
    torque = closed_form_torque(scene, result, load, preload)
    assert -result["drive_torque"][-1] == pytest.approx(torque, rel=1e-9)
    # Above the plain nut's torque at that coefficient: the preload costs.
    plain = closed_form_torque(scene, result, load, 0.0)
    assert torque > plain
    # Half B's normal force at the law's coefficient; both halves' flank normal.
    s = ls.Scene.from_dict(scene)
    kappa = reference.effective_mu(law_coefficient(scene["friction"],
                                                   abs(result["slip_velocity"][-1])),
                                   s.thread.flank_angle)
    alpha = s.thread.lead_angle
    # (raising: the slip moves half B the way its spring pushes, the lower factor)
    half_b = preload / (math.cos(alpha) + kappa * math.sin(alpha))
    normal_a = result["normal_force_a"][-1]
    assert result["flank_normal"][-1] == pytest.approx(abs(normal_a) + half_b, rel=1e-9)
    assert abs(result["friction_force"][-1]) == pytest.approx(
        kappa * result["flank_normal"][-1], rel=1e-9)
    assert all_checks_pass(result)


def test_arctan_velocity_meets_exact_coulomb_as_k_v_grows():
    # kappa = (2/pi) mu atan(k_v v) -> mu: the torque's distance to exact
    # Coulomb's falls as 1/k_v (2 mu / (pi k_v v) of the coefficient).
    load, preload = 100.0, 200.0
    coulomb = ls.simulate(ls.Scene.from_dict(raising({"law": "coulomb", "mu": 0.3}, load,
                                                     preload)), T_END)
    reference_torque = coulomb["drive_torque"][-1]
    distances = []
    for k_v in (1e2, 1e4, 1e6):
        scene = raising({"law": "arctan_velocity", "mu": 0.3, "k_v": k_v}, load, preload)
        result = ls.simulate(ls.Scene.from_dict(scene), T_END)
        distances.append(abs(result["drive_torque"][-1] / reference_torque - 1.0))
    assert distances[0] > 50 * distances[1] > 50 * 50 * distances[2]
    assert distances[2] < 1e-5


def test_lugres_steady_state_meets_stribecks_curve():
    load, preload = 100.0, 200.0
    stribeck = ls.simulate(ls.Scene.from_dict(raising(LAWS["stribeck"], load, preload)), T_END)
    lugre = ls.simulate(ls.Scene.from_dict(raising(LAWS["lugre"], load, preload)), T_END)
    assert lugre["drive_torque"][-1] == pytest.approx(stribeck["drive_torque"][-1], rel=1e-9)
    assert lugre["friction_force"][-1] == pytest.approx(stribeck["friction_force"][-1],
                                                        rel=1e-9)


def cycling(law, concept, preload=20.0, **changes):
    """A sine drive torque on a loaded preloaded nut: the thread slips both
    ways (sticks, with a set-valued law)."""
    return thesis_scene(concept=concept, friction=dict(law) if isinstance(law, dict) else LAWS[law],
                        nut={"preload": preload, **changes.pop("nut", {})},
                        loads={"drive_torque": {"type": "sine", "amplitude": -0.6,
                                                "omega": 4 * math.pi},
                               "axial_force": -10.0}, **changes)


@pytest.mark.parametrize("law", sorted(LAWS))
@pytest.mark.parametrize("concept", ["rigid", "flexible_nut", "flexible"])
def test_energy_account_closes_and_friction_takes_energy(law, concept):
    scene = cycling(law, concept)
    result = ls.simulate(ls.Scene.from_dict(scene), 0.5, rtol=1e-10, t_eval="steps")
    slip = result["slip_velocity"]
    assert np.any(slip > 1e-3) and np.any(slip < -1e-3)
    work = result["work_drive"] + result["work_axial"]
    account = (result["kinetic"] + result["elastic"] - result["elastic"][0]
               + result["friction_loss"] + result["damping_loss"])
    scale = np.max(np.abs(result["work_drive"]))
    assert np.max(np.abs(work - account)) <= 1e-6 * scale
    # Friction never gives energy back: its loss never falls (LuGre's stored
    # bristle energy is not lost: the loss books what remains).
    assert np.all(np.diff(result["friction_loss"]) >= -1e-9 * result["friction_loss"][-1])
    if law != "lugre":  # (a bristle unloading pushes for a moment)
        power = result["friction_force"] * slip
        assert np.all(power <= 1e-9 * np.max(np.abs(power)))
    assert all_checks_pass(result)
    options = {"t_end": 0.5, "rtol": 1e-10}  # (every step: t_eval "steps")
    assert failed(check_result(result, ls.Scene.from_dict(scene).to_dict(), options)) == []


@pytest.mark.parametrize("law", [*sorted(LAWS), "arctan_acceleration"])
@pytest.mark.parametrize("contact", ["bistop", "cubic"])
def test_lift_off_with_each_law(law, contact):
    # Half A's penalty flank lifts off under a reversing axial load; half B
    # keeps its flank and the law's friction on the common slip: the account
    # closes (half B's friction books its own slip).
    loads = {"drive_torque": {"type": "sine", "amplitude": -0.3, "omega": 6 * math.pi},
             "axial_force": {"type": "sine", "amplitude": 300.0, "omega": 2 * math.pi,
                             "offset": -1.0}}
    friction = (dict(LAWS[law], mu=0.1, **({"mu_static": 0.12} if law != "arctan_velocity"
                                           else {}))
                if law in LAWS else {"law": law, "mu": 0.1, "k_v": 10.0})
    scene = thesis_scene(concept="flexible_nut", friction=friction,
                         nut={"preload": 50.0, "preload_stiffness": 1e6},
                         backlash={"axial": 1e-4, "contact": contact}, loads=loads)
    result = ls.simulate(ls.Scene.from_dict(scene), 0.5, rtol=1e-10, integrator="event_driven")
    normal_a = result["normal_force_a"]
    assert np.any(normal_a == 0.0) and np.any(normal_a != 0.0)
    work = result["work_drive"] + result["work_axial"]
    account = (result["kinetic"] + result["elastic"] - result["elastic"][0]
               + result["friction_loss"] + result["damping_loss"] + result["contact_loss"]
               + result["impact_loss"])
    scale = np.max(np.abs(result["work_axial"]))
    assert np.max(np.abs(work - account)) <= 1e-6 * scale
    assert all_checks_pass(result)


@pytest.mark.parametrize("law", ["arctan_velocity", "lugre"])
def test_ode_methods_run_the_smooth_laws_as_the_event_driven_scheme(law):
    # The same driver with another integrator between events: the same run
    # to the tolerances.
    scene = ls.Scene.from_dict(cycling(law, "rigid"))
    event_driven = ls.simulate(scene, 0.2, rtol=1e-10, t_eval=np.linspace(0, 0.2, 41))
    ode = ls.simulate(scene, 0.2, rtol=1e-10, integrator="cvode_bdf",
                      t_eval=np.linspace(0, 0.2, 41))
    scale = np.max(np.abs(event_driven["drive_torque"])) / 0.01  # (a force)
    np.testing.assert_allclose(ode["friction_force"], event_driven["friction_force"],
                               atol=1e-5 * scale)


def test_exact_play_closed_by_the_preload_is_the_no_play_run_with_a_smooth_law():
    friction = LAWS["arctan_velocity"]
    played = raising(friction, 50.0, 100.0, concept="flexible_nut",
                     backlash={"contact": "exact", "axial": 1e-4})
    closed = raising(friction, 50.0, 100.0, concept="flexible_nut")
    a = ls.simulate(ls.Scene.from_dict(played), 0.02)
    b = ls.simulate(ls.Scene.from_dict(closed), 0.02)
    np.testing.assert_array_equal(a["drive_torque"], b["drive_torque"])


def test_exact_play_half_a_lifting_off_raises_with_a_smooth_law():
    # A load reversed beyond the preload lifts half A off into the exact play
    # (not modelled): the guard's root on half A's normal force at the law's
    # N_B raises, as with Coulomb.
    table = {"type": "table", "times": [0.0, 0.05], "values": [-10.0, 400.0]}
    scene = thesis_scene(concept="flexible_nut", friction=LAWS["arctan_velocity"],
                         nut={"preload": 100.0}, backlash={"contact": "exact", "axial": 1e-4},
                         loads={"drive_torque": None, "drive_speed": 0.0, "axial_force": table})
    with pytest.raises(ls.SimulationError, match="half A of the preloaded nut lifts off"):
        ls.simulate(ls.Scene.from_dict(scene), 0.05)


@settings(max_examples=15, deadline=None)
@given(law=st.sampled_from(sorted(LAWS)), mu=st.floats(0.02, 0.5),
       load=st.floats(1.0, 500.0), preload=st.floats(1.0, 1000.0),
       speed=st.floats(2.0, 100.0))
def test_property_steady_raise_at_the_laws_coefficient(law, mu, load, preload, speed):
    friction = dict(LAWS[law], mu=mu)
    if "mu_static" in friction:
        friction["mu_static"] = 1.3 * mu
    scene = raising(friction, load, preload, speed=speed)
    result = ls.simulate(ls.Scene.from_dict(scene), T_END)
    torque = closed_form_torque(scene, result, load, preload)
    assert -result["drive_torque"][-1] == pytest.approx(torque, rel=1e-8)


ACCELERATION = {"law": "arctan_acceleration", "mu": 0.3, "k_v": 10.0}


def test_arctan_acceleration_at_steady_slip_costs_nothing():
    # Eq. (3.15) opposes the slip acceleration: at a steady slip neither
    # half rubs, and the raise torque is the frictionless r_m F tan a
    # whatever the preload (half B's force along the helix's normal).
    load = 100.0
    scene = raising(ACCELERATION, load, 200.0)
    result = ls.simulate(ls.Scene.from_dict(scene), T_END)
    s = ls.Scene.from_dict(scene)
    expected = s.thread.mean_radius * load * math.tan(s.thread.lead_angle)
    assert -result["drive_torque"][-1] == pytest.approx(expected, rel=1e-12)


def test_arctan_acceleration_follows_its_law_on_both_halves():
    # friction = -(2/pi) mu' atan(k_v x) (|N_A| + |N_B|), x the slip
    # acceleration (no channel: the slip velocity's difference quotient on
    # 2001 rows; measured 5.5e-4 N of 15 N), the account closed (7e-8 J).
    scene = cycling(ACCELERATION, "rigid")
    result = ls.simulate(ls.Scene.from_dict(scene), 0.2, rtol=1e-10,
                         t_eval=np.linspace(0.0, 0.2, 2001))
    acceleration = np.gradient(result["slip_velocity"], result.t)
    mu = reference.effective_mu(0.3, ls.Scene.from_dict(scene).thread.flank_angle)
    expected = -2 / math.pi * mu * np.arctan(10.0 * acceleration) * result["flank_normal"]
    scale = np.max(np.abs(result["friction_force"]))
    assert np.max(np.abs(result["friction_force"] - expected)[5:-5]) <= 2e-4 * scale
    assert np.max(np.abs(result["energy_residual"])) <= 1e-6 * np.max(np.abs(result["work_drive"]))
    assert all_checks_pass(result)


def test_refused_with_the_reason():
    with pytest.raises(ValueError, match=r"integrator = \"moreau\""):
        ls.simulate(ls.Scene.from_dict(raising(ACCELERATION, 10.0, 20.0)), 0.01,
                    integrator="moreau")
    smooth = ls.Scene.from_dict(raising(LAWS["arctan_velocity"], 10.0, 20.0))
    stribeck = ls.Scene.from_dict(raising(LAWS["stribeck"], 10.0, 20.0))
    with pytest.raises(ValueError, match=r"integrator = \"cvode_bdf\" is invalid with "
                                         r"nut\.preload = 20 N and friction\.law = \"stribeck\""):
        ls.simulate(stribeck, 0.01, integrator="cvode_bdf")
    assert ls._core.drive_integrators(smooth.model().parameters)[-2:] == ["event_driven",
                                                                          "moreau"]


def holding(torque, preload, concept, **changes):
    """The thesis drive at rest in its static equilibrium under a drive
    torque and 50 N on half A's flank."""
    return thesis_scene(concept=concept, nut={"preload": preload, **changes.pop("nut", {})},
                        initial={"state": "equilibrium"},
                        loads={"drive_torque": -torque, "axial_force": -50.0}, **changes)


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut", "flexible"])
def test_the_static_equilibrium_with_a_preload(concept):
    # The halves' spring is internal: the equilibrium's deflections and net
    # forces are the plain nut's (bit for bit where the plain nut holds);
    # its cone is the halves', mu' (|N - N_B^s| + |N_B^s|), so a torque the
    # plain nut cannot hold is held at rest (the run stays stuck there).
    plain = ls.simulate(ls.Scene.from_dict(holding(0.05, 0.0, concept)), 0.02)
    preloaded = ls.simulate(ls.Scene.from_dict(holding(0.05, 100.0, concept)), 0.02)
    assert preloaded["u_load"][0] == plain["u_load"][0]
    for channel in ("normal_force", "friction_force", "elastic"):  # (the stuck row's solve)
        assert preloaded[channel][0] == pytest.approx(plain[channel][0], rel=1e-14, abs=1e-300)
    with pytest.raises(ls.NoEquilibriumError):
        ls.simulate(ls.Scene.from_dict(holding(0.4, 0.0, concept)), 0.02)
    held = ls.simulate(ls.Scene.from_dict(holding(0.4, 100.0, concept)), 0.02)
    assert np.all(held["stick"] == 1.0)
    # (stuck: the load stays at its equilibrium to the integrator's round-off)
    assert np.ptp(held["u_load"]) <= 1e-9 * abs(held["u_load"][0]) + 1e-18
    s = ls.Scene.from_dict(holding(0.4, 100.0, concept))
    alpha = s.thread.lead_angle
    mu = reference.effective_mu(0.3, s.thread.flank_angle)
    normal, friction = held["normal_force"][0], held["friction_force"][0]
    # (the edge the friction heads for: half B's normal force there)
    side = -np.sign(normal)
    edge = -np.sign(friction)
    half_b = side * 100.0 / (math.cos(alpha) - edge * side * mu * math.sin(alpha))
    plain_cone = mu * abs(normal)
    assert plain_cone < abs(friction) <= mu * (abs(normal - half_b) + abs(half_b))


def test_the_equilibrium_with_lift_off_is_refused():
    scene = holding(0.05, 50.0, "flexible_nut", nut={"preload_stiffness": 1e6},
                    backlash={"axial": 1e-4, "contact": "bistop"})
    with pytest.raises(ValueError, match=r"nut\.preload = 50 is invalid with initial\.state = "
                                         r"\"equilibrium\" and backlash\.contact = \"bistop\": a "
                                         r"preloaded nut that lifts off starts assembled"):
        ls.Scene.from_dict(scene).model()
