"""Explicit engines on stiff problems say so at once (issue 31, reproduction
11 (a)): the own Runge-Kutta engines carry Hairer's stiffness test (DOPRI5's,
for any tableau with two evaluations at c = 1: rk_stiffness.hpp), and where
the step size is held at the method's stability boundary and the rest of
the run would take more steps than max_steps leaves, they stop with
RK_STIFF and the hint to use cvode_bdf, not after max_steps steps (a
flexible drive on rk_verner6 took over a minute to reach RK_TOO_MUCH_WORK)."""

import math
import time

import numpy as np
import pytest

import leadscrew as ls
from leadscrew import integrate as li
from helpers.scenes import thesis_scene

EXPLICIT_OWN = ["rk_dopri5", "rk_verner6"]
# ARKODE's explicit methods: no stiffness test of their own; their budget is
# watched (sundials_integrator.cpp, check_budget).
EXPLICIT_ARKODE = ["dopri5", "verner6"]


def stiff(t, y):
    """y' = -1e6 (y - cos t): lambda = -1e6."""
    return -1e6 * (y - math.cos(t))


def stiff_failure(method):
    """The SimulationError of 10 s of ``stiff`` on ``method`` within 1e6
    steps (found within 20 s of wall time), and its message."""
    start = time.perf_counter()
    with pytest.raises(ls.SimulationError) as error:
        li.solve_ode(stiff, (0.0, 10.0), [0.0], method=method, t_eval=[10.0],
                     max_steps=1_000_000)
    assert time.perf_counter() - start < 20.0
    return error.value, str(error.value)


@pytest.mark.parametrize("method, boundary", [("rk_dopri5", 3.3066), ("rk_verner6", 4.0648)])
def test_the_step_is_found_held_at_the_stability_boundary(method, boundary):
    # Over 10 s the stability limit h = boundary / 1e6 takes 2.5e6 to 3e6
    # steps, beyond the budget of 1e6: found stiff at its first test after
    # 1,000 steps, the run stops once the stiffness has lasted for 1,000
    # steps more (2,015 steps of 3.3e-6 to 4.1e-6 s: t < 0.01 s), with h
    # lambda at the method's
    # stability boundary on the negative real axis (DOPRI5's 3.3066, Hairer
    # & Wanner II, IV.2; Verner 6(5)'s computed from its tableau).
    error, message = stiff_failure(method)
    assert "RK_STIFF" in message and "use an implicit method" in message
    assert "cvode_bdf" in message
    assert error.time < 0.01
    h = float(message.split("held at h = ")[1].split(" s")[0])
    assert h * 1e6 == pytest.approx(boundary, rel=0.02)


@pytest.mark.parametrize("method", EXPLICIT_OWN + EXPLICIT_ARKODE)
def test_a_stiff_run_that_fits_its_budget_finishes(method):
    # 0.1 s at the stability limit: some 3e4 steps, within the budget; the
    # answer is the smooth solution cos t + 1e-6 sin t after the layer, to
    # the tolerance (rtol 1e-8 of |y| ~ 1: the local errors of 3e4 steps
    # held by stability, not accuracy, stay far below it each; ARKODE's
    # pieces of 10,000 steps give the solution one call gives).
    sol = li.solve_ode(stiff, (0.0, 0.1), [1.0], method=method, t_eval=[0.1])
    assert sol.stats["steps"] > 20_000  # (held at the limit, 0.1 s / 3.4e-6 s)
    assert sol.y[0, -1] == pytest.approx(math.cos(0.1) + 1e-6 * math.sin(0.1), abs=1e-8)


def test_a_stiff_drive_on_rk_verner6_fails_fast_with_the_hint():
    # A flexible nut held by a speed-controlled motor at rest (drive_speed
    # 0) under the velocity-regularized law with k_v = 1e4 s/m: at zero slip
    # the law's slope mu' |N| k_v (2/pi) damps the nut's light body at some
    # 7e6 1/s, and rk_verner6's steps are held near 5.5e-7 s. 10 s would take
    # 1.6e7 steps against a budget of 1e7 (held later at 1e-6 s, it took
    # 1e6 steps per simulated second before, some 45 s); it stops once the
    # stiffness has lasted for 1,000 steps (a few thousand steps of 6e-7 to
    # 1e-6 s: t < 0.05 s). cvode_bdf answers in a few thousand steps.
    scene = ls.Scene.from_dict(thesis_scene(
        concept="flexible_nut", friction={"law": "arctan_velocity", "mu": 0.3, "k_v": 1e4},
        loads={"drive_torque": None, "drive_speed": 0.0, "axial_force": -10.0}))
    start = time.perf_counter()
    with pytest.raises(ls.SimulationError) as error:
        ls.simulate(scene, 10.0, integrator="rk_verner6")
    assert time.perf_counter() - start < 20.0
    message = str(error.value)
    assert "RK_STIFF" in message and "cvode_bdf" in message
    assert error.value.time < 0.05
    r = ls.simulate(scene, 1.0, integrator="cvode_bdf", t_eval=np.linspace(0.0, 1.0, 3))
    assert r.t[-1] == 1.0 and r.stats["steps"] < 20_000


@pytest.mark.parametrize("method", EXPLICIT_ARKODE)
def test_arkode_explicit_methods_stop_where_the_rest_cannot_fit_the_budget(method):
    # ARKODE's explicit methods have no stiffness test of their own: their
    # budget is watched over every 10,000 steps (sundials_integrator.cpp,
    # check_budget). Over 10 s at the stability limit (~3e-6 s) the rest
    # takes some 3e6 steps against the 1e6 of max_steps: three pieces in a
    # row say so, and the run stops after 30,000 steps (t < 0.1 s), not
    # after 1e6 (ARK_TOO_MUCH_WORK).
    error, message = stiff_failure(method)
    assert "ARK_STIFF" in message and "cvode_bdf" in message and "max_steps" in message
    assert error.time < 0.2  # (30,000 steps of at most 4.1e-6 s: 0.12 s)
    h = float(message.split("held its step at h = ")[1].split(" s")[0])
    assert 1e-7 < h < 1e-5  # (held near the stability limit, some 3e-6 s)


@pytest.mark.parametrize("method", EXPLICIT_ARKODE)
def test_a_stiff_drive_on_arkode_fails_fast_with_the_hint(method):
    # The stiff drive above (rk_verner6's) on ARKODE's explicit methods as
    # the smooth integrator of the event-driven scheme with sampled output,
    # 10 s with a budget of 2e6 steps (their steps near 1e-6 s need some 1e7):
    # before the budget's watch, dopri5 ran 31 s to ARK_TOO_MUCH_WORK at
    # t = 8.2 s of 10 with the default budget (1e6 per simulated second),
    # which it still exceeds (1.2e7 projected). (verner6 fits that default
    # budget, 9.9e6 steps: it goes on, in some 40 s, as a run that fits must.)
    scene = ls.Scene.from_dict(thesis_scene(
        concept="flexible_nut", friction={"law": "arctan_velocity", "mu": 0.3, "k_v": 1e4},
        loads={"drive_torque": None, "drive_speed": 0.0, "axial_force": -10.0}))
    start = time.perf_counter()
    with pytest.raises(ls.SimulationError) as error:
        ls.simulate(scene, 10.0, integrator=method, max_steps=2_000_000)
    assert time.perf_counter() - start < 20.0
    message = str(error.value)
    assert "ARK_STIFF" in message and "cvode_bdf" in message
    assert error.value.time < 0.1
