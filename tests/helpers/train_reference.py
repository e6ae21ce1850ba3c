"""Closed forms of the drive train's friction stages on the rigid drive
without play (issue 19, items 1 and 2; docs/physics/gear.md, "Friction
stages"), written from the rotor's and the driven side's equations of
motion, independent of the leadscrew package. SI units.

The rotor (inertia J_r, motor torque T, Coulomb friction T_c) turns n times
the driven part (angle phi, the screw with the thread and the load); every
contact slips with the sign s of phi'. On phi:

  rotor         n^2 J_r phi'' = U - x,       U = n T - |n| T_c s
  stage         x = k tau_b                  (k = 1 / eta where the power flows
                                              to the driven part, tau_b s > 0;
                                              k = eta_b where it flows back)
  driven side   phi'' = a tau_b + b F        (the bare rigid drive without the
                                              rotor, rigid_drive_reference's
                                              slip mode eps, its rotor inertia 0)

so phi'' = (a U + k b F) / (k + a n^2 J_r). A combination (eps, power flow)
is consistent where the thread's normal force has the sign eps assumes and
tau_b s the stage's. A worm is the lossy law with eta = tan(g) / tan(g + rho'),
eta_b = tan(g - rho') / tan(g), rho' = atan(mu / cos(beta_w / 2)).

At a steady slip (phi'' = 0) the driven part takes its bare steady torque
T_d (dc_motor_reference.steady_torque) = tau_b, so the rotor's torque is
T = (k T_d + |n| T_c s) / n: the train's efficiency raising is eta times the
thread's (with T_c = 0).
"""

from __future__ import annotations

import dataclasses
import math

from . import dc_motor_reference
from .rigid_drive_reference import RigidDrive

__all__ = ["worm_efficiencies", "slip_acceleration", "consistent_starts",
           "steady_rotor_torque", "holds_at_rest"]


def worm_efficiencies(lead_angle: float, mu: float, flank_angle: float):
    """(eta, eta_b) of a worm of lead angle gamma [rad], coefficient mu and
    included flank angle beta_w [rad]."""
    rho = math.atan(mu / math.cos(flank_angle / 2))
    return (math.tan(lead_angle) / math.tan(lead_angle + rho),
            math.tan(lead_angle - rho) / math.tan(lead_angle))


def _ratio(stage_sign: int, efficiency: float, efficiency_backdrive: float) -> float:
    return 1.0 / efficiency if stage_sign > 0 else efficiency_backdrive


def slip_acceleration(drive: RigidDrive, ratio: float, torque: float, force: float,
                      direction: int, friction_torque: float = 0.0, efficiency: float = 1.0,
                      efficiency_backdrive: float = 1.0) -> list:
    """The accelerations phi'' [rad/s^2] of the driven part of every
    consistent combination in a slip of sign ``direction``: the rotor of
    ``drive`` (drive.rotor_inertia its own) behind the stage of ratio n,
    under the rotor's torque T and the axial force F."""
    driven = dataclasses.replace(drive, rotor_inertia=0.0)
    reflected = ratio * ratio * drive.rotor_inertia
    s = direction
    u = ratio * torque - abs(ratio) * friction_torque * s
    found = []
    for eps in (1.0, -1.0):
        a, b = driven.a(eps), driven.b(eps)
        for stage_sign in (1, -1):
            k = _ratio(stage_sign, efficiency, efficiency_backdrive)
            acceleration = (a * u + k * b * force) / (k + a * reflected)
            tau_b = (acceleration - b * force) / a
            normal = float(driven.K(tau_b, force)) / (driven.cos_alpha * driven.delta(eps))
            if normal != 0.0 and driven.h * s * math.copysign(1.0, normal) != eps:
                continue
            if stage_sign * s * tau_b < 0.0:
                continue
            found.append(acceleration)
    return found


def consistent_starts(drive: RigidDrive, ratio: float, torque: float, force: float,
                      friction_torque: float = 0.0, efficiency: float = 1.0,
                      efficiency_backdrive: float = 1.0) -> list:
    """The accelerations phi'' [rad/s^2] from rest of every consistent slip
    combination in either direction (slip_acceleration's whose sign is the
    slip's): one where the train starts, none where it holds."""
    return [a for direction in (1, -1)
            for a in slip_acceleration(drive, ratio, torque, force, direction, friction_torque,
                                       efficiency, efficiency_backdrive)
            if a * direction > 0.0]


def steady_rotor_torque(drive: RigidDrive, ratio: float, force: float, direction: int,
                        friction_torque: float = 0.0, efficiency: float = 1.0,
                        efficiency_backdrive: float = 1.0) -> float:
    """The rotor's torque [N m] that keeps the driven part slipping at a
    constant speed of the sign ``direction`` under the axial force F."""
    driven_torque = dc_motor_reference.steady_torque(drive, force, direction)
    stage_sign = 1 if driven_torque * direction > 0.0 else -1
    k = _ratio(stage_sign, efficiency, efficiency_backdrive)
    return (k * driven_torque + abs(ratio) * friction_torque * direction) / ratio


def holds_at_rest(drive: RigidDrive, ratio: float, torque: float, force: float,
                  friction_torque: float = 0.0, efficiency: float = 1.0,
                  efficiency_backdrive: float = 1.0, samples: int = 51) -> bool:
    """Coulomb's static solution: some torque tau_b on the driven part that
    its thread holds at rest (|T_st| <= mu' |N_st|, the reference's stick
    forces, linear in tau_b: an interval between the edges T_st = +-mu' N_st)
    for which the stage's rotor-side torque x (between eta_b tau_b and
    tau_b / eta) lies within |n| T_c of n T; tau_b sampled over the interval,
    its edges included."""
    driven = dataclasses.replace(drive, rotor_inertia=0.0)
    mu = driven.mu_eff
    n0, t0 = (float(v) for v in driven.stick_forces(0.0, force))
    n1, t1 = (float(v) - w for v, w in zip(driven.stick_forces(1.0, force), (n0, t0)))
    edges = [-(t0 - c * mu * n0) / (t1 - c * mu * n1) for c in (1.0, -1.0)]
    low_edge, high_edge = min(edges), max(edges)
    u, c = ratio * torque, abs(ratio) * friction_torque
    for k in range(samples):
        tau = low_edge + (high_edge - low_edge) * k / (samples - 1)
        low, high = sorted((efficiency_backdrive * tau, tau / efficiency))
        if low <= u + c and high >= u - c:
            return True
    return False


def simulate(drive: RigidDrive, ratio: float, torque, force: float, t_end: float,
             friction_torque: float = 0.0, efficiency: float = 1.0,
             efficiency_backdrive: float = 1.0):
    """The train from rest under the rotor's torque M(t) (a callable) and a
    constant axial force F, by modes: in a slip the one consistent
    combination's acceleration (slip_acceleration) integrated by SciPy's
    DOP853 to its end (phi' = 0), at rest the static stick test
    (holds_at_rest) scanned and bisected to its end. Returns (events,
    omega): the mode changes [(time, "stick->slip+"), ...] and phi'(t) as a
    callable (the driven part's speed)."""
    from scipy.integrate import solve_ivp

    args = (friction_torque, efficiency, efficiency_backdrive)

    def holds(t):
        return holds_at_rest(drive, ratio, torque(t), force, *args)

    def start(t):
        starts = [d for d in (1, -1) if any(a * d > 0.0 for a in slip_acceleration(
            drive, ratio, torque(t), force, d, *args))]
        assert len(starts) == 1, (t, starts)
        return starts[0]

    def acceleration(t, direction):
        found = slip_acceleration(drive, ratio, torque(t), force, direction, *args)
        assert len(found) >= 1
        assert max(found) - min(found) <= 1e-9 * max(abs(a) for a in found) + 1e-300
        return found[0]

    events, pieces, t = [], [], 0.0
    mode, omega0 = "stick", 0.0
    while t < t_end:
        if mode == "stick":
            step, after = 1e-4, t
            while after < t_end and holds(min(after + step, t_end)):
                after += step
            if after >= t_end:
                pieces.append((t, t_end, lambda s: 0.0 * s))
                break
            low, high = after, min(after + step, t_end)
            for _ in range(200):
                middle = 0.5 * (low + high)
                if middle in (low, high):
                    break
                low, high = (middle, high) if holds(middle) else (low, middle)
            pieces.append((t, high, lambda s: 0.0 * s))
            direction = start(high + 1e-9)  # (at its edge a start's phi'' is 0)
            mode = "slip+" if direction > 0 else "slip-"
            events.append((high, "stick->" + mode))
            t, omega0 = high, 0.0
            continue
        direction = 1 if mode == "slip+" else -1

        def stopped(s, y):
            return y[0]
        stopped.terminal, stopped.direction = True, -direction
        solution = solve_ivp(lambda s, y: [acceleration(s, direction)], (t, t_end), [omega0],
                             method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True,
                             events=stopped)
        pieces.append((t, solution.t[-1], lambda s, f=solution.sol: f(s)[0]))
        if solution.status != 1:
            break
        t = float(solution.t_events[0][0])
        before = mode
        if holds(t):
            mode = "stick"
        else:
            mode = "slip+" if start(t) > 0 else "slip-"
        events.append((t, before + "->" + mode))
        omega0 = 0.0

    def omega(s):
        for begin, end, f in pieces:
            if begin <= s <= end:
                return float(f(s))
        return float(pieces[-1][2](pieces[-1][1]))

    return events, omega
