"""ODE integrators of the core (issue 4), parametrised over every method:
accuracy against closed forms, tolerance proportionality, root finding,
restarts, failures and option validation. Orders of convergence are in
test_integrate_order.py."""

import math

import numpy as np
import pytest

import leadscrew
import leadscrew.integrate as li
from helpers import ode_reference as ref

METHODS = li.METHODS
EXPLICIT = [m for m in METHODS if not m.startswith("cvode")]


def test_method_names():
    assert {"cvode_bdf", "cvode_adams", "dopri5"} <= set(METHODS)
    assert len(set(METHODS)) == len(METHODS)


# --- accuracy against closed forms --------------------------------------------------------


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize(
    "problem, t_end",
    [
        (ref.HarmonicOscillator(), 5.0),
        (ref.ExponentialDecay(k=2.0), 3.0),
        (ref.ForcedDecay(), 4.0),
    ],
    ids=["harmonic", "decay", "forced"],
)
def test_accuracy_against_closed_form(method, problem, t_end):
    t_eval = np.linspace(0.0, t_end, 21)
    sol = li.solve_ode(problem.rhs, (0.0, t_end), problem.y0, method=method, rtol=1e-10,
                       atol=1e-12, t_eval=t_eval)
    np.testing.assert_array_equal(sol.t, t_eval)  # outputs exactly at t_eval
    assert sol.y.shape == (problem.y0.size, t_eval.size)
    error = np.max(np.abs(sol.y - problem.exact(t_eval)))
    # The tolerances bound local errors; on these O(1), non-growing solutions
    # the global error stays within a few rtol for the Runge-Kutta pairs
    # (local extrapolation) and within a few hundred rtol for CVODE's
    # variable-order multistep methods (BDF damps the oscillator's amplitude:
    # measured 2.3e-8 here, the worst case).
    assert error < (1e-7 if method.startswith("cvode") else 1e-9), error
    assert sol.stats["steps"] > 0 and sol.stats["rhs_evaluations"] >= sol.stats["steps"]
    assert sol.method == method


@pytest.mark.parametrize("method", METHODS)
def test_every_step_output(method):
    problem = ref.HarmonicOscillator()
    sol = li.solve_ode(problem.rhs, (0.0, 2.0), problem.y0, method=method, rtol=1e-9, atol=1e-11)
    assert sol.t[0] == 0.0 and sol.t[-1] == 2.0
    assert np.all(np.diff(sol.t) > 0)
    # One output per internal step (plus t0).
    assert sol.t.size == sol.stats["steps"] + 1
    assert np.max(np.abs(sol.y - problem.exact(sol.t))) < 1e-7


@pytest.mark.parametrize("method", METHODS)
def test_error_falls_with_tolerance(method):
    problem = ref.ForcedDecay()
    errors, work = [], []
    for tol in (1e-4, 1e-7, 1e-10):
        sol = li.solve_ode(problem.rhs, (0.0, 4.0), problem.y0, method=method, rtol=tol,
                           atol=tol, t_eval=[4.0])
        errors.append(abs(sol.y[0, -1] - problem.exact(4.0)[0]))
        work.append(sol.stats["rhs_evaluations"])
    # Each 1000-fold tightening buys at least a 10-fold smaller error, at more cost.
    assert errors[1] < errors[0] / 10 and errors[2] < errors[1] / 10, errors
    assert errors[2] < 1e-8
    assert work[0] < work[1] < work[2]


# --- root finding -------------------------------------------------------------------------


def height(t, y):
    return y[0]


@pytest.mark.parametrize("method", METHODS)
def test_root_located_to_machine_precision(method):
    # h(t) = h0 - g t^2 / 2 is a polynomial of degree 2: every method and its
    # dense output reproduce it, so the root must come out to roundoff.
    problem = ref.FreeFall()
    # (CVODE starts at order 1, which does not reproduce it: its root is as
    # accurate as its solution, hence the tight tolerances.) The state at the
    # root must lie on g = 0 to roundoff whatever the solution's accuracy.
    sol = li.solve_ode(problem.rhs, (0.0, 1.0), problem.y0, method=method, rtol=1e-13,
                       atol=1e-14, events=height)
    t_impact = problem.impact_time()
    assert len(sol.t_events[0]) == 1
    assert abs(sol.y_events[0][0][0]) < 1e-12
    assert sol.t_events[0][0] == pytest.approx(t_impact, abs=1e-12)
    assert sol.direction_events[0][0] == -1
    np.testing.assert_allclose(sol.y_events[0][0], problem.exact(t_impact), atol=1e-10)


@pytest.mark.parametrize("method", METHODS)
def test_root_directions_and_count(method):
    # x = cos(2 t) + 0.25 sin(2 t) = A cos(2 t - phi), tan(phi) = 0.25: zeros
    # at 2 t = phi + pi/2 + k pi, falling first (x starts positive).
    problem = ref.HarmonicOscillator(omega=2.0, x0=1.0, v0=0.5)
    sol = li.solve_ode(problem.rhs, (0.0, 6.0), problem.y0, method=method, rtol=1e-10,
                       atol=1e-12, events=height)
    first = (math.atan2(0.25, 1.0) + math.pi / 2) / 2.0
    expected = first + np.arange(0, 5) * math.pi / 2.0
    expected = expected[expected < 6.0]
    np.testing.assert_allclose(sol.t_events[0], expected, atol=1e-8)
    expected_dirs = np.array([(-1) ** (k + 1) for k in range(expected.size)])
    np.testing.assert_array_equal(sol.direction_events[0], expected_dirs)


@pytest.mark.parametrize("method", METHODS)
def test_direction_filter_and_terminal(method):
    problem = ref.HarmonicOscillator(omega=2.0, x0=1.0, v0=0.5)

    def rising(t, y):
        return y[0]

    rising.direction = 1
    rising.terminal = True
    sol = li.solve_ode(problem.rhs, (0.0, 6.0), problem.y0, method=method, rtol=1e-10,
                       atol=1e-12, events=rising)
    first_rise = (math.atan2(0.25, 1.0) + math.pi / 2) / 2.0 + math.pi / 2.0
    assert sol.terminated
    assert sol.t_events[0] == pytest.approx([first_rise], abs=1e-8)
    assert sol.t[-1] == sol.t_events[0][0]


class RootCounter:
    """g(t, y) = y[0] recording every time it is evaluated."""

    def __init__(self):
        self.times = []

    def __call__(self, t, y):
        self.times.append(t)
        return y[0]


@pytest.mark.parametrize("method", METHODS)
def test_advance_never_passes_t_out(method):
    # The right-hand side is only defined up to t = 1 (beyond it the model
    # would switch, e.g. after an event): nothing may evaluate it later.
    latest = []

    def fun(t, y):
        latest.append(t)
        return np.array([y[1], -4.0 * y[0]])

    integrator = leadscrew._core.integrate.make_integrator(method, rtol=1e-9, atol=1e-11)
    system = leadscrew._core.integrate.PythonOdeSystem(fun, 2)
    integrator.initialize(system, 0.0, np.array([1.0, 0.0]))
    for t_out in (0.3, 0.7, 1.0):
        t, root, y = integrator.advance(t_out)
        assert t == t_out and not root
        assert max(latest) <= t_out
    t, root, y = integrator.advance(1.0, one_step=True)  # already there: no step
    assert t == 1.0 and max(latest) <= 1.0
    np.testing.assert_allclose(y, [math.cos(2.0), -2.0 * math.sin(2.0)], atol=1e-8)


@pytest.mark.parametrize("method", METHODS)
def test_reinitialize_after_events_bouncing_ball(method):
    # Event-driven use: stop at each impact, apply v+ = -e v-, restart.
    ball = ref.BouncingBall()
    integrator = leadscrew._core.integrate.make_integrator(method, rtol=1e-10, atol=1e-12)
    system = leadscrew._core.integrate.PythonOdeSystem(
        ball.rhs, 2, lambda t, y: np.array([y[0]]), 1)
    integrator.initialize(system, 0.0, ball.y0)
    impacts = []
    t_end = 4.0
    t = 0.0
    for _ in range(100):
        t, root, y = integrator.advance(t_end)
        if not root:
            break
        assert integrator.root_info == [-1]
        impacts.append(t)
        integrator.reinitialize(t, np.array([0.0, -ball.e * y[1]]))
    expected = ball.impact_times(20)
    expected = expected[expected < t_end]
    assert t == t_end
    np.testing.assert_allclose(impacts, expected, atol=1e-9)
    stats = integrator.stats
    assert stats["restarts"] == len(impacts)
    # Counters accumulate over restarts (SUNDIALS resets its own on restart):
    # at least one step per flight.
    assert stats["steps"] >= len(impacts) + 1


@pytest.mark.parametrize("method", METHODS)
def test_no_root_reported_at_restart_on_the_surface(method):
    # Restarting exactly on g = 0 (as after an event) must not report a root
    # at the restart time.
    problem = ref.FreeFall()
    integrator = leadscrew._core.integrate.make_integrator(method, rtol=1e-10, atol=1e-12)
    system = leadscrew._core.integrate.PythonOdeSystem(
        problem.rhs, 2, lambda t, y: np.array([y[0]]), 1)
    integrator.initialize(system, 0.0, np.array([0.0, 3.0]))  # on the ground, going up
    t, root, y = integrator.advance(1.0)
    t_land = 2 * 3.0 / problem.g
    assert root and integrator.root_info == [-1]
    assert t == pytest.approx(t_land, abs=1e-9)


# --- failures -----------------------------------------------------------------------------


FLAG = r"(CV|ARK|RK)_[A-Z_]+: "


@pytest.mark.parametrize("method", METHODS)
def test_blow_up_raises_simulation_error(method):
    # y' = y^2, y(0) = 1: y = 1 / (1 - t) blows up at t = 1.
    with pytest.raises(leadscrew.SimulationError, match=FLAG) as info, np.errstate(over="ignore"):
        li.solve_ode(lambda t, y: y * y, (0.0, 2.0), [1.0], method=method)
    assert 0.99 < info.value.time < 1.0 + 1e-6
    assert "hint:" in str(info.value)


@pytest.mark.parametrize("method", METHODS)
def test_max_steps_exhausted(method):
    # The budget is the total over the whole run, whatever the output mode.
    for t_eval in (None, np.linspace(0.0, 50.0, 200)):
        with pytest.raises(leadscrew.SimulationError, match=r"_TOO_MUCH_WORK: ") as info:
            li.solve_ode(lambda t, y: np.array([y[1], -25.0 * y[0]]), (0.0, 50.0), [1.0, 0.0],
                         method=method, max_steps=40, t_eval=t_eval)
        assert "max_steps" in str(info.value)
        assert 0.0 < info.value.time < 50.0


@pytest.mark.parametrize("method", METHODS)
def test_nan_right_hand_side(method):
    with pytest.raises(leadscrew.SimulationError, match=FLAG + r".*NaN or inf") as info:
        li.solve_ode(lambda t, y: np.array([math.nan]), (0.0, 1.0), [1.0], method=method)
    assert info.value.time == 0.0


@pytest.mark.parametrize("method", METHODS)
def test_nan_beyond_some_time_fails_promptly(method):
    calls = []

    def fun(t, y):
        calls.append(t)
        return np.array([math.nan if t > 0.5 else 1.0])

    with pytest.raises(leadscrew.SimulationError, match=FLAG + r".*NaN or inf") as info:
        li.solve_ode(fun, (0.0, 1.0), [1.0], method=method)
    if method.startswith("cvode"):
        assert 0.4 < info.value.time <= 0.5 + 1e-6  # the last accepted step
    else:
        assert 0.4 < info.value.time < 1.0  # ARKODE reports the failed stage's time
    assert len(calls) < 5000  # not max_steps tiny steps towards t = 0.5


@pytest.mark.parametrize("method", METHODS)
def test_python_exception_in_rhs_propagates(method):
    def fun(t, y):
        if t > 0.25:
            raise KeyError("model failed")
        return -y

    with pytest.raises(KeyError, match="model failed"):
        li.solve_ode(fun, (0.0, 1.0), [1.0], method=method)


def test_rhs_of_wrong_size():
    with pytest.raises(ValueError, match=r"fun\(t, y\) returned 1 values.*must return 2"):
        li.solve_ode(lambda t, y: np.array([0.0]), (0.0, 1.0), [1.0, 2.0])


# --- options ------------------------------------------------------------------------------


def test_unknown_method_lists_the_allowed_names():
    with pytest.raises(ValueError, match=r"method = \"rk4\" is invalid: must be one of") as info:
        li.solve_ode(lambda t, y: -y, (0.0, 1.0), [1.0], method="rk4")
    for name in METHODS:
        assert f'"{name}"' in str(info.value)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize(
    "option, value",
    [("rtol", 0.0), ("rtol", -1e-6), ("rtol", math.nan), ("rtol", 1.5), ("atol", 0.0),
     ("atol", -1.0), ("max_step", -0.1), ("first_step", -1.0), ("fixed_step", -1e-3),
     ("max_steps", 0), ("max_order", -1)],
)
def test_bad_option_names_the_option(method, option, value):
    with pytest.raises(ValueError, match=rf"^{option} = .* is invalid: must be"):
        li.solve_ode(lambda t, y: -y, (0.0, 1.0), [1.0], method=method, **{option: value})


@pytest.mark.parametrize("method", ["cvode_bdf", "cvode_adams"])
def test_fixed_step_is_rejected_by_variable_step_methods(method):
    with pytest.raises(ValueError, match=r"fixed_step = 0.01 is invalid: must be 0 for " + method):
        li.solve_ode(lambda t, y: -y, (0.0, 1.0), [1.0], method=method, fixed_step=0.01)


@pytest.mark.parametrize("method, highest", [("cvode_bdf", 5), ("cvode_adams", 12)])
def test_max_order_range(method, highest):
    li.solve_ode(lambda t, y: -y, (0.0, 1.0), [1.0], method=method, max_order=highest)
    with pytest.raises(ValueError, match=rf"max_order = {highest + 1} is invalid: .*1..{highest}"):
        li.solve_ode(lambda t, y: -y, (0.0, 1.0), [1.0], method=method, max_order=highest + 1)


@pytest.mark.parametrize("method", EXPLICIT)
def test_max_order_is_rejected_by_one_step_methods(method):
    with pytest.raises(ValueError, match=r"max_order = 3 is invalid: must be 0 for " + method):
        li.solve_ode(lambda t, y: -y, (0.0, 1.0), [1.0], method=method, max_order=3)


def test_bad_arguments():
    f = lambda t, y: -y  # noqa: E731
    with pytest.raises(ValueError, match="t_span"):
        li.solve_ode(f, (1.0, 0.0), [1.0])
    with pytest.raises(ValueError, match="t_eval"):
        li.solve_ode(f, (0.0, 1.0), [1.0], t_eval=[0.5, 0.2])
    with pytest.raises(ValueError, match="t_eval"):
        li.solve_ode(f, (0.0, 1.0), [1.0], t_eval=[0.5, 2.0])
    with pytest.raises(ValueError, match=r"y0\[0\] = nan is invalid"):
        li.solve_ode(f, (0.0, 1.0), [math.nan])
    with pytest.raises(ValueError, match=r"events\[0\]"):
        li.solve_ode(f, (0.0, 1.0), [1.0], events=[1.0])


def test_advance_backwards_is_rejected():
    integrator = leadscrew._core.integrate.make_integrator("dopri5")
    integrator.initialize(leadscrew._core.integrate.PythonOdeSystem(lambda t, y: -y, 1), 1.0,
                          np.array([1.0]))
    with pytest.raises(ValueError, match=r"t_out = 0.5 is invalid: must be >= the current time 1"):
        integrator.advance(0.5)
    with pytest.raises(ValueError, match=r"y0 has 2 components"):
        integrator.reinitialize(1.0, np.array([1.0, 2.0]))


@pytest.mark.parametrize("method", METHODS)
def test_close_and_simultaneous_roots(method):
    # x = t: g0 = x - 0.5 and g1 = x - (0.5 + 1e-7) cross 1e-7 apart; g2 = g0
    # crosses with g0. The earliest comes first, each exactly once.
    def events(t, y):
        return np.array([y[0] - 0.5, y[0] - 0.5 - 1e-7, y[0] - 0.5])

    integrator = leadscrew._core.integrate.make_integrator(method, rtol=1e-10, atol=1e-12)
    integrator.initialize(
        leadscrew._core.integrate.PythonOdeSystem(lambda t, y: np.array([1.0]), 1, events, 3),
        0.0, np.array([0.0]))
    t, root, y = integrator.advance(1.0)
    assert root and integrator.root_info == [1, 0, 1]
    assert t == pytest.approx(0.5, abs=1e-13)
    t, root, y = integrator.advance(1.0)
    assert root and integrator.root_info == [0, 1, 0]
    assert t == pytest.approx(0.5 + 1e-7, abs=1e-13)
    t, root, y = integrator.advance(1.0)
    assert not root and t == 1.0


@pytest.mark.parametrize("method", ["rk_dopri5", "rk_verner6"])
def test_own_engine_event_times_as_accurate_as_the_solution(method):
    # The roots come from the exact continuation of the step, not from the
    # (lower-order) interpolant: the event states of x = cos(2t) + 0.25 sin(2t)
    # are as accurate as the solution at output times, and the event times
    # accordingly (error in x / |x'|).
    problem = ref.HarmonicOscillator(omega=2.0, x0=1.0, v0=0.5)
    t_eval = np.linspace(0.0, 6.0, 61)
    sol = li.solve_ode(problem.rhs, (0.0, 6.0), problem.y0, method=method, rtol=1e-11,
                       atol=1e-13, events=height, t_eval=t_eval)
    solution_error = np.max(np.abs(sol.y - problem.exact(t_eval)))
    assert solution_error < 1e-9
    first = (math.atan2(0.25, 1.0) + math.pi / 2) / 2.0
    expected = first + np.arange(0, 4) * math.pi / 2.0
    speed = math.hypot(2.0 * 1.0, 0.5)  # |x'| at the zeros of x
    np.testing.assert_allclose(sol.t_events[0], expected, rtol=0,
                               atol=2 * solution_error / speed + 1e-14)
    for t, y in zip(sol.t_events[0], sol.y_events[0]):
        np.testing.assert_allclose(y, problem.exact(t), rtol=0, atol=2 * solution_error + 1e-14)
        # On the switching surface to roundoff: x / |x'| within 16 ulp of t.
        assert abs(y[0]) / speed < 16 * np.finfo(float).eps * t


@pytest.mark.parametrize("method", METHODS)
def test_step_options(method):
    problem = ref.HarmonicOscillator()
    sol = li.solve_ode(problem.rhs, (0.0, 3.0), problem.y0, method=method, rtol=1e-6,
                       atol=1e-8, max_step=0.05, first_step=1e-3)
    steps = np.diff(sol.t)
    # The first step is first_step unless its error test fails (CVODE starts
    # at order 1, whose error at h = 1e-3 is above rtol: it shrinks the step).
    if method.startswith("cvode"):
        assert steps[0] <= 1e-3 * (1 + 1e-12)
    else:
        assert steps[0] == pytest.approx(1e-3, rel=1e-12)
    assert np.all(steps <= 0.05 * (1 + 1e-12))
    if method in EXPLICIT:
        sol = li.solve_ode(problem.rhs, (0.0, 3.0), problem.y0, method=method, fixed_step=0.1)
        np.testing.assert_allclose(np.diff(sol.t), 0.1, rtol=1e-9)


@pytest.mark.parametrize("method", EXPLICIT)
def test_stiff_problem_on_an_explicit_method_says_use_bdf(method):
    # y' = -1e6 (y - cos t): the explicit stability limit forces h ~ 3e-6.
    def fun(t, y):
        return -1e6 * (y - math.cos(t))

    # (The own engines test for stiffness, Hairer's test: after 1,015 steps
    # held at their stability boundary, the 3e5 steps to t = 1 exceed the
    # budget; ARKODE's run out of it.)
    flag = "RK_STIFF" if method.startswith("rk_") else "TOO_MUCH_WORK"
    with pytest.raises(leadscrew.SimulationError, match=flag + r".*cvode_bdf"):
        li.solve_ode(fun, (0.0, 1.0), [1.0], method=method, max_steps=2000, t_eval=[1.0])
    sol = li.solve_ode(fun, (0.0, 1.0), [1.0], method="cvode_bdf", max_steps=2000, t_eval=[1.0])
    assert sol.stats["steps"] < 500
    # y = cos t + 1e-6 sin t + O(1e-12) after the initial layer
    assert sol.y[0, -1] == pytest.approx(math.cos(1.0) + 1e-6 * math.sin(1.0), abs=1e-9)
