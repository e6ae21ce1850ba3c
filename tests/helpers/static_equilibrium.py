"""Closed forms of a drive at rest in static equilibrium under a drive torque
M and an axial force F (docs/physics/drive_models.md, "The start").

Written from the statics of the bodies, not from the core's coordinates:

- the stuck thread carries the loads alone: its in-plane force (normal and
  friction, orthogonal) has the magnitude sqrt((M / r_m)^2 + F^2), the
  torque's force at the mean radius and the axial force; without a torque
  it splits into |N| = |F| cos(alpha) and |T| = |F| sin(alpha);
- a spring in the load path deflects by the force it carries over its
  stiffness: a screw-driven drive (right hand h = +1, left h = -1) has the
  nut's axial spring carrying F (u_load - u_nut = F / k), its torsion spring
  the torque (phi_nut = M / k), the flexible screw's torsion spring the
  torque (phi_screw - phi_rotor = -M / k) and its axial spring F
  (u_screw = F / k);
- the thread's play e = e_0 + (u_screw - u_nut) - h p (phi_screw - phi_nut)
  is 0 without backlash and +-c/2 on a flank (the flank the force presses
  the nut against: +c/2 for F < 0, the nut pushed along -x).
"""

import math
from typing import Dict


def thread_force(torque: float, force: float, mean_diameter: float) -> float:
    """|(N, T)| [N]: the magnitude of the thread's in-plane force holding the loads."""
    return math.hypot(torque / (0.5 * mean_diameter), force)


def screw_driven(torque: float, force: float, lead: float, hand: int, springs: Dict[str, float],
                 flank: float = 0.0) -> Dict[str, float]:
    """The coordinates of a screw-driven flexible_nut (``springs``: nut axial
    and torsional stiffness) or flexible drive (also screw axial and
    torsional, constant) at rest under (torque, force), the play at
    ``flank`` (0, or +-c/2 the flank)."""
    p = lead / (2.0 * math.pi)
    q = {"phi_rotor": 0.0}
    if "screw_axial" in springs:
        q["phi_screw"] = -torque / springs["screw_torsional"]
        q["u_screw"] = force / springs["screw_axial"]
    screw_u, screw_phi = q.get("u_screw", 0.0), q.get("phi_screw", 0.0)
    q["phi_nut"] = torque / springs["nut_torsional"]
    # e = (u_screw - u_nut) - h p (phi_screw - phi_nut) = flank
    q["u_nut"] = screw_u - hand * p * (screw_phi - q["phi_nut"]) - flank
    q["u_load"] = q["u_nut"] + force / springs["nut_axial"]
    return q


def elastic_energy(torque: float, force: float, springs: Dict[str, float]) -> float:
    """The springs' energy [J] of :func:`screw_driven`'s state: each carries
    the torque or the force."""
    energy = 0.5 * force ** 2 / springs["nut_axial"] + 0.5 * torque ** 2 / springs["nut_torsional"]
    if "screw_axial" in springs:
        energy += 0.5 * force ** 2 / springs["screw_axial"]
        energy += 0.5 * torque ** 2 / springs["screw_torsional"]
    return energy
