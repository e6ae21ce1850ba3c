"""Linear complementarity problems (LCP) and the Coulomb-friction LCPs of the thesis.

An LCP (thesis eq. 2.13) asks for z with

    w = M z + q,   z >= 0,   w >= 0,   z^T w = 0.

Four methods share one interface (``method=``):

- ``"lemke"``: Lemke's complementary pivoting with a lexicographic ratio test
  (no cycling on degenerate problems). Solves every P-matrix problem and every
  feasible problem with a copositive-plus M (e.g. positive semidefinite);
  ``"ray_termination"`` on such an M proves there is no solution.
- ``"pgs"``: projected Gauss-Seidel / SOR (``relaxation``), warm start with
  ``z0``. Converges for symmetric positive definite M; needs M_ii > 0.
- ``"newton_fb"``: semismooth Newton on the Fischer-Burmeister function with
  an Armijo line search, warm start with ``z0``.
- ``"enumerate"``: all 2^n complementary bases (n <= 12); the reference.

A result's ``status`` is ``"solved"`` only when the returned z verifiably
satisfies the LCP: ``residual <= tol`` with ``w`` recomputed as M z + q.

Coulomb friction as an LCP (thesis sec. 2.2.1 and 3.2.6) with the builders
below. Conventions: contact forces act through the force directions W,
M y'' = h + W_N lambda_N + W_T lambda_T; the contact accelerations are
g'' = G lambda + c with the Delassus matrix G = W^T M^-1 W and the free
accelerations c = W^T M^-1 h (+ the velocity terms of eq. 2.18). Coulomb's law
(eq. 2.17): g_T'' > 0 => lambda_T = -mu lambda_N, g_T'' < 0 => lambda_T =
+mu lambda_N, g_T'' = 0 => |lambda_T| <= mu lambda_N. The friction reserves
x1 = mu lambda_N - lambda_T and x2 = mu lambda_N + lambda_T (eq. 3.13) are
complementary to the backward and forward parts of g_T''.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple, Optional, Sequence

import numpy as np

from . import _core

__all__ = [
    "METHODS",
    "STATUSES",
    "MAX_ENUMERATE_SIZE",
    "LcpResult",
    "solve",
    "complementarity_residual",
    "default_max_iterations",
    "block_friction_lcp",
    "block_friction_state",
    "BlockFrictionState",
    "friction_lcp",
    "friction_state",
    "contact_lcp",
    "contact_state",
    "ContactState",
]

METHODS = ("lemke", "pgs", "newton_fb", "enumerate")
STATUSES = ("solved", "ray_termination", "max_iterations", "singular", "no_solution")
MAX_ENUMERATE_SIZE = _core.lcp.MAX_ENUMERATE_SIZE


@dataclass(frozen=True)
class LcpResult:
    """The outcome of :func:`solve`.

    Attributes:
        z: the method's z (the solution when ``status == "solved"``).
        w: M z + q for that z.
        status: ``"solved"``; ``"ray_termination"`` (Lemke ended on a
            secondary ray: for a copositive-plus M there is no solution);
            ``"max_iterations"``; ``"singular"`` (the method met linear algebra
            it cannot continue with, or its basis misses tol); ``"no_solution"``
            (enumerate proved that none exists).
        iterations: pivots (lemke), sweeps (pgs), Newton steps (newton_fb) or
            bases tried (enumerate).
        residual: max_i |min(z_i, w_i)| + max(0, -min z) + max(0, -min w).
        method: the method used.
    """

    z: np.ndarray
    w: np.ndarray
    status: str
    iterations: int
    residual: float
    method: str

    @property
    def solved(self) -> bool:
        """True when ``status == "solved"``."""
        return self.status == "solved"


def _matrix(name: str, value, rows: Optional[int] = None) -> np.ndarray:
    array = np.asarray(value, dtype=float)
    if array.ndim != 2 or array.shape[0] != array.shape[1]:
        raise ValueError(
            f"{name} has shape {array.shape} is invalid: must be a square 2-D array"
        )
    if rows is not None and array.shape[0] != rows:
        raise ValueError(f"{name} has shape {array.shape} is invalid: must be {rows}x{rows}")
    return np.asfortranarray(array)


def _vector(name: str, value, size: Optional[int] = None) -> np.ndarray:
    array = np.asarray(value, dtype=float)
    if array.ndim != 1:
        raise ValueError(f"{name} has shape {array.shape} is invalid: must be a 1-D array")
    if size is not None and array.shape[0] != size:
        raise ValueError(
            f"{name} has size {array.shape[0]} is invalid: must have size {size}"
        )
    return array


def solve(
    M,
    q,
    method: str = "lemke",
    tol: float = 1e-12,
    max_iter: Optional[int] = None,
    z0: Optional[Sequence[float]] = None,
    relaxation: float = 1.0,
) -> LcpResult:
    """Solve the LCP w = M z + q, z >= 0, w >= 0, z^T w = 0.

    Args:
        M: (n, n) matrix, finite.
        q: (n,) vector, finite.
        method: one of ``METHODS``.
        tol: bound on the complementarity residual for ``"solved"`` (absolute,
            in the units of z and w), > 0.
        max_iter: iteration budget (pivots, sweeps, Newton steps or bases),
            integer >= 1; None for the method's default
            (:func:`default_max_iterations`).
        z0: warm start (n,) for ``"pgs"`` and ``"newton_fb"`` (ignored by the
            pivoting methods); None starts from z = 0.
        relaxation: SOR relaxation factor of ``"pgs"`` in (0, 2).

    Returns:
        An :class:`LcpResult`; check ``status`` (or ``.solved``): a method that
        fails says so and never returns ``"solved"`` with a residual above tol.

    Raises:
        ValueError: M not square, q or z0 of the wrong size, a non-finite
            entry, an unknown method, enumerate with n > 12, or an option out
            of range; the message names the argument.
    """
    M = _matrix("M", M)
    q = _vector("q", q)
    if q.shape[0] != M.shape[0]:
        raise ValueError(
            f"q has size {q.shape[0]} is invalid: must equal the size of M ({M.shape[0]})"
        )
    if max_iter is None:
        budget = 0
    else:
        if isinstance(max_iter, bool) or int(max_iter) != max_iter or max_iter < 1:
            raise ValueError(f"max_iter = {max_iter!r} is invalid: must be an integer >= 1")
        budget = int(min(max_iter, 2**31 - 1))
    start = None if z0 is None else _vector("z0", z0, q.shape[0])
    z, w, status, iterations, residual = _core.lcp.solve(
        M, q, method, float(tol), budget, start, float(relaxation)
    )
    return LcpResult(
        z=np.asarray(z), w=np.asarray(w), status=status, iterations=int(iterations),
        residual=float(residual), method=method,
    )


def complementarity_residual(z, w) -> float:
    """max_i |min(z_i, w_i)| + max(0, -min z) + max(0, -min w).

    Args:
        z: (n,) vector.
        w: (n,) vector, same size.

    Returns:
        The residual; 0 exactly at a solution; +inf if an entry of z or w is
        NaN or inf (no solution).

    Raises:
        ValueError: z or w not 1-D or of different sizes.
    """
    z = _vector("z", z)
    w = _vector("w", w, z.shape[0])
    return float(_core.lcp.complementarity_residual(z, w))


def default_max_iterations(method: str, n: int) -> int:
    """The iteration budget ``max_iter=None`` stands for.

    Args:
        method: one of ``METHODS``.
        n: problem size.

    Returns:
        lemke 1000 + 2^(min(n, 20) + 1) pivots, pgs 10000 sweeps, newton_fb
        100 steps, enumerate 2^n bases.

    Raises:
        ValueError: unknown method.
    """
    return int(_core.lcp.default_max_iterations(method, int(n)))


def _require(name: str, value, ok: bool, valid: str) -> float:
    if not ok:
        raise ValueError(f"{name} = {value!r} is invalid: must be {valid}")
    return float(value)


def _finite(name: str, value) -> float:
    value = float(value)
    return _require(name, value, math.isfinite(value), "a finite number")


class BlockFrictionState(NamedTuple):
    """Friction force and acceleration of the thesis's block (eq. 3.9).

    Attributes:
        friction_force: lambda_T [N], acting against u: m u'' = F_Exc - lambda_T.
        acceleration: u'' [m/s^2].
    """

    friction_force: float
    acceleration: float


def block_friction_lcp(mass: float, mu: float, normal_force: float, excitation_force: float):
    """The thesis's friction LCP of a block on a plane (eq. 3.9-3.14).

    m u'' = F_Exc - lambda_T with Coulomb friction |lambda_T| <= mu lambda_N.
    Unknowns z = (x1, x2) = (lambda_N mu - lambda_T, lambda_N mu + lambda_T)
    (eq. 3.13), w = ((|u''| + u'')/2, (|u''| - u'')/2) (eq. 3.10), and

        A = [[1/m, 0], [0, 1/m]],
        b = ((F_Exc - mu lambda_N)/m, -(F_Exc + mu lambda_N)/m).

    The thesis (eq. 3.14, with lambda_N = m g) prints b2 = +(F_Exc + m g mu)/m;
    substituting eq. (3.12)-(3.13) into the second row gives the minus sign,
    which is the one that makes the block stick for |F_Exc| <= mu m g.

    Args:
        mass: m [kg], > 0.
        mu: friction coefficient, >= 0.
        normal_force: lambda_N [N] (m g on a horizontal plane), >= 0.
        excitation_force: F_Exc [N], finite.

    Returns:
        (A, b): the (2, 2) matrix and (2,) vector of the LCP w = A z + b.

    Raises:
        ValueError: a value out of range (the message names it).
    """
    mass = float(mass)
    _require("mass", mass, math.isfinite(mass) and mass > 0.0, "a finite number > 0")
    force = _finite("excitation_force", excitation_force)
    A, b = _core.lcp.single_friction_lcp(1.0 / mass, -force / mass, float(mu), float(normal_force))
    return np.asarray(A), np.asarray(b)


def block_friction_state(z, w, mu: float, normal_force: float) -> BlockFrictionState:
    """Friction force and acceleration from a solution of :func:`block_friction_lcp`.

    u'' = w1 - w2 (eq. 3.11); lambda_T = mu lambda_N - x1, or x2 - mu lambda_N
    while the block slides backwards (eq. 3.13).

    Args:
        z: (2,) solution (x1, x2).
        w: (2,) A z + b.
        mu: friction coefficient, >= 0.
        normal_force: lambda_N [N], >= 0.

    Returns:
        A :class:`BlockFrictionState` (friction_force [N], acceleration [m/s^2]).

    Raises:
        ValueError: z or w not of size 2, a value out of range.
    """
    friction, tangential = _core.lcp.single_friction_state(
        _vector("z", z, 2), _vector("w", w, 2), float(mu), float(normal_force)
    )
    # The block's W_T = -1: u'' = -g_T''.
    return BlockFrictionState(float(friction), 0.0 - float(tangential))


def friction_lcp(delassus, free_acceleration, mu, normal_force):
    """Friction LCP of n coupled contacts with known normal forces (size 2n).

    With r = mu lambda_N and the reserves x1 = r - lambda_T, x2 = r + lambda_T:
    z = (x1, g_T''+), w = (g_T''-, x2), g_T'' = g_T''+ - g_T''-, and

        A = [[G, I], [-I, 0]],   b = (-(G r + c), 2 r),

    from g_T'' = G lambda_T + c. For a positive semidefinite G, Lemke always
    solves it (PGS cannot: zero diagonal). One contact of the thesis's block:
    G = 1/m, c = -F_Exc/m.

    Args:
        delassus: G = W_T^T M^-1 W_T, (n, n) (a scalar for n = 1), symmetric
            positive semidefinite.
        free_acceleration: c = W_T^T M^-1 h, (n,) [m/s^2].
        mu: friction coefficients, (n,), >= 0.
        normal_force: lambda_N, (n,) [N], >= 0.

    Returns:
        (A, b): (2n, 2n) matrix and (2n,) vector.

    Raises:
        ValueError: inconsistent sizes, non-finite or negative entries.
    """
    G = np.atleast_2d(np.asarray(delassus, dtype=float))
    n = G.shape[0] if G.ndim == 2 else -1
    G = _matrix("delassus", G, n)
    A, b = _core.lcp.friction_lcp(
        G,
        _vector("free_acceleration", np.atleast_1d(free_acceleration), n),
        _vector("mu", np.atleast_1d(mu), n),
        _vector("normal_force", np.atleast_1d(normal_force), n),
    )
    return np.asarray(A), np.asarray(b)


def friction_state(z, w, mu, normal_force):
    """Friction forces and tangential accelerations from a solution of :func:`friction_lcp`.

    Args:
        z: (2n,) solution.
        w: (2n,) A z + b.
        mu: (n,) friction coefficients, >= 0.
        normal_force: (n,) lambda_N [N], >= 0.

    Returns:
        A :class:`ContactState` of arrays of size n: ``friction_force``,
        lambda_T = mu lambda_N - x1 [N], and ``tangential_acceleration``,
        g_T'' = g_T''+ - g_T''- [m/s^2].

    Raises:
        ValueError: inconsistent sizes, non-finite or negative entries.
    """
    mu = _vector("mu", np.atleast_1d(mu))
    n = mu.shape[0]
    friction, tangential = _core.lcp.friction_state(
        _vector("z", z, 2 * n), _vector("w", w, 2 * n), mu,
        _vector("normal_force", np.atleast_1d(normal_force), n),
    )
    return np.asarray(friction), np.asarray(tangential)


class ContactState(NamedTuple):
    """Contact forces and accelerations of planar contacts (arrays of size n).

    Attributes:
        normal_force: lambda_N [N].
        friction_force: lambda_T [N].
        normal_acceleration: g_N'' [m/s^2].
        tangential_acceleration: g_T'' [m/s^2].
    """

    normal_force: np.ndarray
    friction_force: np.ndarray
    normal_acceleration: np.ndarray
    tangential_acceleration: np.ndarray


def contact_lcp(delassus, free_acceleration, mu):
    """LCP of n planar contacts with unilateral normal contact and Coulomb friction.

    Pfeiffer & Glocker's decomposition (thesis eq. 2.14, 2.17, 2.24): per
    contact g_N'' _|_ lambda_N, g_T''+ _|_ x2, g_T''- _|_ x1, with
    z = (lambda_N, x2, g_T''-), w = (g_N'', g_T''+, x1) (blocks of size n) and

        g_N''  = (G_NN - G_NT mu) lambda_N + G_NT x2 + c_N
        g_T''+ = (G_TN - G_TT mu) lambda_N + G_TT x2 + g_T''- + c_T
        x1     = 2 mu lambda_N - x2.

    Not copositive in general: for large mu and G_NT != 0 the LCP may have no
    solution or several (Painleve).

    Args:
        delassus: G = [W_N W_T]^T M^-1 [W_N W_T], (2n, 2n), all normal
            directions first.
        free_acceleration: (c_N, c_T), (2n,) [m/s^2].
        mu: friction coefficients, (n,) (a scalar for n = 1), >= 0.

    Returns:
        (A, b): (3n, 3n) matrix and (3n,) vector.

    Raises:
        ValueError: inconsistent sizes, non-finite entries, mu < 0.
    """
    mu = _vector("mu", np.atleast_1d(mu))
    n = mu.shape[0]
    A, b = _core.lcp.contact_lcp(
        _matrix("delassus", delassus, 2 * n),
        _vector("free_acceleration", free_acceleration, 2 * n),
        mu,
    )
    return np.asarray(A), np.asarray(b)


def contact_state(z, w, mu) -> ContactState:
    """Contact forces and accelerations from a solution of :func:`contact_lcp`.

    Args:
        z: (3n,) solution.
        w: (3n,) A z + b.
        mu: (n,) friction coefficients, >= 0.

    Returns:
        A :class:`ContactState`: lambda_N = z_N, lambda_T = x2 - mu lambda_N,
        g_N'' = w_N, g_T'' = g_T''+ - g_T''-.

    Raises:
        ValueError: inconsistent sizes, non-finite entries, mu < 0.
    """
    mu = _vector("mu", np.atleast_1d(mu))
    n = mu.shape[0]
    values = _core.lcp.contact_state(_vector("z", z, 3 * n), _vector("w", w, 3 * n), mu)
    return ContactState(*(np.asarray(v) for v in values))
