"""Independent reference: the rigid lead-screw drive with exact Coulomb friction.

Pure Python (numpy, scipy.optimize.brentq), written from
docs/physics/rigid_drive.md and independent of the leadscrew package. SI units:
m, kg, s, rad, N, N*m.

Model (one degree of freedom, the rotor angle phi about +x):
  J_eff phi_dd = M - h p F - rho mu' |lam~| sign(phi_d)          (slip)
  phi_dd = a_eps M(t) + b_eps F(t),  eps = h s sig~ in {+1, -1}
  a_eps = (1 + eps mu' t) / Delta_eps,  b_eps = -h r (t - eps mu') / Delta_eps
  Delta_eps = J (1 + eps mu' t) + m r^2 t (t - eps mu'),  t = tan(alpha)
  lam~ = K / (cos(alpha) Delta_eps),  K = -(h m p M + J F)
with J the rotating inertia (rotor + screw for drive="screw", rotor + nut for
drive="nut"), m the translating mass (nut + load, resp. screw + load),
p = lead / (2 pi), r the mean thread radius, h = +1 (right) / -1 (left), s the
sign of phi_d, sig~ the sign of the normal force the rotating member exerts on
the translating one, mu' = mu / cos(beta / 2).
Stick (phi_d = 0) holds while |T~_st| <= mu' |lam~_st| with
  T~_st = (M / r) cos(alpha) - h F sin(alpha),
  lam~_st = -(F cos(alpha) + h (M / r) sin(alpha)).

The loads are M(t) = M0 + M1 sin(w t + phi_M) and F(t) = F0 + F1 sin(w_F t + phi_F).
Between events the motion is integrated in closed form; event times (velocity
zero, flank change K = 0, stick limit reached) are found by bracketing every
root of the event function with its extrema (recursively down to the third
derivative, sampled at 1/32 of the shortest load period) and brentq to machine
precision. A slip state in which not exactly one normal-force sign is
consistent (Painleve paradox, dynamic jamming) raises ReferenceJamming.

Reported forces follow the thesis's sign convention (F_CN, F_CT of eq. 4.7):
normal_force is the force the screw exerts on the nut along
n = (cos(alpha), -h sin(alpha)) (axial, circumferential), friction_force the
one along the helix tangent (h sin(alpha), cos(alpha)); slip_velocity is the
nut's velocity relative to the screw along that tangent.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Sequence

import numpy as np
from scipy.optimize import brentq

from .series import x_minus_sin

__all__ = [
    "ReferenceJamming",
    "Harmonic",
    "RigidDrive",
    "Phase",
    "Event",
    "Solution",
    "simulate",
    "thesis_drive",
    "thesis_loads",
]

_MAX_PHASES = 200_000
_MAX_ZERO_LENGTH_PHASES = 8
_GRID_PER_PERIOD = 32
_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(20)


class ReferenceJamming(Exception):
    """No or more than one normal-force sign is consistent in slip (Painleve paradox).

    Attributes:
        time: time [s] of the state.
        reason: which case (no consistent mode / two consistent modes) and the numbers.
    """

    def __init__(self, time: float, reason: str):
        super().__init__(f"dynamic jamming at t = {time!r} s: {reason}")
        self.time = time
        self.reason = reason


def _check(name, value, ok, valid):
    if not (isinstance(value, (int, float)) and math.isfinite(value) and ok(value)):
        raise ValueError(f"{name} = {value!r} is invalid: must be {valid}")


# ---------------------------------------------------------------------------
# Loads
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Harmonic:
    """mean + amplitude sin(omega t + phase); omega [rad/s] >= 0."""

    mean: float = 0.0
    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0

    def __post_init__(self):
        _check("mean", self.mean, lambda v: True, "a finite number")
        _check("amplitude", self.amplitude, lambda v: True, "a finite number")
        _check("omega", self.omega, lambda v: v >= 0, "a finite number >= 0")
        _check("phase", self.phase, lambda v: True, "a finite number")

    @property
    def oscillates(self) -> bool:
        return self.amplitude != 0.0 and self.omega > 0.0

    def __call__(self, t, derivative: int = 0):
        t = np.asarray(t, dtype=float)
        w = self.omega
        osc = self.amplitude * w**derivative * np.sin(w * t + self.phase + derivative * math.pi / 2)
        if derivative == 0:
            return self.mean + osc
        return osc

    def integral(self, t0: float, t):
        """int_{t0}^{t} f(s) ds."""
        tau = np.asarray(t, dtype=float) - t0
        if self.omega == 0.0:
            return (self.mean + self.amplitude * math.sin(self.phase)) * tau
        th0 = self.omega * t0 + self.phase
        x = self.omega * tau
        osc = 2.0 * np.sin(th0 + 0.5 * x) * np.sin(0.5 * x) / self.omega
        return self.mean * tau + self.amplitude * osc

    def double_integral(self, t0: float, t):
        """int_{t0}^{t} int_{t0}^{s} f(v) dv ds."""
        tau = np.asarray(t, dtype=float) - t0
        if self.omega == 0.0:
            return 0.5 * (self.mean + self.amplitude * math.sin(self.phase)) * tau**2
        th0 = self.omega * t0 + self.phase
        x = self.omega * tau
        one_minus_cos = 2.0 * np.sin(0.5 * x) ** 2
        osc = (math.cos(th0) * x_minus_sin(x) + math.sin(th0) * one_minus_cos) / self.omega**2
        return 0.5 * self.mean * tau**2 + self.amplitude * osc


# ---------------------------------------------------------------------------
# Drive parameters
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class RigidDrive:
    """Rigid lead-screw drive: bodies rotor, screw, nut, load (SI units).

    drive="screw": the rotor turns the axially fixed screw; nut and load translate
    without turning (J = rotor + screw, m = nut + load). drive="nut": the rotor turns
    the axially fixed nut; screw and load translate (J = rotor + nut, m = screw + load).
    flank_angle is the included thread angle beta; mu' = mu / cos(beta / 2).
    """

    lead: float
    mean_radius: float
    mu: float
    rotor_inertia: float
    screw_inertia: float
    screw_mass: float
    nut_inertia: float
    nut_mass: float
    load_mass: float
    flank_angle: float = 0.0
    hand: str = "right"
    drive: str = "screw"

    @classmethod
    def from_scene(cls, scene) -> "RigidDrive":
        """The rigid drive of a leadscrew.Scene: its thread, friction, rotor
        and load, and the screw's and nut's masses and inertias it derives."""
        d, derived = scene.to_dict(), scene.derived()
        thread = d["thread"]
        return cls(lead=thread["pitch"] * thread["starts"],
                   mean_radius=thread["mean_diameter"] / 2, mu=d["friction"]["mu"],
                   rotor_inertia=d["rotor"]["inertia"], screw_inertia=derived["screw_inertia"],
                   screw_mass=derived["screw_mass"], nut_inertia=derived["nut_inertia"],
                   nut_mass=derived["nut_mass"], load_mass=d["load"]["mass"],
                   flank_angle=thread["flank_angle"], hand=thread["hand"], drive=d["drive"])

    def __post_init__(self):
        pos = lambda v: v > 0  # noqa: E731
        nonneg = lambda v: v >= 0  # noqa: E731
        _check("lead", self.lead, pos, "a finite number > 0")
        _check("mean_radius", self.mean_radius, pos, "a finite number > 0")
        _check("mu", self.mu, nonneg, "a finite number >= 0")
        for name in ("rotor_inertia", "screw_inertia", "screw_mass",
                     "nut_inertia", "nut_mass", "load_mass"):
            _check(name, getattr(self, name), nonneg, "a finite number >= 0")
        _check("flank_angle", self.flank_angle, lambda v: 0 <= v < math.pi, "in [0, pi)")
        if self.hand not in ("right", "left"):
            raise ValueError(f"hand = {self.hand!r} is invalid: must be 'right' or 'left'")
        if self.drive not in ("screw", "nut"):
            raise ValueError(f"drive = {self.drive!r} is invalid: must be 'screw' or 'nut'")
        if self.J <= 0 and self.m <= 0:
            raise ValueError(
                "rotating inertia and translating mass are both zero: must have J + m p^2 > 0")

    # geometry
    @property
    def h(self) -> float:
        return 1.0 if self.hand == "right" else -1.0

    @property
    def d(self) -> float:
        return 1.0 if self.drive == "screw" else -1.0

    @property
    def p(self) -> float:
        return self.lead / (2.0 * math.pi)

    @property
    def tan_alpha(self) -> float:
        return self.p / self.mean_radius

    @property
    def alpha(self) -> float:
        return math.atan2(self.p, self.mean_radius)

    @property
    def cos_alpha(self) -> float:
        return self.mean_radius / math.hypot(self.mean_radius, self.p)

    @property
    def sin_alpha(self) -> float:
        return self.p / math.hypot(self.mean_radius, self.p)

    @property
    def rho(self) -> float:
        """Helix factor: slip velocity = rho * phi_dot, rho = sqrt(r^2 + p^2)."""
        return math.hypot(self.mean_radius, self.p)

    @property
    def mu_eff(self) -> float:
        return self.mu / math.cos(0.5 * self.flank_angle)

    # inertia
    @property
    def J(self) -> float:
        other = self.screw_inertia if self.drive == "screw" else self.nut_inertia
        return self.rotor_inertia + other

    @property
    def m(self) -> float:
        other = self.nut_mass if self.drive == "screw" else self.screw_mass
        return self.load_mass + other

    @property
    def J_eff(self) -> float:
        return self.J + self.m * self.p**2

    # modes
    def delta(self, eps: float) -> float:
        t, mu, r = self.tan_alpha, self.mu_eff, self.mean_radius
        return self.J * (1.0 + eps * mu * t) + self.m * r * r * t * (t - eps * mu)

    def a(self, eps: float) -> float:
        return (1.0 + eps * self.mu_eff * self.tan_alpha) / self.delta(eps)

    def b(self, eps: float) -> float:
        return -self.h * self.mean_radius * (self.tan_alpha - eps * self.mu_eff) / self.delta(eps)

    @property
    def jam_prone(self) -> bool:
        """Delta_+ <= 0 or Delta_- <= 0: slip states without a unique mode exist."""
        return self.delta(1.0) <= 0.0 or self.delta(-1.0) <= 0.0

    def K(self, M, F):
        return -(self.h * self.m * self.p * np.asarray(M) + self.J * np.asarray(F))

    def stick_forces(self, M, F):
        """(lam~_st, T~_st): rotating-on-translating normal and friction force at rest."""
        M, F = np.asarray(M, dtype=float), np.asarray(F, dtype=float)
        c, s, r, h = self.cos_alpha, self.sin_alpha, self.mean_radius, self.h
        return -(F * c + h * (M / r) * s), (M / r) * c - h * F * s


# ---------------------------------------------------------------------------
# Root finding on smooth explicit functions
# ---------------------------------------------------------------------------


def _brent(f, x0, x1):
    return brentq(lambda x: float(f(x)), x0, x1, xtol=1e-300, rtol=4.0 * np.finfo(float).eps,
                  maxiter=500)


def _roots(fs: Sequence, ta: float, tb: float, step: float) -> List[float]:
    """All roots of fs[0] in [ta, tb]; fs[k] is the k-th derivative.

    The extrema of f (roots of f') split [ta, tb] into monotone pieces, found
    recursively; the last derivative is sampled on a grid of the given step.
    """
    f = fs[0]
    if len(fs) == 1:
        n = max(2, int(math.ceil((tb - ta) / step)) + 1)
        pts = np.linspace(ta, tb, n)
    else:
        pts = np.array([ta] + _roots(fs[1:], ta, tb, step) + [tb])
    vals = np.asarray(f(pts), dtype=float)
    roots = []
    for i in range(len(pts) - 1):
        x0, x1, f0, f1 = pts[i], pts[i + 1], vals[i], vals[i + 1]
        if x1 <= x0:
            continue
        if f0 == 0.0:
            roots.append(float(x0))
        elif f0 * f1 < 0.0:
            roots.append(_brent(f, x0, x1))
    if vals[-1] == 0.0:
        roots.append(float(pts[-1]))
    out = []
    for x in sorted(roots):
        if not out or x > out[-1]:
            out.append(x)
    return out


# ---------------------------------------------------------------------------
# Solution
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Phase:
    """One stick or slip phase on [t0, t1].

    In slip, phi_dd = a M(t) + b F(t) with mode eps = h s sig~ (sig~ = sign of the
    rotating-on-translating normal force; 0 where K vanishes identically).
    """

    t0: float
    t1: float
    kind: str  # "stick" or "slip"
    s: int  # sign of phi_d in slip, 0 in stick
    sigma: int  # sign of the screw-on-nut normal force (slip), 0 if undetermined
    eps: int  # h s sig~ in slip, 0 in stick
    a: float
    b: float
    phi0: float
    omega0: float


@dataclass(frozen=True)
class Event:
    time: float
    kind: str  # "stick->slip", "slip->stick", "reversal", "flank change"


@dataclass
class Solution:
    drive: RigidDrive
    torque: Harmonic
    force: Harmonic
    t_end: float
    phases: List[Phase] = field(default_factory=list)
    events: List[Event] = field(default_factory=list)

    # -- evaluation ---------------------------------------------------------
    def _index(self, t):
        starts = np.array([ph.t0 for ph in self.phases])
        idx = np.searchsorted(starts, t, side="right") - 1
        return np.clip(idx, 0, len(self.phases) - 1)

    def _eval(self, t, fn):
        t = np.asarray(t, dtype=float)
        flat = np.atleast_1d(t).ravel()
        if np.any(flat < 0.0) or np.any(flat > self.t_end):
            raise ValueError(f"t is invalid: must be in [0, {self.t_end}]")
        out = np.empty_like(flat)
        idx = self._index(flat)
        for i in np.unique(idx):
            sel = idx == i
            out[sel] = fn(self.phases[i], flat[sel])
        return out.reshape(t.shape) if t.ndim else out[0]

    def _omega(self, ph, t):
        if ph.kind == "stick":
            return np.zeros_like(t)
        return (ph.omega0 + ph.a * self.torque.integral(ph.t0, t)
                + ph.b * self.force.integral(ph.t0, t))

    def _phi(self, ph, t):
        if ph.kind == "stick":
            return np.full_like(t, ph.phi0)
        tau = t - ph.t0
        return (
            ph.phi0
            + ph.omega0 * tau
            + ph.a * self.torque.double_integral(ph.t0, t)
            + ph.b * self.force.double_integral(ph.t0, t)
        )

    def _accel(self, ph, t):
        if ph.kind == "stick":
            return np.zeros_like(t)
        return ph.a * self.torque(t) + ph.b * self.force(t)

    def _lam_tilde(self, ph, t):
        dr = self.drive
        M, F = self.torque(t), self.force(t)
        if ph.kind == "stick":
            return dr.stick_forces(M, F)[0]
        if ph.sigma == 0:
            return np.zeros_like(t)
        return dr.K(M, F) / (dr.cos_alpha * dr.delta(ph.eps))

    def _T_tilde(self, ph, t):
        dr = self.drive
        if ph.kind == "stick":
            return dr.stick_forces(self.torque(t), self.force(t))[1]
        return dr.mu_eff * np.abs(self._lam_tilde(ph, t)) * ph.s

    def phi(self, t):
        """Rotor angle [rad] (phi(0) = 0)."""
        return self._eval(t, self._phi)

    def omega(self, t):
        """Rotor angular velocity [rad/s]."""
        return self._eval(t, self._omega)

    def accel(self, t):
        """Rotor angular acceleration [rad/s^2] (right-continuous at events)."""
        return self._eval(t, self._accel)

    def u_load(self, t):
        """Load displacement along +x from its start [m]: -h p phi."""
        return -self.drive.h * self.drive.p * self.phi(t)

    def v_load(self, t):
        return -self.drive.h * self.drive.p * self.omega(t)

    def normal_force(self, t):
        """Normal force of the screw on the nut [N] along (cos a, -h sin a) (thesis F_CN)."""
        return self.drive.d * self._eval(t, self._lam_tilde)

    def flank_normal_force(self, t):
        """Normal force on the inclined flank [N]: normal_force / cos(beta / 2)."""
        return self.normal_force(t) / math.cos(0.5 * self.drive.flank_angle)

    def friction_force(self, t):
        """Friction force of the screw on the nut [N] along (h sin a, cos a) (thesis F_CT)."""
        return self.drive.d * self._eval(t, self._T_tilde)

    def slip_velocity(self, t):
        """Velocity of the nut relative to the screw along (h sin a, cos a) [m/s]: -d rho phi_d."""
        return -self.drive.d * self.drive.rho * self.omega(t)

    def stick(self, t):
        t = np.asarray(t, dtype=float)
        return self._eval(t, lambda ph, tt: np.full_like(tt, ph.kind == "stick")).astype(bool)

    def _layout(self, rot):
        """(axial, angular) of rotor, screw, nut, load from the rotor's angular quantity."""
        ax = -self.drive.h * self.drive.p * rot
        z = np.zeros_like(rot)
        turning, sliding = ("screw", "nut") if self.drive.drive == "screw" else ("nut", "screw")
        return {"rotor": (z, rot), turning: (z, rot), sliding: (ax, z), "load": (ax, z)}

    def bodies(self, t):
        """Axial positions u [m] and angles phi [rad] of rotor, screw, nut, load."""
        return self._layout(self.phi(t))

    def body_velocities(self, t):
        """Axial velocities [m/s] and angular velocities [rad/s] of rotor, screw, nut, load."""
        return self._layout(self.omega(t))

    # -- energy -------------------------------------------------------------
    def energy(self):
        """Work of M and F, friction loss and kinetic energy over [0, t_end] [J].

        The integrals are Gauss-Legendre quadratures of the evaluated power on
        slip phases (stick phases do no work); friction loss is
        -int friction_force * slip_velocity dt.
        """
        dr = self.drive
        w_m = w_f = loss = 0.0
        step = _grid_step(self.torque, self.force, self.t_end)
        for ph in self.phases:
            if ph.kind == "stick" or ph.t1 <= ph.t0:
                continue
            n_sub = max(1, int(math.ceil((ph.t1 - ph.t0) / (4.0 * step))))
            edges = np.linspace(ph.t0, ph.t1, n_sub + 1)
            for x0, x1 in zip(edges[:-1], edges[1:]):
                tq = 0.5 * (x1 - x0) * _GAUSS_X + 0.5 * (x1 + x0)
                wq = 0.5 * (x1 - x0) * _GAUSS_W
                om = self._omega(ph, tq)
                w_m += float(np.sum(wq * self.torque(tq) * om))
                w_f += float(np.sum(wq * self.force(tq) * (-dr.h * dr.p * om)))
                fr = dr.d * self._T_tilde(ph, tq)
                vs = -dr.d * dr.rho * om
                loss -= float(np.sum(wq * fr * vs))
        w0 = self.phases[0].omega0
        w1 = float(self.omega(self.t_end))
        dke = 0.5 * dr.J_eff * (w1 * w1 - w0 * w0)
        return dict(
            work_torque=w_m,
            work_force=w_f,
            friction_loss=loss,
            kinetic_energy_change=dke,
            residual=w_m + w_f - loss - dke,
        )


# ---------------------------------------------------------------------------
# Simulation
# ---------------------------------------------------------------------------


def _grid_step(torque: Harmonic, force: Harmonic, t_end: float) -> float:
    periods = [2.0 * math.pi / h.omega for h in (torque, force) if h.oscillates]
    if not periods:
        return max(t_end, 1e-300) / 8.0
    return min(periods) / _GRID_PER_PERIOD


def _lin(torque, force, cM, cF):
    """Derivative list of cM M(t) + cF F(t)."""
    return [lambda t, k=k: cM * torque(t, k) + cF * force(t, k) for k in range(4)]


def _sign(x: float) -> int:
    return 1 if x > 0 else (-1 if x < 0 else 0)


class _Integrator:
    def __init__(self, drive, torque, force, t_end):
        self.dr, self.tq, self.fc, self.t_end = drive, torque, force, t_end
        self.step = _grid_step(torque, force, t_end)
        self.window = 64.0 * self.step
        self.excl = 1e-12 * min(self.window, t_end)
        dr = drive
        c, s, r, h, mu = dr.cos_alpha, dr.sin_alpha, dr.mean_radius, dr.h, dr.mu_eff
        # lam~_st = -(c F + h (s/r) M), T~_st = (c/r) M - h s F
        self.A = _lin(torque, force, c / r + mu * h * s / r, -h * s + mu * c)  # T~ - mu lam~
        self.B = _lin(torque, force, c / r - mu * h * s / r, -h * s - mu * c)  # T~ + mu lam~
        self.Kf = _lin(torque, force, -h * dr.m * dr.p, -dr.J)
        self.K_scale = abs(dr.m * dr.p) * (abs(torque.mean) + abs(torque.amplitude)) + dr.J * (
            abs(force.mean) + abs(force.amplitude)
        )

    def windows(self, t0):
        a = t0
        while a < self.t_end:
            b = min(a + self.window, self.t_end)
            yield a, b
            a = b

    # stick ---------------------------------------------------------------
    def stick_exit(self, t0):
        """First time >= t0 at which the stick limit is exceeded, and the slip direction."""
        A, B = self.A[0], self.B[0]
        for wa, wb in self.windows(t0):
            roots = _roots(self.A, wa, wb, self.step) + _roots(self.B, wa, wb, self.step)
            pts = sorted(set([wa, wb] + roots))
            for x0, x1 in zip(pts[:-1], pts[1:]):
                if x1 <= x0:
                    continue
                mid = 0.5 * (x0 + x1)
                am, bm = float(A(mid)), float(B(mid))
                if am * bm > 0.0:
                    return x0, _sign(am)
        return None, 0

    # slip ----------------------------------------------------------------
    def K_identically_zero(self):
        """K(t) = -(h m p M(t) + J F(t)) vanishes for all t (e.g. zero loads)."""
        dr, tq, fc = self.dr, self.tq, self.fc
        kM, kF = -dr.h * dr.m * dr.p, -dr.J
        const = kM * tq.mean + kF * fc.mean
        waves = {}
        for k, hm in ((kM, tq), (kF, fc)):
            if hm.omega == 0.0:
                const += k * hm.amplitude * math.sin(hm.phase)
            else:
                waves[hm.omega] = waves.get(hm.omega, 0j) + k * hm.amplitude * complex(
                    math.cos(hm.phase), math.sin(hm.phase))
        tol = 1e-13 * self.K_scale
        return abs(const) <= tol and all(abs(v) <= tol for v in waves.values())

    def K_sign_after(self, t0):
        """Sign of K just after t0 (0 if K vanishes identically)."""
        if self.K_identically_zero():
            return 0
        Kf = self.Kf[0]
        for wa, wb in self.windows(t0):
            pts = sorted(set([wa, wb] + _roots(self.Kf, wa, wb, self.step)))
            for x0, x1 in zip(pts[:-1], pts[1:]):
                sg = _sign(float(Kf(0.5 * (x0 + x1)))) if x1 > x0 else 0
                if sg != 0:
                    return sg
        return 0

    def K_sign_change(self, wa, wb, sig_t):
        """First time in [wa, wb] after which K no longer has the sign sig_t."""
        if sig_t == 0:
            return None
        Kf = self.Kf[0]
        pts = sorted(set([wa, wb] + _roots(self.Kf, wa, wb, self.step)))
        for x0, x1 in zip(pts[:-1], pts[1:]):
            if x1 > x0 and _sign(float(Kf(0.5 * (x0 + x1)))) == -sig_t:
                return x0
        return None

    def velocity_funcs(self, t0, w0, a, b):
        tq, fc = self.tq, self.fc
        return [
            lambda t: w0 + a * tq.integral(t0, t) + b * fc.integral(t0, t),
            lambda t: a * tq(t) + b * fc(t),
            lambda t: a * tq(t, 1) + b * fc(t, 1),
            lambda t: a * tq(t, 2) + b * fc(t, 2),
        ]

    def slip_end(self, t0, w0, a, b, sig_t, from_rest):
        """First event of a slip phase: ("zero", t) velocity zero, ("flank", t) K changes
        sign, or ("end", t_end); searched window by window."""
        fs = self.velocity_funcs(t0, w0, a, b)
        lo = t0 + (self.excl if from_rest else 0.0)
        for wa, wb in self.windows(t0):
            t_zero = next((x for x in _roots(fs, wa, wb, self.step) if x > lo), None)
            t_flank = self.K_sign_change(wa, wb, sig_t)
            found = [(x, why) for x, why in ((t_zero, "zero"), (t_flank, "flank")) if x is not None]
            if found:
                return min(found)[::-1]
        return "end", self.t_end

    def select_mode(self, t, s, sig_t):
        """The unique consistent eps for slip direction s, given sign(K) just after t."""
        dr = self.dr
        if sig_t == 0:
            return 1, 0  # K identically zero: no normal force, both modes coincide
        consistent = []
        for cand in (1, -1):
            eps = int(dr.h) * s * cand
            delta = dr.delta(eps)
            if delta != 0.0 and sig_t * _sign(delta) == cand:
                consistent.append((eps, cand))
        if len(consistent) != 1:
            what = "no" if not consistent else "two"
            raise ReferenceJamming(
                t,
                f"{what} consistent normal-force sign in slip s = {s:+d}, sign(K) = {sig_t:+d}, "
                f"Delta_+ = {dr.delta(1.0)!r}, Delta_- = {dr.delta(-1.0)!r}",
            )
        return consistent[0]

    def run(self, omega0):
        dr = self.dr
        sol = Solution(dr, self.tq, self.fc, self.t_end)
        t, phi, w = 0.0, 0.0, float(omega0)
        state = "rest" if w == 0.0 else "slip"
        s = _sign(w)
        from_rest = False
        zero_len = 0
        for _ in range(_MAX_PHASES):
            if t >= self.t_end:
                break
            if state == "rest":
                t_exit, s_new = self.stick_exit(t)
                if t_exit is None or t_exit > t:
                    t1 = self.t_end if t_exit is None else t_exit
                    sol.phases.append(Phase(t, t1, "stick", 0, 0, 0, 0.0, 0.0, phi, 0.0))
                    if t_exit is None:
                        break
                    sol.events.append(Event(t1, "stick->slip"))
                    t = t1
                s, state, from_rest, w = s_new, "slip", True, 0.0
                continue
            # slip phase from t with velocity w (sign s)
            sig_t = self.K_sign_after(t)
            eps, _ = self.select_mode(t, s, sig_t)
            a, b = dr.a(eps), dr.b(eps)
            why, t1 = self.slip_end(t, w, a, b, sig_t, from_rest)
            sigma = int(dr.d) * sig_t
            sol.phases.append(Phase(t, t1, "slip", s, sigma, eps if sig_t else 0, a, b, phi, w))
            ph = sol.phases[-1]
            zero_len = zero_len + 1 if t1 <= t + self.excl else 0
            if zero_len > _MAX_ZERO_LENGTH_PHASES:
                raise RuntimeError(f"reference: no progress at t = {t!r} (zero-length phases)")
            phi = float(sol._phi(ph, np.array([t1]))[0])
            w_end = float(sol._omega(ph, np.array([t1]))[0])
            t = t1
            if why == "end":
                break
            if why == "flank":
                sol.events.append(Event(t, "flank change"))
                w, from_rest = w_end, False
                continue
            # velocity zero: stick or reversal
            w = 0.0
            t_exit, s_new = self.stick_exit(t)
            if t_exit is not None and t_exit <= t:
                sol.events.append(Event(t, "reversal" if s_new != s else "touch"))
                s, from_rest = s_new, True
                continue
            sol.events.append(Event(t, "slip->stick"))
            state = "rest"
        else:
            raise RuntimeError(f"reference: more than {_MAX_PHASES} phases")
        if not sol.phases:
            sol.phases.append(Phase(0.0, self.t_end, "stick", 0, 0, 0, 0.0, 0.0, 0.0, 0.0))
        return sol


def simulate(drive: RigidDrive, torque: Harmonic, force: Harmonic, t_end: float,
             omega0: float = 0.0) -> Solution:
    """Exact-Coulomb trajectory of the rigid drive on [0, t_end], phi(0) = 0.

    Args:
        drive: the drive.
        torque: drive torque M(t) on the rotor about +x [N m].
        force: axial force F(t) on the load along +x [N].
        t_end: end time [s], > 0.
        omega0: initial rotor angular velocity [rad/s].

    Returns:
        The Solution (phases, events, evaluators, energy account).

    Raises:
        ReferenceJamming: a slip state has no or two consistent normal-force signs.
        ValueError: bad input.
    """
    _check("t_end", t_end, lambda v: v > 0, "a finite number > 0")
    _check("omega0", omega0, lambda v: True, "a finite number")
    return _Integrator(drive, torque, force, float(t_end)).run(omega0)


# ---------------------------------------------------------------------------
# The thesis's example (Table 5.1, eq. 5.1) with stated masses and inertias
# ---------------------------------------------------------------------------

STEEL_DENSITY = 7850.0  # kg/m^3
PLASTIC_DENSITY = 1400.0  # kg/m^3 (POM-like nut)


def thesis_drive(drive: str = "screw", hand: str = "right", flank_angle: float = 0.0,
                 load_mass: float = 1.0, mu: float = 0.3) -> RigidDrive:
    """Table 5.1: lead 1 mm, r_m = 10 mm, mu = 0.3; inertias from the geometry.

    Screw: solid steel cylinder r = 10 mm, length 500 mm; nut: plastic tube
    r = 10...12 mm, length 20 mm; rotor 1e-6 kg m^2; load 1 kg (not in the thesis).
    """
    r_s, l_s = 0.010, 0.500
    m_s = STEEL_DENSITY * math.pi * r_s**2 * l_s
    j_s = 0.5 * m_s * r_s**2
    r_i, r_o, l_n = 0.010, 0.012, 0.020
    m_n = PLASTIC_DENSITY * math.pi * (r_o**2 - r_i**2) * l_n
    j_n = 0.5 * m_n * (r_o**2 + r_i**2)
    return RigidDrive(
        lead=0.001, mean_radius=0.010, mu=mu, rotor_inertia=1e-6,
        screw_inertia=j_s, screw_mass=m_s, nut_inertia=j_n, nut_mass=m_n,
        load_mass=load_mass, flank_angle=flank_angle, hand=hand, drive=drive,
    )


def thesis_loads():
    """Eq. (5.1): M = -40 sin(4 pi t) N mm, F = -10 N."""
    return Harmonic(0.0, -0.040, 4.0 * math.pi, 0.0), Harmonic(-10.0, 0.0, 0.0, 0.0)
