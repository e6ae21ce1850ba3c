"""Symbolic check of every formula derived in docs/physics/rigid_drive.md.

Run with ``python3 docs/physics/rigid_drive_check.py`` (needs sympy). Each
step asserts an identity; the script prints one line per checked section and
fails with an AssertionError on the first wrong formula.

Notation (as in the document):
  t = tan(alpha) > 0, c = cos(alpha) = 1/sqrt(1+t^2), sn = sin(alpha) = t c,
  r = mean thread radius, p = lead/(2 pi) = r t, rho = r / c = sqrt(r^2 + p^2),
  mu = effective friction coefficient mu' = mu_flank / cos(beta/2),
  h = +1 right hand / -1 left hand, d = +1 drive="screw" / -1 drive="nut",
  s = sign(phi_dot), sig = sign of the normal force the screw exerts on the nut,
  eps = h d s sig (the only combination the slip dynamics depend on).
"""

import itertools

import sympy as sp

J, m, r, t, mu = sp.symbols("J m r t mu", positive=True)
M, F = sp.symbols("M F", real=True)
c = 1 / sp.sqrt(1 + t**2)
sn = t * c
p = r * t
rho = r / c
J_eff = J + m * p**2
SIGNS = (1, -1)


def zero(expr):
    return sp.simplify(sp.together(sp.expand(expr))) == 0


def Delta(eps_mu):
    """Denominator of the slip acceleration, eps_mu = eps * mu (or x in [-mu, mu])."""
    return J * (1 + eps_mu * t) + m * r**2 * t * (t - eps_mu)


def a_coef(eps, h):
    return (1 + eps * mu * t) / Delta(eps * mu)


def b_coef(eps, h):
    return -h * r * (t - eps * mu) / Delta(eps * mu)


def K_of(h):
    """Mode-independent numerator of the normal force (rotating on translating)."""
    return -(h * m * p * M + J * F)


def lam_tilde_stick(h):
    return -(F * c + h * (M / r) * sn)


def T_tilde_stick(h):
    return (M / r) * c - h * F * sn


# ---------------------------------------------------------------------------
# 1. Kinematics: helix, normal, slip velocity, both drive variants and hands.
# ---------------------------------------------------------------------------
uS, phS, uN, phN, uR, phR, uL, phL = sp.symbols("uS phS uN phN uR phR uL phL", real=True)
q = sp.Matrix([uS, phS, uN, phN, uR, phR, uL, phL])
phi = sp.symbols("phi", real=True)


def supports(drive):
    """Bilateral support/coupling constraints (besides the thread), as expressions = 0."""
    if drive == "screw":  # motor turns the axially fixed screw; nut + load translate
        return [uS, phN, uR, phR - phS, uL - uN, phL - phN]
    return [uN, phS, uR, phR - phN, uL - uS, phL - phS]  # motor turns the nut


def gaps(h):
    """Normal gap and tangential slip of the nut relative to the screw (unrolled at r)."""
    du, darc = uN - uS, r * (phN - phS)
    n = sp.Matrix([c, -h * sn])  # flank normal (axial, circumferential)
    tau = sp.Matrix([h * sn, c])  # helix tangent
    rel = sp.Matrix([du, darc])
    return (n.T * rel)[0], (tau.T * rel)[0], n, tau


for h, drive in itertools.product(SIGNS, ("screw", "drive_nut")):
    drive = "screw" if drive == "screw" else "nut"
    d = 1 if drive == "screw" else -1
    gN, gT, n, tau = gaps(h)
    assert zero((n.T * tau)[0]) and zero((n.T * n)[0] - 1) and zero((tau.T * tau)[0] - 1)
    # Configuration as a function of the rotor angle phi (u_load starts at 0).
    if drive == "screw":
        sol = {uS: 0, phS: phi, phN: 0, uR: 0, phR: phi, uN: -h * p * phi, uL: -h * p * phi, phL: 0}
    else:
        sol = {uN: 0, phN: phi, phS: 0, uR: 0, phR: phi, uS: -h * p * phi, uL: -h * p * phi, phL: 0}
    for g in supports(drive):
        assert zero(g.subs(sol))
    # Thread: u_screw - u_nut = h p (phi_screw - phi_nut) holds, and the normal gap is closed.
    assert zero((uS - uN - h * p * (phS - phN)).subs(sol))
    assert zero(gN.subs(sol))
    # Slip of the nut relative to the screw along the helix: -d rho phi.
    assert zero(gT.subs(sol) + d * rho * phi)
    # rho = sqrt(r^2 + p^2) (thesis eq. 4.3/4.4)
    assert zero(rho**2 - (r**2 + p**2))
print("1 kinematics: u_load = -h p phi in both variants; helix slip = -d rho phi: ok")

# ---------------------------------------------------------------------------
# 1b. Flank angle: 3D flank normal of a thread with included angle beta.
# ---------------------------------------------------------------------------
hb = sp.symbols("hb", positive=True)  # beta / 2
for h in SIGNS:
    tau3 = sp.Matrix([h * sn, c, 0])  # (axial, circumferential, radial)
    profile = sp.Matrix([sp.sin(hb), 0, sp.cos(hb)])  # flank line in the axial section
    n3 = tau3.cross(profile)
    n3 = n3 / sp.sqrt((n3.T * n3)[0])
    # In-plane part of the normal is along the square-thread normal (c, -h sn) ...
    assert zero(n3[0] * (-h * sn) - n3[1] * c)
    # ... with magnitude cos(alpha_n), tan(alpha_n) = tan(beta/2) cos(alpha):
    inplane = sp.sqrt(n3[0] ** 2 + n3[1] ** 2)
    cos_alpha_n = 1 / sp.sqrt(1 + (sp.tan(hb) * c) ** 2)
    assert zero(sp.simplify(inplane**2 - cos_alpha_n**2).rewrite(sp.cos))
    # The helix (slip direction) lies in the flank surface.
    assert zero((n3.T * tau3)[0])
    # cos(alpha_n) -> cos(beta/2) for a vanishing lead angle (both positive for beta < pi).
    assert sp.simplify(cos_alpha_n.subs(t, 0) ** 2 - sp.cos(hb) ** 2) == 0
print("1b flank angle: bound mu|N_flank| = mu/cos(alpha_n) |lambda|, alpha_n -> beta/2: ok")

# ---------------------------------------------------------------------------
# 2. Dynamics of the 8-coordinate multibody system (rotor, screw, nut, load)
#    with Lagrange multipliers, solved for every (h, d, s, sig).
# ---------------------------------------------------------------------------
mS, mN, mR, mL, JS, JN, JR, JL = sp.symbols("mS mN mR mL JS JN JR JL", positive=True)
mass = sp.diag(mS, JS, mN, JN, mR, JR, mL, JL)
f_applied = sp.Matrix([0, 0, 0, 0, 0, M, F, 0])  # M on the rotor, F on the load along +x
qdd = sp.Matrix(sp.symbols("a0:8", real=True))
Lam = sp.Matrix(sp.symbols("L0:6", real=True))
lam, T = sp.symbols("lam T", real=True)  # normal / friction force of the screw on the nut


def solve_multibody(h, drive, friction):
    """friction: ('slip', coefficient k with T = k * lam) or ('stick',)."""
    gN, gT, _, _ = gaps(h)
    G = sp.Matrix([[sp.diff(g, qi) for qi in q] for g in supports(drive)])
    WN = sp.Matrix([sp.diff(gN, qi) for qi in q])
    WT = sp.Matrix([sp.diff(gT, qi) for qi in q])
    eqs = list(mass * qdd - f_applied - G.T * Lam - WN * lam - WT * T)
    eqs += list(G * qdd) + [(WN.T * qdd)[0]]
    unknowns = list(qdd) + list(Lam) + [lam]
    if friction[0] == "slip":
        eqs = [e.subs(T, friction[1] * lam) for e in eqs]
    else:
        eqs.append((WT.T * qdd)[0])
        unknowns.append(T)
    sol = sp.solve(eqs, unknowns, dict=True)
    assert len(sol) == 1
    return sol[0]


for h, drive in itertools.product(SIGNS, ("screw", "nut")):
    d = 1 if drive == "screw" else -1
    Jrot = JR + (JS if drive == "screw" else JN)
    mtr = mL + (mN if drive == "screw" else mS)
    sub = {J: Jrot, m: mtr}
    for s, sig in itertools.product(SIGNS, SIGNS):
        # Coulomb slip: friction on the nut opposes the nut's slip -d rho phi_dot:
        # T = -mu |lam| sign(-d phi_dot) = mu d s sig lam.
        sol = solve_multibody(h, drive, ("slip", mu * d * s * sig))
        eps = h * d * s * sig
        acc = sol[qdd[5]]  # rotor angle
        assert zero(acc - (a_coef(eps, h) * M + b_coef(eps, h) * F).subs(sub)), (h, drive, s, sig)
        assert zero(sol[lam] - (d * K_of(h) / (c * Delta(eps * mu))).subs(sub))
        # Reduced equations (R1), (R2) with N~ = d lam, T~ = d T (rotating on translating):
        lam_t, T_t = d * sol[lam], d * mu * d * s * sig * sol[lam]
        assert zero((J_eff * acc - (M - h * p * F - rho * T_t)).subs(sub))  # (R1)
        assert zero((lam_t * c + (h * m * p * acc + F) + h * T_t * sn).subs(sub))  # (R2)
        # T~ = mu |N~| s for a normal force of sign sig (|N~| = |lam|):
        labs = sp.Symbol("labs", positive=True)
        assert zero((d * mu * d * s * sig * lam - mu * s * sp.Abs(d * lam)).subs(lam, sig * labs))
        # Power transmitted from the rotating to the translating member:
        # A v_load = -p |w| |N~| cos(alpha) (eps + mu t), A = N~ c + h T~ sn.
        wabs, nabs = sp.symbols("wabs nabs", positive=True)
        A_ax = (d * sig) * nabs * c + h * (mu * nabs * s) * sn  # N~ = d sig |N~|, T~ = mu |N~| s
        assert zero(A_ax * (-h * p * s * wabs) + p * wabs * nabs * c * (eps + mu * t))
        # Energy: d/dt(1/2 J_eff w^2) = M w + F v_load + P_friction, P_friction <= 0.
        w = sp.symbols("w", real=True)
        P_fric = (mu * d * s * sig * sol[lam]) * (-d * rho * w)  # T * d(gT)/dt
        assert zero((J_eff.subs(sub) * acc * w) - (M * w + F * (-h * p * w) + P_fric))
        assert zero(P_fric.subs(w, s * sp.Symbol("wabs", positive=True))
                    + rho * mu * sig * sol[lam] * sp.Symbol("wabs", positive=True))
    # Stick: phi_dd = 0, normal and friction force are projections of the loads.
    sol = solve_multibody(h, drive, ("stick",))
    assert zero(sol[qdd[5]])
    assert zero(sol[lam] - d * lam_tilde_stick(h))
    assert zero(sol[T] - d * T_tilde_stick(h))
print("2 multibody Newton-Euler == phi_dd = a_eps M + b_eps F, lam = d K/(c Delta_eps), stick: ok")

# ---------------------------------------------------------------------------
# 3. Mode structure, consistency, transitions.
# ---------------------------------------------------------------------------
x = sp.symbols("x", real=True)  # eps*mu, or the regularized friction factor in [-mu, mu]
for h in SIGNS:
    K = K_of(h)
    # Regularized friction T~ = x |lam~| ... gives the same structure with eps*mu -> x.
    acc_x = (M * (1 + x * t) - h * r * F * (t - x)) / Delta(x)
    lam_x = -(h * m * p * acc_x + F) / (c * (1 + x * t))
    assert zero(lam_x - K / (c * Delta(x)))  # K does not depend on the mode
    # Numerator of the slip acceleration = (r/c)(T~_st - x h lam~_st).
    assert zero(M * (1 + x * t) - h * r * F * (t - x)
                - (r / c) * (T_tilde_stick(h) - x * h * lam_tilde_stick(h)))
    # Slip and stick share lam at the transition (phi_dd = 0):
    ratio = sp.simplify((lam_x - lam_tilde_stick(h)) / acc_x)
    assert not ratio.has(M) and not ratio.has(F)
    # Flank change K = 0: friction vanishes, both modes give (M - h p F)/J_eff.
    F_K0 = sp.solve(sp.Eq(K, 0), F)[0]
    for eps in SIGNS:
        acc_eps = (a_coef(eps, h) * M + b_coef(eps, h) * F).subs(F, F_K0)
        assert zero(acc_eps - ((M - h * p * F) / J_eff).subs(F, F_K0))
# Delta_eps = J_eff + eps mu t (J - m r^2): the mode's effective inertia.
for eps in SIGNS:
    assert zero(Delta(eps * mu) - (J_eff + eps * mu * t * (J - m * r**2)))
# Delassus form: two free bodies (rotating phi with J, translating u with m), the flank
# constraint g_N = c u + h sn r phi, slip g_T = h sn u - c r phi (translating relative
# to rotating): Delta_eps = (m J / c^2) (G_NN + eps h mu G_NT), so
# min(Delta_+, Delta_-) <= 0  <=>  mu |G_NT| >= G_NN.
for h in SIGNS:
    WNv = sp.Matrix([h * sn * r, c])  # d g_N / d(phi, u)
    WTv = sp.Matrix([-c * r, h * sn])
    Minv = sp.diag(1 / J, 1 / m)
    G_NN = (WNv.T * Minv * WNv)[0]
    G_NT = (WNv.T * Minv * WTv)[0]
    for eps in SIGNS:
        assert zero(Delta(eps * mu) - m * J / c**2 * (G_NN + eps * h * mu * G_NT))
# Theorem 1 (sign table): for given s, candidate sig~ is consistent iff
# sign(K / Delta_eps) = sig~ with eps = h s sig~.
for h, s, sK, sDp, sDm in itertools.product(SIGNS, SIGNS, SIGNS, (1, 0, -1), (1, 0, -1)):
    if sDp <= 0 and sDm <= 0:
        continue  # Delta_+ + Delta_- > 0
    sD = {1: sDp, -1: sDm}
    ok = [cand for cand in SIGNS if sD[h * s * cand] != 0 and sK * sD[h * s * cand] == cand]
    if sDp > 0 and sDm > 0:
        assert ok == [sK]
    elif sDp < 0:
        assert len(ok) == (2 if h * s * sK < 0 else 0)
    elif sDm < 0:
        assert len(ok) == (2 if h * s * sK > 0 else 0)
    elif sDp == 0:
        assert ok == ([-h * s] if h * s * sK < 0 else [])  # the eps = -1 mode
    else:  # sDm == 0
        assert ok == ([h * s] if h * s * sK > 0 else [])  # the eps = +1 mode
# Frictionless limit.
for h in SIGNS:
    assert zero((a_coef(1, h) * M + b_coef(1, h) * F).subs(mu, 0) - (M - h * p * F) / J_eff)
# Delta is linear in x: positive on [-mu, mu] iff positive at both ends.
assert sp.degree(sp.expand(Delta(x)), x) == 1
assert zero(Delta(mu) + Delta(-mu) - 2 * (J + m * r**2 * t**2))
# The two jamming inequalities of the issue are exactly Delta_+ <= 0 and Delta_- <= 0.
assert zero(Delta(mu) - (J * (1 + mu * t) - m * r**2 * t * (mu - t)))
cot = 1 / t
assert zero(Delta(-mu) / t**2 - (m * r**2 * (1 + mu * cot) - J * cot * (mu - cot)))
print("3 modes: K mode-independent, numerator identity, continuity, K = 0, Delta_+/-: ok")

# Uniqueness at rest (regular case), the two end-point identities of the proof.
kappa = sp.symbols("kappa", positive=True)  # m r^2 / J
Dp_over_J = sp.expand(Delta(mu) / J).subs(m, kappa * J / r**2)
Dm_over_J = sp.expand(Delta(-mu) / J).subs(m, kappa * J / r**2)
assert zero(1 + kappa * t**2 - mu * t * (kappa - 1) - Dp_over_J)
assert zero(1 + kappa * t**2 - mu * t * (1 - kappa) - Dm_over_J)
print("3b uniqueness at rest (end-point identities): ok")

# ---------------------------------------------------------------------------
# 4. Static bounds.
# ---------------------------------------------------------------------------
for h in SIGNS:
    # Pure axial load: T_st^2 - mu^2 lam_st^2 = F^2 c^2 (t^2 - mu^2).
    e = (T_tilde_stick(h) ** 2 - mu**2 * lam_tilde_stick(h) ** 2).subs(M, 0)
    assert zero(e - F**2 * c**2 * (t**2 - mu**2))
    # Pure torque: = (M c / r)^2 (1 - mu^2 t^2).
    e = (T_tilde_stick(h) ** 2 - mu**2 * lam_tilde_stick(h) ** 2).subs(F, 0)
    assert zero(e - (M * c / r) ** 2 * (1 - mu**2 * t**2))
    # Beyond the bounds the start-up mode and direction follow from the sign rules.
    for sF in SIGNS:  # pure axial load F = sF |F|, tan(alpha) > mu'
        s_dir = -h * sF  # sign(T~_st) = sign(-h F sn)
        sig_t = -sF  # sign(K) = sign(-J F), Delta_+ > 0
        assert h * s_dir * sig_t == 1  # back-driving mode eps = +1
        acc = b_coef(1, h) * sF  # phi_dd per unit |F|, M = 0
        assert zero(acc - (-h * sF * r * (t - mu) / Delta(mu)))
        # sign(acc) = s_dir when t > mu and Delta_+ > 0: acc = s_dir * r (t - mu)/Delta_+.
        assert zero(acc - s_dir * r * (t - mu) / Delta(mu))
    for sM in SIGNS:  # pure torque M = sM |M|, mu' < cot(alpha)
        s_dir = sM  # sign(T~_st) = sign(M c / r)
        sig_t = -h * sM  # sign(K) = sign(-h m p M), Delta_- > 0
        assert h * s_dir * sig_t == -1  # forward-driving mode eps = -1
        acc = a_coef(-1, h) * sM
        assert zero(acc - s_dir * (1 - mu * t) / Delta(-mu))
    # Torques of the textbook: steady raising (eps = -1) and lowering (eps = +1) at phi_dd = 0.
    Fm = sp.symbols("Fm", positive=True)  # load magnitude
    raise_M = sp.solve(sp.Eq(M * (1 - mu * t) - h * r * (-h * Fm) * (t + mu), 0), M)[0]
    assert zero(raise_M + Fm * r * (t + mu) / (1 - mu * t))
    lower_M = sp.solve(sp.Eq(M * (1 + mu * t) - h * r * (-h * Fm) * (t - mu), 0), M)[0]
    assert zero(lower_M + Fm * r * (t - mu) / (1 + mu * t))
print("4 static bounds tan(alpha) <= mu' (holding), mu' < cot(alpha) (drivable): ok")

# ---------------------------------------------------------------------------
# 5. The thesis's eq. (4.8) -> (4.10)/(4.11) (screw drive, right hand, F on the load).
# ---------------------------------------------------------------------------
z, s_lead, FCN = sp.symbols("z s_lead F_CN", real=True)
ca, sa = c, sn
p_th = s_lead / (2 * sp.pi)
I13 = sp.symbols("I13", positive=True)  # I_P1 + I_P3
m24 = sp.symbols("m24", positive=True)  # m_2 + m_4
acc3 = sp.symbols("acc3", real=True)
for sgn in SIGNS:  # sign of F_CN
    FCT = sgn * FCN * z  # |F_CN| z
    FCR = FCT * ca - FCN * sa  # (4.7)
    FCA = FCT * sa + FCN * ca
    eq_rot = sp.Eq(I13 * acc3, M - FCR * r)  # rotor + screw, (4.8)
    eq_tr = sp.Eq(m24 * (-p_th * acc3), FCA + F)  # nut + load, (4.8) with (4.9) and F
    sol = sp.solve([eq_rot, eq_tr], [acc3, FCN], dict=True)[0]
    if sgn > 0:  # (4.10) as printed, with C_a read as c_a
        printed = 2 * sp.pi * (F * r * (ca * z - sa) + M * (ca + sa * z)) / (
            2 * sp.pi * I13 * (ca + sa * z) + r * s_lead * m24 * (sa - ca * z))
    else:  # (4.11)
        printed = -2 * sp.pi * (F * r * (sa + ca * z) + M * (-ca + sa * z)) / (
            2 * sp.pi * I13 * (ca - sa * z) + r * s_lead * m24 * (sa + ca * z))
    assert zero(sol[acc3] - printed)
    # Same as the document's formula with eps*mu' = sgn * z (h = d = 1):
    ours = (M * (1 + sgn * z * t) - r * F * (t - sgn * z)) / (
        I13 * (1 + sgn * z * t) + m24 * r**2 * t * (t - sgn * z))
    assert zero(printed.subs(s_lead, 2 * sp.pi * r * t) - ours)
    # Power of the friction force F_CT on the nut, which slides with d(u_C)/dt
    # = -rho phi3_dot (4.4): with the printed z = mu (2/pi) atan(k_V u_C_dot)
    # it is |F_CN| z u_C_dot >= 0, i.e. the printed sign makes friction do positive work.
    uCdot = sp.symbols("uCdot", real=True)
    kV = sp.symbols("k_V", positive=True)
    z_printed = mu * 2 / sp.pi * sp.atan(kV * uCdot)
    power = sp.Abs(FCN) * z_printed * uCdot
    assert sp.simplify(power.subs(uCdot, 1)) .is_nonnegative
    assert sp.simplify(power.subs(uCdot, -1)).is_nonnegative
print("5 thesis (4.10)/(4.11) re-derived (C_a -> c_a); printed z sign: friction does positive work")

# ---------------------------------------------------------------------------
# 6. The thesis's (4.32)/(4.34): flank forces in terms of the axial force F_CA.
# ---------------------------------------------------------------------------
A = sp.symbols("F_CA", real=True)
for sgn in SIGNS:
    FCT = sgn * FCN * z
    FCA = FCT * sa + FCN * ca
    FCR = FCT * ca - FCN * sa
    fcn = sp.solve(sp.Eq(FCA, A), FCN)[0]
    fct, fcr = FCT.subs(FCN, fcn), FCR.subs(FCN, fcn)
    if sgn > 0:
        assert zero(fct - A * z / (ca + z * sa))  # (4.32), first case: as printed
        assert zero(fcr - A * (z * ca - sa) / (ca + z * sa))
        printed_434 = A * z * ca / (ca + z * sa) - A * z * sa / (ca + z * sa)
        assert not zero(fcr - printed_434)  # (4.34): the second term has a spurious z
    else:
        assert zero(fct + A * z / (ca - z * sa))  # (4.32), third case needs c - z s
        assert not zero(fct + A * z / (ca + z * sa))
print("6 thesis (4.32) third case and (4.34) second term are misprinted: ok")

# ---------------------------------------------------------------------------
# 7. Sampled: solutions at rest = {stick if admissible} + consistent slip starts.
#    Regular (Delta_+/- > 0): always exactly one (Theorem 2). Jamming regime:
#    1 or 3 with stick admissible, 1 without.
# ---------------------------------------------------------------------------
import numpy as np  # noqa: E402

rng = np.random.default_rng(2013)
n = 200_000
Jn, mr2 = 10 ** rng.uniform(-3, 3, n), 10 ** rng.uniform(-3, 3, n)
tn, mun = np.tan(rng.uniform(0.01, 1.55, n)), 10 ** rng.uniform(-2, 1.5, n)
Mn, Fn, hn = rng.normal(size=n), rng.normal(size=n), rng.choice([-1.0, 1.0], n)
rn = 1.0
cn = 1 / np.sqrt(1 + tn**2)
Dn = {e: Jn * (1 + e * mun * tn) + mr2 * tn * (tn - e * mun) for e in SIGNS}
Kn = -(hn * mr2 * tn * Mn + Jn * Fn)
Tst = cn * (Mn - hn * rn * tn * Fn) / rn
Nst = -cn * (rn * Fn + hn * tn * Mn) / rn
stick_ok = np.abs(Tst) <= mun * np.abs(Nst)
count = stick_ok.astype(int)
for s_, sg in itertools.product(SIGNS, SIGNS):
    e = hn * s_ * sg
    D = np.where(e > 0, Dn[1], Dn[-1])
    acc_n = (Mn * (1 + e * mun * tn) - hn * rn * Fn * (tn - e * mun)) / D
    count += (np.sign(Kn / (cn * D)) == sg) & (np.sign(acc_n) == s_)
regular = (Dn[1] > 0) & (Dn[-1] > 0)
assert np.all(count[regular] == 1)
assert set(np.unique(count[~regular & stick_ok])) == {1, 3}
assert np.all(count[~regular & ~stick_ok] == 1)
print("7 sampled uniqueness at rest (regular: 1; jamming: 1 or 3 with stick admissible): ok")
print("all checks passed")
