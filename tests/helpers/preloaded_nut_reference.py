"""Closed forms of a preloaded split nut on the rigid drive (issue 19, item 4;
docs/physics/preloaded_nut.md), written from the power screw's raising and
lowering torques, independent of the leadscrew package. SI units.

Two nut halves sprung apart by the preload P: half A carries the axial load
F (F > 0 presses half A's flank) plus P, half B carries P on the opposite
flank. Each half is a power screw under its own axial force a: moving
against a it needs r_m a tan(alpha + rho'), moving with it r_m a
tan(rho' - alpha) (rho' = atan mu', mu' = mu / cos(beta / 2)). Where F < -P,
half A's force F + P is negative: it bears on half B's flank side (the
bilateral rigid thread), and the motion moves it with its push.
"""

from __future__ import annotations

import math

__all__ = ["effective_mu", "half_torque", "raise_torque", "lower_torque", "efficiency",
           "bistop_penetration", "cubic_penetration", "stuck_axial_load", "lift_off_load",
           "lift_off_axial"]


def effective_mu(mu: float, flank_angle: float) -> float:
    """mu' = mu / cos(beta / 2) for the included flank angle beta [rad]."""
    return mu / math.cos(0.5 * flank_angle)


def half_torque(axial: float, against: bool, alpha: float, mu_eff: float,
                mean_radius: float) -> float:
    """The torque [N m] that moves one half with axial force ``axial`` >= 0
    [N] on its flank against it (``against``) or with it, in steady slip."""
    rho = math.atan(mu_eff)
    factor = math.tan(alpha + rho) if against else math.tan(rho - alpha)
    return mean_radius * axial * factor


def raise_torque(load: float, preload: float, alpha: float, mu_eff: float,
                 mean_radius: float) -> float:
    """The steady torque [N m] that moves the nut against a load ``load`` on
    half A's flank side (negative: on half B's side) with preload P:
    r_m [(F + P) tan(alpha + rho') + P tan(rho' - alpha)] for F >= -P."""
    a_axial = load + preload
    half_a = (half_torque(a_axial, True, alpha, mu_eff, mean_radius) if a_axial >= 0.0
              else half_torque(-a_axial, False, alpha, mu_eff, mean_radius))
    return half_a + half_torque(preload, False, alpha, mu_eff, mean_radius)


def lower_torque(load: float, preload: float, alpha: float, mu_eff: float,
                 mean_radius: float) -> float:
    """The steady torque [N m] that moves the nut with a load ``load`` >= -P
    on half A's flank side: r_m [(F + P) tan(rho' - alpha) + P tan(alpha + rho')]."""
    return (half_torque(load + preload, False, alpha, mu_eff, mean_radius)
            + half_torque(preload, True, alpha, mu_eff, mean_radius))


def efficiency(load: float, preload: float, alpha: float, mu_eff: float) -> float:
    """Raising efficiency F tan(alpha) / [(F + P) tan(alpha + rho') + P tan(rho' - alpha)]."""
    return load * math.tan(alpha) / raise_torque(load, preload, alpha, mu_eff, 1.0)


# --- Lift-off on the flexible concepts with penalty flanks
# (docs/physics/preloaded_nut.md, "Lift-off"). Half A is the nut body on its
# penalty flank (axial force f(d) at the penetration d), half B a massless
# half on its own rigid flank, sprung against the body by S = P + k_p x, x
# the body's axial displacement toward half B's flank from the assembled
# nut (half A's flank penetrated to d_0 = f^-1(P)).

def bistop_penetration(force: float, stiffness: float, exponent: float) -> float:
    """The penetration [m] at which BISTOP's elastic force k d^e is ``force`` [N]."""
    return (force / stiffness) ** (1.0 / exponent) if force > 0.0 else 0.0


def cubic_penetration(force: float, stiffness: float, depth: float) -> float:
    """The penetration [m] of the cubic contact at ``force`` [N]: k d^3 / (3 d_0^2)
    below d_0 = ``depth``, k (d - d_0) + k d_0 / 3 beyond."""
    if force <= 0.0:
        return 0.0
    if force < stiffness * depth / 3.0:
        return (3.0 * depth * depth * force / stiffness) ** (1.0 / 3.0)
    return depth + (force - stiffness * depth / 3.0) / stiffness


def stuck_axial_load(axial: float, x: float, alpha: float, mean_radius: float,
                     torsional_stiffness: float) -> float:
    """The axial load [N] on the nut body that holds the forces ``axial`` [N]
    along grad(e) (the flanks' and the spring's, toward half B's flank) while
    the thread sticks, at the body's displacement ``x`` [m] toward half B's
    flank: stuck, the body moves along its flank's normal (turning by
    tan(alpha) x / r_m), so the stick force takes tan(alpha)^2 of the axial
    force and the torsional stiffness k_r [N m/rad] that holds the body's
    rotation against the screw (the nut's, in series with the screw's on a
    flexible screw) adds k_r sin(alpha)^2 x / r_m^2:
    F = axial / cos(alpha)^2 + k_r sin(alpha)^2 x / r_m^2."""
    return (axial / math.cos(alpha) ** 2
            + torsional_stiffness * math.sin(alpha) ** 2 * x / mean_radius ** 2)


def lift_off_load(preload: float, preload_stiffness: float, assembled_penetration: float,
                  alpha: float, mean_radius: float, torsional_stiffness: float) -> float:
    """The axial load [N] toward half B's flank at which half A's normal force
    reaches 0 (the thread stuck, quasi-static): the spring's force then is
    P + k_p d_0 (with a linear flank k_c: P (1 + k_p / k_c)), at x = d_0."""
    spring = preload + preload_stiffness * assembled_penetration
    return stuck_axial_load(spring, assembled_penetration, alpha, mean_radius,
                            torsional_stiffness)


def lift_off_axial(x: float, preload: float, preload_stiffness: float,
                   flank_stiffness: float, clearance: float) -> float:
    """The forces [N] along grad(e) toward half B's flank at the body's
    displacement x [m] with a linear flank k_c: the spring P + k_p x, half
    A's flank -k_c (d_0 - x) while it bears (x < d_0), the opposite flank
    k_c (x - d_0 - c) once the play c is taken up."""
    d0 = preload / flank_stiffness
    return (preload + preload_stiffness * x - flank_stiffness * max(0.0, d0 - x)
            + flank_stiffness * max(0.0, x - d0 - clearance))
