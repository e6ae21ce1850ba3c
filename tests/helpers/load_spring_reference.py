"""Closed forms of a spring on the load (docs/physics/load_spring.md), written
from its law F = -(P + k u) - c u' and the drive's kinematics, independent of
the simulator.

On the rigid drive without play and without friction (mu = 0) the thread
ties the rotating group to the load, u = -h (lead / 2 pi) phi, and the
drive is one degree of freedom of the effective mass
m_eff = m_translating + J_rotating (2 pi / lead)^2; the spring's preload
P moves the load from rest at u = 0 to oscillate about u* = -P / k.
A self-locking thread (flexible nut, screw-driven) holds the nut; the load
then rests on two springs in parallel, its own and the nut's axial one.
"""

import math

import numpy as np


def effective_mass(translating_mass, rotating_inertia, lead):
    """m_eff = m + J (2 pi / lead)^2 [kg] of the rigid drive."""
    return translating_mass + rotating_inertia * (2.0 * math.pi / lead) ** 2


def free_oscillation(t, stiffness, preload, damping, mass):
    """u(t) and u'(t) of m u'' = -(P + k u) - c u' from rest at u = 0
    (underdamped: c < 2 sqrt(k m))."""
    t = np.asarray(t, dtype=float)
    omega = math.sqrt(stiffness / mass)
    sigma = damping / (2.0 * mass)
    omega_d = math.sqrt(omega ** 2 - sigma ** 2)
    x0 = preload / stiffness  # u - u* at the start
    decay = np.exp(-sigma * t)
    cos, sin = np.cos(omega_d * t), np.sin(omega_d * t)
    u = -x0 + x0 * decay * (cos + sigma / omega_d * sin)
    v = -x0 * decay * (omega ** 2 / omega_d) * sin
    return u, v


def static_deflection(preload, stiffness, other_stiffness):
    """u* = -P / (k + k_other): the load at rest on its spring and another in
    parallel held at its far end (the nut's axial spring on a locked thread)."""
    return -preload / (stiffness + other_stiffness)
