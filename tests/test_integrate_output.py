"""Output between steps and quadrature states (issue 5): advance_to_output
lets the methods whose interpolant has the accuracy of their steps (CVODE)
step past output times, up to the next discontinuity only; quadrature states
stay out of CVODE's Newton matrix. Parametrised over every method."""

import math

import numpy as np
import pytest

import leadscrew
import leadscrew.integrate as li
from helpers import ode_reference as ref

core = leadscrew._core.integrate
METHODS = li.METHODS
CVODE = [m for m in METHODS if m.startswith("cvode")]


def start(method, fun, size, y0, rtol=1e-10, atol=1e-12, **system):
    integrator = core.make_integrator(method, rtol=rtol, atol=atol)
    integrator.initialize(core.PythonOdeSystem(fun, size, **system), 0.0, np.asarray(y0, float))
    return integrator


@pytest.mark.parametrize("method", METHODS)
def test_interpolates_output_is_a_property_of_the_method(method):
    integrator = core.make_integrator(method)
    # CVODE: the Nordsieck polynomial of the current order; the Runge-Kutta
    # engines' interpolants are of lower order than their steps.
    assert integrator.interpolates_output == method.startswith("cvode")


@pytest.mark.parametrize("method", METHODS)
def test_output_between_steps_is_accurate(method):
    problem = ref.HarmonicOscillator()
    t_out = np.linspace(0.0, 10.0, 401)[1:]
    integrator = start(method, problem.rhs, 2, problem.y0)
    states = np.array([integrator.advance_to_output(t, 10.0)[2] for t in t_out]).T
    # As the closed-form accuracy test of test_integrate.py (the same bound
    # for stops at the output times).
    error = np.max(np.abs(states - problem.exact(t_out)))
    assert error < (1e-7 if method in CVODE else 1e-9), error


@pytest.mark.parametrize("method", METHODS)
def test_output_times_end_steps_only_without_an_interpolant(method):
    problem = ref.HarmonicOscillator()
    t_out = np.linspace(0.0, 10.0, 401)[1:]
    stopping = start(method, problem.rhs, 2, problem.y0)
    for t in t_out:
        assert stopping.advance(t)[0] == t
    passing = start(method, problem.rhs, 2, problem.y0)
    for t in t_out:
        assert passing.advance_to_output(t, 10.0)[0] == t
    clipped, free = stopping.stats["steps"], passing.stats["steps"]
    if method in CVODE:
        # 400 stops clip most steps (about 540 free steps at this tolerance).
        assert free < 0.75 * clipped, (free, clipped)
    else:
        assert free == clipped


@pytest.mark.parametrize("method", METHODS)
def test_never_steps_past_the_stop(method):
    # The right-hand side is defined up to t = 1 (a discontinuity there).
    latest = []

    def fun(t, y):
        latest.append(t)
        return np.array([y[1], -4.0 * y[0]])

    integrator = start(method, fun, 2, [1.0, 0.0], rtol=1e-9, atol=1e-11)
    for t in np.linspace(0.05, 1.0, 20):
        t_reached, root, y = integrator.advance_to_output(t, 1.0)
        assert t_reached == t and not root
        np.testing.assert_allclose(y, [math.cos(2 * t), -2 * math.sin(2 * t)], atol=1e-7)
    assert max(latest) <= 1.0


@pytest.mark.parametrize("method", METHODS)
def test_a_root_before_the_output_ends_the_call(method):
    problem = ref.HarmonicOscillator(omega=1.0, x0=1.0, v0=0.0)  # x = cos t: root at pi/2
    integrator = start(method, problem.rhs, 2, problem.y0,
                       events=lambda t, y: np.array([y[0]]), root_count=1)
    t, root, y = integrator.advance_to_output(2.0, 5.0)
    assert root and abs(t - math.pi / 2) < 1e-9
    assert abs(y[0]) < 1e-9
    t, root, y = integrator.advance_to_output(2.0, 5.0)  # on to the output
    assert t == 2.0 and not root
    np.testing.assert_allclose(y, problem.exact(2.0), atol=1e-7)


@pytest.mark.parametrize("method", METHODS)
def test_bad_stop_times(method):
    problem = ref.ExponentialDecay()
    integrator = start(method, problem.rhs, 1, problem.y0)
    with pytest.raises(ValueError, match="t_stop"):
        integrator.advance_to_output(1.0, 0.5)
    with pytest.raises(ValueError, match="t_stop"):
        integrator.advance_to_output(1.0, float("nan"))
    integrator.advance_to_output(0.1, 2.0)
    if method in CVODE:
        # Its last step ended past 0.1 (the output came from the
        # interpolant): a stop behind that step is refused.
        with pytest.raises(ValueError, match="t_stop"):
            integrator.advance_to_output(0.1 + 1e-12, 0.1 + 1e-12)
    else:
        t, _, _ = integrator.advance_to_output(0.1 + 1e-12, 0.1 + 1e-12)
        assert t == 0.1 + 1e-12


K = 1000.0  # [1/s]


def stiff_with_quadratures(t, y):
    """y0' = -K (y0 - cos t), y1 = integral of y0^2, y2 = integral of t y0."""
    return np.array([-K * (y[0] - math.cos(t)), y[0] ** 2, t * y[0]])


def stiff_exact(t):
    a = K / (K * K + 1.0)
    return a * (K * math.cos(t) + math.sin(t)) - a * K * math.exp(-K * t)


@pytest.mark.parametrize("method", CVODE)
def test_quadratures_outside_the_newton_matrix(method):
    from scipy.integrate import quad

    results = {}
    for quadratures in (0, 2):
        integrator = start(method, stiff_with_quadratures, 3, [0.0, 0.0, 0.0], rtol=1e-9,
                           atol=1e-12, quadrature_count=quadratures)
        t, _, y = integrator.advance(2.0)
        results[quadratures] = (y, integrator.stats)
    (y_full, full), (y_block, block) = results[0], results[2]
    # The same answer as the full dense solve, to the tolerance.
    np.testing.assert_allclose(y_block, y_full, rtol=1e-8, atol=1e-10)
    # Against the closed form and its integrals.
    exact = [stiff_exact(2.0),
             quad(lambda s: stiff_exact(s) ** 2, 0.0, 2.0, points=[0.01], epsabs=1e-14)[0],
             quad(lambda s: s * stiff_exact(s), 0.0, 2.0, points=[0.01], epsabs=1e-14)[0]]
    np.testing.assert_allclose(y_block, exact, rtol=1e-6, atol=1e-9)
    # A difference-quotient Jacobian costs one rhs per non-quadrature state.
    assert block["jacobian_evaluations"] > 0
    others_full = full["rhs_evaluations"] - 3 * full["jacobian_evaluations"]
    others_block = block["rhs_evaluations"] - 1 * block["jacobian_evaluations"]
    assert others_block == pytest.approx(others_full, rel=0.2)


@pytest.mark.parametrize("count", [-1, 3])
def test_quadrature_count_out_of_range(count):
    with pytest.raises(ValueError, match="quadrature_count"):
        core.PythonOdeSystem(stiff_with_quadratures, 3, quadrature_count=count)
