"""ODE test problems with closed-form solutions (written independently of the
integrators under test)."""

import math

import numpy as np


class HarmonicOscillator:
    """x'' = -omega^2 x as y = (x, v); x(0) = x0, v(0) = v0."""

    def __init__(self, omega=2.0, x0=1.0, v0=0.5):
        self.omega, self.y0 = omega, np.array([x0, v0])

    def rhs(self, t, y):
        return np.array([y[1], -self.omega**2 * y[0]])

    def exact(self, t):
        w, (x0, v0) = self.omega, self.y0
        t = np.asarray(t, dtype=float)
        x = x0 * np.cos(w * t) + v0 / w * np.sin(w * t)
        v = -x0 * w * np.sin(w * t) + v0 * np.cos(w * t)
        return np.array([x, v])


class ExponentialDecay:
    """y' = -k y, y(0) = y0."""

    def __init__(self, k=1.0, y0=1.0):
        self.k, self.y0 = k, np.array([y0])

    def rhs(self, t, y):
        return -self.k * y

    def exact(self, t):
        return np.array([self.y0[0] * np.exp(-self.k * np.asarray(t, dtype=float))])


class ForcedDecay:
    """y' = -a y + b sin(w t), y(0) = y0 (a forced, non-autonomous linear system).

    y(t) = (y0 + b w / (a^2 + w^2)) e^{-a t} + b (a sin(w t) - w cos(w t)) / (a^2 + w^2).
    """

    def __init__(self, a=1.5, b=2.0, w=3.0, y0=0.5):
        self.a, self.b, self.w, self.y0 = a, b, w, np.array([y0])

    def rhs(self, t, y):
        return np.array([-self.a * y[0] + self.b * math.sin(self.w * t)])

    def exact(self, t):
        a, b, w = self.a, self.b, self.w
        t = np.asarray(t, dtype=float)
        d = a * a + w * w
        return np.array(
            [(self.y0[0] + b * w / d) * np.exp(-a * t) + b * (a * np.sin(w * t) - w * np.cos(w * t)) / d]
        )


class FreeFall:
    """h'' = -g as y = (h, v) from height h0 at rest: h = 0 at t = sqrt(2 h0 / g)."""

    def __init__(self, g=9.81, h0=2.0):
        self.g, self.y0 = g, np.array([h0, 0.0])

    def rhs(self, t, y):
        return np.array([y[1], -self.g])

    def exact(self, t):
        t = np.asarray(t, dtype=float)
        return np.array([self.y0[0] - 0.5 * self.g * t * t, -self.g * t])

    def impact_time(self):
        return math.sqrt(2.0 * self.y0[0] / self.g)


class BouncingBall(FreeFall):
    """Free fall with elastic-with-restitution impacts v+ = -e v- at h = 0.

    Impact k (k = 0, 1, ...) happens at t_k; the rebound speed after impact k
    is e^(k+1) sqrt(2 g h0).
    """

    def __init__(self, g=9.81, h0=2.0, restitution=0.8):
        super().__init__(g, h0)
        self.e = restitution

    def impact_times(self, count):
        g, e = self.g, self.e
        v = math.sqrt(2.0 * g * self.y0[0])
        times = [v / g]
        for _ in range(count - 1):
            v *= e
            times.append(times[-1] + 2.0 * v / g)
        return np.array(times)


class Riccati:
    """y' = -2 t y^2, y(0) = 1: y = 1 / (1 + t^2) (nonlinear, non-autonomous)."""

    def __init__(self):
        self.y0 = np.array([1.0])

    def rhs(self, t, y):
        return np.array([-2.0 * t * y[0] * y[0]])

    def exact(self, t):
        return np.array([1.0 / (1.0 + np.asarray(t, dtype=float) ** 2)])
