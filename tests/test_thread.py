"""Closed-form thread mechanics (issue: foundation), against the bounds
tan(alpha) < mu' < cot(alpha) of thesis eq. (3.5)-(3.8)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import leadscrew as ls
from helpers import thread_reference as ref

pitches = st.floats(1e-4, 0.05)
diameters = st.floats(1e-3, 0.2)
starts = st.integers(1, 6)
flank_angles = st.floats(0.0, math.radians(60.0))
mus = st.floats(0.0, 3.0)
loads = st.floats(1e-3, 1e6)


@st.composite
def threads(draw):
    return ls.Thread(draw(pitches), draw(diameters), draw(starts), draw(flank_angles))


def test_geometry():
    t = ls.Thread(pitch=0.004, mean_diameter=0.030, starts=2, flank_angle=math.radians(30))
    assert t.lead == pytest.approx(0.008, rel=1e-15)
    assert t.lead_angle == pytest.approx(math.atan(0.008 / (math.pi * 0.030)), rel=1e-15)
    assert t.lead_per_radian == pytest.approx(0.008 / (2 * math.pi), rel=1e-15)
    assert t.mean_radius == 0.015
    assert t.hand == "right" and t.hand_sign == 1.0
    assert ls.Thread(0.004, 0.03, hand="left").hand_sign == -1.0
    assert t.effective_mu(0.1) == pytest.approx(0.1 / math.cos(math.radians(15)), rel=1e-15)


def test_shigley_example_8_1():
    """Shigley's Mechanical Engineering Design (Budynas, Nisbett, 9th ed.),
    Example 8-1: square double thread, major diameter 32 mm, pitch 4 mm,
    f = f_c = 0.08, collar mean diameter 40 mm, F = 6.4 kN.

    By hand: d_m = 32 - 4/2 = 30 mm, l = 2 * 4 = 8 mm,
      T_R = F d_m/2 (l + pi f d_m) / (pi d_m - f l) + F f_c d_c / 2
          = 6400 * 0.015 * 15.5398 / 93.6077 + 10.24 = 15.94 + 10.24 = 26.18 N m,
      T_L = 6400 * 0.015 * (7.5398 - 8) / 94.8877 + 10.24 = -0.466 + 10.24 = 9.77 N m,
      e   = F l / (2 pi T_R) = 6400 * 0.008 / (2 pi 26.18) = 0.311.
    """
    thread = ls.Thread(pitch=0.004, mean_diameter=0.030, starts=2)
    load, f, dc = 6400.0, 0.08, 0.040
    assert ls.raise_torque(thread, f, load) == pytest.approx(15.94, abs=5e-3)
    assert ls.raise_torque(thread, f, load, f, dc) == pytest.approx(26.18, abs=5e-3)
    assert ls.lower_torque(thread, f, load) == pytest.approx(-0.466, abs=5e-4)
    assert ls.lower_torque(thread, f, load, f, dc) == pytest.approx(9.77, abs=5e-3)
    assert ls.efficiency(thread, f, f, dc) == pytest.approx(0.311, abs=5e-4)
    # The thread alone back-drives; the collar friction holds the load.
    assert not ls.is_self_locking(thread, f)


@settings(max_examples=400, deadline=None)
@given(threads(), mus, loads)
def test_bounds_agree_with_torques_and_efficiency(thread, mu, load):
    """self-locking <=> lower torque > 0 <=> back-drive efficiency < 0;
    not drivable <=> no finite positive raise torque."""
    locking = ls.is_self_locking(thread, mu)
    assert locking == (ls.lower_torque(thread, mu, load) > 0.0)
    assert locking == (ls.efficiency(thread, mu, backdrive=True) < 0.0)
    assert locking == (math.tan(thread.lead_angle) < thread.effective_mu(mu))
    drivable = ls.is_drivable(thread, mu)
    raise_t = ls.raise_torque(thread, mu, load)
    assert drivable == (math.isfinite(raise_t) and raise_t > 0.0)
    assert drivable == (thread.effective_mu(mu) < 1.0 / math.tan(thread.lead_angle))
    assert drivable == (ls.efficiency(thread, mu) > 0.0)


@settings(max_examples=300, deadline=None)
@given(pitches, diameters, starts, flank_angles, mus, loads)
def test_against_independent_angle_form(pitch, d_m, n, beta, mu, load):
    thread = ls.Thread(pitch, d_m, n, beta)
    expected_raise = ref.raise_torque(pitch, d_m, mu, load, n, beta)
    got_raise = ls.raise_torque(thread, mu, load)
    alpha = ref.lead_angle(pitch, d_m, n)
    rho = ref.friction_angle(mu, beta)
    if abs(alpha + rho - math.pi / 2) > 1e-6:  # away from the tan pole
        if math.isinf(expected_raise):
            assert math.isinf(got_raise)
        else:
            assert got_raise == pytest.approx(expected_raise, rel=1e-9)
        assert ls.efficiency(thread, mu) == pytest.approx(
            ref.efficiency(pitch, d_m, mu, n, beta), rel=1e-9, abs=1e-12
        )
    scale = load * d_m / 2
    assert ls.lower_torque(thread, mu, load) == pytest.approx(
        ref.lower_torque(pitch, d_m, mu, load, n, beta), rel=1e-9, abs=1e-12 * scale
    )
    assert ls.efficiency(thread, mu, backdrive=True) == pytest.approx(
        ref.backdrive_efficiency(pitch, d_m, mu, n, beta), rel=1e-9, abs=1e-12
    )


@given(threads())
def test_frictionless_limit(thread):
    assert ls.efficiency(thread, 0.0) == pytest.approx(1.0, rel=1e-14)
    assert ls.efficiency(thread, 0.0, backdrive=True) == pytest.approx(1.0, rel=1e-14)
    # Without friction the drive torque is the ideal one, F lead / (2 pi).
    assert ls.raise_torque(thread, 0.0, 100.0) == pytest.approx(100.0 * thread.lead_per_radian)
    assert ls.lower_torque(thread, 0.0, 100.0) == pytest.approx(-100.0 * thread.lead_per_radian)
    assert ls.is_drivable(thread, 0.0) and not ls.is_self_locking(thread, 0.0)


@settings(max_examples=200, deadline=None)
@given(threads(), st.floats(0.0, 1.0), st.floats(1e-3, 1.0))
def test_monotonic_in_mu(thread, mu, step):
    mu2 = mu + step
    assert ls.efficiency(thread, mu2) <= ls.efficiency(thread, mu)
    assert ls.efficiency(thread, mu2, backdrive=True) < ls.efficiency(thread, mu, backdrive=True)
    assert ls.raise_torque(thread, mu2, 10.0) >= ls.raise_torque(thread, mu, 10.0)
    assert ls.lower_torque(thread, mu2, 10.0) > ls.lower_torque(thread, mu, 10.0)


@settings(max_examples=200, deadline=None)
@given(pitches, diameters, st.floats(1e-3, 1.0), st.floats(0.0, 1.0), st.floats(1e-3, 0.5))
def test_monotonic_in_flank_angle(pitch, d_m, mu, beta, step):
    flat = ls.Thread(pitch, d_m, flank_angle=beta)
    steep = ls.Thread(pitch, d_m, flank_angle=beta + step)
    assert ls.efficiency(steep, mu) <= ls.efficiency(flat, mu)
    assert ls.raise_torque(steep, mu, 1.0) >= ls.raise_torque(flat, mu, 1.0)
    assert ls.lower_torque(steep, mu, 1.0) > ls.lower_torque(flat, mu, 1.0)


def test_efficiency_is_work_ratio():
    thread = ls.Thread(0.003, 0.018, flank_angle=math.radians(30))
    for mu in (0.05, 0.1, 0.2):
        eta = ls.efficiency(thread, mu, 0.1, 0.025)
        torque = ls.raise_torque(thread, mu, 500.0, 0.1, 0.025)
        assert eta == pytest.approx(500.0 * thread.lead / (2 * math.pi * torque), rel=1e-14)


def test_not_drivable_returns_inf_and_zero_efficiency():
    thread = ls.Thread(pitch=0.2, mean_diameter=0.01)  # lead angle ~81 deg
    mu = 0.5  # cot(alpha) ~ 0.157 < mu
    assert not ls.is_drivable(thread, mu)
    assert ls.raise_torque(thread, mu, 1.0) == math.inf
    assert ls.efficiency(thread, mu) == 0.0


@given(threads(), st.lists(mus, min_size=1, max_size=20))
@settings(max_examples=50, deadline=None)
def test_array_forms_equal_the_scalar_functions(thread, mu_values):
    # The sweeps' closed-form columns (efficiency_vs_mu) come from these.
    from leadscrew import _core

    mu = np.array(mu_values)
    efficiency = _core.efficiency_array(thread, mu)
    drivable = _core.is_drivable_array(thread, mu)
    assert efficiency.dtype == float and drivable.dtype == bool
    assert efficiency.tolist() == [ls.efficiency(thread, m) for m in mu_values]
    assert drivable.tolist() == [ls.is_drivable(thread, m) for m in mu_values]


def test_array_forms_reject_bad_mu():
    from leadscrew import _core

    thread = ls.Thread(pitch=3e-3, mean_diameter=20e-3)
    for call in (_core.efficiency_array, _core.is_drivable_array):
        with pytest.raises(ValueError, match="mu"):
            call(thread, np.array([0.1, -0.2]))
        with pytest.raises(ValueError, match="mu"):
            call(thread, np.array([0.1, np.nan]))


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(pitch=-0.001, mean_diameter=0.01), "pitch"),
        (dict(pitch=0.0, mean_diameter=0.01), "pitch"),
        (dict(pitch=float("nan"), mean_diameter=0.01), "pitch"),
        (dict(pitch=0.001, mean_diameter=float("inf")), "mean_diameter"),
        (dict(pitch=0.001, mean_diameter=0.01, starts=0), "starts"),
        (dict(pitch=0.001, mean_diameter=0.01, flank_angle=-0.1), "flank_angle"),
        (dict(pitch=0.001, mean_diameter=0.01, flank_angle=math.pi), "flank_angle"),
        (dict(pitch=0.001, mean_diameter=0.01, hand="up"), "hand"),
    ],
)
def test_bad_thread_raises(kwargs, name):
    with pytest.raises(ValueError, match=name) as info:
        ls.Thread(**kwargs)
    assert "must be" in str(info.value)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda t: ls.raise_torque(t, -0.1, 1.0), "mu"),
        (lambda t: ls.raise_torque(t, 0.1, -1.0), "load"),
        (lambda t: ls.lower_torque(t, 0.1, float("nan")), "load"),
        (lambda t: ls.efficiency(t, float("inf")), "mu"),
        (lambda t: ls.efficiency(t, 0.1, collar_mu=-1.0), "collar_mu"),
        (lambda t: ls.raise_torque(t, 0.1, 1.0, 0.1, -0.02), "collar_diameter"),
        (lambda t: ls.is_self_locking(t, -1.0), "mu"),
        (lambda t: ls.is_drivable(t, float("nan")), "mu"),
    ],
)
def test_bad_friction_input_raises(call, name):
    thread = ls.Thread(0.003, 0.02)
    with pytest.raises(ValueError, match=rf"^{name} = .* must be"):
        call(thread)


def test_thread_pickles():
    import pickle

    t = ls.Thread(0.003, 0.02, 2, 0.5, "left")
    u = pickle.loads(pickle.dumps(t))
    assert (u.pitch, u.mean_diameter, u.starts, u.flank_angle, u.hand) == (0.003, 0.02, 2, 0.5, "left")


# --- unit strings and messages without internals ----------------------------------------


def test_thread_takes_unit_strings():
    t = ls.Thread(pitch="2 mm", mean_diameter="9 mm", starts="2", flank_angle="30 deg",
                  hand="left")
    assert isinstance(t, ls.Thread)
    assert (t.pitch, t.starts, t.hand) == (0.002, 2, "left")
    assert t.mean_diameter == pytest.approx(0.009, rel=1e-15)
    assert t.flank_angle == pytest.approx(math.radians(30), rel=1e-15)
    import pickle

    again = pickle.loads(pickle.dumps(t))
    assert type(again) is ls.Thread and repr(again) == repr(t)
    scene = ls.Scene.from_dict({"thread": {"pitch": "2 mm", "mean_diameter": "9 mm"},
                                "friction": {"mu": 0.1}})
    assert isinstance(scene.thread, ls.Thread)


@pytest.mark.parametrize("kwargs, message", [
    (dict(pitch="2 N", mean_diameter=0.01), 'pitch = "2 N" is invalid: "2 N" is not a length (m)'),
    (dict(pitch=None, mean_diameter=0.01),
     'pitch = None is invalid: must be a number [m] or a string with a unit such as "2 mm"'),
    (dict(pitch=1e-3, mean_diameter="wide"), 'mean_diameter = "wide" is invalid'),
    (dict(pitch=1e-3, mean_diameter=0.01, starts=1.5),
     "starts = 1.5 is invalid: must be an integer >= 1"),
    (dict(pitch=1e-3, mean_diameter=0.01, starts=True), "starts = True is invalid"),
    (dict(pitch=1e-3, mean_diameter=0.01, flank_angle="30 %"), 'flank_angle = "30 %" is invalid'),
    (dict(pitch=1e-3, mean_diameter=0.01, hand=1),
     'hand = 1 is invalid: must be one of "right", "left"'),
    (dict(pitch=10**400, mean_diameter=0.01), "pitch = 1000"),
])
def test_bad_thread_parameters_are_named_without_a_constructor_dump(kwargs, message):
    with pytest.raises(ValueError) as info:
        ls.Thread(**kwargs)
    assert str(info.value).startswith(message), str(info.value)
    assert "incompatible" not in str(info.value)


def test_closed_forms_take_unit_strings():
    t = ls.Thread(0.003, 0.02, flank_angle=math.radians(30))
    assert ls.raise_torque(t, "0.3", "1 kN", "10 %", "25 mm") == \
        ls.raise_torque(t, 0.3, 1000.0, 0.1, 0.025)
    assert ls.lower_torque(t, "30 %", "100 N") == ls.lower_torque(t, 0.3, 100.0)
    assert ls.efficiency(t, "0.3", collar_mu="0.1", collar_diameter="25 mm",
                         backdrive=True) == ls.efficiency(t, 0.3, 0.1, 0.025, True)
    assert ls.is_self_locking(t, "0.3") is ls.is_self_locking(t, 0.3)
    assert ls.is_drivable(t, "30 %") is ls.is_drivable(t, 0.3)


@pytest.mark.parametrize("call, message", [
    (lambda t: ls.raise_torque(t, "0.3", "100 N*m"), 'load = "100 N*m" is invalid: '
                                                     '"100 N*m" is not a force (N)'),
    (lambda t: ls.lower_torque(t, "0.3 m", 1.0), 'mu = "0.3 m" is invalid'),
    (lambda t: ls.efficiency(t, 0.3, collar_diameter="2 N"), 'collar_diameter = "2 N"'),
    (lambda t: ls.efficiency(t, 0.3, backdrive="yes"),
     "backdrive = 'yes' is invalid: must be True or False"),
    (lambda t: ls.is_self_locking(t, None), "mu = None is invalid: must be a number"),
    (lambda t: ls.is_drivable(t, [0.3]), "mu = [0.3] is invalid: must be a number"),
    (lambda t: ls.raise_torque("Tr 10x2", 0.3, 1.0),
     "thread = 'Tr 10x2' is invalid: must be a leadscrew.Thread"),
])
def test_closed_forms_name_a_bad_parameter(call, message):
    with pytest.raises(ValueError) as info:
        call(ls.Thread(0.003, 0.02))
    assert str(info.value).startswith(message), str(info.value)
