"""Thread geometry and the closed-form mechanics of a power screw.

All quantities are SI: lengths in m, angles in rad, forces in N, torques in N*m.
Every numeric parameter may instead be a string with a unit (``"2 mm"``,
``"30 deg"``, ``"100 N"``), converted by :func:`leadscrew.units.to_si` as in a
scene; a wrong dimension or a value that is no number raises ``ValueError``
naming the parameter.
The effective friction coefficient of a thread with included flank angle beta is
mu' = mu / cos(beta / 2). The bounds tan(alpha) < mu' < cot(alpha) of static
position holding and drivability are eq. (3.5), (3.7), (3.8) of the thesis.
"""

from __future__ import annotations

from typing import Any, Union

from . import _core
from .units import quantity

__all__ = [
    "Thread",
    "raise_torque",
    "lower_torque",
    "efficiency",
    "is_self_locking",
    "is_drivable",
]


Number = Union[float, str]


class Thread(_core.Thread):
    # The core's docstring (Args, Raises) and what this class adds.
    __doc__ = (_core.Thread.__doc__.strip() + """

Lengths and the angle may be strings with units: ``Thread("2 mm", "9 mm",
flank_angle="30 deg")``; a value that is no number, or a string of another
dimension, raises ValueError naming the parameter.
""")

    def __init__(self, pitch: Number, mean_diameter: Number, starts: int = 1,
                 flank_angle: Number = 0.0, hand: str = "right"):
        super().__init__(quantity("pitch", pitch, "m"),
                         quantity("mean_diameter", mean_diameter, "m"),
                         _starts(starts), quantity("flank_angle", flank_angle, "rad"),
                         _hand(hand))

    @classmethod
    def _validated(cls, pitch: float, mean_diameter: float, starts: int, flank_angle: float,
                   hand: str) -> "Thread":
        """A Thread of values a scene has validated (SI floats, an int, a
        hand name): without this class's conversions."""
        thread = cls.__new__(cls)
        _core.Thread.__init__(thread, pitch, mean_diameter, starts, flank_angle, hand)
        return thread

    def __reduce__(self):
        return (Thread, (self.pitch, self.mean_diameter, self.starts, self.flank_angle,
                         self.hand))


def _starts(value: Any) -> int:
    """The number of starts as an int (the core checks >= 1)."""
    if value.__class__ is int:
        return value
    number = quantity("starts", value, "")
    if not (number == number and abs(number) < 2 ** 31 and number == int(number)):
        raise ValueError(f"starts = {value!r} is invalid: must be an integer >= 1")
    return int(number)


def _hand(value: Any) -> str:
    """The hand as text (the core checks the name)."""
    if value.__class__ is not str and not isinstance(value, str):
        raise ValueError(f'hand = {value!r} is invalid: must be one of "right", "left"')
    return value


def _checked_thread(thread: Any) -> "_core.Thread":
    if not isinstance(thread, _core.Thread):
        raise ValueError(f"thread = {thread!r} is invalid: must be a leadscrew.Thread")
    return thread


def raise_torque(
    thread: Thread,
    mu: Number,
    load: Number,
    collar_mu: Number = 0.0,
    collar_diameter: Number = 0.0,
) -> float:
    """Torque to move an axial load against its direction (to "raise" it).

    T = F r_m (tan(alpha) + mu') / (1 - mu' tan(alpha)) + F mu_c d_c / 2.

    Args:
        thread: the thread.
        mu: flank friction coefficient, >= 0.
        load: axial load magnitude F [N], >= 0.
        collar_mu: thrust-collar friction coefficient, >= 0.
        collar_diameter: mean collar diameter d_c [m], >= 0.

    Returns:
        The drive torque [N*m]; ``inf`` where no torque can move the load
        (mu' >= cot(alpha), see :func:`is_drivable`).

    Raises:
        ValueError: a value is negative, not finite, or not a number (or a
            string with a unit of its dimension); the message names it.
    """
    return _core.raise_torque(_checked_thread(thread), quantity("mu", mu, ""),
                              quantity("load", load, "N"), quantity("collar_mu", collar_mu, ""),
                              quantity("collar_diameter", collar_diameter, "m"))


def lower_torque(
    thread: Thread,
    mu: Number,
    load: Number,
    collar_mu: Number = 0.0,
    collar_diameter: Number = 0.0,
) -> float:
    """Torque to move an axial load with its direction (to "lower" it).

    T = F r_m (mu' - tan(alpha)) / (1 + mu' tan(alpha)) + F mu_c d_c / 2.

    Args:
        thread: the thread.
        mu: flank friction coefficient, >= 0.
        load: axial load magnitude F [N], >= 0.
        collar_mu: thrust-collar friction coefficient, >= 0.
        collar_diameter: mean collar diameter d_c [m], >= 0.

    Returns:
        The drive torque [N*m]: negative where the load back-drives the thread
        (it has to be held back), positive where the thread is self-locking.

    Raises:
        ValueError: a value is negative, not finite, or not a number (or a
            string with a unit of its dimension); the message names it.
    """
    return _core.lower_torque(_checked_thread(thread), quantity("mu", mu, ""),
                              quantity("load", load, "N"), quantity("collar_mu", collar_mu, ""),
                              quantity("collar_diameter", collar_diameter, "m"))


def efficiency(
    thread: Thread,
    mu: Number,
    collar_mu: Number = 0.0,
    collar_diameter: Number = 0.0,
    backdrive: bool = False,
) -> float:
    """Efficiency of the thread (and collar), independent of the load.

    Forward: eta = F lead / (2 pi T_raise) = tan(alpha) / tan(alpha + rho') for
    a thread without collar friction. Back-driving (the axial load turns the
    screw): eta' = -2 pi T_lower / (F lead) = tan(alpha - rho') / tan(alpha).

    Args:
        thread: the thread.
        mu: flank friction coefficient, >= 0.
        collar_mu: thrust-collar friction coefficient, >= 0.
        collar_diameter: mean collar diameter [m], >= 0.
        backdrive: False for the forward efficiency, True for back-driving.

    Returns:
        The efficiency [1]. Forward: in (0, 1], 1 at mu = 0, 0 where the thread
        cannot be driven. Back-driving: <= 0 where the thread is self-locking.

    Raises:
        ValueError: a value is negative, not finite, or not a number (or a
            string with a unit of its dimension); the message names it.
    """
    if backdrive not in (True, False):
        raise ValueError(f"backdrive = {backdrive!r} is invalid: must be True or False")
    return _core.efficiency(_checked_thread(thread), quantity("mu", mu, ""),
                            quantity("collar_mu", collar_mu, ""),
                            quantity("collar_diameter", collar_diameter, "m"), bool(backdrive))


def is_self_locking(thread: Thread, mu: Number) -> bool:
    """Static position holding under a pure axial load: tan(alpha) < mu' (eq. 3.5).

    Args:
        thread: the thread.
        mu: flank friction coefficient, >= 0.

    Returns:
        True if a pure axial load cannot turn the thread.

    Raises:
        ValueError: mu is negative, not finite or not a number.
    """
    return _core.is_self_locking(_checked_thread(thread), quantity("mu", mu, ""))


def is_drivable(thread: Thread, mu: Number) -> bool:
    """A pure drive torque can turn the thread: mu' < cot(alpha) (eq. 3.7).

    Args:
        thread: the thread.
        mu: flank friction coefficient, >= 0.

    Returns:
        True if a torque alone can drive the thread.

    Raises:
        ValueError: mu is negative, not finite or not a number.
    """
    return _core.is_drivable(_checked_thread(thread), quantity("mu", mu, ""))
