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

__all__ = ["effective_mu", "half_torque", "raise_torque", "lower_torque", "efficiency"]


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
