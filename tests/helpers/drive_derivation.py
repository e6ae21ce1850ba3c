"""Independent reference: a drive's masses, inertias and stiffnesses from its
geometry and material (thesis eq. 4.17, 4.18, 4.24; docs/physics/drive_models.md),
written from the formulas, not from the package's code.

Screw: a solid cylinder (radius r_S, length L); nut: a hollow cylinder of outer
radius r_o on it (inner radius r_S, length l_M). G = E / (2 (1 + nu)).

    m_S = rho_S pi r_S^2 L              J_S = m_S r_S^2 / 2
    m_M = rho_M pi (r_o^2 - r_S^2) l_M  J_M = m_M (r_o^2 + r_S^2) / 2
    screw axial rigidity E_S pi r_S^2, torsional G_S pi r_S^4 / 2
    nut axial stiffness E_M pi (r_o^2 - r_S^2) / l_M          (eq. 4.17)
    nut torsional stiffness G_M pi (r_o^4 - r_S^4) / (2 l_M)  (eq. 4.18, polar)

The screw's own stiffness follows the nut (0 here unless overridden). With
backlash: penetration of full damping d_0 = max(c_a / 100, 1e-7 m); contact
stiffness k = k_M d_0^(1 - e) for 'bistop' (exponent e: the force k d_0^e
equals the nut's k_M d_0), k_M otherwise; damping 2 sqrt(k d_0^(e - 1) m_t)
(critical, of the linear-equivalent stiffness, e = 1 but for 'bistop') with
m_t the load and the translating part (the nut for drive = 'screw', the screw
for 'nut'). Each override replaces its quantity (damping and stiffness of
the contact, its penetration, and overrides.*).
"""

from __future__ import annotations

import math
from typing import Any, Dict

__all__ = ["DEFAULTS", "derived_reference", "thread_reference"]

# The scene's defaults of the fields the derivation reads (scene.py's schema).
DEFAULTS = {
    "screw": {"radius": 10e-3, "length": 0.5, "youngs_modulus": 210e9, "poisson": 0.3,
              "density": 7850.0},
    "nut": {"outer_radius": 12e-3, "length": 20e-3, "youngs_modulus": 2e9, "poisson": 0.3,
            "density": 1400.0},
    "load": {"mass": 1.0},
    "backlash": {"contact": "exact", "exponent": 1.5},
}


def _section(scene: Dict[str, Any], name: str) -> Dict[str, Any]:
    return {**DEFAULTS.get(name, {}), **scene.get(name, {})}


def derived_reference(scene: Dict[str, Any]) -> Dict[str, float]:
    """What Scene.derived() gives for the scene dict ``scene`` (SI numbers;
    absent fields take their defaults)."""
    screw, nut, load = _section(scene, "screw"), _section(scene, "nut"), _section(scene, "load")
    over = scene.get("overrides", {})
    r_s, r_o = screw["radius"], nut["outer_radius"]
    shear_s = screw["youngs_modulus"] / (2 * (1 + screw["poisson"]))
    shear_n = nut["youngs_modulus"] / (2 * (1 + nut["poisson"]))
    # The annulus and its polar moment in forms without cancellation (a thin
    # wall, r_o -> r_S, loses digits in r_o^2 - r_S^2 by its condition number
    # (r_o^2 + r_S^2) / (r_o^2 - r_S^2), which the tests allow for).
    annulus = math.pi * (r_o - r_s) * (r_o + r_s)
    annulus_polar = annulus * (r_o**2 + r_s**2) / 2
    screw_mass = over.get("screw_mass", screw["density"] * math.pi * r_s**2 * screw["length"])
    nut_mass = over.get("nut_mass", nut["density"] * annulus * nut["length"])
    nut_axial = over.get("nut_axial_stiffness", nut["youngs_modulus"] * annulus / nut["length"])
    out = {
        "screw_mass": screw_mass,
        "screw_inertia": over.get("screw_inertia", screw_mass * r_s**2 / 2),
        "nut_mass": nut_mass,
        "nut_inertia": over.get("nut_inertia", nut_mass * (r_o**2 + r_s**2) / 2),
        "screw_axial_rigidity": screw["youngs_modulus"] * math.pi * r_s**2,
        "screw_torsional_rigidity": shear_s * math.pi * r_s**4 / 2,
        "nut_axial_stiffness": nut_axial,
        "nut_torsional_stiffness": over.get(
            "nut_torsional_stiffness", shear_n * annulus_polar / nut["length"]),
        "screw_axial_stiffness": over.get("screw_axial_stiffness", 0.0),
        "screw_torsional_stiffness": over.get("screw_torsional_stiffness", 0.0),
    }
    if "backlash" in scene:
        backlash = _section(scene, "backlash")
        d0 = backlash.get("penetration", max(backlash["axial"] / 100, 1e-7))
        e = backlash["exponent"] if backlash["contact"] == "bistop" else 1.0
        k = backlash.get("stiffness", nut_axial * d0 / d0**e)
        carried = load["mass"] + (nut_mass if scene.get("drive", "screw") == "screw"
                                  else screw_mass)
        out["contact_stiffness"] = k
        out["contact_damping"] = backlash.get("damping",
                                              2 * math.sqrt(k * d0**(e - 1) * carried))
        out["contact_penetration"] = d0
    return out


def thread_reference(scene: Dict[str, Any]) -> Dict[str, float]:
    """tan(lead angle) = starts pitch / (pi d_m) and mu' = mu / cos(beta / 2)."""
    t = scene["thread"]
    return {"tan_lead_angle": t.get("starts", 1) * t["pitch"] / (math.pi * t["mean_diameter"]),
            "effective_mu": scene["friction"]["mu"] / math.cos(t.get("flank_angle", 0.0) / 2)}
