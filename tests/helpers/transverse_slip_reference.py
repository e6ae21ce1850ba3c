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

The thread (docs/physics/rigid_drive.md's model and conventions): the flank
carries the normal force N~ and the helix-direction friction T~; quasi-static
(phi'' = 0) they are the stick forces of section 6,

    N~_st = -(F cos(alpha) + h (M / r) sin(alpha)),
    T~_st = (M / r) cos(alpha) - h F sin(alpha),

whatever the friction law, and on the flank's 2-D cone (mu' = mu / cos(beta/2)
on the in-plane normal force) the helix slip gamma = rho phi' with transverse
slip w balances T~_st = mu' |N~_st| gamma / |(gamma, w)|: the block's form
with r -> q = |T~_st| / (mu' |N~_st|) (thread_flank_ratio). Free rotor
(M = 0): q = tan(alpha) / mu', below 1 exactly where the thread is
self-locking. The load then creeps along F at sin(alpha) |gamma|
(u_load = -h p phi, p = rho sin(alpha)).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["creep_speed", "mean_creep_speed_sine", "inertia_number", "thread_flank_ratio",
           "thread_load_creep_speed", "thread_load_creep_speed_driven",
           "thread_inertia_number", "stribeck_mean_creep_speed_sine",
           "thread_dc_motor_mean_creep_speed_sine"]


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



def thread_flank_ratio(torque: float, force: float, lead_angle: float, mean_radius: float,
                       effective_mu: float, hand: int = 1) -> float:
    """q = |T~_st| / (mu' |N~_st|): the share of the flank's cone the loads use
    at rest (rigid_drive.md section 6), the thread's r.

    Args:
        torque: drive torque M on the rotor [N*m].
        force: axial force F on the load [N].
        lead_angle: alpha [rad].
        mean_radius: r [m].
        effective_mu: mu' = mu / cos(beta / 2).
        hand: h = +1 (right) or -1 (left).
    """
    normal = -(force * math.cos(lead_angle) + hand * torque / mean_radius * math.sin(lead_angle))
    tangential = torque / mean_radius * math.cos(lead_angle) - hand * force * math.sin(lead_angle)
    return abs(tangential) / (effective_mu * abs(normal))


def thread_load_creep_speed(force: float, lead_angle: float, effective_mu: float,
                            transverse: float, hand: int = 1) -> float:
    """Quasi-static creep of the load [m/s] of a thread held by friction alone
    (free rotor, M = 0) at transverse flank slip w: along F at
    sin(alpha) |w| q / sqrt(1 - q^2), q = tan(alpha) / mu' < 1."""
    q = math.tan(lead_angle) / effective_mu
    if not q < 1.0:
        raise ValueError(f"q = {q} must be < 1: the thread is not self-locking")
    helix = abs(transverse) * q / math.sqrt(1.0 - q * q)
    return math.copysign(math.sin(lead_angle) * helix, force)


def thread_load_creep_speed_driven(torque: float, force: float, lead_angle: float,
                                   mean_radius: float, effective_mu: float, transverse: float,
                                   hand: int = 1) -> float:
    """Quasi-static creep of the load [m/s] of a thread under a drive torque M
    and an axial force F at transverse flank slip w, the loads inside the cone
    (q < 1, thread_flank_ratio).

    The helix slip takes the stick force's direction, gamma = sign(T~_st) |w|
    q / sqrt(1 - q^2), and the load follows it: u_load = -h p phi with
    gamma = rho phi', p = rho sin(alpha), so v_load = -h sin(alpha) gamma.
    With M = 0 this is thread_load_creep_speed.
    """
    q = thread_flank_ratio(torque, force, lead_angle, mean_radius, effective_mu, hand)
    if not q < 1.0:
        raise ValueError(f"q = {q} must be < 1: the loads leave the cone, the thread slides")
    tangential = torque / mean_radius * math.cos(lead_angle) - hand * force * math.sin(lead_angle)
    helix = math.copysign(abs(transverse) * q / math.sqrt(1.0 - q * q), tangential)
    return -hand * math.sin(lead_angle) * helix


def thread_inertia_number(rotor_inertia: float, load_mass: float, torque: float, force: float,
                          lead_angle: float, mean_radius: float, effective_mu: float,
                          amplitude: float, omega: float, hand: int = 1) -> float:
    """The block's inertia number for the rigid thread: m_h W omega / (mu' |N~_st|
    (1 - q^2)^(3/2)), with the drive's inertia reduced to the helix slip,
    m_h = (J + m p^2) / rho^2 (gamma = rho phi', rho = r / cos(alpha),
    p = r tan(alpha) the load's travel per radian)."""
    q = thread_flank_ratio(torque, force, lead_angle, mean_radius, effective_mu, hand)
    rho = mean_radius / math.cos(lead_angle)
    p = mean_radius * math.tan(lead_angle)
    helix_mass = (rotor_inertia + load_mass * p * p) / (rho * rho)
    normal = abs(force * math.cos(lead_angle) + hand * torque / mean_radius * math.sin(lead_angle))
    return helix_mass * amplitude * omega / (effective_mu * normal * (1.0 - q * q) ** 1.5)


def _stribeck_creep_speed(force, normal_force, curve, viscous, transverse):
    """The quasi-static v >= 0 of (mu(s) N + c s) v / s = F, s = |(v, w)|,
    by bisection; the balance must be increasing in v (checked on a grid:
    a falling curve can make it fold, and then the creep is no function)."""
    def path_force(v):
        s = math.hypot(v, transverse)
        return (curve(s) * normal_force + viscous * s) * v / s

    hi = abs(transverse)
    while path_force(hi) < force:
        hi *= 2.0
    grid = [path_force(hi * k / 400) for k in range(401)]
    if any(b < a for a, b in zip(grid, grid[1:])):
        raise ValueError("the quasi-static balance folds: no unique creep speed")
    lo = 0.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if path_force(mid) < force:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def stribeck_mean_creep_speed_sine(force, normal_force, mu, mu_static, stribeck_velocity,
                                   stribeck_exponent, viscous, amplitude):
    """Mean quasi-static creep speed [m/s] under w = W sin(omega t) with
    Stribeck's curve on the slip speed, mu(s) = mu + (mu_static - mu)
    exp(-(s / v_s)^delta), and a viscous term c s along the slip: the
    balance (mu(s) N + c s) v / s = F solved at each w (no closed form) and
    averaged over a half period by 64-point Gauss-Legendre on each of its
    halves (v(W sin theta) is smooth on (0, pi/2] and symmetric)."""
    def curve(s):
        return mu + (mu_static - mu) * math.exp(-((s / stribeck_velocity) ** stribeck_exponent))

    nodes, weights = np.polynomial.legendre.leggauss(64)
    total = 0.0
    for x, weight in zip(nodes, weights):  # theta in (0, pi/2)
        theta = 0.25 * math.pi * (x + 1.0)
        total += weight * _stribeck_creep_speed(force, normal_force, curve, viscous,
                                                amplitude * math.sin(theta))
    return total * 0.25 * math.pi / (0.5 * math.pi)


def _dc_motor_helix_slip(force, lead_angle, mean_radius, effective_mu, hand, voltage,
                         resistance, torque_constant, transverse):
    """The quasi-static helix slip gamma [m/s] of a thread driven by a DC
    motor without inductance at transverse slip w: the helix balance
    T~_st(M) = mu' |N~_st(M)| gamma / |(gamma, w)| with the motor's torque
    M = k (V - k phi') / R at the rotor speed phi' = gamma / rho the slip
    itself moves (rho = r / cos(alpha)), by bisection. The balance falls
    with gamma (the motor's torque falls, the friction's helix component
    rises); checked on a grid, as the Stribeck balance is."""
    rho = mean_radius / math.cos(lead_angle)

    def balance(gamma):
        torque = torque_constant * (voltage - torque_constant * gamma / rho) / resistance
        normal = -(force * math.cos(lead_angle)
                   + hand * torque / mean_radius * math.sin(lead_angle))
        tangential = (torque / mean_radius * math.cos(lead_angle)
                      - hand * force * math.sin(lead_angle))
        return tangential - effective_mu * abs(normal) * gamma / math.hypot(gamma, transverse)

    low, high = -1.0, 1.0
    while balance(low) < 0.0:
        low *= 2.0
    while balance(high) > 0.0:
        high *= 2.0
    grid = [balance(low + (high - low) * k / 400) for k in range(401)]
    if any(b > a for a, b in zip(grid, grid[1:])):
        raise ValueError("the quasi-static balance is not monotonic: no unique creep speed")
    for _ in range(200):
        mid = 0.5 * (low + high)
        if balance(mid) > 0.0:
            low = mid
        else:
            high = mid
    return 0.5 * (low + high)


def thread_dc_motor_mean_creep_speed_sine(force, lead_angle, mean_radius, effective_mu, hand,
                                          voltage, resistance, torque_constant, amplitude):
    """Mean quasi-static creep of the load [m/s] under w = W sin(omega t) of
    a thread whose rotor a DC motor drives (no inductance: the current
    follows the voltage and the back-EMF at once, i = (V - k phi') / R):
    the helix slip solved at each w (_dc_motor_helix_slip) and averaged over
    a quarter period by 64-point Gauss-Legendre (it depends on |w| alone);
    the load follows it, v_load = -h sin(alpha) gamma. At V = 0 the motor
    is a brake (M = -k^2 phi' / R), and as k -> 0 this is the free rotor's
    thread_load_creep_speed."""
    nodes, weights = np.polynomial.legendre.leggauss(64)
    total = 0.0
    for x, weight in zip(nodes, weights):  # theta in (0, pi/2)
        theta = 0.25 * math.pi * (x + 1.0)
        total += weight * _dc_motor_helix_slip(force, lead_angle, mean_radius, effective_mu,
                                               hand, voltage, resistance, torque_constant,
                                               amplitude * math.sin(theta))
    return -hand * math.sin(lead_angle) * total * 0.5
