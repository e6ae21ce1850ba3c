"""Independent pure-NumPy implementation of the smooth drive models.

Written from docs/physics/drive_models.md only (not from the C++ sources), as
a reference for ``leadscrew.simulate`` and as the Python right-hand side of
the drive benchmark. SI units: m, kg, s, rad, N, N*m, J.

Scope: the smooth formulations of the document:

- friction ``arctan_velocity``: lambda_T = -(2/pi) mu' |lambda_N| atan(k_V gamma_T),
  mu' = mu / cos(beta / 2);
- thread without play: the kinematic constraint e = 0 (the translating part's
  axial contact coordinate is eliminated), lambda_N its multiplier with the
  sign sigma chosen so that sigma lambda_N >= 0 (none or both consistent:
  :class:`PythonJamming`);
- backlash ``bistop`` or ``cubic``: penalty force P(d, d') on each flank,
  clamped at P >= 0, lambda_N = (P_lower - P_upper) / cos(alpha);
- concepts ``rigid``, ``flexible_nut``, ``flexible``; ``drive`` screw or nut;
  both hands, flank angle; drive torque or speed-controlled motor; loads
  constant or sine.

Generalized coordinates (all displacements from the initial configuration,
springs relaxed at t = 0), in this order: ``phi_rotor``; ``u_R``, ``phi_R``
of a flexible rotating part; ``u_T``, ``phi_T`` of a flexible translating
part; ``u_load``. The mass matrix is diagonal.

Thread pair (h = +1 right, -1 left, p = lead / 2 pi, r = mean radius):
  e = e_0 + (u_screw - u_nut) - h p (phi_screw - phi_nut)
  W_N = cos(alpha) grad(e)
  W_T = grad of sin(alpha) du + h r cos(alpha) dphi,  gamma_T = W_T . v
Generalized flank force W_N lambda_N + W_T lambda_T (the force on the screw
along the flank normal and the helix tangent, the opposite on the nut).

State vector layout of :meth:`DriveEquations.rhs`:
  y = [positions of every coordinate except the eliminated one,
       velocities of every coordinate except the eliminated and the
       prescribed (speed-controlled rotor) one,
       (optional) work_drive, work_axial, friction_loss, damping_loss,
       contact_loss]
"""

from __future__ import annotations

import math
from typing import Dict, Optional, Sequence

import numpy as np
from scipy.integrate import solve_ivp

__all__ = ["DriveEquations", "PythonJamming", "simulate_python", "ENERGY_NAMES",
           "OUTPUT_NAMES"]

ENERGY_NAMES = ("work_drive", "work_axial", "friction_loss", "damping_loss", "contact_loss")
OUTPUT_NAMES = ("u_load", "v_load", "phi_drive", "omega_drive", "normal_force",
                "friction_force", "slip_velocity", "drive_torque", "axial_force", "play",
                "kinetic", "elastic") + ENERGY_NAMES + ("energy_residual",)


class PythonJamming(RuntimeError):
    """No or two consistent normal-force signs of the thread without play."""

    def __init__(self, time: float, reason: str):
        super().__init__(f"t = {time:.17g} s: {reason}")
        self.time = time
        self.reason = reason


class _Load:
    """value(t) and derivative(t) of a scene load (number, constant or sine dict)."""

    def __init__(self, spec, path: str):
        if isinstance(spec, (int, float)) and not isinstance(spec, bool):
            self.offset, self.amplitude, self.omega, self.phase = float(spec), 0.0, 0.0, 0.0
        elif isinstance(spec, dict) and spec.get("type") == "constant":
            self.offset = float(spec["value"])
            self.amplitude, self.omega, self.phase = 0.0, 0.0, 0.0
        elif isinstance(spec, dict) and spec.get("type") == "sine":
            self.offset = float(spec.get("offset", 0.0))
            self.amplitude = float(spec["amplitude"])
            self.omega = float(spec["omega"])
            self.phase = float(spec.get("phase", 0.0))
        else:
            raise ValueError(f"{path} = {spec!r}: drive_python supports constant and sine "
                             "loads only")

    def value(self, t: float) -> float:
        return self.offset + self.amplitude * math.sin(self.omega * t + self.phase)

    def derivative(self, t: float) -> float:
        return self.amplitude * self.omega * math.cos(self.omega * t + self.phase)


def _step3(x: float, x1: float) -> float:
    """Adams STEP(x, 0, 0, x1, 1): cubic 3 s^2 - 2 s^3 with s = x / x1 clamped to [0, 1]."""
    if x <= 0.0:
        return 0.0
    if x >= x1:
        return 1.0
    s = x / x1
    return s * s * (3.0 - 2.0 * s)


class DriveEquations:
    """The equations of motion of a scene's drive (smooth formulations).

    Args:
        scene: a ``leadscrew.Scene``. Read from it: ``to_dict()`` (geometry,
            friction, backlash, loads, initial state) and ``derived()``
            (masses, inertias, rigidities E A, G I_p, stiffnesses, contact
            defaults). Spring damping follows the document's rule
            c = 2 zeta sqrt(k(a_0) m_max) unless overridden.

    Raises:
        ValueError: a formulation outside the scope (exact Coulomb,
            arctan_acceleration, exact backlash, table loads).
    """

    def __init__(self, scene):
        d = scene.to_dict()
        der = scene.derived()
        self.data, self.derived = d, der
        friction = d["friction"]
        if friction["law"] != "arctan_velocity":
            raise ValueError(f"friction.law = {friction['law']!r}: drive_python implements "
                             "'arctan_velocity' only")
        backlash = d.get("backlash")
        if backlash is not None and backlash["contact"] not in ("bistop", "cubic"):
            raise ValueError(f"backlash.contact = {backlash['contact']!r}: drive_python "
                             "implements 'bistop' and 'cubic' only")
        thread = d["thread"]
        self.h = 1.0 if thread["hand"] == "right" else -1.0
        lead = thread["starts"] * thread["pitch"]
        self.p = lead / (2.0 * math.pi)
        self.r = thread["mean_diameter"] / 2.0
        self.alpha = math.atan2(self.p, self.r)
        self.cos_a, self.sin_a = math.cos(self.alpha), math.sin(self.alpha)
        self.mu_eff = friction["mu"] / math.cos(thread["flank_angle"] / 2.0)
        self.k_v = friction["k_v"]
        self.concept, self.drive = d["concept"], d["drive"]

        # ---- coordinates and the diagonal mass matrix --------------------------------
        rotating = "screw" if self.drive == "screw" else "nut"
        translating = "nut" if self.drive == "screw" else "screw"
        flexible = {"rigid": set(), "flexible_nut": {"nut"},
                    "flexible": {"screw", "nut"}}[self.concept]
        names, mass = ["phi_rotor"], [d["rotor"]["inertia"]]
        contact = {}  # part -> (index of u or None for ground, index of phi or None)
        if rotating in flexible:
            names += [f"u_{rotating}", f"phi_{rotating}"]
            mass += [der[f"{rotating}_mass"], der[f"{rotating}_inertia"]]
            contact[rotating] = (1, 2)
        else:
            mass[0] += der[f"{rotating}_inertia"]
            contact[rotating] = (None, 0)
        load_mass = d["load"]["mass"]
        if translating in flexible:
            i = len(names)
            names += [f"u_{translating}", f"phi_{translating}"]
            mass += [der[f"{translating}_mass"], der[f"{translating}_inertia"]]
            contact[translating] = (i, i + 1)
        else:
            load_mass += der[f"{translating}_mass"]
        self.load = len(names)
        names.append("u_load")
        mass.append(load_mass)
        if translating not in flexible:
            contact[translating] = (self.load, None)
        self.names = names
        self.n = n = len(names)
        self.mass = np.array(mass, dtype=float)
        self.rotating, self.translating = rotating, translating
        self.flexible = flexible

        # ---- thread kinematics: grad(e) and W_T -------------------------------------
        grad_e = np.zeros(n)
        w_t = np.zeros(n)
        for part, sign in (("screw", 1.0), ("nut", -1.0)):
            iu, iphi = contact[part]
            if iu is not None:
                grad_e[iu] += sign
                w_t[iu] += sign * self.sin_a
            if iphi is not None:
                grad_e[iphi] += -sign * self.h * self.p
                w_t[iphi] += sign * self.h * self.r * self.cos_a
        self.grad_e, self.w_n, self.w_t = grad_e, self.cos_a * grad_e, w_t
        self.u_screw_index, self.u_nut_index = contact["screw"][0], contact["nut"][0]
        self.e0 = d["initial"]["play_position"]

        # ---- springs --------------------------------------------------------------
        zeta = d["overrides"]["damping_ratio"]
        over = d["overrides"]
        self.springs = []  # (i, j or None, k0, c, (A, B) for k(a) = A/a + B/(L-a) or None)
        a0, length = d["nut"]["position"], d["screw"]["length"]
        self.a0, self.screw_length = a0, length

        def add(name, i, j, k_const, law=None, damping_key=None):
            k0 = k_const if law is None else law[0] / a0 + (law[1] / (length - a0)
                                                            if law[1] else 0.0)
            m_max = max(self.mass[i], self.mass[j] if j is not None else 0.0)
            c = over.get(damping_key, 2.0 * zeta * math.sqrt(k0 * m_max))
            self.springs.append((name, i, j, k0, c, law))

        if "nut" in flexible:
            iu, iphi = contact["nut"]
            if self.drive == "screw":  # translating: axial to the load, torsion to ground
                add("nut axial", iu, self.load, der["nut_axial_stiffness"],
                    damping_key="nut_axial_damping")
                add("nut torsion", iphi, None, der["nut_torsional_stiffness"],
                    damping_key="nut_torsional_damping")
            else:  # rotating: torsion to the rotor, axial to ground
                add("nut torsion", iphi, 0, der["nut_torsional_stiffness"],
                    damping_key="nut_torsional_damping")
                add("nut axial", iu, None, der["nut_axial_stiffness"],
                    damping_key="nut_axial_damping")
        if "screw" in flexible:
            iu, iphi = contact["screw"]
            ea, gip = der["screw_axial_rigidity"], der["screw_torsional_rigidity"]
            if der["screw_axial_stiffness"] > 0.0:
                axial_law, axial_k = None, der["screw_axial_stiffness"]
            else:
                both = self.drive == "screw" and d["screw"]["support"] == "both_ends"
                axial_law, axial_k = (ea, ea if both else 0.0), None
            if der["screw_torsional_stiffness"] > 0.0:
                torsion_law, torsion_k = None, der["screw_torsional_stiffness"]
            else:
                torsion_law, torsion_k = (gip, 0.0), None
            if self.drive == "screw":  # rotating: torsion to the rotor, axial to ground
                add("screw torsion", iphi, 0, torsion_k, torsion_law, "screw_torsional_damping")
                add("screw axial", iu, None, axial_k, axial_law, "screw_axial_damping")
            else:  # translating: axial to the load, torsion to ground
                add("screw axial", iu, self.load, axial_k, axial_law, "screw_axial_damping")
                add("screw torsion", iphi, None, torsion_k, torsion_law,
                    "screw_torsional_damping")
        self.position_dependent = any(s[5] is not None for s in self.springs)

        # ---- backlash ---------------------------------------------------------------
        self.backlash = backlash
        if backlash is not None:
            self.half_clearance = backlash["axial"] / 2.0
            self.contact_law = backlash["contact"]
            self.k_c = der["contact_stiffness"]
            self.c_c = der["contact_damping"]
            self.d_0 = der["contact_penetration"]
            self.exponent = backlash["exponent"]

        # ---- loads --------------------------------------------------------------------
        loads = d["loads"]
        self.speed_controlled = "drive_speed" in loads
        # A scene that gives no drive torque has none (the core's default 0).
        self.torque = None if self.speed_controlled else _Load(loads.get("drive_torque", 0.0),
                                                               "loads.drive_torque")
        self.speed = _Load(loads["drive_speed"], "loads.drive_speed") \
            if self.speed_controlled else None
        self.force = _Load(loads["axial_force"], "loads.axial_force")

        # ---- which coordinates are integrated ---------------------------------------
        # Without play the translating part's axial contact coordinate is eliminated
        # through e = 0 (a linear constraint with constant gradient).
        self.eliminated = contact[translating][0] if backlash is None else None
        self.position_index = np.array([i for i in range(n) if i != self.eliminated], dtype=int)
        self.velocity_index = np.array([i for i in range(n) if i != self.eliminated
                                        and not (self.speed_controlled and i == 0)], dtype=int)
        if self.eliminated is not None:
            others = np.array([i for i in range(n) if i != self.eliminated], dtype=int)
            self._others = others
            self._elim_weights = -grad_e[others] / grad_e[self.eliminated]
        self.inverse_mass = 1.0 / self.mass
        if self.speed_controlled:
            self.inverse_mass_free = self.inverse_mass.copy()
            self.inverse_mass_free[0] = 0.0
        else:
            self.inverse_mass_free = self.inverse_mass
        # constants of the constraint solve
        self._g_minv_wn = float(self.grad_e @ (self.inverse_mass_free * self.w_n))
        self._g_minv_wt = float(self.grad_e @ (self.inverse_mass_free * self.w_t))
        self.n_pos, self.n_vel = len(self.position_index), len(self.velocity_index)

        # ---- initial state: springs relaxed, every body moving with the thread -----
        omega0 = self.speed.value(0.0) if self.speed_controlled else d["initial"].get("rotor_speed", 0.0)
        v0 = np.zeros(n)
        v0[0] = omega0
        if rotating in flexible:
            v0[contact[rotating][1]] = omega0
        v0[self.load] = -self.h * self.p * omega0
        if translating in flexible:
            v0[contact[translating][0]] = -self.h * self.p * omega0
        self.v0 = v0
        self.rotor_angle0 = d["initial"]["rotor_angle"]

    # ------------------------------------------------------------------------------
    def full_state(self, t: float, y: np.ndarray):
        """Positions q and velocities v of every coordinate from the state y."""
        n = self.n
        q = np.empty(n)
        v = np.empty(n)
        q[self.position_index] = y[:self.n_pos]
        v[self.velocity_index] = y[self.n_pos:self.n_pos + self.n_vel]
        if self.speed_controlled:
            v[0] = self.speed.value(t)
        if self.eliminated is not None:
            w = self._elim_weights
            q[self.eliminated] = w @ q[self._others]  # e_0 = 0 without play
            v[self.eliminated] = w @ v[self._others]
        return q, v

    def initial_state(self, with_energy: bool = True) -> np.ndarray:
        y = [np.zeros(self.n_pos), self.v0[self.velocity_index]]
        if with_energy:
            y.append(np.zeros(len(ENERGY_NAMES)))
        return np.concatenate(y)

    def _penalty(self, d: float, d_dot: float):
        """Flank penalty: (applied force P >= 0, elastic part, potential)."""
        if d <= 0.0:
            return 0.0, 0.0, 0.0
        k, d0 = self.k_c, self.d_0
        if self.contact_law == "bistop":
            n = self.exponent
            elastic = k * d ** n
            potential = k * d ** (n + 1.0) / (n + 1.0)
        elif d < d0:
            elastic = k * d ** 3 / (3.0 * d0 * d0)
            potential = k * d ** 4 / (12.0 * d0 * d0)
        else:
            elastic = k * (d - d0) + k * d0 / 3.0
            potential = k * d0 * d0 / 12.0 + 0.5 * k * (d - d0) ** 2 + k * d0 / 3.0 * (d - d0)
        force = elastic + self.c_c * _step3(d, d0) * d_dot
        return max(force, 0.0), elastic, potential

    def _applied(self, t: float, q: np.ndarray, v: np.ndarray):
        """Generalized forces of springs, loads and penalty flanks (everything but
        the thread constraint's multiplier), and the terms of the energy account."""
        Q = np.zeros(self.n)
        elastic = 0.0
        p_damping = 0.0
        # springs, with the position-dependent screw stiffness k(a) and its k'(a) force
        if self.springs:
            a_nut = self.a0
            if self.position_dependent:
                a_nut += q[self.u_nut_index] - q[self.u_screw_index]
            for _name, i, j, k0, c, law in self.springs:
                x = q[i] - (q[j] if j is not None else 0.0)
                xd = v[i] - (v[j] if j is not None else 0.0)
                if law is None:
                    k = k0
                else:
                    rest = self.screw_length - a_nut
                    k = law[0] / a_nut + (law[1] / rest if law[1] else 0.0)
                    dk = -law[0] / (a_nut * a_nut) + (law[1] / (rest * rest) if law[1] else 0.0)
                    # -(1/2) k'(a) x^2 da/dq with da/du_nut = +1, da/du_screw = -1
                    g = -0.5 * dk * x * x
                    Q[self.u_nut_index] += g
                    Q[self.u_screw_index] -= g
                f = -k * x - c * xd
                Q[i] += f
                if j is not None:
                    Q[j] -= f
                elastic += 0.5 * k * x * x
                p_damping += c * xd * xd
        force = self.force.value(t)
        Q[self.load] += force
        torque = 0.0
        if not self.speed_controlled:
            torque = self.torque.value(t)
            Q[0] += torque
        gamma = float(self.w_t @ v)
        kappa = (2.0 / math.pi) * self.mu_eff * math.atan(self.k_v * gamma)
        e = self.e0 + float(self.grad_e @ q)
        terms = {"elastic": elastic, "p_damping": p_damping, "p_contact": 0.0,
                 "torque": torque, "force": force, "gamma": gamma, "kappa": kappa, "e": e,
                 "lam_n": 0.0}
        if self.backlash is not None:
            e_dot = float(self.grad_e @ v)
            half = self.half_clearance
            p_lower, el_lower, pot_lower = self._penalty(-e - half, -e_dot)
            p_upper, el_upper, pot_upper = self._penalty(e - half, e_dot)
            terms["elastic"] += pot_lower + pot_upper
            # loss rate (P - P_elastic) d' of each flank: its damping and its clamp
            terms["p_contact"] = (p_lower - el_lower) * (-e_dot) + (p_upper - el_upper) * e_dot
            lam_n = (p_lower - p_upper) / self.cos_a
            Q += self.w_n * lam_n + self.w_t * (-kappa * abs(lam_n))
            terms["lam_n"] = lam_n
        return Q, terms

    def _constraint_numerator(self, t: float, Q: np.ndarray) -> float:
        """A in e'' = A + lambda_N grad(e) . M^-1 (W_N - kappa sigma W_T) = 0."""
        numerator = float(self.grad_e @ (self.inverse_mass_free * Q))
        if self.speed_controlled:
            numerator += self.grad_e[0] * self.speed.derivative(t)
        return numerator

    def _denominators(self, kappa: float):
        """grad(e) . M^-1 (W_N - kappa sigma W_T) for sigma = +1, -1."""
        return (self._g_minv_wn - kappa * self._g_minv_wt,
                self._g_minv_wn + kappa * self._g_minv_wt)

    def jamming_margin(self, t: float, y: np.ndarray) -> float:
        """min over sigma of the constraint denominators (thread without play).

        With A != 0 exactly one normal-force sign is consistent iff both
        denominators are > 0 (they sum to 2 grad(e) . M^-1 W_N > 0, so at most
        one is <= 0; if den_s < 0 both signs or none are consistent). A root
        of this function is therefore where the drive jams (Painleve). With
        A = 0 (K = 0) the slip stays unique: then the margin returned is the
        frictionless value, > 0.
        """
        q, v = self.full_state(t, y)
        Q, terms = self._applied(t, q, v)
        if self._constraint_numerator(t, Q) == 0.0:
            return self._g_minv_wn
        return min(self._denominators(terms["kappa"]))

    def forces(self, t: float, q: np.ndarray, v: np.ndarray, strict: bool = True):
        """Everything at (t, q, v): accelerations and the terms of the energy account.

        Args:
            strict: without play, raise PythonJamming where not exactly one
                normal-force sign is consistent. Off inside the right-hand side,
                whose trial states may lie beyond a jam (the jam is located as
                a root of :meth:`jamming_margin` on accepted steps); there the
                regular sign sigma = sign(-A) is kept.

        Returns:
            dict with ``a`` (accelerations of every coordinate), ``normal_force``,
            ``friction_force``, ``slip_velocity``, ``drive_torque``,
            ``axial_force``, ``play`` (e), the powers ``p_drive``, ``p_axial``,
            ``p_friction`` (>= 0), ``p_damping``, ``p_contact`` and ``elastic``.

        Raises:
            PythonJamming: strict, no play, and no or two consistent signs.
        """
        Q, terms = self._applied(t, q, v)
        kappa = terms["kappa"]
        lam_n = terms["lam_n"]
        a_prescribed = self.speed.derivative(t) if self.speed_controlled else 0.0
        if self.backlash is None:
            # e'' = grad(e) . a = 0 with a = M^-1 (Q + (W_N - kappa sigma W_T) lambda_N)
            numerator = self._constraint_numerator(t, Q)
            lam_n = 0.0
            if numerator != 0.0:
                dens = self._denominators(kappa)
                consistent = [-numerator / den for sigma, den in zip((1.0, -1.0), dens)
                              if den != 0.0 and -sigma * numerator / den > 0.0]
                if len(consistent) == 1:
                    lam_n = consistent[0]
                elif strict:
                    raise PythonJamming(t, f"{'no' if not consistent else 'two'} consistent "
                                           "normal-force signs")
                else:  # trial state beyond a jam: keep the regular sign, stay finite
                    den = dens[0] if numerator < 0.0 else dens[1]
                    lam_n = -numerator / (den if den > 0.0 else self._g_minv_wn)
            Q += self.w_n * lam_n + self.w_t * (-kappa * abs(lam_n))
        lam_t = -kappa * abs(lam_n)
        torque = terms["torque"]
        a = self.inverse_mass_free * Q
        if self.speed_controlled:
            a[0] = a_prescribed
            torque = self.mass[0] * a_prescribed - Q[0]  # the motor's multiplier
        gamma = terms["gamma"]
        return {
            "a": a, "normal_force": lam_n, "friction_force": lam_t, "slip_velocity": gamma,
            "drive_torque": torque, "axial_force": terms["force"], "play": terms["e"],
            "p_drive": torque * v[0], "p_axial": terms["force"] * v[self.load],
            "p_friction": -lam_t * gamma, "p_damping": terms["p_damping"],
            "p_contact": terms["p_contact"], "elastic": terms["elastic"],
        }

    def rhs(self, t: float, y: np.ndarray, with_energy: bool = True) -> np.ndarray:
        """dy/dt in the layout of the module docstring."""
        q, v = self.full_state(t, y)
        f = self.forces(t, q, v, strict=False)
        parts = [v[self.position_index], f["a"][self.velocity_index]]
        if with_energy:
            parts.append([f["p_drive"], f["p_axial"], f["p_friction"], f["p_damping"],
                          f["p_contact"]])
        return np.concatenate(parts)

    def outputs(self, t: np.ndarray, y: np.ndarray,
                with_energy: bool = True) -> Dict[str, np.ndarray]:
        """Channels at the times t from the states y (shape (n_state, len(t)))."""
        out = {name: np.empty(len(t)) for name in OUTPUT_NAMES}
        for k, tk in enumerate(t):
            q, v = self.full_state(tk, y[:, k])
            f = self.forces(tk, q, v)
            out["u_load"][k] = q[self.load]
            out["v_load"][k] = v[self.load]
            out["phi_drive"][k] = self.rotor_angle0 + q[0]
            out["omega_drive"][k] = v[0]
            for name in ("normal_force", "friction_force", "slip_velocity", "drive_torque",
                         "axial_force", "play", "elastic"):
                out[name][k] = f[name]
            out["kinetic"][k] = 0.5 * float(self.mass @ (v * v))
        if with_energy:
            base = self.n_pos + self.n_vel
            for m, name in enumerate(ENERGY_NAMES):
                out[name] = y[base + m].copy()
            change = (out["kinetic"] - out["kinetic"][0]) + (out["elastic"] - out["elastic"][0])
            out["energy_residual"] = (out["work_drive"] + out["work_axial"] - change
                                      - out["friction_loss"] - out["damping_loss"]
                                      - out["contact_loss"])
        else:
            for name in ENERGY_NAMES + ("energy_residual",):
                del out[name]
        return out


def simulate_python(scene, t_end: float, t_eval: Optional[Sequence[float]] = None,
                    method: str = "Radau", rtol: float = 1e-10, atol: float = 1e-12,
                    with_energy: bool = True, detect_jamming: bool = True,
                    **options) -> Dict[str, np.ndarray]:
    """Integrate a scene's smooth drive equations with scipy.integrate.solve_ivp.

    Args:
        scene: a ``leadscrew.Scene`` (arctan_velocity friction; no backlash,
            or bistop/cubic backlash).
        t_end: end time [s].
        t_eval: output times [s] (default: 101 points on [0, t_end]).
        method: a solve_ivp method ("Radau", "LSODA", "BDF", "DOP853", ...).
        rtol, atol: solve_ivp tolerances (atol on every state component:
            positions [m, rad], velocities [m/s, rad/s], energies [J]).
        with_energy: integrate the energy account as quadrature states.
        detect_jamming: thread without play: locate the jam as a root of
            :meth:`DriveEquations.jamming_margin` (one extra evaluation of the
            applied forces per step).
        options: passed on to solve_ivp (e.g. max_step, first_step).

    Returns:
        dict with ``t`` and the channels of :data:`OUTPUT_NAMES` (energy terms
        only with ``with_energy``), plus solve_ivp's counters ``nfev``,
        ``njev``, ``nlu``.

    Raises:
        RuntimeError: solve_ivp failed.
        PythonJamming: the thread without play jams (time of the root).
    """
    eq = DriveEquations(scene)
    if t_eval is None:
        t_eval = np.linspace(0.0, t_end, 101)
    t_eval = np.asarray(t_eval, dtype=float)
    events = None
    if detect_jamming and eq.backlash is None and eq.mu_eff > 0.0:
        def jam(t, y):
            return eq.jamming_margin(t, y)
        jam.terminal = True
        events = [jam]
    sol = solve_ivp(lambda t, y: eq.rhs(t, y, with_energy), (0.0, float(t_end)),
                    eq.initial_state(with_energy), method=method, t_eval=t_eval, rtol=rtol,
                    atol=atol, events=events, **options)
    if sol.status == 1:
        raise PythonJamming(float(sol.t_events[0][0]), "a normal-force denominator "
                            "reaches zero: beyond it no or two signs are consistent")
    if sol.status != 0:
        raise RuntimeError(f"solve_ivp ({method}) failed: {sol.message}")
    out = eq.outputs(sol.t, sol.y, with_energy)
    out["t"] = sol.t
    out["nfev"], out["njev"], out["nlu"] = sol.nfev, sol.njev, sol.nlu
    return out
