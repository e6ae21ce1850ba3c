"""Independent LCP references in pure Python, written without the package.

- ``lemke_exact``: Lemke's method (covering vector e, lexicographic ratio test)
  in exact rational arithmetic (fractions.Fraction): its pivot counts and
  solutions carry no rounding at all.
- ``all_solutions_by_bases``: every basic solution of a small LCP, by brute
  force over the 2^n index sets with numpy.linalg.
- ``murty_problem``: Murty's problem family on which Lemke needs 2^n pivots.
"""

from fractions import Fraction
from itertools import product

import numpy as np


def murty_problem(n):
    """M upper triangular, 1 on the diagonal, 2 above; q_i = -(2^(n+1) - 2^i), i = 1..n.

    M is a P-matrix; the unique solution is z = 2^n e_n, with w = M z + q =
    (2^1, 2^2, ..., 2^(n-1), 0).
    """
    M = np.triu(np.full((n, n), 2.0), 1) + np.eye(n)
    q = -np.array([2.0 ** (n + 1) - 2.0**i for i in range(1, n + 1)])
    return M, q


def lemke_exact(M, q, max_pivots=100000):
    """Lemke's method in exact arithmetic.

    Returns (z, pivots, status) with z a list of Fractions; status "solved" or
    "ray_termination". The pivot count includes the pivot that brings in z0.
    """
    n = len(q)
    M = [[Fraction(x) for x in row] for row in np.asarray(M, dtype=float).tolist()]
    q = [Fraction(x) for x in np.asarray(q, dtype=float).tolist()]
    if all(x >= 0 for x in q):
        return [Fraction(0)] * n, 0, "solved"
    # Tableau rows: [B^-1 (n) | coefficients of z (n) | z0 | rhs], in the form
    # B^-1 (I w - M z - e z0) = B^-1 q.
    rows = []
    for i in range(n):
        row = [Fraction(int(i == j)) for j in range(n)]
        row += [-M[i][j] for j in range(n)]
        row += [Fraction(-1), q[i]]
        rows.append(row)
    basic = list(range(n))  # variable ids: w_j = j, z_j = n + j, z0 = 2n
    z0, rhs = 2 * n, 2 * n + 1

    def do_pivot(r, col):
        p = rows[r][col]
        rows[r] = [x / p for x in rows[r]]
        for i in range(n):
            if i != r and rows[i][col] != 0:
                f = rows[i][col]
                rows[i] = [a - f * b for a, b in zip(rows[i], rows[r])]

    def key(i, col):
        c = rows[i][col]
        return [rows[i][rhs] / c] + [rows[i][j] / c for j in range(n)]

    # z0 enters: the lexicographic minimum of (q_i, e_i).
    r = min(range(n), key=lambda i: [q[i]] + [Fraction(int(i == j)) for j in range(n)])
    leaving = basic[r]
    do_pivot(r, z0)
    basic[r] = z0
    pivots = 1
    while leaving != z0:
        if pivots >= max_pivots:
            raise RuntimeError("pivot budget exceeded")
        entering = leaving + n if leaving < n else leaving - n
        candidates = [i for i in range(n) if rows[i][entering] > 0]
        if not candidates:
            return None, pivots, "ray_termination"
        r = min(candidates, key=lambda i: key(i, entering))
        leaving = basic[r]
        do_pivot(r, entering)
        basic[r] = entering
        pivots += 1
    z = [Fraction(0)] * n
    for i, v in enumerate(basic):
        if n <= v < 2 * n:
            z[v - n] = rows[i][rhs]
    return z, pivots, "solved"


def all_solutions_by_bases(M, q, tol=1e-9):
    """Every basic solution z of LCP(M, q) (n <= 10) by brute force, as a list.

    For each index set a with M_aa regular: z_a = -M_aa^-1 q_a, z = 0 elsewhere,
    kept if z >= -tol and M z + q >= -tol.
    """
    M = np.asarray(M, dtype=float)
    q = np.asarray(q, dtype=float)
    n = len(q)
    found = []
    for mask in product((False, True), repeat=n):
        a = np.array(mask, dtype=bool)
        z = np.zeros(n)
        if a.any():
            sub = M[np.ix_(a, a)]
            if abs(np.linalg.det(sub)) < 1e-12 * max(1.0, np.abs(sub).max()) ** a.sum():
                continue
            z[a] = np.linalg.solve(sub, -q[a])
        w = M @ z + q
        if (z >= -tol).all() and (w >= -tol).all():
            found.append(z)
    return found
