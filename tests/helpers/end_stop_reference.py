"""Closed forms of the penalty end stop (issue 19, item 3;
docs/physics/end_stops.md), written from the stop's law and the power-screw
balance, independent of the leadscrew package. SI units.

The stop at the face u_s (side +1 upper, -1 lower) with penetration
d = side (u - u_s) pushes with F = max(0, k d + c d') where d > 0:

- Static deflection under a held force F_h into the stop: d = F_h / k.
- Clamp force of a rigid drive (no play) driven into the stop by a drive
  torque M, approaching slowly (the thread slipping forward, the load's and
  the rotor's inertia negligible): the stop is the load the screw raises,
  M = F r_m tan(alpha + rho'), so F = M / (r_m tan(alpha + rho')) with
  rho' = atan(mu / cos(beta / 2)) (thread_reference.raise_torque).
- The stop's energy: elastic k d^2 / 2, loss power F d' - k d d' >= 0.
- Breakaway of a clamp F held by a self-locking thread (end_stop_jam): the
  reverse torque that moves the clamped load back, quasi-statically with
  the static coefficient, is the lowering torque T_b = F r_m tan(rho_s' -
  alpha) (thread_reference.lower_torque with mu_static); a DC motor at rest
  gives k_t U / R, so U_b = R T_b / k_t.
"""

from __future__ import annotations

import numpy as np

from . import thread_reference

__all__ = ["static_deflection", "clamp_force", "breakaway_torque", "pushing_force",
           "elastic_energy", "loss_power", "train_clamp_force", "train_breakaway_torque"]


def static_deflection(force: float, stiffness: float) -> float:
    """The penetration d = F / k under a held force F [N] into a stop of stiffness k [N/m]."""
    return force / stiffness


def clamp_force(torque: float, thread: dict, mu: float) -> float:
    """The torque-limited quasi-static clamp force M / (r_m tan(alpha + rho')) [N]:
    the axial load the drive torque M [N m] raises, from the raise torque of a
    unit load (thread: the scene's thread section, SI)."""
    unit = thread_reference.raise_torque(thread["pitch"], thread["mean_diameter"], mu, 1.0,
                                         thread.get("starts", 1),
                                         thread.get("flank_angle", 0.0))
    return abs(torque) / unit


def breakaway_torque(clamp: float, thread: dict, mu_static: float) -> float:
    """F r_m tan(rho_s' - alpha) [N m]: the reverse torque that breaks a clamp
    F [N] free (thread: the scene's thread section, SI)."""
    return thread_reference.lower_torque(thread["pitch"], thread["mean_diameter"], mu_static,
                                         clamp, thread.get("starts", 1),
                                         thread.get("flank_angle", 0.0))


def pushing_force(d, rate, stiffness: float, damping: float):
    """F = max(0, k d + c d') where d > 0, else 0 [N] (arrays or numbers)."""
    d, rate = np.asarray(d, float), np.asarray(rate, float)
    return np.where(d > 0.0, np.maximum(0.0, stiffness * d + damping * rate), 0.0)


def elastic_energy(d, stiffness: float):
    """k d^2 / 2 where d > 0 [J]."""
    d = np.asarray(d, float)
    return np.where(d > 0.0, 0.5 * stiffness * d * d, 0.0)


def loss_power(d, rate, stiffness: float, damping: float):
    """F d' - k d d' where d > 0 [W]: c d'^2 in contact, -k d d' after the release."""
    d, rate = np.asarray(d, float), np.asarray(rate, float)
    force = pushing_force(d, rate, stiffness, damping)
    return np.where(d > 0.0, (force - stiffness * d) * rate, 0.0)


# --- through the train's friction stages (docs/physics/gear.md, "End stops") --
#
# Behind a stage of ratio n and forward efficiency eta and a motor with its
# own Coulomb friction T_c, the motor's torque T needed to move the thread's
# torque T_thread forward (the motor driving, the power flowing to the
# driven part) is T = T_thread / (n eta) + T_c.


def train_clamp_force(motor_torque: float, thread: dict, mu: float, ratio: float,
                      efficiency: float, friction_torque: float = 0.0) -> float:
    """The quasi-static clamp F [N] at which the train needs the motor's torque
    T [N m] (its stall torque k_t U / R, or k_t i_max): F r_m tan(alpha + rho')
    / (n eta) + T_c = T."""
    unit = thread_reference.raise_torque(thread["pitch"], thread["mean_diameter"], mu, 1.0,
                                         thread.get("starts", 1),
                                         thread.get("flank_angle", 0.0))
    return (abs(motor_torque) - friction_torque) * abs(ratio) * efficiency / unit


def train_breakaway_torque(clamp: float, thread: dict, mu_static: float, ratio: float,
                           efficiency_static: float, friction_torque: float = 0.0,
                           efficiency_backdrive_static: float = 1.0):
    """(the motor's torque [N m], the driven part's [N m]) that break a clamp
    F [N] free through the train, by Coulomb's static solution: at rest the
    thread holds any torque tau on the driven part between -T_b (T_b = F r_m
    tan(rho_s' - alpha), its lowering torque with mu_static) and T_r (F r_m
    tan(alpha + rho_s'), its raising torque), the stage passes x = k tau on
    its input with k between eta_b,static and 1 / eta_static (its extremes
    at the ends), and the motor's friction holds |n| T_c: the motor moves the
    clamp back beyond the largest -k tau, plus T_c. A self-locking thread
    driven back through the stage: T_b / (n eta_static) + T_c; a self-locking
    stage (eta_b,static < 0) locked by the thread's holding at its raising
    edge: |eta_b,static| T_r / n + T_c, where that is larger."""
    low = -breakaway_torque(clamp, thread, mu_static)
    high = thread_reference.raise_torque(thread["pitch"], thread["mean_diameter"], mu_static,
                                         clamp, thread.get("starts", 1),
                                         thread.get("flank_angle", 0.0))
    splits = [(-k * tau, abs(tau)) for k in (efficiency_backdrive_static, 1.0 / efficiency_static)
              for tau in (low, high)]
    held, driven = max(splits)
    return held / abs(ratio) + friction_torque, driven
