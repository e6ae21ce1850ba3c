"""Exact end stops where the load is rigid in the thread (issue 32, item 3):
the rigid drive (one degree of freedom) and the nut-driven flexible nut.
docs/physics/end_stops.md, "The rigid drive at an exact stop": Newton's
restitution on the load's velocity through the frictional thread, the
closed stop holding the drive and carrying the loads (the thread's friction
0 while it holds: the rule), its opening an event where its force would
pull, the thread deciding stick or slip then; the Painleve regime at the
impact a JammingError. Closed forms with tan a = p / r, p = lead / 2 pi:
u_load = -h p phi, the generalized force M - h p F on phi, the stick
interval F r (t + mu') / (1 - mu' t) <= M <= F r (t - mu') / (1 + mu' t)
(docs/physics/rigid_drive.md, section 5, 6)."""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers.result_invariants import check_result, failed
from helpers.scenes import thesis_scene

# The invariants read each run step by step.
pytestmark = pytest.mark.usefixtures("every_step")

FACE = 1e-4  # the upper stop's face [m]


def stop_scene(mu, restitution, torque, force, pitch=1e-3, **changes):
    """The thesis's rigid drive (right-hand, screw-driven, flank angle 0:
    mu' = mu) from rest, its load 0.1 mm below an exact upper stop."""
    return thesis_scene(thread={"pitch": pitch}, friction={"law": "coulomb", "mu": mu},
                        loads={"drive_torque": torque, "axial_force": force},
                        end_stops={"upper": FACE, "contact": "exact",
                                   "restitution": restitution}, **changes)


def drive_constants(scene):
    """(m, J, p, r): the translating mass (load and nut), the rotating
    inertia (rotor and screw), lead / 2 pi and the mean radius."""
    derived = ls.Scene.from_dict(scene).derived()
    m = scene["load"]["mass"] + derived["nut_mass"]
    inertia = scene["rotor"]["inertia"] + derived["screw_inertia"]
    return m, inertia, scene["thread"]["pitch"] / (2 * math.pi), 0.01


def ramp(start, end, duration):
    """A drive torque from `start` to `end` over `duration`, then held."""
    return {"type": "table", "times": [0.0, duration, 10.0], "values": [start, end, end]}


def assert_invariants(result, scene, t_end, **options):
    assert [k for k, c in result.checks.items() if c["applies"] and not c["passed"]] == []
    options = {**options, "t_end": t_end}
    assert failed(check_result(result, ls.Scene.from_dict(scene).to_dict(), options)) == []


def rows_at(result, time):
    rows = np.flatnonzero(result.t == time)
    return rows[0], rows[-1]


# --- impacts --------------------------------------------------------------------


@pytest.mark.parametrize("restitution", [1.0, 0.5, 0.2])
def test_a_frictionless_rigid_drive_bounces_to_e_squared_of_its_drop(restitution):
    # A constant torque accelerates the drive from rest: the load reaches
    # the face 0.1 mm ahead at v = a t1, a = p M / (J + m p^2), leaves at
    # -e v, climbs back to e^2 of the drop and returns at t1 + 2 e v / a.
    torque = -0.02
    scene = stop_scene(0.0, restitution, torque, 0.0)
    m, inertia, p, _ = drive_constants(scene)
    a = p * -torque / (inertia + m * p * p)
    t1 = math.sqrt(2 * FACE / a)
    v = a * t1
    t_end = t1 + 3 * restitution * v / a
    result = ls.simulate(ls.Scene.from_dict(scene), t_end, rtol=1e-10, atol=1e-14)
    impacts = [e for e in result.events if "upper end stop impact" in e.kind]
    assert impacts[0].time == pytest.approx(t1, rel=1e-9)
    assert impacts[1].time == pytest.approx(t1 + 2 * restitution * v / a, rel=1e-8)
    first, after = rows_at(result, impacts[0].time)
    assert result["v_load"][first] == pytest.approx(v, rel=1e-9)
    assert result["v_load"][after] == pytest.approx(-restitution * v, rel=1e-12)
    apex = t1 + restitution * v / a
    lowest = ls.simulate(ls.Scene.from_dict(scene), t_end, rtol=1e-10, atol=1e-14,
                         t_eval=[apex])["u_load"][0]
    assert FACE - lowest == pytest.approx(restitution ** 2 * FACE, rel=1e-8)
    # The loss: the kinetic energy of the whole drive, (m + J / p^2) v^2 / 2,
    # less its rebound's.
    loss = 0.5 * (m + inertia / p ** 2) * (1 - restitution ** 2) * v ** 2
    assert result["impact_loss"][after] == pytest.approx(loss, rel=1e-9)
    assert_invariants(result, scene, t_end, rtol=1e-10, atol=1e-14)


@pytest.mark.parametrize("restitution", [0.8, 0.3])
def test_the_rebound_through_a_frictional_thread_is_newtons(restitution):
    # A steep thread (5 mm lead: tan a = 0.0796 > mu' = 0.03, the stop
    # back-drives it): the impulse passes through the sliding thread
    # (compression along the approach's slip, expansion reversed), and the
    # load leaves at -e times its approach speed; the loss is the kinetic
    # energy's drop, friction's and restitution's together.
    scene = stop_scene(0.03, restitution, -0.05, 0.0, pitch=5e-3)
    m, inertia, p, _ = drive_constants(scene)
    result = ls.simulate(ls.Scene.from_dict(scene), 0.05, rtol=1e-10, atol=1e-14)
    impact = next(e for e in result.events if "upper end stop impact" in e.kind)
    before, after = rows_at(result, impact.time)
    v = result["v_load"][before]
    assert v > 0.0
    assert result["v_load"][after] == pytest.approx(-restitution * v, rel=1e-12)
    loss = 0.5 * (m + inertia / p ** 2) * (1 - restitution ** 2) * v ** 2
    assert result["impact_loss"][after] - result["impact_loss"][before] == pytest.approx(
        loss, rel=1e-9)
    assert_invariants(result, scene, 0.05, rtol=1e-10, atol=1e-14)


def test_a_self_locking_thread_keeps_the_drive_at_the_stop_without_rebound():
    # tan a = 0.0159 <= mu' = 0.3: after the compression the stop's
    # expansion impulse cannot back-drive the thread, which sticks: the
    # drive stays at the face whatever e (no rebound, the whole kinetic
    # energy lost), held there while the torque presses it on.
    scene = stop_scene(0.3, 0.9, -0.05, 0.0)
    m, inertia, p, _ = drive_constants(scene)
    result = ls.simulate(ls.Scene.from_dict(scene), 0.05)
    impact = next(e for e in result.events if "upper end stop impact" in e.kind)
    assert "closed" in impact.kind
    before, after = rows_at(result, impact.time)
    v = result["v_load"][before]
    assert result["v_load"][after] == 0.0
    assert result["impact_loss"][after] == pytest.approx(0.5 * (m + inertia / p ** 2) * v ** 2,
                                                         rel=1e-9)
    held = result.t >= impact.time
    # (on the face to round-off: the load's position follows the rotor's)
    assert np.max(np.abs(result["u_load"][held] - FACE)) <= 64 * np.finfo(float).eps * FACE
    assert_invariants(result, scene, 0.05)


# --- the closed stop: the rule ----------------------------------------------------


@pytest.mark.parametrize("integrator", ["event_driven", "moreau"])
def test_the_closed_stop_carries_the_loads_and_the_friction_nothing(integrator):
    # A self-locking drive (mu = 0.3) pressed into the stop by a torque and
    # an axial force of 20 N; the torque then ramps to zero ("released").
    # Held, the stop's force is the loads' balance with the thread's
    # friction 0 (the rule): stop_force = M / (h p) - F; after the release
    # the stop carries the axial force alone, -20 N: the clamp the torque
    # made is not kept (a rigid model has no compliance to store it).
    force = 20.0
    scene = stop_scene(0.3, 0.0, ramp(-0.1, 0.0, 0.3), force)
    _, _, p, _ = drive_constants(scene)
    t_eval = np.linspace(0.0, 0.4, 401)
    options = {"integrator": "moreau", "dt": 1e-5} if integrator == "moreau" else {}
    result = ls.simulate(ls.Scene.from_dict(scene), 0.4, t_eval=t_eval, **options)
    reached = result.t[np.argmax(result["u_load"] >= FACE - 1e-7)]
    assert 0.0 < reached < 0.1
    held = result.t > reached + 0.002
    assert np.all(result["v_load"][held] == 0.0)
    assert np.all(np.abs(result["u_load"][held] - FACE) <= 1e-7)
    # (Moreau-Jean's step takes the torque at t - (1 - theta) h, the ramp's
    # slope 1/3 N m/s; its row the impulse over the step ending at t)
    torque = result["drive_torque"][held] - (0.5 * 1e-5 / 3.0 if options else 0.0) * (
        result.t[held] <= 0.3 + 1e-12)
    expected = torque / p - force
    np.testing.assert_allclose(result["stop_force"][held], expected, rtol=1e-9,
                               atol=1e-9 * force)
    assert np.all(result["friction_force"][held] == 0.0)
    assert result["stop_force"][-1] == pytest.approx(-force, rel=1e-9)
    assert not [e for e in result.events if "opens" in e.kind]
    assert_invariants(result, scene, 0.4, t_eval=list(t_eval), **options)


def stick_interval(force, mu, t, r):
    """The torques that hold the drive at rest under the axial force F
    (rigid_drive.md, section 6, h = +1, flank angle 0)."""
    return (force * r * (t + mu) / (1 - mu * t), force * r * (t - mu) / (1 + mu * t))


@pytest.mark.parametrize("mu, pitch, end", [
    (0.3, 1e-3, 0.1),     # self-locking: held after the release until the torque drives it
    (0.03, 5e-3, 0.0),    # not self-locking: the pull back-drives it at the interval's edge
])
def test_the_stop_opens_where_its_force_would_pull_and_the_thread_decides(mu, pitch, end):
    # F = -20 N pulls the load off the stop, a torque ramping from -0.1 N m
    # presses it on. The stop's force M / p - F reaches 0 at M = p F: the
    # stop opens there (an event). The thread then sticks while M lies in
    # the stick interval and the drive leaves the face at its upper edge,
    # F r (t - mu') / (1 + mu' t), at the closed-form time of the ramp.
    force, start, duration = -20.0, -0.1, 0.5
    scene = stop_scene(mu, 0.0, ramp(start, end, duration), force, pitch=pitch)
    _, _, p, r = drive_constants(scene)
    t = p / r
    low, high = stick_interval(force, mu, t, r)
    assert low < p * force < high < end
    at = lambda torque: (torque - start) / (end - start) * duration  # noqa: E731
    result = ls.simulate(ls.Scene.from_dict(scene), duration, rtol=1e-10, atol=1e-14)
    kinds = [(e.time, e.kind) for e in result.events]
    opens = next(time for time, kind in kinds if "upper end stop opens" in kind)
    assert opens == pytest.approx(at(p * force), rel=1e-7)
    leaves = next(time for time, kind in kinds if time > opens and "stick->slip" in kind)
    assert leaves == pytest.approx(at(high), rel=1e-7)
    between = (result.t > opens) & (result.t < leaves)
    assert np.all(result["v_load"][between] == 0.0)
    assert np.all(result["stop_force"][between] == 0.0)
    assert result["u_load"][-1] < FACE - 1e-9  # it left
    assert_invariants(result, scene, duration, rtol=1e-10, atol=1e-14)


def test_moreau_jean_converges_to_the_event_driven_run_at_first_order():
    # The non-self-locking drive driven into the stop (plastic), held,
    # released and back-driven off it by the axial force: the load's path
    # converges to the event-driven run's at first order in dt. Moreau-Jean
    # meets the face on the velocity level a step late: the held load lies
    # beyond it by (1 - theta) h u' times the impact's phase in its step,
    # which dt = t_impact / (N + 1/4) holds fixed (measured order 1.000;
    # at an arbitrary dt that phase scatters the error within the bound).
    scene = stop_scene(0.03, 0.0, ramp(-0.05, 0.0, 0.3), -20.0, pitch=5e-3)
    s = ls.Scene.from_dict(scene)
    t_end = 0.3
    t_eval = np.linspace(0.0, t_end, 301)
    exact = ls.simulate(s, t_end, rtol=1e-11, atol=1e-14, t_eval=t_eval)
    kinds = [e.kind for e in exact.events]
    assert "closed" in kinds[0] and "opens" in kinds[1] and "stick->slip" in kinds[2], kinds
    impact = exact.events[0].time
    dts, errors = [], []
    for target in (4e-5, 2e-5, 1e-5, 5e-6):
        dt = impact / (round(impact / target) + 0.25)
        options = {"integrator": "moreau", "dt": dt}
        result = ls.simulate(s, t_end, t_eval=t_eval, **options)
        assert_invariants(result, scene, t_end, t_eval=list(t_eval), **options)
        dts.append(dt)
        errors.append(np.max(np.abs(result["u_load"] - exact["u_load"])))
    order = np.polyfit(np.log(dts), np.log(errors), 1)[0]
    assert 0.95 < order < 1.05, (errors, order)
    assert errors[-1] < 1e-4 * np.ptp(exact["u_load"])


@pytest.mark.parametrize("integrator", ["event_driven", "moreau"])
def test_the_energy_account_closes_through_bounces_holds_and_releases(integrator):
    # A sine torque rattles the rigid drive between two exact stops 0.2 mm
    # apart with e = 0.5 and friction: impacts, closings, openings, sticks
    # and slips; the account closes, friction never works positively, the
    # load never passes a face (the invariants).
    scene = thesis_scene(friction={"law": "coulomb", "mu": 0.05},
                         loads={"drive_torque": {"type": "sine", "amplitude": 0.1,
                                                 "omega": 30.0}, "axial_force": 5.0},
                         end_stops={"lower": -1e-4, "upper": 1e-4, "contact": "exact",
                                    "restitution": 0.5})
    options = {"integrator": "moreau", "dt": 1e-5} if integrator == "moreau" else {}
    result = ls.simulate(ls.Scene.from_dict(scene), 0.5, **options)
    if integrator == "event_driven":
        kinds = " ".join(e.kind for e in result.events)
        assert "lower end stop impact" in kinds and "upper end stop impact" in kinds
        assert "opens" in kinds
    scale = np.max(np.abs(result["work_drive"])) + np.max(np.abs(result["work_axial"]))
    assert result["impact_loss"][-1] > 0.0 or integrator == "moreau"
    assert np.max(np.abs(result["energy_residual"])) <= (1e-6 if integrator == "event_driven"
                                                         else 1.0) * scale
    assert_invariants(result, scene, 0.5, **options)


# --- the Painleve regime and the other concepts -------------------------------


@pytest.mark.parametrize("force, stops", [(50.0, {"upper": FACE}), (-50.0, {"lower": -FACE})])
def test_the_painleve_regime_raises_jamming_before_the_stop(force, stops):
    # tan a = 1.73 (lead 109 mm on r = 10 mm), mu' = 0.8, a heavy rotor:
    # Delta_- = J (1 - mu' t) + m r^2 t (t + mu') < 0 < Delta_+. Every load
    # has both or no consistent sign of the normal force then, the stop's
    # impulse among them (the same Delassus terms): the drive jams at its
    # first slip and never reaches its stop (end_stops.md, "Impacts").
    pitch = 2 * math.pi * 0.01 * math.sqrt(3.0)
    scene = stop_scene(0.8, 0.0, 0.0, force, pitch=pitch, rotor={"inertia": 1e-2})
    scene["end_stops"] = {**stops, "contact": "exact"}
    m, inertia, p, r = drive_constants(scene)
    t = p / r
    assert inertia * (1 - 0.8 * t) + m * r * r * t * (t + 0.8) < 0.0
    assert inertia * (1 + 0.8 * t) + m * r * r * t * (t - 0.8) > 0.0
    with pytest.raises(ls.JammingError, match="Painleve condition .* [(]holds[)]"):
        ls.simulate(ls.Scene.from_dict(scene), 0.2)


SINE = {"type": "sine", "amplitude": -0.05, "omega": 40.0}  # [N m], [rad/s]


@pytest.mark.parametrize("integrator", ["event_driven", "moreau"])
@pytest.mark.parametrize("changes", [
    {},
    {"drive": "nut"},
    {"concept": "flexible_nut", "drive": "nut"},
    {"backlash": {"axial": 2e-5, "contact": "bistop"}},
    {"backlash": {"axial": 2e-5, "contact": "cubic"}},
    {"concept": "flexible_nut", "drive": "nut", "backlash": {"axial": 2e-5, "contact": "bistop"}},
])
def test_every_concept_and_play_runs_exact_stops(changes, integrator):
    # The load rigid in the thread (the nut-driven drives carry it on the
    # screw) or on a penalty flank's spring: a sine torque and 30 N drive it
    # into the stop, it bounces (e = 0.3) or is held (the self-locking
    # thread: no rebound), is released and driven in again; the invariants
    # hold (the energy account, friction's work, the
    # load never beyond the face by more than the root's resolution or
    # Moreau-Jean's step).
    scene = stop_scene(0.1, 0.3, SINE, 30.0, **changes)
    options = {"integrator": "moreau", "dt": 1e-5} if integrator == "moreau" else {}
    result = ls.simulate(ls.Scene.from_dict(scene), 0.5, **options)
    assert np.max(result["u_load"]) <= FACE + 1e-7
    # It pushed the load back (toward -u), never pulled (but for an
    # opening's root, where the force passes 0 within its resolution).
    force = result["stop_force"]
    assert np.min(force) < -1.0 and np.max(force) <= 1e-9 * -np.min(force)
    if integrator == "event_driven":
        assert any("upper end stop impact" in e.kind for e in result.events)
    assert_invariants(result, scene, 0.5, **options)


@pytest.mark.parametrize("restitution", [0.0, 0.5])
@pytest.mark.parametrize("mu", [0.0, 0.05, 0.3])
@pytest.mark.parametrize("concept, drive", [("rigid", "screw"), ("rigid", "nut"),
                                            ("flexible_nut", "nut")])
def test_exact_play_runs_on_moreau_jean_where_the_load_rides_on_the_flank(concept, drive, mu,
                                                                         restitution):
    # A flank's impact while the stop holds the load is two impacts at once
    # on a tied body: Moreau-Jean's step solves them as its rows (the
    # scene's default and only integrator); the event-driven scheme is
    # refused naming the keys (unrefused it passed the flank by 0.6 mm or
    # jammed on the stop's impulse through a closed flank that had to open),
    # a smooth law too. Two exact stops, 0.2 mm apart, a sine torque.
    scene = stop_scene(mu, restitution, {**SINE, "amplitude": -0.2}, 10.0, concept=concept,
                       drive=drive, backlash={"axial": 2e-5, "contact": "exact"})
    scene["end_stops"]["lower"] = -FACE
    s = ls.Scene.from_dict(scene)
    options = {"integrator": "moreau", "dt": 1e-5}
    result = ls.simulate(s, 0.4, dt=1e-5)
    assert result.integrator == "moreau"
    assert np.min(result["stop_force"]) < -1.0  # (the upper stop pushed it back)
    assert_invariants(result, scene, 0.4, **options)
    with pytest.raises(ValueError, match="integrator = .event_driven. is invalid with "
                                         "end_stops.contact = .exact. and backlash.contact"):
        ls.simulate(s, 0.4, integrator="event_driven")
    scene["friction"] = {"law": "lugre", "mu": 0.1}
    with pytest.raises(ValueError, match="which Moreau-Jean's step takes with a set-valued "
                                         "law only"):
        ls.Scene.from_dict(scene)


@pytest.mark.parametrize("integrator", ["event_driven", "moreau"])
def test_a_speed_controlled_rotor_driving_the_rigid_drive_into_the_stop_fails(integrator):
    # The prescribed speed and the rigid stop both fix the one degree of
    # freedom: an infinite impulse, a SimulationError at the impact; the
    # same drive turning away from the stop runs.
    options = {"integrator": "moreau", "dt": 1e-5} if integrator == "moreau" else {}
    scene = stop_scene(0.1, 0.0, None, 0.0)
    for speed in (-50.0, 50.0):
        scene["loads"] = {"drive_speed": speed, "axial_force": 0.0}
        s = ls.Scene.from_dict(scene)
        if speed < 0.0:
            with pytest.raises(ls.SimulationError, match="an infinite impulse") as raised:
                ls.simulate(s, 0.05, **options)
            assert raised.value.time == pytest.approx(FACE / (50.0 * 1e-3 / (2 * math.pi)),
                                                      abs=1.1e-5)
        else:
            assert np.all(ls.simulate(s, 0.05, **options)["stop_force"] == 0.0)


# --- an equilibrium start -----------------------------------------------------


@pytest.mark.parametrize("integrator", ["event_driven", "moreau"])
@pytest.mark.parametrize("stops", [{"upper": 2e-4, "contact": "exact", "restitution": 0.3},
                                   {"upper": 2e-4, "stiffness": 1e7, "damping": 1e3}])
def test_an_equilibrium_start_places_the_stops_relative_to_it(stops, integrator):
    # The flexible drive under -200 N starts in static equilibrium, its load
    # at u0 != 0 (the springs' deflection): the stops' faces are relative
    # to the load's start, u0 + upper; the start is the drive's equilibrium
    # without stops (they exert nothing there). A torque ramp then drives
    # the load into the upper stop, which it meets at u0 + upper.
    torque = {"type": "table", "times": [0.0, 0.05, 0.1, 10.0],
              "values": [0.0, 0.0, -1.5, -1.5]}
    scene = thesis_scene(concept="flexible", loads={"drive_torque": torque,
                                                    "axial_force": -200.0},
                         initial={"state": "equilibrium"}, end_stops=stops)
    options = {"integrator": "moreau", "dt": 1e-5} if integrator == "moreau" else {}
    free = dict(scene)
    free.pop("end_stops")
    u0 = ls.simulate(ls.Scene.from_dict(free), 0.01, **options)["u_load"][0]
    assert abs(u0) > 1e-5
    result = ls.simulate(ls.Scene.from_dict(scene), 0.3, **options)
    assert result["u_load"][0] == u0 and result["v_load"][0] == 0.0
    face = u0 + 2e-4
    touching = result["stop_force"] != 0.0
    first = np.argmax(touching)
    # (Moreau-Jean meets the face within a step's travel)
    reach = 1e-9 + (np.max(np.abs(result["v_load"])) * 1e-5 if options else 0.0)
    assert touching[first] and np.all(result["u_load"][:first] < face + reach)
    assert result["u_load"][first] >= face - reach
    if integrator == "event_driven":
        meets = next(e.time for e in result.events if "upper end stop" in e.kind)
        row = np.flatnonzero(result.t == meets)[0]
        assert result["u_load"][row] == pytest.approx(face, abs=1e-12)
    assert_invariants(result, scene, 0.3, **options)


# --- the stepper ------------------------------------------------------------------


@pytest.mark.parametrize("concept, drive", [("rigid", "screw"), ("flexible_nut", "nut")])
def test_the_stepper_keeps_the_tied_load_held_across_its_pieces(concept, drive):
    # The axial force changed at every piece (each rebuilds the run): the
    # load closed on the stop stays held (a tied load carries its
    # coordinates' round-off, 4e-20 m/s: a resume that asked for exact rest
    # left the stop open with the gap at 0, and the load passed it by 3 um).
    from leadscrew import _core

    scene = ls.Scene.from_dict(thesis_scene(
        concept=concept, drive=drive, friction={"mu": 0.1},
        loads={"drive_torque": 0.05, "axial_force": -40.0},
        end_stops={"lower": -1e-6, "contact": "exact"}))
    stepper = _core.DriveStepper(scene.model(), "", "", 1e-8, 1e-12, 1_000_000, 100_000, 0.0,
                                 0.0, 1e-6, 0)
    for k in range(1, 11):
        stepper.set_input("axial_force", -40.0 - k)
        stepper.advance(0.01 * k)
    closings = [kind for _, kind in stepper.events if "lower end stop" in kind]
    assert len(closings) == 1 and "closed" in closings[0], closings
    assert abs(stepper.channel("u_load") + 1e-6) <= 1e-20
    assert abs(stepper.channel("v_load")) <= 1e-15
    if concept == "rigid":  # the rule: M / (h p) - F, the friction 0
        p = 1e-3 / (2 * math.pi)
        assert stepper.channel("stop_force") == pytest.approx(0.05 / p + 50.0, rel=1e-9)
