"""Exact piecewise closed-form solution of the thesis's friction benchmark.

Thesis section 3.2.6, eq. (3.9): a block of mass ``m`` on a rough plane,

    m u'' = F_Exc(t) - lambda_T,        lambda_N = m g,
    F_Exc(t) = V sin(omega t + phi) + c,

with exact, set-valued Coulomb friction (eq. (3.10)-(3.14) are its LCP form):

    u' = 0:  |lambda_T| <= mu lambda_N   (stick, lambda_T = F_Exc),
    u' != 0: lambda_T = mu lambda_N sign(u')   (slip).

Written from the physics alone (no package code), as an independent check of
the package's event-driven and LCP integrators.  Let N = mu m g.

Stick (u' = 0, u constant, lambda_T = F_Exc) lasts while |F_Exc| <= N; it ends
at the first *outward* crossing of |F_Exc| = N, found in closed form with asin:
    F = +N rising:  omega t + phi = asin((N - c)/V)        + 2 pi k,
    F = -N falling: omega t + phi = pi - asin((-N - c)/V) + 2 pi k.
Slip then starts in the direction of F_Exc.

Slip with direction s = +-1, started at t0 with u0, v0 (tau = t - t0,
x = omega tau, theta0 = omega t0 + phi, A = V/(m omega), B = (c - s N)/m):

    u'' = (F_Exc - s N)/m
    u'  = v0 + A [2 cos(theta0) sin^2(x/2) + sin(theta0) sin x] + B tau
    u   = u0 + v0 tau + (A/omega) [2 sin(theta0) sin^2(x/2)
                                   + cos(theta0) (x - sin x)] + B tau^2 / 2

(the half-angle forms avoid the cancellation of cos(theta0) - cos(theta)
for small tau).  The slip ends at the first root of s u'(t) = 0 after t0.
s u' is monotone between consecutive roots of its derivative, i.e. between
the times where F_Exc = s N, which again follow from asin: these times cut
the horizon into monotone pieces, the first piece whose end value drops to
<= 0 brackets the unique root, and Brent's method refines it to a relative
accuracy of 4 eps.  A root within rounding noise of a piece end (a
tangential / double root) is snapped onto that analytically known end.

At a velocity zero the new mode is decided from the force: |F_Exc| <= N
gives stick, otherwise slip in the direction of F_Exc -- which is always the
reverse of the old direction (a pass-through reversal), since s u' can only
decrease through zero while s F_Exc <= N.  When |F_Exc| is at N to rounding,
the sign of dF/dt (then d2F/dt2) decides whether the force is leaving the
friction cone (slip, a zero-length stick) or not (stick).

Initial mode: v0 > 0 gives slip+, v0 < 0 slip-, v0 = 0 the same decision as
at a velocity zero (an |v0| below the formula's rounding level counts as 0).

Phase kinds: ``'stick'``, ``'slip+'`` (u' > 0), ``'slip-'`` (u' < 0).
Event kinds, one at each boundary between consecutive phases:

    'stick->slip'  stick ends because |F_Exc| reaches mu m g;
    'slip->stick'  the velocity reaches zero with |F_Exc| <= mu m g;
    'reversal'     the velocity passes through zero with |F_Exc| > mu m g
                   and the block slips on in the opposite direction;
    'touch'        the velocity touches zero tangentially with |F_Exc| at
                   mu m g (a zero-length stick) and slip resumes in the same
                   direction -- only in degenerate cases, e.g. mu = 0.

No event is recorded at t = 0 or t_end.  At an event time the evaluators
return the value of the phase that starts there (right limit); position and
velocity are continuous, acceleration and friction force jump.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from .series import x_minus_sin

__all__ = ["Phase", "Event", "BlockSolution", "solve_block", "free_motion"]

_EPS = np.finfo(float).eps
_TWO_PI = 2.0 * math.pi
_MAX_PHASES_PER_PERIOD = 16
_MAX_PERIODS = 200_000


@dataclass(frozen=True)
class Phase:
    """One mode interval [start, end] of the motion.

    Attributes:
        start, end: times [s].
        kind: 'stick', 'slip+' or 'slip-'.
        position: u at ``start`` [m].
        velocity: u' at ``start`` [m/s] (zero except possibly the first phase).
    """

    start: float
    end: float
    kind: str
    position: float
    velocity: float

    @property
    def direction(self) -> int:
        """+1 for 'slip+', -1 for 'slip-', 0 for 'stick'."""
        return {"stick": 0, "slip+": 1, "slip-": -1}[self.kind]


@dataclass(frozen=True)
class Event:
    """A mode change at ``time`` [s]; ``kind`` as in the module docstring;
    ``position`` u [m] and ``force`` F_Exc [N] at that time."""

    time: float
    kind: str
    position: float
    force: float


def _require_finite(name, value):
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} = {value!r} must be finite")
    return value


def _require_positive(name, value):
    value = _require_finite(name, value)
    if not value > 0.0:
        raise ValueError(f"{name} = {value!r} must be > 0 (valid range (0, inf))")
    return value


def _require_nonnegative(name, value):
    value = _require_finite(name, value)
    if not value >= 0.0:
        raise ValueError(f"{name} = {value!r} must be >= 0 (valid range [0, inf))")
    return value


class BlockSolution:
    """Piecewise closed-form motion of the block; built by :func:`solve_block`.

    Attributes:
        phases: list of :class:`Phase`, contiguous from 0 to ``t_end``.
        events: list of :class:`Event` at the inner phase boundaries.
        friction_limit: mu m g [N].
    """

    def __init__(self, mass, mu, g, amplitude, omega, phase, offset, t_end, u0, v0):
        self.mass = mass
        self.mu = mu
        self.g = g
        self.amplitude = amplitude
        self.omega = omega
        self.phase = phase
        self.offset = offset
        self.t_end = t_end
        self.friction_limit = mu * mass * g
        # Rounding level of a force value (sin of an argument up to
        # omega t_end + |phi| carries an absolute error ~ eps times that
        # argument), and of its first two time derivatives.
        scale = amplitude * (2.0 + omega * t_end + abs(phase)) + abs(offset) + self.friction_limit
        self._force_tol = 32.0 * _EPS * scale
        self._dforce_tol = 64.0 * _EPS * amplitude * omega * (1.0 + omega * t_end)
        self._ddforce_tol = 64.0 * _EPS * amplitude * omega**2 * (1.0 + omega * t_end)
        periods = omega * t_end / _TWO_PI
        if amplitude > 0.0 and periods > _MAX_PERIODS:
            raise ValueError(
                f"omega * t_end / (2 pi) = {periods:.6g} forcing periods exceeds the "
                f"supported {_MAX_PERIODS}; shorten t_end or lower omega")
        self._max_phases = int(_MAX_PHASES_PER_PERIOD * (periods + 1.0)) + 64
        self.phases: list[Phase] = []
        self.events: list[Event] = []
        self._build(u0, v0)
        self._starts = np.array([p.start for p in self.phases])
        self._dissipated_before = np.concatenate(
            ([0.0], np.cumsum([self.friction_limit * abs(float(self._phase_displacement(p, p.end)))
                               for p in self.phases])))

    # ----- forcing ---------------------------------------------------------
    def force(self, t):
        """Excitation F_Exc(t) = V sin(omega t + phi) + c [N] (vectorised)."""
        t = np.asarray(t, dtype=float)
        return self.amplitude * np.sin(self.omega * t + self.phase) + self.offset

    def _dforce(self, t):
        return self.amplitude * self.omega * math.cos(self.omega * t + self.phase)

    def _ddforce(self, t):
        return -self.amplitude * self.omega**2 * math.sin(self.omega * t + self.phase)

    def _level_times(self, level, t_lo, t_hi, branches):
        """Sorted times in (t_lo, t_hi) where F_Exc = level, on the chosen asin
        branches: 'rising' (cos >= 0), 'falling' (cos <= 0) or both.
        Empty if the level is not reached or only touched (|L| >= 1 is kept
        only for 'both', where tangential points still split monotone pieces)."""
        if self.amplitude == 0.0:
            return np.empty(0)
        ratio = (level - self.offset) / self.amplitude
        if abs(ratio) > 1.0 or (abs(ratio) == 1.0 and branches != "both"):
            return np.empty(0)
        base = math.asin(ratio)
        angles = {"rising": [base], "falling": [math.pi - base], "both": [base, math.pi - base]}
        w, phi = self.omega, self.phase
        out = []
        for a in angles[branches]:
            k_lo = math.floor((w * t_lo + phi - a) / _TWO_PI)
            k_hi = math.ceil((w * t_hi + phi - a) / _TWO_PI)
            k = np.arange(k_lo, k_hi + 1, dtype=float)
            times = (a - phi + _TWO_PI * k) / w
            out.append(times[(times > t_lo) & (times < t_hi)])
        return np.unique(np.concatenate(out))

    # ----- closed forms inside one phase (vectorised over t) ---------------
    def _slip_terms(self, t, t0, s):
        tau = np.asarray(t, dtype=float) - t0
        x = self.omega * tau
        theta0 = self.omega * t0 + self.phase
        s0, c0 = math.sin(theta0), math.cos(theta0)
        half = np.sin(0.5 * x)
        a_amp = self.amplitude / (self.mass * self.omega)
        b = (self.offset - s * self.friction_limit) / self.mass
        dv = a_amp * (2.0 * c0 * half * half + s0 * np.sin(x)) + b * tau
        du = (a_amp / self.omega) * (2.0 * s0 * half * half + c0 * x_minus_sin(x)) \
            + 0.5 * b * tau * tau
        return tau, dv, du

    def _phase_velocity(self, p, t):
        if p.kind == "stick":
            return np.zeros_like(np.asarray(t, dtype=float))
        _, dv, _ = self._slip_terms(t, p.start, p.direction)
        return p.velocity + dv

    def _phase_displacement(self, p, t):
        """u(t) - u(start) within phase p (kept apart from the absolute position
        so that distances slid do not lose digits against a large u)."""
        if p.kind == "stick":
            return np.zeros_like(np.asarray(t, dtype=float))
        tau, _, du = self._slip_terms(t, p.start, p.direction)
        return p.velocity * tau + du

    def _phase_position(self, p, t):
        return p.position + self._phase_displacement(p, t)

    def _phase_end_position(self, p):
        return float(self._phase_position(p, np.array([p.end]))[0])

    def _velocity_noise(self, v0, t0, t1):
        """Rounding level of the slip velocity formula over [t0, t1]; the
        trigonometric arguments (up to omega t1 + |phi|) are off by ~eps times
        their size."""
        a_amp = self.amplitude / (self.mass * self.omega)
        b = (abs(self.offset) + self.friction_limit) / self.mass
        arg = 3.0 + self.omega * t1 + abs(self.phase)
        return 16.0 * _EPS * (abs(v0) + a_amp * arg + b * (t1 - t0))

    # ----- mode logic -------------------------------------------------------
    def _mode_from_rest(self, t):
        """Mode on (t, t + 0) for a block at rest at time t: +1, -1 or 0 (stick)."""
        f = float(self.force(t))
        n = self.friction_limit
        if f - n > self._force_tol:
            return 1
        if -f - n > self._force_tol:
            return -1
        for sigma in (1, -1):
            if abs(sigma * f - n) <= self._force_tol:  # on the cone boundary
                d1 = sigma * self._dforce(t)
                if d1 > self._dforce_tol:
                    return sigma
                if abs(d1) <= self._dforce_tol and sigma * self._ddforce(t) > self._ddforce_tol:
                    return sigma
        return 0

    def _stick_end(self, t0):
        """End of a stick phase starting at t0 and the slip direction after it."""
        n = self.friction_limit
        rise = self._level_times(n, t0, self.t_end, "rising")
        fall = self._level_times(-n, t0, self.t_end, "falling")
        t_rise = float(rise[0]) if rise.size else math.inf
        t_fall = float(fall[0]) if fall.size else math.inf
        if t_rise == math.inf and t_fall == math.inf:
            return self.t_end, 0
        return (t_rise, 1) if t_rise <= t_fall else (t_fall, -1)

    def _slip_end(self, t0, v0, s):
        """First time after t0 where s u' drops to zero (None: not before t_end)."""
        delta = 16.0 * _EPS * (abs(t0) + (abs(self.phase) + _TWO_PI) / self.omega)
        cuts = self._level_times(s * self.friction_limit, t0 + delta, self.t_end, "both")
        pts = np.concatenate(([t0], cuts, [self.t_end]))
        h = s * (v0 + self._slip_terms(pts, t0, s)[1])
        noise = self._velocity_noise(v0, t0, self.t_end)
        low = np.nonzero(h[1:] <= noise)[0]
        if low.size == 0:
            return None
        k = int(low[0]) + 1
        if h[k] >= -noise:
            # Root within rounding of a piece end: a tangential zero on a cut
            # (snap onto the analytically known time) or a zero at t_end.
            return None if k == pts.size - 1 else float(pts[k])
        if not h[k - 1] > 0.0:
            raise RuntimeError(
                f"block reference: slip {s:+d} started at t = {t0!r} with s*u' = {h[k - 1]!r} "
                "and no positive velocity before its next zero (inconsistent mode decision)")

        def hv(t):
            return s * (v0 + float(self._slip_terms(np.array([t]), t0, s)[1][0]))

        # Absolute tolerance: a few ulps of the shortest time scale (forcing
        # period / 2 pi, or t_end), so roots near t = 0 converge as well.
        xtol = 2.0 * _EPS * min(self.t_end, 1.0 / self.omega if self.amplitude > 0 else math.inf)
        root = brentq(hv, pts[k - 1], pts[k], xtol=xtol, rtol=4.0 * _EPS, maxiter=400)
        return None if root >= self.t_end else float(root)

    def _build(self, u0, v0):
        # An initial speed below the rounding level of the velocity formula
        # cannot define a slip direction: it is treated as rest.
        if abs(v0) <= self._velocity_noise(0.0, 0.0, self.t_end):
            v0 = 0.0
        t, u, v = 0.0, u0, v0
        if v0 > 0.0:
            mode = 1
        elif v0 < 0.0:
            mode = -1
        else:
            mode = self._mode_from_rest(0.0)
        prev = None
        for _ in range(self._max_phases):
            if mode == 0:
                end, next_mode = self._stick_end(t)
                kind = "stick"
            else:
                end = self._slip_end(t, v, mode)
                end = self.t_end if end is None else end
                kind = "slip+" if mode > 0 else "slip-"
            phase = Phase(start=t, end=end, kind=kind, position=u, velocity=v)
            if prev is not None:
                self.events.append(Event(time=t, kind=self._event_kind(prev, phase),
                                         position=u, force=float(self.force(t))))
            self.phases.append(phase)
            prev = phase
            if end >= self.t_end:
                return
            u = self._phase_end_position(phase)
            t, v = end, 0.0
            if kind != "stick":
                next_mode = self._mode_from_rest(t)
            mode = next_mode
        raise RuntimeError(
            f"block reference: more than {self._max_phases} phases before t_end = {self.t_end}"
            f" (stopped at t = {t}); the mode logic is cycling")

    @staticmethod
    def _event_kind(before, after):
        if before.kind == "stick":
            return "stick->slip"
        if after.kind == "stick":
            return "slip->stick"
        return "touch" if before.kind == after.kind else "reversal"

    # ----- public evaluators --------------------------------------------------
    def _locate(self, t):
        t = np.asarray(t, dtype=float)
        if np.any(~np.isfinite(t)) or np.any(t < 0.0) or np.any(t > self.t_end):
            raise ValueError(f"t must lie in [0, t_end = {self.t_end}]")
        idx = np.searchsorted(self._starts, t, side="right") - 1
        return t, np.clip(idx, 0, len(self.phases) - 1)

    def _evaluate(self, t, per_phase):
        t, idx = self._locate(t)
        out = np.empty(t.shape)
        for i in np.unique(idx):  # bounded by the number of phases
            sel = idx == i
            out[sel] = per_phase(int(i), t[sel])
        return out if out.ndim else float(out)

    def position(self, t):
        """u(t) [m] (vectorised over t in [0, t_end])."""
        return self._evaluate(t, lambda i, tt: self._phase_position(self.phases[i], tt))

    def velocity(self, t):
        """u'(t) [m/s]; exactly 0 in stick phases."""
        return self._evaluate(t, lambda i, tt: self._phase_velocity(self.phases[i], tt))

    def friction_force(self, t):
        """lambda_T(t) [N], the friction force in eq. (3.9) (m u'' = F_Exc - lambda_T):
        F_Exc in stick, s mu m g in slip with direction s."""
        def per_phase(i, tt):
            p = self.phases[i]
            if p.kind == "stick":
                return self.force(tt)
            return np.full(tt.shape, p.direction * self.friction_limit)
        return self._evaluate(t, per_phase)

    def acceleration(self, t):
        """u''(t) = (F_Exc - lambda_T)/m [m/s^2]; 0 in stick phases."""
        def per_phase(i, tt):
            p = self.phases[i]
            if p.kind == "stick":
                return np.zeros(tt.shape)
            return (self.force(tt) - p.direction * self.friction_limit) / self.mass
        return self._evaluate(t, per_phase)

    def stick(self, t):
        """True where the block sticks (bool, vectorised)."""
        flag = self._evaluate(
            t, lambda i, tt: np.full(tt.shape, float(self.phases[i].kind == "stick")))
        return np.asarray(flag, dtype=bool) if np.ndim(flag) else bool(flag)

    def dissipated_energy(self, t):
        """Friction dissipation int_0^t lambda_T u' dt [J] in closed form:
        mu m g times the distance slid."""
        def per_phase(i, tt):
            slid = np.abs(self._phase_displacement(self.phases[i], tt))
            return self._dissipated_before[i] + self.friction_limit * slid
        return self._evaluate(t, per_phase)

    def event_times(self, kind=None):
        """Times [s] of all events, or of those of one ``kind``."""
        return np.array([e.time for e in self.events if kind is None or e.kind == kind])


def solve_block(mass, mu, g, amplitude, omega, phase=0.0, offset=0.0, t_end=2.0,
                u0=0.0, v0=0.0):
    """Exact motion of the thesis's block on a rough plane (eq. 3.9).

    Args:
        mass: m [kg], > 0.
        mu: Coulomb friction coefficient [-], >= 0.
        g: gravitational acceleration [m/s^2], >= 0 (lambda_N = m g).
        amplitude: V [N], >= 0.
        omega: angular frequency [rad/s], > 0.
        phase: phi [rad], finite.
        offset: constant force c [N], finite (amplitude = 0: constant forcing).
        t_end: end time [s], > 0; the motion starts at t = 0.
        u0, v0: initial position [m] and velocity [m/s], finite.

    Returns:
        BlockSolution with ``phases``, ``events`` and vectorised evaluators.

    Raises:
        ValueError: a parameter outside its valid range, naming it.
        RuntimeError: internal inconsistency of the mode logic (not expected).
    """
    mass = _require_positive("mass", mass)
    mu = _require_nonnegative("mu", mu)
    g = _require_nonnegative("g", g)
    amplitude = _require_nonnegative("amplitude", amplitude)
    omega = _require_positive("omega", omega)
    phase = _require_finite("phase", phase)
    offset = _require_finite("offset", offset)
    t_end = _require_positive("t_end", t_end)
    u0 = _require_finite("u0", u0)
    v0 = _require_finite("v0", v0)
    return BlockSolution(mass, mu, g, amplitude, omega, phase, offset, t_end, u0, v0)


def free_motion(t, mass, amplitude, omega, phase=0.0, offset=0.0, u0=0.0, v0=0.0):
    """Frictionless motion (mu = 0) of m u'' = V sin(omega t + phi) + c:

        u' = v0 + V/(m omega) (cos phi - cos(omega t + phi)) + c t/m,
        u  = u0 + v0 t + V/(m omega^2) (omega t cos phi - sin(omega t + phi) + sin phi)
             + c t^2/(2 m).

    Returns:
        (u, u') as arrays over t [s].
    """
    t = np.asarray(t, dtype=float)
    th = omega * t + phase
    v = v0 + amplitude / (mass * omega) * (math.cos(phase) - np.cos(th)) + offset * t / mass
    u = (u0 + v0 * t + amplitude / (mass * omega**2) * (omega * t * math.cos(phase) - np.sin(th)
                                                        + math.sin(phase))
         + 0.5 * offset * t * t / mass)
    return u, v
