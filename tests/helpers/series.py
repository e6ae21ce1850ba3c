"""Series shared by the closed-form references (free of cancellation)."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["x_minus_sin"]


def x_minus_sin(x):
    """x - sin(x) without cancellation for small |x| (vectorised).

    For |x| < 1 the series sum_{k>=1} (-1)^(k+1) x^(2k+1)/(2k+1)! is summed by
    Horner in x^2 up to k = 11; the first omitted term is below 1/25! < 1e-25.
    """
    shape = np.shape(x)
    x = np.atleast_1d(np.asarray(x, dtype=float))
    out = x - np.sin(x)
    small = np.abs(x) < 1.0
    if np.any(small):
        xs = x[small]
        x2 = xs * xs
        acc = np.zeros_like(xs)
        for k in range(11, 0, -1):
            acc = (-1.0) ** (k + 1) / math.factorial(2 * k + 1) + acc * x2
        out[small] = xs * x2 * acc
    return out.reshape(shape)
