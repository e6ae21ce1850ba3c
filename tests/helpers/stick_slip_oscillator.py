"""Closed form of the stick-slip oscillator: a block of mass m on a plane with
exact Coulomb friction (static mu_s >= kinetic mu, normal force N = m g), pulled
through a spring of stiffness k whose far end starts at the block's position
and moves at the speed V > 0; no other force.

Written from the mechanics, independent of leadscrew. With the spring's
extension s = V t - (u - u_0) and its force k s on the block:

- stick: u' = 0, s grows as V t, until k s reaches mu_s N;
- slip (u' > 0): m u'' = k s - mu N, so s'' = -omega^2 (s - s_0) with
  omega = sqrt(k / m), s_0 = mu N / k. The slip starts at s = mu_s N / k,
  s' = V: on the circle of radius R = sqrt(A^2 + (V / omega)^2), A =
  (mu_s - mu) N / k, about (s_0, 0) in the plane (s - s_0, s' / omega), it
  turns clockwise from (A, V / omega) (angle theta_0 = atan2(V / omega, A))
  to (-A, V / omega), where u' = V - s' is zero again: an angle of
  pi + 2 theta_0, so the slip lasts (pi + 2 theta_0) / omega (2 pi / omega
  for mu_s = mu: u' = V (1 - cos omega t) touches zero after a period), and
  its arc passes both ends of the circle (the spring's force mu N +- k R)
  and its bottom (s' = -R omega: the block's peak velocity V + R omega);
- the next stick: s from s_0 - A up to s_0 + A at the speed V: 2 A / V.

The first stick lasts mu_s N / (k V). Per cycle the block advances V T.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["StickSlipOscillator"]


@dataclass(frozen=True)
class StickSlipOscillator:
    mass: float
    mu: float
    mu_static: float
    g: float
    stiffness: float
    pull_speed: float

    @property
    def normal(self) -> float:
        return self.mass * self.g

    @property
    def omega(self) -> float:
        return math.sqrt(self.stiffness / self.mass)

    @property
    def amplitude_offset(self) -> float:
        """A = (mu_s - mu) N / k [m]."""
        return (self.mu_static - self.mu) * self.normal / self.stiffness

    @property
    def radius(self) -> float:
        """R [m] of the slip's circle."""
        return math.hypot(self.amplitude_offset, self.pull_speed / self.omega)

    @property
    def first_stick(self) -> float:
        return self.mu_static * self.normal / (self.stiffness * self.pull_speed)

    @property
    def slip_duration(self) -> float:
        start = math.atan2(self.pull_speed / self.omega, self.amplitude_offset)
        return (math.pi + 2.0 * start) / self.omega

    @property
    def stick_duration(self) -> float:
        return 2.0 * self.amplitude_offset / self.pull_speed

    @property
    def period(self) -> float:
        return self.slip_duration + self.stick_duration

    @property
    def peak_velocity(self) -> float:
        """The block's largest velocity: V + R omega, where s' = -R omega."""
        return self.pull_speed + self.radius * self.omega

    @property
    def spring_force_extremes(self) -> tuple:
        """(min, max) of the spring's force over a slip: mu N -+ k R."""
        centre = self.mu * self.normal
        return centre - self.stiffness * self.radius, centre + self.stiffness * self.radius

    def event_times(self, t_end: float) -> list:
        """[(time, "stick->slip+" or "slip+->stick")] up to t_end."""
        events, t = [], self.first_stick
        while t <= t_end:
            events.append((t, "stick->slip+"))
            t += self.slip_duration
            if t > t_end:
                break
            events.append((t, "slip+->stick"))
            t += self.stick_duration
        return events

    def extension(self, t: float) -> float:
        """The spring's extension s(t) [m]."""
        if t <= self.first_stick:
            return self.pull_speed * t
        cycle = math.floor((t - self.first_stick) / self.period)
        tau = t - self.first_stick - cycle * self.period
        centre = self.mu * self.normal / self.stiffness
        if tau <= self.slip_duration:
            w = self.omega
            return (centre + self.amplitude_offset * math.cos(w * tau)
                    + self.pull_speed / w * math.sin(w * tau))
        return centre - self.amplitude_offset + self.pull_speed * (tau - self.slip_duration)

    def position(self, t: float) -> float:
        """u(t) - u_0 = V t - s(t) [m]."""
        return self.pull_speed * t - self.extension(t)
