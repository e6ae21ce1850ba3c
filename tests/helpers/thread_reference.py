"""Independent closed forms of power-screw mechanics (angle form).

Written with the friction angle rho' = atan(mu') rather than the torque
ratios the package uses, so that the two implementations check each other:
  T_raise = F r_m tan(alpha + rho'),      valid while alpha + rho' < pi/2
  T_lower = F r_m tan(rho' - alpha)
  eta     = tan(alpha) / tan(alpha + rho')
  eta'    = tan(alpha - rho') / tan(alpha)
"""

import math


def lead_angle(pitch, mean_diameter, starts=1):
    return math.atan(starts * pitch / (math.pi * mean_diameter))


def friction_angle(mu, flank_angle=0.0):
    return math.atan(mu / math.cos(flank_angle / 2.0))


def raise_torque(pitch, mean_diameter, mu, load, starts=1, flank_angle=0.0):
    alpha = lead_angle(pitch, mean_diameter, starts)
    rho = friction_angle(mu, flank_angle)
    if alpha + rho >= math.pi / 2:
        return math.inf
    return load * mean_diameter / 2.0 * math.tan(alpha + rho)


def lower_torque(pitch, mean_diameter, mu, load, starts=1, flank_angle=0.0):
    alpha = lead_angle(pitch, mean_diameter, starts)
    rho = friction_angle(mu, flank_angle)
    return load * mean_diameter / 2.0 * math.tan(rho - alpha)


def efficiency(pitch, mean_diameter, mu, starts=1, flank_angle=0.0):
    alpha = lead_angle(pitch, mean_diameter, starts)
    rho = friction_angle(mu, flank_angle)
    if alpha + rho >= math.pi / 2:
        return 0.0
    return math.tan(alpha) / math.tan(alpha + rho)


def backdrive_efficiency(pitch, mean_diameter, mu, starts=1, flank_angle=0.0):
    alpha = lead_angle(pitch, mean_diameter, starts)
    rho = friction_angle(mu, flank_angle)
    return math.tan(alpha - rho) / math.tan(alpha)
