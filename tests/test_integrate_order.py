"""Orders of convergence of the ODE integrators (issue 4), by fitting the slope
of log(error) against log(step size) or log(number of steps), as diffrax's
order tests do.

The test problem y' = -2 t y^2, y(0) = 1, y = 1 / (1 + t^2) is nonlinear and
non-autonomous, so it exercises every order condition, not only those of
linear constant-coefficient problems.
"""

import numpy as np
import pytest

import leadscrew._core
import leadscrew.integrate as li
from helpers import ode_reference as ref

PROBLEM = ref.Riccati()
T_END = 2.0


def slope(x, y):
    return np.polyfit(np.log(x), np.log(y), 1)[0]


# (method, classical order, step counts in the asymptotic range with errors
# above roundoff: the poles of y at t = +-i make coarser steps pre-asymptotic)
FIXED_STEP = [
    ("dopri5", 5, [32, 64, 128, 256]),
    ("rk_dopri5", 5, [32, 64, 128, 256]),
    ("verner6", 6, [16, 32, 64, 128]),
    ("rk_verner6", 6, [16, 32, 64, 128]),
]


def test_every_fixed_step_method_has_an_order_test():
    explicit = {m for m in li.METHODS if not m.startswith("cvode")}
    assert explicit == {name for name, _, _ in FIXED_STEP}


@pytest.mark.parametrize("method, order, counts", FIXED_STEP)
def test_fixed_step_order(method, order, counts):
    errors = []
    for n in counts:
        sol = li.solve_ode(PROBLEM.rhs, (0.0, T_END), PROBLEM.y0, method=method,
                           fixed_step=T_END / n, t_eval=[T_END])
        assert sol.stats["steps"] == n  # really fixed steps
        errors.append(abs(sol.y[0, -1] - PROBLEM.exact(T_END)[0]))
    errors = np.array(errors)
    assert np.all(errors > 1e-15) and np.all(errors < 1e-6), errors
    # Error ~ C h^order: the fitted slope within 0.3 of the order (an order
    # lower or higher would be off by about 1).
    assert slope(T_END / np.array(counts), errors) == pytest.approx(order, abs=0.3)


# CVODE has no fixed steps. With the order pinned by max_order, the global
# error of a variable-step method of order q falls like N^-q in the number
# of steps N (the controller keeps the local error ~ tol ~ h^(q+1), so
# N ~ tol^(-1/(q+1)) and the global error ~ N tol ~ N^-q). The tolerance is
# swept, (N, error) recorded, and the slope fitted over the runs with N >= 50
# (CVODE starts at order 1 and needs steps to reach order q) and error > 1e-12
# (roundoff). From order 4 on the error reaches roundoff within ~300 steps,
# while the start-up still weighs: the fitted slope then lies anywhere between
# q and q + 1 depending on the interval (measured: Adams 4 gives 4.3 on [0, 2]
# with 10 tolerances, 5.4 with 21, 4.5 on [0, 5]), so orders >= 4 are checked
# by their step counts instead (test_higher_pinned_orders_take_fewer_steps).
PINNED = [("cvode_bdf", 1), ("cvode_bdf", 2), ("cvode_bdf", 3), ("cvode_adams", 2),
          ("cvode_adams", 3)]


@pytest.mark.parametrize("method, order", PINNED)
def test_pinned_order(method, order):
    steps, errors = [], []
    for rtol in np.logspace(-2, -11, 10):
        sol = li.solve_ode(PROBLEM.rhs, (0.0, T_END), PROBLEM.y0, method=method, max_order=order,
                           rtol=rtol, atol=rtol * 1e-3, t_eval=[T_END])
        steps.append(sol.stats["steps"])
        errors.append(abs(sol.y[0, -1] - PROBLEM.exact(T_END)[0]))
        if steps[-1] > 5000:
            break
    steps, errors = np.array(steps), np.array(errors)
    used = (steps >= 50) & (errors > 1e-12)
    assert used.sum() >= 4, (steps, errors)
    assert -slope(steps[used], errors[used]) == pytest.approx(order, abs=0.4), (steps, errors)


@pytest.mark.parametrize("method, highest", [("cvode_bdf", 5), ("cvode_adams", 6)])
def test_higher_pinned_orders_take_fewer_steps(method, highest):
    # At a tight tolerance each higher order needs fewer steps (measured at
    # rtol 1e-9, BDF 1..5: 71922, 2142, 444, 230, 158 steps).
    counts = []
    for order in range(1, highest + 1):
        sol = li.solve_ode(PROBLEM.rhs, (0.0, T_END), PROBLEM.y0, method=method, max_order=order,
                           rtol=1e-9, atol=1e-12, t_eval=[T_END], max_steps=10**6)
        counts.append(sol.stats["steps"])
    assert all(a > b for a, b in zip(counts, counts[1:])), counts
    assert counts[0] > 100 * counts[-1], counts


@pytest.mark.parametrize("problem", [ref.HarmonicOscillator(), ref.ForcedDecay()],
                         ids=["oscillator", "forced"])
def test_rk_dopri5_dense_output_order(problem):
    # The continuous extension of rk_dopri5 (Shampine's) has order 4: its
    # error at an interior point of one step falls like h^5. (On the Riccati
    # problem the h^6 term is still comparable at these step sizes.)
    t0 = 0.3
    errors, sizes = [], np.array([0.2, 0.1, 0.05, 0.025])
    for h in sizes:
        integrator = leadscrew._core.integrate.make_integrator("rk_dopri5", fixed_step=h)
        integrator.initialize(
            leadscrew._core.integrate.PythonOdeSystem(problem.rhs, problem.y0.size), t0,
            problem.exact(t0))
        integrator.advance(t0 + h)
        t = t0 + 0.37 * h
        errors.append(np.max(np.abs(integrator.dense_output(t) - problem.exact(t))))
    assert slope(sizes, np.array(errors)) == pytest.approx(5.0, abs=0.2), errors


@pytest.mark.parametrize("pair", [("dopri5", "rk_dopri5"), ("verner6", "rk_verner6")])
def test_own_engine_matches_arkode(pair):
    # The same Butcher tableau in two independent implementations (rk_dopri5's
    # coefficients are typed in from the paper, ARKODE's are its own): fixed
    # steps must agree to roundoff.
    results = []
    for method in pair:
        sol = li.solve_ode(PROBLEM.rhs, (0.0, T_END), PROBLEM.y0, method=method,
                           fixed_step=T_END / 40, t_eval=np.linspace(0.0, T_END, 41))
        results.append(sol.y[0])
    np.testing.assert_allclose(results[0], results[1], rtol=1e-14, atol=0)


@pytest.mark.parametrize("method", li.METHODS)
def test_dense_output_within_the_last_step(method):
    problem = ref.HarmonicOscillator()
    integrator = leadscrew._core.integrate.make_integrator(method, rtol=1e-10, atol=1e-12)
    integrator.initialize(leadscrew._core.integrate.PythonOdeSystem(problem.rhs, 2), 0.0,
                          problem.y0)
    t, _, y = integrator.advance(1.0, one_step=True)
    np.testing.assert_array_equal(integrator.dense_output(t), y)
    middle = 0.5 * t
    if method.startswith("cvode"):
        middle = t * (1 - 1e-3)  # the first CVODE step is tiny: stay inside it
    np.testing.assert_allclose(integrator.dense_output(middle), problem.exact(middle), atol=1e-8)
    with pytest.raises(ValueError, match="t = 2 is invalid"):
        integrator.dense_output(2.0)
