"""Closed forms of a DC motor on the rigid drive (issue 19, item 1), written
from the armature equation L di/dt = U - R i - k_e omega and the torque k_t i,
independent of the leadscrew package. SI units.

- Steady state on the rigid drive without play: the rotor turns at a constant
  speed omega > 0 where the motor's torque equals the torque the train needs,
  T (the rigid drive's slip mode with zero acceleration,
  rigid_drive_reference: a_eps T + b_eps F = 0 with the consistent
  eps = h s sign(lam~)); then i = T / k_t and omega = (U - R i) / k_e.
- Back-driven (a thread with tan(alpha) > mu' under a load the stalled
  motor cannot hold): the same balance slipping at omega < 0 (direction
  -1), i = T / k_t > U / R, so omega = (U - R i) / k_e < 0.
- Stalled rotor (the thread sticks): omega = 0, so
  i(t) = U / R (1 - exp(-t R / L)), the stall current U / R, the electrical
  time constant L / R.
- A current-limited driver bounded by its supply, |U_d| <= |U| (L = 0): the
  free current (U - k_e omega) / R where it lies within i_max; beyond, the
  driver's voltage that holds the limit, R (+-i_max) + k_e omega, clipped to
  [-|U|, |U|], and the current (U_d - k_e omega) / R that voltage gives.
  On Moreau-Jean a row reports its step's armature (docs/physics/dc_motor.md,
  "Moreau-Jean"): the back-EMF at the step's speed omega_theta = (1 - theta)
  omega_k + theta omega_k+1, held over the step (``step_speed``).
"""

from __future__ import annotations

import math

import numpy as np

from .rigid_drive_reference import RigidDrive

__all__ = ["rigid_drive", "steady_torque", "steady_state", "stalled_current", "step_speed",
           "limited_driver"]


def rigid_drive(scene: dict, derived: dict) -> RigidDrive:
    """The rigid drive of a scene dict (Scene.to_dict()) and its derived
    masses and inertias (Scene.derived()), screw-driven, right-hand."""
    thread, friction = scene["thread"], scene["friction"]
    return RigidDrive(lead=thread["pitch"] * thread["starts"],
                      mean_radius=thread["mean_diameter"] / 2, mu=friction["mu"],
                      rotor_inertia=scene["rotor"]["inertia"],
                      screw_inertia=derived["screw_inertia"], screw_mass=derived["screw_mass"],
                      nut_inertia=derived["nut_inertia"], nut_mass=derived["nut_mass"],
                      load_mass=scene["load"]["mass"])


def steady_torque(drive: RigidDrive, axial_force: float, direction: float = 1.0) -> float:
    """The rotor torque [N m] that keeps the rigid drive slipping at a constant
    speed of the sign ``direction`` (+1, -1) under the axial force F [N] (the
    raise torque where F opposes a positive motion: M = -b_eps F / a_eps with
    a_eps, b_eps of the reference's slip mode, eps = h s sign(lam~), s the
    direction).

    Raises:
        ValueError: no sign of the normal force is consistent, or both are.
    """
    found = []
    for eps in (1.0, -1.0):
        torque = -drive.b(eps) * axial_force / drive.a(eps)
        normal = float(drive.K(torque, axial_force)) / (drive.cos_alpha * drive.delta(eps))
        if normal != 0.0 and drive.h * direction * math.copysign(1.0, normal) == eps:
            found.append(torque)
    if len(found) != 1:
        raise ValueError(f"steady slip at F = {axial_force!r} N: {len(found)} consistent modes")
    return found[0]


def steady_state(drive: RigidDrive, axial_force: float, voltage: float, resistance: float,
                 torque_constant: float, back_emf_constant: float, direction: float = 1.0):
    """(current [A], omega [rad/s], torque [N m]) of the DC motor at steady
    state on the rigid drive, slipping in ``direction`` (+1, -1: back-driven):
    i = T / k_t, omega = (U - R i) / k_e."""
    torque = steady_torque(drive, axial_force, direction)
    current = torque / torque_constant
    omega = (voltage - resistance * current) / back_emf_constant
    return current, omega, torque


def stalled_current(t, voltage: float, resistance: float, inductance: float):
    """i(t) = U / R (1 - exp(-t R / L)) [A] with the rotor held (L > 0)."""
    t = np.asarray(t, dtype=float)
    return voltage / resistance * -np.expm1(-t * resistance / inductance)


def limited_driver(voltage, omega, resistance: float, back_emf_constant: float,
                   current_limit: float):
    """(driver voltage U_d [V], current [A]) of a current-limited driver
    bounded by its supply |U| without inductance, at the rotor speed omega."""
    voltage, omega = np.asarray(voltage, dtype=float), np.asarray(omega, dtype=float)
    emf = back_emf_constant * omega
    free = (voltage - emf) / resistance
    side = np.sign(free)
    hold = np.clip(resistance * side * current_limit + emf, -np.abs(voltage), np.abs(voltage))
    driver = np.where(np.abs(free) <= current_limit, voltage, hold)
    return driver, (driver - emf) / resistance


def step_speed(omega, moreau: bool, theta: float = 0.5) -> np.ndarray:
    """The rotor speed each row's armature takes: the row's own (the
    event-driven scheme), or Moreau-Jean's omega_theta of the step that ends
    at the row (row 0, before any step: its own)."""
    omega = np.asarray(omega, dtype=float)
    if not moreau:
        return omega
    return np.concatenate([omega[:1], (1 - theta) * omega[:-1] + theta * omega[1:]])
