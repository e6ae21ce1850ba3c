"""Seeded random LCP families for the solver tests (sizes 1 to 16).

Each generator takes (n, rng) and returns (M, q). The families:
  spd            symmetric positive definite M, q random
  pd_nonsym      M = SPD + skew: positive definite, nonsymmetric, a P-matrix
  triangular_p   triangular with positive diagonal: a P-matrix, not definite
  dominant_p     row diagonally dominant, positive diagonal: a P-matrix
  psd_feasible   positive semidefinite (rank about n/2, plus a skew part),
                 q built from a known solution: feasible, many solutions
  degenerate_psd integer PSD data (singular) and degenerate_p integer
                 triangular P-matrices, both with q from a degenerate known
                 solution (z_i = w_i = 0 for some i; zeros in q): ties in
                 Lemke's ratio test
"""

import numpy as np


def spd(n, rng):
    A = rng.normal(size=(n, n))
    M = A @ A.T / n + 0.1 * np.eye(n)
    return M, rng.normal(size=n)


def pd_nonsym(n, rng):
    A = rng.normal(size=(n, n))
    K = rng.normal(size=(n, n))
    M = A @ A.T / n + 0.2 * np.eye(n) + (K - K.T)
    return M, rng.normal(size=n)


def triangular_p(n, rng):
    T = np.tril(rng.normal(size=(n, n)), -1) + np.diag(rng.uniform(0.5, 2.0, size=n))
    M = T if rng.random() < 0.5 else T.T
    return M, rng.normal(size=n) * 2.0


def dominant_p(n, rng):
    M = rng.normal(size=(n, n))
    np.fill_diagonal(M, 0.0)
    M += np.diag(np.abs(M).sum(axis=1) + rng.uniform(0.1, 1.0, size=n))
    return M, rng.normal(size=n)


def _from_solution(M, rng, degenerate_fraction=0.0, integer=False):
    """q = w* - M z* for a complementary pair z*, w* >= 0 with random support;
    a fraction of the indices gets z*_i = w*_i = 0 (degenerate)."""
    n = M.shape[0]
    draw = (lambda: rng.integers(1, 4, size=n).astype(float)) if integer else (
        lambda: rng.uniform(0.1, 2.0, size=n)
    )
    in_z = rng.random(n) < 0.5
    z = np.where(in_z, draw(), 0.0)
    w = np.where(in_z, 0.0, draw())
    zero = rng.random(n) < degenerate_fraction
    z[zero] = 0.0
    w[zero] = 0.0
    return w - M @ z


def psd_feasible(n, rng):
    k = max(1, n // 2)
    A = rng.normal(size=(n, k))
    K = rng.normal(size=(n, n)) * 0.5
    M = A @ A.T + (K - K.T)
    return M, _from_solution(M, rng)


def degenerate_psd(n, rng):
    """Integer PSD B B^T, B in {-1, 0, 1} (singular for n > 2)."""
    B = rng.integers(-1, 2, size=(n, max(1, n // 2))).astype(float)
    M = B @ B.T
    return M, _from_solution(M, rng, degenerate_fraction=0.4, integer=True)


def degenerate_p(n, rng):
    """Integer triangular P-matrix: 1 on the diagonal, entries in {-1, 0, 1, 2}."""
    M = np.triu(rng.integers(-1, 3, size=(n, n)).astype(float), 1) + np.eye(n)
    if rng.random() < 0.5:
        M = M.T.copy()
    return M, _from_solution(M, rng, degenerate_fraction=0.4, integer=True)


FAMILIES = {
    "spd": spd,
    "pd_nonsym": pd_nonsym,
    "triangular_p": triangular_p,
    "dominant_p": dominant_p,
    "psd_feasible": psd_feasible,
    "degenerate_psd": degenerate_psd,
    "degenerate_p": degenerate_p,
}
# Families whose M is a P-matrix (unique solution for every q).
P_MATRIX_FAMILIES = ("spd", "pd_nonsym", "triangular_p", "dominant_p", "degenerate_p")
