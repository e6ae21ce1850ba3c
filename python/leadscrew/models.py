"""Models: the friction benchmark block (thesis section 3.2.6), and the
stick-slip oscillator it becomes with a spring to a pulled point."""

from __future__ import annotations

from . import _core
from .excitation import check_load_unit, checked_callable
from .units import quantity

__all__ = ["FrictionBlock"]


class FrictionBlock(_core.FrictionBlock):
    """A block on a rough plane driven by a horizontal force (thesis eq. 3.9).

    ``m u'' = F(t) + F_spring - lambda_T`` with normal force ``lambda_N = m g``
    and the friction law :func:`leadscrew.simulate` runs (``friction=``:
    exact Coulomb ``|lambda_T| <= mu_static lambda_N`` in stick and
    ``mu lambda_N`` in slip by default). With a spring of ``stiffness`` k to
    a point that starts at the block's initial position and moves at
    ``pull_speed`` V, ``F_spring = k (initial_position + V t - u)``: the
    classic stick-slip oscillator.

    Args:
        mass: block mass m [kg], > 0.
        mu: (kinetic) friction coefficient, >= 0.
        g: gravitational acceleration [m/s^2], >= 0.
        force: the excitation F(t) [N]: a number, Constant, Sine, Table or
            callable f(t).
        initial_position: u(0) [m].
        initial_velocity: u'(0) [m/s].
        mu_static: static friction coefficient, >= mu (default: mu); for the
            laws with a static coefficient (coulomb, stribeck, lugre).
        stiffness: the spring's stiffness k [N/m], >= 0 (0: no spring).
        pull_speed: the speed V of the spring's pulled end [m/s].

    Numbers may be strings with units (``mass="2 kg"``, ``g="9.81 m/s^2"``,
    ``force="6 N"``, ``force=ls.Sine("6 N", "2 Hz")``).

    Raises:
        ValueError: a parameter is out of range, not a number or of the
            wrong dimension (a force in N*m); a callable force that returns
            no number when it is called (the message names the parameter).
    """

    def __init__(self, mass: float, mu: float, g: float = 9.81, force=0.0,
                 initial_position: float = 0.0, initial_velocity: float = 0.0,
                 mu_static=None, stiffness: float = 0.0, pull_speed: float = 0.0):
        if isinstance(force, str):
            force_value = quantity("force", force, "N")
        elif callable(force) and not isinstance(force, _core.Excitation):
            force_value = checked_callable("force", force, "N")
        else:
            check_load_unit("force", force, "N")
            force_value = force
        super().__init__(quantity("mass", mass, "kg"), quantity("mu", mu, ""),
                         quantity("g", g, "m/s^2"), force_value,
                         quantity("initial_position", initial_position, "m"),
                         quantity("initial_velocity", initial_velocity, "m/s"),
                         None if mu_static is None else quantity("mu_static", mu_static, ""),
                         quantity("stiffness", stiffness, "N/m"),
                         quantity("pull_speed", pull_speed, "m/s"))
        self._force_argument = force

    def __repr__(self) -> str:
        extra = "".join(f", {name}={getattr(self, name)!r}"
                        for name, default in (("mu_static", self.mu), ("stiffness", 0.0),
                                              ("pull_speed", 0.0))
                        if getattr(self, name) != default)
        return (f"FrictionBlock(mass={self.mass!r}, mu={self.mu!r}, g={self.g!r}, "
                f"force={self.force.describe()}{extra})")

    def __reduce__(self):
        return (FrictionBlock, (self.mass, self.mu, self.g, self._force_argument,
                                self.initial_position, self.initial_velocity, self.mu_static,
                                self.stiffness, self.pull_speed))
