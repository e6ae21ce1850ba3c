"""Coulomb friction as an LCP (thesis sec. 2.2.1 and 3.2.6, eq. 3.9-3.14): the
builders of leadscrew.lcp against the block's closed form and an independent
contact-mode enumeration (tests/helpers/lcp_friction_reference.py)."""

import math

import numpy as np
import pytest

import leadscrew.lcp as lcp
from helpers import lcp_friction_reference as ref

METHODS = lcp.METHODS
# The thesis's block (sec. 3.2.6): m = 1, g = 10, mu = 0.3, lambda_N = m g.
MASS, GRAVITY, MU = 1.0, 10.0, 0.3
NORMAL = MASS * GRAVITY
BOUND = MU * NORMAL  # the largest static friction force, 3 N
FORCES = np.concatenate([np.linspace(-10.0, 10.0, 201), [-BOUND, BOUND, 3.0 - 1e-9, 3.0 + 1e-9]])


def block_closed_form(force):
    """Stick while |F| <= mu m g (lambda_T = F, u'' = 0), else slide with
    u'' = (F -+ mu m g)/m (eq. 3.9 with lambda_T = +-mu m g)."""
    if abs(force) <= BOUND:
        return force, 0.0
    friction = math.copysign(BOUND, force)
    return friction, (force - friction) / MASS


def check_block(friction, acceleration, force):
    expected_friction, expected_acceleration = block_closed_form(force)
    if abs(force) <= BOUND:  # stick exactly: no creep, friction within the cone
        assert abs(acceleration) <= 1e-12
        assert abs(friction) <= BOUND * (1 + 1e-15)
    assert acceleration == pytest.approx(expected_acceleration, abs=1e-12)
    assert friction == pytest.approx(expected_friction, abs=1e-12)
    # The equation of motion (3.9) itself.
    assert MASS * acceleration == pytest.approx(force - friction, abs=1e-12)


@pytest.mark.parametrize("method", METHODS)
def test_thesis_block_lcp(method):
    """Eq. (3.10)-(3.14): every method solves it (A = I/m is diagonal)."""
    for force in FORCES:
        A, b = lcp.block_friction_lcp(MASS, MU, NORMAL, force)
        np.testing.assert_array_equal(A, np.eye(2) / MASS)
        assert b[0] == pytest.approx((force - MASS * GRAVITY * MU) / MASS, abs=1e-15)
        result = lcp.solve(A, b, method=method)
        assert result.status == "solved", force
        state = lcp.block_friction_state(result.z, result.w, MU, NORMAL)
        check_block(state.friction_force, state.acceleration, force)
        # In stick the reserves are those of eq. (3.13).
        if abs(force) <= BOUND:
            np.testing.assert_allclose(result.z, [BOUND - force, BOUND + force], atol=1e-12)


def test_thesis_printed_sign_of_b2_contradicts_eq_3_9():
    """Eq. (3.14) prints b2 = +(F + m g mu)/m. With that sign the resting
    block (F = 0) would slide with u'' = w1 - w2 = -mu g instead of resting; the
    builder's b2 = -(F + m g mu)/m gives rest."""
    A = np.eye(2) / MASS
    printed_b = np.array([(0.0 - MASS * GRAVITY * MU) / MASS, (0.0 + MASS * GRAVITY * MU) / MASS])
    result = lcp.solve(A, printed_b)
    assert result.w[0] - result.w[1] == pytest.approx(-MU * GRAVITY, abs=1e-15)
    _, b = lcp.block_friction_lcp(MASS, MU, NORMAL, 0.0)
    assert b[1] == -printed_b[1]


@pytest.mark.parametrize("method", METHODS)
def test_block_through_system_form(method):
    """friction_lcp with n = 1, G = 1/m, c = -F/m (W_T = -1, so u'' = -g_T'')."""
    for force in FORCES[::4]:
        A, b = lcp.friction_lcp(1.0 / MASS, -force / MASS, MU, NORMAL)
        result = lcp.solve(A, b, method=method)
        if method == "pgs":  # A = [[G, 1], [-1, 0]] has a zero on the diagonal
            assert result.status == "singular"
            continue
        assert result.status == "solved"
        friction, tangential = lcp.friction_state(result.z, result.w, MU, NORMAL)
        check_block(friction[0], -tangential[0], force)


@pytest.mark.parametrize("method", METHODS)
def test_block_with_unknown_normal_force(method):
    """contact_lcp: the block's normal contact (W_N = 1 on the vertical
    coordinate, c_N = -g) carries lambda_N = m g without being told."""
    G = np.eye(2) / MASS
    for force in FORCES[::4]:
        A, b = lcp.contact_lcp(G, [-GRAVITY, -force / MASS], MU)
        result = lcp.solve(A, b, method=method)
        if method == "pgs":
            assert result.status == "singular"
            continue
        assert result.status == "solved"
        state = lcp.contact_state(result.z, result.w, MU)
        assert state.normal_force[0] == pytest.approx(NORMAL, abs=1e-12)
        assert state.normal_acceleration[0] == pytest.approx(0.0, abs=1e-12)
        check_block(state.friction_force[0], -state.tangential_acceleration[0], force)


def test_block_lifts_off():
    """An upward force above m g opens the contact: no normal force, no
    friction, free accelerations."""
    G = np.eye(2) / MASS
    lift, force = 12.0, 2.0
    c = np.array([(lift - MASS * GRAVITY) / MASS, -force / MASS])
    A, b = lcp.contact_lcp(G, c, MU)
    result = lcp.solve(A, b)
    assert result.status == "solved"
    state = lcp.contact_state(result.z, result.w, MU)
    assert state.normal_force[0] == 0.0 and state.friction_force[0] == 0.0
    assert state.normal_acceleration[0] == pytest.approx(c[0], abs=1e-14)
    assert state.tangential_acceleration[0] == pytest.approx(c[1], abs=1e-14)


def random_spd(rng, n, shift=0.05):
    B = rng.normal(size=(n, n))
    return B @ B.T / n + shift * np.eye(n)


@pytest.mark.parametrize("n", range(1, 6))
def test_coupled_friction_contacts(n):
    """n contacts with a coupling Delassus matrix: Lemke solves the 2n-LCP and
    its friction forces/accelerations are the unique Coulomb solution found by
    mode enumeration."""
    rng = np.random.default_rng([31, n])
    for _ in range(20):
        G = random_spd(rng, n)
        c = rng.normal(size=n) * 3
        mu = rng.uniform(0.0, 0.8, size=n)
        normal = rng.uniform(0.0, 5.0, size=n)
        A, b = lcp.friction_lcp(G, c, mu, normal)
        solutions = ref.friction_modes(G, c, mu, normal)
        assert len(solutions) == 1  # G positive definite: unique
        expected_friction, expected_acc = solutions[0]
        for method in ("lemke", "newton_fb") + (("enumerate",) if 2 * n <= 12 else ()):
            result = lcp.solve(A, b, method=method)
            if method == "lemke":
                assert result.status == "solved"
            if result.solved:
                friction, acc = lcp.friction_state(result.z, result.w, mu, normal)
                np.testing.assert_allclose(friction, expected_friction, atol=1e-9)
                np.testing.assert_allclose(acc, expected_acc, atol=1e-9)
                np.testing.assert_allclose(acc, G @ friction + c, atol=1e-9)


@pytest.mark.parametrize("n", range(1, 5))
def test_coupled_planar_contacts(n):
    """n planar contacts with normal-tangential coupling (G_NT != 0) and
    mu <= 0.5: Lemke solves the 3n-LCP and matches the unique mode solution."""
    rng = np.random.default_rng([37, n])
    for _ in range(15):
        G = random_spd(rng, 2 * n)
        c = rng.normal(size=2 * n) * 3
        mu = rng.uniform(0.0, 0.5, size=n)
        A, b = lcp.contact_lcp(G, c, mu)
        solutions = ref.contact_modes(G, c, mu)
        assert len(solutions) == 1
        expected = solutions[0]
        result = lcp.solve(A, b, method="lemke")
        assert result.status == "solved"
        state = lcp.contact_state(result.z, result.w, mu)
        for got, want in zip(state, expected):
            np.testing.assert_allclose(got, want, atol=1e-9)
        lam = np.concatenate([state.normal_force, state.friction_force])
        acc = np.concatenate([state.normal_acceleration, state.tangential_acceleration])
        np.testing.assert_allclose(acc, G @ lam + c, atol=1e-9)


def test_friction_lcp_structure():
    """A = [[G, I], [-I, 0]], b = (-(G r + c), 2 r) for r = mu lambda_N."""
    G = np.array([[2.0, 0.5], [0.5, 1.0]])
    c = np.array([1.0, -2.0])
    mu = np.array([0.2, 0.4])
    normal = np.array([10.0, 5.0])
    A, b = lcp.friction_lcp(G, c, mu, normal)
    r = mu * normal
    np.testing.assert_array_equal(A[:2, :2], G)
    np.testing.assert_array_equal(A[:2, 2:], np.eye(2))
    np.testing.assert_array_equal(A[2:, :2], -np.eye(2))
    np.testing.assert_array_equal(A[2:, 2:], 0.0)
    np.testing.assert_allclose(b, np.concatenate([-(G @ r + c), 2 * r]), rtol=1e-15)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: lcp.block_friction_lcp(0.0, MU, NORMAL, 1.0), "mass"),
        (lambda: lcp.block_friction_lcp(MASS, -0.1, NORMAL, 1.0), "mu"),
        (lambda: lcp.block_friction_lcp(MASS, MU, -1.0, 1.0), "normal_force"),
        (lambda: lcp.block_friction_lcp(MASS, MU, NORMAL, math.nan), "excitation_force"),
        (lambda: lcp.block_friction_state([1.0], [0.0, 0.0], MU, NORMAL), "z"),
        (lambda: lcp.friction_lcp(np.eye(2), [1.0], [0.1, 0.1], [1.0, 1.0]), "free_acceleration"),
        (lambda: lcp.friction_lcp(np.ones((2, 3)), [1.0, 1.0], [0.1, 0.1], [1.0, 1.0]), "delassus"),
        (lambda: lcp.friction_lcp(np.eye(2), [1.0, 1.0], [0.1, -0.1], [1.0, 1.0]), r"mu\[1\]"),
        (lambda: lcp.friction_lcp(np.eye(2), [1.0, 1.0], [0.1, 0.1], [1.0, math.inf]), r"normal_force\[1\]"),
        (lambda: lcp.friction_state(np.zeros(3), np.zeros(4), [0.1, 0.1], [1.0, 1.0]), "z"),
        (lambda: lcp.contact_lcp(np.eye(3), [0.0, 0.0], 0.3), "delassus"),
        (lambda: lcp.contact_lcp(np.eye(2), [0.0, math.nan], 0.3), r"free_acceleration\[1\]"),
        (lambda: lcp.contact_lcp(np.eye(2), [0.0, 0.0], -0.3), r"mu\[0\]"),
        (lambda: lcp.contact_state(np.zeros(3), np.zeros(2), 0.3), "w"),
    ],
)
def test_bad_input_names_the_argument(call, name):
    with pytest.raises(ValueError, match="^" + name):
        call()
