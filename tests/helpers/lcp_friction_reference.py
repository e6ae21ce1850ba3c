"""Coulomb-friction contact problems solved by enumerating contact modes.

Independent of the LCP formulations: each contact is assigned a mode, the
resulting linear equations g'' = G lambda + c are solved with numpy, and the
mode is kept if its sign conditions hold. Conventions as in
leadscrew/friction/coulomb_lcp.hpp: g_T'' > 0 => lambda_T = -mu lambda_N.
"""

from itertools import product

import numpy as np

STICK, FORWARD, BACKWARD, OPEN = "stick", "forward", "backward", "open"


def friction_modes(G, c, mu, normal_force, tol=1e-9):
    """All (lambda_T, g_T'') consistent with Coulomb's law for known normal forces.

    Modes per contact: stick (g_T'' = 0, |lambda_T| <= r), forward sliding
    (lambda_T = -r, g_T'' >= 0), backward sliding (lambda_T = r, g_T'' <= 0),
    with r = mu lambda_N.
    """
    G = np.atleast_2d(np.asarray(G, dtype=float))
    c = np.atleast_1d(np.asarray(c, dtype=float))
    r = np.atleast_1d(np.asarray(mu, dtype=float)) * np.atleast_1d(normal_force)
    n = len(c)
    solutions = []
    for modes in product((STICK, FORWARD, BACKWARD), repeat=n):
        stick = np.array([m == STICK for m in modes])
        lam = np.array([{STICK: 0.0, FORWARD: -ri, BACKWARD: ri}[m] for m, ri in zip(modes, r)])
        if stick.any():
            rhs = -(c[stick] + G[np.ix_(stick, ~stick)] @ lam[~stick])
            sub = G[np.ix_(stick, stick)]
            try:
                lam[stick] = np.linalg.solve(sub, rhs)
            except np.linalg.LinAlgError:
                continue
            if not np.allclose(sub @ lam[stick], rhs, atol=tol):
                continue
        acc = G @ lam + c
        ok = True
        for i, m in enumerate(modes):
            if m == STICK:
                ok &= abs(lam[i]) <= r[i] + tol and abs(acc[i]) <= tol
            elif m == FORWARD:
                ok &= acc[i] >= -tol
            else:
                ok &= acc[i] <= tol
        if ok:
            solutions.append((lam, acc))
    return solutions


def contact_modes(G, c, mu, tol=1e-9):
    """All (lambda_N, lambda_T, g_N'', g_T'') of n planar contacts (G: 2n x 2n,
    normal directions first) consistent with unilateral contact and Coulomb."""
    G = np.asarray(G, dtype=float)
    c = np.asarray(c, dtype=float)
    mu = np.atleast_1d(np.asarray(mu, dtype=float))
    n = len(mu)
    solutions = []
    for modes in product((OPEN, STICK, FORWARD, BACKWARD), repeat=n):
        # Unknowns: lambda_N of closed contacts, lambda_T of sticking ones.
        columns = []  # each column: the lambda (2n) produced by a unit unknown
        rows = []  # constrained accelerations: g_N'' of closed, g_T'' of sticking
        for i, m in enumerate(modes):
            if m == OPEN:
                continue
            col = np.zeros(2 * n)
            col[i] = 1.0
            if m == FORWARD:
                col[n + i] = -mu[i]
            elif m == BACKWARD:
                col[n + i] = mu[i]
            columns.append(col)
            rows.append(i)
            if m == STICK:
                col_t = np.zeros(2 * n)
                col_t[n + i] = 1.0
                columns.append(col_t)
                rows.append(n + i)
        lam = np.zeros(2 * n)
        if columns:
            P = np.array(columns).T
            E = G[rows] @ P
            try:
                u = np.linalg.solve(E, -c[rows])
            except np.linalg.LinAlgError:
                continue
            lam = P @ u
        acc = G @ lam + c
        ok = True
        for i, m in enumerate(modes):
            lam_n, lam_t, acc_n, acc_t = lam[i], lam[n + i], acc[i], acc[n + i]
            if m == OPEN:
                ok &= acc_n >= -tol
            else:
                ok &= lam_n >= -tol and abs(acc_n) <= tol
                if m == STICK:
                    ok &= abs(lam_t) <= mu[i] * lam_n + tol and abs(acc_t) <= tol
                elif m == FORWARD:
                    ok &= acc_t >= -tol
                else:
                    ok &= acc_t <= tol
        if ok:
            solutions.append((lam[:n], lam[n:], acc[:n], acc[n:]))
    return solutions
