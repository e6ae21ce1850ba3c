"""The exact-Coulomb reference of the rigid drive (tests/helpers/rigid_drive_reference.py)
against computations that share none of its formulas:

- an 8-coordinate Newton-Euler model (rotor, screw, nut, load, each with u and phi;
  supports as Lagrange multipliers; flank normal and helix friction from the unrolled
  thread geometry), integrated segment by segment with scipy's DOP853 and the thesis's
  y+/y- normal-force procedure (section 4.3) with event detection;
- the thesis's own regularized equations (4.10)/(4.11) with the arctan friction factor
  (sign of z corrected, see docs/physics/rigid_drive.md), converging as k_V grows;
- the static bounds tan(alpha) < mu' < cot(alpha) (eq. 3.5, 3.7) and the jamming
  inequalities of the issue, written here from the issue's text.
"""

import math

import numpy as np
import pytest
from hypothesis import assume, event, given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from helpers import rigid_drive_reference as ref

BODY = dict(rotor_mass=0.3, load_inertia=0.01)  # axially / rotationally fixed: irrelevant


# ---------------------------------------------------------------------------
# Independent model: 8 coordinates q = (uS, phiS, uN, phiN, uR, phiR, uL, phiL)
# ---------------------------------------------------------------------------


class Multibody:
    ROTOR_PHI, LOAD_U = 5, 6

    def __init__(self, d: ref.RigidDrive):
        self.r = d.mean_radius
        alpha = math.atan(d.lead / (2.0 * math.pi * d.mean_radius))
        c, s = math.cos(alpha), math.sin(alpha)
        h = 1.0 if d.hand == "right" else -1.0
        self.mu = d.mu / math.cos(d.flank_angle / 2.0)
        self.mass = np.diag(
            [d.screw_mass, d.screw_inertia, d.nut_mass, d.nut_inertia,
             BODY["rotor_mass"], d.rotor_inertia, d.load_mass, BODY["load_inertia"]]
        )
        rows = []

        def row(**kw):
            v = np.zeros(8)
            for k, val in kw.items():
                v[["uS", "pS", "uN", "pN", "uR", "pR", "uL", "pL"].index(k)] = val
            rows.append(v)

        # screw drive: screw axially fixed, nut does not turn, rotor on screw, load on nut
        if d.drive == "screw":
            row(uS=1), row(pN=1), row(uR=1), row(pR=1, pS=-1), row(uL=1, uN=-1), row(pL=1, pN=-1)
        else:  # nut axially fixed, screw does not turn, rotor on nut, load on screw
            row(uN=1), row(pS=1), row(uR=1), row(pR=1, pN=-1), row(uL=1, uS=-1), row(pL=1, pS=-1)
        self.G = np.array(rows)
        r = self.r
        # gap g_N = c (uN - uS) - h s r (pN - pS); slip g_T = h s (uN - uS) + c r (pN - pS)
        self.WN = np.array([-c, h * s * r, c, -h * s * r, 0, 0, 0, 0])
        self.WT = np.array([-h * s, -c * r, h * s, c * r, 0, 0, 0, 0])
        self._inv = {}
        for sT in (1, -1):
            for sig in (1, -1):
                k = -self.mu * sig * sT  # T = -mu |lam| sT = k lam
                A = np.zeros((15, 15))
                A[:8, :8] = self.mass
                A[:8, 8:14] = -self.G.T
                A[:8, 14] = -(self.WN + k * self.WT)
                A[8:14, :8] = self.G
                A[14, :8] = self.WN
                self._inv[(sT, sig)] = (np.linalg.inv(A), k)
        A = np.zeros((16, 16))
        A[:8, :8] = self.mass
        A[:8, 8:14] = -self.G.T
        A[:8, 14] = -self.WN
        A[:8, 15] = -self.WT
        A[8:14, :8] = self.G
        A[14, :8] = self.WN
        A[15, :8] = self.WT
        self._stick_inv = np.linalg.inv(A)

    def f(self, M, F):
        v = np.zeros(8)
        v[5], v[6] = M, F
        return v

    def slip(self, M, F, sT, sig):
        inv, k = self._inv[(sT, sig)]
        rhs = np.zeros(15)
        rhs[:8] = self.f(M, F)
        x = inv @ rhs
        return x[:8], x[14], k * x[14]

    def thesis_slip(self, M, F, sT):
        """y+/y- procedure: first assume lam > 0, else lam < 0; also count consistent signs."""
        plus = self.slip(M, F, sT, 1)
        minus = self.slip(M, F, sT, -1)
        ok = [plus[1] > 0, minus[1] < 0]
        if not any(ok) and max(abs(plus[1]), abs(minus[1])) <= 1e-10 * (abs(F) + abs(M) / self.r):
            return plus, 1  # at a flank change both signs give lam = 0 and the same motion
        chosen = plus if ok[0] else (minus if ok[1] else None)
        return chosen, sum(ok)

    def stick(self, M, F):
        rhs = np.zeros(16)
        rhs[:8] = self.f(M, F)
        x = self._stick_inv @ rhs
        return x[14], x[15]

    def stick_ok(self, M, F):
        lam, T = self.stick(M, F)
        return abs(T) <= self.mu * abs(lam)

    def start_direction(self, M, F):
        """Slip directions sT (of the nut relative to the screw) consistent from rest."""
        out = []
        for sT in (1, -1):
            for sig in (1, -1):
                qdd, lam, _ = self.slip(M, F, sT, sig)
                if np.sign(lam) == sig and np.sign(self.WT @ qdd) == sT:
                    out.append(sT)
        return out


class ComparatorJam(Exception):
    pass


class Comparator:
    """Event-driven DOP853 integration of the 8-coordinate model with exact Coulomb."""

    def __init__(self, drive, torque, force, t_end, rtol=1e-12, atol=1e-16):
        self.mb = Multibody(drive)
        self.M, self.F, self.t_end = torque, force, t_end
        periods = [2 * math.pi / h.omega for h in (torque, force) if h.amplitude and h.omega]
        self.max_step = (min(periods) if periods else t_end) / 64.0
        self.segments = []  # (t0, t1, kind, sT, dense or constant state)
        self.events = []
        self._run(rtol, atol)

    def loads(self, t):
        return float(self.M(t)), float(self.F(t))

    def _direction(self, t):
        dirs = self.mb.start_direction(*self.loads(t))
        if len(dirs) != 1:
            raise ComparatorJam(f"t={t}: start directions {dirs}")
        return dirs[0]

    def _run(self, rtol, atol):
        mb, t, y = self.mb, 0.0, np.zeros(16)
        rest = True
        for _ in range(10_000):
            if t >= self.t_end:
                return
            if rest:
                if mb.stick_ok(*self.loads(t)):
                    def g(tt, yy):
                        lam, T = mb.stick(*self.loads(tt))
                        return (mb.mu * lam) ** 2 - T**2
                    g.terminal, g.direction = True, -1
                    sol = solve_ivp(lambda tt, yy: np.zeros(1), (t, self.t_end), [0.0], events=g,
                                    max_step=self.max_step, rtol=1e-13, atol=1e-13)
                    t1 = sol.t_events[0][0] if sol.t_events[0].size else self.t_end
                    self.segments.append((t, t1, "stick", 0, y.copy()))
                    if t1 >= self.t_end:
                        return
                    self.events.append((t1, "stick->slip"))
                    t = t1
                    # at the limit the slip acceleration is 0: read the direction just after
                    sT = self._direction(t + 1e-7 * self.max_step)
                else:
                    sT = self._direction(t)
                rest = False
            y, t, why = self._slip(t, y, sT, rtol, atol)
            if why == "end":
                return
            if why == "flank":
                self.events.append((t, "flank change"))
                continue
            y[8:] = 0.0
            if mb.stick_ok(*self.loads(t)):
                self.events.append((t, "slip->stick"))
                rest = True
            else:
                self.events.append((t, "reversal"))
                sT = self._direction(t)
        raise RuntimeError("comparator: too many segments")

    def _slip(self, t, y, sT, rtol, atol):
        mb = self.mb

        def chosen(tt):
            res, n = mb.thesis_slip(*self.loads(tt), sT)
            if n != 1:
                raise ComparatorJam(f"t={tt}: {n} consistent normal-force signs")
            return res

        def rhs(tt, yy):
            qdd, _, _ = chosen(tt)
            return np.concatenate([yy[8:], qdd])

        def stop(tt, yy):
            return mb.WT @ yy[8:]

        stop.terminal, stop.direction = True, -sT

        def flank(tt, yy):
            plus = mb.slip(*self.loads(tt), sT, 1)
            minus = mb.slip(*self.loads(tt), sT, -1)
            return plus[1] if plus[1] > 0 else minus[1]

        flank.terminal = True
        # lam just after t (it may be ~0 at t after a flank change): only the next crossing counts
        flank.direction = -np.sign(flank(t + 1e-7 * self.max_step, y))
        sol = solve_ivp(rhs, (t, self.t_end), y, method="DOP853", events=[stop, flank],
                        dense_output=True, rtol=rtol, atol=atol, max_step=self.max_step)
        assert sol.status >= 0, sol.message
        t1 = sol.t[-1]
        self.segments.append((t, t1, "slip", sT, sol.sol))
        if sol.status == 0:
            return sol.y[:, -1], t1, "end"
        why = "zero" if sol.t_events[0].size else "flank"
        return sol.y[:, -1].copy(), t1, why

    def state(self, t):
        t = np.atleast_1d(t)
        out = np.empty((16, t.size))
        starts = np.array([s[0] for s in self.segments])
        idx = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(self.segments) - 1)
        for i, tt in enumerate(t):
            seg = self.segments[idx[i]]
            out[:, i] = seg[4] if seg[2] == "stick" else seg[4](tt)
        return out

    def forces(self, t):
        """(lam, T) of the screw on the nut."""
        t = np.atleast_1d(t)
        starts = np.array([s[0] for s in self.segments])
        idx = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(self.segments) - 1)
        lam, T = np.empty(t.size), np.empty(t.size)
        for i, tt in enumerate(t):
            seg = self.segments[idx[i]]
            if seg[2] == "stick":
                lam[i], T[i] = self.mb.stick(*self.loads(tt))
            else:
                (qdd, lam[i], T[i]), _ = self.mb.thesis_slip(*self.loads(tt), seg[3])
        return lam, T


# ---------------------------------------------------------------------------
# Cases
# ---------------------------------------------------------------------------

MIXED = (ref.Harmonic(0.004, 0.03, 4 * math.pi, 0.3), ref.Harmonic(-3.0, 8.0, 6 * math.pi, 1.1))
VARIANTS = [(drv, hand, beta) for drv in ("screw", "nut") for hand in ("right", "left")
            for beta in (0.0, math.radians(30))]


def _compare(drive, torque, force, t_end, n=401):
    sol = ref.simulate(drive, torque, force, t_end)
    cmp_ = Comparator(drive, torque, force, t_end)
    ts = np.linspace(0.0, t_end, n)
    y = cmp_.state(ts)
    phi, w, ul = y[Multibody.ROTOR_PHI], y[8 + Multibody.ROTOR_PHI], y[Multibody.LOAD_U]
    assert np.max(np.abs(sol.phi(ts) - phi)) <= 1e-9 * max(1e-300, np.max(np.abs(phi)))
    assert np.max(np.abs(sol.omega(ts) - w)) <= 1e-9 * np.max(np.abs(w))
    assert np.max(np.abs(sol.u_load(ts) - ul)) <= 1e-9 * np.max(np.abs(ul))
    # forces away from the event instants (they jump there)
    ev = np.array([e.time for e in sol.events])
    far = np.array([np.all(np.abs(ev - t) > 1e-6) for t in ts])
    lam, T = cmp_.forces(ts[far])
    scale = np.max(np.abs(lam))
    assert np.max(np.abs(sol.normal_force(ts[far]) - lam)) <= 1e-9 * scale
    assert np.max(np.abs(sol.friction_force(ts[far]) - T)) <= 1e-9 * scale
    assert np.array_equal(sol.stick(ts[far]), np.array(
        [cmp_.segments[i][2] == "stick" for i in np.clip(np.searchsorted(
            [s[0] for s in cmp_.segments], ts[far], side="right") - 1, 0, None)]))
    # same events, same kinds, same times
    assert [e.kind for e in sol.events] == [k for _, k in cmp_.events]
    got, want = np.array([e.time for e in sol.events]), np.array([t for t, _ in cmp_.events])
    assert np.max(np.abs(got - want), initial=0.0) <= 1e-9 * t_end
    return sol, cmp_


@pytest.mark.parametrize("drv, hand, beta", VARIANTS)
def test_thesis_load_case_against_multibody_integration(drv, hand, beta):
    drive = ref.thesis_drive(drv, hand=hand, flank_angle=beta)
    torque, force = ref.thesis_loads()
    sol, _ = _compare(drive, torque, force, 2.0)
    assert sum(e.kind == "stick->slip" for e in sol.events) == 8  # 2 per load period
    assert all(ph.kind == "stick" or ph.sigma == (1 if drv == "screw" else -1) for ph in sol.phases)


@pytest.mark.parametrize("drv", ["screw", "nut"])
@pytest.mark.parametrize("hand", ["right", "left"])
def test_mixed_loads_with_flank_changes_against_multibody_integration(drv, hand):
    drive = ref.thesis_drive(drv, hand=hand, flank_angle=math.radians(30))
    sol, _ = _compare(drive, *MIXED, 1.0)
    kinds = {e.kind for e in sol.events}
    assert kinds == {"flank change", "slip->stick", "stick->slip", "reversal"}
    assert {ph.sigma for ph in sol.phases if ph.kind == "slip"} == {1, -1}


def test_initial_velocity_and_reversal():
    drive = ref.thesis_drive("screw")
    torque, force = ref.Harmonic(0.02), ref.Harmonic(0.0)
    sol = ref.simulate(drive, torque, force, 0.5, omega0=-30.0)
    # friction and M decelerate the rotor, which reverses and keeps turning with M
    assert [e.kind for e in sol.events] == ["reversal"]
    assert sol.omega(0.5) > 0
    # no axial load: K = -h m p M, constant; closed form of each phase
    t_r = sol.events[0].time
    a1 = sol.phases[0].a * 0.02
    assert t_r == pytest.approx(30.0 / a1, rel=1e-14)


# ---------------------------------------------------------------------------
# The closed form: phi_dd = a M(t) + b F(t) per phase, a and b from the multibody model
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("drv, hand, beta", VARIANTS)
def test_phase_coefficients_equal_multibody_accelerations(drv, hand, beta):
    drive = ref.thesis_drive(drv, hand=hand, flank_angle=beta)
    sol = ref.simulate(drive, *MIXED, 1.0)
    mb = Multibody(drive)
    for ph in sol.phases:
        if ph.kind != "slip":
            continue
        sT = -int(drive.d) * ph.s  # nut relative to screw: -d rho phi_dot
        # phi_dd is linear in (M, F) within the mode: finite differences are exact
        tm = 0.5 * (ph.t0 + ph.t1)
        M, F = float(MIXED[0](tm)), float(MIXED[1](tm))
        dM, dF = 1e-4 * 0.034, 1e-4 * 11.0
        acc = []
        for m_, f_ in ((M, F), (M + dM, F), (M, F + dF)):
            qdd, lam, _ = mb.slip(m_, f_, sT, ph.sigma)
            assert np.sign(lam) == ph.sigma
            acc.append(qdd[Multibody.ROTOR_PHI])
        a, b = (acc[1] - acc[0]) / dM, (acc[2] - acc[0]) / dF
        assert ph.a == pytest.approx(a, rel=1e-8)
        assert ph.b == pytest.approx(b, rel=1e-8)
        terms = abs(ph.a * M) + abs(ph.b * F)
        assert ph.a * M + ph.b * F == pytest.approx(acc[0], abs=1e-12 * terms)


# ---------------------------------------------------------------------------
# Regularized arctan model of the thesis, eq. (4.10)/(4.11), converging to the reference
# ---------------------------------------------------------------------------


def _thesis_regularized(drive, torque, force, t_end, k_v, ts):
    """Screw drive, right hand. z = mu' (2/pi) atan(k_V rho phi3_dot), the sign-corrected
    friction factor; (4.10) if F_CN > 0 else (4.11), as in the thesis's section 4.3."""
    assert drive.drive == "screw" and drive.hand == "right"
    alpha = math.atan(drive.lead / (2 * math.pi * drive.mean_radius))
    ca, sa = math.cos(alpha), math.sin(alpha)
    s, r = drive.lead, drive.mean_radius
    I13 = drive.rotor_inertia + drive.screw_inertia
    m24 = drive.nut_mass + drive.load_mass
    mu = drive.mu / math.cos(drive.flank_angle / 2)
    rho = math.sqrt(r**2 + (s / (2 * math.pi)) ** 2)

    def rhs(t, y):
        M, F = float(torque(t)), float(force(t))
        z = mu * 2 / math.pi * math.atan(k_v * rho * y[1])
        acc = 2 * math.pi * (F * r * (ca * z - sa) + M * (ca + sa * z)) / (
            2 * math.pi * I13 * (ca + sa * z) + r * s * m24 * (sa - ca * z))
        fcn = (m24 * (-s / (2 * math.pi)) * acc - F) / (ca + z * sa)
        if fcn <= 0:
            acc = -2 * math.pi * (F * r * (sa + ca * z) + M * (-ca + sa * z)) / (
                2 * math.pi * I13 * (ca - sa * z) + r * s * m24 * (sa + ca * z))
            fcn = (m24 * (-s / (2 * math.pi)) * acc - F) / (ca - z * sa)
            assert fcn < 0, "thesis procedure: no consistent sign"
        return [y[1], acc]

    # The right-hand side does not depend on the angle y[0]: Radau's
    # finite-difference Jacobian sees a zero column and multiplies that
    # column's step factor by 10 at every evaluation until it overflows to
    # inf (scipy's num_jac), harmlessly (the column stays 0). Only that
    # overflow is silenced, here.
    with np.errstate(over="ignore"):
        sol = solve_ivp(rhs, (0, t_end), [0.0, 0.0], method="Radau", t_eval=ts, rtol=1e-9,
                        atol=1e-12)
    assert sol.success
    return -s / (2 * math.pi) * sol.y[0]  # u_2 = -(s/2pi) phi_3, eq. (4.9)


def test_regularized_thesis_model_converges_to_reference():
    drive = ref.thesis_drive("screw")
    torque, force = ref.thesis_loads()
    ts = np.linspace(0, 1.0, 101)
    exact = ref.simulate(drive, torque, force, 1.0).u_load(ts)
    errors = []
    for k_v in (1e3, 1e4, 1e5):  # [s/m]
        u = _thesis_regularized(drive, torque, force, 1.0, k_v, ts)
        errors.append(np.max(np.abs(u - exact)) / np.max(np.abs(exact)))
    # measured: 0.15, 0.033, 0.0072 (about k_V^-2/3: creep while "sticking" and delayed
    # transitions); each decade of k_V must cut the error by more than 3
    assert errors[1] < 0.3 * errors[0] and errors[2] < 0.3 * errors[1]
    assert errors[2] < 1e-2


# ---------------------------------------------------------------------------
# Energy
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("drv, hand, beta", VARIANTS)
@pytest.mark.parametrize("loads", ["thesis", "mixed"])
def test_energy_balance_closes(drv, hand, beta, loads):
    drive = ref.thesis_drive(drv, hand=hand, flank_angle=beta)
    torque, force = ref.thesis_loads() if loads == "thesis" else MIXED
    e = ref.simulate(drive, torque, force, 2.0).energy()
    scale = max(abs(e["work_torque"]), abs(e["work_force"]), e["friction_loss"])
    assert e["friction_loss"] > 0
    assert abs(e["residual"]) <= 1e-12 * scale


@pytest.mark.parametrize("drv, hand, beta", VARIANTS)
def test_friction_never_does_positive_work(drv, hand, beta):
    drive = ref.thesis_drive(drv, hand=hand, flank_angle=beta)
    sol = ref.simulate(drive, *MIXED, 1.0)
    ts = np.linspace(0, 1.0, 4001)
    # slip of the nut relative to the screw along the helix, from the body velocities
    v = sol.body_velocities(ts)
    alpha = math.atan(drive.lead / (2 * math.pi * drive.mean_radius))
    hs = 1.0 if hand == "right" else -1.0
    v_rel = (hs * math.sin(alpha) * (v["nut"][0] - v["screw"][0])
             + math.cos(alpha) * drive.mean_radius * (v["nut"][1] - v["screw"][1]))
    np.testing.assert_allclose(v_rel, sol.slip_velocity(ts), rtol=1e-12, atol=1e-15)
    power = sol.friction_force(ts) * v_rel
    scale = np.max(np.abs(sol.friction_force(ts))) * np.max(np.abs(v_rel))
    assert np.max(power) <= 1e-12 * scale
    assert np.min(power) < -1e-3 * scale  # it does dissipate
    # Coulomb: |T| <= mu' |N| everywhere, equality in slip
    T, N = sol.friction_force(ts), sol.normal_force(ts)
    assert np.all(np.abs(T) <= drive.mu_eff * np.abs(N) * (1 + 1e-12) + 1e-12 * scale)
    slip = ~sol.stick(ts)
    np.testing.assert_allclose(np.abs(T[slip]), drive.mu_eff * np.abs(N[slip]), rtol=1e-12)


# ---------------------------------------------------------------------------
# The jamming inequalities, written from its text (used by several tests)
# ---------------------------------------------------------------------------


def _first_inequality(d):  # m r^2 tan a (mu' - tan a) >= J (1 + mu' tan a)
    t = d.lead / (2 * math.pi * d.mean_radius)
    return d.m * d.mean_radius**2 * t * (d.mu_eff - t) - d.J * (1 + d.mu_eff * t)


def _second_inequality(d):  # J cot a (mu' - cot a) >= m r^2 (1 + mu' cot a)
    ct = 2 * math.pi * d.mean_radius / d.lead
    return d.J * ct * (d.mu_eff - ct) - d.m * d.mean_radius**2 * (1 + d.mu_eff * ct)


def _first_scale(d):  # size of the terms of the first inequality
    t = d.lead / (2 * math.pi * d.mean_radius)
    return d.m * d.mean_radius**2 * t * (d.mu_eff + t) + d.J * (1 + d.mu_eff * t)


def _second_scale(d):
    ct = 2 * math.pi * d.mean_radius / d.lead
    return d.J * ct * (d.mu_eff + ct) + d.m * d.mean_radius**2 * (1 + d.mu_eff * ct)


# ---------------------------------------------------------------------------
# Static bounds (eq. 3.5, 3.7)
# ---------------------------------------------------------------------------


@st.composite
def drives_near_bound(draw, bound):
    lead = draw(st.floats(1e-4, 0.05))
    diameter = draw(st.floats(1e-3, 0.2))
    beta = draw(st.sampled_from([0.0, math.radians(29), math.radians(30), math.radians(60)]))
    tan_a = lead / (math.pi * diameter)
    target = tan_a if bound == "holding" else 1.0 / tan_a
    kind = draw(st.sampled_from(["near", "free"]))
    if kind == "near":
        sign = draw(st.sampled_from([-1.0, 1.0]))
        delta = 10 ** draw(st.floats(-9, -1))
        mu_eff = target * (1 + sign * delta)
    else:
        mu_eff = draw(st.floats(0.0, 3.0))
    masses = [draw(st.floats(1e-7, 1e-3)), draw(st.floats(1e-7, 1e-3)), draw(st.floats(1e-3, 10)),
              draw(st.floats(1e-8, 1e-4)), draw(st.floats(1e-3, 1)), draw(st.floats(0.01, 100))]
    return ref.RigidDrive(lead, diameter / 2, mu_eff * math.cos(beta / 2), *masses,
                          flank_angle=beta, hand=draw(st.sampled_from(["right", "left"])),
                          drive=draw(st.sampled_from(["screw", "nut"])))


def _moves(drive, torque, force):
    try:
        sol = ref.simulate(drive, torque, force, 0.01)
    except ref.ReferenceJamming:
        return "jam", None
    moved = any(ph.kind == "slip" for ph in sol.phases)
    assert moved == (sol.phi(0.01) != 0.0)
    return moved, sol


@settings(max_examples=200, deadline=None)
@given(drives_near_bound("holding"), st.floats(1.0, 1e4), st.sampled_from([-1.0, 1.0]))
def test_pure_axial_load_holds_iff_tan_alpha_below_mu(drive, magnitude, sign):
    tan_a = drive.lead / (2 * math.pi * drive.mean_radius)
    mu_eff = drive.mu / math.cos(drive.flank_angle / 2)
    assume(abs(mu_eff - tan_a) > 1e-12 * tan_a)
    F = sign * magnitude
    moved, sol = _moves(drive, ref.Harmonic(0.0), ref.Harmonic(F))
    event(f"moved={moved}, near={abs(mu_eff / tan_a - 1) < 0.1}")
    mb = Multibody(drive)
    assert mb.stick_ok(0.0, F) == (tan_a < mu_eff)
    if tan_a < mu_eff:
        assert moved is False
        assert mb.start_direction(0.0, F) == [] or drive.jam_prone
    elif moved == "jam":
        # only where the second inequality holds
        assert _second_inequality(drive) >= -1e-9 * _second_scale(drive)
    else:
        assert moved is True
        assert np.sign(sol.v_load(0.01)) == np.sign(F)  # the load moves with the force
        sT = mb.start_direction(0.0, F)
        assert len(sT) == 1
        (qdd, lam, _), n = mb.thesis_slip(0.0, F, sT[0])
        assert n == 1
        # phi_dd ~ (tan a - mu'): compare relative to the size of the two terms
        scale = abs(F) * drive.mean_radius * (tan_a + mu_eff) / drive.delta(1.0)
        assert abs(sol.accel(0.0) - qdd[Multibody.ROTOR_PHI]) <= 1e-9 * scale
        assert sol.normal_force(0.0) == pytest.approx(lam, rel=1e-9)


@settings(max_examples=200, deadline=None)
@given(drives_near_bound("drivable"), st.floats(1e-3, 10.0), st.sampled_from([-1.0, 1.0]))
def test_pure_torque_moves_iff_mu_below_cot_alpha(drive, magnitude, sign):
    tan_a = drive.lead / (2 * math.pi * drive.mean_radius)
    mu_eff = drive.mu / math.cos(drive.flank_angle / 2)
    assume(abs(mu_eff * tan_a - 1) > 1e-12)
    M = sign * magnitude
    moved, sol = _moves(drive, ref.Harmonic(M), ref.Harmonic(0.0))
    event(f"moved={moved}, near={abs(mu_eff * tan_a - 1) < 0.1}")
    mb = Multibody(drive)
    assert mb.stick_ok(M, 0.0) == (mu_eff * tan_a > 1)
    if mu_eff * tan_a > 1:
        assert moved is False
    elif moved == "jam":
        assert _first_inequality(drive) >= -1e-9 * _first_scale(drive)
    else:
        assert moved is True
        assert np.sign(sol.omega(0.01)) == np.sign(M)  # the rotor turns with the torque
        (qdd, lam, _), n = mb.thesis_slip(M, 0.0, mb.start_direction(M, 0.0)[0])
        assert n == 1
        scale = abs(M) * (1 + mu_eff * tan_a) / drive.delta(-1.0)  # phi_dd ~ (1 - mu' tan a)
        assert abs(sol.accel(0.0) - qdd[Multibody.ROTOR_PHI]) <= 1e-9 * scale


def test_exactly_at_the_holding_bound_the_drive_stays():
    # tan(alpha) = mu' exactly in floating point: lead = 2 pi r mu'
    drive = ref.RigidDrive(2 * math.pi * 0.25 * 0.5, 0.5, 0.25, 1e-4, 1e-4, 1.0, 1e-6, 0.01, 1.0)
    assert drive.tan_alpha == drive.mu_eff
    sol = ref.simulate(drive, ref.Harmonic(0.0), ref.Harmonic(-50.0), 1.0)
    assert [ph.kind for ph in sol.phases] == ["stick"]
    # lowering (the load moves along F), it keeps its velocity: phi_dd = b_+ F = 0
    sol = ref.simulate(drive, ref.Harmonic(0.0), ref.Harmonic(-50.0), 1.0, omega0=2.0 * drive.h)
    assert sol.v_load(0.0) < 0
    assert sol.omega(1.0) == pytest.approx(2.0 * drive.h, rel=1e-15)
    assert sol.events == []
    # raising, it stops and stays
    sol = ref.simulate(drive, ref.Harmonic(0.0), ref.Harmonic(-50.0), 1.0, omega0=-2.0 * drive.h)
    assert [e.kind for e in sol.events] == ["slip->stick"] and sol.omega(1.0) == 0.0


def test_zero_loads():
    drive = ref.thesis_drive("nut", flank_angle=0.4)
    sol = ref.simulate(drive, ref.Harmonic(0.0), ref.Harmonic(0.0), 1.0)
    assert [ph.kind for ph in sol.phases] == ["stick"] and sol.phi(1.0) == 0.0
    # coasting: no normal force, so no friction, constant velocity
    sol = ref.simulate(drive, ref.Harmonic(0.0), ref.Harmonic(0.0), 1.0, omega0=3.0)
    assert sol.omega(1.0) == 3.0 and sol.phi(1.0) == pytest.approx(3.0, rel=1e-15)
    assert sol.normal_force(0.5) == 0.0 and sol.friction_force(0.5) == 0.0


# ---------------------------------------------------------------------------
# Jamming (Painleve): the inequalities
# ---------------------------------------------------------------------------


def _with(d, **kw):
    fields = {k: getattr(d, k) for k in d.__dataclass_fields__}
    fields.update(kw)
    return ref.RigidDrive(**fields)


@pytest.mark.parametrize("hand", ["right", "left"])
@pytest.mark.parametrize("rel", [1e-6, 1e-2])
def test_first_jamming_inequality_separates_jam_from_trajectory(hand, rel):
    # the nut-driven thesis drive jams with a load heavier than ~2.04 kg
    base = ref.thesis_drive("nut", hand=hand)
    t = base.tan_alpha
    m_crit = base.J * (1 + base.mu_eff * t) / (base.mean_radius**2 * t * (base.mu_eff - t))
    load_crit = m_crit - base.screw_mass
    assert 2.0 < load_crit < 2.1
    torque, force = ref.thesis_loads()
    heavy = _with(base, load_mass=load_crit * (1 + rel))
    light = _with(base, load_mass=load_crit * (1 - rel))
    assert _first_inequality(heavy) > 0 > _first_inequality(light)
    with pytest.raises(ref.ReferenceJamming) as info:
        ref.simulate(heavy, torque, force, 2.0)
    sol = ref.simulate(light, torque, force, 2.0)
    assert info.value.time == sol.events[0].time  # it jams at the first stick->slip
    assert sol.phases[-1].t1 == 2.0
    with pytest.raises(ComparatorJam):
        Comparator(heavy, torque, force, 0.2)
    _compare(light, torque, force, 0.5)


@pytest.mark.parametrize("rel", [1e-6, 1e-2])
def test_second_jamming_inequality_separates_jam_from_trajectory(rel):
    # steep lead (alpha ~ 72 deg), mu' = 0.5 > cot(alpha): not drivable by torque but back-drivable
    base = ref.RigidDrive(lead=0.2, mean_radius=0.01, mu=0.5, rotor_inertia=1e-5, screw_inertia=0.0,
                          screw_mass=0.5, nut_inertia=1e-6, nut_mass=0.1, load_mass=1.0)
    ct = 1 / base.tan_alpha
    assert ct < base.mu_eff < base.tan_alpha
    j_crit = base.m * base.mean_radius**2 * (1 + base.mu_eff * ct) / (ct * (base.mu_eff - ct))
    heavy = _with(base, rotor_inertia=j_crit * (1 + rel))
    light = _with(base, rotor_inertia=j_crit * (1 - rel))
    assert _second_inequality(heavy) > 0 > _second_inequality(light)
    force = ref.Harmonic(-20.0, 5.0, 10.0, 0.0)
    with pytest.raises(ref.ReferenceJamming):
        ref.simulate(heavy, ref.Harmonic(0.0), force, 0.5)
    sol = ref.simulate(light, ref.Harmonic(0.0), force, 0.5)
    assert sol.v_load(0.5) < 0  # back-driven along the force
    with pytest.raises(ComparatorJam):
        Comparator(heavy, ref.Harmonic(0.0), force, 0.5)
    _compare(light, ref.Harmonic(0.0), force, 0.5)


@settings(max_examples=400, deadline=None)
@given(
    st.floats(0.01, 1.55), st.floats(0.0, 5.0), st.floats(1e-6, 1e-2), st.floats(1e-3, 100.0),
    st.floats(-1, 1), st.floats(-1, 1), st.sampled_from([1, -1]),
    st.sampled_from(["right", "left"]), st.sampled_from(["screw", "nut"]),
)
def test_paradox_in_slip_iff_an_inequality_holds(alpha, mu, j, mass, m_dir, f_dir, sT, hand, drv):
    """The multibody y+/y- procedure finds 0 or 2 consistent normal-force signs in slip
    exactly where one of the issue's inequalities holds (for loads with K != 0)."""
    r = 0.01
    d = ref.RigidDrive(2 * math.pi * r * math.tan(alpha), r, mu, j, j, mass, j, mass, mass,
                       hand=hand, drive=drv)
    first, second = _first_inequality(d), _second_inequality(d)
    assume(abs(first) > 1e-9 * _first_scale(d) and abs(second) > 1e-9 * _second_scale(d))
    M, F = 0.1 * m_dir, 100.0 * f_dir
    K = -(d.h * d.m * d.p * M + d.J * F)
    assume(abs(K) > 1e-6 * (abs(d.m * d.p * M) + abs(d.J * F)))
    _, n = Multibody(d).thesis_slip(M, F, sT)
    event(f"consistent signs: {n}")
    assert (n != 1) == (first >= 0 or second >= 0)
    assert d.jam_prone == (first >= 0 or second >= 0)


# ---------------------------------------------------------------------------
# Input validation and the thesis example's figures
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("kw, name", [
    (dict(lead=0.0), "lead"), (dict(mean_radius=-1.0), "mean_radius"), (dict(mu=-0.1), "mu"),
    (dict(load_mass=float("nan")), "load_mass"), (dict(flank_angle=math.pi), "flank_angle"),
    (dict(hand="up"), "hand"), (dict(drive="belt"), "drive"),
])
def test_bad_drive_raises(kw, name):
    with pytest.raises(ValueError, match=name):
        _with(ref.thesis_drive(), **kw)


def test_bad_simulation_input_raises():
    with pytest.raises(ValueError, match="t_end"):
        ref.simulate(ref.thesis_drive(), *ref.thesis_loads(), 0.0)
    with pytest.raises(ValueError, match="omega"):
        ref.Harmonic(0.0, 1.0, -1.0)
    sol = ref.simulate(ref.thesis_drive(), *ref.thesis_loads(), 0.1)
    with pytest.raises(ValueError, match="t"):
        sol.phi(0.2)


@pytest.mark.parametrize("drv", ["screw", "nut"])
def test_thesis_example_event_pattern(drv):
    """|M|/r (4 N) exceeds the friction limit (~3 N) once per half period of M: 8 slips in
    2 s, each ending in stick except the last, still slipping at t = 2 s."""
    sol = ref.simulate(ref.thesis_drive(drv), *ref.thesis_loads(), 2.0)
    assert [e.kind for e in sol.events] == ["stick->slip", "slip->stick"] * 7 + ["stick->slip"]
    assert [ph.s for ph in sol.phases if ph.kind == "slip"] == [-1, 1] * 4  # with M's sign
    assert not sol.stick(2.0)
