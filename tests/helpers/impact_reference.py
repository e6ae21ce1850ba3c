"""Independent frictional impact law of a flank (Newton's law on the normal
velocity, Coulomb's law on the impulses), by enumerating its three cases.

Written from docs/physics/drive_models.md (thread kinematics W_N, W_T) with
NumPy only, not from the C++ code: the velocity jump is
    M (v+ - v-) = W_N P_N + W_T P_T,    W_N . v+ = -e W_N . v-,
and either stick (W_T . v+ = 0, |P_T| <= mu' |P_N|) or slip
(P_T = -mu' |P_N| sign(W_T . v+), W_T . v+ != 0). The normal impulse pushes
the flanks apart: P_N has the sign opposite to the approach W_N . v-.
"""

import numpy as np


def frictional_impact(mass, normal, tangent, mu, velocity_before, restitution=0.0):
    """Post-impact velocities of a diagonal-mass system.

    Args:
        mass: diagonal of the mass matrix [kg or kg*m^2].
        normal, tangent: W_N and W_T (the flank's normal and sliding directions
            in generalized coordinates).
        mu: friction coefficient mu' [1].
        velocity_before: generalized velocities before the impact.
        restitution: Newton's coefficient e [1].

    Returns:
        (velocity_after, normal_impulse, tangential_impulse, mode) with mode
        "stick", "slip+" or "slip-".

    Raises:
        AssertionError: not exactly one case consistent (no impact law).
    """
    inverse_mass = 1.0 / np.asarray(mass, dtype=float)
    normal = np.asarray(normal, dtype=float)
    tangent = np.asarray(tangent, dtype=float)
    v = np.asarray(velocity_before, dtype=float)
    approach = normal @ v
    assert approach != 0.0
    side = -np.sign(approach)  # sign of P_N
    g_nn = normal @ (inverse_mass * normal)
    g_nt = normal @ (inverse_mass * tangent)
    g_tt = tangent @ (inverse_mass * tangent)
    normal_target = -(1.0 + restitution) * approach  # W_N . dv
    slip_before = tangent @ v

    def after(p_n, p_t):
        return v + inverse_mass * (normal * p_n + tangent * p_t)

    found = []
    # Stick: [g_nn g_nt; g_nt g_tt] [P_N; P_T] = [normal_target; -slip_before].
    p_n, p_t = np.linalg.solve([[g_nn, g_nt], [g_nt, g_tt]], [normal_target, -slip_before])
    if side * p_n >= 0.0 and abs(p_t) <= mu * abs(p_n) * (1.0 + 1e-12):
        found.append((after(p_n, p_t), p_n, p_t, "stick"))
    # Slip with sign s after the impact: P_T = -s mu side P_N.
    for s in (1.0, -1.0):
        k = -s * mu * side
        p_n = normal_target / (g_nn + g_nt * k)
        p_t = k * p_n
        slip_after = slip_before + g_nt * p_n + g_tt * p_t
        if side * p_n >= 0.0 and s * slip_after > 0.0:
            found.append((after(p_n, p_t), p_n, p_t, "slip+" if s > 0 else "slip-"))
    assert len(found) == 1, f"{len(found)} consistent impact cases"
    return found[0]


def flank_impact(mass, normal, tangent, mu, velocity_before, restitution, closes):
    """The event-driven scheme's flank impact (docs/physics/result_checks.md,
    "losses"): :func:`frictional_impact` at restitution e, or, where Newton's
    restitution with Coulomb friction would create kinetic energy (Kane and
    Levinson's paradox), at the largest restitution in [0, e] that creates
    none (an energetic coefficient, Stronge; a plastic frictional impact
    dissipates, so bisection on [0, e] finds it). Where the flank then
    closes (``closes``: a bounce too weak to leave it), the normal velocity
    left (and the slip, where the impact stuck) is taken out by plastic
    impulses along M^-1 W_N (and M^-1 W_T), so that the closed flank has
    zero normal velocity (and sticks). Returns what
    :func:`frictional_impact` returns."""
    mass = np.asarray(mass, dtype=float)
    normal = np.asarray(normal, dtype=float)
    v = np.asarray(velocity_before, dtype=float)

    def kinetic(u):
        return 0.5 * float(np.sum(mass * u * u))

    before = kinetic(v)
    round_off = 64 * np.finfo(float).eps * before
    result = frictional_impact(mass, normal, tangent, mu, v, restitution)
    if kinetic(result[0]) - before > round_off:
        low, high = 0.0, restitution
        for _ in range(60):
            middle = 0.5 * (low + high)
            if kinetic(frictional_impact(mass, normal, tangent, mu, v, middle)[0]) - before \
                    <= round_off:
                low = middle
            else:
                high = middle
        result = frictional_impact(mass, normal, tangent, mu, v, low)
    if closes:
        # Closed: zero normal velocity, and zero slip where the impact stuck
        # (the closed contact's stick); the least change in the metric of M.
        rows = [normal] + ([np.asarray(tangent, dtype=float)] if result[3] == "stick" else [])
        along = np.array([row / mass for row in rows])
        gram = np.array([[a @ b for b in along * mass] for a in along])
        impulses = np.linalg.solve(gram, [row @ result[0] for row in rows])
        result = (result[0] - impulses @ along,) + tuple(result[1:])
    return result
