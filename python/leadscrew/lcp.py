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
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence

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
        The residual; 0 exactly at a solution.

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
