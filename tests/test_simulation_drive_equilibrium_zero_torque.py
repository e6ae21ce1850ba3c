"""The static-equilibrium start (``initial.state = "equilibrium"``) under no
drive torque (docs/guide/known_problems.md's item of 2026-12-07: the shipped
seat_adjuster on the flexible concept, no motor, no stops, raised
SimulationError at t = 0 under 5, 10, 20, 40 and -60 N, "did not converge
in 50 Newton iterations", with exact, penalty or no play).

The cause: Newton reached the balance in 3 or 4 iterations, but its test
judged each balance against the forces meeting at its coordinate alone. The
rotor's coupling to the screw carries nothing under a zero torque: its
torque is round-off of the screw's angle (1e-36 N*m), judged against itself
it never balanced (the runs that started had round-off leave the angle at
exactly 0). Without play the nut's coordinates balance at zero too and the
play's equation had the same fault (the flexible nut at 150 N). The scales
now take what the springs pass on from their other ends
(docs/physics/drive_models.md, "The start").

Checked against the closed forms of the thread's statics (the stuck thread
carries the loads: |N| = |F| cos(alpha), |T| = |F| sin(alpha) without a
torque, helpers/static_equilibrium.py, with the flexible screw's force of
its stiffness's change along the nut; the nut's axial spring carries F), the
static cone, and a run from the start that stays where it started."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import leadscrew as ls
from helpers import static_equilibrium as closed
from helpers import thread_reference

FORCES = [-60.0, -40.0, -20.0, -10.0, -5.0, 5.0, 10.0, 20.0, 40.0, 80.0]  # [N]
CONCEPTS = ["flexible", "flexible_nut", "rigid"]
PLAYS = {"exact": {"contact": "exact"}, "bistop": {"contact": "bistop"},
         "cubic": {"contact": "cubic"}, "none": None}


def seat(concept="flexible", torque=0.0, force=5.0, play="exact", **changes):
    """The shipped seat_adjuster without motor and stops, started in static
    equilibrium under the drive torque [N*m] and the axial force [N]."""
    return ls.scenes.load("seat_adjuster").replace(
        concept=concept, motor=None, end_stops=None, backlash=PLAYS[play],
        loads={"drive_torque": torque, "axial_force": force},
        initial={"state": "equilibrium"}, **changes)


def thread_of(scene):
    d = scene.to_dict()
    return d["thread"], d["friction"], d.get("gear", {}).get("ratio", 1.0)


def holding_band(scene, force):
    """The rotor torques [N*m] the stuck thread holds under the axial force
    [N] (the closed form at mu_static through the gear's ratio, mirrored by
    the force's sign: tests/test_moreau_holding_theta.py)."""
    thread, friction, ratio = thread_of(scene)
    args = (thread["pitch"], thread["mean_diameter"], friction["mu_static"], abs(force),
            thread["starts"], thread["flank_angle"])
    low = -thread_reference.lower_torque(*args) / ratio
    high = thread_reference.raise_torque(*args) / ratio
    return (low, high) if force > 0 else (-high, -low)


def screw_potential_force(scene, screw_torque, force):
    """The force [N] the flexible screw's springs put on the translating
    part besides F: their stiffness follows the nut (eq. 4.24, here the
    segment between the nut and the drive end, k = E A / a and G I_p / a), so
    their energy k(a) x^2 / 2 pushes along a by -k'(a) x^2 / 2 = F^2 / (2 E A)
    + M^2 / (2 G I_p) (x = F / k, M / k), along +x on this drive (4.7e-6 of
    F at -60 N; 0 on the other concepts)."""
    d = scene.to_dict()
    if d["concept"] != "flexible":
        return 0.0
    screw = d["screw"]
    area = math.pi * screw["radius"] ** 2
    axial_rigidity = screw["youngs_modulus"] * area
    torsional_rigidity = (screw["youngs_modulus"] / (2.0 * (1.0 + screw["poisson"]))
                          * area * screw["radius"] ** 2 / 2.0)
    return force ** 2 / (2.0 * axial_rigidity) + screw_torque ** 2 / (2.0 * torsional_rigidity)


def assert_thread_holds(scene, start, torque, force):
    """The thread's forces against the statics' closed form, in the static
    cone, the nut where they press it."""
    thread, friction, ratio = thread_of(scene)
    normal, tangential = start["normal_force"], start["friction_force"]
    # (a penalty flank's normal force is its own elastic force at the
    # penetration found: the balance's 1e-9)
    rel = 1e-12 if scene.to_dict().get("backlash", {}).get("contact") in (None, "exact") else 1e-9
    axial = force - screw_potential_force(scene, torque * ratio, force)
    assert math.hypot(normal, tangential) == pytest.approx(
        closed.thread_force(torque * ratio, axial, thread["mean_diameter"]), rel=rel)
    if torque == 0.0:
        alpha = thread_reference.lead_angle(thread["pitch"], thread["mean_diameter"],
                                            thread["starts"])
        assert abs(normal) == pytest.approx(abs(axial) * math.cos(alpha), rel=rel)
        assert abs(tangential) == pytest.approx(abs(axial) * math.sin(alpha), rel=rel)
    mu_flank = friction["mu_static"] / math.cos(thread["flank_angle"] / 2.0)
    assert abs(tangential) <= mu_flank * abs(normal)
    backlash = scene.to_dict().get("backlash")
    half = 0.5 * backlash["axial"] if backlash else 0.0
    if backlash is None:
        assert abs(start["play"]) <= 1e-15
    elif backlash["contact"] == "exact":
        # the flank the normal force presses the nut against, e* = -sign(N) c/2
        assert start["play"] == -math.copysign(half, normal)
    else:
        assert start["play"] * -math.copysign(1.0, normal) > half


def assert_springs_carry(scene, start, torque, force):
    """Zero torque: the nut's axial spring carries the axial force, the
    torsion springs nothing (their angles round-off: below 1e-12 of the
    angle that turns the thread by the half clearance)."""
    if scene.to_dict()["concept"] == "rigid":
        return
    q = start["q"]
    k_nut = scene.derived()["nut_axial_stiffness"]
    # (the seat adjuster drives its nut: its axial spring holds it to the
    # frame and carries F)
    assert q["u_nut"] * k_nut == pytest.approx(force, rel=1e-12)
    if torque == 0.0:
        thread = thread_of(scene)[0]
        turn = 0.5e-4 * 2.0 * math.pi / (thread["pitch"] * thread["starts"])
        for name in ("phi_rotor", "phi_nut", "phi_screw"):
            assert abs(q.get(name, 0.0)) <= 1e-12 * turn


def assert_stays_put(scene, start, t_end=0.05):
    """A run from the start stays there: event-driven to its tolerances,
    Moreau-Jean to round-off (tests/test_moreau_holding_theta.py's bounds)."""
    for moreau in (False, True):
        result = (ls.simulate(scene, t_end, integrator="moreau") if moreau
                  else ls.simulate(scene, t_end))
        assert np.max(np.abs(result["phi_drive"] - result["phi_drive"][0])) <= (
            1e-12 if moreau else 1e-8)
        assert np.max(np.abs(result["u_load"] - start["q"]["u_load"])) <= (
            1e-15 if moreau else 1e-10)
        if moreau:
            assert np.all(result["stick"][1:] == 1.0)


@pytest.mark.parametrize("play", list(PLAYS))
@pytest.mark.parametrize("concept", CONCEPTS)
@pytest.mark.parametrize("force", FORCES)
def test_zero_torque_starts_held_by_the_thread(force, concept, play):
    """known_problems.md's reproduction: every concept and play, each force
    of the ten tried (5, 10, 20, 40 and -60 N raised on the flexible
    concept), in 2 to 6 Newton iterations."""
    scene = seat(concept, 0.0, force, play)
    low, high = holding_band(scene, force)
    assert low < 0.0 < high  # (the thread is self-locking: zero is inside)
    start = scene.initial_state()
    assert 1 <= start["iterations"] <= 6
    assert start["v"] == dict.fromkeys(start["q"], 0.0)
    assert_thread_holds(scene, start, 0.0, force)
    assert_springs_carry(scene, start, 0.0, force)


@pytest.mark.parametrize("force", [5.0, 10.0, 20.0, 40.0, -60.0])
def test_the_reported_starts_stay_at_rest(force):
    scene = seat("flexible", 0.0, force, "exact")
    assert_stays_put(scene, scene.initial_state())


def test_with_stops_and_a_motor_at_zero_volts():
    """The stops are placed from the same equilibrium (DriveModel::
    place_stops_at_equilibrium: it raised at construction) and a DC motor at
    0 V gives no torque at rest."""
    scene = ls.scenes.load("seat_adjuster").replace(
        motor={"voltage": 0.0}, loads={"axial_force": 20.0}, initial={"state": "equilibrium"})
    start = scene.initial_state()
    assert_thread_holds(scene, start, 0.0, 20.0)
    assert_springs_carry(scene, start, 0.0, 20.0)
    result = ls.simulate(scene, 0.05, integrator="moreau")
    assert np.max(np.abs(result["phi_drive"] - result["phi_drive"][0])) <= 1e-12


@pytest.mark.parametrize("force", [-300.0, -150.0, -5.0, 5.0, 150.0, 300.0])
@pytest.mark.parametrize("hand", ["right", "left"])
@pytest.mark.parametrize("concept", ["flexible_nut", "flexible"])
def test_without_play_every_coordinate_is_the_closed_forms(concept, force, hand):
    """No play, no torque, constant springs (the thesis drive): every
    coordinate is helpers/static_equilibrium.py's, to round-off. The nut's
    coordinates balance at zero there, and the play's equation was judged
    against round-off of itself: the flexible nut raised at 150 and 300 N."""
    from test_simulation_drive_equilibrium import scene as thesis, springs_of, PITCH
    scene = thesis(concept, 0.0, force, hand)
    start = scene.initial_state()
    expected = closed.screw_driven(0.0, force, PITCH, 1 if hand == "right" else -1,
                                   springs_of(concept))
    for name, value in expected.items():
        assert start["q"][name] == pytest.approx(value, rel=1e-12, abs=1e-18)


@pytest.mark.parametrize("force", [5.0, -60.0])
@pytest.mark.parametrize("side", [0, 1])
def test_beyond_the_band_no_equilibrium_is_named(force, side):
    """A torque 2 % beyond the band's edge: no static equilibrium, refused
    naming initial.state, the loads and the cone (as before the fix)."""
    scene = seat("flexible", 0.0, force)
    torque = 1.02 * holding_band(scene, force)[side]
    with pytest.raises(ls.NoEquilibriumError, match=r'initial\.state = "equilibrium" is invalid'
                       r'.*beyond the static friction cone.*no static equilibrium exists'):
        seat("flexible", torque, force).initial_state()


def test_a_thread_that_is_not_self_locking_has_no_equilibrium_without_torque():
    """mu_static' < tan(alpha): zero torque lies outside the band, the load
    drives the thread."""
    scene = seat("flexible", 0.0, 20.0, friction={"mu": 0.01, "mu_static": 0.01})
    low, high = holding_band(scene, 20.0)
    assert not low < 0.0 < high
    with pytest.raises(ls.NoEquilibriumError, match="the loads drive the thread"):
        scene.initial_state()


@settings(max_examples=40, deadline=None)
@given(force=st.floats(1.0, 400.0) | st.floats(-400.0, -1.0),
       share=st.just(0.0) | st.floats(-0.97, 0.97),
       concept=st.sampled_from(CONCEPTS), play=st.sampled_from(list(PLAYS)))
def test_inside_the_band_an_equilibrium_is_found(force, share, concept, play):
    """Any axial force, any torque inside the band (a share of its edge on
    the torque's side, zero among them), every concept and play: the start
    is found, its thread forces are the closed form's, in the cone, and a
    Moreau-Jean run from it stays put."""
    scene0 = seat(concept, 0.0, force, play)
    low, high = holding_band(scene0, force)
    torque = share * (high if share > 0 else -low)
    scene = seat(concept, torque, force, play)
    start = scene.initial_state()
    assert_thread_holds(scene, start, torque, force)
    assert_springs_carry(scene, start, torque, force)
    result = ls.simulate(scene, 0.02, integrator="moreau")
    assert np.max(np.abs(result["phi_drive"] - result["phi_drive"][0])) <= 1e-12
    assert np.all(result["stick"][1:] == 1.0)
