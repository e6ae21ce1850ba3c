"""Closed forms of creep under a transverse slip on an isotropic Coulomb cone
(issue 34; docs/physics/transverse_slip.md), written from the physics alone
(no package code).

A block of mass m, normal force N, friction coefficient mu, under a constant
tangential load F along its path, on a plane that slips across the path at
the prescribed velocity w(t). Its slip is the vector (v, w); in slip the
friction is -mu N (v, w) / |(v, w)|, so along the path

    m v' = F - mu N v / sqrt(v^2 + w^2).

Quasi-static (inertia negligible, m v' << mu N) the path force balances,
F = mu N v / sqrt(v^2 + w^2); with r = F / (mu N) < 1

    v = |w| r / sqrt(1 - r^2),

and under w = W sin(omega t), the mean of |sin| over a period being 2/pi,

    <v> = (2 W / pi) r / sqrt(1 - r^2).

The first inertial correction, v1 = -m v0' / (d lambda_path / dv) =
-m r |w| |w|' / (mu N (1 - r^2)^2), is a time derivative of w^2 and averages
to zero over a period: the mean's error is second order in the inertia
number m W omega / (mu N (1 - r^2)^(3/2)) (inertia_number).
"""

from __future__ import annotations

import math

__all__ = ["creep_speed", "mean_creep_speed_sine", "inertia_number"]


def creep_speed(force: float, mu: float, normal_force: float, transverse: float) -> float:
    """Quasi-static creep speed [m/s] along the path at transverse slip w.

    Args:
        force: tangential load F [N], |F| < mu N.
        mu: friction coefficient.
        normal_force: N [N] > 0.
        transverse: w [m/s].

    Returns:
        v = sign(F) |w| r / sqrt(1 - r^2), r = |F| / (mu N).
    """
    r = abs(force) / (mu * normal_force)
    if not r < 1.0:
        raise ValueError(f"r = {r} must be < 1: the block slides away, it does not creep")
    return math.copysign(abs(transverse) * r / math.sqrt(1.0 - r * r), force)


def mean_creep_speed_sine(force: float, mu: float, normal_force: float,
                          amplitude: float) -> float:
    """Mean quasi-static creep speed [m/s] under w = W sin(omega t) over whole
    periods: (2 W / pi) r / sqrt(1 - r^2)."""
    return 2.0 / math.pi * creep_speed(force, mu, normal_force, amplitude)


def inertia_number(mass: float, force: float, mu: float, normal_force: float,
                   amplitude: float, omega: float) -> float:
    """m W omega / (mu N (1 - r^2)^(3/2)): the inertia time over the slip's
    period (the friction's stiffness d lambda/dv = mu N (1 - r^2)^(3/2) / |w|
    on the quasi-static path); the quasi-static closed form's regime is
    where this is small."""
    r = abs(force) / (mu * normal_force)
    return mass * amplitude * omega / (mu * normal_force * (1.0 - r * r) ** 1.5)

