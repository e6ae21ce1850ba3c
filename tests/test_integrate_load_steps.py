"""Step control around the loads (issue 17 review): what a load's shape lets
an integrator step over, and what it cannot.

A table load is linear between its knots, and its knots are breakpoints the
event-driven and ODE drivers stop and restart at, so no step straddles one
and a root function linear in the loads changes sign at most once between
two of them: however short an interval, it is no reason to cap the steps of
the whole run (it used to be: the shortest interval / 16 bounded every
step, and a 1e-6 s interval in a 10 s run ran into max_steps).

A prescribed speed that steps is an infinite acceleration: no differentiating
scheme follows it. A callable `drive_speed` that jumps is named with the
time and size of its step (it used to end in a generic CV_TOO_MUCH_WORK, an
energy check, or a result with a motor torque spike set by the central
difference's width); Moreau-Jean takes the step as an impulse, as before.
"""

import math

import numpy as np
import pytest

import leadscrew as ls
from helpers.scenes import thesis_scene

T_END = 10.0
RTOL, ATOL = 1e-8, 1e-12


def torque_tables(t_short=3.0, interval=1e-6):
    """The same piecewise-linear torque twice: without and with an extra knot
    `interval` after the knot at `t_short`, on the line between its
    neighbours (so both tables are one function, up to round-off)."""
    times = [0.0, 1.0, t_short, T_END]
    values = [0.0, 0.05, -0.03, 0.02]
    t_extra = t_short + interval
    v_extra = values[2] + (t_extra - times[2]) * (values[3] - values[2]) / (times[3] - times[2])
    with_interval = ([*times[:3], t_extra, times[3]], [*values[:3], v_extra, values[3]])
    return (times, values), with_interval


def table(times, values):
    return {"type": "table", "times": list(times), "values": list(values)}


SCENES = {
    # exact Coulomb, the rigid drive's one-degree-of-freedom path (stick/slip events)
    "rigid_coulomb": dict(concept="rigid"),
    # the regularized law: one ODE, no events
    "rigid_arctan": dict(concept="rigid", friction={"law": "arctan_velocity", "mu": 0.3,
                                                     "k_v": 1e3}),
    # exact play: flights and impacts between the flanks
    "rigid_play": dict(concept="rigid", backlash={"axial": 1e-4, "contact": "exact"}),
}


@pytest.mark.parametrize("name", SCENES)
def test_a_short_table_interval_does_not_cap_the_steps(name):
    """A 1e-6 s interval in a 10 s run: about the steps of the same table
    without it (one restart more), the same answer to the tolerance."""
    plain, short = torque_tables()
    results = []
    for times, values in (plain, short):
        scene = ls.Scene.from_dict(thesis_scene(
            **SCENES[name], loads={"drive_torque": table(times, values), "axial_force": -10.0}))
        results.append(ls.simulate(scene, T_END, rtol=RTOL, atol=ATOL,
                                   t_eval=np.linspace(0.0, T_END, 201)))
    without, with_interval = results
    assert with_interval.stats["steps"] <= 1.2 * without.stats["steps"] + 20, \
        (with_interval.stats["steps"], without.stats["steps"])
    assert [e.kind for e in with_interval.events] == [e.kind for e in without.events]
    for ours, theirs in zip(with_interval.events, without.events):
        assert abs(ours.time - theirs.time) <= 1e-6
    scale = np.max(np.abs(without["u_load"]))
    assert scale > 1e-4  # the drive moves: the comparison means something
    assert np.max(np.abs(with_interval["u_load"] - without["u_load"])) <= 10 * RTOL * scale
    assert with_interval.t[-1] == T_END


def test_a_short_interval_after_the_run_changes_nothing():
    """Knots after t_end are no breakpoints of the run: the same steps, bit
    for bit (a 1e-7 s ramp after t_end used to cap every step at 6e-9 s)."""
    times = [0.0, 1.0, 2.0]
    values = [0.0, 0.04, -0.04]
    ramp = ([*times, 20.0, 20.0 + 1e-7], [*values, -0.04, 0.04])
    runs = []
    for t, v in ((times, values), ramp):
        scene = ls.Scene.from_dict(thesis_scene(
            loads={"drive_torque": table(t, v), "axial_force": -10.0}))
        runs.append(ls.simulate(scene, 2.5))
    assert runs[0].stats["steps"] == runs[1].stats["steps"]
    np.testing.assert_array_equal(runs[0]["u_load"], runs[1]["u_load"])


@pytest.mark.parametrize("friction", ["coulomb", "arctan_velocity"])
def test_the_friction_block_steps_over_a_short_table_interval(friction):
    """The friction block alike (its exact system took the table's shortest
    interval as its step bound)."""
    times = [0.0, 1.0, 1.0 + 1e-6, T_END]
    slope = (4.0 - 6.0) / (T_END - 1.0)
    values = [0.0, 6.0, 6.0 + 1e-6 * slope, 4.0]
    runs = []
    for t, v in (([times[0], times[1], times[3]], [values[0], values[1], values[3]]),
                 (times, values)):
        block = ls.FrictionBlock(mass=1.0, mu=0.3, g=10.0, force=ls.Table(t, v))
        kwargs = {} if friction == "coulomb" else dict(friction=friction, k_v=100.0,
                                                       integrator="cvode_bdf")
        runs.append(ls.simulate(block, T_END, rtol=RTOL, atol=ATOL,
                                t_eval=np.linspace(0.0, T_END, 101), **kwargs))
    without, with_interval = runs
    assert with_interval.stats["steps"] <= 1.2 * without.stats["steps"] + 20
    scale = np.max(np.abs(without["u"]))
    assert scale > 1.0
    assert np.max(np.abs(with_interval["u"] - without["u"])) <= 10 * RTOL * scale


def speed_scene(concept, speed, **changes):
    return ls.Scene.from_dict(thesis_scene(
        concept=concept, loads={"drive_torque": None, "drive_speed": speed,
                                "axial_force": -10.0}, **changes))


def reversal(t):
    return 5.0 if t < 0.05 else -5.0


def start(t):
    return 0.0 if t < 0.05 else 5.0


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut", "flexible"])
@pytest.mark.parametrize("speed, before, after", [(reversal, 5.0, -5.0), (start, 0.0, 5.0)])
def test_a_speed_callable_that_steps_is_named(concept, speed, before, after):
    with pytest.raises(ls.SimulationError) as caught:
        ls.simulate(speed_scene(concept, speed), 0.1)
    error = caught.value
    assert error.time == 0.05  # the first double with the new value
    assert error.reason.startswith(f"loads.drive_speed steps from {before:g} to {after:g} "
                                   "at t = 0.05 s")
    assert "infinite acceleration" in error.reason
    assert "ramp" in str(error) and "table" in str(error) and "moreau" in str(error)


def test_a_speed_step_with_play_is_named_too():
    scene = speed_scene("flexible_nut", reversal, backlash={"axial": 1e-4, "contact": "exact"})
    with pytest.raises(ls.SimulationError, match=r"loads\.drive_speed steps from 5 to -5"):
        ls.simulate(scene, 0.1)


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut", "flexible"])
def test_moreau_takes_a_speed_step_as_an_impulse(concept):
    """On Moreau-Jean's grid (0.05 s is a step time): no error, the rotor at
    the new speed after the step."""
    r = ls.simulate(speed_scene(concept, reversal), 0.1, integrator="moreau", dt=1e-3)
    assert r["omega_drive"][-1] == -5.0
    assert np.all(r["omega_drive"][r.t < 0.049] == 5.0)


@pytest.mark.parametrize("concept", ["rigid", "flexible_nut"])
def test_continuous_speed_callables_run_as_their_excitations(concept):
    """A smooth callable (through its extrema, where the difference's halves
    differ most) and one with kinks run, as the sine and the table they are."""
    cases = [(lambda t: 5.0 * math.sin(10.0 * t), ls.Sine(5.0, 10.0)),
             (lambda t: min(100.0 * t, 5.0) if t < 0.2 else max(5.0 - 100.0 * (t - 0.2), -5.0),
              ls.Table([0.0, 0.05, 0.2, 0.3], [0.0, 5.0, 5.0, -5.0]))]
    for function, excitation in cases:
        t = np.linspace(0.0, 0.5, 51)
        ours = ls.simulate(speed_scene(concept, function), 0.5, t_eval=t, rtol=RTOL, atol=ATOL)
        theirs = ls.simulate(speed_scene(concept, excitation), 0.5, t_eval=t, rtol=RTOL,
                             atol=ATOL)
        scale = np.max(np.abs(theirs["u_load"]))
        assert scale > 1e-5
        assert np.max(np.abs(ours["u_load"] - theirs["u_load"])) <= 10 * RTOL * scale
