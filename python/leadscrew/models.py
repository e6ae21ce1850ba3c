"""Models: the friction benchmark block (thesis section 3.2.6)."""

from __future__ import annotations

from . import _core

__all__ = ["FrictionBlock"]


class FrictionBlock(_core.FrictionBlock):
    """A block on a rough plane driven by a horizontal force (thesis eq. 3.9).

    ``m u'' = F(t) - lambda_T`` with normal force ``lambda_N = m g`` and
    Coulomb friction ``|lambda_T| <= mu lambda_N``.

    Args:
        mass: block mass m [kg], > 0.
        mu: friction coefficient, >= 0.
        g: gravitational acceleration [m/s^2], >= 0.
        force: the excitation F(t) [N]: a number, Constant, Sine, Table or
            callable f(t).
        initial_position: u(0) [m].
        initial_velocity: u'(0) [m/s].

    Raises:
        ValueError: a parameter is out of range (the message names it).
    """

    def __init__(self, mass: float, mu: float, g: float = 9.81, force=0.0,
                 initial_position: float = 0.0, initial_velocity: float = 0.0):
        super().__init__(mass, mu, g, force, initial_position, initial_velocity)
        self._force_argument = force

    def __repr__(self) -> str:
        return (f"FrictionBlock(mass={self.mass!r}, mu={self.mu!r}, g={self.g!r}, "
                f"force={self.force.describe()})")

    def __reduce__(self):
        return (FrictionBlock, (self.mass, self.mu, self.g, self._force_argument,
                                self.initial_position, self.initial_velocity))
