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
        transverse_velocity: the plane's slip w(t) across the block's path
            [m/s] (a number, Sine, Table or callable; default None: none).
            Friction is then an isotropic 2-D cone on the slip (u', w):
            ``mu N (u', w) / |(u', w)|`` in slip, stick only where both
            vanish (docs/physics/transverse_slip.md). Runs exact Coulomb
            (``friction="coulomb"``, with ``mu_static``) and Stribeck's
            curve on the slip speed on ``integrator="event_driven"`` or
            ``"moreau"``, LuGre's bristles as a 2-D vector on its ODE
            integrators; the arctan laws and Stribeck's regularization are
            refused (ValueError). The result gains the
            channels ``transverse_velocity``, ``transverse_friction`` and
            ``work_transverse`` (the plane's excitation's work, in the
            energy account).

    Numbers may be strings with units (``mass="2 kg"``, ``g="9.81 m/s^2"``,
    ``force="6 N"``, ``force=ls.Sine("6 N", "2 Hz")``).

    Raises:
        ValueError: a parameter is out of range, not a number or of the
            wrong dimension (a force in N*m); a callable force that returns
            no number when it is called (the message names the parameter).
    """

    def __init__(self, mass: float, mu: float, g: float = 9.81, force=0.0,
                 initial_position: float = 0.0, initial_velocity: float = 0.0,
                 mu_static=None, stiffness: float = 0.0, pull_speed: float = 0.0,
                 transverse_velocity=None):
        force_value = _load_value("force", force, "N")
        transverse_value = (None if transverse_velocity is None else
                            _load_value("transverse_velocity", transverse_velocity, "m/s"))
        super().__init__(quantity("mass", mass, "kg"), quantity("mu", mu, ""),
                         quantity("g", g, "m/s^2"), force_value,
                         quantity("initial_position", initial_position, "m"),
                         quantity("initial_velocity", initial_velocity, "m/s"),
                         None if mu_static is None else quantity("mu_static", mu_static, ""),
                         quantity("stiffness", stiffness, "N/m"),
                         quantity("pull_speed", pull_speed, "m/s"), transverse_value)
        self._force_argument = force
        self._transverse_argument = transverse_velocity

    def __repr__(self) -> str:
        extra = "".join(f", {name}={getattr(self, name)!r}"
                        for name, default in (("mu_static", self.mu), ("stiffness", 0.0),
                                              ("pull_speed", 0.0))
                        if getattr(self, name) != default)
        if self.transverse_velocity is not None:
            extra += f", transverse_velocity={self.transverse_velocity.describe()}"
        return (f"FrictionBlock(mass={self.mass!r}, mu={self.mu!r}, g={self.g!r}, "
                f"force={self.force.describe()}{extra})")

    def __reduce__(self):
        return (FrictionBlock, (self.mass, self.mu, self.g, self._force_argument,
                                self.initial_position, self.initial_velocity, self.mu_static,
                                self.stiffness, self.pull_speed, self._transverse_argument))


def _load_value(name: str, value, unit: str):
    """A load argument as the core takes it: a number (a string with a unit
    converted), an Excitation (its unit checked) or a checked callable.

    Raises:
        ValueError: the value's unit is not ``unit``, or a callable returns
            no number (the message names ``name``).
    """
    if isinstance(value, str):
        return quantity(name, value, unit)
    if callable(value) and not isinstance(value, _core.Excitation):
        return checked_callable(name, value, unit)
    check_load_unit(name, value, unit)
    return value
