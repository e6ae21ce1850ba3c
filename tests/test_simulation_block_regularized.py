"""The regularized friction laws of the block (thesis eq. 3.15, 3.16) at the
level of a single evaluation: the acceleration that eq. (3.15) defines is
solved to rounding level at every output point, against an independent
bisection; eq. (3.16) and the equation of motion hold bit for bit or to
rounding; and the result object converts lazily but completely."""

import math
import pickle

import numpy as np
import pytest

import leadscrew as ls

MASS, MU, G, OMEGA = 1.0, 0.3, 10.0, 4 * math.pi
SCALE = 2.0 / math.pi * MU * MASS * G  # (2/pi) mu lambda_N
EPS = np.finfo(float).eps


def block(amplitude=6.0, mass=MASS):
    return ls.FrictionBlock(mass, MU, g=G, force=ls.Sine(amplitude, OMEGA))


def acceleration_by_bisection(force, k_v, mass=MASS):
    """The root of m a + (2/pi) mu N atan(k_V a) = F by plain bisection on
    [(F - mu N)/m, (F + mu N)/m] down to adjacent floating-point numbers:
    slow, independent of the core's Newton-type solver."""
    bound = MU * mass * G
    low, high = (force - bound) / mass, (force + bound) / mass
    for _ in range(2000):
        middle = 0.5 * (low + high)
        if middle in (low, high):
            break
        if mass * middle + SCALE * mass * math.atan(k_v * middle) - force > 0.0:
            high = middle
        else:
            low = middle
    return low, high


@pytest.mark.parametrize("k_v", [1.0, 10.0, 100.0, 1e3, 1e4])
@pytest.mark.parametrize("integrator", ["rk_dopri5", "rk_verner6", "cvode_bdf"])
def test_acceleration_law_is_solved_to_rounding(k_v, integrator):
    r = ls.simulate(block(), 2.0, friction="arctan_acceleration", k_v=k_v, integrator=integrator,
                    rtol=1e-6, atol=1e-8)
    force, a = r["force"], r["acceleration"]
    # Eq. (3.15) residual: rounding of its largest term.
    residual = MASS * a + SCALE * np.arctan(k_v * a) - force
    terms = np.abs(MASS * a) + SCALE * np.abs(np.arctan(k_v * a)) + np.abs(force)
    assert np.all(np.abs(residual) <= 8 * EPS * terms)
    # Against bisection, to the root's condition: a residual at rounding
    # level eps * terms moves the root by that over r'(a) = m + c k_V q.
    slope = MASS + SCALE * k_v / (1.0 + (k_v * a) ** 2)
    for i in range(0, len(force), max(1, len(force) // 40)):
        low, high = acceleration_by_bisection(force[i], k_v)
        width = 8 * EPS * terms[i] / slope[i]
        assert low - width <= a[i] <= high + width, (force[i], a[i], low, high)
    # The friction force is what eq. (3.9) leaves of the load.
    np.testing.assert_array_equal(r["friction_force"], force - MASS * a)
    assert np.all(np.abs(r["friction_force"]) < MU * MASS * G)


def test_acceleration_solve_takes_one_or_two_arctan_evaluations():
    # A cost figure of the solver (cubic predictor from the last root, Newton
    # and Chebyshev correctors stopped by their error bounds): measured 0.94,
    # 1.19 and 1.49 arctan evaluations per right-hand side (memo hits
    # included) for k_V = 1, 10, 100; Newton from the last root, stopped by a
    # step below an ulp, took ~4.
    for k_v in (1.0, 10.0, 100.0):
        r = ls.simulate(block(), 2.0, friction="arctan_acceleration", k_v=k_v,
                        integrator="rk_dopri5", rtol=1e-7, atol=1e-9)
        stats = r.stats
        assert stats["nonlinear_iterations"] <= 1.8 * stats["rhs_evaluations"], (k_v, stats)


def test_acceleration_law_with_a_heavy_block_and_far_from_the_last_root():
    # m != 1 (the scale of a enters the stopping rule) and a load with jumps
    # (a table: the first evaluation after a knot starts far from the last root).
    table = ls.Table([0.0, 0.1, 0.1 + 1e-9, 0.3, 0.5], [0.0, 40.0, -40.0, 5.0, 0.0])
    heavy = ls.FrictionBlock(7.5, MU, g=G, force=table)
    r = ls.simulate(heavy, 0.5, friction="arctan_acceleration", k_v=1e3, integrator="rk_dopri5",
                    rtol=1e-8, atol=1e-10)
    a, force = r["acceleration"], r["force"]
    residual = 7.5 * a + 2.0 / math.pi * MU * 7.5 * G * np.arctan(1e3 * a) - force
    assert np.all(np.abs(residual) <= 8 * EPS * (np.abs(7.5 * a) + np.abs(force) + MU * 7.5 * G))


@pytest.mark.parametrize("integrator", ["rk_dopri5", "rk_verner6", "cvode_adams"])
def test_velocity_law_channels_are_the_law(integrator):
    k_v = 10.0
    r = ls.simulate(block(), 2.0, friction="arctan_velocity", k_v=k_v, integrator=integrator,
                    rtol=1e-6, atol=1e-8)
    # Eq. (3.16) and eq. (3.9), evaluated here independently of the core's
    # memoized evaluation: to rounding.
    friction = SCALE * np.arctan(k_v * r["v"])
    np.testing.assert_allclose(r["friction_force"], friction, rtol=4 * EPS, atol=1e-300)
    np.testing.assert_allclose(r["force"], 6.0 * np.sin(OMEGA * r.t), rtol=0, atol=16 * EPS * 6)
    np.testing.assert_allclose(r["acceleration"], (r["force"] - r["friction_force"]) / MASS,
                               rtol=0, atol=4 * EPS * 10)


def test_memoized_evaluations_do_not_change_the_solution():
    # The same run with output at every step (the output re-evaluates the law
    # at the step ends, served by the memo) and at fixed times (no
    # re-evaluation between the steps): the same steps, the same solution.
    for friction in ("arctan_velocity", "arctan_acceleration"):
        every = ls.simulate(block(), 2.0, friction=friction, k_v=10.0, integrator="rk_dopri5",
                            rtol=1e-7, atol=1e-9)
        final = ls.simulate(block(), 2.0, friction=friction, k_v=10.0, integrator="rk_dopri5",
                            rtol=1e-7, atol=1e-9, t_eval=[2.0])
        assert every.stats["steps"] == final.stats["steps"]
        assert every["u"][-1] == final["u"][-1] and every["v"][-1] == final["v"][-1]


def test_result_converts_lazily_and_completely():
    r = ls.simulate(block(), 1.0, friction="arctan_velocity", k_v=10.0, integrator="rk_dopri5")
    assert r.friction == "arctan_velocity" and r.integrator == "rk_dopri5"
    assert r.channels[:3] == ["u", "v", "acceleration"] and r.keys() == r.channels
    assert "u" in r and "w" not in r
    assert r["u"].shape == r.t.shape and r.t[-1] == 1.0
    with pytest.raises(KeyError, match="no channel 'w'; channels are"):
        r["w"]
    copy = pickle.loads(pickle.dumps(r))
    for name in r.channels:
        np.testing.assert_array_equal(copy[name], r[name])
    np.testing.assert_array_equal(copy.t, r.t)
    assert copy.stats == r.stats and copy.events == r.events
    assert (copy.friction, copy.integrator) == (r.friction, r.integrator)
    assert repr(copy) == repr(r)
    frame = copy.to_frame()
    assert list(frame.columns) == ["t"] + r.channels and len(frame) == len(r.t)


def test_one_channel_without_the_others_matches_the_matrix():
    fresh = ls.simulate(block(), 1.0, friction="arctan_velocity", k_v=10.0, integrator="rk_dopri5")
    with pytest.raises(KeyError, match="no channel 'w'; channels are"):
        fresh["w"]
    with pytest.raises(KeyError):
        fresh[0]
    u = fresh["u"]  # before any other conversion: the core's one-channel path
    assert fresh._data is None
    frame = fresh.to_frame()  # converts the whole matrix
    np.testing.assert_array_equal(u, frame["u"].to_numpy())
    for name in fresh.channels:
        np.testing.assert_array_equal(fresh[name], frame[name].to_numpy())
    with pytest.raises(KeyError, match="no channel 'w'; channels are"):
        fresh["w"]
